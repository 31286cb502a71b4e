#include <deal.II/base/utilities.h>
#include <deal.II/dofs/dof_handler.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <random>
#include <set>
#include <sstream>
#include <sys/resource.h>
#include <thread>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/contact_heat.h>
#include <tmfdem/discrete/discrete_mesh.h>
#include <tmfdem/discrete/discrete_output.h>
#include <tmfdem/discrete/explicit_solver.h>
#include <tmfdem/discrete/joint_compliance.h>
#include <tmfdem/discrete/stable_step.h>
#include <tmfdem/discrete/stress_recovery.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/output_files.h>
#include <tmfdem/mesh/mesh_checks.h>
#include <tmfdem/mesh/mesh_generator.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      const bool registered = register_simulation(
        "discrete mechanics",
        "explicit FDEM dynamics: finite-strain triangles, cohesive joints, "
        "contact with friction (no heat)",
        [](const Parameters &parameters, MPI_Comm communicator) {
          return std::make_unique<ExplicitSolver>(parameters, communicator);
        });
      const bool registered_thermal = register_simulation(
        "discrete thermo-mechanics",
        "the discrete layer with heat: conduction, joint exchange and contact "
        "heat drive F = F_T F_e; fracture and contact reshape the heat flow "
        "(multi-rate: one thermal step every n mechanical steps)",
        [](const Parameters &parameters, MPI_Comm communicator) {
          return std::make_unique<ExplicitSolver>(parameters,
                                                  communicator,
                                                  true);
        });
    } // namespace

    double
    EnergyBalance::scale() const
    {
      return std::max({std::abs(initial_kinetic + initial_strain),
                       std::abs(external_work),
                       std::abs(kinetic),
                       std::abs(strain),
                       std::abs(joint_work),
                       std::abs(contact_work),
                       std::abs(viscous_dissipation),
                       std::abs(relaxation_work),
                       1e-9}); // [J/m]: below this nothing happened
    }

    ExplicitSolver::ExplicitSolver(const Parameters &parameters,
                                   MPI_Comm          communicator,
                                   const bool        with_heat)
      : parameters(parameters)
      , communicator(communicator)
      , fe(1)
      , with_heat(with_heat)
    {}

    ExplicitSolver::~ExplicitSolver() = default;

    // --------------------------------------------------------------- input
    void
    ExplicitSolver::check_input()
    {
      if (input_checked)
        return;

      const auto &dm = parameters.discrete_mechanics;
      idealisation   = parameters.mechanics.idealisation ==
                         MechanicsParameters::Idealisation::plane_strain ?
                         Idealisation::plane_strain :
                         Idealisation::plane_stress;
      for (const auto &[name, law] : softening_law_registry())
        if (name == dm.softening_law)
          softening_law = law;

      build_discrete_mesh(parameters,
                          communicator,
                          triangulation,
                          dof_handler,
                          fe,
                          model);

      setup_materials();
      setup_bodies();
      setup_boundary_conditions();
      setup_joints();
      setup_element_stiffness();
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
            parameters.discrete_heat.temperature_source,
            parameters,
            model,
            communicator);
          heat->initialise(time);
          const unsigned int n =
            parameters.discrete_heat.mechanical_steps_per_thermal_step;
          quasi_static = parameters.discrete_heat.coupling == "quasi-static";
          if (n > 0)
            steps_per_thermal_step = n;
          else if (quasi_static)
            steps_per_thermal_step = 2000;
          else if (heat->implicit())
            steps_per_thermal_step =
              std::max(1.,
                       std::floor(parameters.time.time_step / time_step + 0.5));
          else
            steps_per_thermal_step =
              std::max(1.,
                       std::floor(parameters.discrete_heat.safety_factor *
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
              // motions imposed in thermal time are ramped in over the
              // first relaxation steps of each thermal step
              using Type   = MechanicalBoundaryCondition::Type;
              bool imposed = false;
              for (const auto &c : parameters.mechanical_boundary.conditions)
                imposed |=
                  c.type == Type::velocity || c.type == Type::displacement;
              for (const auto motion : body_motion)
                imposed |= motion == DiscreteBody::Motion::velocity;
              quasi_static_ramp_steps = imposed ? 100 : 0;
              if (imposed &&
                  steps_per_thermal_step <= 2 * quasi_static_ramp_steps)
                throw InputError(
                  "Discrete heat/Mechanical steps per thermal step = " +
                  std::to_string(steps_per_thermal_step) +
                  " is too few for quasi-static coupling with imposed "
                  "velocities or displacements, which are ramped in over " +
                  std::to_string(quasi_static_ramp_steps) +
                  " relaxation steps; allowed is more than " +
                  std::to_string(2 * quasi_static_ramp_steps) +
                  " (or 0: automatic).");
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
        with_heat && parameters.discrete_heat.coupling == "quasi-static";
      if (n_steps > 1e10 && !quasi_static_run)
        throw InputError(
          "Time stepping/End time: " + Utilities::to_string(n_steps) +
          " explicit steps of " + Utilities::to_string(time_step) +
          " s; allowed are at most 1e10.");

      // contact
      contact_enabled = dm.contact;
      double min_h    = 1e300;
      for (unsigned int j = 0; j < model.n_joints; ++j)
        min_h = std::min(min_h, model.joint_length[j]);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        min_h = std::min(min_h, std::sqrt(2. * model.reference_area[e]));
      contact_buffer =
        dm.contact_buffer > 0. ? dm.contact_buffer : 0.25 * min_h;
      friction_coefficient = dm.friction_coefficient;

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
      if (heat)
        heat->set_threads(n_threads);

      locate_monitors(parameters.monitors, model, probe_samples, line_samples);
      input_checked = true;
    }

    void
    ExplicitSolver::setup_materials()
    {
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
          const double node_mass = m.density * model.reference_area[e] / 3.;
          for (unsigned int k = 0; k < 3; ++k)
            model.mass[3 * e + k] = node_mass;
        }
    }

    void
    ExplicitSolver::setup_element_stiffness()
    {
      const auto &dm = parameters.discrete_mechanics;
      element_lame.resize(model.n_elements);
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
                                            max_compensated_share);
              element_lame[e] = c.lame;
              max_share       = std::max(max_share, c.share);
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
    ExplicitSolver::setup_joints()
    {
      const auto     &dm = parameters.discrete_mechanics;
      std::mt19937_64 generator(dm.random_seed);
      for (unsigned int j = 0; j < model.n_joints; ++j)
        {
          const unsigned int        ea = model.joint_elements[2 * j];
          const unsigned int        eb = model.joint_elements[2 * j + 1];
          const MaterialProperties &ma =
            parameters.materials[model.material[ea]];
          const MaterialProperties &mb =
            parameters.materials[model.material[eb]];
          // interfaces between materials take the weaker of both
          double       ft  = std::min(ma.tensile_strength, mb.tensile_strength);
          double       coh = std::min(ma.cohesion, mb.cohesion);
          const double phi = std::min(ma.friction_angle, mb.friction_angle);
          const double GI =
            std::min(ma.fracture_energy_I, mb.fracture_energy_I);
          const double GII =
            std::min(ma.fracture_energy_II, mb.fracture_energy_II);
          const double E = std::max(ma.youngs_modulus, mb.youngs_modulus);
          if (dm.heterogeneity != "none")
            {
              double factor = 1.;
              if (dm.heterogeneity == "Weibull")
                {
                  // Weibull with mean 1: scale = 1 / Gamma(1 + 1/m)
                  const double                      m = dm.weibull_modulus;
                  std::weibull_distribution<double> weibull(
                    m,
                    1. / std::tgamma(1. + 1. / m));
                  factor = weibull(generator);
                }
              else
                {
                  std::normal_distribution<double> normal(
                    1.,
                    dm.coefficient_of_variation);
                  factor = std::max(0.01, normal(generator));
                }
              ft *= factor;
              coh *= factor;
            }
          const bool ok =
            make_joint_constants(ft,
                                 coh,
                                 phi,
                                 GI,
                                 GII,
                                 dm.joint_normal_penalty_factor * E,
                                 dm.joint_tangential_penalty_factor * E,
                                 model.joint_length[j],
                                 softening_law,
                                 model.joint_constants[j]);
          if (!ok)
            {
              const double h = model.joint_length[j];
              const double stored_I =
                4. / 3. * ft * ft * h / (dm.joint_normal_penalty_factor * E);
              const double stored_II = 4. / 3. * coh * coh * h /
                                       (dm.joint_tangential_penalty_factor * E);
              const bool mode_I = GI <= stored_I;
              throw InputError(
                "joint " + std::to_string(j) + " between materials " +
                std::to_string(model.material[ea]) + " and " +
                std::to_string(model.material[eb]) + " (length " +
                Utilities::to_string(h) + " m): Mode " + (mode_I ? "I" : "II") +
                " fracture energy " + Utilities::to_string(mode_I ? GI : GII) +
                " J/m^2 is below the work stored before the peak, 4 f^2 h / "
                "(3 p) = " +
                Utilities::to_string(mode_I ? stored_I : stored_II) +
                " J/m^2; allowed are larger fracture energies or larger "
                "joint penalty factors (Discrete mechanics).");
            }
        }
      double E_max = 0.;
      for (unsigned int e = 0; e < model.n_elements; ++e)
        E_max =
          std::max(E_max,
                   parameters.materials[model.material[e]].youngs_modulus);
      contact_penalty            = dm.contact_penalty_factor * E_max;
      contact_tangential_penalty = dm.contact_tangential_penalty_factor * E_max;
    }

    void
    ExplicitSolver::setup_bodies()
    {
      const auto &bodies = parameters.discrete_bodies.bodies;
      body_motion.clear();
      body_velocity.clear();
      for (const auto &b : bodies)
        {
          body_motion.push_back(b.motion);
          body_velocity.push_back(
            make_expression_function(b.velocity_x, b.name + "/Velocity x"));
          body_velocity.push_back(
            make_expression_function(b.velocity_y, b.name + "/Velocity y"));
        }
      body_velocity_now.assign(bodies.size(), {{0., 0.}});
      body_reaction.assign(bodies.size(), {{0., 0.}});
      std::vector<unsigned char> body_of_material(256, 255);
      for (unsigned int b = 0; b < bodies.size(); ++b)
        for (const auto id : bodies[b].material_ids)
          body_of_material[id] = b;
      std::vector<bool> body_has_cells(bodies.size(), false);
      node_body.assign(model.n_nodes, 255);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          model.body[e] = body_of_material[model.material[e]];
          if (model.body[e] != 255)
            body_has_cells[model.body[e]] = true;
          for (unsigned int k = 0; k < 3; ++k)
            node_body[3 * e + k] = model.body[e];
        }
      for (unsigned int b = 0; b < bodies.size(); ++b)
        if (!body_has_cells[b])
          throw InputError(bodies[b].name +
                           "/Material ids: no cell of the mesh has these "
                           "material ids.");
      // initial velocities
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          auto vx0 =
            make_expression_function(bodies[b].initial_velocity_x,
                                     bodies[b].name + "/Initial velocity x");
          auto vy0 =
            make_expression_function(bodies[b].initial_velocity_y,
                                     bodies[b].name + "/Initial velocity y");
          for (unsigned int n = 0; n < model.n_nodes; ++n)
            if (node_body[n] == b &&
                bodies[b].motion == DiscreteBody::Motion::free)
              {
                const Point<2> p(model.x_ref[n], model.y_ref[n]);
                model.vx[n] = vx0->value(p);
                model.vy[n] = vy0->value(p);
              }
        }
      gravity = {{parameters.discrete_mechanics.gravity[0],
                  parameters.discrete_mechanics.gravity[1]}};
    }

    void
    ExplicitSolver::setup_boundary_conditions()
    {
      conditions.clear();
      node_conditions.clear();
      node_condition_slot.assign(model.n_nodes, -1);
      using Type = MechanicalBoundaryCondition::Type;
      std::vector<int> condition_of_id(256, -1);
      for (const auto &c : parameters.mechanical_boundary.conditions)
        {
          ConditionFunctions f;
          f.type              = c.type;
          const char *axis[2] = {" x", " y"};
          for (unsigned int d = 0; d < 2; ++d)
            {
              const std::string expression =
                c.type == Type::displacement ? c.displacement[d] :
                c.type == Type::traction     ? c.traction[d] :
                                               c.velocity[d];
              const std::string entry =
                c.name +
                (c.type == Type::displacement ? "/Displacement" :
                 c.type == Type::traction     ? "/Traction" :
                                                "/Velocity") +
                axis[d];
              f.value[d] = make_expression_function(expression, entry);
              // a function that names t is evaluated every step
              for (std::size_t i = 0; i < expression.size(); ++i)
                if (expression[i] == 't' &&
                    (i == 0 || !std::isalnum(expression[i - 1])) &&
                    (i + 1 == expression.size() ||
                     !std::isalnum(expression[i + 1])))
                  f.time_dependent[d] = true;
            }
          model.check_boundary_ids(c.name + "/Boundary ids", c.boundary_ids);
          for (const auto id : c.boundary_ids)
            if (id < condition_of_id.size())
              condition_of_id[id] = conditions.size();
          conditions.push_back(std::move(f));
        }
      // nodes on boundary edges with a condition (free bodies only; fixed
      // and driven bodies move as their body says)
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int k = 0; k < 3; ++k)
          {
            const types::boundary_id id = model.edge_boundary[3 * e + k];
            if (id == numbers::internal_face_boundary_id ||
                id >= condition_of_id.size() || condition_of_id[id] < 0)
              continue;
            const unsigned int c       = condition_of_id[id];
            const unsigned int ends[2] = {3 * e + k, 3 * e + (k + 1) % 3};
            const double       length =
              std::hypot(model.x_ref[ends[1]] - model.x_ref[ends[0]],
                         model.y_ref[ends[1]] - model.y_ref[ends[0]]);
            for (const unsigned int node : ends)
              {
                if (node_body[node] != 255 &&
                    body_motion[node_body[node]] != DiscreteBody::Motion::free)
                  continue;
                if (node_condition_slot[node] < 0)
                  {
                    NodeCondition nc;
                    nc.node          = node;
                    nc.condition     = c;
                    nc.prescribed[0] = false;
                    nc.prescribed[1] = false;
                    nc.velocity[0] = nc.velocity[1] = 0.;
                    nc.force[0] = nc.force[1] = 0.;
                    nc.traction_length        = 0.;
                    nc.traction_condition     = -1;
                    node_condition_slot[node] = node_conditions.size();
                    node_conditions.push_back(nc);
                  }
                NodeCondition &nc = node_conditions[node_condition_slot[node]];
                const Type     type = conditions[c].type;
                if (type == Type::traction)
                  {
                    nc.traction_length += 0.5 * length;
                    nc.traction_condition = c;
                  }
                else
                  {
                    // a kinematic condition wins over a traction at corners
                    nc.condition     = c;
                    nc.prescribed[0] = type != Type::roller_y;
                    nc.prescribed[1] = type != Type::roller_x;
                  }
              }
          }
      boundary_conditions_change = false;
      for (const ConditionFunctions &f : conditions)
        boundary_conditions_change |= f.type == Type::displacement ||
                                      f.time_dependent[0] ||
                                      f.time_dependent[1];
      evaluate_boundary_conditions();
    }

    void
    ExplicitSolver::evaluate_boundary_conditions()
    {
      using Type = MechanicalBoundaryCondition::Type;
      // quasi-static coupling: the clock is the thermal time, which does not
      // move while the mechanics relaxes: velocities at the middle of the
      // thermal step (scaled to spread v dt_thermal over the ramp),
      // displacements reached at the end of the ramp
      const double t_mid  = quasi_static ? time - 0.5 * current_thermal_step :
                                           time + 0.5 * time_step;
      const double t_next = quasi_static ? time : time + time_step;
      const double scale  = imposed_velocity_scale();
      const double steps_to_target =
        quasi_static && relaxation_step < quasi_static_ramp_steps ?
          quasi_static_ramp_steps - relaxation_step :
          1.;
      for (ConditionFunctions &f : conditions)
        for (unsigned int d = 0; d < 2; ++d)
          f.value[d]->set_time(f.type == Type::displacement ? t_next :
                               f.type == Type::velocity     ? t_mid :
                                                              time);
      for (NodeCondition &nc : node_conditions)
        {
          const unsigned int  n = nc.node;
          const Point<2>      p(model.x_ref[n], model.y_ref[n]);
          ConditionFunctions &f = conditions[nc.condition];
          for (unsigned int d = 0; d < 2; ++d)
            {
              if (nc.prescribed[d])
                {
                  if (f.type == Type::velocity)
                    nc.velocity[d] = scale * f.value[d]->value(p);
                  else if (f.type == Type::displacement)
                    {
                      // reach X + u(t + dt) at the end of the step
                      const double target =
                        (d == 0 ? model.x_ref[n] : model.y_ref[n]) +
                        f.value[d]->value(p);
                      const double now = d == 0 ? model.x[n] : model.y[n];
                      nc.velocity[d] =
                        time_step > 0. ?
                          (target - now) / (steps_to_target * time_step) :
                          0.;
                    }
                  else
                    nc.velocity[d] = 0.;
                }
            }
        }
      // tractions: conditions of traction type, per node share of length
      for (NodeCondition &nc : node_conditions)
        if (nc.traction_length > 0.)
          {
            const unsigned int  n = nc.node;
            const Point<2>      p(model.x_ref[n], model.y_ref[n]);
            ConditionFunctions &f = conditions[nc.traction_condition];
            nc.force[0]           = f.value[0]->value(p) * nc.traction_length;
            nc.force[1]           = f.value[1]->value(p) * nc.traction_length;
          }
    }

    void
    ExplicitSolver::update_thermal_stretch()
    {
      const Vector<double> &T      = heat->temperature();
      double                before = 0., after = 0.;
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          const MaterialProperties &m = parameters.materials[model.material[e]];
          const double dT = (T[3 * e] + T[3 * e + 1] + T[3 * e + 2]) / 3. -
                            reference_temperature[e];
          const double s_new = thermal_stretch(m.thermal_expansion,
                                               m.poisson_ratio,
                                               dT,
                                               idealisation);
          const double s_old = model.thermal_stretch[e];
          if (s_new == s_old)
            continue;
          const unsigned int n0     = 3 * e;
          const double      *ib     = &model.inverse_basis[4 * e];
          const Matrix2      F      = multiply(element_basis(model.x[n0],
                                                   model.y[n0],
                                                   model.x[n0 + 1],
                                                   model.y[n0 + 1],
                                                   model.x[n0 + 2],
                                                   model.y[n0 + 2]),
                                     Matrix2{ib[0], ib[1], ib[2], ib[3]});
          const auto         energy = [&](const double s) {
            return model.reference_area[e] * s * s *
                   strain_energy_density(
                     {F.a00 / s, F.a01 / s, F.a10 / s, F.a11 / s},
                     element_lame[e]);
          };
          before += energy(s_old);
          after += energy(s_new);
          model.thermal_stretch[e] = s_new;
        }
      balance.thermal_work += after - before;
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
      in.lame      = element_lame[e];
      in.viscosity = viscosity[e];
      in.node_mass = model.mass[n0];
      if (parameters.discrete_mechanics.contact)
        // a node pressed into a target of altitude ~ its edge feels about
        // 3 p_n per unit penetration (both pair directions) and at most p_t
        // of stick stiffness
        in.node_contact_stiffness =
          3. * contact_penalty + contact_tangential_penalty;
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

    // ------------------------------------------------------------- contact
    void
    ExplicitSolver::update_contact_candidates()
    {
      // active: elements with a free edge, and their intact neighbours
      std::vector<unsigned char> active(model.n_elements, 0);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int k = 0; k < 3; ++k)
          if (model.intact_neighbour(e, k) < 0)
            {
              active[e] = 1;
              break;
            }
      std::vector<unsigned char> with_neighbours = active;
      for (unsigned int e = 0; e < model.n_elements; ++e)
        if (active[e])
          for (unsigned int k = 0; k < 3; ++k)
            {
              const int n = model.intact_neighbour(e, k);
              if (n >= 0)
                with_neighbours[n] = 1;
            }
      active_elements.clear();
      for (unsigned int e = 0; e < model.n_elements; ++e)
        if (with_neighbours[e])
          active_elements.push_back(e);

      const auto excluded = [&](const unsigned int a, const unsigned int b) {
        if (model.body[a] == model.body[b] && model.body[a] != 255 &&
            body_motion[model.body[a]] != DiscreteBody::Motion::free)
          return true;
        return model.joined(a, b);
      };
      linked_cells.rebuild(model.x,
                           model.y,
                           active_elements,
                           contact_buffer,
                           excluded,
                           pairs,
                           arena_for(n_threads));
      index_contact_pairs();
      travel_since_search   = 0.;
      contact_search_needed = false;
      ++n_contact_searches;
    }

    void
    ExplicitSolver::index_contact_pairs()
    {
      pair_force.assign(12 * pairs.size(), 0.);
      pair_friction.assign(pairs.size(), 0.);
      element_pair_start.assign(model.n_elements + 1, 0);
      for (const auto &p : pairs)
        {
          ++element_pair_start[p.first + 1];
          ++element_pair_start[p.second + 1];
        }
      for (unsigned int e = 0; e < model.n_elements; ++e)
        element_pair_start[e + 1] += element_pair_start[e];
      element_pair_entries.resize(2 * pairs.size());
      std::vector<unsigned int> fill(element_pair_start.begin(),
                                     element_pair_start.end() - 1);
      for (unsigned int p = 0; p < pairs.size(); ++p)
        {
          element_pair_entries[fill[pairs[p].first]++]  = 2 * p;
          element_pair_entries[fill[pairs[p].second]++] = 2 * p + 1;
        }
    }

    void
    ExplicitSolver::compute_contact_forces()
    {
      if (pairs.empty())
        return;
      const double   p_n = contact_penalty, p_t = contact_tangential_penalty;
      const double   mu = friction_coefficient;
      const double   dt = time_step;
      DiscreteModel &m  = model;
      for_each_chunk(
        arena_for(n_threads),
        pairs.size(),
        256,
        [&](const std::size_t begin, const std::size_t end, const std::size_t) {
          for (std::size_t p = begin; p < end; ++p)
            {
              ContactPair &pair  = pairs[p];
              double      *force = &pair_force[12 * p];
              for (unsigned int i = 0; i < 12; ++i)
                force[i] = 0.;
              double dissipated = 0.;
              for (unsigned int direction = 0; direction < 2; ++direction)
                {
                  const unsigned int c =
                    direction == 0 ? pair.first : pair.second;
                  const unsigned int t =
                    direction == 0 ? pair.second : pair.first;
                  double       *fc = force + 6 * direction;
                  double       *ft = force + 6 * (1 - direction);
                  const double *tx = &m.x[3 * t], *ty = &m.y[3 * t];
                  for (unsigned int edge = 0; edge < 3; ++edge)
                    {
                      double            &slip = pair.slip[3 * direction + edge];
                      const unsigned int a    = 3 * c + edge,
                                         b    = 3 * c + (edge + 1) % 3;
                      EdgePotentialIntegrals I;
                      if (!edge_potential_integrals(m.x[a],
                                                    m.y[a],
                                                    m.x[b],
                                                    m.y[b],
                                                    tx,
                                                    ty,
                                                    I))
                        {
                          slip = 0.;
                          continue;
                        }
                      const double ex = m.x[b] - m.x[a], ey = m.y[b] - m.y[a];
                      const double L    = std::sqrt(ex * ex + ey * ey);
                      const double tx_u = ex / L, ty_u = ey / L;
                      const double nx = ty_u, ny = -tx_u; // outward of c
                      const double scale = p_n * L;
                      // normal: on c -p L int phi_t N n, reaction on t
                      const double fa       = scale * I.phi_start,
                                   fb       = scale * I.phi_end;
                      const unsigned int ka = edge, kb = (edge + 1) % 3;
                      fc[2 * ka] -= fa * nx;
                      fc[2 * ka + 1] -= fa * ny;
                      fc[2 * kb] -= fb * nx;
                      fc[2 * kb + 1] -= fb * ny;
                      for (unsigned int k = 0; k < 3; ++k)
                        {
                          ft[2 * k] += scale * I.phi_target[k] * nx;
                          ft[2 * k + 1] += scale * I.phi_target[k] * ny;
                        }
                      // Coulomb friction with elastic slip history
                      const double normal_force = fa + fb;
                      if (!(normal_force > 0.) || mu <= 0.)
                        {
                          slip = 0.;
                          continue;
                        }
                      const double total = I.total();
                      const double u     = I.phi_end / total;
                      const double lt[3] = {I.phi_target[0] / total,
                                            I.phi_target[1] / total,
                                            I.phi_target[2] / total};
                      const double vcx   = (1. - u) * m.vx[a] + u * m.vx[b];
                      const double vcy   = (1. - u) * m.vy[a] + u * m.vy[b];
                      double       vtx = 0., vty = 0.;
                      for (unsigned int k = 0; k < 3; ++k)
                        {
                          vtx += lt[k] * m.vx[3 * t + k];
                          vty += lt[k] * m.vy[3 * t + k];
                        }
                      const double rate =
                        (vcx - vtx) * tx_u + (vcy - vty) * ty_u;
                      const double trial      = slip + rate * dt;
                      const double stiffness  = p_t * I.clipped_length_fraction;
                      double       tangential = -stiffness * trial;
                      const double limit      = mu * normal_force;
                      double       new_slip   = trial;
                      if (std::abs(tangential) > limit)
                        {
                          tangential = trial > 0. ? -limit : limit;
                          new_slip   = -tangential / stiffness;
                          dissipated +=
                            limit * (std::abs(trial) - std::abs(new_slip));
                        }
                      slip = new_slip;
                      fc[2 * ka] += (1. - u) * tangential * tx_u;
                      fc[2 * ka + 1] += (1. - u) * tangential * ty_u;
                      fc[2 * kb] += u * tangential * tx_u;
                      fc[2 * kb + 1] += u * tangential * ty_u;
                      for (unsigned int k = 0; k < 3; ++k)
                        {
                          ft[2 * k] -= lt[k] * tangential * tx_u;
                          ft[2 * k + 1] -= lt[k] * tangential * ty_u;
                        }
                    }
                }
              pair_friction[p] = dissipated;
            }
        });
      // friction dissipation, summed in pair order
      double sum = 0.;
      for (const double d : pair_friction)
        sum += d;
      balance.friction_dissipation += sum;
    }

    // -------------------------------------------------------------- joints
    template <SofteningLaw law>
    void
    ExplicitSolver::compute_joint_forces_with()
    {
      DiscreteModel     &m              = model;
      const double       t              = time;
      std::vector<char> &broke_in_chunk = joint_chunk_broke;
      broke_in_chunk.assign((m.n_joints + chunk_size - 1) / chunk_size, 0);
      for_each_chunk(
        arena_for(n_threads),
        m.n_joints,
        chunk_size,
        [&](const std::size_t begin,
            const std::size_t end,
            const std::size_t c) {
          // Gauss points on the edge, parameter u in [0, 1]
          constexpr double g0 = 0.21132486540518713, g1 = 0.78867513459481287;
          for (std::size_t j = begin; j < end; ++j)
            {
              double *f = &m.joint_force[8 * j];
              if (m.joint_status[j] != JointStatus::intact)
                continue;
              const unsigned int *n   = &m.joint_nodes[4 * j];
              const double        d0x = m.x[n[2]] - m.x[n[0]];
              const double        d0y = m.y[n[2]] - m.y[n[0]];
              const double        d1x = m.x[n[3]] - m.x[n[1]];
              const double        d1y = m.y[n[3]] - m.y[n[1]];
              const double        ex =
                0.5 * (m.x[n[1]] + m.x[n[3]] - m.x[n[0]] - m.x[n[2]]);
              const double ey =
                0.5 * (m.y[n[1]] + m.y[n[3]] - m.y[n[0]] - m.y[n[2]]);
              const double          L  = std::sqrt(ex * ex + ey * ey);
              const double          tx = ex / L, ty = ey / L;
              const double          nx = ty, ny = -tx; // outward of element A
              const JointConstants &k    = m.joint_constants[j];
              double                fa0x = 0, fa0y = 0, fa1x = 0, fa1y = 0;
              double                last_do = 0., last_ds = 0.;
              for (unsigned int q = 0; q < 2; ++q)
                {
                  const double        u  = q == 0 ? g0 : g1;
                  const double        dx = (1. - u) * d0x + u * d1x;
                  const double        dy = (1. - u) * d0y + u * d1y;
                  const double        o  = dx * nx + dy * ny;
                  const double        s  = dx * tx + dy * ty;
                  const JointTraction tr =
                    cohesive_traction<law>(o, s, k, m.joint_damage[2 * j + q]);
                  last_do = std::max(last_do, tr.d_opening);
                  last_ds = std::max(last_ds, tr.d_slip);
                  // traction on A (pulls A toward B), weight L/2
                  const double w  = 0.5 * L;
                  const double px = w * (tr.normal * nx + tr.shear * tx);
                  const double py = w * (tr.normal * ny + tr.shear * ty);
                  fa0x += (1. - u) * px;
                  fa0y += (1. - u) * py;
                  fa1x += u * px;
                  fa1y += u * py;
                }
              if (m.joint_damage[2 * j] >= 1. &&
                  m.joint_damage[2 * j + 1] >= 1.)
                {
                  const double ratio =
                    last_do * last_do /
                    std::max(1e-300, last_do * last_do + last_ds * last_ds);
                  m.joint_status[j]     = ratio > 0.9 ? JointStatus::mode_I :
                                          ratio < 0.1 ? JointStatus::mode_II :
                                                        JointStatus::mixed;
                  m.joint_break_time[j] = t;
                  for (unsigned int i = 0; i < 8; ++i)
                    f[i] = 0.;
                  broke_in_chunk[c] = 1;
                  continue;
                }
              f[0] = fa0x;
              f[1] = fa0y;
              f[2] = fa1x;
              f[3] = fa1y;
              f[4] = -fa0x;
              f[5] = -fa0y;
              f[6] = -fa1x;
              f[7] = -fa1y;
            }
        });
      for (const char b : broke_in_chunk)
        if (b)
          {
            contact_search_needed = true;
          }
    }

    void
    ExplicitSolver::compute_joint_forces()
    {
      if (softening_law == SofteningLaw::linear)
        compute_joint_forces_with<SofteningLaw::linear>();
      else
        compute_joint_forces_with<SofteningLaw::munjiza>();
    }

    // ---------------------------------------------------- the fused update
    void
    ExplicitSolver::update_nodes()
    {
      DiscreteModel     &m        = model;
      const double       dt       = time_step;
      const unsigned int n_bodies = body_motion.size();
      const unsigned int stride  = n_sums + 2 * max_bodies + 2 * max_conditions;
      const std::size_t n_chunks = (m.n_elements + chunk_size - 1) / chunk_size;
      chunk_sums.assign(n_chunks * stride, 0.);
      const bool have_contact = !pairs.empty();
      // mass-proportional damping f_d = -c m v_avg, integrated exactly:
      // v_new = (a v_old + dt f / m) with a = (1 - c dt/2) / (1 + c dt/2)
      const double c_damp = parameters.discrete_mechanics.mass_damping;
      const double damp_a = (1. - 0.5 * c_damp * dt) / (1. + 0.5 * c_damp * dt);
      const double damp_b = dt / (1. + 0.5 * c_damp * dt);
      for_each_chunk(
        arena_for(n_threads),
        m.n_elements,
        chunk_size,
        [&](const std::size_t begin,
            const std::size_t end,
            const std::size_t c) {
          double *sums      = &chunk_sums[c * stride];
          double  w_elastic = 0., w_viscous = 0., w_joint = 0., w_contact = 0.,
                 w_external = 0., max_speed = 0.;
          // out-of-balance force (free components, no viscous part) and the
          // scale of the internal forces, both squared
          double unbalanced = 0., internal = 0., kinetic = 0.;
          // guards: first non-finite node and first inverted element
          double bad_node = -1., inverted = -1.;
          for (std::size_t e = begin; e < end; ++e)
            {
              const unsigned int n0 = 3 * e;
              const double      *X = &m.x[n0], *Y = &m.y[n0];
              const double      *VX = &m.vx[n0], *VY = &m.vy[n0];
              const double      *ib = &m.inverse_basis[4 * e];
              const Matrix2      Fi_inv{ib[0], ib[1], ib[2], ib[3]};
              const Matrix2      F =
                multiply(element_basis(X[0], Y[0], X[1], Y[1], X[2], Y[2]),
                         Fi_inv);
              if (!(F.a00 * F.a11 - F.a01 * F.a10 > 0.) && inverted < 0.)
                inverted = e;
              const double  s     = m.thermal_stretch[e];
              const double  inv_s = 1. / s;
              const Matrix2 Fe{F.a00 * inv_s,
                               F.a01 * inv_s,
                               F.a10 * inv_s,
                               F.a11 * inv_s};
              const Stress2 sigma = elastic_stress(Fe, element_lame[e]);
              // viscous stress 2 eta sym(dF/dt F^-1), only where eta > 0
              const double eta = viscosity[e];
              Stress2      sigma_v;
              double       f_el[6], f_v[6] = {0., 0., 0., 0., 0., 0.};
              nodal_forces(sigma, X[0], Y[0], X[1], Y[1], X[2], Y[2], f_el);
              if (eta > 0.)
                {
                  const Matrix2 Fdot = multiply(
                    element_basis(VX[0], VY[0], VX[1], VY[1], VX[2], VY[2]),
                    Fi_inv);
                  const Matrix2 L = multiply(Fdot, inverse(F));
                  sigma_v         = {2. * eta * L.a00,
                                     2. * eta * L.a11,
                                     eta * (L.a01 + L.a10)};
                  nodal_forces(sigma_v,
                               X[0],
                               Y[0],
                               X[1],
                               Y[1],
                               X[2],
                               Y[2],
                               f_v);
                }
              m.stress[3 * e]     = sigma.xx + sigma_v.xx;
              m.stress[3 * e + 1] = sigma.yy + sigma_v.yy;
              m.stress[3 * e + 2] = sigma.xy + sigma_v.xy;

              double f_contact[6] = {0., 0., 0., 0., 0., 0.};
              if (have_contact)
                add_contact_forces(e, f_contact);
              for (unsigned int k = 0; k < 3; ++k)
                {
                  const unsigned int node = n0 + k;
                  // joints: node k starts edge k and ends edge k+2
                  double    fjx = 0., fjy = 0.;
                  const int start_code = m.edge_joint[n0 + k];
                  if (start_code >= 0)
                    {
                      const double *jf = &m.joint_force[8 * (start_code / 2)];
                      const unsigned int slot = start_code % 2 == 0 ? 0 : 3;
                      fjx += jf[2 * slot];
                      fjy += jf[2 * slot + 1];
                    }
                  const int end_code = m.edge_joint[n0 + (k + 2) % 3];
                  if (end_code >= 0)
                    {
                      const double *jf = &m.joint_force[8 * (end_code / 2)];
                      const unsigned int slot = end_code % 2 == 0 ? 1 : 2;
                      fjx += jf[2 * slot];
                      fjy += jf[2 * slot + 1];
                    }
                  const double mass = m.mass[node];
                  const double fgx = mass * gravity[0], fgy = mass * gravity[1];
                  const double fx =
                    f_el[2 * k] + f_v[2 * k] + fjx + f_contact[2 * k] + fgx;
                  const double fy = f_el[2 * k + 1] + f_v[2 * k + 1] + fjy +
                                    f_contact[2 * k + 1] + fgy;
                  const double        vx_old = m.vx[node], vy_old = m.vy[node];
                  double              vx_new, vy_new;
                  const unsigned char b    = node_body[node];
                  const int           slot = node_condition_slot[node];
                  if (slot >= 0)
                    {
                      // boundary conditions of boundary ids
                      const NodeCondition &nc = node_conditions[slot];
                      const double         tx = nc.force[0], ty = nc.force[1];
                      double               gx = fx + tx, gy = fy + ty;
                      vx_new = damp_a * vx_old + damp_b * gx / mass;
                      vy_new = damp_a * vy_old + damp_b * gy / mass;
                      if (!nc.prescribed[0])
                        unbalanced += (gx - f_v[2 * k]) * (gx - f_v[2 * k]);
                      if (!nc.prescribed[1])
                        unbalanced +=
                          (gy - f_v[2 * k + 1]) * (gy - f_v[2 * k + 1]);
                      double rx = 0., ry = 0.;
                      if (nc.prescribed[0])
                        {
                          vx_new = nc.velocity[0];
                          rx     = mass * (vx_new - vx_old) / dt - gx;
                        }
                      if (nc.prescribed[1])
                        {
                          vy_new = nc.velocity[1];
                          ry     = mass * (vy_new - vy_old) / dt - gy;
                        }
                      w_external += 0.5 * dt *
                                    ((tx + rx) * (vx_old + vx_new) +
                                     (ty + ry) * (vy_old + vy_new));
                      double *r =
                        sums + n_sums + 2 * max_bodies + 2 * nc.condition;
                      r[0] += rx;
                      r[1] += ry;
                    }
                  else if (b == 255 ||
                           body_motion[b] == DiscreteBody::Motion::free)
                    {
                      vx_new          = damp_a * vx_old + damp_b * fx / mass;
                      vy_new          = damp_a * vy_old + damp_b * fy / mass;
                      const double ux = fx - f_v[2 * k],
                                   uy = fy - f_v[2 * k + 1];
                      unbalanced += ux * ux + uy * uy;
                    }
                  else
                    {
                      if (body_motion[b] == DiscreteBody::Motion::fixed)
                        vx_new = vy_new = 0.;
                      else
                        {
                          vx_new = body_velocity_now[b][0];
                          vy_new = body_velocity_now[b][1];
                        }
                      // reaction of the support or driver
                      const double rx = mass * (vx_new - vx_old) / dt - fx;
                      const double ry = mass * (vy_new - vy_old) / dt - fy;
                      w_external +=
                        0.5 * dt *
                        (rx * (vx_old + vx_new) + ry * (vy_old + vy_new));
                      sums[n_sums + 2 * b] += rx;
                      sums[n_sums + 2 * b + 1] += ry;
                    }
                  const double ax = 0.5 * dt * (vx_old + vx_new);
                  const double ay = 0.5 * dt * (vy_old + vy_new);
                  w_elastic += f_el[2 * k] * ax + f_el[2 * k + 1] * ay;
                  internal += f_el[2 * k] * f_el[2 * k] +
                              f_el[2 * k + 1] * f_el[2 * k + 1];
                  w_viscous += f_v[2 * k] * ax + f_v[2 * k + 1] * ay;
                  if (c_damp > 0. && (b == 255 || body_motion[b] ==
                                                    DiscreteBody::Motion::free))
                    {
                      // work of -c m v_avg on the components not prescribed
                      const bool px =
                        slot >= 0 && node_conditions[slot].prescribed[0];
                      const bool py =
                        slot >= 0 && node_conditions[slot].prescribed[1];
                      w_viscous -= c_damp * mass / dt *
                                   ((px ? 0. : ax * ax) + (py ? 0. : ay * ay));
                    }
                  w_joint += fjx * ax + fjy * ay;
                  w_contact +=
                    f_contact[2 * k] * ax + f_contact[2 * k + 1] * ay;
                  w_external += fgx * ax + fgy * ay;
                  m.vx[node] = vx_new;
                  m.vy[node] = vy_new;
                  m.x[node] += dt * vx_new;
                  m.y[node] += dt * vy_new;
                  const double v2 = vx_new * vx_new + vy_new * vy_new;
                  max_speed       = std::max(max_speed, v2);
                  kinetic += 0.5 * mass * v2;
                  if (!(v2 < 1e300) && bad_node < 0.)
                    bad_node = node;
                }
            }
          sums[8]  = unbalanced;
          sums[9]  = internal;
          sums[10] = kinetic;
          sums[0]  = w_elastic;
          sums[1]  = w_viscous;
          sums[2]  = w_joint;
          sums[3]  = w_contact;
          sums[4]  = w_external;
          sums[5]  = max_speed;
          sums[6]  = bad_node;
          sums[7]  = inverted;
        });
      double max_speed = 0., unbalanced_sq = 0., internal_sq = 0., kinetic = 0.;
      for (auto &r : body_reaction)
        r = {{0., 0.}};
      condition_reaction.assign(conditions.size(), {{0., 0.}});
      for (std::size_t c = 0; c < n_chunks; ++c)
        {
          const double *sums = &chunk_sums[c * stride];
          balance.elastic_work -= sums[0];
          balance.viscous_dissipation -= sums[1];
          balance.joint_work -= sums[2];
          balance.contact_work -= sums[3];
          balance.external_work += sums[4];
          max_speed = std::max(max_speed, sums[5]);
          unbalanced_sq += sums[8];
          internal_sq += sums[9];
          kinetic += sums[10];
          // chunks in element order: the first flagged is the lowest index
          if (first_nonfinite_node < 0 && sums[6] >= 0.)
            first_nonfinite_node = static_cast<long long>(sums[6]);
          if (first_inverted_element < 0 && sums[7] >= 0.)
            first_inverted_element = static_cast<long long>(sums[7]);
          for (unsigned int b = 0; b < n_bodies; ++b)
            {
              body_reaction[b][0] += sums[n_sums + 2 * b];
              body_reaction[b][1] += sums[n_sums + 2 * b + 1];
            }
          for (unsigned int k = 0; k < conditions.size(); ++k)
            {
              condition_reaction[k][0] += sums[n_sums + 2 * max_bodies + 2 * k];
              condition_reaction[k][1] +=
                sums[n_sums + 2 * max_bodies + 2 * k + 1];
            }
        }
      relative_unbalanced_force =
        std::sqrt(unbalanced_sq / std::max(internal_sq, 1e-300));
      step_kinetic = kinetic;
      travel_since_search += std::sqrt(max_speed) * dt;
      if (2. * travel_since_search > contact_buffer)
        contact_search_needed = true;
    }

    void
    ExplicitSolver::step()
    {
      if (quasi_static)
        {
          // one thermal step of physical time (M -> T: current geometry,
          // joints, contacts) and the new thermal stretch (T -> M) ...
          const double dt = quasi_static_thermal_step();
          check_cracks_seen_by_heat();
          heat->update_contact_pairs();
          heat->step(time, dt);
          time += dt;
          thermal_time = time;
          ++n_thermal_steps;
          update_thermal_stretch();
          // ... then the mechanics relaxes at these temperatures (no clock),
          // from the extrapolated state where asked for
          if (parameters.discrete_heat.relaxation_predictor == "extrapolate")
            predict_relaxation(dt);
          current_thermal_step = dt;
          unsigned int i       = 0;
          bool         relaxed = false;
          // kinetic damping: the kinetic energy of the last step and the
          // largest one since the last check (a reset just before a check
          // must not pass for convergence)
          const bool kinetic_damping =
            parameters.discrete_heat.relaxation_damping == "kinetic";
          double previous_kinetic = 0., window_kinetic = 0.;
          while (i < steps_per_thermal_step)
            {
              relaxation_step = i;
              mechanical_step();
              ++i;
              if (kinetic_damping)
                {
                  window_kinetic = std::max(window_kinetic, step_kinetic);
                  if (step_kinetic < previous_kinetic)
                    {
                      reset_velocities();
                      previous_kinetic = 0.;
                    }
                  else
                    previous_kinetic = step_kinetic;
                }
              if (i % 50 == 0)
                {
                  energy();
                  last_kinetic_to_strain =
                    (kinetic_damping ? window_kinetic : balance.kinetic) /
                    std::max(balance.strain, 1e-300);
                  window_kinetic = 0.;
                  if (i > quasi_static_ramp_steps &&
                      last_kinetic_to_strain <
                        parameters.discrete_heat.relaxation_tolerance &&
                      relative_unbalanced_force <=
                        parameters.discrete_heat.relaxation_force_tolerance)
                    {
                      relaxed = true;
                      break;
                    }
                }
            }
          relaxation_step       = quasi_static_ramp_steps + 1;
          last_relaxation_steps = i;
          if (parameters.discrete_heat.relaxation_predictor == "extrapolate")
            damaged_after_relaxation = n_damaged_or_broken_joints();
          if (parameters.discrete_heat.maximum_utilisation_change > 0.)
            {
              const double u         = max_joint_utilisation();
              joint_utilisation_rate = (u - joint_utilisation) / dt;
              joint_utilisation      = u;
            }
          if (!relaxed)
            {
              ++relaxations_at_cap;
              if (relaxations_at_cap == 1)
                std::cerr
                  << "[tmfdem] warning: at t = " << time
                  << " s the relaxation reached its cap of "
                  << steps_per_thermal_step
                  << " mechanical steps (Discrete heat/Mechanical steps per "
                     "thermal step) with kinetic / strain energy "
                  << last_kinetic_to_strain << " above Relaxation tolerance = "
                  << parameters.discrete_heat.relaxation_tolerance
                  << ": the state is not in equilibrium. Raise the cap, "
                     "shorten the thermal step or add Mass damping; "
                     "summary.json counts these steps "
                     "(relaxations_at_cap).\n";
              if (parameters.discrete_heat.relaxation_cap_is_error)
                guard_failure(
                  "guard: the relaxation at t = " + Utilities::to_string(time) +
                  " s reached its cap of " +
                  std::to_string(steps_per_thermal_step) +
                  " mechanical steps without reaching Relaxation tolerance "
                  "(Discrete heat/Relaxation cap is error = true).");
            }
          return;
        }
      mechanical_step();
      time += time_step;
      if (with_heat && step_number % steps_per_thermal_step == 0)
        {
          // M -> T: current geometry, broken joints, contacts
          check_cracks_seen_by_heat();
          heat->update_contact_pairs();
          heat->step(thermal_time, time - thermal_time);
          thermal_time = time;
          ++n_thermal_steps;
          // T -> M
          update_thermal_stretch();
        }
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
      if (!parameters.discrete_heat.accept_continuum_source_at_broken_joints)
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
      double removed = 0.;
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        {
          const unsigned char b = node_body[n];
          if (b != 255 && body_motion[b] != DiscreteBody::Motion::free)
            continue;
          const int    slot = node_condition_slot[n];
          const bool   px   = slot >= 0 && node_conditions[slot].prescribed[0];
          const bool   py   = slot >= 0 && node_conditions[slot].prescribed[1];
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
      ++velocity_resets;
    }

    unsigned int
    ExplicitSolver::n_damaged_or_broken_joints() const
    {
      unsigned int n = 0;
      for (unsigned int j = 0; j < model.n_joints; ++j)
        n += model.joint_status[j] != JointStatus::intact ||
             model.joint_damage[2 * j] > 0. ||
             model.joint_damage[2 * j + 1] > 0.;
      return n;
    }

    void
    ExplicitSolver::predict_relaxation(const double dt)
    {
      // the last relaxation took the state from relaxed_x to x over the
      // thermal step relaxed_thermal_step; a response linear in time goes on
      // by the same increment per unit time. Not across a relaxation that
      // damaged or broke joints (its increment holds the crack's jump).
      const unsigned int damaged = n_damaged_or_broken_joints();
      const bool         extrapolate =
        relaxed_thermal_step > 0. && relaxed_x.size() == model.n_nodes &&
        damaged_before_relaxation == damaged_after_relaxation &&
        damaged == damaged_after_relaxation;
      if (extrapolate)
        {
          const EnergyBalance before = energy();
          const double        ratio  = dt / relaxed_thermal_step;
          for (unsigned int n = 0; n < model.n_nodes; ++n)
            {
              const double dx       = model.x[n] - relaxed_x[n];
              const double dy       = model.y[n] - relaxed_y[n];
              relaxed_x[n]          = model.x[n];
              relaxed_y[n]          = model.y[n];
              const unsigned char b = node_body[n];
              if (b != 255 && body_motion[b] != DiscreteBody::Motion::free)
                continue;
              const int slot = node_condition_slot[n];
              if (slot < 0 || !node_conditions[slot].prescribed[0])
                model.x[n] += ratio * dx;
              if (slot < 0 || !node_conditions[slot].prescribed[1])
                model.y[n] += ratio * dy;
            }
          energy();
          // the jump's work on the solid and the intact joints (damaged
          // joints and contacts: force x jump, not booked)
          balance.relaxation_work += balance.strain - before.strain +
                                     balance.joint_stored - before.joint_stored;
          balance.joint_work += balance.joint_stored - before.joint_stored;
          contact_search_needed |= contact_enabled;
          ++predicted_relaxations;
        }
      else
        {
          relaxed_x = model.x;
          relaxed_y = model.y;
        }
      relaxed_thermal_step      = dt;
      damaged_before_relaxation = damaged;
    }

    double
    ExplicitSolver::max_joint_utilisation() const
    {
      constexpr double gauss[2] = {0.21132486540518713, 0.78867513459481287};
      double           highest  = 0.;
      for (unsigned int j = 0; j < model.n_joints; ++j)
        {
          if (model.joint_status[j] != JointStatus::intact ||
              model.joint_damage[2 * j] > 0. ||
              model.joint_damage[2 * j + 1] > 0.)
            continue;
          // the geometry of compute_joint_forces_with()
          const unsigned int   *n   = &model.joint_nodes[4 * j];
          const double          d0x = model.x[n[2]] - model.x[n[0]];
          const double          d0y = model.y[n[2]] - model.y[n[0]];
          const double          d1x = model.x[n[3]] - model.x[n[1]];
          const double          d1y = model.y[n[3]] - model.y[n[1]];
          const double          ex  = 0.5 * (model.x[n[1]] + model.x[n[3]] -
                                   model.x[n[0]] - model.x[n[2]]);
          const double          ey  = 0.5 * (model.y[n[1]] + model.y[n[3]] -
                                   model.y[n[0]] - model.y[n[2]]);
          const double          L   = std::sqrt(ex * ex + ey * ey);
          const double          tx = ex / L, ty = ey / L, nx = ty, ny = -tx;
          const JointConstants &k = model.joint_constants[j];
          for (const double u : gauss)
            {
              const double dx = (1. - u) * d0x + u * d1x;
              const double dy = (1. - u) * d0y + u * d1y;
              const double o  = dx * nx + dy * ny;
              const double s  = dx * tx + dy * ty;
              const double fs =
                k.cohesion -
                (o < 0. ? k.normal_stiffness * o : 0.) * k.friction_tangent;
              highest =
                std::max({highest,
                          o * k.normal_stiffness / (2. * k.tensile_strength),
                          std::abs(s) * k.tangential_stiffness / (2. * fs)});
            }
        }
      return std::min(highest, 1.);
    }

    double
    ExplicitSolver::quasi_static_thermal_step() const
    {
      const DiscreteHeatParameters &dh = parameters.discrete_heat;
      double                        dt =
        parameters.time.time_step *
        std::pow(dh.thermal_step_growth, static_cast<double>(n_thermal_steps));
      if (dh.maximum_thermal_step > 0.)
        dt = std::min(dt, dh.maximum_thermal_step);
      dt = std::max(dt, parameters.time.time_step);
      // joints approaching their strength: at most the allowed rise of the
      // utilisation per step, predicted from its last rate (no shorter than
      // 1e-3 Time step, so that a jump cannot stall the run)
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
          dt = std::min(dt, std::max(1e-3 * parameters.time.time_step, limit));
        }
      // land on the end time instead of stepping past it
      const double left = parameters.time.end_time - time;
      return left < 1.5 * dt ? left : dt;
    }

    void
    ExplicitSolver::mechanical_step()
    {
      // driven bodies move with their velocity at mid step; in quasi-static
      // coupling with the velocity at the middle of the thermal step, its
      // displacement v dt_thermal spread over the first relaxation steps
      const Point<2> mid_time(0., 0.);
      const double   t_velocity = quasi_static ?
                                    time - 0.5 * current_thermal_step :
                                    time + 0.5 * time_step;
      const double   scale      = imposed_velocity_scale();
      for (unsigned int b = 0; b < body_motion.size(); ++b)
        if (body_motion[b] == DiscreteBody::Motion::velocity)
          {
            body_velocity[2 * b]->set_time(t_velocity);
            body_velocity[2 * b + 1]->set_time(t_velocity);
            body_velocity_now[b] = {
              {scale * body_velocity[2 * b]->value(mid_time),
               scale * body_velocity[2 * b + 1]->value(mid_time)}};
          }
      if (boundary_conditions_change ||
          (quasi_static && relaxation_step <= quasi_static_ramp_steps))
        evaluate_boundary_conditions();
      if (contact_enabled)
        {
          if (contact_search_needed)
            update_contact_candidates();
          compute_contact_forces();
        }
      compute_joint_forces();
      update_nodes();
      ++step_number;
    }

    EnergyBalance
    ExplicitSolver::energy()
    {
      double kinetic = 0., strain = 0., stored = 0.;
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        kinetic += 0.5 * model.mass[n] *
                   (model.vx[n] * model.vx[n] + model.vy[n] * model.vy[n]);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          const unsigned int n0 = 3 * e;
          const double      *ib = &model.inverse_basis[4 * e];
          const Matrix2      F  = multiply(element_basis(model.x[n0],
                                                   model.y[n0],
                                                   model.x[n0 + 1],
                                                   model.y[n0 + 1],
                                                   model.x[n0 + 2],
                                                   model.y[n0 + 2]),
                                     Matrix2{ib[0], ib[1], ib[2], ib[3]});
          const double       s  = model.thermal_stretch[e];
          const Matrix2      Fe{F.a00 / s, F.a01 / s, F.a10 / s, F.a11 / s};
          strain += model.reference_area[e] * s * s *
                    strain_energy_density(Fe, element_lame[e]);
        }
      for (unsigned int j = 0; j < model.n_joints; ++j)
        if (model.joint_status[j] == JointStatus::intact &&
            model.joint_damage[2 * j] == 0. &&
            model.joint_damage[2 * j + 1] == 0.)
          {
            const unsigned int *n  = &model.joint_nodes[4 * j];
            const double        ex = model.x[n[1]] - model.x[n[0]];
            const double        ey = model.y[n[1]] - model.y[n[0]];
            const double        L  = std::hypot(ex, ey);
            const double        tx = ex / L, ty = ey / L;
            const double        d0x = model.x[n[2]] - model.x[n[0]];
            const double        d0y = model.y[n[2]] - model.y[n[0]];
            const double        d1x = model.x[n[3]] - model.x[n[1]];
            const double        d1y = model.y[n[3]] - model.y[n[1]];
            // the two Gauss points of the force computation
            for (const double u : {0.21132486540518713, 0.78867513459481287})
              {
                const double dx = (1. - u) * d0x + u * d1x;
                const double dy = (1. - u) * d0y + u * d1y;
                stored += 0.5 * L *
                          stored_joint_energy(dx * ty - dy * tx,
                                              dx * tx + dy * ty,
                                              model.joint_constants[j]);
              }
          }
      balance.kinetic      = kinetic;
      balance.strain       = strain;
      balance.joint_stored = stored;
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
      for (const auto &r : body_reaction)
        row << ',' << r[0] << ',' << r[1];
      for (const auto &r : condition_reaction)
        row << ',' << r[0] << ',' << r[1];
      row << '\n';
      history_csv->append(row.str());
    }

    void
    ExplicitSolver::write_output()
    {
      if (parameters.output.write_vtu)
        {
          if (with_heat)
            {
              std::vector<double> T(heat->temperature().begin(),
                                    heat->temperature().end());
              solution_series->write(time,
                                     discrete_solution_vtu(model, {{"T", &T}}));
            }
          else
            solution_series->write(time, discrete_solution_vtu(model));
          crack_series->write(time, crack_vtu(model));
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
            if (model.body[e] != 255 &&
                body_motion[model.body[e]] != DiscreteBody::Motion::free)
              continue;
            // in contact: contact forces on the element above 1e-3 of its
            // internal forces (|sigma| times the perimeter; elements that
            // share only a vertex exchange tiny forces in an intact mesh)
            if (!pairs.empty())
              {
                double f[6] = {0., 0., 0., 0., 0., 0.};
                add_contact_forces(e, f);
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
                edge.thermal_stretch        = model.thermal_stretch[e];
                if (with_heat)
                  edge.thermal_stretch =
                    thermal_stretch(m.thermal_expansion,
                                    m.poisson_ratio,
                                    0.5 * (heat->temperature()[a] +
                                           heat->temperature()[b]) -
                                      reference_temperature[e],
                                    idealisation);
                const int c =
                  id < condition_of_id.size() ? condition_of_id[id] : -1;
                if (c < 0)
                  edge.kind = BoundaryEdgeKnowledge::Kind::traction;
                else if (conditions[c].type == Type::traction)
                  {
                    edge.kind = BoundaryEdgeKnowledge::Kind::traction;
                    for (unsigned int d = 0; d < 2; ++d)
                      {
                        conditions[c].value[d]->set_time(time);
                        // the mean of the ends, as the nodal loads
                        edge.traction[d] =
                          0.5 * (conditions[c].value[d]->value(
                                   Point<2>(model.x_ref[a], model.y_ref[a])) +
                                 conditions[c].value[d]->value(
                                   Point<2>(model.x_ref[b], model.y_ref[b])));
                      }
                  }
                else if (conditions[c].type == Type::roller_x ||
                         conditions[c].type == Type::roller_y)
                  {
                    // roller x holds u_x: no traction along y, and v.v.
                    edge.kind = BoundaryEdgeKnowledge::Kind::component;
                    edge.component =
                      conditions[c].type == Type::roller_x ? 1 : 0;
                  }
              }
          }
      }
      const std::vector<double> vertex_stress =
        recover_vertex_stress(model, boundary);
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
            double stress[3] = {0., 0., 0.};
            for (unsigned int k = 0; k < 3; ++k)
              for (unsigned int c = 0; c < 3; ++c)
                stress[c] +=
                  s.lambda[k] *
                  vertex_stress[3 * model.node_vertex[3 * s.element + k] + c];
            out << ux << ',' << uy << ',' << stress[0] << ',' << stress[1]
                << ',' << stress[2] << '\n';
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
      double px = 0., py = 0.;
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        {
          px += model.mass[n] * model.vx[n];
          py += model.mass[n] * model.vy[n];
        }
      std::vector<JsonObject> reactions;
      for (unsigned int b = 0; b < body_reaction.size(); ++b)
        {
          JsonObject r;
          r.add("body", parameters.discrete_bodies.bodies[b].name)
            .add("force_x", body_reaction[b][0])
            .add("force_y", body_reaction[b][1]);
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
        .add("joint_compliance_compensation",
             parameters.discrete_mechanics.joint_compliance_compensation)
        .add("compensation_max_share", compensation_share)
        .add("compensation_capped_elements", compensation_capped)
        .add("threads", n_threads)
        .add("threads_requested", threads_requested)
        .add("threads_available", threads_available)
        .add("threads_used", threads_used)
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
        .add("contact_searches", static_cast<long long>(n_contact_searches))
        .add("contact_pairs", static_cast<unsigned int>(pairs.size()))
        .add("peak_resident_memory_bytes",
             [] {
               rusage usage;
               getrusage(RUSAGE_SELF, &usage);
               return static_cast<long long>(usage.ru_maxrss) * 1024;
             }())
        .add("momentum_x", px)
        .add("momentum_y", py)
        .add("energy", energies)
        .add("body_reactions", reactions);
      if (!stop_reason.empty())
        summary.add("stop_reason", stop_reason);
      if (with_heat)
        {
          const HeatBalance &b = heat->balance();
          JsonObject         boundary;
          for (const auto &[id, q] : b.boundary_heat_in)
            boundary.add(std::to_string(id), q);
          JsonObject hb;
          hb.add("boundary_heat_in", boundary)
            .add("source_heat", b.source_heat)
            .add("contact_exchange", b.contact_exchange)
            .add("stored_heat", b.stored_heat)
            .add("imbalance", b.imbalance())
            .add("relative_imbalance", std::abs(b.imbalance()) / b.scale());
          JsonObject rates;
          for (const auto &[id, q] : heat->last_boundary_rate())
            rates.add(std::to_string(id), q);
          hb.add("boundary_heat_rate_last_step", rates);
          summary.add("coupling", parameters.discrete_heat.coupling)
            .add("temperature_source", heat->name())
            .add("contact_heat_model",
                 contact_heat_model_name(
                   parameters.discrete_heat.contact_heat_model))
            .add("continuum_heat_across_cracks", heat_across_cracks)
            .add("thermal_steps", static_cast<long long>(n_thermal_steps))
            .add("last_relaxation_steps", last_relaxation_steps)
            .add("relaxations_at_cap", relaxations_at_cap)
            .add("predicted_relaxations", predicted_relaxations)
            .add("velocity_resets", static_cast<long long>(velocity_resets))
            .add("last_relative_unbalanced_force", relative_unbalanced_force)
            .add("last_kinetic_to_strain_energy", last_kinetic_to_strain)
            .add("mechanical_steps_per_thermal_step", steps_per_thermal_step)
            .add("thermal_time_step",
                 quasi_static ? parameters.time.time_step :
                                steps_per_thermal_step * time_step)
            .add("heat_balance", hb);
        }
      write_file_atomically(parameters.output.directory + "/summary.json",
                            summary.str() + "\n");
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
      for (unsigned int b = 0; b < body_motion.size(); ++b)
        header += ",body" + std::to_string(b + 1) + "_fx,body" +
                  std::to_string(b + 1) + "_fy";
      condition_reaction.assign(conditions.size(), {{0., 0.}});
      for (unsigned int k = 0; k < conditions.size(); ++k)
        header += ",condition" + std::to_string(k + 1) + "_fx,condition" +
                  std::to_string(k + 1) + "_fy";
      history_csv = open_csv(folder + "/history.csv", header);
      const std::string monitor_header = with_heat ?
                                           "time,name,x,y,T,ux,uy,sxx,syy,sxy" :
                                           "time,name,x,y,ux,uy,sxx,syy,sxy";
      if (!probe_samples.empty())
        probes_csv = open_csv(folder + "/probes.csv", monitor_header);
      if (!line_samples.empty())
        lines_csv = open_csv(folder + "/lines.csv", monitor_header);

      const double start = time, end = parameters.time.end_time;
      output_times.clear();
      for (const double t : parameters.output.times)
        if (t > start && t < end)
          output_times.push_back(t);
      if (parameters.output.interval > 0.)
        for (double t = start + parameters.output.interval; t < end;
             t += parameters.output.interval)
          output_times.push_back(t);
      output_times.push_back(end);
      std::sort(output_times.begin(), output_times.end());
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
                                true);
      const unsigned long max_steps = parameters.discrete_mechanics.max_steps;
      const double        advance =
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
      while (time < end - 0.5 * advance &&
             (max_steps == 0 || step_number < max_steps))
        {
          step();
          check_step_guards();
          if (quasi_static)
            std::cerr << "[tmfdem] t = " << time << " s: relaxed in "
                      << last_relaxation_steps
                      << " mechanical steps, kinetic / strain energy "
                      << last_kinetic_to_strain << ", out-of-balance force "
                      << relative_unbalanced_force << "\n";
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
              time >= output_times[next_output] - 0.5 * advance)
            {
              if (!snap_reported && std::abs(time - output_times[next_output]) >
                                      1e-9 * std::max(1., std::abs(time)))
                {
                  snap_reported = true; // once per run
                  std::cerr
                    << "[tmfdem] output time " << output_times[next_output]
                    << " s requested, written at t = " << time
                    << " s: outputs snap to the nearest "
                    << (quasi_static ? "thermal" : "mechanical") << " step ("
                    << advance << " s)\n";
                }
              energy();
              write_output();
              while (next_output < output_times.size() &&
                     time >= output_times[next_output] - 0.5 * advance)
                ++next_output;
            }
          if ((step_number & 255) == 0)
            {
              wall_time = progress.elapsed() + resumed_wall_time;
              progress.update(step_number,
                              time,
                              " broken joints " +
                                std::to_string(model.n_broken_joints()));
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
        write_file_atomically(parameters.output.directory + "/final_mesh.msh",
                              deformed_mesh_msh(model));
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
