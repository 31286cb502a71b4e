/**
 * @file
 * The heat of the discrete layer in 3D and its coupling to the mechanics
 * of the tetrahedra (models `discrete heat` and `discrete thermo-mechanics`
 * with Mesh/Dimension = 3), the multi-rate loop of 2D: one thermal step of
 * TetrahedralHeat every n mechanical steps over the same time, at the
 * current geometry and joints (M -> T), then the new thermal stretch
 * F_T = s I of every tetrahedron from its mean temperature (T -> M). The
 * strain energy each new stretch changes at fixed geometry is the thermal
 * work of the energy balance. With Discrete heat/Coupling = quasi-static,
 * the quasi-static loop of 2D: a thermal step of physical time, then the
 * damped relaxation at its temperatures without advancing the clock, with
 * the step control of coupling::QuasiStaticRelaxation (the rise of the
 * joints' utilisation, the joints that break, re-runs from the step's
 * start).
 */
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/element_kernel.h>
#include <tmfdem/discrete/joints.h>
#include <tmfdem/discrete/tetrahedral_heat.h>
#include <tmfdem/discrete/tetrahedral_solver.h>
#include <tmfdem/discrete/tetrahedron_contact_system.h>
#include <tmfdem/io/checkpoint.h>

namespace tmfdem
{
  namespace discrete
  {
    void
    TetrahedralSolver::setup_heat()
    {
      const auto &dh = parameters.get<DiscreteHeatParameters>();
      heat           = std::make_unique<TetrahedralHeat>(parameters, model);
      heat->set_threads(n_threads);
      // contact heat: the pairs of the mechanics' contact search; the heat
      // alone searches its fixed geometry itself
      heat->set_contact_candidates(contact ? &contact->pairs() : nullptr,
                                   with_mechanics());
      heat->initialise(parameters.time.start_time);
      thermal_time    = parameters.time.start_time;
      n_thermal_steps = 0;
      if (!with_mechanics())
        {
          // the heat alone marches at Time stepping/Time step
          time_step = parameters.time.time_step;
          if (!heat->implicit() && time_step > heat->stable_time_step())
            throw InputError(
              "Time stepping/Time step = " + Utilities::to_string(time_step) +
              " s exceeds the stable explicit thermal step " +
              Utilities::to_string(heat->stable_time_step()) +
              " s of this mesh (lumped capacity, joint conductance, Robin "
              "coefficients, contact conductance of the pairs in contact); "
              "allowed is at most the stable step, or "
              "Discrete heat/Time integration = implicit.");
          return;
        }
      // the multi-rate cadence, as in 2D; quasi-static: the cap of each
      // relaxation
      quasi_static =
        dh.coupling == DiscreteHeatParameters::Coupling::quasi_static;
      const unsigned int n = dh.mechanical_steps_per_thermal_step;
      if (n > 0)
        steps_per_thermal_step = n;
      else if (quasi_static)
        steps_per_thermal_step = 2000;
      else if (heat->implicit())
        steps_per_thermal_step =
          std::max(1., std::floor(parameters.time.time_step / time_step + 0.5));
      else
        steps_per_thermal_step =
          std::max(1.,
                   std::floor(dh.safety_factor * heat->stable_time_step() /
                              time_step));
      const double thermal_step = quasi_static ?
                                    parameters.time.time_step :
                                    steps_per_thermal_step * time_step;
      if (quasi_static)
        {
          // velocities and displacements imposed in thermal time are
          // ramped in over the first relaxation steps of each thermal step
          // (as in 2D)
          relaxation.set_ramp(!velocity_functions.empty() ||
                                imposed_displacements,
                              steps_per_thermal_step,
                              imposed_displacements ?
                                "velocities or displacements" :
                                "velocities");
          // an unloaded body relaxes at once (strains below 1e-10)
          double EV = 0.;
          for (unsigned int e = 0; e < model.n_elements; ++e)
            EV += parameters.materials[model.material[e]].youngs_modulus *
                  model.reference_area[e];
          relaxation.unloaded_energy = 1e-20 * EV;
        }
      if (!heat->implicit() && thermal_step > heat->stable_time_step())
        throw InputError("Discrete heat/Mechanical steps per thermal step = " +
                         std::to_string(steps_per_thermal_step) +
                         " makes the thermal step " +
                         Utilities::to_string(thermal_step) +
                         " s, above the stable explicit thermal step " +
                         Utilities::to_string(heat->stable_time_step()) +
                         " s; allowed is at most " +
                         std::to_string(static_cast<unsigned long>(
                           heat->stable_time_step() / time_step)) +
                         ", or 0 (automatic), or implicit heat.");
      // the stress-free temperature of each tetrahedron
      reference_temperature.resize(model.n_elements);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        reference_temperature[e] =
          parameters.initial.stress_free ?
            heat->element_temperature(e) :
            parameters.materials[model.material[e]].reference_temperature;
      update_thermal_stretch();
    }

    void
    TetrahedralSolver::thermal_step()
    {
      if (!(time > thermal_time))
        return;
      heat->step(thermal_time, time - thermal_time);
      thermal_time = time;
      ++n_thermal_steps;
      if (with_mechanics())
        update_thermal_stretch();
    }

    void
    TetrahedralSolver::update_thermal_stretch()
    {
      const std::size_t n_chunks =
        (model.n_elements + chunk_size - 1) / chunk_size;
      std::vector<double> work(n_chunks, 0.);
      for_each_chunk(arena_for(n_threads),
                     model.n_elements,
                     chunk_size,
                     [&](const std::size_t begin,
                         const std::size_t end,
                         const std::size_t c) {
                       for (std::size_t e = begin; e < end; ++e)
                         {
                           const MaterialProperties &m =
                             parameters.materials[model.material[e]];
                           const double alpha =
                             model.expansion_factor.empty() ?
                               m.thermal_expansion :
                               m.thermal_expansion * model.expansion_factor[e];
                           const double s_new = constitutive::thermal_stretch(
                             alpha,
                             m.poisson_ratio,
                             heat->element_temperature(e) -
                               reference_temperature[e],
                             Idealisation::solid_3d);
                           const double s_old = model.thermal_stretch[e];
                           if (s_new == s_old)
                             continue;
                           work[c] += element_strain_energy(e, s_new) -
                                      element_strain_energy(e, s_old);
                           model.thermal_stretch[e] = s_new;
                         }
                     });
      for (const double w : work)
        energies.thermal_work += w;
    }

    bool
    TetrahedralSolver::relaxation_step()
    {
      // imposed velocities: v (at the middle of the thermal step) times
      // dt_thermal / (ramp dt) during the ramp, 0 after it
      if (!velocity_functions.empty())
        {
          const double scale = relaxation.imposed_velocity_scale(time_step);
          if (!(scale == imposed_velocity_scale))
            {
              evaluate_imposed_velocities(time -
                                            0.5 *
                                              relaxation.current_thermal_step,
                                          scale);
              imposed_velocity_scale = scale;
            }
        }
      // displacements: reached at the end of the ramp (thermal time does
      // not move while the mechanics relaxes)
      evaluate_imposed_displacements(time,
                                     relaxation.steps_to_ramp_end() *
                                       time_step);
      const bool broke = compute_joint_forces();
      if (contact)
        {
          if (broke)
            {
              contact->update_active_elements(model);
              contact->request_search();
            }
          compute_contact_forces(time_step);
        }
      update_nodes(time_step);
      ++step_number;
      return broke;
    }

    void
    TetrahedralSolver::predict_relaxation(const double dt)
    {
      // the last relaxation took the state from relaxed_x/y/z to x/y/z over
      // the thermal step relaxed_thermal_step; a response linear in time
      // goes on by the same increment per unit time (where
      // QuasiStaticRelaxation::extrapolates() says it does)
      std::vector<double> *relaxed[3]  = {&relaxation.relaxed_x,
                                          &relaxation.relaxed_y,
                                          &relaxation.relaxed_z};
      std::vector<double> *position[3] = {&model.x, &model.y, &model.z};
      const unsigned int   damaged     = n_damaged_or_broken_joints(model);
      if (relaxation.extrapolates(model.n_nodes, damaged))
        {
          // the jump's energy: the strain energy exactly (before and
          // after), the intact joints' by the trapezoidal rule on their
          // forces along the jump (the joint kernel gives forces, not a
          // stored energy; the jump is small against a joint's opening)
          compute_state_energies();
          const double strain_before = energies.strain;
          // and the contact's stored energy (the pairs of the last search)
          const double contact_before =
            contact ? contact->stored_energy(model, arena_for(n_threads)) : 0.;
          compute_joint_forces();
          const std::vector<double> joint_force_before = model.node_joint_force;
          const double        ratio = dt / relaxation.relaxed_thermal_step;
          std::vector<double> jump(3 * model.n_nodes, 0.);
          for (unsigned int n = 0; n < model.n_nodes; ++n)
            {
              const int ci = node_constraint[n];
              for (unsigned int i = 0; i < 3; ++i)
                {
                  const double d   = (*position[i])[n] - (*relaxed[i])[n];
                  (*relaxed[i])[n] = (*position[i])[n];
                  if (ci >= 0 && constraints[ci].prescribed[i])
                    continue;
                  jump[3 * n + i] = ratio * d;
                  (*position[i])[n] += ratio * d;
                }
            }
          compute_joint_forces();
          double joint_jump = 0.;
          for (unsigned int n = 0; n < model.n_nodes; ++n)
            for (unsigned int i = 0; i < 3; ++i)
              {
                const double *before = &joint_force_before[9 * n];
                const double *after  = &model.node_joint_force[9 * n];
                const double  f_before =
                  before[i] + before[3 + i] + before[6 + i];
                const double f_after = after[i] + after[3 + i] + after[6 + i];
                // the forces act on the nodes: the joints store minus
                // their work
                joint_jump -= 0.5 * (f_before + f_after) * jump[3 * n + i];
              }
          compute_state_energies();
          const double contact_jump =
            contact ? contact->stored_energy(model, arena_for(n_threads)) -
                        contact_before :
                      0.;
          energies.relaxation_work +=
            energies.strain - strain_before + joint_jump + contact_jump;
          energies.joint_work += joint_jump;
          energies.contact_work += contact_jump;
          ++relaxation.predicted_relaxations;
        }
      else
        for (unsigned int i = 0; i < 3; ++i)
          *relaxed[i] = *position[i];
      relaxation.relaxed_thermal_step      = dt;
      relaxation.damaged_before_relaxation = damaged;
    }

    double
    TetrahedralSolver::kinetic_energy() const
    {
      // per chunk of tetrahedra (their nodes) on the solver's threads, the
      // chunks added in order: the same on any number of threads
      const std::size_t n_chunks =
        (model.n_elements + chunk_size - 1) / chunk_size;
      chunk_kinetic.assign(n_chunks, 0.);
      const DiscreteModel &m = model;
      for_each_chunk(arena_for(n_threads),
                     m.n_elements,
                     chunk_size,
                     [&](const std::size_t begin,
                         const std::size_t end,
                         const std::size_t c) {
                       double kinetic = 0.;
                       for (std::size_t n = 4 * begin; n < 4 * end; ++n)
                         kinetic += 0.5 * m.mass[n] *
                                    (m.vx[n] * m.vx[n] + m.vy[n] * m.vy[n] +
                                     m.vz[n] * m.vz[n]);
                       chunk_kinetic[c] = kinetic;
                     });
      double kinetic = 0.;
      for (const double k : chunk_kinetic)
        kinetic += k;
      return kinetic;
    }

    void
    TetrahedralSolver::reset_velocities()
    {
      double removed = 0.;
      for (std::size_t n = 0; n < model.n_nodes; ++n)
        {
          const int ci   = node_constraint[n];
          double   *v[3] = {&model.vx[n], &model.vy[n], &model.vz[n]};
          double   *x[3] = {&model.x[n], &model.y[n], &model.z[n]};
          for (unsigned int i = 0; i < 3; ++i)
            {
              if (ci >= 0 && constraints[ci].prescribed[i])
                continue;
              removed += 0.5 * model.mass[n] * *v[i] * *v[i];
              *x[i] -= 0.5 * time_step * *v[i];
              *v[i] = 0.;
            }
        }
      energies.damping += removed;
      ++relaxation.velocity_resets;
    }

    double
    TetrahedralSolver::unbalanced_force()
    {
      // the joint forces at the current positions, as the element forces
      // (the next step evaluates them here again: the same values); the
      // contact forces of the last step (evaluating them again would
      // advance the friction history twice), and the weight (no ramp in
      // quasi-static coupling; with mass scaling the physical weight)
      compute_joint_forces();
      const auto &dm         = parameters.get<DiscreteMechanicsParameters>();
      double      gravity[3] = {0., 0., 0.};
      if (dm.gravity.size() == 3)
        for (unsigned int i = 0; i < 3; ++i)
          gravity[i] = dm.gravity[i] / dm.mass_scaling_factor;
      // per chunk of tetrahedra (their nodes), summed in chunk order
      const std::size_t n_chunks =
        (model.n_elements + chunk_size - 1) / chunk_size;
      std::vector<std::array<double, 2>> sums(n_chunks, {{0., 0.}});
      for_each_chunk(
        arena_for(n_threads),
        model.n_elements,
        chunk_size,
        [&](const std::size_t begin,
            const std::size_t end,
            const std::size_t c) {
          for (std::size_t e = begin; e < end; ++e)
            {
              const std::size_t          n0            = 4 * e;
              const double *const        nodes[3]      = {&model.x[n0],
                                                          &model.y[n0],
                                                          &model.z[n0]};
              const double *const        velocities[3] = {&model.vx[n0],
                                                          &model.vy[n0],
                                                          &model.vz[n0]};
              const double               s = model.thermal_stretch[e];
              ElementResponse<3, double> r;
              element_response<3, double>(nodes,
                                          velocities,
                                          &model.inverse_basis[9 * e],
                                          s == 1. ? 1. : 1. / s,
                                          element_lame[e].mu,
                                          element_lame[e].lambda,
                                          anisotropy_of(e),
                                          0.,
                                          r);
              double f_contact[12] = {};
              if (contact && element_in_contact[e])
                contact->add_forces(e, f_contact);
              for (unsigned int k = 0; k < 4; ++k)
                {
                  const std::size_t node = n0 + k;
                  const double     *jf   = &model.node_joint_force[9 * node];
                  const int         ci   = node_constraint[node];
                  for (unsigned int i = 0; i < 3; ++i)
                    {
                      sums[c][1] += r.f_elastic[k][i] * r.f_elastic[k][i];
                      if (ci >= 0 && constraints[ci].prescribed[i])
                        continue;
                      const double f = r.f_elastic[k][i] + jf[i] + jf[3 + i] +
                                       jf[6 + i] + f_contact[3 * k + i] +
                                       model.mass[node] * gravity[i];
                      sums[c][0] += f * f;
                    }
                }
            }
        });
      double unbalanced = 0., internal = 0.;
      for (const auto &c : sums)
        {
          unbalanced += c[0];
          internal += c[1];
        }
      return std::sqrt(unbalanced / std::max(internal, 1e-300));
    }

    void
    TetrahedralSolver::advance_thermal_step(const double dt)
    {
      heat->step(time, dt);
      time += dt;
      thermal_time = time;
      ++n_thermal_steps;
      update_thermal_stretch();
      // ... then the mechanics relaxes at these temperatures (no clock),
      // from the extrapolated state where asked for
      const bool predictor =
        parameters.get<DiscreteHeatParameters>().relaxation_predictor ==
        DiscreteHeatParameters::RelaxationPredictor::extrapolate;
      if (predictor)
        predict_relaxation(dt);
      relaxation.current_thermal_step = dt;
      imposed_velocity_scale = std::numeric_limits<double>::quiet_NaN();
      // the relaxation (QuasiStaticRelaxation::relax(), written once for
      // triangles and tetrahedra) on this solver's steps and energies
      struct Steps
      {
        TetrahedralSolver &s;
        bool
        relaxation_step()
        {
          return s.relaxation_step();
        }
        double
        step_kinetic() const
        {
          return s.kinetic_energy();
        }
        void
        reset_velocities()
        {
          s.reset_velocities();
        }
        coupling::QuasiStaticRelaxation::Energies
        relaxation_energies()
        {
          s.compute_state_energies();
          return {s.energies.kinetic, s.energies.strain, s.energies.strain};
        }
        double
        relative_unbalanced_force()
        {
          s.relative_unbalanced_force = s.unbalanced_force();
          return s.relative_unbalanced_force;
        }
      } steps{*this};
      relaxation.relax(steps,
                       steps_per_thermal_step,
                       relaxation.control(time_step));
      if (predictor)
        relaxation.damaged_after_relaxation = n_damaged_or_broken_joints(model);
    }

    void
    TetrahedralSolver::quasi_static_step()
    {
      const double dt =
        relaxation.next_thermal_step(time,
                                     n_thermal_steps,
                                     next_output < output_times.size() ?
                                       std::optional<double>(
                                         output_times[next_output]) :
                                       std::nullopt);
      // the thermal step, re-run shorter from its start where too many
      // joints break in it or its relaxation does not converge:
      // QuasiStaticRelaxation::thermal_step(), written once for triangles
      // and tetrahedra, on this solver's joints, state and steps
      struct Step
      {
        TetrahedralSolver &s;
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
          s.relaxation.thermal_step_start =
            std::make_unique<CheckpointWriter>("thermal step", "");
          s.put_state(*s.relaxation.thermal_step_start);
        }
        void
        restore_thermal_step_start()
        {
          CheckpointReader in(*s.relaxation.thermal_step_start,
                              "start of the thermal step");
          s.get_state(in);
          in.finish();
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
          return true;
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

    namespace
    {
      /** The per-node, per-element and per-joint arrays of the state a
       *  thermal step is re-run from and a checkpoint holds, in the order
       *  they are written (const or not, as @p model). */
      template <typename Model>
      auto
      state_vectors(Model &model)
      {
        return std::array<decltype(&model.x), 11>{{&model.x,
                                                   &model.y,
                                                   &model.z,
                                                   &model.vx,
                                                   &model.vy,
                                                   &model.vz,
                                                   &model.thermal_stretch,
                                                   &model.stress,
                                                   &model.joint_damage,
                                                   &model.joint_break_time,
                                                   &model.node_joint_force}};
      }
    } // namespace

    void
    TetrahedralSolver::put_state(CheckpointWriter &out) const
    {
      out.put(time);
      out.put<std::uint64_t>(step_number);
      out.put(thermal_time);
      out.put<std::uint64_t>(n_thermal_steps);
      relaxation.save_step_control(out);
      for (const std::vector<double> *v : state_vectors(model))
        out.put(*v);
      out.put(model.joint_status);
      out.put(energies);
      out.put(owner_reaction);
      relaxation.save_relaxation(out);
      if (heat)
        heat->save(out);
      if (contact)
        contact->save(out);
    }

    void
    TetrahedralSolver::get_state(CheckpointReader &in)
    {
      std::uint64_t count = 0;
      in.get(time);
      in.get(count);
      step_number = count;
      in.get(thermal_time);
      in.get(count);
      n_thermal_steps = count;
      relaxation.load_step_control(in);
      for (std::vector<double> *v : state_vectors(model))
        in.get(*v, v->size());
      in.get(model.joint_status, model.n_joints);
      in.get(energies);
      in.get(owner_reaction, owner_reaction.size());
      relaxation.load_relaxation(in);
      if (heat)
        heat->load(in);
      if (contact)
        {
          contact->load(in, model.n_elements);
          contact->update_active_elements(model);
          for (unsigned int e = 0; e < model.n_elements; ++e)
            element_in_contact[e] = contact->has_pairs(e) ? 1 : 0;
        }
    }
  } // namespace discrete
} // namespace tmfdem
