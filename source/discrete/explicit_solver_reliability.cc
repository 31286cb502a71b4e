/**
 * @file
 * Reliability of the explicit discrete runs (doc/reliability.md):
 * checkpoints and --resume, stopping on SIGINT/SIGTERM, and the guards of
 * the time loop. Kept apart from explicit_solver.cc, whose run() only calls
 * these at fixed points.
 */
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/discrete/discrete_output.h>
#include <tmfdem/discrete/explicit_solver.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/output_files.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      std::string
      number(const double value)
      {
        std::ostringstream text;
        text << std::setprecision(6) << value;
        return text.str();
      }

      std::string
      seconds(const double t)
      {
        std::ostringstream text;
        text << std::setprecision(8) << t << " s";
        return text.str();
      }
    } // namespace

    std::string
    ExplicitSolver::checkpoint_kind() const
    {
      return with_heat ? "discrete thermo-mechanics" : "discrete mechanics";
    }

    std::unique_ptr<CsvSeries>
    ExplicitSolver::open_csv(const std::string &file_name,
                             const std::string &header) const
    {
      if (parameters.resume) // cut to the checkpoint's length by load
        return std::make_unique<CsvSeries>(
          CsvSeries::reopen(file_name, file_size(file_name), communicator));
      return std::make_unique<CsvSeries>(file_name, header, communicator);
    }

    // --------------------------------------------------------- checkpoints
    void
    ExplicitSolver::on_rank_zero(const std::function<void()> &write) const
    {
      // rank 0 writes; a failure there stops every rank with its message
      tmfdem::on_rank_zero(communicator, write);
    }

    void
    ExplicitSolver::save_checkpoint()
    {
      // the whole state, friction history included, on every rank; rank 0
      // writes it (every rank can resume from it, on any number of ranks)
      synchronise();
      contact.synchronise_pairs(partition);
      // the work counters of all ranks (summary.json's vectorised shares
      // continue from them after --resume)
      for (double *counter : {&element_steps_done,
                              &vectorised_element_steps,
                              &joint_steps_done,
                              &vectorised_joint_steps})
        {
          const double sum = Utilities::MPI::sum(*counter, communicator);
          if (partition.rank() == 0)
            *counter = sum;
          else
            *counter = 0.;
        }
      on_rank_zero([this]() { write_checkpoint_file(); });
    }

    void
    ExplicitSolver::write_checkpoint_file()
    {
      const auto       start = std::chrono::steady_clock::now();
      CheckpointWriter out(checkpoint_kind(), parameters.input_digest);
      out.put<std::uint32_t>(model.n_elements);
      out.put<std::uint32_t>(model.n_nodes);
      out.put<std::uint32_t>(model.n_joints);
      out.put(time_step);
      put_state(out);
      // output counters and series
      out.put(next_output);
      out.put(next_history);
      out.put(history_interval);
      out.put(output_times);
      solution_series->save_records(out);
      crack_series->save_records(out);
      out.put<std::uint64_t>(history_csv->size());
      out.put<std::uint64_t>(probes_csv ? probes_csv->size() : 0);
      out.put<std::uint64_t>(lines_csv ? lines_csv->size() : 0);
      out.put(wall_time);
      out.put(element_steps_done);
      out.put(vectorised_element_steps);
      out.put(joint_steps_done);
      out.put(vectorised_joint_steps);
      const std::size_t bytes = write_checkpoint(parameters, step_number, out);
      const double      seconds_taken =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
          .count();
      std::ostringstream line;
      line << "[tmfdem] checkpoint at step " << step_number
           << ", t = " << seconds(time) << ": " << bytes << " bytes in "
           << std::setprecision(3) << seconds_taken << " s\n";
      std::cerr << line.str();
    }

    void
    ExplicitSolver::put_state(CheckpointWriter &out) const
    {
      // clocks
      out.put(time);
      out.put<std::uint64_t>(step_number);
      out.put(thermal_time);
      out.put<std::uint64_t>(n_thermal_steps);
      relaxation.save_step_control(out);
      // state of the nodes, elements and joints
      out.put(model.x);
      out.put(model.y);
      out.put(model.vx);
      out.put(model.vy);
      out.put(model.thermal_stretch);
      out.put(model.stress);
      out.put(model.joint_damage);
      out.put(model.joint_status);
      out.put(model.joint_break_time);
      // energy terms and reactions
      out.put(balance);
      out.put(drivers.body_reaction);
      out.put(drivers.condition_reaction);
      out.put(drivers.body_velocity_now);
      // relaxation predictor and counters
      relaxation.save_relaxation(out);
      // contact candidates with their friction history
      contact.save(out);
      out.put<std::uint8_t>(with_heat);
      if (with_heat)
        heat->save(out);
    }

    void
    ExplicitSolver::get_state(CheckpointReader &in)
    {
      std::uint64_t count = 0;
      in.get(time);
      in.get(count);
      step_number = count;
      in.get(thermal_time);
      in.get(count);
      n_thermal_steps = count;
      relaxation.load_step_control(in);
      const std::size_t n = model.n_nodes, e = model.n_elements,
                        j = model.n_joints;
      in.get(model.x, n);
      in.get(model.y, n);
      in.get(model.vx, n);
      in.get(model.vy, n);
      in.get(model.thermal_stretch, e);
      in.get(model.stress, model.stress.size());
      in.get(model.joint_damage, model.joint_damage.size());
      in.get(model.joint_status, j);
      in.get(model.joint_break_time, j);
      in.get(balance);
      in.get(drivers.body_reaction, drivers.body_reaction.size());
      in.get(drivers.condition_reaction);
      in.get(drivers.body_velocity_now, drivers.body_velocity_now.size());
      relaxation.load_relaxation(in);
      contact.load(in, e);
      std::uint8_t flag = 0;
      in.get(flag);
      if ((flag != 0) != with_heat)
        throw InputError("the checkpoint '" + in.name() +
                         "' does not match the model (heat).");
      if (with_heat)
        heat->load(in);
    }

    void
    ExplicitSolver::keep_thermal_step_start()
    {
      // this rank's whole state, synchronised by the caller, and its own
      // contact pairs with their friction history: every rank returns to
      // the same state without a message
      relaxation.thermal_step_start =
        std::make_unique<CheckpointWriter>("thermal step", "");
      put_state(*relaxation.thermal_step_start);
    }

    void
    ExplicitSolver::restore_thermal_step_start()
    {
      CheckpointReader in(*relaxation.thermal_step_start,
                          "start of the thermal step");
      get_state(in);
      in.finish();
      synchronised_step      = step_number;
      thermal_state_gathered = true;
      partition.build_ghost_plan(model, contact.pairs());
    }

    void
    ExplicitSolver::load_checkpoint()
    {
      const std::string file = newest_checkpoint(parameters);
      CheckpointReader  in(file, checkpoint_kind(), parameters.input_digest);
      std::uint32_t     sizes[3];
      for (auto &n : sizes)
        in.get(n);
      if (sizes[0] != model.n_elements || sizes[1] != model.n_nodes ||
          sizes[2] != model.n_joints)
        throw InputError("the checkpoint '" + file + "' is of another mesh (" +
                         std::to_string(sizes[0]) + " elements, this run " +
                         std::to_string(model.n_elements) + ").");
      double saved_time_step = 0.;
      in.get(saved_time_step);
      if (saved_time_step != time_step)
        throw InputError("the checkpoint '" + file + "' has the time step " +
                         seconds(saved_time_step) + ", this run " +
                         seconds(time_step) + ".");
      get_state(in);
      in.get(next_output);
      in.get(next_history);
      in.get(history_interval);
      std::vector<double> saved_output_times;
      in.get(saved_output_times);
      if (next_output > saved_output_times.size())
        throw InputError("the checkpoint '" + file +
                         "' is corrupt (output counter).");
      // End time may have changed (a run continued): the output times of
      // this input from the next unwritten one on; the history keeps the
      // checkpoint's interval
      next_output = continue_output_times(
        file,
        time,
        parameters.time.end_time,
        saved_output_times,
        next_output,
        output_times,
        1e-9 * std::max(1., std::abs(parameters.time.end_time)));
      const auto    solution_records = VtuSeries::load_records(in);
      const auto    crack_records    = VtuSeries::load_records(in);
      std::uint64_t csv_bytes[3];
      for (auto &b : csv_bytes)
        in.get(b);
      in.get(resumed_wall_time);
      wall_time = resumed_wall_time;
      // the work counters of every rank summed, continued on rank 0
      for (double *counter : {&element_steps_done,
                              &vectorised_element_steps,
                              &joint_steps_done,
                              &vectorised_joint_steps})
        {
          in.get(*counter);
          if (partition.rank() != 0)
            *counter = 0.;
        }
      in.finish();

      // every rank has the whole state; the ghost plan of its pairs
      synchronised_step      = step_number;
      thermal_state_gathered = true;
      partition.build_ghost_plan(model, contact.pairs());
      // the outputs continue exactly where the checkpoint left them (every
      // rank numbers the vtu pieces; rank 0 writes the rest)
      if (parameters.output.write_vtu)
        {
          solution_series->restore(solution_records, writes_files());
          crack_series->restore(crack_records, writes_files());
        }
      if (!writes_files())
        return;
      const std::string &folder = parameters.output.directory;
      truncate_file(folder + "/history.csv", csv_bytes[0]);
      if (probes_csv)
        truncate_file(folder + "/probes.csv", csv_bytes[1]);
      if (lines_csv)
        truncate_file(folder + "/lines.csv", csv_bytes[2]);
      std::cerr << "[tmfdem] resumed from " << file << ": step " << step_number
                << ", t = " << seconds(time) << "\n";
    }

    void
    ExplicitSolver::after_step(CheckpointSchedule &schedule)
    {
      bool checkpoint_due = schedule.active() && schedule.due(step_number);
      bool stop           = stop_requested();
      if (partition.distributed())
        {
          // wall-clock checkpoints and signals: decided together, every
          // 16th step (every thermal step in quasi-static coupling)
          if (!quasi_static && (++after_step_calls & 15) != 0)
            return;
          checkpoint_due =
            Utilities::MPI::max(checkpoint_due ? 1 : 0, communicator) != 0;
          stop = stop_requested_on_any_rank(communicator);
        }
      if (checkpoint_due)
        {
          save_checkpoint();
          schedule.written(step_number);
        }
      if (!stop)
        return;
      const std::string signal = stop_signal_name();
      if (writes_files())
        std::cerr << "[tmfdem] " << signal
                  << ": finishing the step, writing a checkpoint and the "
                     "outputs\n";
      save_checkpoint();
      energy();
      stop_reason = "stopped by " + signal;
      write_summary(false);
      throw StopRequested("stopped by " + signal + " at t = " + seconds(time) +
                          " after step " + std::to_string(step_number) +
                          "; checkpoint in " + checkpoint_folder(parameters) +
                          ", outputs so far in " + parameters.output.directory +
                          ". Continue with: tmfdem " + parameters.prm_file +
                          " --resume (and the same --set options).");
    }

    // -------------------------------------------------------------- guards
    void
    ExplicitSolver::keep_good_state()
    {
      good_state.time = time;
      good_state.step = step_number;
      good_state.x.assign(model.x.begin(), model.x.end());
      good_state.y.assign(model.y.begin(), model.y.end());
      good_state.vx.assign(model.vx.begin(), model.vx.end());
      good_state.vy.assign(model.vy.begin(), model.vy.end());
      good_state.stress.assign(model.stress.begin(), model.stress.end());
      good_state.damage.assign(model.joint_damage.begin(),
                               model.joint_damage.end());
      good_state.break_time.assign(model.joint_break_time.begin(),
                                   model.joint_break_time.end());
      good_state.status.assign(model.joint_status.begin(),
                               model.joint_status.end());
      if (with_heat)
        good_state.T.assign(heat->temperature().begin(),
                            heat->temperature().end());
      good_state.valid = true;
    }

    void
    ExplicitSolver::step_guard_failure()
    {
      synchronise(); // the flagged element may be another rank's
      std::ostringstream message;
      message << std::setprecision(6);
      const std::string when = " at t = " + seconds(time) + " (step " +
                               std::to_string(step_number) + ")";
      long long element = first_inverted_element;
      bool      finite  = true;
      if (first_nonfinite_node >= 0)
        {
          element = first_nonfinite_node / 3;
          finite  = false;
        }
      else
        for (unsigned int k = 0; k < 3; ++k)
          finite = finite && std::isfinite(model.x[3 * element + k]) &&
                   std::isfinite(model.y[3 * element + k]);
      const double cx =
                     (model.x_ref[3 * element] + model.x_ref[3 * element + 1] +
                      model.x_ref[3 * element + 2]) /
                     3.,
                   cy =
                     (model.y_ref[3 * element] + model.y_ref[3 * element + 1] +
                      model.y_ref[3 * element + 2]) /
                     3.;
      const std::string where =
        "element " + std::to_string(element) + " (material id " +
        std::to_string(model.material[element]) + ", reference centroid (" +
        number(cx) + ", " + number(cy) + ") m)";
      if (!finite)
        message << "guard: non-finite values (NaN or infinite) at "
                << (first_nonfinite_node >= 0 ?
                      "node " + std::to_string(first_nonfinite_node) + " of " :
                      std::string())
                << where << when
                << ": the explicit integration diverged. Likely causes: a "
                   "time step too large (Discrete mechanics/Time step or "
                   "Safety factor), penalties too stiff (Discrete "
                   "mechanics/Contact penalty factor, Joint normal or "
                   "tangential penalty factor), or a load or velocity "
                   "function that is not finite.";
      else
        message << "guard: inverted " << where << " (J = det F <= 0)" << when
                << ". Likely causes: a time step too large for the "
                   "deformation (Discrete mechanics/Time step or Safety "
                   "factor), a contact penalty too soft for the impact so "
                   "that triangles pass through each other (Discrete "
                   "mechanics/Contact penalty factor), or a prescribed "
                   "velocity or load that crushes the elements.";
      guard_failure(message.str());
    }

    void
    ExplicitSolver::check_slow_guards()
    {
      synchronise(); // same state, same verdict on every rank
      const std::string when = " at t = " + seconds(time) + " (step " +
                               std::to_string(step_number) + ")";
      if (with_heat)
        {
          const auto &T = heat->temperature();
          for (unsigned int n = 0; n < model.n_nodes; ++n)
            if (!std::isfinite(T[n]))
              guard_failure(
                "guard: non-finite temperature at node " + std::to_string(n) +
                " (element " + std::to_string(n / 3) + ")" + when +
                ". Likely causes: a thermal step beyond the stable explicit "
                "thermal step (Discrete heat/Mechanical steps per thermal "
                "step), a contact conductance too high, or a boundary or "
                "source function that is not finite.");
        }
      if (!std::isfinite(balance.kinetic) || !std::isfinite(balance.strain))
        {
          first_nonfinite_node = 0;
          for (unsigned int n = 0; n < model.n_nodes; ++n)
            if (!std::isfinite(model.x[n] + model.y[n] + model.vx[n] +
                               model.vy[n]))
              {
                first_nonfinite_node = n;
                break;
              }
          step_guard_failure();
        }
      const double factor = parameters.guards.kinetic_energy_factor;
      if (factor > 0.)
        {
          const double put_in = balance.initial_kinetic +
                                balance.initial_strain +
                                std::max(0., balance.external_work) +
                                std::max(0., balance.thermal_work);
          if (balance.kinetic > factor * std::max(put_in, 1e-9))
            {
              unsigned int fastest = 0;
              double       v2_max  = -1.;
              for (unsigned int n = 0; n < model.n_nodes; ++n)
                {
                  const double v2 =
                    model.vx[n] * model.vx[n] + model.vy[n] * model.vy[n];
                  if (v2 > v2_max)
                    {
                      v2_max  = v2;
                      fastest = n;
                    }
                }
              guard_failure(
                "guard: runaway kinetic energy " + number(balance.kinetic) +
                " J/m, more than Guards/Kinetic energy factor = " +
                number(factor) + " times the energy put in (" + number(put_in) +
                " J/m)" + when + "; fastest node " + std::to_string(fastest) +
                " (element " + std::to_string(fastest / 3) + ", " +
                number(std::sqrt(v2_max)) +
                " m/s). Likely causes: an unstable time step (Discrete "
                "mechanics/Time step or Safety factor), penalties too stiff "
                "(Contact penalty factor, Joint normal or tangential penalty "
                "factor), or too little damping.");
            }
        }
      if (parameters.guards.stability_check)
        {
          // the bound of compute_stable_time_step() on the current geometry
          // and the joints still intact
          double       dt_min = std::numeric_limits<double>::infinity();
          double       ratio  = 1.;
          unsigned int worst  = 0;
          for (unsigned int e = 0; e < model.n_elements; ++e)
            {
              const ElementStepInput in = element_step_input(e, true);
              if (stable_at(in, time_step))
                continue;
              // only elements the step is too long for get the bisection
              const double dt = critical_time_step(in);
              if (dt < dt_min)
                {
                  dt_min = dt;
                  worst  = e;
                  ratio  = 0.5 *
                          ((in.x[1] - in.x[0]) * (in.y[2] - in.y[0]) -
                           (in.x[2] - in.x[0]) * (in.y[1] - in.y[0])) /
                          model.reference_area[e];
                }
            }
          if (time_step > dt_min)
            guard_failure(
              "guard: the time step " + seconds(time_step) +
              " exceeds the stable step " + seconds(dt_min) +
              " of the deformed element " + std::to_string(worst) +
              " (material id " + std::to_string(model.material[worst]) +
              ", area now " + number(100. * ratio) +
              " % of its reference area)" + when +
              ". Likely causes: a time step too close to the stable step of "
              "the undeformed mesh (lower Discrete mechanics/Safety factor or "
              "Time step), or excessive compression (a load or prescribed "
              "velocity too large, a contact penalty too soft); Guards/"
              "Stability check = false turns this check off.");
        }
      keep_good_state();
    }

    void
    ExplicitSolver::guard_failure(const std::string &message)
    {
      const std::string &folder = parameters.output.directory;
      stop_reason               = message;
      std::string written;
      // every rank gets here with the same state (guards decide on the
      // synchronised state or on reduced flags); rank 0 writes
      synchronise();
      if (writes_files())
        try
          {
            write_file_atomically(folder + "/failure_state.vtu",
                                  solution_vtu());
            written = " Wrote " + folder +
                      "/failure_state.vtu (t = " + seconds(time) + ")";
            if (good_state.valid)
              {
                // swap the last good state in, write it, swap back
                const auto swap_state = [&]() {
                  model.x.swap(good_state.x);
                  model.y.swap(good_state.y);
                  model.vx.swap(good_state.vx);
                  model.vy.swap(good_state.vy);
                  model.stress.swap(good_state.stress);
                  model.joint_damage.swap(good_state.damage);
                  model.joint_break_time.swap(good_state.break_time);
                  model.joint_status.swap(good_state.status);
                  if (with_heat)
                    for (unsigned int n = 0; n < model.n_nodes; ++n)
                      std::swap(heat->temperature()[n], good_state.T[n]);
                };
                swap_state();
                const std::string text = solution_vtu();
                swap_state();
                write_file_atomically(folder + "/last_good_state.vtu", text);
                written +=
                  " and the last good state " + folder +
                  "/last_good_state.vtu (t = " + seconds(good_state.time) +
                  ", step " + std::to_string(good_state.step) + ")";
              }
            written += ".";
          }
        catch (const std::exception &)
          {
            // the message matters more than the files
          }
      try
        {
          write_summary(false); // collective: every rank
        }
      catch (const std::exception &)
        {}
      throw RunError(message + written);
    }
  } // namespace discrete
} // namespace tmfdem
