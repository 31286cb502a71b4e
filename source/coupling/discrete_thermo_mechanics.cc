/**
 * @file
 * The staggered thermo-mechanical loops of the discrete layer (model
 * `discrete thermo-mechanics`; theory manual, "Coupling"), each readable in
 * one screen:
 *
 * - multi-rate (Discrete heat/Coupling = dynamic): one explicit mechanical
 *   step per call of ExplicitSolver::step(); every n-th step one thermal
 *   step of the temperature source over the same time (M -> T: current
 *   geometry, broken joints, contacts), then the new thermal stretch
 *   F_T = s I (T -> M): multi_rate_thermal_step();
 * - quasi-static (Coupling = quasi-static): one thermal step of physical
 *   time per call, then the mechanics relaxes at these temperatures without
 *   advancing the clock (damped explicit steps until kinetic/strain energy
 *   and out-of-balance force are below their tolerances), optionally from
 *   an extrapolated start: quasi_static_step(). The state of the
 *   relaxations and of the thermal step control, and the decisions that
 *   read only it (the next step, a re-run, the ramp of imposed motion), are
 *   coupling::QuasiStaticRelaxation (ExplicitSolver::relaxation).
 *
 * The mechanical step itself is ExplicitSolver::mechanical_step()
 * (source/discrete/explicit_solver.cc); the temperature source is a
 * discrete::TemperatureSource (discrete heat or the continuum heat).
 */
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <optional>
#include <tmfdem/discrete/explicit_solver.h>
#include <tmfdem/discrete/joints.h>
#include <tmfdem/discrete/temperature_source.h>

namespace tmfdem
{
  namespace discrete
  {
    void
    ExplicitSolver::update_heat_contact_pairs()
    {
      // one pair search feeds contact forces and contact heat: bring the
      // mechanics' candidates up to date (the next mechanical step would
      // search at these same positions) before the source filters them
      if (contact.enabled() && contact.search_needed())
        search_contacts();
      // on several ranks each keeps the pairs of its own triangles; a heat
      // that runs replicated reads all (one gather per search)
      if (contact.enabled() && !heat_distributed)
        contact.gather_all_pairs(partition);
      heat->update_contact_pairs();
    }

    void
    ExplicitSolver::multi_rate_thermal_step()
    {
      // M -> T: current geometry, broken joints, contacts (on several
      // ranks each advances its own triangles, or, replicated, all of
      // them from the whole state: partition.h)
      if (!heat_distributed)
        synchronise();
      check_cracks_seen_by_heat();
      update_heat_contact_pairs();
      heat->step(thermal_time, time - thermal_time);
      thermal_time = time;
      ++n_thermal_steps;
      // T -> M
      update_thermal_stretch();
    }

    void
    ExplicitSolver::quasi_static_step()
    {
      const double dt =
        relaxation.next_thermal_step(time,
                                     n_thermal_steps,
                                     next_output < output_times.size() ?
                                       std::optional<double>(
                                         output_times[next_output]) :
                                       std::nullopt);
      // the whole state (on several ranks): the relaxation predictor
      // extrapolates every node from it; the heat reads its own part
      synchronise();
      // the thermal step, re-run shorter from its start where too many
      // joints break in it or its relaxation does not converge (theory
      // manual 8, "Thermal steps through the fracture process"):
      // QuasiStaticRelaxation::thermal_step(), written once for triangles
      // and tetrahedra, on this solver's joints, state and steps
      struct Step
      {
        ExplicitSolver &s;
        void
        joint_damages(std::vector<double> &d) const
        {
          discrete::joint_damages(s.model, d);
        }
        void
        joint_utilisations(std::vector<double> &u) const
        {
          discrete::joint_utilisations(s.model, u);
        }
        void
        keep_thermal_step_start()
        {
          s.keep_thermal_step_start();
        }
        void
        restore_thermal_step_start()
        {
          s.restore_thermal_step_start();
        }
        void
        advance_thermal_step(const double dt)
        {
          s.advance_thermal_step(dt);
        }
        double
        time() const
        {
          return s.time;
        }
        bool
        writes_files() const
        {
          return s.writes_files();
        }
        unsigned int
        cap() const
        {
          return s.steps_per_thermal_step;
        }
        double
        relative_unbalanced_force() const
        {
          return s.relative_unbalanced_force;
        }
        void
        guard_failure(const std::string &message)
        {
          s.guard_failure(message);
        }
      } step{*this};
      relaxation.thermal_step(step, dt, relaxation.control(time_step));
    }

    void
    ExplicitSolver::advance_thermal_step(const double dt)
    {
      check_cracks_seen_by_heat();
      update_heat_contact_pairs();
      heat->step(time, dt);
      time += dt;
      thermal_time = time;
      ++n_thermal_steps;
      update_thermal_stretch();
      // ... then the mechanics relaxes at these temperatures (no clock),
      // from the extrapolated state where asked for
      if (parameters.get<DiscreteHeatParameters>().relaxation_predictor ==
          DiscreteHeatParameters::RelaxationPredictor::extrapolate)
        predict_relaxation(dt);
      relaxation.current_thermal_step = dt;
      // the relaxation (QuasiStaticRelaxation::relax(), written once for
      // triangles and tetrahedra) on this solver's steps and energies
      struct Steps
      {
        ExplicitSolver &s;
        bool
        relaxation_step()
        {
          s.mechanical_step();
          return s.joints_broke_anywhere;
        }
        double
        step_kinetic() const
        {
          return s.step_kinetic;
        }
        void
        reset_velocities()
        {
          s.reset_velocities();
        }
        coupling::QuasiStaticRelaxation::Energies
        relaxation_energies()
        {
          s.energy();
          return {s.balance.kinetic,
                  s.balance.strain,
                  s.balance.strain + s.balance.joint_stored};
        }
        double
        relative_unbalanced_force() const
        {
          return s.relative_unbalanced_force;
        }
      } steps{*this};
      relaxation.relax(steps,
                       steps_per_thermal_step,
                       relaxation.control(time_step));
      synchronise(); // joint counts and utilisation of the whole state
      if (parameters.get<DiscreteHeatParameters>().relaxation_predictor ==
          DiscreteHeatParameters::RelaxationPredictor::extrapolate)
        relaxation.damaged_after_relaxation = n_damaged_or_broken_joints(model);
    }

    void
    ExplicitSolver::update_thermal_stretch()
    {
      // this rank's triangles where the heat is distributed (the others'
      // stretches come with the next synchronise()), else every triangle;
      // the work per chunk, the chunks added in order: the same on any
      // number of ranks
      const Vector<double> &T     = heat->temperature();
      const unsigned int    first = heat_distributed ? partition.begin() : 0;
      const unsigned int    end =
        heat_distributed ? partition.end() : model.n_elements;
      std::vector<double> work(2 * ((model.n_elements + chunk_size - 1) /
                                    chunk_size),
                               0.);
      for (unsigned int e = first; e < end; ++e)
        {
          const MaterialProperties &m = parameters.materials[model.material[e]];
          const double dT = (T[3 * e] + T[3 * e + 1] + T[3 * e + 2]) / 3. -
                            reference_temperature[e];
          const double s_new = thermal_stretch(expansion_coefficient(e),
                                               m.poisson_ratio,
                                               dT,
                                               idealisation);
          const double s_old = model.thermal_stretch[e];
          if (s_new == s_old)
            continue;
          // the strain energy this changes at fixed geometry (energy.h)
          const Matrix2 F = deformation_gradient(model, e);
          double       *w = &work[2 * (e / chunk_size)];
          const double *anisotropy =
            element_anisotropy.empty() ? nullptr : &element_anisotropy[6 * e];
          w[0] += element_strain_energy(model,
                                        e,
                                        F,
                                        s_old,
                                        element_lame[e],
                                        anisotropy);
          w[1] += element_strain_energy(model,
                                        e,
                                        F,
                                        s_new,
                                        element_lame[e],
                                        anisotropy);
          model.thermal_stretch[e] = s_new;
        }
      if (heat_distributed)
        {
          partition.sum(work); // exact: each chunk from one rank
          thermal_state_gathered = false;
        }
      double before = 0., after = 0.;
      for (std::size_t c = 0; c < work.size(); c += 2)
        {
          before += work[c];
          after += work[c + 1];
        }
      balance.thermal_work += after - before;
    }

    void
    ExplicitSolver::check_cracks_seen_by_heat()
    {
      if (heat->sees_cracks() || heat_across_cracks)
        return;
      const unsigned int broken = model.n_broken_joints();
      if (broken == 0)
        return;
      const std::string what =
        "Discrete heat/Temperature source = " + heat->name() + ": " +
        std::to_string(broken) +
        " joint(s) broken by t = " + Utilities::to_string(time) +
        " s, and this source conducts across them as if intact (no crack, "
        "no contact heat)";
      if (!parameters.get<DiscreteHeatParameters>()
             .accept_continuum_source_at_broken_joints)
        guard_failure(what +
                      "; the temperature near the cracks would be wrong from "
                      "here on. Set Discrete heat/Continuum source at broken "
                      "joints = accept to go on regardless, or Temperature "
                      "source = discrete heat.");
      heat_across_cracks = true;
      std::cerr << "[tmfdem] warning: " << what
                << "; going on (Continuum source at broken joints = "
                   "accept); summary.json records "
                   "continuum_heat_across_cracks.\n";
    }

    void
    ExplicitSolver::reset_velocities()
    {
      // the energy removed is summed over all nodes in node order: on
      // several ranks from the whole state
      synchronise();
      double removed = 0.;
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        {
          if (!drivers.node_is_free(n))
            continue;
          const bool   px = drivers.prescribed(n, 0);
          const bool   py = drivers.prescribed(n, 1);
          const double vx = px ? 0. : model.vx[n], vy = py ? 0. : model.vy[n];
          removed += 0.5 * model.mass[n] * (vx * vx + vy * vy);
          // back to the middle of the last step, where v^{n+1/2} lives:
          // resting there (not at x^{n+1}) keeps the reset from feeding
          // the highest modes, whose kinetic energy peaks every step
          model.x[n] -= 0.5 * time_step * vx;
          model.y[n] -= 0.5 * time_step * vy;
          model.vx[n] = px ? model.vx[n] : 0.;
          model.vy[n] = py ? model.vy[n] : 0.;
        }
      balance.viscous_dissipation += removed;
      ++relaxation.velocity_resets;
    }

    void
    ExplicitSolver::predict_relaxation(const double dt)
    {
      // the last relaxation took the state from relaxed_x to x over the
      // thermal step relaxed_thermal_step; a response linear in time goes on
      // by the same increment per unit time (where
      // QuasiStaticRelaxation::extrapolates() says it does)
      std::vector<double> &relaxed_x = relaxation.relaxed_x;
      std::vector<double> &relaxed_y = relaxation.relaxed_y;
      const unsigned int   damaged   = n_damaged_or_broken_joints(model);
      if (relaxation.extrapolates(model.n_nodes, damaged))
        {
          const EnergyBalance before = energy();
          const double        contact_before =
            contact.enabled() ? contact.stored_energy(model, partition) : 0.;
          const double ratio = dt / relaxation.relaxed_thermal_step;
          for (unsigned int n = 0; n < model.n_nodes; ++n)
            {
              const double dx = model.x[n] - relaxed_x[n];
              const double dy = model.y[n] - relaxed_y[n];
              relaxed_x[n]    = model.x[n];
              relaxed_y[n]    = model.y[n];
              if (!drivers.node_is_free(n))
                continue;
              if (!drivers.prescribed(n, 0))
                model.x[n] += ratio * dx;
              if (!drivers.prescribed(n, 1))
                model.y[n] += ratio * dy;
            }
          energy();
          // the jump's work on the solid, the intact joints and the
          // contacts of the current pairs, each the change of its stored
          // energy (damaged joints: not booked)
          const double contact_jump =
            contact.enabled() ?
              contact.stored_energy(model, partition) - contact_before :
              0.;
          balance.relaxation_work += balance.strain - before.strain +
                                     balance.joint_stored -
                                     before.joint_stored + contact_jump;
          balance.joint_work += balance.joint_stored - before.joint_stored;
          balance.contact_work += contact_jump;
          if (contact.enabled())
            contact.request_search();
          ++relaxation.predicted_relaxations;
        }
      else
        {
          relaxed_x = model.x;
          relaxed_y = model.y;
        }
      relaxation.relaxed_thermal_step      = dt;
      relaxation.damaged_before_relaxation = damaged;
    }

  } // namespace discrete
} // namespace tmfdem
