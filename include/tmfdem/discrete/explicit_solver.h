/**
 * @file
 * The explicit dynamics of the discrete layer (model `discrete mechanics`):
 * central differences (paper Eq. 2) over the exploded triangle mesh with
 * finite-strain triangles, cohesive joints and potential contact with
 * friction, bodies that are free, fixed or driven, gravity, energy
 * bookkeeping, and the output contract (solution.pvd, cracks.pvd,
 * probes.csv, lines.csv, history.csv, summary.json).
 */
#ifndef tmfdem_discrete_explicit_solver_h
#define tmfdem_discrete_explicit_solver_h

#include <deal.II/base/function_parser.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/tria.h>

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <tmfdem/base/parameters.h>
#include <tmfdem/base/simulation.h>
#include <tmfdem/coupling/quasi_static_relaxation.h>
#include <tmfdem/discrete/cohesive_law.h>
#include <tmfdem/discrete/contact_system.h>
#include <tmfdem/discrete/discrete_mesh.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/drivers.h>
#include <tmfdem/discrete/energy.h>
#include <tmfdem/discrete/partition.h>
#include <tmfdem/discrete/solid.h>
#include <tmfdem/discrete/stable_step.h>
#include <tmfdem/discrete/temperature_source.h>
#include <tmfdem/io/validation_report.h>
#include <vector>

namespace tmfdem
{
  class CheckpointWriter;
  class CheckpointReader;

  class CsvSeries;
  class CheckpointSchedule;

  namespace discrete
  {
    class VtuSeries;

    /** Explicit FDEM mechanics (paper Sec. 2). */
    class ExplicitSolver : public Simulation, public ValidationReporter
    {
    public:
      /** With @p with_heat, the model `discrete thermo-mechanics`: heat in
       *  the same exploded mesh, one thermal step every n mechanical steps,
       *  and F_T = s I from the element temperatures. */
      ExplicitSolver(const Parameters &parameters,
                     MPI_Comm          communicator,
                     const bool        with_heat = false);
      ~ExplicitSolver() override;

      void
      check_input() override;
      void
      run() override;

      /** What check_input() set up, for `--validate`. */
      void
      report_validation(std::ostream     &out,
                        const Parameters &parameters,
                        MPI_Comm          communicator) const override;

      /** The exploded mesh and its state. */
      DiscreteModel &
      get_model()
      {
        return model;
      }
      /** The FE_SimplexDGP(1) DoFHandler whose DoFs are the nodes. */
      const DoFHandler<2> &
      get_dof_handler() const
      {
        return dof_handler;
      }
      /** Explicit time step in use [s]. */
      double
      get_time_step() const
      {
        return time_step;
      }
      /** Stable time step of the mesh, penalties and damping [s]. */
      double
      get_stable_time_step() const
      {
        return stable_time_step;
      }
      /** Quasi-static coupling: the cap of each relaxation (mechanical
       *  steps per thermal step, after check_input); 0 otherwise. */
      unsigned int
      get_relaxation_cap() const
      {
        return quasi_static ? steps_per_thermal_step : 0;
      }
      /** The temperature source (thermo-mechanics, after check_input);
       *  nullptr without heat. */
      const TemperatureSource *
      get_temperature_source() const
      {
        return heat.get();
      }
      /** Advance by one explicit step. */
      void
      step();
      /** Current energy terms (computes kinetic and strain energy). */
      EnergyBalance
      energy();

    private:
      /** Per material constants of the solid. */
      struct SolidMaterial
      {
        LameConstants lame;
        double        density = 0.;
      };

      void
      setup_materials();
      /** Per-element Lame constants (element_lame): the material's, or
       *  compensated for the element's joints (Joint compliance
       *  compensation, joint_compliance.h); and the viscosity of the
       *  Damping ratio from them. */
      void
      setup_element_stiffness();
      /** Contact settings (penalties from the stiffest material, buffer
       *  from the smallest element) into `contact`. */
      void
      setup_contact();
      /** F_T = s I per element from its mean nodal temperature; the strain
       *  energy this changes at fixed geometry is booked as thermal work. */
      void
      update_thermal_stretch();
      /** Thermal expansion coefficient of element @p e [1/K]: its
       *  material's, times its random factor (Expansion heterogeneity). */
      double
      expansion_coefficient(const unsigned int e) const
      {
        const double alpha =
          parameters.materials[model.material[e]].thermal_expansion;
        return model.expansion_factor.empty() ?
                 alpha :
                 alpha * model.expansion_factor[e];
      }
      /** When imposed motions are evaluated in the step under way. */
      ImposedMotionClock
      imposed_motion_clock() const;
      void
      compute_stable_time_step();
      /**
       * What the stable-step bound of stable_step.h needs of element @p e:
       * its geometry (reference or @p deformed), Lame constants, viscosity,
       * node mass, the stiffness of its intact joints and the contact
       * springs' bound.
       */
      ElementStepInput
      element_step_input(const unsigned int e, const bool deformed) const;
      /** The fused node update (node_update.cc): element stresses and
       *  forces, joint and contact forces gathered per node, bodies and
       *  conditions, central-difference update, energy and reaction sums. */
      void
      update_nodes();
      /** The outputs at the current time (collective; rank 0 writes them
       *  with write_output_files()). */
      void
      write_output();
      /** On several ranks: every rank writes its piece of the solution and
       *  crack vtu files, rank 0 their pvtu records (collective; a failure
       *  on any rank stops every rank with its message). */
      void
      write_vtu_pieces();
      /** The solution vtu of the triangles [@p first, @p end) (one rank's
       *  piece; end = -1: to the last) with the temperature where heat
       *  runs and sigma_rr, sigma_tt where Mechanics/Polar frame asks. */
      std::string
      solution_vtu(
        const unsigned int first = 0,
        const unsigned int end   = static_cast<unsigned int>(-1)) const;
      void
      write_output_files();
      void
      write_history_row();
      void
      write_summary(const bool finished) const;

      const Parameters &parameters;
      MPI_Comm          communicator;
      bool              input_checked = false;

      Triangulation<2>           triangulation;
      FE_SimplexDGP<2>           fe;
      DoFHandler<2>              dof_handler;
      DiscreteModel              model;
      Idealisation               idealisation  = Idealisation::plane_stress;
      SofteningLaw               softening_law = SofteningLaw::munjiza;
      std::vector<SolidMaterial> solid;     ///< by material id
      std::vector<double>        viscosity; ///< eta per element [Pa s]
      /** Lame constants per element [Pa] (setup_element_stiffness()). */
      std::vector<LameConstants> element_lame;
      /** Anisotropic joint compliance compensation: Delta C per element,
       *  6 Mandel components [Pa] (joint_compliance.h); empty without. */
      std::vector<double> element_anisotropy;
      /** Factor f >= 1 per element with C_e <= f C(element_lame) (empty
       *  without the anisotropic compensation): the stable step's bound. */
      std::vector<double> element_stiffness_bound;
      /** Joints' share of an element's compliance above which the
       *  compensation is capped (the element at most 4 x stiffer) [-]. */
      static constexpr double max_compensated_share = 0.75;
      /** Triangles whose compensation was capped. */
      unsigned int compensation_capped = 0;
      /** Largest joints' share of an element's compliance [-]. */
      double compensation_share = 0.;

      // heat (thermo-mechanical runs)
      bool with_heat = false;
      /** The temperature source (Discrete heat/Temperature source). */
      std::unique_ptr<TemperatureSource> heat;
      /** On several ranks: the source advances each rank's own triangles
       *  (TemperatureSource::distribute()); else it runs on every rank on
       *  the whole state, synchronised before each thermal step. */
      bool heat_distributed = false;
      /** The temperatures and thermal stretches of the other ranks are
       *  current (gathered by synchronise() since the last thermal step). */
      bool thermal_state_gathered = true;
      /** A source blind to cracks went on past a broken joint (accepted). */
      bool heat_across_cracks = false;
      /** Before a thermal step: stop (or warn once) if joints are broken and
       *  the temperature source does not see cracks. */
      void
      check_cracks_seen_by_heat();
      /** Multi-rate coupling: mechanical steps per thermal step;
       *  quasi-static coupling: the cap of each relaxation (Discrete
       *  heat/Mechanical steps per thermal step, or automatic). */
      unsigned int steps_per_thermal_step = 1;
      /** Discrete heat/Coupling = quasi-static: each step() is a thermal
       *  step and a relaxation (coupling/quasi_static_relaxation.h). */
      bool quasi_static = false;
      /** |out-of-balance force| / |internal element forces| over the free
       *  node components after the last step (viscous force left out) [-]. */
      double relative_unbalanced_force = 0.;
      /** Kinetic energy sum 1/2 m |v|^2 after the last step [J/m]. */
      double step_kinetic = 0.;
      /**
       * Relaxation damping = kinetic: sets the velocities of the free node
       * components to zero (the kinetic energy has just passed a peak),
       * booking the energy removed as viscous dissipation.
       */
      void
      reset_velocities();
      /** Quasi-static coupling: the relaxation, its predictor's start and
       *  the thermal step control (coupling/quasi_static_relaxation.h). */
      coupling::QuasiStaticRelaxation relaxation;
      /** Keeps the whole state of this rank (synchronised) in
       *  relaxation.thermal_step_start. */
      void
      keep_thermal_step_start();
      /** Returns to the state of keep_thermal_step_start(). */
      void
      restore_thermal_step_start();
      /** The thermal step @p dt [s] and its relaxation, without the
       *  step control (source/coupling/discrete_thermo_mechanics.cc). */
      void
      advance_thermal_step(const double dt);
      /** The clocks, counters and state that a thermal step changes (the
       *  part that a checkpoint and a re-run step share). */
      void
      put_state(CheckpointWriter &out) const;
      void
      get_state(CheckpointReader &in);
      /**
       * Relaxation predictor = extrapolate, before the relaxation of a
       * thermal step @p dt [s]: moves the free node components by the last
       * relaxation's increment times dt / (its thermal step), booking the
       * strain and joint energy this changes as relaxation_work.
       */
      void
      predict_relaxation(const double dt);
      /** Thermal steps taken (multi-rate and quasi-static coupling). */
      unsigned long n_thermal_steps = 0;
      /** Stress-free temperature per element [C]. */
      std::vector<double> reference_temperature;
      /** One explicit mechanical step without advancing the clock. */
      void
      mechanical_step();
      /** Before a thermal step: the contact search brought up to date and
       *  the source's conducting pairs taken from it. */
      void
      update_heat_contact_pairs();
      /** Multi-rate coupling, after the mechanical step that completes a
       *  thermal step: heat over it, then the thermal stretch
       *  (source/coupling/discrete_thermo_mechanics.cc). */
      void
      multi_rate_thermal_step();
      /** Quasi-static coupling: one thermal step, then the relaxation of
       *  the mechanics at its temperatures
       *  (source/coupling/discrete_thermo_mechanics.cc). */
      void
      quasi_static_step();
      /** Time the temperature source has reached [s]. */
      double thermal_time = 0.;

      /** Bodies, gravity and boundary conditions, and their reactions. */
      Drivers drivers;
      /** Contact: pair search, law, pair forces. */
      ContactSystem contact;
      /** The triangles this rank owns and the exchanges with the others
       *  (one rank: owns all, exchanges nothing). */
      ElementPartition partition;
      /** Step at which the whole state was last gathered on every rank. */
      unsigned long synchronised_step = static_cast<unsigned long>(-1);
      /** Joints broke in this rank's part during the step under way. */
      bool joints_broke = false;
      /** Joints broke on some rank in the last step (update_nodes()). */
      bool joints_broke_anywhere = false;
      /**
       * Gives every rank the whole state (partition.h) unless it already
       * has it at this step; a no-op on one rank. Called before whatever
       * reads the whole state: contact search, heat, energy, outputs,
       * checkpoints, guards.
       */
      void
      synchronise();
      /** The contact search (on several ranks: by bounding boxes, unless
       *  the whole state is there anyway), then the ghost plan from its
       *  pairs. */
      void
      search_contacts();
      /**
       * The overlap guard, after a contact search once the fastest node
       * has travelled half the search buffer since the last check (so no
       * pair passes through unseen): the largest overlap of a force-carrying
       * pair against the smaller triangle's area. With @p initial (set-up): an
       * overlap of two triangles not joined beyond max_initial_overlap is bad
       * input (InputError naming them and their bodies); later, an overlap
       * beyond max_contact_overlap stops the run (guard: the contact penalty is
       * too soft for the impact).
       */
      void
      check_contact_overlap(const bool initial);
      /** Overlap area / smaller triangle area beyond which contact has
       *  failed: about a quarter of the smaller altitude pressed flat in. */
      static constexpr double max_contact_overlap = 0.5;
      /** The same at the start: about 5 % of the altitude pressed flat in;
       *  a deliberate press (prm/contact_conduction.prm: 10 micrometres
       *  at element sizes of millimetres) stays below it. */
      static constexpr double max_initial_overlap = 0.1;
      /** Broken joints on all ranks (collective; no synchronisation). */
      unsigned int
      n_broken_joints() const;
      /** This rank writes the files (rank 0). */
      bool
      writes_files() const
      {
        return partition.rank() == 0;
      }

      // time
      double        time              = 0.;
      double        time_step         = 0.;
      double        stable_time_step  = 0.;
      unsigned long step_number       = 0;
      unsigned int  n_threads         = 1;
      unsigned int  threads_requested = 0; ///< Discrete mechanics/Threads
      unsigned int  threads_available = 1; ///< cores this process may use
      unsigned int  threads_used = 1; ///< measured concurrency of the arena
      /** Instruction set of the loop's batches (Vector instructions). */
      VectorInstructions vector_instructions = VectorInstructions::none;
      /** Triangle-steps and joint-steps of this run done in vector batches
       *  (summary.json vectorised_element_share, _joint_share). */
      double vectorised_element_steps = 0., vectorised_joint_steps = 0.;
      /** Triangle-steps and intact-joint-steps of this run. */
      double element_steps_done = 0., joint_steps_done = 0.;
      double loop_cpu_time  = 0.; ///< process CPU, time loop [s]
      double loop_wall_time = 0.; ///< wall, time loop, this run [s]
      /** Wall time this rank spent composing and writing the solution and
       *  crack vtu files (pieces, records and pvd) in this run
       *  (summary.json vtu_write_time_s: the largest of the ranks) [s]. */
      double vtu_write_time = 0.;
      /// CPU time of each thread in the time loop, largest first [s]
      std::vector<double> loop_thread_cpu_times;

      // bookkeeping: per chunk sums, summed in chunk order (thread-count
      // independent)
      static constexpr unsigned int chunk_size = 512;
      static constexpr unsigned int n_sums     = 13;
      /** n_sums + 2 bodies + 2 conditions per chunk */
      std::vector<double> chunk_sums;
      EnergyBalance       balance;
      /** per chunk of the joint forces: breaks, joints, batches */
      std::vector<JointChunkTally> joint_tally;

      // output
      std::unique_ptr<VtuSeries>   solution_series, crack_series;
      std::unique_ptr<CsvSeries>   history_csv, probes_csv, lines_csv;
      std::vector<double>          output_times;
      unsigned int                 next_output      = 0;
      double                       history_interval = 0.;
      double                       next_history     = 0.;
      double                       wall_time        = 0.;
      std::vector<ReferenceSample> probe_samples, line_samples;

      // ------------------------------------------ reliability (checkpoints,
      // --resume, signals, guards; doc/reliability.md)
      /** Kind of run in checkpoints: the model name. */
      std::string
      checkpoint_kind() const;
      /** Writes a checkpoint of the complete state after the current step
       *  (atomically; the newest Checkpoint/Keep are kept); collective, rank
       *  0 writes. */
      void
      save_checkpoint();
      /** The file of save_checkpoint() (this rank writes it). */
      void
      write_checkpoint_file();
      /** Runs @p write on rank 0; if it throws there, every rank throws
       *  RunError with its message (no rank is left waiting). */
      void
      on_rank_zero(const std::function<void()> &write) const;
      /** after_step() calls, for the collective checks every 16th. */
      unsigned long after_step_calls = 0;
      /** Restores the newest checkpoint (--resume): state, clocks, energy
       *  and heat balance, contact history, output counters; CSV files are
       *  cut to their length at the checkpoint, pvd series to its records. */
      void
      load_checkpoint();
      /** A CSV series: new with @p header, or continued on --resume. */
      std::unique_ptr<CsvSeries>
      open_csv(const std::string &file_name, const std::string &header) const;
      /** After every step: a checkpoint when due; on SIGINT/SIGTERM the
       *  outputs, a checkpoint and StopRequested. */
      void
      after_step(CheckpointSchedule &schedule);
      /** Every step (cheap flags from the force kernel): non-finite
       *  velocities, inverted elements (J <= 0). Throws RunError. */
      void
      check_step_guards()
      {
        if (first_nonfinite_node >= 0 || first_inverted_element >= 0)
          step_guard_failure();
      }
      void
      step_guard_failure();
      /** With the history rows: non-finite temperatures, the time step
       *  against the stable step of the deformed mesh, runaway kinetic
       *  energy; if all pass, the state is kept as the last good one. */
      void
      check_slow_guards();
      /** Writes failure_state.vtu (now), last_good_state.vtu and
       *  summary.json, then throws RunError(@p message). */
      [[noreturn]] void
      guard_failure(const std::string &message);
      /** Keeps the current state as the last good state (no allocation
       *  after the first call). */
      void
      keep_good_state();

      /** First node with a non-finite velocity in the last step, or -1. */
      long long first_nonfinite_node = -1;
      /** First element with J <= 0 in the last step, or -1. */
      long long     first_inverted_element = -1;
      std::uint64_t history_bytes = 0, probes_bytes = 0, lines_bytes = 0;
      std::string   stop_reason; ///< in summary.json when the run stopped
      double        resumed_wall_time = 0.; ///< wall time before --resume [s]
      struct GoodState
      {
        double                   time = 0.;
        unsigned long            step = 0;
        std::vector<double>      x, y, vx, vy, stress, damage, break_time, T;
        std::vector<JointStatus> status;
        bool                     valid = false;
      } good_state;
    };
  } // namespace discrete
} // namespace tmfdem

#endif
