#include <cmath>
#include <iomanip>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/contact_heat.h>
#include <tmfdem/discrete/discrete_heat_solver.h>
#include <tmfdem/discrete/discrete_output.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/tetrahedral_solver.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/output_files.h>
#include <tmfdem/io/output_schedule.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      const bool registered = register_simulation(
        "discrete heat",
        "heat conduction in the discrete layer (exploded triangles, joint "
        "exchange), mechanics off, marching at the thermal step",
        {{"Mesh",
          "Materials",
          "Thermal boundary conditions",
          "Initial conditions",
          "Time stepping",
          "Discrete mechanics",
          "Discrete bodies",
          "Discrete heat",
          "Output",
          "Monitors",
          "Checkpoint"},
         {}},
        [](const Parameters &parameters,
           MPI_Comm          communicator) -> std::unique_ptr<Simulation> {
          if (parameters.mesh.dimension == 3)
            return std::make_unique<TetrahedralSolver>(
              parameters,
              communicator,
              TetrahedralSolver::Physics::heat);
          return std::make_unique<DiscreteHeatSolver>(parameters, communicator);
        },
        {2, 3});
    } // namespace

    DiscreteHeatSolver::DiscreteHeatSolver(const Parameters &parameters,
                                           MPI_Comm          communicator)
      : parameters(parameters)
      , communicator(communicator)
      , fe(1)
    {}

    DiscreteHeatSolver::~DiscreteHeatSolver() = default;

    void
    DiscreteHeatSolver::check_input()
    {
      if (input_checked)
        return;
      if (parameters.get<DiscreteHeatParameters>().temperature_source !=
          "discrete heat")
        throw InputError(
          "Discrete heat/Temperature source = " +
          parameters.get<DiscreteHeatParameters>().temperature_source +
          " applies to Model = discrete thermo-mechanics; Model = discrete "
          "heat is the discrete heat itself (for the continuum heat alone use "
          "Model = continuum heat); allowed here is discrete heat.");
      build_discrete_mesh(parameters,
                          communicator,
                          triangulation,
                          dof_handler,
                          fe,
                          model);
      heat = std::make_unique<DiscreteHeat>(parameters, model);
      {
        // Discrete mechanics/Threads, capped at the cores of this process
        // unless oversubscription is allowed (include/tmfdem/base/threads.h)
        const auto        &dm = parameters.get<DiscreteMechanicsParameters>();
        const unsigned int available = core_share(communicator).cores_per_rank;
        const unsigned int threads =
          dm.threads == 0                                      ? available :
          dm.threads > available && !dm.allow_oversubscription ? available :
                                                                 dm.threads;
        if (threads > thread_limit())
          set_thread_limit(threads);
        heat->set_threads(threads);
      }
      // each rank its own triangles (whole chunks); the ghosts: triangles
      // joined to or in contact with them (the geometry never changes)
      partition.setup(communicator, model, chunk_size);
      heat->distribute(partition);
      heat->initialise(parameters.time.start_time); // T0, contact pairs
      partition.build_ghost_plan(model, heat->contact_pair_list());
      locate_monitors(parameters.monitors, model, probe_samples, line_samples);
      const auto &ts = parameters.time;
      if (ts.mode != TimeSteppingParameters::Mode::transient)
        throw InputError("Time stepping/Mode = steady: the discrete heat "
                         "model is transient only; allowed is transient.");
      time_step = ts.time_step;
      if (!heat->implicit())
        {
          const double stable = heat->stable_time_step();
          if (time_step > stable)
            throw InputError(
              "Time stepping/Time step = " + Utilities::to_string(time_step) +
              " s exceeds the stable explicit thermal step " +
              Utilities::to_string(stable) +
              " s of this mesh (lumped capacity, joint conductance, Robin "
              "coefficients); allowed is at most the stable step, or "
              "Discrete heat/Time integration = implicit.");
        }
      input_checked = true;
    }

    void
    DiscreteHeatSolver::run()
    {
      check_input();
      const std::string &folder = parameters.output.directory;
      VtuSeries          series(folder, "solution");
      const std::string  header = "time,name,x,y,T";
      CsvSeries          probes_csv, lines_csv;
      const auto         open_csv = [&](const std::string &file) {
        return parameters.resume ?
                         CsvSeries::reopen(file, file_size(file), communicator) :
                         CsvSeries(file, header, communicator);
      };
      if (!probe_samples.empty())
        probes_csv = open_csv(folder + "/probes.csv");
      if (!line_samples.empty())
        lines_csv = open_csv(folder + "/lines.csv");

      double       time = parameters.time.start_time;
      const double end  = parameters.time.end_time;
      heat->initialise(time);
      // the output schedule every model uses (io/output_schedule.h): times
      // within half a thermal step of each other are one output, the end
      // time always one of them
      std::vector<double> output_times =
        OutputSchedule(parameters.output.times,
                       parameters.output.interval,
                       time,
                       end,
                       0.5 * time_step)
          .times();

      const bool distributed  = partition.distributed();
      auto       write_output = [&]() {
        // every rank the whole field (probes, lines); each its vtu piece
        partition.gather_element_values(heat->temperature().begin(), 3);
        if (parameters.output.write_vtu)
          {
            std::vector<double> T(heat->temperature().begin(),
                                  heat->temperature().end());
            if (!distributed)
              series.write(time,
                           discrete_solution_vtu(model,
                                                 vtu_encoding(
                                                   parameters.output),
                                                 {{"T", &T}}));
            else
              {
                const std::string piece =
                  discrete_solution_vtu(model,
                                        vtu_encoding(parameters.output),
                                        {{"T", &T}},
                                        partition.begin(),
                                        partition.end());
                std::string failure;
                try
                  {
                    series.write_piece(partition.rank(), piece);
                  }
                catch (const std::exception &e)
                  {
                    failure = e.what();
                  }
                for (const std::string &message :
                     Utilities::MPI::all_gather(communicator, failure))
                  if (!message.empty())
                    throw RunError(message);
                tmfdem::on_rank_zero(communicator, [&]() {
                  series.write_parallel_record(time,
                                               partition.n_processes(),
                                               piece);
                });
                if (partition.rank() != 0)
                  series.add_parallel_record(time);
              }
          }
        auto rows = [&](const std::vector<ReferenceSample> &samples) {
          std::ostringstream out;
          out << std::setprecision(12);
          for (const auto &s : samples)
            {
              double T = 0.;
              for (unsigned int k = 0; k < 3; ++k)
                T += s.lambda[k] * heat->temperature()[3 * s.element + k];
              out << time << ',' << s.name << ',' << s.x << ',' << s.y << ','
                  << T << '\n';
            }
          return out.str();
        };
        if (!probe_samples.empty())
          probes_csv.append(rows(probe_samples));
        if (!line_samples.empty())
          lines_csv.append(rows(line_samples));
      };
      if (!parameters.resume)
        write_output();

      ProgressReporter progress(parameters.output.progress_interval,
                                time,
                                end,
                                partition.rank() == 0);
      unsigned long    steps         = 0;
      unsigned long    cg_iterations = 0;
      unsigned int     next_output   = 0;

      // checkpoints (doc/reliability.md): time, counters, output series and
      // the thermal state
      const std::string kind = "discrete heat";
      const auto        save = [&]() {
        CheckpointWriter out(kind, parameters.input_digest);
        out.put<std::uint32_t>(model.n_nodes);
        out.put(time);
        out.put<std::uint64_t>(steps);
        out.put<std::uint64_t>(cg_iterations);
        out.put(next_output);
        out.put(output_times);
        series.save_records(out);
        out.put<std::uint64_t>(probes_csv.size());
        out.put<std::uint64_t>(lines_csv.size());
        heat->save(out);
        const std::size_t bytes = write_checkpoint(parameters, steps, out);
        std::cerr << "[tmfdem] checkpoint at step " << steps << ", t = " << time
                  << " s: " << bytes << " bytes\n";
      };
      // the whole field on every rank, rank 0 writes (any rank count resumes)
      const auto save_checkpoint = [&]() {
        partition.gather_element_values(heat->temperature().begin(), 3);
        tmfdem::on_rank_zero(communicator, save);
      };
      if (parameters.resume)
        {
          const std::string file = newest_checkpoint(parameters);
          CheckpointReader  in(file, kind, parameters.input_digest);
          std::uint32_t     n_nodes = 0;
          in.get(n_nodes);
          if (n_nodes != model.n_nodes)
            throw InputError("the checkpoint '" + file +
                             "' is of another mesh.");
          std::uint64_t count = 0;
          in.get(time);
          in.get(count);
          steps = count;
          in.get(count);
          cg_iterations = count;
          in.get(next_output);
          std::vector<double> saved_output_times;
          in.get(saved_output_times);
          if (next_output > saved_output_times.size())
            throw InputError("the checkpoint '" + file +
                             "' is corrupt (output counter).");
          // End time may have changed (a run continued): this input's
          // output times from the next unwritten one on
          next_output           = continue_output_times(file,
                                              time,
                                              end,
                                              saved_output_times,
                                              next_output,
                                              output_times,
                                              0.5 * time_step);
          const auto    records = VtuSeries::load_records(in);
          std::uint64_t csv_bytes[2];
          in.get(csv_bytes[0]);
          in.get(csv_bytes[1]);
          heat->load(in);
          in.finish();
          if (parameters.output.write_vtu)
            series.restore(records);
          if (!probe_samples.empty())
            truncate_file(folder + "/probes.csv", csv_bytes[0]);
          if (!line_samples.empty())
            truncate_file(folder + "/lines.csv", csv_bytes[1]);
          if (partition.rank() == 0)
            std::cerr << "[tmfdem] resumed from " << file << ": step " << steps
                      << ", t = " << time << " s\n";
        }
      CheckpointSchedule checkpoints(parameters.checkpoint);
      checkpoints.written(steps);
      std::string stop_reason;

      while (time < end - 1e-9 * time_step)
        {
          // land exactly on output times
          double dt = std::min(time_step, end - time);
          if (next_output < output_times.size() &&
              output_times[next_output] - time < dt + 1e-9 * time_step)
            dt = output_times[next_output] - time;
          heat->step(time, dt);
          cg_iterations += heat->last_iterations();
          time += dt;
          ++steps;
          while (next_output < output_times.size() &&
                 time >= output_times[next_output] - 1e-9 * time_step)
            {
              write_output();
              ++next_output;
            }
          progress.update(steps, time);
          // guard: temperatures finite (one pass over this rank's nodes;
          // the first bad node of all ranks, so every rank stops with the
          // same message and none waits in a later exchange)
          unsigned int bad = numbers::invalid_unsigned_int;
          for (unsigned int n = 3 * partition.begin(); n < 3 * partition.end();
               ++n)
            if (!std::isfinite(heat->temperature()[n]))
              {
                bad = n;
                break;
              }
          if (distributed)
            bad = Utilities::MPI::min(bad, communicator);
          if (bad != numbers::invalid_unsigned_int)
            throw RunError(
              "guard: non-finite temperature at node " + std::to_string(bad) +
              " (element " + std::to_string(bad / 3) + ") at t = " +
              Utilities::to_string(time) + " s (step " + std::to_string(steps) +
              "). Likely causes: an explicit time step above the stable "
              "one, a contact conductance or Robin coefficient too high, or "
              "a boundary or source function that is not finite. The "
              "outputs up to the last output time are intact.");
          // checkpoints due (wall clock) and signals: decided together
          bool due  = checkpoints.active() && checkpoints.due(steps);
          bool stop = stop_requested();
          if (distributed)
            {
              due  = Utilities::MPI::max(due ? 1 : 0, communicator) != 0;
              stop = stop_requested_on_any_rank(communicator);
            }
          if (due)
            {
              save_checkpoint();
              checkpoints.written(steps);
            }
          if (stop)
            {
              if (partition.rank() == 0)
                std::cerr << "[tmfdem] " << stop_signal_name()
                          << ": finishing the step, writing a checkpoint and "
                             "the outputs\n";
              save_checkpoint();
              stop_reason = "stopped by " + stop_signal_name();
              break;
            }
        }

      const HeatBalance &b       = heat->balance();
      const JsonObject   balance = heat_balance_summary(*heat);
      JsonObject         summary;
      summary.add("model", std::string("discrete heat"))
        .add("finished", stop_reason.empty())
        .add("elements", model.n_elements)
        .add("nodes", model.n_nodes)
        .add("joints", model.n_joints)
        .add("time_integration",
             parameters.get<DiscreteHeatParameters>().time_integration_name())
        .add("contact_heat_model",
             contact_heat_model_name(
               parameters.get<DiscreteHeatParameters>().contact_heat_model))
        .add("steps", static_cast<long long>(steps))
        .add("end_time", time)
        .add("time_step", time_step)
        .add("stable_explicit_time_step", heat->stable_time_step())
        .add("cg_iterations", static_cast<long long>(cg_iterations))
        .add("amg_setups", static_cast<long long>(heat->amg_setups()))
        .add("contact_pairs",
             Utilities::MPI::sum(heat->n_contact_pairs(), communicator))
        .add("mpi_processes", partition.n_processes())
        .add("heat_distributed", partition.distributed())
        .add("ghost_elements", partition.n_ghosts())
        .add("ghost_exchange_bytes",
             Utilities::MPI::sum(static_cast<double>(
                                   partition.ghost_bytes_sent()),
                                 communicator))
        .add("communication_time_s",
             Utilities::MPI::max(partition.communication_time(), communicator))
        .add("wall_time", progress.elapsed())
        .add("element_steps_per_second",
             progress.elapsed() > 0. ?
               model.n_elements * double(steps) / progress.elapsed() :
               0.)
        .add("heat_balance", balance);
      if (!stop_reason.empty())
        summary.add("stop_reason", stop_reason);
      const std::string summary_text = summary.str() + "\n";
      tmfdem::on_rank_zero(communicator, [&]() {
        write_file_atomically(folder + "/summary.json", summary_text);
      });
      if (!stop_reason.empty())
        throw StopRequested(
          stop_reason + " at t = " + Utilities::to_string(time) +
          " s after step " + std::to_string(steps) + "; checkpoint in " +
          checkpoint_folder(parameters) + ". Continue with: tmfdem " +
          parameters.prm_file + " --resume (and the same --set options).");
      if (partition.rank() == 0)
        std::cerr << "[tmfdem] discrete heat: " << steps
                  << " steps to t = " << time << " s, heat imbalance "
                  << std::abs(b.imbalance()) / b.scale() << " (relative)\n";
    }

  } // namespace discrete
} // namespace tmfdem
