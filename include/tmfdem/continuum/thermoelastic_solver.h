/**
 * @file
 * The continuum thermoelastic solver: quasi-static small- or finite-strain
 * thermoelasticity in 2D (plane stress or plane strain) and 3D driven by a
 * temperature field, one-way coupled T -> u. Total Lagrangian, Newton's
 * method with the consistent tangent and a backtracking line search, Trilinos
 * CG with algebraic multigrid, Kelly adaptive refinement on quadrilaterals
 * and hexahedra, MPI (p4est for quadrilaterals and hexahedra, a shared
 * triangulation for triangles and tetrahedra).
 */
#ifndef tmfdem_continuum_thermoelastic_solver_h
#define tmfdem_continuum_thermoelastic_solver_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/index_set.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <array>
#include <boost/signals2/connection.hpp>
#include <chrono>
#include <functional>
#include <memory>
#include <set>
#include <tmfdem/base/parameters.h>
#include <tmfdem/continuum/continuum_model.h>
#include <tmfdem/continuum/temperature_field_source.h>
#include <tmfdem/continuum/thermoelastic_material.h>
#include <vector>

namespace tmfdem
{
  /**
   * Quasi-static thermoelasticity: find u with div P(grad u, T) = 0 in the
   * reference configuration, P from ThermoelasticMaterial (first
   * Piola-Kirchhoff stress; in small strain the Cauchy stress), with
   * displacement, roller and nominal traction boundary conditions. Units:
   * u in m, stresses in Pa, T in C, t in s.
   *
   * The temperature comes from `Mechanics/Temperature` (a function of x, y,
   * (z,) t), from a HeatSolver on the same triangulation (the continuum
   * thermo-mechanical loop, coupling::ContinuumThermomechanics, sets it
   * before each solve), or from another layer: a TemperatureFieldSource
   * registered under the `Mechanics/Temperature source` name (the discrete
   * layer's heat, coupling::DiscreteHeatField, 2D only) or
   * set_temperature().
   */
  template <int dim>
  class ThermoelasticSolver : public ContinuumModel<dim>
  {
    using Base = ContinuumModel<dim>;

  public:
    using Base::refuse_resume;
    using Base::stop_if_requested;

  protected:
    using Base::add_run_entries;
    using Base::cell_quadrature;
    using Base::check_adaptivity;
    using Base::check_boundary_ids;
    using Base::check_material_ids;
    using Base::communicator;
    using Base::create_fe;
    using Base::create_mesh;
    using Base::distribute_dofs;
    using Base::distributed_sparsity;
    using Base::dof_handler;
    using Base::face_quadrature_rule;
    using Base::fe;
    using Base::locally_owned_dofs;
    using Base::locally_relevant_dofs;
    using Base::mapping;
    using Base::mesh_report;
    using Base::monitors;
    using Base::open_solution_series;
    using Base::output_schedule;
    using Base::parameters;
    using Base::refine_mesh_by_kelly;
    using Base::summary_head;
    using Base::triangulation;
    using Base::use_mesh;
    using Base::write_solution;

  public:
    /** Temperature [C] at points of a cell (temperature_field_source.h). */
    using TemperatureField = TemperatureFieldOf<dim>;

    ThermoelasticSolver(const Parameters &parameters, MPI_Comm communicator);
    ~ThermoelasticSolver() override;

    void
    check_input() override;
    void
    run() override;

    /** Uses @p field for the temperature of the following solves. */
    void
    set_temperature(const TemperatureField &field);
    /**
     * Uses the finite element field @p temperature [C] (ghosted) on
     * @p dof_handler, which must live on get_triangulation(), for the
     * temperature of the following solves.
     */
    void
    set_temperature(const DoFHandler<dim>               &dof_handler,
                    const Mapping<dim>                  &mapping,
                    const TrilinosWrappers::MPI::Vector &temperature);

    /**
     * Builds mesh (Temperature source = function) or takes @p triangulation
     * (non-null: another solver's, kept alive by the caller), the DoFs,
     * boundary conditions and monitors, and checks the input.
     */
    void
    setup(parallel::TriangulationBase<dim> *triangulation = nullptr);
    /** Quasi-static solve at @p time [s]: Newton to equilibrium. Throws
     *  RunError if Newton or CG fails. */
    void
    solve(const double time);
    /** Writes vtu, probes and lines for @p time [s]. */
    void
    write_output(const double time);
    /** If the owner of the triangulation adapted it since the last set-up:
     *  new DoFs, and the displacement starts from rest. */
    void
    follow_mesh_change();
    /** InputError for Initial conditions/Stress free = true (the thermal
     *  strain is measured from each material's Reference temperature). */
    void
    check_initial_conditions() const;
    /** Prints the "done" line (solves, iterations, cells, DoFs, wall). */
    void
    report_done() const;

    /** Current displacement, ghosted [m]. */
    const TrilinosWrappers::MPI::Vector &
    get_displacement() const;

  private:
    /** One Newton iteration, for summary.json and stderr. */
    struct NewtonRecord
    {
      double       time;
      unsigned int iteration;
      double       residual;
      double       step_length;
      unsigned int linear_iterations;
    };

    void
    check_boundary_conditions() const;
    void
    setup_dofs();
    void
    find_pinned_dofs();
    /** Temperatures at the quadrature points of every owned cell. */
    void
    compute_quadrature_temperatures();
    /**
     * Newton constraints at the current time: hanging nodes, and on
     * Dirichlet DoFs the increment (prescribed - current displacement).
     * Returns the largest increment [m].
     */
    double
    make_newton_constraints(const double time);
    /**
     * Assembles -R(u) (and the tangent if @p with_matrix) into system_rhs
     * with @p constraints_used for @p displacement; returns false if some
     * quadrature point has J_e <= 0.
     */
    bool
    assemble(const TrilinosWrappers::MPI::Vector &displacement,
             const AffineConstraints<double>     &constraints_used,
             const bool                           with_matrix);
    /** Norm of the residual at free DoFs for @p displacement; infinity if
     *  inadmissible. */
    double
    residual_norm(const TrilinosWrappers::MPI::Vector &displacement);
    unsigned int
    solve_linear_system(TrilinosWrappers::MPI::Vector &update);
    void
    adapt_mesh();
    void
    write_summary(const double time) const;
    /** Temperatures at arbitrary points of one cell. */
    std::vector<double>
    temperatures_at(
      const typename Triangulation<dim>::active_cell_iterator &cell,
      const std::vector<Point<dim>>                           &unit_points,
      const std::vector<Point<dim>>                           &points) const;
    /** The values written to probes.csv and lines.csv at one point. */
    std::vector<double>
    monitor_values(const typename DoFHandler<dim>::active_cell_iterator &cell,
                   const Point<dim> &unit_point) const;
    void
    run_with_temperature_function();
    /** Wall time since construction [s]. */
    double
    wall_time() const;

    boost::signals2::connection mesh_change_connection;
    bool                        mesh_changed = false;
    double                      domain_area  = 0.; ///< [m^dim]

    AffineConstraints<double>            hanging_node_constraints;
    AffineConstraints<double>            newton_constraints;   ///< increments
    AffineConstraints<double>            residual_constraints; ///< homogeneous
    TrilinosWrappers::SparseMatrix       system_matrix;
    TrilinosWrappers::MPI::Vector        system_rhs;
    TrilinosWrappers::MPI::Vector        solution; ///< ghosted displacement
    std::vector<types::global_dof_index> pinned_dofs;

    std::vector<ThermoelasticMaterial<dim>> materials;
    std::unique_ptr<FunctionParser<dim>>    temperature_function;
    TemperatureField                        temperature_field;
    std::vector<std::vector<double>>        quadrature_temperatures;
    /** Per mechanical condition: the functions of its components. */
    std::vector<std::array<std::unique_ptr<FunctionParser<dim>>, dim>>
      displacement_functions, traction_functions;

    std::vector<NewtonRecord>             newton_history;
    unsigned long                         solves                  = 0;
    unsigned long                         total_newton_iterations = 0;
    unsigned long                         total_linear_iterations = 0;
    std::chrono::steady_clock::time_point wall_start;
    /** Extremes of the Cauchy stress at the last output [Pa]: the largest
     *  |sigma_ij| of the dim (dim + 1) / 2 components (xx, yy, (zz,) xy (,
     *  yz, xz)), the largest and the smallest principal stress. */
    std::vector<double> stress_extremes;
  };
} // namespace tmfdem

#endif
