/**
 * @file
 * The continuum heat solver: rho c dT/dt = div(k grad T) + Q on a deal.II
 * mesh, with Dirichlet, Neumann and Robin (convective) boundary conditions,
 * one-step theta time stepping or a direct steady-state solve, Kelly
 * adaptive refinement on quadrilateral meshes, Trilinos linear algebra with
 * algebraic multigrid, and MPI (p4est for quadrilaterals, a shared
 * triangulation for triangles).
 */
#ifndef tmfdem_continuum_heat_solver_h
#define tmfdem_continuum_heat_solver_h

#include <deal.II/base/function_parser.h>
#include <deal.II/base/index_set.h>
#include <deal.II/distributed/tria_base.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <functional>
#include <map>
#include <memory>
#include <tmfdem/base/parameters.h>
#include <tmfdem/base/simulation.h>
#include <vector>

namespace tmfdem
{
  class Monitors;
  class SolutionSeries;
  struct MeshReport;

  /**
   * Heat conduction in the continuum (units: T in C, k in W/(m K), rho c in
   * J/(m^3 K), fluxes in W/m^2, heats per unit thickness in J/m).
   *
   * Time stepping with theta in [1/2, 1]:
   * (M + theta dt (K + R)) T^{n+1} = (M - (1-theta) dt (K + R)) T^n
   *                                 + dt (theta F^{n+1} + (1-theta) F^n),
   * (a Crank-Nicolson run starts with Time stepping/Rannacher steps
   * backward Euler half steps), with M the consistent capacity matrix, K the
   * conductivity matrix, R the Robin boundary matrix and F the sources, Neumann
   * and Robin loads. The heat balance (stored = in through each boundary id +
   * sources) is kept every step, the Dirichlet heat from the reaction of the
   * discrete equations.
   */
  class HeatSolver : public Simulation
  {
  public:
    HeatSolver(const Parameters &parameters, MPI_Comm communicator);
    ~HeatSolver() override;

    void
    check_input() override;
    void
    run() override;

    /** The temperature DoFHandler (after run or check_input). */
    const DoFHandler<2> &
    get_dof_handler() const;
    /** The mapping used for geometry. */
    const Mapping<2> &
    get_mapping() const;
    /** Current temperature, with ghost entries [C]. */
    const TrilinosWrappers::MPI::Vector &
    get_temperature() const;
    /** The triangulation (after run or check_input); other solvers may
     *  attach DoFHandlers to it. */
    parallel::TriangulationBase<2> &
    get_triangulation();
    /**
     * Calls @p hook(time [s]) at every output time, before this solver
     * writes its own outputs, with the temperature of that time current.
     * The thermoelastic solver solves for stress there.
     */
    void
    set_output_hook(const std::function<void(const double time)> &hook);

  private:
    /** Heat that crossed each boundary id and came from sources [J/m]. */
    struct HeatBalance
    {
      std::map<types::boundary_id, double> boundary_heat_in;
      double                               source_heat = 0.;
      double                               stored_heat = 0.;
    };

    /** Builds the mesh, checks it, and everything that depends on it. */
    void
    make_mesh();
    void
    check_boundary_ids_and_materials() const;
    void
    setup_dofs();
    /** Hanging nodes and Dirichlet values at @p time. */
    void
    make_constraints(const double time);
    /** Per-cell capacity and conductivity matrices (cached). */
    void
    compute_cell_matrices();
    /**
     * Assembles the theta-step system from @p old_time to @p new_time, the
     * matrix only if @p assemble_matrix, and records the local systems for
     * the heat balance. With @p steady the system is K + R = F.
     */
    void
    assemble_system(const double old_time,
                    const double new_time,
                    const bool   assemble_matrix,
                    const bool   steady);
    /** Solves system_matrix T = system_rhs; returns CG iterations. */
    unsigned int
    solve(const bool rebuild_preconditioner);
    /** Adds this step's heats to @p balance, from the recorded systems. */
    void
    accumulate_heat_balance(HeatBalance &balance) const;
    /**
     * Interpolates the initial temperature [C]; with @p hold_dirichlet the
     * Dirichlet values at the start time replace it on the boundary (the
     * field that the initial adaptive refinement estimates), without them
     * the Dirichlet values act from the first step on (the initial state).
     */
    void
    set_initial_condition(const bool hold_dirichlet);
    /** Kelly estimate, mark, refine and coarsen, transfer the solution. */
    void
    adapt_mesh(const bool transfer_solution);
    void
    write_output(const double time);
    void
    run_transient();
    void
    run_steady();
    void
    write_summary(const unsigned long             steps,
                  const double                    end_time,
                  const double                    wall_time,
                  const HeatBalance              &balance,
                  const std::vector<std::string> &cycles) const;
    bool
    uses_quadrilaterals() const;

    const Parameters parameters;
    MPI_Comm         communicator;
    /** Theta of the current step: that of Time stepping/Method, 1 during
     *  the Rannacher start of a Crank-Nicolson run. */
    double theta;

    std::unique_ptr<parallel::TriangulationBase<2>> triangulation;
    std::unique_ptr<FiniteElement<2>>               fe;
    std::unique_ptr<Mapping<2>>                     mapping;
    std::unique_ptr<DoFHandler<2>>                  dof_handler;
    std::unique_ptr<MeshReport>                     mesh_report;
    unsigned int                                    coarse_level = 0;

    IndexSet                       locally_owned_dofs, locally_relevant_dofs;
    AffineConstraints<double>      constraints;
    TrilinosWrappers::SparseMatrix system_matrix;
    TrilinosWrappers::MPI::Vector  system_rhs;
    TrilinosWrappers::MPI::Vector  solution;     ///< ghosted, T^{n+1}
    TrilinosWrappers::MPI::Vector  old_solution; ///< ghosted, T^n
    std::unique_ptr<TrilinosWrappers::PreconditionBase> preconditioner;

    /** Cached per active cell index (locally owned cells only). */
    std::vector<FullMatrix<double>> cell_capacity, cell_conductivity;
    /** The local systems of the last assembly, for the heat balance. */
    std::vector<FullMatrix<double>> last_cell_matrix;
    std::vector<Vector<double>>     last_cell_rhs;
    /** Robin/Neumann heat of the last step that is known before solving,
     *  and the Robin matrices that multiply T^{n+1} [J/m]. */
    std::map<types::boundary_id, double> last_boundary_load;
    struct RobinFaceRecord
    {
      unsigned int       cell_index;
      types::boundary_id boundary_id;
      FullMatrix<double> matrix;
    };
    std::vector<RobinFaceRecord> last_robin_faces;
    double                       last_source_heat = 0.;
    /** Dirichlet DoF -> boundary id. */
    std::map<types::global_dof_index, types::boundary_id> dirichlet_dof_ids;

    std::vector<std::unique_ptr<FunctionParser<2>>> heat_sources;
    /** Per boundary condition: functions for its value entries. */
    struct BoundaryFunctions
    {
      std::unique_ptr<FunctionParser<2>> temperature, heat_flux,
        heat_transfer_coefficient, ambient_temperature;
      bool time_dependent_coefficient = false;
      bool time_dependent_temperature = false;
    };
    std::vector<BoundaryFunctions>     boundary_functions;
    std::unique_ptr<FunctionParser<2>> initial_temperature;
    bool                               any_heat_source = false;

    std::unique_ptr<Monitors>         monitors;
    std::unique_ptr<SolutionSeries>   solution_series;
    unsigned long                     total_linear_iterations = 0;
    std::function<void(const double)> output_hook;
  };
} // namespace tmfdem

#endif
