#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/coupling/quasi_static_relaxation.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/io/checkpoint.h>

namespace tmfdem
{
  namespace coupling
  {
    QuasiStaticRelaxation::QuasiStaticRelaxation(const Parameters &parameters)
      : parameters(parameters)
    {}

    QuasiStaticRelaxation::~QuasiStaticRelaxation() = default;

    QuasiStaticRelaxation::Control
    QuasiStaticRelaxation::control(const double time_step) const
    {
      const auto &dh = parameters.get<DiscreteHeatParameters>();
      Control     c;
      c.kinetic_damping = dh.relaxation_damping ==
                          DiscreteHeatParameters::RelaxationDamping::kinetic;
      const double event_duration = dh.fracture_event_duration;
      c.event_length =
        event_duration > 0. ?
          static_cast<unsigned int>(
            std::min(std::ceil(event_duration / time_step), double(1u << 30))) :
          0u;
      c.tolerance                  = dh.relaxation_tolerance;
      c.force_tolerance            = dh.relaxation_force_tolerance;
      c.maximum_broken_joints      = dh.maximum_broken_joints_per_step;
      c.maximum_utilisation_change = dh.maximum_utilisation_change;
      c.cap_is_error               = dh.relaxation_cap_is_error;
      return c;
    }

    void
    QuasiStaticRelaxation::count_breaks(const std::vector<double> &start,
                                        const std::vector<double> &end,
                                        unsigned int              &broken,
                                        bool                      &grew)
    {
      broken = 0;
      grew   = false;
      for (std::size_t j = 0; j < start.size(); ++j)
        {
          broken += start[j] < 1. && end[j] >= 1.;
          grew |= end[j] > start[j];
        }
    }

    void
    QuasiStaticRelaxation::record_utilisation(const std::vector<double> &start,
                                              const std::vector<double> &end,
                                              const double               dt,
                                              const bool unstable)
    {
      // each joint may use up, per thermal step, Maximum utilisation change
      // or, once a joint of the model is damaged, the fraction Utilisation
      // margin fraction of its margin to the peak (1 - U), whichever is
      // larger: near the peak the change rules, farther from it a joint
      // may rise faster, so that the ups and downs of joints far from their
      // strength from one relaxation to the next (friction and contact
      // make its end state path dependent) do not hold the step. Before
      // the first damage the load rises smoothly and the change alone
      // keeps the thermal steps short enough for the heat's time
      // integration to bring the stress to the strength at the right time.
      // The rate is scaled to the change, so that the next step is at most
      // change / rate. (U < 0: a damaged or broken joint.)
      const DiscreteHeatParameters &dh =
        parameters.get<DiscreteHeatParameters>();
      const double change  = dh.maximum_utilisation_change;
      const bool   damaged = std::any_of(end.begin(),
                                       end.end(),
                                       [](const double u) { return u < 0.; });
      const double margin_fraction =
        damaged ? dh.utilisation_margin_fraction : 0.;
      double rise = 0., highest = 0.;
      for (std::size_t j = 0; j < end.size(); ++j)
        if (end[j] >= 0.)
          {
            highest = std::max(highest, end[j]);
            if (start[j] >= 0. && end[j] > start[j])
              {
                const double allowed =
                  std::max(change, margin_fraction * (1. - end[j]));
                rise = std::max(rise,
                                (end[j] - start[j]) *
                                  (allowed > 0. ? change / allowed : 1.));
              }
          }
      joint_utilisation_rate = unstable ? 0. : rise / dt;
      joint_utilisation      = highest;
    }

    std::string
    QuasiStaticRelaxation::rerun_message(const double       time,
                                         const unsigned int broken,
                                         const double       dt,
                                         const Control     &c)
    {
      std::ostringstream message;
      message << "[tmfdem] t = " << time << " s: thermal step re-run "
              << (broken > 2. * c.maximum_broken_joints ?
                    "(" + std::to_string(broken) + " joints broke in it)" :
                    std::string("(the relaxation did not converge)"))
              << " with " << dt << " s\n";
      return message.str();
    }

    std::string
    QuasiStaticRelaxation::cap_warning(const double       time,
                                       const unsigned int cap,
                                       const double       unbalanced_force,
                                       const bool         control_breaks,
                                       const Control     &c) const
    {
      std::ostringstream message;
      message << "[tmfdem] warning: at t = " << time
              << " s the relaxation reached its cap of " << cap
              << " mechanical steps (Discrete heat/Mechanical steps per "
                 "thermal step) with kinetic / strain energy "
              << last_kinetic_to_strain
              << " above Relaxation tolerance = " << c.tolerance
              << " or the out-of-balance force " << unbalanced_force
              << " above Relaxation force tolerance = " << c.force_tolerance
              << ": the state is not in equilibrium"
              << (control_breaks ? ", also with Minimum thermal step" : "")
              << ". Raise the cap, add Mass damping or run the fracture with "
                 "inertia (Relaxation damping = kinetic, Fracture event "
                 "duration); summary.json counts these steps "
                 "(relaxations_at_cap).\n";
      return message.str();
    }

    std::string
    QuasiStaticRelaxation::cap_error(const double time, const unsigned int cap)
    {
      return "guard: the relaxation at t = " +
             dealii::Utilities::to_string(time) + " s reached its cap of " +
             std::to_string(cap) +
             " mechanical steps without reaching Relaxation tolerance "
             "(Discrete heat/Relaxation cap is error = true).";
    }

    double
    QuasiStaticRelaxation::next_thermal_step(
      const double                time,
      const unsigned long         n_thermal_steps,
      const std::optional<double> next_output_time) const
    {
      const DiscreteHeatParameters &dh =
        parameters.get<DiscreteHeatParameters>();
      double dt =
        parameters.time.time_step *
        std::pow(dh.thermal_step_growth, static_cast<double>(n_thermal_steps));
      if (dh.maximum_thermal_step > 0.)
        dt = std::min(dt, dh.maximum_thermal_step);
      dt = std::max(dt, parameters.time.time_step);
      // after a step cut short (by the controls below or a re-run), the
      // step grows back by at most 2 per step, not to the schedule at once
      if (last_thermal_step > 0.)
        dt = std::min(dt, 2. * last_thermal_step);
      const double minimum_step = minimum_thermal_step();
      // joints approaching their strength: at most the allowed rise of the
      // utilisation per step, predicted from its last rate
      if (dh.maximum_utilisation_change > 0.)
        {
          double limit = dt;
          if (joint_utilisation_rate > 0.)
            limit = dh.maximum_utilisation_change / joint_utilisation_rate;
          // near the peak the rate may flatten while U creeps to 1: steps of
          // at most this fraction of the elapsed time bracket the onset
          if (joint_utilisation > 1. - 10. * dh.maximum_utilisation_change)
            limit = std::min(limit,
                             dh.maximum_utilisation_change *
                               (time - parameters.time.start_time));
          dt = std::min(dt, std::max(minimum_step, limit));
        }
      // joints breaking: at most the allowed number per step, from their
      // rate over the last step where it had more
      if (dh.maximum_broken_joints_per_step > 0 && break_rate > 0.)
        dt = std::min(dt,
                      std::max(minimum_step,
                               dh.maximum_broken_joints_per_step / break_rate));
      // land on the end time instead of stepping past it
      const double to_end = parameters.time.end_time - time;
      if (to_end < 1.5 * dt)
        dt = to_end;
      // and on the next requested output time (two equal steps where one
      // would come within half a step of it)
      if (next_output_time)
        {
          const double left = *next_output_time - time;
          if (left > 0. && left <= dt * (1. + 1e-9))
            dt = left;
          else if (left > 0. && left < 1.5 * dt)
            dt = 0.5 * left;
        }
      return dt;
    }

    double
    QuasiStaticRelaxation::minimum_thermal_step() const
    {
      const DiscreteHeatParameters &dh =
        parameters.get<DiscreteHeatParameters>();
      return dh.minimum_thermal_step > 0. ? dh.minimum_thermal_step :
                                            1e-3 * parameters.time.time_step;
    }

    bool
    QuasiStaticRelaxation::resolves_thermal_step(
      const unsigned int joints_broken,
      const bool         damage_grew) const
    {
      const double allowed =
        parameters.get<DiscreteHeatParameters>().maximum_broken_joints_per_step;
      return joints_broken <= 2. * allowed &&
             (last_relaxation_converged || !damage_grew);
    }

    double
    QuasiStaticRelaxation::rerun_factor(const unsigned int joints_broken) const
    {
      const double allowed =
        parameters.get<DiscreteHeatParameters>().maximum_broken_joints_per_step;
      return joints_broken > 2. * allowed ? 0.5 * allowed / joints_broken :
                                            0.25;
    }

    void
    QuasiStaticRelaxation::accept_thermal_step(const double       dt,
                                               const bool         unstable,
                                               const unsigned int joints_broken)
    {
      const DiscreteHeatParameters &dh =
        parameters.get<DiscreteHeatParameters>();
      const double allowed = dh.maximum_broken_joints_per_step;
      last_thermal_step    = dt;
      if (dh.maximum_broken_joints_per_step > 0)
        break_rate =
          unstable || joints_broken <= allowed ? 0. : joints_broken / dt;
    }

    void
    QuasiStaticRelaxation::save_step_control(CheckpointWriter &out) const
    {
      out.put(last_relaxation_steps);
      out.put(last_kinetic_to_strain);
      out.put<std::uint64_t>(relaxations_at_cap);
      out.put(joint_utilisation);
      out.put(joint_utilisation_rate);
      out.put(break_rate);
      out.put(last_thermal_step);
      out.put<std::uint64_t>(rejected_thermal_steps);
      out.put<std::uint64_t>(unstable_thermal_steps);
    }

    void
    QuasiStaticRelaxation::load_step_control(CheckpointReader &in)
    {
      std::uint64_t count = 0;
      in.get(last_relaxation_steps);
      in.get(last_kinetic_to_strain);
      in.get(count);
      relaxations_at_cap = count;
      in.get(joint_utilisation);
      in.get(joint_utilisation_rate);
      in.get(break_rate);
      in.get(last_thermal_step);
      in.get(count);
      rejected_thermal_steps = count;
      in.get(count);
      unstable_thermal_steps = count;
    }

    void
    QuasiStaticRelaxation::set_ramp(const bool         imposes,
                                    const unsigned int steps_per_thermal_step,
                                    const std::string &what)
    {
      quasi_static_ramp_steps = imposes ? ramp_steps : 0;
      if (imposes && steps_per_thermal_step <= 2 * quasi_static_ramp_steps)
        throw InputError("Discrete heat/Mechanical steps per thermal step = " +
                         std::to_string(steps_per_thermal_step) +
                         " is too few for quasi-static coupling with imposed " +
                         what + ", which are ramped in over " +
                         std::to_string(quasi_static_ramp_steps) +
                         " relaxation steps; allowed is more than " +
                         std::to_string(2 * quasi_static_ramp_steps) +
                         " (or 0: automatic).");
    }

    void
    QuasiStaticRelaxation::save_relaxation(CheckpointWriter &out) const
    {
      out.put(relaxed_x);
      out.put(relaxed_y);
      out.put(relaxed_z);
      out.put(relaxed_thermal_step);
      out.put(damaged_before_relaxation);
      out.put(damaged_after_relaxation);
      out.put<std::uint32_t>((last_relaxation_converged ? 1 : 0) |
                             (previous_relaxation_converged ? 2 : 0));
      out.put(predicted_relaxations);
      out.put(velocity_resets);
      out.put(fracture_events);
      out.put(fracture_event_steps);
    }

    void
    QuasiStaticRelaxation::load_relaxation(CheckpointReader &in)
    {
      in.get(relaxed_x);
      in.get(relaxed_y);
      in.get(relaxed_z);
      in.get(relaxed_thermal_step);
      in.get(damaged_before_relaxation);
      in.get(damaged_after_relaxation);
      {
        std::uint32_t converged = 1;
        in.get(converged);
        last_relaxation_converged     = (converged & 1) != 0;
        previous_relaxation_converged = (converged & 2) != 0;
      }
      in.get(predicted_relaxations);
      in.get(velocity_resets);
      in.get(fracture_events);
      in.get(fracture_event_steps);
    }
  } // namespace coupling
} // namespace tmfdem
