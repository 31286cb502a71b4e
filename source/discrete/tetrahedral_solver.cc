/**
 * @file
 * The discrete layer in 3D: set-up, the explicit step (joint forces on the
 * faces, element forces and the node update, fused per element as in 2D,
 * in fixed chunks so that the result does not depend on the thread count),
 * and the outputs.
 */
#include <deal.II/base/mpi.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <set>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/discrete_output.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/element_kernel.h>
#include <tmfdem/discrete/joint_compliance.h>
#include <tmfdem/discrete/joint_kernel.h>
#include <tmfdem/discrete/joints.h>
#include <tmfdem/discrete/stable_step.h>
#include <tmfdem/discrete/tetrahedral_heat.h>
#include <tmfdem/discrete/tetrahedral_solver.h>
#include <tmfdem/discrete/tetrahedral_update.h>
#include <tmfdem/discrete/tetrahedron_contact_system.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/output_files.h>
#include <tmfdem/io/output_schedule.h>
#include <tmfdem/mesh/cell_order.h>
#include <tmfdem/mesh/mesh_checks.h>
#include <tmfdem/mesh/mesh_generator.h>

namespace tmfdem
{
  namespace discrete
  {
    TetrahedralSolver::TetrahedralSolver(const Parameters &parameters,
                                         MPI_Comm          communicator,
                                         const Physics     physics)
      : parameters(parameters)
      , communicator(communicator)
      , physics(physics)
      , fe(1)
      , relaxation(parameters)
    {}

    TetrahedralSolver::~TetrahedralSolver() = default;

    void
    TetrahedralSolver::check_supported() const
    {
      const auto       &dm = parameters.get<DiscreteMechanicsParameters>();
      const std::string in_3d =
        " is not modelled in 3D yet (Mesh/Dimension = 3: tetrahedra with "
        "cohesive joints, bodies and boundary conditions, heat with the "
        "multi-rate and quasi-static coupling, contact with contact heat, "
        "gravity); ";
      if (physics != Physics::mechanics)
        {
          const auto &dh = parameters.get<DiscreteHeatParameters>();
          if (dh.temperature_source != "discrete heat")
            throw InputError(
              "Discrete heat/Temperature source = " + dh.temperature_source +
              in_3d + "allowed is discrete heat.");
          if (parameters.time.mode != TimeSteppingParameters::Mode::transient)
            throw InputError("Time stepping/Mode = steady: the discrete heat "
                             "is transient only; allowed is transient.");
        }
      // every 3D model, heat alone too
      if (!parameters.monitors.probes.empty() ||
          !parameters.monitors.lines.empty())
        throw InputError("Monitors/Probes, Lines: probes and lines of the "
                         "discrete layer" +
                         in_3d +
                         "allowed in 3D is none (solution.pvd holds "
                         "the fields).");
      if (Utilities::MPI::n_mpi_processes(communicator) > 1)
        throw InputError("Mesh/Dimension = 3: the discrete layer in 3D runs "
                         "on one MPI process; allowed is mpirun -np 1 (or "
                         "no mpirun), with Discrete mechanics/Threads for "
                         "the cores.");
      if (physics == Physics::heat)
        return;
      parameters.mechanics.check_dimension(3);
      const auto as_text = [](const double value) {
        std::ostringstream text;
        text << value;
        return text.str();
      };
      if (dm.gravity.size() == 2 &&
          (dm.gravity[0] != 0. || dm.gravity[1] != 0.))
        throw InputError(
          "Discrete mechanics/Gravity = " + as_text(dm.gravity[0]) + ", " +
          as_text(dm.gravity[1]) +
          " has two components: Mesh/Dimension = 3 takes g_x, g_y, g_z; "
          "allowed are three (or the default 0, 0: no gravity).");
      if (physics == Physics::thermo_mechanics && dm.gravity_ramp_time > 0. &&
          parameters.get<DiscreteHeatParameters>().coupling ==
            DiscreteHeatParameters::Coupling::quasi_static)
        throw InputError(
          "Discrete mechanics/Gravity ramp time = " +
          Utilities::to_string(dm.gravity_ramp_time) +
          " s: a gravity ramp is for dynamic runs; with Discrete "
          "heat/Coupling = quasi-static every relaxation finds the "
          "equilibrium under full gravity. Set it to 0.");
      if (!dm.initial_cracks.empty())
        throw InputError("Discrete mechanics/Initial cracks: segments are 2D "
                         "cracks; allowed in 3D is none.");
      for (const auto &condition : parameters.mechanical_boundary.conditions)
        if (condition.type == MechanicalBoundaryCondition::Type::traction)
          throw InputError(
            condition.name +
            "/Type = traction: the discrete layer in 3D imposes fixed, roller "
            "x, roller y, roller z, velocity and displacement conditions; "
            "allowed are those.");
    }

    void
    TetrahedralSolver::setup_mesh()
    {
      create_output_folder(parameters.output.directory, communicator);
      create_coarse_mesh(parameters.mesh,
                         parameters.output.directory,
                         triangulation,
                         communicator);
      const std::string source =
        parameters.mesh.source == MeshParameters::Source::file ?
          "mesh file '" + parameters.mesh.file_name + "'" :
          "generated mesh";
      const bool curved =
        parameters.mesh.source == MeshParameters::Source::ball ||
        parameters.mesh.source == MeshParameters::Source::spherical_shell ||
        parameters.mesh.source == MeshParameters::Source::cylinder ||
        parameters.mesh.source == MeshParameters::Source::hollow_cylinder;
      const MeshReport report = check_mesh(triangulation,
                                           source,
                                           domain_volume(parameters.mesh),
                                           curved);
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->reference_cell() != ReferenceCells::Tetrahedron)
          throw InputError(source +
                           " has hexahedra; the discrete layer needs "
                           "tetrahedra (Mesh/Element type = triangles, "
                           "which splits generated boxes into "
                           "tetrahedra in 3D).");
      for (const auto id : report.material_ids)
        parameters.materials.require_given(id, "cells of the " + source);
      triangulation.refine_global(parameters.mesh.global_refinements);
      std::vector<unsigned int> mesh_index;
      if (parameters.get<DiscreteMechanicsParameters>().hilbert_curve_numbering)
        mesh_index = order_cells_along_hilbert_curve(triangulation);
      dof_handler.reinit(triangulation);
      dof_handler.distribute_dofs(fe);
      model.build(dof_handler);
      if (!mesh_index.empty())
        model.mesh_index = mesh_index;

      // the face of each joint side
      joint_face.assign(2 * model.n_joints, 0);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int f = 0; f < 4; ++f)
          {
            const int code = model.edge_joint[4 * e + f];
            if (code >= 0)
              joint_face[code] = f;
          }
    }

    void
    TetrahedralSolver::setup_materials()
    {
      const auto &dm = parameters.get<DiscreteMechanicsParameters>();
      softening_law  = dm.softening_law;
      element_lame.resize(model.n_elements);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          const MaterialProperties &m = parameters.materials[model.material[e]];
          element_lame[e]             = lame_constants(m.youngs_modulus,
                                           m.poisson_ratio,
                                           Idealisation::solid_3d);
          const double node_mass =
            m.density * dm.mass_scaling_factor * model.reference_area[e] / 4.;
          for (unsigned int k = 0; k < 4; ++k)
            model.mass[4 * e + k] = node_mass;
        }
      setup_joint_constants(parameters, softening_law, model);

      // joint compliance compensation: each tetrahedron in series with
      // half of its joints has the material's stiffness (isotropic, or
      // direction by direction with the anisotropic correction)
      compensation_capped = 0;
      compensation_share  = 0.;
      element_anisotropy.clear();
      element_stiffness_bound.clear();
      if (!dm.joint_compliance_compensation)
        return;
      const bool anisotropic = dm.anisotropic_joint_compliance_compensation;
      if (anisotropic)
        {
          element_anisotropy.assign(anisotropy_size<3> * model.n_elements, 0.);
          element_stiffness_bound.assign(model.n_elements, 1.);
        }
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          std::array<double, 4> x, y, z, p_n{}, p_t{};
          for (unsigned int k = 0; k < 4; ++k)
            {
              x[k] = model.x_ref[4 * e + k];
              y[k] = model.y_ref[4 * e + k];
              z[k] = model.z_ref[4 * e + k];
            }
          for (unsigned int f = 0; f < 4; ++f)
            {
              const int code = model.edge_joint[4 * e + f];
              if (code < 0)
                continue;
              // the penalty p = k h of the joint; deal.II's face f is the
              // one opposite vertex 3 - f
              const unsigned int    j = code / 2;
              const JointConstants &k = model.joint_constants[j];
              p_n[3 - f] = k.normal_stiffness * model.joint_length[j];
              p_t[3 - f] = k.tangential_stiffness * model.joint_length[j];
            }
          const CompensatedElement c =
            compensate_joint_compliance(x,
                                        y,
                                        z,
                                        element_lame[e],
                                        p_n,
                                        p_t,
                                        max_compensated_share,
                                        anisotropic);
          element_lame[e] = c.lame;
          if (anisotropic)
            {
              std::copy(c.anisotropy.begin(),
                        c.anisotropy.end(),
                        &element_anisotropy[anisotropy_size<3> * e]);
              element_stiffness_bound[e] = c.stiffness_bound_factor;
            }
          compensation_capped += c.capped;
          compensation_share = std::max(compensation_share, c.share);
        }
      if (compensation_capped > 0)
        std::cerr << "note: joint compliance compensation capped in "
                  << compensation_capped
                  << " tetrahedra (their joints take more than "
                  << 100. * max_compensated_share
                  << " % of the material's compliance; at most "
                  << 100. * compensation_share
                  << " %): those stay softer than the material\n";
    }

    void
    TetrahedralSolver::setup_constraints()
    {
      node_constraint.assign(model.n_nodes, -1);
      constraints.clear();
      velocity_functions.clear();
      imposed_displacements = false;
      owner_names.clear();
      const auto constraint_of = [&](const unsigned int node,
                                     const unsigned int owner) {
        if (node_constraint[node] < 0)
          {
            node_constraint[node] = constraints.size();
            NodeConstraint c;
            c.node  = node;
            c.owner = owner;
            constraints.push_back(c);
          }
        return &constraints[node_constraint[node]];
      };
      const auto add_function = [&](const std::string &expression,
                                    const std::string &entry) -> int {
        if (expression == "0")
          return -1;
        velocity_functions.push_back(
          make_expression_function<3>(expression, entry));
        imposed_depend_on_time |= expression.find('t') != std::string::npos;
        return velocity_functions.size() - 1;
      };

      // bodies: their cells (DiscreteModel::body), every node of the fixed
      // and driven ones constrained
      const auto &bodies = parameters.get<DiscreteBodyParameters>().bodies;
      model.body_number.clear();
      for (unsigned int b = 0; b < bodies.size(); ++b)
        {
          model.body_number.push_back(bodies[b].number);
          for (unsigned int e = 0; e < model.n_elements; ++e)
            if (std::find(bodies[b].material_ids.begin(),
                          bodies[b].material_ids.end(),
                          model.material[e]) != bodies[b].material_ids.end())
              model.body[e] = b;
        }
      for (const auto &body : bodies)
        {
          if (body.motion == DiscreteBody::Motion::free)
            continue;
          const unsigned int owner = owner_names.size();
          owner_names.push_back("body" + std::to_string(body.number));
          int functions[3] = {-1, -1, -1};
          if (body.motion == DiscreteBody::Motion::velocity)
            {
              functions[0] =
                add_function(body.velocity_x, body.name + "/Velocity x");
              functions[1] =
                add_function(body.velocity_y, body.name + "/Velocity y");
              functions[2] =
                add_function(body.velocity_z, body.name + "/Velocity z");
            }
          for (unsigned int e = 0; e < model.n_elements; ++e)
            if (std::find(body.material_ids.begin(),
                          body.material_ids.end(),
                          model.material[e]) != body.material_ids.end())
              {
                for (unsigned int k = 0; k < 4; ++k)
                  {
                    NodeConstraint *c = constraint_of(4 * e + k, owner);
                    for (unsigned int i = 0; i < 3; ++i)
                      {
                        c->prescribed[i] = true;
                        c->function[i]   = functions[i];
                      }
                  }
              }
        }
      // the initial velocity of free bodies' nodes
      for (const auto &body : bodies)
        if (body.motion == DiscreteBody::Motion::free)
          {
            const std::string *expressions[3] = {&body.initial_velocity_x,
                                                 &body.initial_velocity_y,
                                                 &body.initial_velocity_z};
            const char        *axes[3]        = {"x", "y", "z"};
            for (unsigned int i = 0; i < 3; ++i)
              {
                if (*expressions[i] == "0")
                  continue;
                const auto function =
                  make_expression_function<3>(*expressions[i],
                                              body.name + "/Initial velocity " +
                                                axes[i]);
                std::vector<double> &v =
                  i == 0 ? model.vx : (i == 1 ? model.vy : model.vz);
                for (unsigned int e = 0; e < model.n_elements; ++e)
                  if (std::find(body.material_ids.begin(),
                                body.material_ids.end(),
                                model.material[e]) != body.material_ids.end())
                    for (unsigned int k = 0; k < 4; ++k)
                      {
                        const unsigned int n = 4 * e + k;
                        v[n] = function->value(Point<3>(model.x_ref[n],
                                                        model.y_ref[n],
                                                        model.z_ref[n]));
                      }
              }
          }

      // boundary conditions: the nodes of the faces with their ids
      const auto &conditions = parameters.mechanical_boundary.conditions;
      for (const auto &condition : conditions)
        model.check_boundary_ids(condition.name + "/Boundary ids",
                                 condition.boundary_ids);
      for (unsigned int n = 0; n < conditions.size(); ++n)
        {
          const auto        &condition = conditions[n];
          const unsigned int owner     = owner_names.size();
          owner_names.push_back("condition" + std::to_string(n + 1));
          using Type         = MechanicalBoundaryCondition::Type;
          bool prescribed[3] = {false, false, false};
          int  functions[3]  = {-1, -1, -1};
          switch (condition.type)
            {
              case Type::fixed:
                prescribed[0] = prescribed[1] = prescribed[2] = true;
                break;
              case Type::roller_x:
                prescribed[0] = true;
                break;
              case Type::roller_y:
                prescribed[1] = true;
                break;
              case Type::roller_z:
                prescribed[2] = true;
                break;
              default: // velocity or displacement
                {
                  const bool  held    = condition.type == Type::displacement;
                  const char *axes[3] = {"x", "y", "z"};
                  for (unsigned int i = 0; i < 3; ++i)
                    {
                      prescribed[i] = true;
                      functions[i] =
                        held ?
                          add_function(condition.displacement[i],
                                       condition.name + "/Displacement " +
                                         axes[i]) :
                          add_function(condition.velocity[i],
                                       condition.name + "/Velocity " + axes[i]);
                    }
                  imposed_displacements |= held;
                }
            }
          for (unsigned int e = 0; e < model.n_elements; ++e)
            for (unsigned int f = 0; f < 4; ++f)
              {
                const types::boundary_id id = model.edge_boundary[4 * e + f];
                if (id == numbers::internal_face_boundary_id ||
                    std::find(condition.boundary_ids.begin(),
                              condition.boundary_ids.end(),
                              id) == condition.boundary_ids.end())
                  continue;
                for (unsigned int k = 0; k < 4; ++k)
                  if (k != 3 - f) // the face's vertices
                    {
                      NodeConstraint *c = constraint_of(4 * e + k, owner);
                      for (unsigned int i = 0; i < 3; ++i)
                        if (prescribed[i])
                          {
                            // a body's motion takes precedence
                            if (c->owner != owner && c->prescribed[i])
                              continue;
                            c->prescribed[i] = true;
                            c->function[i]   = functions[i];
                            c->displacement[i] =
                              condition.type == Type::displacement;
                          }
                    }
              }
        }
      owner_reaction.assign(owner_names.size(), {{0., 0., 0.}});
      evaluate_imposed_velocities(parameters.time.start_time);
    }

    void
    TetrahedralSolver::evaluate_imposed_velocities(const double t,
                                                   const double scale)
    {
      for (auto &function : velocity_functions)
        function->set_time(t);
      for (NodeConstraint &c : constraints)
        for (unsigned int i = 0; i < 3; ++i)
          if (!c.displacement[i])
            c.velocity[i] = c.function[i] < 0 ?
                              0. :
                              scale * velocity_functions[c.function[i]]->value(
                                        Point<3>(model.x_ref[c.node],
                                                 model.y_ref[c.node],
                                                 model.z_ref[c.node]));
    }

    void
    TetrahedralSolver::evaluate_imposed_displacements(const double target_time,
                                                      const double duration)
    {
      if (!imposed_displacements)
        return;
      for (auto &function : velocity_functions)
        function->set_time(target_time);
      const std::vector<double> *reference[3] = {&model.x_ref,
                                                 &model.y_ref,
                                                 &model.z_ref};
      const std::vector<double> *position[3]  = {&model.x, &model.y, &model.z};
      for (NodeConstraint &c : constraints)
        for (unsigned int i = 0; i < 3; ++i)
          if (c.displacement[i])
            {
              const Point<3> X(model.x_ref[c.node],
                               model.y_ref[c.node],
                               model.z_ref[c.node]);
              const double   u = c.function[i] < 0 ?
                                   0. :
                                   velocity_functions[c.function[i]]->value(X);
              // reach X + u at the end of the steps
              c.velocity[i] =
                duration > 0. ?
                  ((*reference[i])[c.node] + u - (*position[i])[c.node]) /
                    duration :
                  0.;
            }
    }

    void
    TetrahedralSolver::setup_time_step()
    {
      const auto &dm = parameters.get<DiscreteMechanicsParameters>();
      viscosity.assign(model.n_elements, 0.);
      stable_time_step = std::numeric_limits<double>::infinity();
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          ElementStepInputT<3> in;
          for (unsigned int k = 0; k < 4; ++k)
            {
              in.x[k] = model.x_ref[4 * e + k];
              in.y[k] = model.y_ref[4 * e + k];
              in.z[k] = model.z_ref[4 * e + k];
            }
          in.lame      = element_lame[e];
          in.node_mass = model.mass[4 * e];
          if (contact)
            {
              double x[4][3];
              for (unsigned int k = 0; k < 4; ++k)
                {
                  x[k][0] = in.x[k];
                  x[k][1] = in.y[k];
                  x[k][2] = in.z[k];
                }
              in.node_contact_stiffness = contact->node_stiffness_bound(x);
            }
          if (dm.damping_ratio > 0.)
            viscosity[e] = dm.damping_ratio /
                           highest_mode_damping_per_viscosity(in.x,
                                                              in.y,
                                                              in.z,
                                                              in.lame,
                                                              in.node_mass);
          in.viscosity = viscosity[e];
          // the anisotropic correction: C_e <= f C(lame) bounds the
          // element's stiffness
          if (!element_stiffness_bound.empty())
            {
              in.lame.lambda *= element_stiffness_bound[e];
              in.lame.mu *= element_stiffness_bound[e];
            }
          for (unsigned int f = 0; f < 4; ++f)
            {
              const int code = model.edge_joint[4 * e + f];
              if (code < 0)
                continue;
              // deal.II's face f is the one opposite vertex 3 - f
              const JointConstants &k = model.joint_constants[code / 2];
              in.face_joint_normal_stiffness[3 - f] = k.normal_stiffness;
              in.face_joint_tangential_stiffness[3 - f] =
                k.tangential_stiffness;
            }
          stable_time_step = std::min(stable_time_step, critical_time_step(in));
        }
      mass_damping = dm.mass_damping;
      if (dm.time_step > 0.)
        {
          time_step = dm.time_step;
          if (time_step > stable_time_step)
            throw InputError(
              "Discrete mechanics/Time step = " +
              Utilities::to_string(time_step) +
              " s exceeds the stable step of the tetrahedra, joints, "
              "contact and damping, " +
              Utilities::to_string(stable_time_step) +
              " s; allowed is at most that (or 0: Safety factor times it).");
        }
      else
        time_step = dm.safety_factor * stable_time_step;
    }

    void
    TetrahedralSolver::check_input()
    {
      check_supported();
      setup_mesh();
      if (with_mechanics())
        {
          setup_materials();
          setup_constraints();
          setup_contact();
          setup_time_step();
        }
      const auto &dm    = parameters.get<DiscreteMechanicsParameters>();
      threads_available = core_share(communicator).cores_per_rank;
      threads_requested = dm.threads;
      n_threads         = dm.threads > 0 ? dm.threads : threads_available;
      if (n_threads > threads_available && !dm.allow_oversubscription)
        {
          std::cerr << "note: Discrete mechanics/Threads = " << dm.threads
                    << " exceeds the " << threads_available
                    << " core(s) this process may use; running on "
                    << threads_available
                    << " (Allow oversubscription = true runs more)\n";
          n_threads = threads_available;
        }
      if (n_threads > thread_limit())
        set_thread_limit(n_threads);
      threads_used = measure_concurrency(arena_for(n_threads));
      if (physics != Physics::mechanics)
        setup_heat(); // coupling/tetrahedral_thermo_mechanics.cc
      input_checked = true;

      // the vector batches: the widest set unless one is named, but AVX2
      // for AVX-512 (the loop waits on memory: AVX2 as fast at 17 496
      // tetrahedra, faster at 117 912, doc/performance.md)
      vector_instructions =
        dm.vector_instructions_auto &&
            dm.vector_instructions == VectorInstructions::avx512 ?
          VectorInstructions::avx2 :
          dm.vector_instructions;
    }

    void
    TetrahedralSolver::report_validation(std::ostream &out,
                                         const Parameters &,
                                         MPI_Comm) const
    {
      double smallest = std::numeric_limits<double>::infinity();
      for (unsigned int j = 0; j < model.n_joints; ++j)
        smallest = std::min(smallest, model.joint_length[j]);
      out << "  discrete layer in 3D: " << model.n_elements << " tetrahedra, "
          << model.n_nodes << " nodes, " << model.n_joints
          << " face joints (smallest mean edge " << smallest << " m)\n"
          << "  time step " << time_step << " s (stable step "
          << stable_time_step << " s), " << n_threads << " thread(s)\n";
    }

    bool
    TetrahedralSolver::compute_joint_forces()
    {
      DiscreteModel &m = model;
      // per chunk: a joint broke (no allocation after the first step)
      std::vector<char> &broke = chunk_broke;
      broke.assign((m.n_joints + chunk_size - 1) / chunk_size, 0);
      const double       t   = time;
      const SofteningLaw law = softening_law;
      // batches of intact joints (tetrahedral_update.h); nullptr: none
      const FaceJointBatchKernel batch =
        face_joint_batch_kernel(vector_instructions, law);
      const unsigned int lanes = vector_lanes(vector_instructions);
      for_each_chunk(
        arena_for(n_threads),
        m.n_joints,
        chunk_size,
        [&](const std::size_t begin,
            const std::size_t end,
            const std::size_t c) {
          for (std::size_t j = begin; j < end; ++j)
            {
              if (batch != nullptr && j + lanes <= end &&
                  std::all_of(&m.joint_status[j],
                              &m.joint_status[j] + lanes,
                              [](const JointStatus s) {
                                return s == JointStatus::intact;
                              }))
                {
                  batch(m, j, joint_face.data(), t, broke[c]);
                  j += lanes - 1;
                  continue;
                }
              const unsigned int *p = &m.joint_nodes[6 * j];
              double              f[2][3][3]; // side, node, component
              if (m.joint_status[j] != JointStatus::intact)
                {
                  for (auto &side : f)
                    for (auto &node : side)
                      node[0] = node[1] = node[2] = 0.;
                }
              else
                {
                  double x[3][6];
                  for (unsigned int k = 0; k < 6; ++k)
                    {
                      x[0][k] = m.x[p[k]];
                      x[1][k] = m.y[p[k]];
                      x[2][k] = m.z[p[k]];
                    }
                  const double *const           nodes[3] = {x[0], x[1], x[2]};
                  const FaceJointFrameT<double> g =
                    face_joint_frame<double>(nodes);
                  FaceJointResponse<double> r;
                  double                   *damage = &m.joint_damage[3 * j];
                  if (law == SofteningLaw::linear)
                    face_joint_response<SofteningLaw::linear>(
                      g,
                      m.joint_constants[j],
                      damage,
                      r);
                  else
                    face_joint_response<SofteningLaw::munjiza>(
                      g,
                      m.joint_constants[j],
                      damage,
                      r);
                  if (damage[0] >= 1. && damage[1] >= 1. && damage[2] >= 1.)
                    {
                      mark_face_joint_broken(m, j, r.d_opening, r.d_slip, t);
                      broke[c] = 1;
                      for (auto &side : f)
                        for (auto &node : side)
                          node[0] = node[1] = node[2] = 0.;
                    }
                  else
                    for (unsigned int k = 0; k < 3; ++k)
                      for (unsigned int i = 0; i < 3; ++i)
                        {
                          f[0][k][i] = r.a[k][i] + r.frame[k][i];
                          f[1][k][i] = -r.a[k][i] + r.frame[k][i];
                        }
                }
              // each node's slot of this face
              write_face_joint_forces(m, j, joint_face.data(), f);
            }
        });
      return std::find(broke.begin(), broke.end(), 1) != broke.end();
    }

    void
    TetrahedralSolver::update_nodes(const double dt)
    {
      DiscreteModel &m = model;
      // v_new = a v_old + b / m f, mass damping integrated exactly
      const double a =
        (1. - 0.5 * mass_damping * dt) / (1. + 0.5 * mass_damping * dt);
      const double      damp_b_factor = dt / (1. + 0.5 * mass_damping * dt);
      const double      c_m           = mass_damping;
      const std::size_t n_chunks = (m.n_elements + chunk_size - 1) / chunk_size;
      const std::size_t n_owners = owner_names.size();
      // (no allocation after the first step)
      chunk_works.assign(n_chunks, {{0., 0., 0., 0., 0., 0.}});
      chunk_reaction.assign(n_chunks * n_owners, {{0., 0., 0.}});
      chunk_guard.assign(n_chunks, {{-1, -1}});
      auto &reaction = chunk_reaction;
      // batches of tetrahedra whose nodes are all free
      // (tetrahedral_update.h); nullptr: none
      const TetrahedronBatchKernel batch =
        tetrahedron_batch_kernel(vector_instructions);
      const unsigned int    lanes = vector_lanes(vector_instructions);
      TetrahedronBatchInput batch_input;
      batch_input.lame      = element_lame.data();
      batch_input.viscosity = viscosity.data();
      batch_input.anisotropy =
        element_anisotropy.empty() ? nullptr : element_anisotropy.data();
      batch_input.dt     = dt;
      batch_input.damp_a = a;
      batch_input.damp_b = damp_b_factor;
      batch_input.c_m    = c_m;
      // gravity at the step's start (Gravity ramp time), the physical
      // weight with mass scaling
      const auto  &dm = parameters.get<DiscreteMechanicsParameters>();
      const double g_share =
        (dm.gravity_ramp_time > 0. ? std::min(1., time / dm.gravity_ramp_time) :
                                     1.) /
        dm.mass_scaling_factor;
      const bool gravity_on =
        dm.gravity.size() == 3 &&
        (dm.gravity[0] != 0. || dm.gravity[1] != 0. || dm.gravity[2] != 0.);
      double gravity[3] = {0., 0., 0.};
      if (gravity_on)
        for (unsigned int i = 0; i < 3; ++i)
          gravity[i] = g_share * dm.gravity[i];
      batch_input.with_gravity = gravity_on;
      for (unsigned int i = 0; i < 3; ++i)
        batch_input.gravity[i] = gravity[i];
      for_each_chunk(
        arena_for(n_threads),
        m.n_elements,
        chunk_size,
        [&](const std::size_t begin,
            const std::size_t end,
            const std::size_t c) {
          std::array<double, 6> &w = chunk_works[c];
          for (std::size_t e = begin; e < end; ++e)
            {
              // the batches: free nodes, no contact force
              if (batch != nullptr && e + lanes <= end &&
                  std::all_of(&node_constraint[4 * e],
                              &node_constraint[4 * (e + lanes)],
                              [](const int ci) { return ci < 0; }) &&
                  (!contact ||
                   std::none_of(element_in_contact.data() + e,
                                element_in_contact.data() + e + lanes,
                                [](const char in) { return in != 0; })))
                {
                  batch(m, e, batch_input, w.data(), chunk_guard[c].data());
                  e += lanes - 1;
                  continue;
                }
              const std::size_t   n0       = 4 * e;
              const double *const nodes[3] = {&m.x[n0], &m.y[n0], &m.z[n0]};
              const double *const velocities[3] = {&m.vx[n0],
                                                   &m.vy[n0],
                                                   &m.vz[n0]};
              const double        s             = m.thermal_stretch[e];
              ElementResponse<3, double> r;
              element_response<3, double>(nodes,
                                          velocities,
                                          &m.inverse_basis[9 * e],
                                          s == 1. ? 1. : 1. / s,
                                          element_lame[e].mu,
                                          element_lame[e].lambda,
                                          anisotropy_of(e),
                                          viscosity[e],
                                          r);
              // guards: the first inverted element of the chunk
              if (!(r.det > 0.) && chunk_guard[c][0] < 0)
                chunk_guard[c][0] = e;
              // xx, yy, zz, xy, yz, xz
              double *stress       = &m.stress[6 * e];
              stress[0]            = r.stress[0][0] + r.viscous[0][0];
              stress[1]            = r.stress[1][1] + r.viscous[1][1];
              stress[2]            = r.stress[2][2] + r.viscous[2][2];
              stress[3]            = r.stress[0][1] + r.viscous[0][1];
              stress[4]            = r.stress[1][2] + r.viscous[1][2];
              stress[5]            = r.stress[0][2] + r.viscous[0][2];
              double f_contact[12] = {};
              if (contact && element_in_contact[e])
                contact->add_forces(e, f_contact);
              for (unsigned int k = 0; k < 4; ++k)
                {
                  const std::size_t node = n0 + k;
                  const double     *jf   = &m.node_joint_force[9 * node];
                  const double      mass = m.mass[node];
                  const double      b_m  = damp_b_factor / mass;
                  double   *v[3] = {&m.vx[node], &m.vy[node], &m.vz[node]};
                  double   *x[3] = {&m.x[node], &m.y[node], &m.z[node]};
                  const int ci   = node_constraint[node];
                  for (unsigned int i = 0; i < 3; ++i)
                    {
                      const double f_joint   = jf[i] + jf[3 + i] + jf[6 + i];
                      const double f_gravity = mass * gravity[i];
                      double       f = r.f_elastic[k][i] + r.f_viscous[k][i] +
                                 f_joint + f_contact[3 * k + i];
                      if (gravity_on)
                        f += f_gravity;
                      const double v_old = *v[i];
                      double v_new = damped_velocity<double>(a, v_old, b_m, f);
                      double f_reaction = 0.;
                      if (ci >= 0 && constraints[ci].prescribed[i])
                        {
                          const NodeConstraint &nc = constraints[ci];
                          v_new                    = nc.velocity[i];
                          f_reaction = (v_new - a * v_old) / b_m - f;
                          reaction[c * n_owners + nc.owner][i] += f_reaction;
                        }
                      const double travel =
                        half_step_travel<double>(dt, v_old, v_new);
                      // the reaction's work and gravity's: external work
                      const TetrahedronNodeWorks<double> nw =
                        tetrahedron_node_works<double>(
                          r.f_elastic[k][i],
                          r.f_viscous[k][i],
                          f_joint,
                          gravity_on ? f_reaction + f_gravity : f_reaction,
                          travel,
                          c_m,
                          mass,
                          dt);
                      w[0] += nw.elastic;
                      w[1] += nw.viscous;
                      w[2] += nw.joint;
                      w[3] += nw.reaction;
                      w[4] += nw.damping;
                      w[5] += f_contact[3 * k + i] * travel;
                      *v[i] = v_new;
                      *x[i] += dt * v_new;
                      // guards: the first non-finite velocity of the chunk
                      if (!(std::abs(v_new) < 1e300) && chunk_guard[c][1] < 0)
                        chunk_guard[c][1] = node;
                    }
                }
            }
        });
      // in chunk order: independent of the thread count
      for (auto &r : owner_reaction)
        r = {{0., 0., 0.}};
      for (std::size_t c = 0; c < n_chunks; ++c)
        {
          energies.joint_work -= chunk_works[c][2];
          energies.contact_work -= chunk_works[c][5];
          energies.external_work += chunk_works[c][3];
          energies.damping += -chunk_works[c][1] + chunk_works[c][4];
          for (std::size_t o = 0; o < n_owners; ++o)
            for (unsigned int i = 0; i < 3; ++i)
              owner_reaction[o][i] += reaction[c * n_owners + o][i];
        }
      element_steps += m.n_elements;
      for (std::size_t c = 0; c < n_chunks; ++c)
        {
          if (chunk_guard[c][0] >= 0)
            guard_failure(
              "tetrahedron " + std::to_string(chunk_guard[c][0]) +
              " inverted (det F <= 0); the time step or a penalty is too "
              "large for the loading, or the material too soft");
          if (chunk_guard[c][1] >= 0)
            guard_failure("node " + std::to_string(chunk_guard[c][1]) +
                          " (tetrahedron " +
                          std::to_string(chunk_guard[c][1] / 4) +
                          ") has a non-finite velocity");
        }
    }

    void
    TetrahedralSolver::guard_failure(const std::string &what)
    {
      stop_reason = what;
      write_summary(false);
      throw RunError(
        "discrete mechanics (3D), at t = " + Utilities::to_string(time) +
        " s, step " + std::to_string(step_number + 1) + ": " + what +
        ". The outputs written before are kept; summary.json "
        "says where the run stopped.");
    }

    void
    TetrahedralSolver::step(const double dt)
    {
      if (!with_mechanics())
        {
          heat->step(time, dt);
          time += dt;
          thermal_time = time;
          ++step_number;
          ++n_thermal_steps;
          return;
        }
      if (imposed_depend_on_time)
        evaluate_imposed_velocities(time + 0.5 * dt);
      evaluate_imposed_displacements(time + dt, dt);
      if (compute_joint_forces() && contact)
        {
          contact->update_active_elements(model);
          contact->request_search();
        }
      if (contact)
        compute_contact_forces(dt);
      update_nodes(dt);
      time += dt;
      ++step_number;
      if (heat && !quasi_static && step_number % steps_per_thermal_step == 0)
        thermal_step(); // coupling/tetrahedral_thermo_mechanics.cc
    }

    double
    TetrahedralSolver::element_strain_energy(const unsigned int e,
                                             const double       s) const
    {
      const double *const nodes[3] = {&model.x[4 * e],
                                      &model.y[4 * e],
                                      &model.z[4 * e]};
      double              F[3][3];
      times_inverse_basis<3>(nodes, &model.inverse_basis[9 * e], F);
      for (auto &row : F)
        for (double &f : row)
          f /= s;
      double psi = constitutive::strain_energy_density<3>(F, element_lame[e]);
      if (const double *c = anisotropy_of(e))
        psi += anisotropic_energy_density<3>(F, c);
      return model.reference_area[e] * s * s * s * psi;
    }

    void
    TetrahedralSolver::compute_state_energies()
    {
      if (!with_mechanics())
        return;
      const DiscreteModel &m = model;
      // per chunk of elements, summed in chunk order: the same on any
      // number of threads (the kinetic energy per chunk of their nodes)
      const std::size_t n_chunks = (m.n_elements + chunk_size - 1) / chunk_size;
      chunk_strain.assign(n_chunks, 0.);
      for_each_chunk(arena_for(n_threads),
                     m.n_elements,
                     chunk_size,
                     [&](const std::size_t begin,
                         const std::size_t end,
                         const std::size_t c) {
                       double strain = 0.;
                       for (std::size_t e = begin; e < end; ++e)
                         strain +=
                           element_strain_energy(e, m.thermal_stretch[e]);
                       chunk_strain[c] = strain;
                     });
      double strain = 0.;
      for (const double c : chunk_strain)
        strain += c;
      energies.kinetic = kinetic_energy();
      energies.strain  = strain;
    }

    void
    TetrahedralSolver::write_output()
    {
      if (!parameters.output.write_vtu)
        return;
      const VtuEncoding encoding = vtu_encoding(parameters.output);
      std::vector<std::pair<std::string, const std::vector<double> *>> fields;
      if (heat)
        fields.emplace_back("T", &heat->temperature());
      solution_series->write(time,
                             discrete_solution_vtu(model, encoding, fields));
      if (with_mechanics())
        crack_series->write(time, crack_vtu(model, encoding));
    }

    void
    TetrahedralSolver::write_history_row()
    {
      compute_state_energies();
      const double factor = parameters.guards.kinetic_energy_factor;
      if (factor > 0. &&
          energies.kinetic > factor * std::max(energy_put_in(), 1e-300))
        guard_failure("the kinetic energy " +
                      Utilities::to_string(energies.kinetic) + " J exceeds " +
                      Utilities::to_string(factor) +
                      " times the energy put in (Guards/Kinetic energy "
                      "factor): the run is unstable");
      history_step = step_number;
      std::ostringstream row;
      row << std::setprecision(10) << time << "," << step_number;
      if (with_mechanics())
        {
          row << "," << energies.kinetic << "," << energies.strain << ","
              << energies.joint_work << "," << energies.damping << ","
              << energies.external_work << ",";
          if (contact)
            row << energies.contact_work << "," << energies.friction << ",";
          if (heat)
            row << energies.thermal_work << ",";
          row << energy_balance_error() << "," << model.n_damaged_joints()
              << "," << model.n_broken_joints();
          for (const auto &r : owner_reaction)
            row << "," << r[0] << "," << r[1] << "," << r[2];
          // free bodies: the displacement of their centre of mass
          const auto &bodies = parameters.get<DiscreteBodyParameters>().bodies;
          for (unsigned int b = 0; b < bodies.size(); ++b)
            if (bodies[b].motion == DiscreteBody::Motion::free)
              {
                double mass = 0., moment[3] = {0., 0., 0.};
                for (unsigned int e = 0; e < model.n_elements; ++e)
                  if (model.body[e] == b)
                    for (unsigned int n = 4 * e; n < 4 * e + 4; ++n)
                      {
                        mass += model.mass[n];
                        moment[0] +=
                          model.mass[n] * (model.x[n] - model.x_ref[n]);
                        moment[1] +=
                          model.mass[n] * (model.y[n] - model.y_ref[n]);
                        moment[2] +=
                          model.mass[n] * (model.z[n] - model.z_ref[n]);
                      }
                for (const double m : moment)
                  row << "," << (mass > 0. ? m / mass : 0.);
              }
        }
      if (heat)
        {
          const std::vector<double> &T = heat->temperature();
          const auto [T_min, T_max] = std::minmax_element(T.begin(), T.end());
          row << "," << *T_min << "," << *T_max << ","
              << heat->balance().stored_heat << ","
              << heat->balance().imbalance();
        }
      row << "\n";
      history_csv->append(row.str());
    }

    void
    TetrahedralSolver::write_summary(const bool finished) const
    {
      JsonObject summary;
      summary.add("model",
                  std::string(physics == Physics::mechanics ?
                                "discrete mechanics" :
                                (physics == Physics::heat ?
                                   "discrete heat" :
                                   "discrete thermo-mechanics")));
      summary.add("dimension", 3u);
      summary.add("finished", finished);
      if (!stop_reason.empty())
        summary.add("stop_reason", stop_reason);
      summary.add("time", time);
      summary.add("steps", static_cast<long long>(step_number));
      summary.add("time_step", time_step);
      summary.add("stable_time_step", stable_time_step);
      summary.add("elements", model.n_elements);
      summary.add("nodes", model.n_nodes);
      summary.add("joints", model.n_joints);
      summary.add("broken_joints", model.n_broken_joints());
      summary.add("damaged_joints", model.n_damaged_joints());
      if (with_mechanics())
        {
          // sum m v and sum m x cross v over the nodes (x at the step, v at
          // its half step: what the central differences keep exactly when
          // the internal forces sum to zero and exert no torque)
          double momentum[3] = {0., 0., 0.}, angular[3] = {0., 0., 0.};
          for (unsigned int n = 0; n < model.n_nodes; ++n)
            {
              const double m    = model.mass[n];
              const double x[3] = {model.x[n], model.y[n], model.z[n]};
              const double v[3] = {model.vx[n], model.vy[n], model.vz[n]};
              for (unsigned int i = 0; i < 3; ++i)
                {
                  const unsigned int j = (i + 1) % 3, k = (i + 2) % 3;
                  momentum[i] += m * v[i];
                  angular[i] += m * (x[j] * v[k] - x[k] * v[j]);
                }
            }
          summary.add("momentum_x", momentum[0]);
          summary.add("momentum_y", momentum[1]);
          summary.add("momentum_z", momentum[2]);
          summary.add("angular_momentum_x", angular[0]);
          summary.add("angular_momentum_y", angular[1]);
          summary.add("angular_momentum_z", angular[2]);
        }
      unsigned int modes[4]   = {0, 0, 0, 0};
      double       crack_area = 0.;
      for (unsigned int j = 0; j < model.n_joints; ++j)
        {
          ++modes[static_cast<int>(model.joint_status[j])];
          if (model.joint_status[j] != JointStatus::intact)
            crack_area += model.joint_area[j];
        }
      summary.add("broken_mode_I", modes[1]);
      summary.add("broken_mode_II", modes[2]);
      summary.add("broken_mixed", modes[3]);
      summary.add("cracks", model.n_cracks());
      summary.add("joint_compliance_compensation",
                  parameters.get<DiscreteMechanicsParameters>()
                    .joint_compliance_compensation);
      summary.add("anisotropic_compensation", !element_anisotropy.empty());
      summary.add("compensation_capped_elements", compensation_capped);
      summary.add("compensation_largest_share", compensation_share);
      summary.add("crack_area", crack_area);
      JsonObject energy;
      energy.add("initial_kinetic", initial_kinetic);
      energy.add("kinetic", energies.kinetic);
      energy.add("strain", energies.strain);
      energy.add("joint_work", energies.joint_work);
      energy.add("damping", energies.damping);
      energy.add("external_work", energies.external_work);
      energy.add("thermal_work", energies.thermal_work);
      energy.add("relaxation_work", energies.relaxation_work);
      if (contact)
        {
          energy.add("contact_work", energies.contact_work);
          energy.add("contact_penalty",
                     energies.contact_work - energies.friction);
          // what the overlaps of the current pairs hold (the penalty work
          // less the energy the faces of joints broken in compression took
          // over, and the O(dt^2) error of the work)
          energy.add("contact_stored",
                     contact->stored_energy(model, arena_for(n_threads)));
          // what the faces of joints broken in compression brought in
          energy.add("contact_handed_over", contact->handed_over_energy());
          energy.add("friction_dissipation", energies.friction);
        }
      energy.add("balance_error", energy_balance_error());
      summary.add("energy", energy);
      if (with_mechanics())
        summary.add("contact", contact != nullptr);
      if (contact)
        {
          summary.add("contact_searches",
                      static_cast<long long>(contact->n_searches()));
          summary.add("contact_pairs", contact->n_mechanical_pairs());
        }
      if (heat)
        {
          const auto &dh = parameters.get<DiscreteHeatParameters>();
          summary.add("time_integration", dh.time_integration_name());
          summary.add("thermal_time", thermal_time);
          summary.add("thermal_steps", static_cast<long long>(n_thermal_steps));
          summary.add("mechanical_steps_per_thermal_step",
                      static_cast<long long>(steps_per_thermal_step));
          summary.add("stable_explicit_thermal_step", heat->stable_time_step());
          summary.add("cg_iterations_last_step", heat->last_iterations());
          summary.add("contact_heat_model",
                      contact_heat_model_name(dh.contact_heat_model));
          summary.add("contact_heat_pairs",
                      static_cast<long long>(heat->n_contact_pairs()));
          summary.add("coupling", dh.coupling_name());
          if (quasi_static)
            {
              summary.add("relaxations_at_cap", relaxation.relaxations_at_cap);
              summary.add("rejected_thermal_steps",
                          static_cast<long long>(
                            relaxation.rejected_thermal_steps));
              summary.add("unstable_thermal_steps",
                          static_cast<long long>(
                            relaxation.unstable_thermal_steps));
              summary.add("last_relaxation_steps",
                          relaxation.last_relaxation_steps);
              summary.add("last_kinetic_to_strain_energy",
                          relaxation.last_kinetic_to_strain);
              summary.add("last_relative_unbalanced_force",
                          relative_unbalanced_force);
              summary.add("velocity_resets",
                          static_cast<long long>(relaxation.velocity_resets));
              summary.add("predicted_relaxations",
                          relaxation.predicted_relaxations);
              summary.add("fracture_events",
                          static_cast<long long>(relaxation.fracture_events));
              summary.add("fracture_event_steps",
                          static_cast<long long>(
                            relaxation.fracture_event_steps));
            }
          summary.add("heat_balance",
                      heat_balance_summary(heat->balance(),
                                           heat->last_boundary_rate()));
        }
      summary.add("threads", n_threads);
      summary.add("threads_requested", threads_requested);
      summary.add("threads_available", threads_available);
      summary.add("threads_used", threads_used);
      summary.add("wall_time_s", loop_wall_time);
      summary.add("cpu_time_s", loop_cpu_time);
      summary.add("cpu_time_busiest_thread_s",
                  loop_thread_cpu_times.empty() ? 0. :
                                                  loop_thread_cpu_times[0]);
      double others = 0.;
      for (std::size_t i = 1; i < loop_thread_cpu_times.size(); ++i)
        others += loop_thread_cpu_times[i];
      summary.add("cpu_time_other_threads_s", others);
      summary.add("element_steps_per_second",
                  loop_wall_time > 0. ? element_steps / loop_wall_time : 0.);
      write_file_atomically(parameters.output.directory + "/summary.json",
                            summary.str());
    }

    std::string
    TetrahedralSolver::checkpoint_kind() const
    {
      return std::string(physics == Physics::mechanics ?
                           "discrete mechanics" :
                           (physics == Physics::heat ?
                              "discrete heat" :
                              "discrete thermo-mechanics")) +
             " (3D)";
    }

    void
    TetrahedralSolver::write_checkpoint_file() const
    {
      CheckpointWriter out(checkpoint_kind(), parameters.input_digest);
      out.put<std::uint32_t>(model.n_elements);
      out.put<std::uint32_t>(model.n_nodes);
      out.put<std::uint32_t>(model.n_joints);
      out.put(time_step);
      put_state(out);
      out.put(next_output);
      out.put(next_history);
      out.put(history_interval);
      out.put(history_step);
      out.put(output_times);
      solution_series->save_records(out);
      crack_series->save_records(out);
      out.put<std::uint64_t>(history_csv->size());
      out.put(initial_kinetic);
      out.put(element_steps);
      const std::size_t bytes = write_checkpoint(parameters, step_number, out);
      std::cerr << "[tmfdem] checkpoint at step " << step_number
                << ", t = " << time << " s: " << bytes << " bytes\n";
    }

    std::uint64_t
    TetrahedralSolver::load_checkpoint()
    {
      const std::string file = newest_checkpoint(parameters);
      CheckpointReader  in(file, checkpoint_kind(), parameters.input_digest);
      std::uint32_t     sizes[3];
      for (auto &n : sizes)
        in.get(n);
      if (sizes[0] != model.n_elements || sizes[1] != model.n_nodes ||
          sizes[2] != model.n_joints)
        throw InputError("the checkpoint '" + file + "' is of another mesh (" +
                         std::to_string(sizes[0]) + " tetrahedra, this run " +
                         std::to_string(model.n_elements) + ").");
      double saved_time_step = 0.;
      in.get(saved_time_step);
      if (saved_time_step != time_step)
        throw InputError("the checkpoint '" + file + "' has the time step " +
                         Utilities::to_string(saved_time_step) +
                         " s, this run " + Utilities::to_string(time_step) +
                         " s.");
      get_state(in);
      in.get(next_output);
      in.get(next_history);
      in.get(history_interval);
      in.get(history_step);
      std::vector<double> saved_output_times;
      in.get(saved_output_times);
      if (next_output > saved_output_times.size())
        throw InputError("the checkpoint '" + file +
                         "' is corrupt (output counter).");
      // End time may have changed (a run continued): this input's output
      // times from the next unwritten one on
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
      std::uint64_t history_bytes    = 0;
      in.get(history_bytes);
      in.get(initial_kinetic);
      in.get(element_steps);
      in.finish();
      if (parameters.output.write_vtu)
        {
          solution_series->restore(solution_records, true);
          crack_series->restore(crack_records, true);
        }
      std::cerr << "[tmfdem] resumed from " << file << ": step " << step_number
                << ", t = " << time << " s\n";
      return history_bytes;
    }

    void
    TetrahedralSolver::after_step(CheckpointSchedule &schedule)
    {
      if (schedule.active() && schedule.due(step_number))
        {
          write_checkpoint_file();
          schedule.written(step_number);
        }
      if (!stop_requested())
        return;
      const std::string signal = stop_signal_name();
      std::cerr << "[tmfdem] " << signal
                << ": finishing the step, writing a checkpoint and the "
                   "outputs\n";
      write_checkpoint_file();
      compute_state_energies();
      stop_reason = "stopped by " + signal;
      write_summary(false);
      throw StopRequested(
        "stopped by " + signal + " at t = " + Utilities::to_string(time) +
        " s after step " + std::to_string(step_number) + "; checkpoint in " +
        checkpoint_folder(parameters) + ", outputs so far in " +
        parameters.output.directory + ". Continue with: tmfdem " +
        parameters.prm_file + " --resume (and the same --set options).");
    }

    void
    TetrahedralSolver::run()
    {
      if (!input_checked)
        check_input();
      const double start = parameters.time.start_time;
      const double end   = parameters.time.end_time;
      time               = start;
      const OutputSchedule schedule(parameters.output, start, end);
      output_times = schedule.times();
      solution_series =
        std::make_unique<VtuSeries>(parameters.output.directory, "solution");
      crack_series =
        std::make_unique<VtuSeries>(parameters.output.directory, "cracks");
      std::string header = "time,step";
      if (with_mechanics())
        {
          header += ",kinetic,strain,joint_work,damping,external_work,";
          if (contact)
            header += "contact_work,friction_dissipation,";
          if (heat)
            header += "thermal_work,";
          header += "balance_error,damaged_joints,broken_joints";
          for (const auto &name : owner_names)
            header += "," + name + "_fx," + name + "_fy," + name + "_fz";
          for (const auto &body :
               parameters.get<DiscreteBodyParameters>().bodies)
            if (body.motion == DiscreteBody::Motion::free)
              {
                const std::string name = "body" + std::to_string(body.number);
                header += "," + name + "_ux," + name + "_uy," + name + "_uz";
              }
        }
      if (heat)
        header += ",T_min,T_max,stored_heat,heat_imbalance";
      const auto         &dm = parameters.get<DiscreteMechanicsParameters>();
      const unsigned long max_steps = dm.max_steps;
      history_interval              = (end - start) / 1000.;
      next_history                  = start;
      if (parameters.resume)
        {
          // the state, the output counters and series of the newest
          // checkpoint; history.csv cut to its length then
          const std::uint64_t history_bytes = load_checkpoint();
          history_csv                       = std::make_unique<CsvSeries>(
            CsvSeries::reopen(parameters.output.directory + "/history.csv",
                              history_bytes,
                              communicator));
        }
      else
        {
          history_csv =
            std::make_unique<CsvSeries>(parameters.output.directory +
                                          "/history.csv",
                                        header,
                                        communicator);
          compute_state_energies();
          initial_kinetic = energies.kinetic;
          if (contact)
            check_contact_overlap(true); // tetrahedral_solver_contact.cc
          write_output();
          write_history_row();
          next_history += history_interval;
        }
      CheckpointSchedule checkpoints(parameters.checkpoint);
      checkpoints.written(step_number);
      ProgressReporter progress(parameters.output.progress_interval,
                                start,
                                end,
                                true);
      const auto       wall_start     = std::chrono::steady_clock::now();
      const double     cpu_start      = process_cpu_time();
      const auto       threads_before = thread_cpu_times();
      // the steps land on the output times (OutputSchedule::step_towards())
      while (next_output < output_times.size())
        {
          if (max_steps > 0 && step_number >= max_steps)
            break;
          if (quasi_static)
            quasi_static_step(); // coupling/tetrahedral_thermo_mechanics.cc
          else
            step(OutputSchedule::step_towards(time,
                                              output_times[next_output],
                                              time_step));
          // quasi-static: a row after every thermal step
          if (quasi_static || time >= next_history - 0.5 * time_step)
            {
              write_history_row();
              next_history += history_interval;
              while (history_interval > 0. && next_history <= time)
                next_history += history_interval;
            }
          while (next_output < output_times.size() &&
                 schedule.reached(time, output_times[next_output]))
            {
              time = output_times[next_output];
              // the temperatures at the output time too
              if (heat)
                thermal_step();
              write_output();
              ++next_output;
            }
          progress.update(step_number, time);
          after_step(checkpoints);
        }
      loop_wall_time = std::chrono::duration<double>(
                         std::chrono::steady_clock::now() - wall_start)
                         .count();
      loop_cpu_time = process_cpu_time() - cpu_start;
      loop_thread_cpu_times =
        thread_cpu_time_differences(threads_before, thread_cpu_times());
      // the last state, unless the loop's last row holds it
      if (step_number != history_step)
        write_history_row();
      write_summary(true);
      if (parameters.output.write_final_mesh)
        write_file_atomically(parameters.output.directory + "/final_mesh.msh",
                              deformed_mesh_msh(model));
    }
  } // namespace discrete
} // namespace tmfdem
