/**
 * @file
 * The outputs of the explicit discrete solver (doc/verification.md, output
 * contract): solution and crack vtu series, history.csv (energy terms,
 * broken joints, reactions), probes.csv and lines.csv (monitor stresses
 * recovered at the vertices, stress_recovery.h) and summary.json.
 */
#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <sys/resource.h>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/polar_stress.h>
#include <tmfdem/discrete/contact_heat.h>
#include <tmfdem/discrete/discrete_output.h>
#include <tmfdem/discrete/explicit_solver.h>
#include <tmfdem/discrete/stress_recovery.h>
#include <tmfdem/discrete/temperature_source.h>
#include <tmfdem/io/output_files.h>

namespace tmfdem
{
  namespace discrete
  {
    EnergyBalance
    ExplicitSolver::energy()
    {
      synchronise(); // the whole state on every rank: same sums as one rank
      measure_stored_energy(model, element_lame, element_anisotropy, balance);
      return balance;
    }

    // -------------------------------------------------------------- output
    void
    ExplicitSolver::write_history_row()
    {
      energy();
      std::ostringstream row;
      row << std::setprecision(10) << time << ',' << step_number << ','
          << balance.kinetic << ',' << balance.strain << ','
          << balance.joint_work << ',' << balance.contact_work << ','
          << balance.friction_dissipation << ',' << balance.viscous_dissipation
          << ',' << balance.external_work << ',' << balance.balance_error()
          << ',' << model.n_broken_joints() << ',' << model.n_damaged_joints();
      for (const auto &r : drivers.body_reaction)
        row << ',' << r[0] << ',' << r[1];
      for (const auto &r : drivers.condition_reaction)
        row << ',' << r[0] << ',' << r[1];
      row << '\n';
      on_rank_zero([&]() { history_csv->append(row.str()); });
    }

    void
    ExplicitSolver::write_output()
    {
      // the whole state and every pair's forces on every rank; each rank
      // writes its piece of the vtu files, rank 0 the rest
      synchronise();
      contact.synchronise_pairs(partition);
      if (partition.distributed() && parameters.output.write_vtu)
        {
          const auto start = std::chrono::steady_clock::now();
          write_vtu_pieces();
          vtu_write_time += std::chrono::duration<double>(
                              std::chrono::steady_clock::now() - start)
                              .count();
        }
      on_rank_zero([this]() { write_output_files(); });
    }

    std::string
    ExplicitSolver::solution_vtu(const unsigned int first,
                                 const unsigned int end) const
    {
      std::vector<double>                                              T;
      std::vector<std::pair<std::string, const std::vector<double> *>> fields;
      if (with_heat)
        {
          T.assign(heat->temperature().begin(), heat->temperature().end());
          fields.emplace_back("T", &T);
        }
      const std::array<double, 2> centre = {
        {parameters.mechanics.polar_centre[0],
         parameters.mechanics.polar_centre[1]}};
      return discrete_solution_vtu(model,
                                   vtu_encoding(parameters.output),
                                   fields,
                                   first,
                                   end,
                                   parameters.mechanics.polar_frame ? &centre :
                                                                      nullptr);
    }

    void
    ExplicitSolver::write_vtu_pieces()
    {
      // this rank's triangles (their nodes) and joints
      const std::string solution =
        solution_vtu(partition.begin(), partition.end());
      const std::string cracks = crack_vtu(model,
                                           vtu_encoding(parameters.output),
                                           partition.first_joint(),
                                           partition.end_joint());
      std::string       failure;
      try
        {
          solution_series->write_piece(partition.rank(), solution);
          crack_series->write_piece(partition.rank(), cracks);
        }
      catch (const std::exception &e)
        {
          failure = e.what();
          if (failure.empty())
            failure = "writing a vtu piece failed on rank " +
                      std::to_string(partition.rank());
        }
      // every rank stops with the first failing rank's message
      for (const std::string &message :
           Utilities::MPI::all_gather(communicator, failure))
        if (!message.empty())
          throw RunError(message);
      // the records once every piece is there
      on_rank_zero([&]() {
        solution_series->write_parallel_record(time,
                                               partition.n_processes(),
                                               solution);
        crack_series->write_parallel_record(time,
                                            partition.n_processes(),
                                            cracks);
      });
      if (!writes_files())
        {
          solution_series->add_parallel_record(time);
          crack_series->add_parallel_record(time);
        }
    }

    void
    ExplicitSolver::write_output_files()
    {
      if (parameters.output.write_vtu && !partition.distributed())
        {
          const auto start = std::chrono::steady_clock::now();
          solution_series->write(time, solution_vtu());
          crack_series->write(time,
                              crack_vtu(model,
                                        vtu_encoding(parameters.output)));
          vtu_write_time += std::chrono::duration<double>(
                              std::chrono::steady_clock::now() - start)
                              .count();
        }
      // monitor stresses: recovered at the mesh vertices (vtu files hold
      // the raw element values); stress_recovery.h. What is known on each
      // boundary edge: the traction (free edges: zero; traction
      // conditions: the applied one), one component (rollers) or nothing
      // (supports, driven bodies, contact)
      std::vector<BoundaryEdgeKnowledge> boundary(3 * model.n_elements);
      {
        using Type = MechanicalBoundaryCondition::Type;
        std::vector<int> condition_of_id(256, -1);
        const auto      &mechanical = parameters.mechanical_boundary.conditions;
        for (unsigned int c = 0; c < mechanical.size(); ++c)
          for (const auto id : mechanical[c].boundary_ids)
            if (id < condition_of_id.size())
              condition_of_id[id] = c;
        for (unsigned int e = 0; e < model.n_elements; ++e)
          {
            if (model.body[e] != no_body &&
                drivers.body_motion[model.body[e]] !=
                  DiscreteBody::Motion::free)
              continue;
            // in contact: contact forces on the element above 1e-3 of its
            // internal forces (|sigma| times the perimeter; elements that
            // share only a vertex exchange tiny forces in an intact mesh)
            if (contact.has_pairs())
              {
                double f[6] = {0., 0., 0., 0., 0., 0.};
                contact.add_forces(e, f);
                double contact = 0., perimeter = 0.;
                for (unsigned int k = 0; k < 3; ++k)
                  {
                    contact += std::hypot(f[2 * k], f[2 * k + 1]);
                    perimeter += std::hypot(model.x[3 * e + (k + 1) % 3] -
                                              model.x[3 * e + k],
                                            model.y[3 * e + (k + 1) % 3] -
                                              model.y[3 * e + k]);
                  }
                const double stress =
                  std::max({std::abs(model.stress[3 * e]),
                            std::abs(model.stress[3 * e + 1]),
                            std::abs(model.stress[3 * e + 2])});
                if (contact > 1e-3 * stress * perimeter)
                  continue;
              }
            const MaterialProperties &m =
              parameters.materials[model.material[e]];
            for (unsigned int k = 0; k < 3; ++k)
              {
                const types::boundary_id id = model.edge_boundary[3 * e + k];
                if (id == numbers::internal_face_boundary_id)
                  continue;
                const unsigned int     a = 3 * e + k, b = 3 * e + (k + 1) % 3;
                BoundaryEdgeKnowledge &edge = boundary[a];
                edge.lame                   = element_lame[e];
                if (!element_anisotropy.empty())
                  std::copy_n(&element_anisotropy[6 * e],
                              6,
                              edge.anisotropy.begin());
                edge.thermal_stretch = model.thermal_stretch[e];
                if (with_heat)
                  edge.thermal_stretch =
                    thermal_stretch(expansion_coefficient(e),
                                    m.poisson_ratio,
                                    0.5 * (heat->temperature()[a] +
                                           heat->temperature()[b]) -
                                      reference_temperature[e],
                                    idealisation);
                const int c =
                  id < condition_of_id.size() ? condition_of_id[id] : -1;
                if (c < 0)
                  edge.kind = BoundaryEdgeKnowledge::Kind::traction;
                else if (drivers.conditions[c].type == Type::traction)
                  {
                    edge.kind = BoundaryEdgeKnowledge::Kind::traction;
                    for (unsigned int d = 0; d < 2; ++d)
                      {
                        drivers.conditions[c].value[d]->set_time(time);
                        // the mean of the ends, as the nodal loads
                        edge.traction[d] =
                          0.5 * (drivers.conditions[c].value[d]->value(
                                   Point<2>(model.x_ref[a], model.y_ref[a])) +
                                 drivers.conditions[c].value[d]->value(
                                   Point<2>(model.x_ref[b], model.y_ref[b])));
                      }
                  }
                else if (drivers.conditions[c].type == Type::roller_x ||
                         drivers.conditions[c].type == Type::roller_y)
                  {
                    // roller x holds u_x: no traction along y, and v.v.
                    edge.kind = BoundaryEdgeKnowledge::Kind::component;
                    edge.component =
                      drivers.conditions[c].type == Type::roller_x ? 1 : 0;
                  }
              }
          }
      }
      const RecoveredStress recovered(model, boundary);
      auto rows = [&](const std::vector<ReferenceSample> &samples) {
        std::ostringstream out;
        out << std::setprecision(10);
        for (const auto &s : samples)
          {
            double ux = 0., uy = 0.;
            for (unsigned int k = 0; k < 3; ++k)
              {
                const unsigned int n = 3 * s.element + k;
                ux += s.lambda[k] * (model.x[n] - model.x_ref[n]);
                uy += s.lambda[k] * (model.y[n] - model.y_ref[n]);
              }
            out << time << ',' << s.name << ',' << s.x << ',' << s.y << ',';
            if (with_heat)
              {
                double T = 0.;
                for (unsigned int k = 0; k < 3; ++k)
                  T += s.lambda[k] * heat->temperature()[3 * s.element + k];
                out << T << ',';
              }
            const Stress2 stress = recovered.value(s.element, s.lambda);
            out << ux << ',' << uy << ',' << stress.xx << ',' << stress.yy
                << ',' << stress.xy;
            if (parameters.mechanics.polar_frame)
              {
                // about the centre, towards the point where it is now
                const auto polar =
                  polar_stress(stress.xx,
                               stress.yy,
                               stress.xy,
                               s.x + ux - parameters.mechanics.polar_centre[0],
                               s.y + uy - parameters.mechanics.polar_centre[1]);
                out << ',' << polar[0] << ',' << polar[1];
              }
            out << '\n';
          }
        return out.str();
      };
      if (!probe_samples.empty())
        probes_csv->append(rows(probe_samples));
      if (!line_samples.empty())
        lines_csv->append(rows(line_samples));
    }

    void
    ExplicitSolver::write_summary(const bool finished) const
    {
      // collective part first (every rank calls this): memory and traffic
      // of all ranks
      rusage usage;
      getrusage(RUSAGE_SELF, &usage);
      const long long peak_memory =
        static_cast<long long>(usage.ru_maxrss) * 1024;
      const long long peak_memory_max = static_cast<long long>(
        Utilities::MPI::max(static_cast<double>(peak_memory), communicator));
      const double ghost_bytes =
        Utilities::MPI::sum(static_cast<double>(partition.ghost_bytes_sent()),
                            communicator);
      const double sync_bytes =
        Utilities::MPI::sum(static_cast<double>(
                              partition.synchronisation_bytes_sent()),
                            communicator);
      const double communication_max =
        Utilities::MPI::max(partition.communication_time(), communicator);
      const double vtu_write_max =
        Utilities::MPI::max(vtu_write_time, communicator);
      const unsigned int contact_pairs = contact.n_mechanical_pairs(partition);
      const double       joint_steps =
        Utilities::MPI::sum(joint_steps_done, communicator);
      const double vectorised_joints =
        Utilities::MPI::sum(vectorised_joint_steps, communicator);
      const double ghosts =
        Utilities::MPI::sum(static_cast<double>(partition.n_ghosts()),
                            communicator);
      on_rank_zero([&]() {
        JsonObject energies;
        energies.add("kinetic", balance.kinetic)
          .add("strain", balance.strain)
          .add("initial_kinetic", balance.initial_kinetic)
          .add("initial_strain", balance.initial_strain)
          .add("joint_work", balance.joint_work)
          .add("joint_stored", balance.joint_stored)
          .add("joint_dissipated", balance.joint_work - balance.joint_stored)
          .add("contact_work", balance.contact_work)
          .add("contact_penalty",
               balance.contact_work - balance.friction_dissipation)
          .add("friction_dissipation", balance.friction_dissipation)
          .add("viscous_dissipation", balance.viscous_dissipation)
          .add("external_work", balance.external_work)
          .add("thermal_work", balance.thermal_work)
          .add("relaxation_work", balance.relaxation_work)
          .add("elastic_work", balance.elastic_work)
          .add("balance_error", balance.balance_error())
          .add("relative_balance_error",
               std::abs(balance.balance_error()) / balance.scale());
        unsigned int by_mode[4] = {0, 0, 0, 0};
        for (const auto s : model.joint_status)
          ++by_mode[static_cast<unsigned int>(s)];
        // momentum and angular momentum about the origin (positions at the
        // step, velocities at its half step) [kg m/s, kg m^2/s per m]
        double px = 0., py = 0., angular = 0.;
        for (unsigned int n = 0; n < model.n_nodes; ++n)
          {
            px += model.mass[n] * model.vx[n];
            py += model.mass[n] * model.vy[n];
            angular += model.mass[n] *
                       (model.x[n] * model.vy[n] - model.y[n] * model.vx[n]);
          }
        std::vector<JsonObject> reactions;
        for (unsigned int b = 0; b < drivers.body_reaction.size(); ++b)
          {
            JsonObject r;
            r.add("body",
                  parameters.get<DiscreteBodyParameters>().bodies[b].name)
              .add("force_x", drivers.body_reaction[b][0])
              .add("force_y", drivers.body_reaction[b][1]);
            reactions.push_back(r);
          }
        JsonObject summary;
        summary
          .add("model",
               std::string(with_heat ? "discrete thermo-mechanics" :
                                       "discrete mechanics"))
          .add("finished", finished)
          .add("elements", model.n_elements)
          .add("nodes", model.n_nodes)
          .add("joints", model.n_joints)
          .add("steps", static_cast<long long>(step_number))
          .add("end_time", time)
          .add("time_step", time_step)
          .add("stable_time_step", stable_time_step)
          .add(
            "mass_scaling_factor",
            parameters.get<DiscreteMechanicsParameters>().mass_scaling_factor)
          .add("joint_compliance_compensation",
               parameters.get<DiscreteMechanicsParameters>()
                 .joint_compliance_compensation)
          .add("anisotropic_compensation", !element_anisotropy.empty())
          .add("compensation_max_share", compensation_share)
          .add("compensation_capped_elements", compensation_capped)
          .add("threads", n_threads)
          .add("threads_requested", threads_requested)
          .add("threads_available", threads_available)
          .add("threads_used", threads_used)
          .add("vector_instructions",
               vector_instructions_name(vector_instructions))
          .add("vectorised_element_share",
               element_steps_done > 0. ?
                 vectorised_element_steps / element_steps_done :
                 0.)
          .add("vectorised_joint_share",
               joint_steps > 0. ? vectorised_joints / joint_steps : 0.)
          .add("cpu_time_s", loop_cpu_time)
          .add("wall_time_s", loop_wall_time)
          .add("cpu_time_busiest_thread_s",
               loop_thread_cpu_times.empty() ? 0. : loop_thread_cpu_times[0])
          .add("cpu_time_other_threads_s",
               [this] {
                 double other = 0.;
                 for (std::size_t k = 1; k < loop_thread_cpu_times.size(); ++k)
                   other += loop_thread_cpu_times[k];
                 return other;
               }())
          .add("wall_time", wall_time)
          .add("element_steps_per_second",
               wall_time > 0. ?
                 model.n_elements * double(step_number) / wall_time :
                 0.)
          .add("broken_joints", model.n_broken_joints())
          .add("broken_mode_I", by_mode[1])
          .add("broken_mode_II", by_mode[2])
          .add("broken_mixed", by_mode[3])
          .add("cracks", model.n_cracks())
          .add("contact_searches", static_cast<long long>(contact.n_searches()))
          .add("contact_pairs", contact_pairs)
          .add("peak_resident_memory_bytes", peak_memory_max)
          .add("mpi_processes", partition.n_processes())
          .add("ghost_elements", ghosts)
          .add("ghost_exchange_bytes", ghost_bytes)
          .add("synchronisations",
               static_cast<long long>(partition.n_synchronisations()))
          .add("synchronisation_bytes", sync_bytes)
          .add("communication_time_s", communication_max)
          .add("vtu_write_time_s", vtu_write_max)
          .add("momentum_x", px)
          .add("momentum_y", py)
          .add("angular_momentum", angular)
          .add("energy", energies)
          .add("body_reactions", reactions);
        if (!model.expansion_factor.empty())
          {
            // the drawn field's statistics, weighted by the triangles' areas
            double area = 0., mean = 0., square = 0.;
            double low = model.expansion_factor[0], high = low;
            for (unsigned int e = 0; e < model.n_elements; ++e)
              {
                const double a = model.reference_area[e];
                const double f = model.expansion_factor[e];
                area += a;
                mean += a * f;
                square += a * f * f;
                low  = std::min(low, f);
                high = std::max(high, f);
              }
            mean /= area;
            JsonObject field;
            field.add("mean", mean)
              .add("standard_deviation",
                   std::sqrt(std::max(0., square / area - mean * mean)))
              .add("min", low)
              .add("max", high);
            summary.add("expansion_factor", field);
          }
        if (!stop_reason.empty())
          summary.add("stop_reason", stop_reason);
        if (with_heat)
          {
            const JsonObject hb = heat_balance_summary(*heat);
            summary
              .add("coupling",
                   parameters.get<DiscreteHeatParameters>().coupling_name())
              .add("temperature_source", heat->name())
              .add("heat_distributed", heat_distributed)
              .add(
                "contact_heat_model",
                contact_heat_model_name(
                  parameters.get<DiscreteHeatParameters>().contact_heat_model))
              .add("continuum_heat_across_cracks", heat_across_cracks)
              .add("thermal_steps", static_cast<long long>(n_thermal_steps))
              .add("last_relaxation_steps", relaxation.last_relaxation_steps)
              .add("relaxations_at_cap", relaxation.relaxations_at_cap)
              .add("rejected_thermal_steps",
                   static_cast<long long>(relaxation.rejected_thermal_steps))
              .add("unstable_thermal_steps",
                   static_cast<long long>(relaxation.unstable_thermal_steps))
              .add("predicted_relaxations", relaxation.predicted_relaxations)
              .add("velocity_resets",
                   static_cast<long long>(relaxation.velocity_resets))
              .add("fracture_events",
                   static_cast<long long>(relaxation.fracture_events))
              .add("fracture_event_steps",
                   static_cast<long long>(relaxation.fracture_event_steps))
              .add("last_relative_unbalanced_force", relative_unbalanced_force)
              .add("last_kinetic_to_strain_energy",
                   relaxation.last_kinetic_to_strain)
              .add("mechanical_steps_per_thermal_step", steps_per_thermal_step)
              .add("thermal_time_step",
                   quasi_static ? parameters.time.time_step :
                                  steps_per_thermal_step * time_step)
              .add("heat_balance", hb);
          }
        write_file_atomically(parameters.output.directory + "/summary.json",
                              summary.str() + "\n");
      });
    }

  } // namespace discrete
} // namespace tmfdem
