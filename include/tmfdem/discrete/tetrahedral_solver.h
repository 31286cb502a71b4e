/**
 * @file
 * The explicit dynamics of the discrete layer in 3D (model `discrete
 * mechanics` with Mesh/Dimension = 3): central differences (paper Eq. 2)
 * over the exploded tetrahedral mesh (DiscreteModel with dim = 3) with the
 * finite-strain tetrahedra of element_response<3>() and the cohesive joints
 * on every interior triangular face of face_joint_response(); damping as in
 * 2D (Damping ratio of the highest element mode, mass damping), the stable
 * step of stable_step.h for tetrahedra, joint compliance compensation (its
 * isotropic part), fixed, driven and free bodies, boundary conditions
 * (fixed, rollers, velocity), energy bookkeeping, guards, and the outputs
 * solution.pvd (tetrahedra), cracks.pvd (broken faces as triangles),
 * history.csv and summary.json. With heat (models `discrete heat` and
 * `discrete thermo-mechanics` with Mesh/Dimension = 3) the temperatures of
 * TetrahedralHeat drive the thermal stretch F_T = s I of every tetrahedron
 * in the multi-rate coupling of 2D (one thermal step every n mechanical
 * steps over the same time: source/coupling/tetrahedral_thermo_mechanics.cc).
 * Quasi-static coupling, checkpoints and --resume as in 2D. Contact
 * between tetrahedra (TetrahedronContactSystem: Munjiza's potential and
 * friction of tetrahedron_contact.h) as in 2D: the contact forces enter the
 * scalar node update of the tetrahedra in contact, their work the energy
 * balance, their stiffness the stable step. Gravity (three components,
 * ramped as in 2D). Monitors and MPI ranks beyond one are refused with a
 * message naming the entry (doc/theory.md 5.12, 5.13, 7.9).
 */
#ifndef tmfdem_discrete_tetrahedral_solver_h
#define tmfdem_discrete_tetrahedral_solver_h

#include <deal.II/base/function_parser.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/tria.h>

#include <array>
#include <cstdint>
#include <memory>
#include <tmfdem/base/parameters.h>
#include <tmfdem/base/simulation.h>
#include <tmfdem/coupling/quasi_static_relaxation.h>
#include <tmfdem/discrete/cohesive_law.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/solid.h>
#include <tmfdem/discrete/vector_instructions.h>
#include <tmfdem/io/validation_report.h>
#include <vector>

namespace tmfdem
{
  class CsvSeries;
  class CheckpointWriter;
  class CheckpointReader;
  class CheckpointSchedule;

  namespace discrete
  {
    class VtuSeries;
    class TetrahedralHeat;
    class TetrahedronContactSystem;

    /** Explicit FDEM mechanics of tetrahedra and face joints (3D). */
    class TetrahedralSolver : public Simulation, public ValidationReporter
    {
    public:
      /** What a run models: the mechanics, the heat alone, or both. */
      enum class Physics
      {
        mechanics,
        heat,
        thermo_mechanics
      };

      TetrahedralSolver(const Parameters &parameters,
                        MPI_Comm          communicator,
                        const Physics     physics = Physics::mechanics);
      ~TetrahedralSolver() override;

      void
      check_input() override;
      void
      run() override;
      void
      report_validation(std::ostream     &out,
                        const Parameters &parameters,
                        MPI_Comm          communicator) const override;

    private:
      /** The energy terms of the run so far [J]. */
      struct Energies
      {
        double kinetic = 0.; ///< 1/2 m |v|^2 at the last half step
        double strain  = 0.; ///< elastic energy of the tetrahedra
        /** Work done on the joints by the nodes (stored + dissipated). */
        double joint_work = 0.;
        /** Work of the imposed motions (reactions of conditions and driven
         *  or fixed bodies). */
        double external_work = 0.;
        /** Viscous and mass-damping dissipation. */
        double damping = 0.;
        /** Work of the thermal stretch: the change of the strain energy
         *  each new stretch makes at fixed geometry. */
        double thermal_work = 0.;
        /** Relaxation predictor = extrapolate: the strain and intact-joint
         *  energy the extrapolated starts put in (their jumps are no
         *  motion the steps integrate). */
        double relaxation_work = 0.;
        /** Work done on the contacts by the nodes: the normal contact
         *  energy stored plus the friction dissipated. */
        double contact_work = 0.;
        /** Energy dissipated by friction. */
        double friction = 0.;
      };

      /** A node's imposed velocity components. */
      struct NodeConstraint
      {
        unsigned int node          = 0;
        bool         prescribed[3] = {false, false, false};
        /** Index into velocity_functions per component, or -1: zero (a
         *  velocity, or with displacement[i] a displacement). */
        int function[3] = {-1, -1, -1};
        /** Per component: the function gives the displacement u(X, t)
         *  [m] (a displacement condition), not the velocity. */
        bool displacement[3] = {false, false, false};
        /** The imposed velocity now [m/s]. */
        double velocity[3] = {0., 0., 0.};
        /** Body or condition it belongs to (reactions are summed per
         *  owner: history.csv). */
        unsigned int owner = 0;
      };

      /** Refuses what the 3D discrete layer does not model (naming the
       *  entry). */
      void
      check_supported() const;
      void
      setup_mesh();
      void
      setup_materials();
      void
      setup_constraints();
      void
      setup_time_step();
      /** The imposed velocities at @p time [s] (conditions and bodies),
       *  times @p scale [-] (quasi-static coupling: the relaxation's ramp,
       *  QuasiStaticRelaxation::imposed_velocity_scale()). */
      void
      evaluate_imposed_velocities(const double time, const double scale = 1.);
      /** The velocities of the components held by displacement conditions
       *  that bring their nodes from where they are to X + u(X,
       *  @p target_time) over @p duration [s] (dynamic: the step, to its
       *  end; quasi-static: the relaxation steps to the end of its ramp). */
      void
      evaluate_imposed_displacements(const double target_time,
                                     const double duration);
      /** The joint forces into DiscreteModel::node_joint_force; true if a
       *  joint broke. */
      bool
      compute_joint_forces();
      /** Contact (with Contact = true): a new pair search where one is due
       *  (travel, broken joints), then the pair forces over the step @p dt
       *  [s] and which tetrahedra have them. */
      void
      compute_contact_forces(const double dt);
      /** The ruling of the contact settings from Discrete mechanics (the
       *  penalties from the stiffest material, the buffer a quarter of the
       *  smallest edge by default). */
      void
      setup_contact();
      /**
       * The overlap guard, after a contact search once the fastest node has
       * travelled half the search buffer since the last check: the largest
       * overlap of a force-carrying pair (TetrahedronContactSystem::
       * largest_overlap()) against the smaller tetrahedron's volume. With
       * @p initial (before the first step): beyond max_initial_overlap it is
       * bad input (InputError naming both tetrahedra and their bodies);
       * later, beyond max_contact_overlap the run stops (guard: the contact
       * penalty is too soft for the impact).
       */
      void
      check_contact_overlap(const bool initial);
      /** Overlap volume / smaller tetrahedron volume beyond which contact
       *  has failed: a face pressed flat in by about a sixth of the
       *  altitude (3 d / H). */
      static constexpr double max_contact_overlap = 0.5;
      /** The same at the start: a face pressed in by about 3 % of the
       *  altitude. */
      static constexpr double max_initial_overlap = 0.1;
      /** Element forces, node update over the step @p dt [s] and the
       *  step's works. */
      void
      update_nodes(const double dt);
      /** One explicit step of @p dt [s] (the time step, or shorter to land
       *  on an output time). */
      void
      step(const double dt);
      /** Strain energy of tetrahedron @p e at its current nodes with the
       *  thermal stretch @p s [J]: V s^3 psi(F / s). */
      double
      element_strain_energy(const unsigned int e, const double s) const;
      /** Kinetic and strain energy of the current state [J]. */
      void
      compute_state_energies();
      /** The energy put in so far: the initial kinetic energy and the
       *  works of the imposed motions and of the thermal stretch [J]. */
      double
      energy_put_in() const
      {
        return initial_kinetic + energies.external_work +
               std::abs(energies.thermal_work);
      }
      /** Energy put in minus the energy in the state and dissipated [J]:
       *  initial kinetic + external + thermal (+ relaxation) work -
       *  (kinetic + strain + joint work + contact work + damping). */
      double
      energy_balance_error() const
      {
        return initial_kinetic + energies.external_work +
               energies.thermal_work + energies.relaxation_work -
               (energies.kinetic + energies.strain + energies.joint_work +
                energies.contact_work + energies.damping);
      }
      /** True if the run has mechanics (not the heat alone). */
      bool
      with_mechanics() const
      {
        return physics != Physics::heat;
      }
      /** The heat, its stress-free temperatures and the multi-rate
       *  cadence (coupling/tetrahedral_thermo_mechanics.cc). */
      void
      setup_heat();
      /** One thermal step from the last one to now, then the new thermal
       *  stretches (multi-rate coupling). */
      void
      thermal_step();
      /** F_T = s I of every tetrahedron from its mean temperature; the
       *  change of strain energy at fixed geometry is thermal work. */
      void
      update_thermal_stretch();
      /** Quasi-static coupling: one thermal step of the step control of
       *  coupling::QuasiStaticRelaxation, re-run shorter where too many
       *  joints break in it or its relaxation does not converge. */
      void
      quasi_static_step();
      /** The heat over @p dt [s], the new stretches, then the damped
       *  relaxation at these temperatures (no clock;
       *  coupling::QuasiStaticRelaxation::relax(): mass or kinetic damping,
       *  fracture events) until kinetic / strain energy and the
       *  out-of-balance force are below their tolerances or the cap of
       *  steps is reached. */
      void
      advance_thermal_step(const double dt);
      /** One mechanical step of the relaxation (the clock stays); true if
       *  a joint broke in it. */
      bool
      relaxation_step();
      /** Relaxation predictor = extrapolate: moves the free nodes on by
       *  the last relaxation's increment scaled to the thermal step @p dt
       *  [s] where QuasiStaticRelaxation::extrapolates() says so (the jump's
       *  energy to relaxation_work), and records the start of the next
       *  extrapolation. */
      void
      predict_relaxation(const double dt);
      /** The kinetic energy of the nodes, summed per chunk of tetrahedra
       *  on the solver's threads, the chunks in order [J]. */
      double
      kinetic_energy() const;
      /** Kinetic damping: every free velocity component to 0, the node
       *  back to the middle of the last step (where v^(n+1/2) lives); the
       *  kinetic energy removed goes to the damping account. */
      void
      reset_velocities();
      /** |out-of-balance force| / |internal force| over the free
       *  components of the nodes, at the current positions [-] (the
       *  elastic and joint forces there; the viscous ones left out). */
      double
      unbalanced_force();
      /** The state a thermal step may be re-run from (and a checkpoint
       *  would hold): clocks, nodes, stretches, stresses, joints, energies,
       *  reactions, the step control and the heat. */
      void
      put_state(CheckpointWriter &out) const;
      void
      get_state(CheckpointReader &in);
      /** Writes summary.json with @p what as the stop reason, then throws
       *  RunError naming the time, the step and @p what (the outputs
       *  written before stay). */
      [[noreturn]] void
      guard_failure(const std::string &what);
      /** The checkpoint's kind: the model and "(3D)". */
      std::string
      checkpoint_kind() const;
      /** Writes a checkpoint (Checkpoint/Interval, a stop signal): the
       *  state of put_state(), the output counters and series. */
      void
      write_checkpoint_file() const;
      /** Restores the newest checkpoint (--resume); returns the length of
       *  history.csv at it [bytes]. */
      std::uint64_t
      load_checkpoint();
      /** Checkpoints due after a step, and a stop signal (SIGTERM, SIGINT):
       *  checkpoint, summary.json, then StopRequested. */
      void
      after_step(CheckpointSchedule &schedule);
      void
      write_output();
      void
      write_history_row();
      void
      write_summary(const bool finished) const;

      const Parameters &parameters;
      MPI_Comm          communicator;
      const Physics     physics;
      bool              input_checked = false;

      Triangulation<3> triangulation;
      FE_SimplexDGP<3> fe;
      DoFHandler<3>    dof_handler;
      DiscreteModel    model;
      SofteningLaw     softening_law = SofteningLaw::munjiza;
      /** Joints' share of an element's compliance above which the
       *  compensation is capped (as in 2D) [-]. */
      static constexpr double max_compensated_share = 0.75;
      /** Tetrahedra whose compensation was capped, and the largest share
       *  of the material's compliance their joints take [-]. */
      unsigned int compensation_capped = 0;
      double       compensation_share  = 0.;
      /** Lame constants per element (compensated for the joints'
       *  compliance, Joint compliance compensation) [Pa] and viscosity eta
       *  [Pa s]. */
      std::vector<LameConstants> element_lame;
      std::vector<double>        viscosity;
      /** Anisotropic joint compliance compensation: Delta C of each
       *  tetrahedron, anisotropy_size<3> = 21 per element (solid.h) [Pa],
       *  and the factor f >= 1 with C_e <= f C(lame) for the stable step;
       *  both empty without it. */
      std::vector<double> element_anisotropy;
      std::vector<double> element_stiffness_bound;
      /** Delta C of element @p e (21 values), nullptr without the
       *  anisotropic compensation. */
      const double *
      anisotropy_of(const unsigned int e) const
      {
        return element_anisotropy.empty() ?
                 nullptr :
                 &element_anisotropy[anisotropy_size<3> * e];
      }
      /** Per joint and side: the face of its element (deal.II's face
       *  index, 0-3). */
      std::vector<unsigned char> joint_face;

      // heat
      std::unique_ptr<TetrahedralHeat> heat;
      /** Stress-free temperature per tetrahedron [C]. */
      std::vector<double> reference_temperature;
      /** Mechanical steps per thermal step (multi-rate). */
      unsigned long steps_per_thermal_step = 1;
      /** Time of the last thermal step [s]. */
      double        thermal_time    = 0.;
      unsigned long n_thermal_steps = 0;
      /** Coupling = quasi-static: the thermal steps and relaxations. */
      bool                            quasi_static = false;
      coupling::QuasiStaticRelaxation relaxation;
      /** The out-of-balance force of the last convergence check [-]. */
      double relative_unbalanced_force = 0.;

      // imposed motions
      std::vector<NodeConstraint> constraints;
      /** Per node: index into constraints, or -1. */
      std::vector<int> node_constraint;
      /** The functions of the imposed velocity components, of x, y, z
       *  (the node's reference position) and t. */
      std::vector<std::unique_ptr<FunctionParser<3>>> velocity_functions;
      /** Names of the owners of constraints (bodies and conditions), and
       *  their reaction forces of the last step [N]. */
      std::vector<std::string>           owner_names;
      std::vector<std::array<double, 3>> owner_reaction;
      bool                               imposed_depend_on_time = false;
      /** Some node component is held by a displacement condition. */
      bool imposed_displacements = false;
      /** Quasi-static coupling: the scale of the imposed velocities now
       *  (the ramp of the relaxation under way); NaN: not yet evaluated in
       *  this thermal step [-]. */
      double imposed_velocity_scale = 1.;

      // time
      double time             = 0.;
      double time_step        = 0.;
      double stable_time_step = 0.;
      /** Mass damping c of -c m v [1/s]. */
      double        mass_damping      = 0.;
      unsigned long step_number       = 0;
      unsigned int  n_threads         = 1;
      unsigned int  threads_requested = 0; ///< Discrete mechanics/Threads
      unsigned int  threads_available = 1; ///< cores this process may use
      unsigned int  threads_used = 1; ///< measured concurrency of the arena
      static constexpr unsigned int chunk_size = 512;
      /** Instruction set of the vector batches of the element and
       *  face-joint loops (Discrete mechanics/Vector instructions;
       *  tetrahedral_update.h). */
      VectorInstructions vector_instructions = VectorInstructions::none;
      /** Per chunk of elements: the works of the step (elastic, viscous,
       *  joint, external, damping, contact). */
      std::vector<std::array<double, 6>> chunk_works;
      /** Per chunk of elements: the largest squared node speed of the step
       *  (the contact search's travel) [m^2/s^2]. */
      std::vector<double> chunk_max_speed;

      // contact between tetrahedra (Contact = true; nullptr otherwise)
      std::unique_ptr<TetrahedronContactSystem> contact;
      /** Per tetrahedron: 1 if it has a contact pair with force (it takes
       *  the scalar node update, which adds the contact forces). */
      std::vector<char> element_in_contact;
      /** Per chunk and owner: the reactions of the step [N]. */
      std::vector<std::array<double, 3>> chunk_reaction;
      /** Per chunk of joints: one broke in the step. */
      std::vector<char> chunk_broke;
      /** Per chunk of elements: the first inverted element and the first
       *  node with a non-finite velocity of the step, or -1 (guards). */
      std::vector<std::array<long long, 2>> chunk_guard;
      /** Per chunk of elements: strain energy [J]. */
      std::vector<double> chunk_strain;
      /** kinetic_energy(): the sum per chunk of tetrahedra [J]. */
      mutable std::vector<double> chunk_kinetic;
      /** Kinetic energy at the start [J]. */
      double initial_kinetic = 0.;
      /** Why the run stopped early (summary.json); empty otherwise. */
      std::string stop_reason;
      Energies    energies;
      double      loop_wall_time = 0.; ///< wall time of the time loop [s]
      double      loop_cpu_time  = 0.; ///< process CPU time of the loop [s]
      /** CPU time of each thread in the loop, largest first [s]. */
      std::vector<double> loop_thread_cpu_times;
      double              element_steps = 0.;

      // output
      std::unique_ptr<VtuSeries> solution_series, crack_series;
      std::unique_ptr<CsvSeries> history_csv;
      std::vector<double>        output_times;
      unsigned int               next_output      = 0;
      double                     history_interval = 0.;
      double                     next_history     = 0.;
      /** The step of the last history row. */
      unsigned long history_step = 0;
    };
  } // namespace discrete
} // namespace tmfdem

#endif
