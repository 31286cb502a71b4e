/**
 * @file
 * What the continuum models share: the mesh (their own, or another
 * model's), the finite element and mapping, the DoFs, the checks of boundary
 * ids, material ids and adaptivity against the mesh, the output schedule,
 * the vtu series, Kelly adaptive refinement with solution transfer, and the
 * clean stop on SIGINT/SIGTERM.
 */
#ifndef tmfdem_continuum_continuum_model_h
#define tmfdem_continuum_continuum_model_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/numerics/data_out.h>

#include <functional>
#include <memory>
#include <set>
#include <string>
#include <tmfdem/base/parameters.h>
#include <tmfdem/base/simulation.h>
#include <tmfdem/io/output_files.h>
#include <tmfdem/io/output_schedule.h>
#include <vector>

namespace tmfdem
{
  template <int dim>
  class Monitors;
  class SolutionSeries;
  struct MeshReport;

  /**
   * The base of the continuum models (HeatSolver, ThermoelasticSolver) in
   * @p dim = 2 or 3 space dimensions: owns or borrows the triangulation
   * and owns the finite element, the mapping and the DoFHandler on it.
   * Lagrange elements of `degree` on either quadrilaterals or hexahedra
   * (FE_Q, MappingQ of the same degree, p4est) or triangles or tetrahedra
   * (FE_SimplexP, the affine MappingFE, a shared triangulation); a
   * vector-valued model takes `n_components` copies in an FESystem.
   */
  template <int dim>
  class ContinuumModel : public Simulation
  {
  public:
    ContinuumModel(const Parameters &parameters, MPI_Comm communicator);
    ~ContinuumModel() override;

    /** The DoFHandler of this model (after check_input or set-up). */
    const DoFHandler<dim> &
    get_dof_handler() const;
    /** The mapping used for geometry. */
    const Mapping<dim> &
    get_mapping() const;
    /** The triangulation (after check_input or set-up); other models may
     *  attach DoFHandlers to it. */
    parallel::TriangulationBase<dim> &
    get_triangulation();
    /** InputError for --resume: continuum runs write no checkpoints. */
    void
    refuse_resume() const;
    /**
     * If SIGINT or SIGTERM arrived on any rank: calls @p write_state (the
     * outputs of the state at @p time [s]) and throws StopRequested naming
     * @p time and @p step.
     */
    void
    stop_if_requested(const double                 time,
                      const unsigned long          step,
                      const std::function<void()> &write_state) const;

  protected:
    /** Creates the output folder and this model's own mesh from the Mesh
     *  subsection (checked; the report in mesh_report). */
    void
    create_mesh();
    /** Computes on @p external, another model's triangulation, which its
     *  owner keeps alive. */
    void
    use_mesh(parallel::TriangulationBase<dim> &external);
    /** Finite element of @p degree with @p n_components components (one:
     *  the scalar element itself), its mapping and an empty DoFHandler. */
    void
    create_fe(const unsigned int degree, const unsigned int n_components);
    /**
     * InputError, naming `<name>/Boundary ids`, if one of @p ids is not a
     * boundary id of the mesh; the message lists those of the mesh.
     */
    void
    check_boundary_ids(const std::string                     &name,
                       const std::vector<types::boundary_id> &ids) const;
    /** InputError for a cell material id without a Materials subsection. */
    void
    check_material_ids() const;
    /** InputError for adaptive refinement on a triangle mesh. */
    void
    check_adaptivity() const;
    /** Distributes the DoFs; sets the owned and relevant index sets. */
    void
    distribute_dofs();
    /**
     * The sparsity pattern of the DoFs on the relevant rows, distributed
     * over the processes; with @p constraints, the constrained entries
     * eliminated (not kept).
     */
    DynamicSparsityPattern
    distributed_sparsity(const AffineConstraints<double> *constraints) const;
    /** Gauss quadrature of degree + 1 points per direction for the cells
     *  (QGauss on quadrilaterals, QGaussSimplex on triangles). */
    Quadrature<dim>
    cell_quadrature() const;
    /** Gauss rule of degree + 1 points per direction on the faces: lines
     *  in 2D, quadrilaterals or triangles in 3D. */
    Quadrature<dim - 1>
    face_quadrature_rule() const;
    bool
    uses_quadrilaterals() const
    {
      return quadrilaterals;
    }
    /** Output/Output times and interval from Start to End time. */
    OutputSchedule
    output_schedule() const;
    /** The first entries of summary.json: model, prm_file, mpi_processes. */
    JsonObject
    summary_head() const;
    /** The run's entries of summary.json: cells, dofs, @p steps,
     *  @p end_time [s], @p wall_time [s], element_steps_per_second. */
    void
    add_run_entries(JsonObject         &summary,
                    const unsigned long steps,
                    const double        end_time,
                    const double        wall_time) const;
    /** Opens the solution.pvd series in the output folder. */
    void
    open_solution_series();
    /**
     * Adds the cells' material_id and subdomain to @p data_out (with the
     * data vectors already attached), builds the patches (the element's
     * degree on quadrilaterals, linear on triangles) and writes them as the
     * vtu output at @p time [s].
     */
    void
    write_solution(DataOut<dim> &data_out, const double time);
    /**
     * Kelly-marks the cells from the ghosted @p solution, refines and
     * coarsens, and calls @p after_refinement (new DoFs, matrices). With
     * @p transferred non-null, @p solution is transferred onto the new
     * mesh into it (owned entries, not yet constrained).
     */
    void
    refine_mesh_by_kelly(const TrilinosWrappers::MPI::Vector &solution,
                         const std::function<void()>         &after_refinement,
                         TrilinosWrappers::MPI::Vector       *transferred);
    const Parameters parameters;
    MPI_Comm         communicator;

    /** This model's own mesh (null when it computes on another's). */
    std::unique_ptr<parallel::TriangulationBase<dim>> own_triangulation;
    parallel::TriangulationBase<dim>                 *triangulation = nullptr;
    /** The check of the own mesh (null for another model's mesh). */
    std::unique_ptr<MeshReport> mesh_report;
    /** Boundary and material ids of the coarse mesh (known to every rank). */
    std::set<types::boundary_id> mesh_boundary_ids;
    std::set<types::material_id> mesh_material_ids;
    /** Mesh/Global refinements: the coarsest level adaptivity keeps. */
    unsigned int coarse_level   = 0;
    bool         quadrilaterals = false;

    std::unique_ptr<FiniteElement<dim>> fe;
    std::unique_ptr<Mapping<dim>>       mapping;
    std::unique_ptr<DoFHandler<dim>>    dof_handler;
    IndexSet locally_owned_dofs, locally_relevant_dofs;

    std::unique_ptr<Monitors<dim>>  monitors;
    std::unique_ptr<SolutionSeries> solution_series;

  private:
    /** Ids and cell shape of the coarse mesh. */
    void
    describe_mesh();
  };
} // namespace tmfdem

#endif
