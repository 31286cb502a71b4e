/**
 * @file
 * The explicit discrete solver's registration and time loop: the models
 * `discrete mechanics` and `discrete thermo-mechanics`, one explicit
 * mechanical step (imposed motions, contact, joints, the fused node update)
 * and run() with its outputs, checkpoints and guards. The parts live in
 * their own files (doc/architecture.md): set-up (explicit_solver_setup.cc),
 * the node update (node_update.cc), joints (joints.cc), contact
 * (contact_system.cc, contact_law.h), bodies and conditions (drivers.cc),
 * energy (energy.cc), outputs (explicit_solver_output.cc), reliability
 * (explicit_solver_reliability.cc), and the thermo-mechanical loops
 * (source/coupling/discrete_thermo_mechanics.cc).
 */
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/discrete_output.h>
#include <tmfdem/discrete/explicit_solver.h>
#include <tmfdem/discrete/joints.h>
#include <tmfdem/discrete/temperature_source.h>
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
      /** What the explicit models read; the thermo-mechanics adds the heat
       *  and, with the continuum heat as its source, the heat solver. */
      SectionsRead
      explicit_sections(const bool with_heat)
      {
        SectionsRead sections{{"Mesh",
                               "Materials",
                               "Time stepping",
                               "Mechanics",
                               "Mechanical boundary conditions",
                               "Discrete mechanics",
                               "Discrete bodies",
                               "Output",
                               "Monitors",
                               "Checkpoint",
                               "Guards"},
                              {}};
        if (with_heat)
          {
            for (const char *name : {"Thermal boundary conditions",
                                     "Initial conditions",
                                     "Discrete heat"})
              sections.always.emplace_back(name);
            sections.conditional.push_back(
              {"Discrete heat/Temperature source = continuum heat",
               {"Heat solver", "Adaptive refinement"},
               [](const Parameters &parameters) {
                 return parameters.get<DiscreteHeatParameters>()
                          .temperature_source == "continuum heat";
               }});
          }
        return sections;
      }

      const bool registered = register_simulation(
        "discrete mechanics",
        "explicit FDEM dynamics: finite-strain triangles (2D) or tetrahedra "
        "(3D), cohesive joints on their edges or faces, contact with "
        "friction (no heat)",
        explicit_sections(false),
        [](const Parameters &parameters,
           MPI_Comm          communicator) -> std::unique_ptr<Simulation> {
          if (parameters.mesh.dimension == 3)
            return std::make_unique<TetrahedralSolver>(parameters,
                                                       communicator);
          return std::make_unique<ExplicitSolver>(parameters, communicator);
        },
        {2, 3});
      const bool registered_thermal = register_simulation(
        "discrete thermo-mechanics",
        "the discrete layer with heat: conduction, joint exchange and contact "
        "heat drive F = F_T F_e; fracture and contact reshape the heat flow "
        "(multi-rate: one thermal step every n mechanical steps)",
        explicit_sections(true),
        [](const Parameters &parameters,
           MPI_Comm          communicator) -> std::unique_ptr<Simulation> {
          if (parameters.mesh.dimension == 3)
            return std::make_unique<TetrahedralSolver>(
              parameters,
              communicator,
              TetrahedralSolver::Physics::thermo_mechanics);
          return std::make_unique<ExplicitSolver>(parameters,
                                                  communicator,
                                                  true);
        },
        {2, 3});
    } // namespace



    ExplicitSolver::ExplicitSolver(const Parameters &parameters,
                                   MPI_Comm          communicator,
                                   const bool        with_heat)
      : parameters(parameters)
      , communicator(communicator)
      , fe(1)
      , with_heat(with_heat)
      , relaxation(parameters)
    {}

    ExplicitSolver::~ExplicitSolver() = default;

    void
    ExplicitSolver::step()
    {
      if (quasi_static)
        {
          // coupling/discrete_thermo_mechanics.cc
          quasi_static_step();
          return;
        }
      mechanical_step();
      time += time_step;
      if (with_heat && step_number % steps_per_thermal_step == 0)
        multi_rate_thermal_step(); // coupling/discrete_thermo_mechanics.cc
    }

    void
    ExplicitSolver::mechanical_step()
    {
      // imposed motions: driven bodies at mid step, conditions that change
      // (drivers.h); in quasi-static coupling the motion of the thermal step
      // spread over the first relaxation steps
      const ImposedMotionClock clock = imposed_motion_clock();
      drivers.evaluate_body_velocities(clock);
      if (drivers.conditions_change() ||
          (quasi_static && relaxation.imposed_motion_changes()))
        drivers.evaluate_boundary_conditions(model, clock);
      if (contact.enabled())
        {
          if (contact.search_needed())
            search_contacts();
          // (friction dissipation: summed per chunk in update_nodes())
          contact.compute_forces(model,
                                 time_step,
                                 arena_for(n_threads),
                                 partition);
        }
      // this rank's joints; on several ranks a break anywhere asks every
      // rank for a search, through the sums of update_nodes()
      joints_broke = compute_joint_forces(softening_law,
                                          model,
                                          time,
                                          arena_for(n_threads),
                                          joint_tally,
                                          partition.joints(),
                                          vector_instructions);
      for (const JointChunkTally &t : joint_tally)
        {
          joint_steps_done += t.intact;
          vectorised_joint_steps += t.vectorised;
        }
      if (joints_broke && !partition.distributed())
        contact.request_search();
      update_nodes();
      ++step_number;
    }

    void
    ExplicitSolver::synchronise()
    {
      if (!partition.distributed())
        return;
      if (heat_distributed && !thermal_state_gathered)
        {
          // temperatures and thermal stretches of the last thermal step
          partition.gather_element_values(heat->temperature().begin(), 3);
          partition.gather_element_values(model.thermal_stretch.data(), 1);
          thermal_state_gathered = true;
        }
      if (synchronised_step == step_number)
        return;
      partition.synchronise(model);
      synchronised_step = step_number;
    }

    unsigned int
    ExplicitSolver::n_broken_joints() const
    {
      if (!partition.distributed())
        return model.n_broken_joints();
      // each rank counts the joints of its first triangles
      unsigned int broken = 0;
      for (unsigned int j = partition.first_joint(); j < partition.end_joint();
           ++j)
        broken += model.joint_status[j] != JointStatus::intact ? 1 : 0;
      return Utilities::MPI::sum(broken, communicator);
    }

    void
    ExplicitSolver::search_contacts()
    {
      // on several ranks, without the whole state: the joints' status,
      // then the active triangles near each rank's region by bounding
      // boxes, and the ghosts new to the plan (partition.h)
      if (partition.distributed() && synchronised_step != step_number)
        {
          partition.synchronise_joint_status(model);
          contact.update_active_elements(model);
          std::vector<unsigned int> candidates;
          SearchExtent              extent;
          partition.exchange_search_candidates(model,
                                               contact.get_active_elements(),
                                               contact.settings().buffer,
                                               candidates,
                                               extent);
          contact.search(model,
                         arena_for(n_threads),
                         partition,
                         &candidates,
                         &extent);
          partition.build_ghost_plan(model, contact.pairs());
          partition.exchange_new_ghosts(model);
        }
      else
        {
          contact.update_active_elements(model);
          contact.search(model, arena_for(n_threads), partition);
          partition.build_ghost_plan(model, contact.pairs());
        }
      // the overlap guard after the travel of a search (not after every
      // search that breaking joints ask for)
      if (contact.overlap_check_due())
        {
          check_contact_overlap(false);
          contact.overlap_checked();
        }
    }

    void
    ExplicitSolver::check_contact_overlap(const bool initial)
    {
      ContactSystem::Overlap worst;
      if (initial)
        {
          // the pairs of a first search, in a copy and on a partition of
          // this rank alone (every rank holds the whole model at set-up):
          // the run's own search, counters, pair list and ghost plan stay
          // as they were, and every rank finds the same pair
          ElementPartition whole;
          whole.setup(MPI_COMM_SELF, model, chunk_size);
          ContactSystem probe = contact;
          probe.update_active_elements(model);
          probe.search(model, arena_for(n_threads), whole);
          worst = probe.largest_overlap(model);
        }
      else
        {
          const ContactSystem::Overlap local = contact.largest_overlap(model);
          worst                              = local;
          // the largest of all ranks (the first rank's on a tie)
          if (partition.distributed())
            {
              const double        mine[4] = {local.fraction,
                                             local.area,
                                             static_cast<double>(local.first),
                                             static_cast<double>(local.second)};
              std::vector<double> all(
                4 * Utilities::MPI::n_mpi_processes(communicator));
              MPI_Allgather(mine,
                            4,
                            MPI_DOUBLE,
                            all.data(),
                            4,
                            MPI_DOUBLE,
                            communicator);
              for (std::size_t r = 0; r < all.size(); r += 4)
                if (all[r] > worst.fraction || r == 0)
                  worst = ContactSystem::Overlap{
                    all[r],
                    all[r + 1],
                    static_cast<unsigned int>(all[r + 2]),
                    static_cast<unsigned int>(all[r + 3])};
            }
        }
      if (worst.fraction <=
          (initial ? max_initial_overlap : max_contact_overlap))
        return;

      const auto &bodies = parameters.get<DiscreteBodyParameters>().bodies;
      double      smallest_altitude = std::numeric_limits<double>::max();
      const auto  describe          = [&](const unsigned int e) {
        const double *x = &model.x_ref[3 * e], *y = &model.y_ref[3 * e];
        double        longest = 0.;
        for (unsigned int k = 0; k < 3; ++k)
          longest =
            std::max(longest,
                     std::hypot(x[(k + 1) % 3] - x[k], y[(k + 1) % 3] - y[k]));
        smallest_altitude =
          std::min(smallest_altitude, 2. * model.reference_area[e] / longest);
        const unsigned char b = model.body[e];
        std::ostringstream  text;
        text << std::setprecision(6) << "element " << e << " ("
             << (b != no_body && b < bodies.size() ? bodies[b].name :
                                                               std::string("no body"))
             << ", material id " << static_cast<unsigned int>(model.material[e])
             << ", reference centroid (" << (x[0] + x[1] + x[2]) / 3. << ", "
             << (y[0] + y[1] + y[2]) / 3. << ") m)";
        return text.str();
      };
      const std::string  a = describe(worst.first), b = describe(worst.second);
      std::ostringstream message;
      message << std::setprecision(6);
      if (initial)
        {
          message
            << "the triangles " << a << " and " << b << " overlap by "
            << worst.area << " m^2 at Time stepping/Start time, "
            << 100. * worst.fraction
            << " % of the smaller one's area (allowed at the start: "
            << 100. * max_initial_overlap
            << " %, a press of about 5 % of the altitude): bodies, and "
               "disconnected pieces of one body, must not overlap at the "
               "start (contact would push them apart violently and invert "
               "elements). Move them apart in the mesh (Mesh/File name, the "
               ".geo file) or leave a gap.";
          throw InputError(message.str());
        }
      const auto &dm = parameters.get<DiscreteMechanicsParameters>();
      message << "guard: contact failed: the triangles " << a << " and " << b
              << " overlap by " << worst.area << " m^2, "
              << 100. * worst.fraction
              << " % of the smaller one's area (allowed: "
              << 100. * max_contact_overlap
              << " %, about a quarter of the smaller altitude "
              << smallest_altitude * 0.25
              << " m pressed flat in) at t = " << time << " s (step "
              << step_number
              << "): the contact penalty is too soft for the impact, and the "
                 "bodies pass through each other. Raise Discrete "
                 "mechanics/Contact penalty factor (now "
              << dm.contact_penalty_factor
              << " x Young's modulus) or lower the impact velocity or load.";
      guard_failure(message.str());
    }

    void
    ExplicitSolver::run()
    {
      check_input();
      const std::string &folder = parameters.output.directory;
      solution_series = std::make_unique<VtuSeries>(folder, "solution");
      crack_series    = std::make_unique<VtuSeries>(folder, "cracks");
      std::string header =
        "time,step,kinetic,strain,joint_work,contact_work,friction_dissipation,"
        "viscous_dissipation,external_work,balance_error,broken_joints,"
        "damaged_joints";
      for (unsigned int b = 0; b < drivers.body_motion.size(); ++b)
        header += ",body" + std::to_string(model.body_number[b]) + "_fx,body" +
                  std::to_string(model.body_number[b]) + "_fy";
      drivers.condition_reaction.assign(drivers.conditions.size(), {{0., 0.}});
      for (unsigned int k = 0; k < drivers.conditions.size(); ++k)
        header += ",condition" + std::to_string(k + 1) + "_fx,condition" +
                  std::to_string(k + 1) + "_fy";
      history_csv = open_csv(folder + "/history.csv", header);
      const std::string monitor_header =
        std::string(with_heat ? "time,name,x,y,T,ux,uy,sxx,syy,sxy" :
                                "time,name,x,y,ux,uy,sxx,syy,sxy") +
        (parameters.mechanics.polar_frame ? ",srr,stt" : "");
      if (!probe_samples.empty())
        probes_csv = open_csv(folder + "/probes.csv", monitor_header);
      if (!line_samples.empty())
        lines_csv = open_csv(folder + "/lines.csv", monitor_header);

      const double start = time, end = parameters.time.end_time;
      // the output schedule every model uses (io/output_schedule.h): times
      // within its round-off tolerance of each other are one time (the
      // interval's accumulated sums against the end time); an output time
      // is reached within half an explicit step, or landed on by the
      // thermal step, below
      output_times = OutputSchedule(parameters.output.times,
                                    parameters.output.interval,
                                    start,
                                    end,
                                    OutputSchedule::default_tolerance(end))
                       .times();
      // explicit steps of one length write one file per step: two requested
      // times within one step would be written as one (the quasi-static
      // thermal step lands on each instead)
      if (!quasi_static)
        for (std::size_t k = 1; k < output_times.size(); ++k)
          if (output_times[k] - output_times[k - 1] < time_step)
            throw InputError(
              "Output/Times (or Interval): the output times " +
              Utilities::to_string(output_times[k - 1]) + " s and " +
              Utilities::to_string(output_times[k]) +
              " s lie closer than one mechanical time step (" +
              Utilities::to_string(time_step) +
              " s), and each step writes one file at most; allowed are times "
              "at least one time step apart.");
      history_interval = (end - start) / 1000.;
      next_history     = start + history_interval;

      if (!parameters.resume)
        {
          energy();
          balance.initial_kinetic = balance.kinetic;
          balance.initial_strain  = balance.strain;
          balance.thermal_work = 0.; // the initial stretch is in initial_strain
          write_output();
          write_history_row();
        }

      ProgressReporter    progress(parameters.output.progress_interval,
                                start,
                                end,
                                writes_files(),
                                !quasi_static);
      const unsigned long max_steps =
        parameters.get<DiscreteMechanicsParameters>().max_steps;
      const double advance =
        quasi_static ? parameters.time.time_step : time_step;
      if (quasi_static)
        {
          history_interval = std::max(history_interval, advance);
          next_history     = start + history_interval;
        }
      if (parameters.resume)
        load_checkpoint();
      keep_good_state();
      CheckpointSchedule checkpoints(parameters.checkpoint);
      checkpoints.written(step_number);
      bool         snap_reported   = false;
      const auto   threads_start   = thread_cpu_times();
      const double loop_cpu_start  = process_cpu_time();
      const auto   loop_wall_start = std::chrono::steady_clock::now();
      // explicit steps are all of one length: stop within half of one;
      // thermal steps shrink near failure and land on the end time
      // (QuasiStaticRelaxation::next_thermal_step()): stop only there, else
      // a run whose steps were shortened would end up to half a Time step
      // early
      const double end_tolerance =
        quasi_static ? 1e-9 * std::max(std::abs(end), advance) : 0.5 * advance;
      while (time < end - end_tolerance &&
             (max_steps == 0 || step_number < max_steps))
        {
          const double time_before = time;
          step();
          check_step_guards();
          // outputs snap to the nearest step: within half of the step just
          // taken (thermal steps shrink near failure, so not half of Time
          // step, which would write an output, the last one included, up to
          // half a Time step early)
          const double snap =
            0.5 * (quasi_static ? time - time_before : advance);
          if (quasi_static && writes_files())
            std::cerr << "[tmfdem] t = " << time << " s: relaxed in "
                      << relaxation.last_relaxation_steps
                      << " mechanical steps, kinetic / strain energy "
                      << relaxation.last_kinetic_to_strain
                      << ", out-of-balance force " << relative_unbalanced_force
                      << "\n";
          // quasi-static: a row after every thermal step (steps may be
          // shorter than Time step near failure, and each is costly anyway)
          if (quasi_static || time >= next_history - 0.5 * advance)
            {
              write_history_row();
              check_slow_guards();
              while (next_history <= time + 0.5 * advance)
                next_history += history_interval;
            }
          // one file per step at most: a long (growing) thermal step may
          // pass several output times
          if (next_output < output_times.size() &&
              time >= output_times[next_output] - snap)
            {
              if (!snap_reported && writes_files() &&
                  std::abs(time - output_times[next_output]) >
                    1e-9 * std::max(1., std::abs(time)))
                {
                  snap_reported = true; // once per run
                  std::cerr
                    << "[tmfdem] output time " << output_times[next_output]
                    << " s requested, written at t = " << time
                    << " s: outputs snap to the nearest "
                    << (quasi_static ? "thermal" : "mechanical") << " step ("
                    << 2. * snap << " s)\n";
                }
              energy();
              write_output();
              while (next_output < output_times.size() &&
                     time >= output_times[next_output] - snap)
                ++next_output;
            }
          if ((step_number & 255) == 0)
            {
              wall_time = progress.elapsed() + resumed_wall_time;
              progress.update(
                step_number,
                time,
                (quasi_static ?
                   "  thermal step " + std::to_string(n_thermal_steps) +
                     " (last relaxed in " +
                     std::to_string(relaxation.last_relaxation_steps) +
                     " steps)  broken joints " :
                   std::string("  broken joints ")) +
                  std::to_string(n_broken_joints()));
            }
          after_step(checkpoints);
        }
      wall_time     = progress.elapsed() + resumed_wall_time;
      loop_cpu_time = process_cpu_time() - loop_cpu_start;
      loop_thread_cpu_times =
        thread_cpu_time_differences(threads_start, thread_cpu_times());
      loop_wall_time = std::chrono::duration<double>(
                         std::chrono::steady_clock::now() - loop_wall_start)
                         .count();
      energy();
      write_history_row();
      if (next_output < output_times.size())
        write_output();
      write_summary(true);
      if (parameters.output.write_final_mesh)
        on_rank_zero([this]() {
          write_file_atomically(parameters.output.directory + "/final_mesh.msh",
                                deformed_mesh_msh(model));
        });
      if (writes_files())
        std::cerr << "[tmfdem] "
                  << (with_heat ? "discrete thermo-mechanics: " :
                                  "discrete mechanics: ")
                  << step_number << " steps of " << time_step
                  << " s to t = " << time << " s, " << model.n_broken_joints()
                  << " broken joints, " << model.n_cracks()
                  << " cracks, energy balance error "
                  << std::abs(balance.balance_error()) / balance.scale() * 100.
                  << " %\n";
    }
  } // namespace discrete
} // namespace tmfdem
