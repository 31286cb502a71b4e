/**
 * @file
 * The state of the quasi-static coupling of the discrete thermo-mechanics
 * (Discrete heat/Coupling = quasi-static; theory manual, "Coupling"): the
 * relaxation under way (its step, the ramp of the imposed motion), the last
 * relaxation (its length, convergence, energy ratio), the start of the
 * relaxation predictor, the thermal step control through the fracture
 * process (utilisation, break rate, last step, the state kept to re-run a
 * step) and the counters that summary.json reports. discrete::ExplicitSolver
 * holds one; its coupling loop (source/coupling/discrete_thermo_mechanics.cc)
 * runs the relaxations and steps, and the checkpoint writes this state with
 * save_step_control() and save_relaxation().
 */
#ifndef tmfdem_coupling_quasi_static_relaxation_h
#define tmfdem_coupling_quasi_static_relaxation_h

#include <algorithm>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <tmfdem/base/parameters.h>
#include <vector>

namespace tmfdem
{
  class CheckpointWriter;
  class CheckpointReader;

  namespace coupling
  {
    /** Quasi-static relaxation and thermal step control of the discrete
     *  thermo-mechanics: its state and the decisions that read only it. */
    class QuasiStaticRelaxation
    {
    public:
      /** @p parameters: the run's (Time stepping, Discrete heat), read when
       *  a step is chosen; they must outlive this object. */
      explicit QuasiStaticRelaxation(const Parameters &parameters);
      ~QuasiStaticRelaxation();

      // ------------------------------------------------------- the ramp

      /** Relaxation steps over which the motion imposed in one thermal step
       *  is ramped in where the drivers impose motion. */
      static constexpr unsigned int ramp_steps = 100;
      /**
       * The motion imposed over one thermal step (velocity conditions and
       * driven bodies: v dt_thermal; displacement conditions:
       * u(t) - u(t - dt_thermal)) is spread evenly over the first this many
       * relaxation steps; 0 where nothing is imposed (set_ramp()).
       */
      unsigned int quasi_static_ramp_steps = 0;
      /** Sets quasi_static_ramp_steps: ramp_steps where the run @p imposes
       *  motion (@p what: "velocities" or "velocities or displacements",
       *  for the message), else 0; throws InputError where the relaxation
       *  cap @p steps_per_thermal_step (Discrete heat/Mechanical steps per
       *  thermal step) leaves too few steps after the ramp. */
      void
      set_ramp(const bool         imposes,
               const unsigned int steps_per_thermal_step,
               const std::string &what);
      /** Length of the current thermal step [s]. */
      double current_thermal_step = 0.;
      /** Index of the relaxation step under way; quasi_static_ramp_steps + 1
       *  once a relaxation has ended. */
      unsigned int relaxation_step = 0;

      /** Factor from a physical velocity to the velocity of the relaxation
       *  step under way: dt_thermal / (ramp dt) during the ramp, 0 after
       *  it; @p time_step: the mechanical step dt [s]. */
      double
      imposed_velocity_scale(const double time_step) const
      {
        return relaxation_step < quasi_static_ramp_steps ?
                 current_thermal_step / (quasi_static_ramp_steps * time_step) :
                 0.;
      }
      /** Relaxation steps until the imposed displacements reach their target
       *  (the end of the ramp); 1 after it. */
      double
      steps_to_ramp_end() const
      {
        return relaxation_step < quasi_static_ramp_steps ?
                 quasi_static_ramp_steps - relaxation_step :
                 1.;
      }
      /** The imposed motion of the relaxation step under way differs from
       *  that of the step before: during the ramp and in the first step
       *  after it (where it drops to zero). */
      bool
      imposed_motion_changes() const
      {
        return relaxation_step <= quasi_static_ramp_steps;
      }

      // -------------------------------------------------- the relaxation

      /** Energy below which the body counts as unloaded and relaxed: that
       *  of a uniform strain of 1e-10 at the materials' E, 1e-20 sum E A
       *  [J/m] (set by ExplicitSolver::check_input()). */
      double unloaded_energy = 0.;
      /** Mechanical steps of the last relaxation. */
      unsigned int last_relaxation_steps = 0;
      /** Kinetic / strain energy at the last convergence check [-]. */
      double last_kinetic_to_strain = 0.;
      /** Whether the last relaxation converged (did not reach its cap):
       *  the predictor extrapolates only from one that did, not from one
       *  whose increment holds motion still under way (free pieces
       *  drifting after a fracture event). */
      bool last_relaxation_converged = true;
      /** Whether the relaxation before the last one converged: the last
       *  relaxation's increment then runs from one equilibrium to the next.
       *  After a relaxation cut off at its cap (typically by a fracture
       *  event) the next one converges, but its increment holds the pieces
       *  settling after the event: extrapolated, they are pushed into each
       *  other (on a mesh of 1.75 mm this put 78 J/m, half the thermal
       *  work, into a stress-free cracked ring). */
      bool previous_relaxation_converged = true;
      /** Relaxations that ended at the step cap. */
      unsigned int relaxations_at_cap = 0;
      /** Relaxation damping = kinetic: velocity resets so far. */
      unsigned long velocity_resets = 0;
      /** Fracture event duration > 0: relaxations in which a fracture
       *  event paused the velocity resets, and their mechanical steps. */
      unsigned long fracture_events = 0, fracture_event_steps = 0;

      /** At the end of a relaxation of @p steps mechanical steps that
       *  @p converged (or reached its cap): its record, and the ramp over. */
      void
      finish_relaxation(const unsigned int steps, const bool converged)
      {
        relaxation_step               = quasi_static_ramp_steps + 1;
        last_relaxation_steps         = steps;
        previous_relaxation_converged = last_relaxation_converged;
        last_relaxation_converged     = converged;
      }

      // ------------------------------------------------ one relaxation

      /** What relax() reads of Discrete heat: the damping, the fracture
       *  event and the convergence tolerances. */
      struct Control
      {
        /** Relaxation damping = kinetic: velocities reset at each peak of
         *  the kinetic energy. */
        bool kinetic_damping = false;
        /** Fracture event duration in mechanical steps (0: none). */
        unsigned int event_length = 0;
        /** Relaxation tolerance (kinetic / strain energy) and Relaxation
         *  force tolerance (out-of-balance force) [-]. */
        double tolerance = 0., force_tolerance = 0.;
        /** Maximum broken joints per step (0: no re-runs) and Maximum
         *  utilisation change (0: off). */
        unsigned int maximum_broken_joints      = 0;
        double       maximum_utilisation_change = 0.;
        /** Relaxation cap is error. */
        bool cap_is_error = false;
      };
      /** The Control of the run's Discrete heat for the mechanical step
       *  @p time_step [s]. */
      Control
      control(const double time_step) const;

      /** A solver's energies at a convergence check of relax() [J]. */
      struct Energies
      {
        double kinetic = 0.;
        double strain  = 0.;
        /** The energy an unloaded body holds at round-off level: the
         *  strain energy and what the joints store. */
        double stored = 0.;
      };

      /**
       * One relaxation at fixed temperatures (theory manual 8), written
       * once for the triangles and the tetrahedra: at most @p max_steps
       * mechanical steps of @p solver, with the velocity resets of
       * kinetic damping, the fracture events (a joint breaks: the resets
       * pause for event_length steps, then every node comes to rest) and a
       * convergence check every 50 steps (kinetic / strain energy, the
       * out-of-balance force, or an unloaded body); the record in
       * finish_relaxation(). @p solver provides
       *   bool relaxation_step()          one step; true if a joint broke,
       *   double step_kinetic()           the kinetic energy after it [J],
       *   void reset_velocities()         every free node at rest,
       *   Energies relaxation_energies()  the energies at a check,
       *   double relative_unbalanced_force()  the out-of-balance force [-].
       * Returns true if the relaxation converged.
       */
      template <typename Solver>
      bool
      relax(Solver &solver, const unsigned int max_steps, const Control &c)
      {
        unsigned int i       = 0;
        bool         relaxed = false;
        // kinetic damping: the kinetic energy of the last step and the
        // largest one since the last check (a reset just before a check
        // must not pass for convergence)
        double previous_kinetic = 0., window_kinetic = 0.;
        // once a joint breaks, the resets pause until step event_end, so
        // that the fracture runs with inertia (counted again from every
        // later break)
        unsigned int event_end = 0;
        bool         had_event = false;
        while (i < max_steps)
          {
            relaxation_step  = i;
            const bool broke = solver.relaxation_step();
            ++i;
            if (c.event_length > 0 && broke)
              {
                event_end = i + c.event_length;
                had_event = true;
              }
            const bool in_event = i < event_end;
            if (in_event)
              {
                ++fracture_event_steps;
                const double kinetic = solver.step_kinetic();
                window_kinetic       = std::max(window_kinetic, kinetic);
                previous_kinetic     = kinetic;
              }
            else if (i == event_end)
              {
                // the event is over: every piece comes to rest (as on the
                // real support); a free piece drifting at constant speed
                // has no peak of kinetic energy for the damping to catch
                window_kinetic =
                  std::max(window_kinetic, solver.step_kinetic());
                solver.reset_velocities();
                previous_kinetic = 0.;
              }
            else if (c.kinetic_damping)
              {
                const double kinetic = solver.step_kinetic();
                window_kinetic       = std::max(window_kinetic, kinetic);
                if (kinetic < previous_kinetic)
                  {
                    solver.reset_velocities();
                    previous_kinetic = 0.;
                  }
                else
                  previous_kinetic = kinetic;
              }
            // convergence checks, not while a fracture event runs (it is
            // not over until event_end, whatever its energies say)
            if (i % 50 == 0 && !in_event)
              {
                const Energies e = solver.relaxation_energies();
                const double   kinetic =
                  c.kinetic_damping ? window_kinetic : e.kinetic;
                last_kinetic_to_strain = kinetic / std::max(e.strain, 1e-300);
                // an unloaded body: energies at round-off level, where the
                // ratios measure noise and could never pass
                const bool unloaded =
                  e.stored < unloaded_energy && kinetic < unloaded_energy;
                window_kinetic = 0.;
                if (i > quasi_static_ramp_steps && unloaded)
                  {
                    relaxed = true;
                    break;
                  }
                if (i > quasi_static_ramp_steps &&
                    last_kinetic_to_strain < c.tolerance &&
                    solver.relative_unbalanced_force() <= c.force_tolerance)
                  {
                    relaxed = true;
                    break;
                  }
              }
          }
        finish_relaxation(i, relaxed);
        if (had_event)
          ++fracture_events;
        return relaxed;
      }

      /**
       * One thermal step of the quasi-static coupling from the step dt
       * [s] that next_thermal_step() chose, written once for triangles and
       * tetrahedra: the joints' utilisation and damage at its start, the
       * step (the heat and relax()) re-run shorter from its start while
       * too many joints break in it or its relaxation does not converge
       * where damage grew (down to minimum_thermal_step(): unstable), then
       * accept_thermal_step(), the rise of the utilisation and the cap
       * warning (or error). @p solver provides
       *   void joint_damages(std::vector<double> &),
       *   void joint_utilisations(std::vector<double> &),
       *   void keep_thermal_step_start(), restore_thermal_step_start(),
       *   void advance_thermal_step(double dt)   the heat, then relax(),
       *   double time(), bool writes_files(), unsigned int cap(),
       *   double relative_unbalanced_force(),
       *   void guard_failure(const std::string &).
       */
      template <typename Solver>
      void
      thermal_step(Solver &solver, double dt, const Control &c)
      {
        const bool          control_breaks = c.maximum_broken_joints > 0;
        std::vector<double> utilisation_start, damage_start, damage_end;
        if (c.maximum_utilisation_change > 0.)
          solver.joint_utilisations(utilisation_start);
        if (control_breaks)
          {
            solver.joint_damages(damage_start);
            solver.keep_thermal_step_start();
          }
        const double minimum_step  = minimum_thermal_step();
        bool         unstable      = false;
        unsigned int broke_in_step = 0;
        while (true)
          {
            solver.advance_thermal_step(dt);
            if (!control_breaks)
              break;
            // joints that broke in this step (their onset of damage is
            // resolved by the utilisation control)
            solver.joint_damages(damage_end);
            bool damage_grew = false;
            count_breaks(damage_start, damage_end, broke_in_step, damage_grew);
            // an unconverged relaxation is re-run only where damage grew in
            // the step (a crack that runs): without fracture, a shorter
            // step does not help a cap that is too low for the load, which
            // the count of relaxations at the cap reports
            if (resolves_thermal_step(broke_in_step, damage_grew))
              break;
            if (dt <= minimum_step * (1. + 1e-12))
              {
                // no shorter step resolves it: the crack runs at this load
                // (unstable propagation, with inertia where Fracture event
                // duration says so)
                unstable = true;
                ++unstable_thermal_steps;
                break;
              }
            // re-run from the start of the step, shorter
            solver.restore_thermal_step_start();
            ++rejected_thermal_steps;
            dt = std::max(minimum_step, rerun_factor(broke_in_step) * dt);
            if (solver.writes_files())
              std::cerr << rerun_message(solver.time(), broke_in_step, dt, c);
          }
        // the next step shrinks by allowed / broke_in_step where more broke
        // than allowed
        accept_thermal_step(dt, unstable, broke_in_step);
        if (c.maximum_utilisation_change > 0.)
          {
            std::vector<double> utilisation_end;
            solver.joint_utilisations(utilisation_end);
            record_utilisation(utilisation_start,
                               utilisation_end,
                               dt,
                               unstable);
          }
        if (!last_relaxation_converged)
          {
            ++relaxations_at_cap;
            if (relaxations_at_cap == 1)
              std::cerr << cap_warning(solver.time(),
                                       solver.cap(),
                                       solver.relative_unbalanced_force(),
                                       control_breaks,
                                       c);
            if (c.cap_is_error)
              solver.guard_failure(cap_error(solver.time(), solver.cap()));
          }
      }

      // -------------------- the predictor (Relaxation predictor = extrapolate)

      /** Node positions at the end of the last relaxation [m] (relaxed_z:
       *  tetrahedra only, empty for triangles). */
      std::vector<double> relaxed_x, relaxed_y, relaxed_z;
      /** The thermal step of the last relaxation [s]; 0 before the first. */
      double relaxed_thermal_step = 0.;
      /** Joints damaged or broken at the start of the last relaxation and
       *  at its end: the predictor extrapolates only where they agree. */
      unsigned int damaged_before_relaxation = 0, damaged_after_relaxation = 0;
      /** Relaxations started from an extrapolated state. */
      unsigned int predicted_relaxations = 0;

      /**
       * Whether the next relaxation starts from the last one's increment
       * extrapolated: there is a last relaxation of a model of @p n_nodes
       * nodes, it and the one before it converged, and it neither damaged
       * nor broke joints, nor did any since (@p damaged: the joints damaged
       * or broken now). Else the increment holds a crack's jump or motion
       * still under way (free pieces drifting or settling after a fracture
       * event: pushed on, they overlap and the contact and the joints push
       * them apart again).
       */
      bool
      extrapolates(const std::size_t n_nodes, const unsigned int damaged) const
      {
        return relaxed_thermal_step > 0. && relaxed_x.size() == n_nodes &&
               last_relaxation_converged && previous_relaxation_converged &&
               damaged_before_relaxation == damaged_after_relaxation &&
               damaged == damaged_after_relaxation;
      }

      // ------------------------------------------- the thermal step control

      /** Strength utilisation of the most loaded undamaged joint after the
       *  last relaxation [-]. */
      double joint_utilisation = 0.;
      /** Its rate over the last thermal step [1/s]. */
      double joint_utilisation_rate = 0.;
      /**
       * Thermal step control through the fracture process (Discrete
       * heat/Maximum broken joints per step): the joints that broke per unit
       * time over the last accepted thermal step, where more broke than
       * allowed and the step was resolved (not an unstable event); 0
       * otherwise [1/s].
       */
      double break_rate = 0.;
      /** The last accepted thermal step [s]; 0 before the first. */
      double last_thermal_step = 0.;
      /** Thermal steps re-run shorter: more than twice Maximum broken
       *  joints per step broke in them, or their relaxation did not
       *  converge. */
      unsigned long rejected_thermal_steps = 0;
      /** Thermal steps accepted at Minimum thermal step although too many
       *  joints failed in them or the relaxation reached its cap: crack
       *  growth that no shorter step resolves (unstable propagation, run as
       *  a fracture event). */
      unsigned long unstable_thermal_steps = 0;
      /** The solver's state at the start of the thermal step under way (a
       *  step that is re-run starts from it again); null when not kept. */
      std::unique_ptr<CheckpointWriter> thermal_step_start;

      /**
       * Records for next_thermal_step() the joints' strength utilisations
       * @p start and @p end of a thermal step of @p dt [s] (one per joint,
       * negative for a damaged joint): the rate [1/s] at which the joint
       * that uses up its allowance fastest rose, scaled so that the next
       * step is at most Maximum utilisation change / rate (joint j may rise
       * by max(Maximum utilisation change, Utilisation margin fraction x
       * (1 - U_j)) per step; only joints undamaged at both ends count, so a
       * joint that became damaged leaves the set and the most loaded one
       * before it does not stand for the others), 0 for an @p unstable
       * step, and the highest utilisation at its end.
       */
      void
      record_utilisation(const std::vector<double> &start,
                         const std::vector<double> &end,
                         const double               dt,
                         const bool                 unstable);

      /**
       * The next thermal step [s]: Time stepping/Time step grown by Discrete
       * heat/Thermal step growth factor per step taken
       * (@p n_thermal_steps), at most twice the last accepted step, limited
       * by the predicted rise of the joints' utilisation and by their break
       * rate, landing on the end time and on @p next_output_time [s] (the
       * next requested output time, if any); @p time: now [s].
       */
      double
      next_thermal_step(const double                time,
                        const unsigned long         n_thermal_steps,
                        const std::optional<double> next_output_time) const;
      /** The shortest thermal step the step control takes (Discrete
       *  heat/Minimum thermal step, or 1e-3 Time step) [s]. */
      double
      minimum_thermal_step() const;
      /** Whether a thermal step in which @p joints_broken joints broke is
       *  accepted: at most twice the allowed number broke in it and its
       *  relaxation converged, or it did not, but no damage grew in the step
       *  (@p damage_grew; a shorter step does not help a cap that is too low
       *  for the load). */
      bool
      resolves_thermal_step(const unsigned int joints_broken,
                            const bool         damage_grew) const;
      /** The factor by which a thermal step in which @p joints_broken joints
       *  broke is re-run shorter: the one that brings the breaks to half the
       *  allowed number, were they proportional to the step (at most 0.25:
       *  breaks that do not become fewer with the step are an instability,
       *  whose load a few cuts then find) [-]. */
      double
      rerun_factor(const unsigned int joints_broken) const;
      /** Records the accepted thermal step @p dt [s] and, where the breaks
       *  are controlled, the break rate from the @p joints_broken joints
       *  that broke in it (none where it was @p unstable or at most the
       *  allowed number broke: a single break in a short step says nothing
       *  of a rate). */
      void
      accept_thermal_step(const double       dt,
                          const bool         unstable,
                          const unsigned int joints_broken);

      // ------------------------------------------------------ checkpoints

      /** Writes the relaxation's record and the step control's state (the
       *  checkpoint's clocks, after the thermal clock). */
      void
      save_step_control(CheckpointWriter &out) const;
      /** Reads what save_step_control() wrote. */
      void
      load_step_control(CheckpointReader &in);
      /** Writes the predictor's start and the relaxation counters (the
       *  checkpoint's part after the reactions). */
      void
      save_relaxation(CheckpointWriter &out) const;
      /** Reads what save_relaxation() wrote. */
      void
      load_relaxation(CheckpointReader &in);

    private:
      const Parameters &parameters;

      /** The joints that broke between @p start and @p end (damage
       *  reached 1) into @p broken, whether any damage grew into
       *  @p grew. */
      static void
      count_breaks(const std::vector<double> &start,
                   const std::vector<double> &end,
                   unsigned int              &broken,
                   bool                      &grew);
      /** The line that says a thermal step is re-run. */
      static std::string
      rerun_message(const double       time,
                    const unsigned int broken,
                    const double       dt,
                    const Control     &c);
      /** The warning of the first relaxation at its cap of @p cap steps. */
      std::string
      cap_warning(const double       time,
                  const unsigned int cap,
                  const double       unbalanced_force,
                  const bool         control_breaks,
                  const Control     &c) const;
      /** The error of Relaxation cap is error. */
      static std::string
      cap_error(const double time, const unsigned int cap);
    };
  } // namespace coupling
} // namespace tmfdem

#endif
