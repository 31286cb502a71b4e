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
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>
#include <deal.II/lac/vector.h>

#include <array>
#include <functional>
#include <map>
#include <memory>
#include <tmfdem/base/parameters.h>
#include <tmfdem/continuum/continuum_model.h>
#include <tmfdem/io/validation_report.h>
#include <vector>

namespace tmfdem
{
  /**
   * Heat conduction in the continuum in @p dim = 2 or 3 space dimensions
   * (units: T in C, k in W/(m K), rho c in J/(m^3 K), fluxes in W/m^2;
   * heats in J per unit thickness (J/m) in 2D, in J in 3D).
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
   *
   * Mesh, element, DoFs, id checks, output schedule and stop handling come
   * from ContinuumModel; the assembly, linear solve and heat balance are in
   * source/continuum/heat_assembly.cc. run() drives the time loop through
   * the same public steps (prepare_transient, step_towards, write_output)
   * that the continuum thermo-mechanical loop uses
   * (source/coupling/continuum_thermomechanics.cc).
   */
  template <int dim>
  class HeatSolver : public ContinuumModel<dim>, public ValidationReporter
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
    using Base::coarse_level;
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
    using Base::mesh_boundary_ids;
    using Base::mesh_report;
    using Base::monitors;
    using Base::open_solution_series;
    using Base::output_schedule;
    using Base::parameters;
    using Base::refine_mesh_by_kelly;
    using Base::summary_head;
    using Base::triangulation;
    using Base::uses_quadrilaterals;
    using Base::write_solution;

  public:
    HeatSolver(const Parameters &parameters, MPI_Comm communicator);
    ~HeatSolver() override;

    void
    check_input() override;
    void
    run() override;

    /** What check_input() set up, for `--validate`. */
    void
    report_validation(std::ostream     &out,
                      const Parameters &parameters,
                      MPI_Comm          communicator) const override;

    /** Current temperature, with ghost entries [C]. */
    const TrilinosWrappers::MPI::Vector &
    get_temperature() const;
    /**
     * Memory of this process's matrices (system, capacity, conduction, an
     * AMG hierarchy estimated as large as the system matrix), cached element
     * matrices and vectors [bytes] (after check_input).
     */
    double
    memory_estimate() const;

    /** Heat that crossed each boundary id and came from sources [J/m]. */
    struct HeatBalance
    {
      std::map<types::boundary_id, double> boundary_heat_in;
      double                               source_heat = 0.;
      double                               stored_heat = 0.;
    };

    /**
     * @name Stepping by a coupled model
     * A model that takes its temperature from this solver (the discrete
     * layer with `Discrete heat/Temperature source = continuum heat`) builds
     * the mesh, DoFs, matrices and the initial temperature with
     * prepare_coupled_stepping() and then calls advance() at its own thermal
     * steps; this solver writes no outputs then. run_transient() uses the
     * same advance().
     * @{
     */
    /** Mesh, DoFs, matrices, initial temperature at Start time; InputError
     *  for steady mode or adaptive refinement. */
    void
    prepare_coupled_stepping();
    /** True while a Crank-Nicolson run takes its backward Euler start
     *  (Time stepping/Rannacher steps half steps). */
    bool
    in_rannacher_start() const;
    /** One theta step of @p dt [s] from current_time() (backward Euler
     *  during the Rannacher start); keeps the heat balance. */
    void
    advance(const double dt);
    /** Time of the current temperature [s]. */
    double
    current_time() const
    {
      return stepping.time;
    }
    /** Heat balance since the start [J/m]. */
    const HeatBalance &
    heat_balance() const
    {
      return stepping.balance;
    }
    /** Steps taken so far. */
    unsigned long
    steps_taken() const
    {
      return stepping.step;
    }
    /** Replaces the temperature (a restart) at @p time [s], with the steps
     *  taken and the heat balance so far; @p values are the DoF values. */
    void
    restore_state(const double               time,
                  const unsigned long        steps,
                  const HeatBalance         &balance,
                  const std::vector<double> &values);
    /** @} */

    /**
     * @name Driving a run step by step
     * run() and the continuum thermo-mechanical loop
     * (coupling::run_continuum_thermomechanics) call these after
     * check_input(): transient, prepare_transient(), then step_towards() up
     * to each output time, write_output() there, and write_summary() at
     * the end; steady, solve_steady(), write_output(), write_summary().
     * @{
     */
    /** Opens solution.pvd, refines the initial mesh (adaptivity), sets the
     *  initial temperature and the matrices at Start time. */
    void
    prepare_transient();
    /**
     * One time step towards @p target [s]: Time stepping/Time step (half
     * of it during the Rannacher start), shortened to land on @p target
     * (OutputSchedule::step_towards), the time set to @p target when it is
     * reached within @p tolerance [s]; then adaptive refinement every
     * Adaptive refinement/Interval steps.
     */
    void
    step_towards(const double target, const double tolerance);
    /** Opens solution.pvd and solves the steady problem at Start time (all
     *  adaptive cycles). */
    void
    solve_steady();
    /** Probes, lines and the vtu of the temperature at @p time [s]. */
    void
    write_output(const double time);
    /** summary.json at @p end_time [s] after @p wall_time [s], with the
     *  steps, heat balance and adaptive cycles so far; in transient runs
     *  with @p report_done also the "done" line on stdout. */
    void
    write_summary(const double end_time,
                  const double wall_time,
                  const bool   report_done) const;
    /** @} */

  private:
    /** Per boundary condition: functions for its value entries. */
    struct BoundaryFunctions
    {
      std::unique_ptr<FunctionParser<dim>> temperature, heat_flux,
        heat_transfer_coefficient, ambient_temperature;
      bool time_dependent_coefficient = false;
      bool time_dependent_temperature = false;
      /** Neumann flux or Robin h T_inf depends on t. */
      bool time_dependent_load = false;
    };
    /** Load vector at one time [W/m] with its parts per boundary id and from
     *  sources (summed over processes) [W/m]. */
    struct Loads
    {
      double                               time  = 0.;
      bool                                 valid = false;
      TrilinosWrappers::MPI::Vector        vector;
      std::map<types::boundary_id, double> boundary;
      double                               source = 0.;
    };
    /** Per Robin boundary id: w_i = integral of h phi_i [W/(m K)], so that
     *  w . T is the heat rate that h T draws. */
    using RobinWeights = TrilinosWrappers::MPI::Vector;

    /** The mesh, element and DoFHandler; checks boundary ids, material
     *  ids and adaptivity against the mesh. */
    void
    make_mesh();
    void
    setup_dofs();
    /** Hanging nodes and Dirichlet values at @p time. */
    void
    make_constraints(const double time);
    /**
     * Per-cell capacity and conductivity matrices (cached), the assembled
     * capacity matrix M and conduction matrix K (plus the Robin matrix R
     * where its coefficient does not depend on t), the capacity row sums, and
     * the loads that do not depend on t. Called after every mesh change.
     */
    void
    compute_cell_matrices();
    /**
     * The Robin matrix of one face at @p time, times @p weight
     * (weight \f$\int h \phi_i \phi_j\f$, in the units of weight W/(m K)).
     */
    void
    robin_face_matrix(
      const typename DoFHandler<dim>::active_cell_iterator &cell,
      const unsigned int                                    face,
      const BoundaryFunctions                              &functions,
      const double                                          time,
      const double                                          weight,
      FEFaceValues<dim>                                    &fe_face_values,
      FullMatrix<double>                                   &matrix) const;
    /**
     * Assembles the loads (sources, Neumann fluxes, Robin h T_inf) at
     * @p time into @p level: those that depend on t if @p time_dependent,
     * else those that do not.
     */
    void
    assemble_loads(const double time, const bool time_dependent, Loads &level);
    /** The loads that depend on t at @p time, from a two-level cache. */
    const Loads &
    time_dependent_loads(const double time);
    /**
     * The Robin matrix at @p time into robin_matrix and the Robin weights
     * at @p time into @p weights (only for coefficients that depend on t).
     */
    void
    assemble_robin(const double                                time,
                   std::map<types::boundary_id, RobinWeights> &weights);
    /**
     * The theta-step system matrix (if @p assemble_matrix) and the lifting
     * vector of the Dirichlet values at @p new_time; @p mass_weight is 1 for
     * a time step, 0 for the steady problem. Records the Dirichlet rows of
     * the local matrices for the heat balance when @p assemble_matrix.
     */
    void
    assemble_matrix_and_lifting(const double new_time,
                                const double mass_weight,
                                const double stiffness_weight,
                                const bool   assemble_matrix);
    /**
     * The right-hand side from @p old_time to @p new_time from the assembled
     * matrices and load vectors (no cell loop): full_rhs unconstrained,
     * system_rhs condensed with the lifting added. With @p steady the
     * system is K + R = F.
     */
    void
    assemble_rhs(const double old_time,
                 const double new_time,
                 const bool   steady);
    /** Solves system_matrix T = system_rhs; returns CG iterations. */
    unsigned int
    solve(const bool rebuild_preconditioner);
    /** Adds this step's heats to @p balance, from the assembled vectors. */
    void
    accumulate_heat_balance(HeatBalance &balance);
    /**
     * Interpolates the initial temperature [C]; with @p hold_dirichlet the
     * Dirichlet values at the start time replace it on the boundary (the
     * field that the initial adaptive refinement estimates), without them
     * the Dirichlet values act from the first step on (the initial state).
     */
    void
    set_initial_condition(const bool hold_dirichlet);
    /** T^{n+1} (ghosted and owned) and T^n set to @p temperature [C]. */
    void
    set_state(const TrilinosWrappers::MPI::Vector &temperature);
    /** The functions of the Robin condition on face @p face of @p cell, or
     *  nullptr where that face is not on a Robin boundary. */
    const BoundaryFunctions *
    robin_functions(const typename DoFHandler<dim>::active_cell_iterator &cell,
                    const unsigned int face) const;
    /** Kelly estimate, mark, refine and coarsen, transfer the solution. */
    void
    adapt_mesh(const bool transfer_solution);

    /** Stepping state at Start time (time, step count, balance). */
    void
    start_stepping();
    void
    run_steady();
    void
    run_transient();
    /** Adds the cell matrices of the Robin faces at @p time to @p matrix
     *  (not compressed) and sets the Robin weights at @p time in
     *  @p weights (one vector per Robin boundary id, on every process). */
    void
    add_robin_terms(const double                                time,
                    TrilinosWrappers::SparseMatrix             &matrix,
                    std::map<types::boundary_id, RobinWeights> &weights);
    /** Theta of the current step: that of Time stepping/Method, 1 during
     *  the Rannacher start of a Crank-Nicolson run. */
    double                         theta;
    AffineConstraints<double>      constraints;
    TrilinosWrappers::SparseMatrix system_matrix;
    TrilinosWrappers::MPI::Vector  system_rhs;
    TrilinosWrappers::MPI::Vector  solution; ///< ghosted, T^{n+1}
    std::unique_ptr<TrilinosWrappers::PreconditionBase> preconditioner;

    /** Cached per active cell index (locally owned cells only). */
    std::vector<FullMatrix<double>> cell_capacity, cell_conductivity;
    /** Hanging nodes and zero Dirichlet values (condenses right-hand sides). */
    AffineConstraints<double> homogeneous_constraints;
    /** Assembled without constraints: capacity M [J/(m K)], conduction
     *  K [W/(m K)] (plus R where h does not depend on t), and R at the old
     *  time level where h depends on t. */
    TrilinosWrappers::SparseMatrix capacity_matrix, conduction_matrix,
      robin_matrix;
    /** M 1 [J/(m K)]: the stored heat of a change is its dot product. */
    TrilinosWrappers::MPI::Vector capacity_row_sums;
    /** The constrained right-hand side is the condensed full_rhs plus the
     *  lifting of the Dirichlet values. */
    TrilinosWrappers::MPI::Vector full_rhs, condense_transfer, lifting;
    /** Owned copies of T^{n+1} and T^n, and work space. */
    TrilinosWrappers::MPI::Vector owned_solution, owned_old_solution, work;

    /** The loads that do not depend on t, and a two-level cache of those
     *  that do. */
    Loads                constant_loads;
    std::array<Loads, 2> variable_loads;
    bool                 any_time_dependent_load = false;
    /** Robin weights of the constant coefficients, or those at the old and
     *  new time levels where h depends on t. */
    std::map<types::boundary_id, RobinWeights> robin_weights, robin_weights_new;
    bool                                       time_dependent_robin = false;

    /** Dirichlet rows of the local matrices of the owned cells (last
     *  assembly): the reaction heat at Dirichlet node i is sum over these
     *  rows of row . T^{n+1} minus the full right-hand side at i. */
    struct ReactionRow
    {
      types::boundary_id boundary_id;
      unsigned int       start;
    };
    std::vector<ReactionRow>             reaction_rows;
    std::vector<types::global_dof_index> reaction_columns;
    std::vector<double>                  reaction_values;
    /** Owned Dirichlet DoFs with their boundary ids. */
    std::vector<std::pair<types::global_dof_index, types::boundary_id>>
      owned_dirichlet_dofs;
    /** Weights of the new and old time levels of the last assembly [s]. */
    double last_new_weight = 1., last_old_weight = 0.;
    /** Times of the new and old levels of the last assembly [s]. */
    double last_new_time = 0., last_old_time = 0.;
    /** Boundary ids of the thermal conditions -> condition index. */
    std::map<types::boundary_id, unsigned int> condition_of;
    /** Dirichlet DoF -> boundary id. */
    std::map<types::global_dof_index, types::boundary_id> dirichlet_dof_ids;

    std::vector<std::unique_ptr<FunctionParser<dim>>> heat_sources;
    std::vector<BoundaryFunctions>                    boundary_functions;
    std::unique_ptr<FunctionParser<dim>>              initial_temperature;
    bool                                              any_heat_source = false;
    /** Per material id: its heat source depends on t. */
    std::vector<bool> time_dependent_source;

    unsigned long total_linear_iterations = 0;
    /** Cells, DoFs and CG iterations of each steady adaptive cycle. */
    std::vector<std::string> adaptive_cycles;

    /** Where the time stepping stands. */
    struct SteppingState
    {
      double        time              = 0.;  ///< of the current solution [s]
      double        last_dt           = -1.; ///< of the assembled matrix [s]
      double        last_theta        = -1.; ///< of the assembled matrix
      unsigned long step              = 0;
      bool          matrix_is_current = false;
      bool          dirichlet_depends_on_time = false;
      HeatBalance   balance;
    };
    SteppingState stepping;
  };
} // namespace tmfdem

#endif
