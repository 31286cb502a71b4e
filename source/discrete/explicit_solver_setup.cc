/**
 * @file
 * Set-up of the explicit discrete solver: input checks, materials, element
 * stiffness (with the joint compliance compensation), joints, bodies and
 * conditions, contact, the stable step and the threads.
 */
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/explicit_solver.h>
#include <tmfdem/discrete/heterogeneity.h>
#include <tmfdem/discrete/joint_compliance.h>
#include <tmfdem/discrete/joints.h>
#include <tmfdem/discrete/stable_step.h>
#include <tmfdem/discrete/temperature_source.h>
#include <tmfdem/io/output_files.h>

namespace tmfdem
{
  namespace discrete
  {
    // --------------------------------------------------------------- input
    void
    ExplicitSolver::check_input()
    {
      if (input_checked)
        return;

      const auto &dm = parameters.get<DiscreteMechanicsParameters>();
      parameters.mechanics.check_dimension(2);
      if (dm.gravity.size() != 2)
        throw InputError("Discrete mechanics/Gravity has " +
                         std::to_string(dm.gravity.size()) +
                         " components: Mesh/Dimension = 2 takes g_x, g_y; "
                         "allowed are two.");
      for (const auto &body : parameters.get<DiscreteBodyParameters>().bodies)
        for (const auto &[entry, value] :
             {std::make_pair("Velocity z", body.velocity_z),
              std::make_pair("Initial velocity z", body.initial_velocity_z)})
          if (value != "0")
            throw InputError(body.name + "/" + entry + " = " + value +
                             ": Mesh/Dimension = 2 has no z component; "
                             "allowed is 0.");
      idealisation  = parameters.mechanics.idealisation; // one enum
      softening_law = dm.softening_law;

      build_discrete_mesh(parameters,
                          communicator,
                          triangulation,
                          dof_handler,
                          fe,
                          model);

      setup_materials();
      drivers.setup_bodies(parameters, model);
      drivers.setup_boundary_conditions(parameters,
                                        model,
                                        imposed_motion_clock());
      setup_joint_constants(parameters, softening_law, model);
      model.expansion_factor = random_expansion_factors(dm, model);
      setup_element_stiffness();
      setup_contact();
      // this rank's triangles; ghosts of the joints until the first search
      partition.setup(communicator, model, chunk_size);
      partition.build_ghost_plan(model, contact.pairs());
      compute_stable_time_step();

      const double requested = dm.time_step;
      if (requested > stable_time_step)
        throw InputError(
          "Discrete mechanics/Time step = " + Utilities::to_string(requested) +
          " s exceeds the stable step " +
          Utilities::to_string(stable_time_step) +
          " s of this mesh, penalties and damping; allowed is at most the "
          "stable step (or 0 for Safety factor x stable step).");
      time_step =
        requested > 0. ? requested : dm.safety_factor * stable_time_step;
      time = parameters.time.start_time;
      if (with_heat)
        {
          heat = create_temperature_source(
            parameters.get<DiscreteHeatParameters>().temperature_source,
            parameters,
            model,
            communicator);
          // each rank advances the temperatures of its own triangles
          // (discrete heat): its pairs from the contact search, its ghosts
          // from the plan. Without contact mechanics but with contact heat,
          // the heat's own search needs every triangle's position: the
          // heat then runs replicated on the whole state (partition.h)
          heat_distributed =
            (contact.enabled() ||
             parameters.get<DiscreteHeatParameters>().contact_conductance <=
               0.) &&
            heat->distribute(partition) && partition.distributed();
          heat->initialise(time);
          // contact heat takes its candidates from the contact search: on
          // several ranks each rank's pairs, or all of them (replicated)
          if (contact.enabled())
            heat->share_contact_candidates(heat_distributed ?
                                             &contact.pairs() :
                                             &contact.all_pairs(partition));
          const unsigned int n = parameters.get<DiscreteHeatParameters>()
                                   .mechanical_steps_per_thermal_step;
          quasi_static = parameters.get<DiscreteHeatParameters>().coupling ==
                         DiscreteHeatParameters::Coupling::quasi_static;
          const double ramp =
            parameters.get<DiscreteMechanicsParameters>().gravity_ramp_time;
          if (quasi_static && ramp > 0.)
            throw InputError(
              "Discrete mechanics/Gravity ramp time = " + std::to_string(ramp) +
              " s: a gravity ramp is for dynamic runs; with Discrete "
              "heat/Coupling = quasi-static every relaxation finds the "
              "equilibrium under full gravity. Set it to 0.");
          if (n > 0)
            steps_per_thermal_step = n;
          else if (quasi_static)
            steps_per_thermal_step = 2000;
          else if (heat->implicit())
            steps_per_thermal_step =
              std::max(1.,
                       std::floor(parameters.time.time_step / time_step + 0.5));
          else
            steps_per_thermal_step = std::max(
              1.,
              std::floor(
                parameters.get<DiscreteHeatParameters>().safety_factor *
                heat->stable_time_step() / time_step));
          const double thermal_step = quasi_static ?
                                        parameters.time.time_step :
                                        steps_per_thermal_step * time_step;
          if (!heat->implicit() && thermal_step > heat->stable_time_step())
            throw InputError(
              "Discrete heat/Mechanical steps per thermal step = " +
              std::to_string(steps_per_thermal_step) +
              " makes the thermal step " + Utilities::to_string(thermal_step) +
              " s, above the stable explicit thermal step " +
              Utilities::to_string(heat->stable_time_step()) +
              " s; allowed is at most " +
              std::to_string(static_cast<unsigned int>(
                heat->stable_time_step() / time_step)) +
              ", or 0 (automatic), or implicit heat.");
          thermal_time = time;
          if (quasi_static)
            {
              // an unloaded body relaxes at once (strains below 1e-10)
              double EA = 0.;
              for (unsigned int e = 0; e < model.n_elements; ++e)
                EA += parameters.materials[model.material[e]].youngs_modulus *
                      model.reference_area[e];
              relaxation.unloaded_energy = 1e-20 * EA;
              // motions imposed in thermal time are ramped in over the
              // first relaxation steps of each thermal step
              relaxation.set_ramp(drivers.imposes_motion(),
                                  steps_per_thermal_step,
                                  "velocities or displacements");
            }
          // the stress-free temperature of each element
          const Vector<double> &T = heat->temperature();
          reference_temperature.resize(model.n_elements);
          for (unsigned int e = 0; e < model.n_elements; ++e)
            reference_temperature[e] =
              parameters.initial.stress_free ?
                (T[3 * e] + T[3 * e + 1] + T[3 * e + 2]) / 3. :
                parameters.materials[model.material[e]].reference_temperature;
          update_thermal_stretch();
        }
      if (!(parameters.time.end_time > time))
        throw InputError("Time stepping/End time must be later than Start "
                         "time for the discrete layer.");
      const double n_steps = (parameters.time.end_time - time) / time_step;
      const bool   quasi_static_run =
        with_heat && parameters.get<DiscreteHeatParameters>().coupling ==
                       DiscreteHeatParameters::Coupling::quasi_static;
      // explicit steps are all of one length and the run stops within half
      // of one of End time: a shorter span computes nothing
      if (!quasi_static_run && n_steps < 1.)
        throw InputError(
          "Time stepping/End time - Start time = " +
          Utilities::to_string(parameters.time.end_time - time) +
          " s is shorter than one explicit step of " +
          Utilities::to_string(time_step) +
          " s (Discrete mechanics/Time step, or Safety factor x the stable "
          "step): no step would be computed. Allowed is an End time at "
          "least one step after Start time.");
      if (n_steps > 1e10 && !quasi_static_run)
        throw InputError(
          "Time stepping/End time: " + Utilities::to_string(n_steps) +
          " explicit steps of " + Utilities::to_string(time_step) +
          " s; allowed are at most 1e10.");

      // threads: Discrete mechanics/Threads, capped at the cores this
      // process may use (include/tmfdem/base/threads.h)
      threads_available = core_share(communicator).cores_per_rank;
      threads_requested = dm.threads;
      n_threads         = dm.threads > 0 ? dm.threads : threads_available;
      if (n_threads > threads_available && !dm.allow_oversubscription)
        {
          std::cerr << "[tmfdem] Discrete mechanics/Threads = " << n_threads
                    << " exceeds the " << threads_available
                    << " core(s) this process may use: running "
                    << threads_available
                    << " (Allow oversubscription = true runs them all)\n";
          n_threads = threads_available;
        }
      if (n_threads > thread_limit())
        set_thread_limit(n_threads);
      threads_used = measure_concurrency(arena_for(n_threads));
      vector_instructions =
        dm.vector_instructions_auto ?
          vector_instructions_for_mesh(dm.vector_instructions,
                                       partition.end() - partition.begin()) :
          dm.vector_instructions;
      if (heat)
        heat->set_threads(n_threads);

      locate_monitors(parameters.monitors, model, probe_samples, line_samples);
      // bodies that overlap at the start: refused (InputError)
      if (contact.enabled())
        check_contact_overlap(true);
      input_checked = true;
    }

    void
    ExplicitSolver::setup_materials()
    {
      const double mass_scaling =
        parameters.get<DiscreteMechanicsParameters>().mass_scaling_factor;
      solid.assign(256, SolidMaterial());
      viscosity.assign(model.n_elements, 0.);
      std::vector<bool> used(256, false);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        used[model.material[e]] = true;
      for (unsigned int id = 0; id < 256; ++id)
        if (used[id])
          {
            const MaterialProperties &m = parameters.materials[id];
            solid[id].lame =
              lame_constants(m.youngs_modulus, m.poisson_ratio, idealisation);
            solid[id].density = m.density;
          }
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          const MaterialProperties &m = parameters.materials[model.material[e]];
          // the inertia of the run: f rho A / 3 (f = 1: rho A / 3, bit for
          // bit)
          const double node_mass =
            mass_scaling * m.density * model.reference_area[e] / 3.;
          for (unsigned int k = 0; k < 3; ++k)
            model.mass[3 * e + k] = node_mass;
        }
    }

    void
    ExplicitSolver::setup_element_stiffness()
    {
      const auto &dm = parameters.get<DiscreteMechanicsParameters>();
      element_lame.resize(model.n_elements);
      const bool anisotropic = dm.joint_compliance_compensation &&
                               dm.anisotropic_joint_compliance_compensation;
      element_anisotropy.assign(anisotropic ? 6 * model.n_elements : 0, 0.);
      element_stiffness_bound.assign(anisotropic ? model.n_elements : 0, 1.);
      unsigned int n_capped  = 0;
      double       max_share = 0.;
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          const std::array<double, 3> x = {{model.x_ref[3 * e],
                                            model.x_ref[3 * e + 1],
                                            model.x_ref[3 * e + 2]}};
          const std::array<double, 3> y = {{model.y_ref[3 * e],
                                            model.y_ref[3 * e + 1],
                                            model.y_ref[3 * e + 2]}};
          element_lame[e]               = solid[model.material[e]].lame;
          if (dm.joint_compliance_compensation)
            {
              // the penalties of the element's intact joints (p = k L)
              std::array<double, 3> pn = {{0., 0., 0.}}, pt = {{0., 0., 0.}};
              for (unsigned int k = 0; k < 3; ++k)
                {
                  const int code = model.edge_joint[3 * e + k];
                  if (code < 0 ||
                      model.joint_status[code / 2] != JointStatus::intact)
                    continue;
                  const JointConstants &jc = model.joint_constants[code / 2];
                  const double          L  = model.joint_length[code / 2];
                  pn[k]                    = jc.normal_stiffness * L;
                  pt[k]                    = jc.tangential_stiffness * L;
                }
              const CompensatedElement c =
                compensate_joint_compliance(x,
                                            y,
                                            element_lame[e],
                                            pn,
                                            pt,
                                            max_compensated_share,
                                            anisotropic);
              element_lame[e] = c.lame;
              if (anisotropic)
                {
                  std::copy_n(c.anisotropy.begin(),
                              anisotropy_size<2>,
                              &element_anisotropy[6 * e]);
                  element_stiffness_bound[e] = c.stiffness_bound_factor;
                }
              max_share = std::max(max_share, c.share);
              n_capped += c.capped ? 1 : 0;
            }
          // Damping ratio = zeta of the element's highest free mode
          // (stable_step.h): eta = ratio / zeta per unit viscosity
          const double ratio = dm.damping_ratio;
          viscosity[e] =
            ratio > 0. ?
              ratio / highest_mode_damping_per_viscosity(x,
                                                         y,
                                                         element_lame[e],
                                                         model.mass[3 * e]) :
              0.;
        }
      compensation_capped = n_capped;
      compensation_share  = max_share;
      if (n_capped > 0 && Utilities::MPI::this_mpi_process(communicator) == 0)
        std::cerr << "tmfdem: warning: Discrete mechanics/Joint compliance "
                     "compensation: the joints of "
                  << n_capped << " of " << model.n_elements
                  << " triangles take more than "
                  << 100. * max_compensated_share
                  << " % of the material's compliance (largest "
                  << 100. * max_share
                  << " %); their stiffening is capped there and the body is "
                     "softer than E. Larger joint penalty factors or a "
                     "mesh without slivers avoid it."
                  << std::endl;
    }

    void
    ExplicitSolver::setup_contact()
    {
      const auto &dm = parameters.get<DiscreteMechanicsParameters>();
      // penalties from the stiffest material of the mesh
      double E_max = 0.;
      for (unsigned int e = 0; e < model.n_elements; ++e)
        E_max =
          std::max(E_max,
                   parameters.materials[model.material[e]].youngs_modulus);
      // buffer: a quarter of the smallest edge or element size by default
      double min_h = 1e300;
      for (unsigned int j = 0; j < model.n_joints; ++j)
        min_h = std::min(min_h, model.joint_length[j]);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        min_h = std::min(min_h, std::sqrt(2. * model.reference_area[e]));
      contact.setup(make_contact_settings(dm, E_max, min_h),
                    drivers.rigid_groups(model));
    }

    ElementStepInput
    ExplicitSolver::element_step_input(const unsigned int e,
                                       const bool         deformed) const
    {
      ElementStepInput   in;
      const unsigned int n0 = 3 * e;
      const auto        &X  = deformed ? model.x : model.x_ref;
      const auto        &Y  = deformed ? model.y : model.y_ref;
      for (unsigned int k = 0; k < 3; ++k)
        {
          in.x[k] = X[n0 + k];
          in.y[k] = Y[n0 + k];
          // every intact joint the element's nodes belong to
          const int code = model.edge_joint[n0 + k];
          if (code >= 0 && model.joint_status[code / 2] == JointStatus::intact)
            {
              const JointConstants &jc = model.joint_constants[code / 2];
              in.edge_joint_normal_stiffness[k]     = jc.normal_stiffness;
              in.edge_joint_tangential_stiffness[k] = jc.tangential_stiffness;
            }
        }
      in.lame = element_lame[e];
      if (!element_stiffness_bound.empty())
        {
          // C_e <= f C(lame): the isotropic element f times stiffer bounds it
          in.lame.lambda *= element_stiffness_bound[e];
          in.lame.mu *= element_stiffness_bound[e];
        }
      in.viscosity = viscosity[e];
      in.node_mass = model.mass[n0];
      // the contact law's bound (contact_law.h); 0 without contact
      in.node_contact_stiffness = contact.node_stiffness_bound();
      return in;
    }

    void
    ExplicitSolver::compute_stable_time_step()
    {
      double dt = std::numeric_limits<double>::infinity();
      for (unsigned int e = 0; e < model.n_elements; ++e)
        dt = std::min(dt, critical_time_step(element_step_input(e, false)));
      stable_time_step = dt;
    }

    ImposedMotionClock
    ExplicitSolver::imposed_motion_clock() const
    {
      // quasi-static coupling: the clock is the thermal time, which does not
      // move while the mechanics relaxes: velocities at the middle of the
      // thermal step (scaled to spread v dt_thermal over the ramp),
      // displacements reached at the end of the ramp
      ImposedMotionClock clock;
      clock.velocity_time     = quasi_static ?
                                  time - 0.5 * relaxation.current_thermal_step :
                                  time + 0.5 * time_step;
      clock.displacement_time = quasi_static ? time : time + time_step;
      clock.traction_time     = time;
      clock.velocity_scale =
        quasi_static ? relaxation.imposed_velocity_scale(time_step) : 1.;
      clock.steps_to_target =
        quasi_static ? relaxation.steps_to_ramp_end() : 1.;
      clock.time_step = time_step;
      return clock;
    }
  } // namespace discrete
} // namespace tmfdem
