#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_fe.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/error_estimator.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <regex>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>
#include <tmfdem/continuum/adaptivity.h>
#include <tmfdem/continuum/heat_solver.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/monitors.h>
#include <tmfdem/io/output_files.h>
#include <tmfdem/mesh/mesh_checks.h>
#include <tmfdem/mesh/mesh_generator.h>

namespace tmfdem
{
  namespace
  {
    const bool registered = register_simulation(
      "continuum heat",
      "transient or steady heat conduction with deal.II (theta scheme, AMR "
      "on quadrilaterals, MPI)",
      [](const Parameters &parameters, MPI_Comm communicator) {
        return std::make_unique<HeatSolver>(parameters, communicator);
      });

    /** Does @p expression use the variable t? */
    bool
    depends_on_time(const std::string &expression)
    {
      static const std::regex time_variable(
        "(^|[^A-Za-z0-9_])t([^A-Za-z0-9_]|$)");
      return std::regex_search(expression, time_variable);
    }
  } // namespace

  HeatSolver::HeatSolver(const Parameters &parameters, MPI_Comm communicator)
    : parameters(parameters)
    , communicator(communicator)
    , theta(parameters.time.theta)
  {
    for (unsigned int id = 0; id < MaterialParameters::max_materials; ++id)
      {
        const std::string expression =
          parameters.materials.materials[id].heat_source;
        heat_sources.push_back(
          make_expression_function(expression,
                                   "Materials/Material " + std::to_string(id) +
                                     "/Volumetric heat source"));
        if (Utilities::trim(expression) != "0")
          any_heat_source = true;
        time_dependent_source.push_back(depends_on_time(expression));
        any_time_dependent_load |= time_dependent_source.back();
      }
    for (const auto &condition : parameters.thermal_boundary.conditions)
      {
        BoundaryFunctions functions;
        functions.temperature =
          make_expression_function(condition.temperature,
                                   condition.name + "/Temperature");
        functions.heat_flux =
          make_expression_function(condition.heat_flux,
                                   condition.name + "/Heat flux");
        functions.heat_transfer_coefficient =
          make_expression_function(condition.heat_transfer_coefficient,
                                   condition.name +
                                     "/Heat transfer coefficient");
        functions.ambient_temperature =
          make_expression_function(condition.ambient_temperature,
                                   condition.name + "/Ambient temperature");
        functions.time_dependent_coefficient =
          condition.type == ThermalBoundaryCondition::Type::robin &&
          depends_on_time(condition.heat_transfer_coefficient);
        functions.time_dependent_temperature =
          condition.type == ThermalBoundaryCondition::Type::dirichlet &&
          depends_on_time(condition.temperature);
        functions.time_dependent_load =
          (condition.type == ThermalBoundaryCondition::Type::neumann &&
           depends_on_time(condition.heat_flux)) ||
          (condition.type == ThermalBoundaryCondition::Type::robin &&
           (depends_on_time(condition.heat_transfer_coefficient) ||
            depends_on_time(condition.ambient_temperature)));
        any_time_dependent_load |= functions.time_dependent_load;
        time_dependent_robin |= functions.time_dependent_coefficient;
        for (const auto id : condition.boundary_ids)
          condition_of[id] = boundary_functions.size();
        boundary_functions.push_back(std::move(functions));
      }
    initial_temperature =
      make_expression_function(parameters.initial.temperature,
                               "Initial conditions/Temperature");
  }

  HeatSolver::~HeatSolver()
  {
    if (dof_handler)
      dof_handler->clear();
  }

  bool
  HeatSolver::uses_quadrilaterals() const
  {
    return mesh_report->n_quadrilaterals > 0;
  }

  const DoFHandler<2> &
  HeatSolver::get_dof_handler() const
  {
    return *dof_handler;
  }

  const Mapping<2> &
  HeatSolver::get_mapping() const
  {
    return *mapping;
  }

  const TrilinosWrappers::MPI::Vector &
  HeatSolver::get_temperature() const
  {
    return solution;
  }

  parallel::TriangulationBase<2> &
  HeatSolver::get_triangulation()
  {
    return *triangulation;
  }

  void
  HeatSolver::set_output_hook(
    const std::function<void(const double time)> &hook)
  {
    output_hook = hook;
  }

  double
  HeatSolver::memory_estimate() const
  {
    const double n = fe->n_dofs_per_cell();
    return 2. * system_matrix.memory_consumption() +
           capacity_matrix.memory_consumption() +
           conduction_matrix.memory_consumption() +
           robin_matrix.memory_consumption() +
           triangulation->n_locally_owned_active_cells() * 2. * n * n *
             sizeof(double) +
           16. * locally_owned_dofs.n_elements() * sizeof(double) +
           dof_handler->memory_consumption();
  }

  // ------------------------------------------------------------------ mesh
  void
  HeatSolver::make_mesh()
  {
    create_output_folder(parameters.output.directory, communicator);
    mesh_report   = std::make_unique<MeshReport>();
    triangulation = create_continuum_triangulation(parameters.mesh,
                                                   parameters.output.directory,
                                                   communicator,
                                                   *mesh_report);
    coarse_level  = parameters.mesh.global_refinements;

    const unsigned int degree = parameters.heat_solver.degree;
    if (uses_quadrilaterals())
      {
        fe      = std::make_unique<FE_Q<2>>(degree);
        mapping = std::make_unique<MappingQ<2>>(degree);
      }
    else
      {
        fe      = std::make_unique<FE_SimplexP<2>>(degree);
        mapping = std::make_unique<MappingFE<2>>(FE_SimplexP<2>(1));
      }
    dof_handler = std::make_unique<DoFHandler<2>>(*triangulation);
    check_boundary_ids_and_materials();
  }

  void
  HeatSolver::check_boundary_ids_and_materials() const
  {
    std::string mesh_ids;
    for (const auto id : mesh_report->boundary_ids)
      mesh_ids += " " + std::to_string(id);
    for (const auto &condition : parameters.thermal_boundary.conditions)
      for (const auto id : condition.boundary_ids)
        if (mesh_report->boundary_ids.count(id) == 0)
          throw InputError(condition.name + "/Boundary ids: boundary id " +
                           std::to_string(id) +
                           " is not on the mesh; the mesh has boundary ids" +
                           mesh_ids + ".");
    for (const auto id : mesh_report->material_ids)
      parameters.materials[id]; // throws for ids without a subsection
    if (parameters.adaptivity.enable && !uses_quadrilaterals())
      throw InputError(
        "Adaptive refinement/Enable = true needs a quadrilateral mesh: "
        "deal.II 9.4.1 cannot coarsen triangles and its Kelly estimator fails "
        "on triangle meshes with hanging nodes. Set Mesh/Element type = "
        "quadrilaterals, or use Mesh/Global refinements on triangles.");
  }

  // ------------------------------------------------------------ set up
  void
  HeatSolver::setup_dofs()
  {
    dof_handler->distribute_dofs(*fe);
    locally_owned_dofs = dof_handler->locally_owned_dofs();
    DoFTools::extract_locally_relevant_dofs(*dof_handler,
                                            locally_relevant_dofs);

    dirichlet_dof_ids.clear();
    for (const auto &condition : parameters.thermal_boundary.conditions)
      if (condition.type == ThermalBoundaryCondition::Type::dirichlet)
        for (const auto id : condition.boundary_ids)
          {
            const IndexSet dofs =
              DoFTools::extract_boundary_dofs(*dof_handler,
                                              ComponentMask(),
                                              {id});
            for (const auto dof : dofs)
              dirichlet_dof_ids.emplace(dof, id);
          }

    make_constraints(parameters.time.start_time);

    DynamicSparsityPattern sparsity(locally_relevant_dofs);
    DoFTools::make_sparsity_pattern(*dof_handler, sparsity, constraints, false);
    SparsityTools::distribute_sparsity_pattern(sparsity,
                                               locally_owned_dofs,
                                               communicator,
                                               locally_relevant_dofs);
    system_matrix.reinit(locally_owned_dofs,
                         locally_owned_dofs,
                         sparsity,
                         communicator);
    system_rhs.reinit(locally_owned_dofs, communicator);
    solution.reinit(locally_owned_dofs, locally_relevant_dofs, communicator);
    preconditioner.reset();

    // the right-hand side as products of assembled matrices and vectors
    owned_dirichlet_dofs.clear();
    for (const auto &[dof, id] : dirichlet_dof_ids)
      if (locally_owned_dofs.is_element(dof))
        owned_dirichlet_dofs.emplace_back(dof, id);
    homogeneous_constraints.clear();
    homogeneous_constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(*dof_handler,
                                            homogeneous_constraints);
    for (const auto &condition : parameters.thermal_boundary.conditions)
      if (condition.type == ThermalBoundaryCondition::Type::dirichlet)
        for (const auto id : condition.boundary_ids)
          DoFTools::make_zero_boundary_constraints(*dof_handler,
                                                   id,
                                                   homogeneous_constraints);
    homogeneous_constraints.close();

    DynamicSparsityPattern full_sparsity(locally_relevant_dofs);
    DoFTools::make_sparsity_pattern(*dof_handler, full_sparsity);
    SparsityTools::distribute_sparsity_pattern(full_sparsity,
                                               locally_owned_dofs,
                                               communicator,
                                               locally_relevant_dofs);
    capacity_matrix.reinit(locally_owned_dofs,
                           locally_owned_dofs,
                           full_sparsity,
                           communicator);
    conduction_matrix.reinit(locally_owned_dofs,
                             locally_owned_dofs,
                             full_sparsity,
                             communicator);
    if (time_dependent_robin)
      robin_matrix.reinit(locally_owned_dofs,
                          locally_owned_dofs,
                          full_sparsity,
                          communicator);
    for (auto *vector : {&capacity_row_sums,
                         &full_rhs,
                         &lifting,
                         &owned_solution,
                         &owned_old_solution,
                         &work,
                         &constant_loads.vector,
                         &variable_loads[0].vector,
                         &variable_loads[1].vector})
      vector->reinit(locally_owned_dofs, communicator);
    full_rhs_ghosted.reinit(locally_owned_dofs,
                            locally_relevant_dofs,
                            communicator);
    for (auto &level : variable_loads)
      level.valid = false;
    reaction_rows.clear();
    reaction_columns.clear();
    reaction_values.clear();
  }

  void
  HeatSolver::make_constraints(const double time)
  {
    constraints.clear();
    constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(*dof_handler, constraints);
    for (unsigned int c = 0; c < parameters.thermal_boundary.conditions.size();
         ++c)
      {
        const auto &condition = parameters.thermal_boundary.conditions[c];
        if (condition.type != ThermalBoundaryCondition::Type::dirichlet)
          continue;
        auto &temperature = *boundary_functions[c].temperature;
        temperature.set_time(time);
        for (const auto id : condition.boundary_ids)
          VectorTools::interpolate_boundary_values(*mapping,
                                                   *dof_handler,
                                                   id,
                                                   temperature,
                                                   constraints);
      }
    constraints.close();
  }

  void
  HeatSolver::compute_cell_matrices()
  {
    const unsigned int  n = fe->n_dofs_per_cell();
    const Quadrature<2> quadrature =
      uses_quadrilaterals() ? Quadrature<2>(QGauss<2>(fe->degree + 1)) :
                              Quadrature<2>(QGaussSimplex<2>(fe->degree + 1));
    FEValues<2>        fe_values(*mapping,
                          *fe,
                          quadrature,
                          update_values | update_gradients | update_JxW_values);
    const unsigned int n_cells = triangulation->n_active_cells();
    cell_capacity.assign(n_cells, FullMatrix<double>());
    cell_conductivity.assign(n_cells, FullMatrix<double>());
    capacity_matrix   = 0;
    conduction_matrix = 0;
    std::vector<types::global_dof_index> dof_indices(n);
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          const auto  &material = parameters.materials[cell->material_id()];
          const double rho_c    = material.density * material.specific_heat;
          const double k        = material.thermal_conductivity;
          // anisotropic (paper Eqs. 8-9): grad phi_i . K grad phi_j; the
          // isotropic product below is kept as it was (bitwise results)
          const bool         anisotropic = material.anisotropic_conductivity;
          const Tensor<2, 2> K           = material.conductivity_tensor();
          fe_values.reinit(cell);
          FullMatrix<double> capacity(n, n), conductivity(n, n);
          for (const unsigned int q : fe_values.quadrature_point_indices())
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                {
                  capacity(i, j) += rho_c * fe_values.shape_value(i, q) *
                                    fe_values.shape_value(j, q) *
                                    fe_values.JxW(q);
                  if (anisotropic)
                    conductivity(i, j) += fe_values.shape_grad(i, q) *
                                          (K * fe_values.shape_grad(j, q)) *
                                          fe_values.JxW(q);
                  else
                    conductivity(i, j) += k * fe_values.shape_grad(i, q) *
                                          fe_values.shape_grad(j, q) *
                                          fe_values.JxW(q);
                }
          cell->get_dof_indices(dof_indices);
          capacity_matrix.add(dof_indices, capacity);
          conduction_matrix.add(dof_indices, conductivity);
          cell_capacity[cell->active_cell_index()]     = capacity;
          cell_conductivity[cell->active_cell_index()] = conductivity;
        }

    // Robin matrix and weights: into K once where h does not depend on t
    robin_weights.clear();
    robin_weights_new.clear();
    if (!time_dependent_robin)
      {
        const QGauss<1>    face_quadrature(fe->degree + 1);
        FEFaceValues<2>    fe_face_values(*mapping,
                                       *fe,
                                       face_quadrature,
                                       update_values | update_JxW_values |
                                         update_quadrature_points);
        FullMatrix<double> robin(n, n);
        for (const auto &cell : dof_handler->active_cell_iterators())
          if (cell->is_locally_owned())
            for (const unsigned int f : cell->face_indices())
              {
                if (!cell->at_boundary(f))
                  continue;
                const auto condition =
                  condition_of.find(cell->face(f)->boundary_id());
                if (condition == condition_of.end() ||
                    parameters.thermal_boundary.conditions[condition->second]
                        .type != ThermalBoundaryCondition::Type::robin)
                  continue;
                robin_face_matrix(cell,
                                  f,
                                  boundary_functions[condition->second],
                                  parameters.time.start_time,
                                  1.,
                                  fe_face_values,
                                  robin);
                cell->get_dof_indices(dof_indices);
                conduction_matrix.add(dof_indices, robin);
                auto weights = robin_weights.find(cell->face(f)->boundary_id());
                if (weights == robin_weights.end())
                  weights =
                    robin_weights
                      .emplace(cell->face(f)->boundary_id(),
                               RobinWeights(locally_owned_dofs, communicator))
                      .first;
                Vector<double> row_sums(n);
                for (unsigned int i = 0; i < n; ++i)
                  for (unsigned int j = 0; j < n; ++j)
                    row_sums(i) += robin(i, j);
                weights->second.add(dof_indices, row_sums);
              }
        // every Robin id on every process, for the collective compress
        for (const auto &[id, c] : condition_of)
          if (parameters.thermal_boundary.conditions[c].type ==
                ThermalBoundaryCondition::Type::robin &&
              robin_weights.count(id) == 0)
            robin_weights.emplace(id,
                                  RobinWeights(locally_owned_dofs,
                                               communicator));
        for (auto &[id, weights] : robin_weights)
          weights.compress(VectorOperation::add);
      }
    capacity_matrix.compress(VectorOperation::add);
    conduction_matrix.compress(VectorOperation::add);

    // M 1: row sums of the capacity matrix
    work = 1.;
    capacity_matrix.vmult(capacity_row_sums, work);

    assemble_loads(parameters.time.start_time, false, constant_loads);
    for (auto &level : variable_loads)
      level.valid = false;
  }

  void
  HeatSolver::robin_face_matrix(const DoFHandler<2>::active_cell_iterator &cell,
                                const unsigned int                         face,
                                const BoundaryFunctions &functions,
                                const double             time,
                                const double             weight,
                                FEFaceValues<2>         &fe_face_values,
                                FullMatrix<double>      &matrix) const
  {
    const unsigned int n = fe->n_dofs_per_cell();
    fe_face_values.reinit(cell, face);
    matrix = 0;
    functions.heat_transfer_coefficient->set_time(time);
    for (const unsigned int q : fe_face_values.quadrature_point_indices())
      {
        const double h = functions.heat_transfer_coefficient->value(
          fe_face_values.quadrature_point(q));
        for (unsigned int i = 0; i < n; ++i)
          for (unsigned int j = 0; j < n; ++j)
            matrix(i, j) += weight * h * fe_face_values.shape_value(i, q) *
                            fe_face_values.shape_value(j, q) *
                            fe_face_values.JxW(q);
      }
  }

  void
  HeatSolver::assemble_loads(const double time,
                             const bool   time_dependent,
                             Loads       &level)
  {
    const unsigned int  n = fe->n_dofs_per_cell();
    const Quadrature<2> quadrature =
      uses_quadrilaterals() ? Quadrature<2>(QGauss<2>(fe->degree + 1)) :
                              Quadrature<2>(QGaussSimplex<2>(fe->degree + 1));
    const QGauss<1> face_quadrature(fe->degree + 1);
    FEValues<2>     fe_values(*mapping,
                          *fe,
                          quadrature,
                          update_values | update_quadrature_points |
                            update_JxW_values);
    FEFaceValues<2> fe_face_values(*mapping,
                                   *fe,
                                   face_quadrature,
                                   update_values | update_quadrature_points |
                                     update_JxW_values);
    level.vector = 0;
    level.time   = time;
    level.valid  = true;
    level.source = 0.;
    level.boundary.clear();

    bool any_source = false;
    for (unsigned int m = 0; m < time_dependent_source.size(); ++m)
      any_source |=
        (time_dependent_source[m] == time_dependent) &&
        Utilities::trim(parameters.materials.materials[m].heat_source) != "0";
    for (auto &source : heat_sources)
      source->set_time(time);
    for (auto &functions : boundary_functions)
      {
        functions.heat_flux->set_time(time);
        functions.heat_transfer_coefficient->set_time(time);
        functions.ambient_temperature->set_time(time);
      }

    Vector<double>                       local(n);
    std::vector<types::global_dof_index> dof_indices(n);
    for (const auto &cell : dof_handler->active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        local        = 0;
        bool touched = false;
        if (any_source &&
            time_dependent_source[cell->material_id()] == time_dependent)
          {
            auto &source = *heat_sources[cell->material_id()];
            fe_values.reinit(cell);
            for (const unsigned int q : fe_values.quadrature_point_indices())
              {
                const double heat =
                  source.value(fe_values.quadrature_point(q)) *
                  fe_values.JxW(q);
                level.source += heat;
                for (unsigned int i = 0; i < n; ++i)
                  local(i) += heat * fe_values.shape_value(i, q);
              }
            touched = true;
          }
        for (const unsigned int f : cell->face_indices())
          {
            if (!cell->at_boundary(f))
              continue;
            const types::boundary_id id        = cell->face(f)->boundary_id();
            const auto               condition = condition_of.find(id);
            if (condition == condition_of.end())
              continue;
            const auto &type =
              parameters.thermal_boundary.conditions[condition->second].type;
            const auto &functions = boundary_functions[condition->second];
            if (type == ThermalBoundaryCondition::Type::dirichlet ||
                functions.time_dependent_load != time_dependent)
              continue;
            fe_face_values.reinit(cell, f);
            double load = 0.;
            for (const unsigned int q :
                 fe_face_values.quadrature_point_indices())
              {
                const Point<2> &x = fe_face_values.quadrature_point(q);
                // Neumann: inward flux; Robin: the known part h T_inf
                const double flux =
                  (type == ThermalBoundaryCondition::Type::neumann ?
                     functions.heat_flux->value(x) :
                     functions.heat_transfer_coefficient->value(x) *
                       functions.ambient_temperature->value(x)) *
                  fe_face_values.JxW(q);
                load += flux;
                for (unsigned int i = 0; i < n; ++i)
                  local(i) += flux * fe_face_values.shape_value(i, q);
              }
            level.boundary[id] += load;
            touched = true;
          }
        if (touched)
          {
            cell->get_dof_indices(dof_indices);
            level.vector.add(dof_indices, local);
          }
      }
    level.vector.compress(VectorOperation::add);
    level.source = Utilities::MPI::sum(level.source, communicator);
    // the same ids on every process: all Neumann/Robin ids of this kind
    for (const auto &[id, c] : condition_of)
      {
        const auto &type = parameters.thermal_boundary.conditions[c].type;
        if (type != ThermalBoundaryCondition::Type::dirichlet &&
            boundary_functions[c].time_dependent_load == time_dependent)
          level.boundary[id] =
            Utilities::MPI::sum(level.boundary[id], communicator);
      }
  }

  const HeatSolver::Loads &
  HeatSolver::time_dependent_loads(const double time)
  {
    for (const auto &level : variable_loads)
      if (level.valid && level.time == time)
        return level;
    // replace the level that is not the other's time (the older one)
    Loads &level = !variable_loads[0].valid ?
                     variable_loads[0] :
                     (!variable_loads[1].valid ?
                        variable_loads[1] :
                        (variable_loads[0].time < variable_loads[1].time ?
                           variable_loads[0] :
                           variable_loads[1]));
    assemble_loads(time, true, level);
    return level;
  }

  void
  HeatSolver::assemble_robin(
    const double                                time,
    std::map<types::boundary_id, RobinWeights> &weights)
  {
    const unsigned int                   n = fe->n_dofs_per_cell();
    const QGauss<1>                      face_quadrature(fe->degree + 1);
    FEFaceValues<2>                      fe_face_values(*mapping,
                                   *fe,
                                   face_quadrature,
                                   update_values | update_JxW_values |
                                     update_quadrature_points);
    FullMatrix<double>                   robin(n, n);
    std::vector<types::global_dof_index> dof_indices(n);
    robin_matrix = 0;
    for (const auto &[id, c] : condition_of)
      if (parameters.thermal_boundary.conditions[c].type ==
          ThermalBoundaryCondition::Type::robin)
        {
          auto &w = weights[id];
          if (w.size() != dof_handler->n_dofs())
            w.reinit(locally_owned_dofs, communicator);
          w = 0;
        }
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int f : cell->face_indices())
          {
            if (!cell->at_boundary(f))
              continue;
            const auto condition =
              condition_of.find(cell->face(f)->boundary_id());
            if (condition == condition_of.end() ||
                parameters.thermal_boundary.conditions[condition->second]
                    .type != ThermalBoundaryCondition::Type::robin)
              continue;
            robin_face_matrix(cell,
                              f,
                              boundary_functions[condition->second],
                              time,
                              1.,
                              fe_face_values,
                              robin);
            cell->get_dof_indices(dof_indices);
            robin_matrix.add(dof_indices, robin);
            Vector<double> row_sums(n);
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                row_sums(i) += robin(i, j);
            weights[cell->face(f)->boundary_id()].add(dof_indices, row_sums);
          }
    robin_matrix.compress(VectorOperation::add);
    for (auto &[id, w] : weights)
      w.compress(VectorOperation::add);
  }

  // ------------------------------------------------------------ assemble
  void
  HeatSolver::assemble_matrix_and_lifting(const double new_time,
                                          const double mass_weight,
                                          const double stiffness_weight,
                                          const bool   assemble_matrix)
  {
    const unsigned int n = fe->n_dofs_per_cell();
    const QGauss<1>    face_quadrature(fe->degree + 1);
    FEFaceValues<2>    fe_face_values(*mapping,
                                   *fe,
                                   face_quadrature,
                                   update_values | update_quadrature_points |
                                     update_JxW_values);
    if (assemble_matrix)
      {
        system_matrix = 0;
        reaction_rows.clear();
        reaction_columns.clear();
        reaction_values.clear();
      }
    lifting = 0;

    FullMatrix<double>                   local_matrix(n, n), robin(n, n);
    const Vector<double>                 zero_rhs(n);
    std::vector<types::global_dof_index> dof_indices(n);
    for (const auto &cell : dof_handler->active_cell_iterators())
      {
        if (!cell->is_locally_owned())
          continue;
        cell->get_dof_indices(dof_indices);
        // without a new matrix only the cells with Dirichlet values lift
        if (!assemble_matrix &&
            std::none_of(dof_indices.begin(),
                         dof_indices.end(),
                         [&](const types::global_dof_index i) {
                           return constraints.is_inhomogeneously_constrained(i);
                         }))
          continue;
        const unsigned int index = cell->active_cell_index();
        local_matrix             = 0;
        if (mass_weight != 0.)
          local_matrix.add(mass_weight, cell_capacity[index]);
        local_matrix.add(stiffness_weight, cell_conductivity[index]);
        for (const unsigned int f : cell->face_indices())
          {
            if (!cell->at_boundary(f))
              continue;
            const auto condition =
              condition_of.find(cell->face(f)->boundary_id());
            if (condition == condition_of.end() ||
                parameters.thermal_boundary.conditions[condition->second]
                    .type != ThermalBoundaryCondition::Type::robin)
              continue;
            robin_face_matrix(cell,
                              f,
                              boundary_functions[condition->second],
                              new_time,
                              stiffness_weight,
                              fe_face_values,
                              robin);
            local_matrix.add(1., robin);
          }
        if (assemble_matrix)
          {
            constraints.distribute_local_to_global(local_matrix,
                                                   zero_rhs,
                                                   dof_indices,
                                                   system_matrix,
                                                   lifting);
            for (unsigned int i = 0; i < n; ++i)
              {
                const auto dirichlet = dirichlet_dof_ids.find(dof_indices[i]);
                if (dirichlet == dirichlet_dof_ids.end())
                  continue;
                reaction_rows.push_back(
                  {dirichlet->second,
                   static_cast<unsigned int>(reaction_columns.size())});
                for (unsigned int j = 0; j < n; ++j)
                  {
                    reaction_columns.push_back(dof_indices[j]);
                    reaction_values.push_back(local_matrix(i, j));
                  }
              }
          }
        else
          constraints.distribute_local_to_global(zero_rhs,
                                                 dof_indices,
                                                 lifting,
                                                 local_matrix);
      }
    if (assemble_matrix)
      system_matrix.compress(VectorOperation::add);
    lifting.compress(VectorOperation::add);
  }

  void
  HeatSolver::assemble_rhs(const double old_time,
                           const double new_time,
                           const bool   steady)
  {
    const double dt = new_time - old_time;
    // weights of the new and old time levels in the theta scheme [s]
    const double new_weight = steady ? 1. : theta * dt;
    const double old_weight = steady ? 0. : (1. - theta) * dt;
    last_new_weight         = new_weight;
    last_old_weight         = old_weight;
    last_new_time           = new_time;
    last_old_time           = old_time;

    // M T^n - (1-theta) dt (K + R^n) T^n
    if (steady)
      full_rhs = 0;
    else
      capacity_matrix.vmult(full_rhs, owned_old_solution);
    if (old_weight != 0.)
      {
        conduction_matrix.vmult(work, owned_old_solution);
        full_rhs.add(-old_weight, work);
        if (time_dependent_robin)
          {
            assemble_robin(old_time, robin_weights);
            robin_matrix.vmult(work, owned_old_solution);
            full_rhs.add(-old_weight, work);
          }
      }
    // + dt (theta F^{n+1} + (1-theta) F^n)
    full_rhs.add(new_weight + old_weight, constant_loads.vector);
    if (any_time_dependent_load)
      {
        full_rhs.add(new_weight, time_dependent_loads(new_time).vector);
        if (old_weight != 0.)
          full_rhs.add(old_weight, time_dependent_loads(old_time).vector);
      }
    if (time_dependent_robin)
      assemble_robin(new_time, robin_weights_new);

    // condense onto the unconstrained DoFs, add the Dirichlet lifting
    full_rhs_ghosted = full_rhs;
    homogeneous_constraints.condense(full_rhs_ghosted, system_rhs);
    system_rhs += lifting;
  }

  unsigned int
  HeatSolver::solve(const bool rebuild_preconditioner)
  {
    if (rebuild_preconditioner || !preconditioner)
      {
        if (parameters.heat_solver.preconditioner == "AMG")
          {
            auto amg = std::make_unique<TrilinosWrappers::PreconditionAMG>();
            TrilinosWrappers::PreconditionAMG::AdditionalData data;
            data.elliptic              = true;
            data.higher_order_elements = fe->degree > 1;
            data.smoother_sweeps       = 2;
            data.aggregation_threshold = 0.02;
            amg->initialize(system_matrix, data);
            preconditioner = std::move(amg);
          }
        else
          {
            auto jacobi =
              std::make_unique<TrilinosWrappers::PreconditionJacobi>();
            jacobi->initialize(system_matrix);
            preconditioner = std::move(jacobi);
          }
      }
    owned_solution = solution;
    constraints.set_zero(owned_solution);
    const double  rhs_norm = system_rhs.l2_norm();
    SolverControl control(
      parameters.heat_solver.max_iterations,
      std::max(parameters.heat_solver.relative_tolerance * rhs_norm, 1e-300));
    SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
    try
      {
        cg.solve(system_matrix, owned_solution, system_rhs, *preconditioner);
      }
    catch (const SolverControl::NoConvergence &failure)
      {
        std::ostringstream message;
        message << "heat solver: CG did not converge in " << failure.last_step
                << " iterations (residual " << failure.last_residual
                << ", target " << control.tolerance()
                << "). Raise Heat solver/Maximum iterations, loosen Heat "
                   "solver/Relative tolerance, or check the material "
                   "properties and time step.";
        throw RunError(message.str());
      }
    constraints.distribute(owned_solution);
    solution = owned_solution;
    total_linear_iterations += control.last_step();
    return control.last_step();
  }

  void
  HeatSolver::accumulate_heat_balance(HeatBalance &balance)
  {
    const unsigned int n    = fe->n_dofs_per_cell();
    const double new_weight = last_new_weight, old_weight = last_old_weight;
    std::map<types::boundary_id, double> heat_in;
    for (const auto id : mesh_report->boundary_ids)
      heat_in[id] = 0.;

    // reaction of the discrete equations: the heat the Dirichlet boundary
    // supplies to each of its nodes during this step, (A T^{n+1} - b)_i
    for (const auto &row : reaction_rows)
      {
        double product = 0.;
        for (unsigned int j = row.start; j < row.start + n; ++j)
          product += reaction_values[j] * solution(reaction_columns[j]);
        heat_in[row.boundary_id] += product;
      }
    for (const auto &[dof, id] : owned_dirichlet_dofs)
      heat_in[id] -= full_rhs(dof);
    for (auto &[id, heat] : heat_in)
      heat = Utilities::MPI::sum(heat, communicator);

    // Robin: -h T at both time levels (dot products are global)
    const auto &weights_new =
      time_dependent_robin ? robin_weights_new : robin_weights;
    for (const auto &[id, weights] : weights_new)
      heat_in[id] -= new_weight * (weights * owned_solution);
    if (old_weight != 0.)
      for (const auto &[id, weights] : robin_weights)
        heat_in[id] -= old_weight * (weights * owned_old_solution);

    // Neumann fluxes, Robin h T_inf and sources (sums are global)
    double source = (new_weight + old_weight) * constant_loads.source;
    for (const auto &[id, load] : constant_loads.boundary)
      heat_in[id] += (new_weight + old_weight) * load;
    if (any_time_dependent_load)
      {
        const Loads &at_new = time_dependent_loads(last_new_time);
        source += new_weight * at_new.source;
        for (const auto &[id, load] : at_new.boundary)
          heat_in[id] += new_weight * load;
        if (old_weight != 0.)
          {
            const Loads &at_old = time_dependent_loads(last_old_time);
            source += old_weight * at_old.source;
            for (const auto &[id, load] : at_old.boundary)
              heat_in[id] += old_weight * load;
          }
      }

    for (const auto &[id, heat] : heat_in)
      balance.boundary_heat_in[id] += heat;
    balance.source_heat += source;
    if (parameters.time.mode == TimeSteppingParameters::Mode::transient)
      {
        work = owned_solution;
        work -= owned_old_solution;
        balance.stored_heat += capacity_row_sums * work;
      }
  }

  // ------------------------------------------------------------ initial
  void
  HeatSolver::set_initial_condition(const bool hold_dirichlet)
  {
    initial_temperature->set_time(parameters.time.start_time);
    TrilinosWrappers::MPI::Vector distributed(locally_owned_dofs, communicator);
    if (!parameters.has_local_initial_temperature())
      VectorTools::interpolate(*mapping,
                               *dof_handler,
                               *initial_temperature,
                               distributed);
    else
      {
        // per material id (body > material > global entry): every cell
        // evaluates its own entry at its support points; a node shared by
        // cells of different entries (a material interface) takes the mean
        // of their values there, each distinct entry counted once, so that
        // the CG field at the interface is the midpoint of the jump whatever
        // the number of cells on either side
        std::vector<std::unique_ptr<FunctionParser<2>>> functions;
        std::map<std::string, unsigned int>             index_of_entry;
        std::map<types::material_id, unsigned int>      entry_of_material;
        auto entry_index = [&](const types::material_id id) {
          const auto known = entry_of_material.find(id);
          if (known != entry_of_material.end())
            return known->second;
          const InitialTemperatureEntry entry =
            parameters.initial_temperature_of(id);
          const auto [it, inserted] =
            index_of_entry.emplace(entry.entry, functions.size());
          if (inserted)
            {
              functions.push_back(
                make_expression_function(entry.expression, entry.entry));
              functions.back()->set_time(parameters.time.start_time);
            }
          entry_of_material[id] = it->second;
          return it->second;
        };
        const unsigned int         n_owned = locally_owned_dofs.n_elements();
        std::vector<std::uint32_t> entries_at(n_owned, 0); // bit per entry
        std::vector<Point<2>>      point_of(n_owned);
        FEValues<2>                fe_values(*mapping,
                              *fe,
                              Quadrature<2>(fe->get_unit_support_points()),
                              update_quadrature_points);
        std::vector<types::global_dof_index> dofs(fe->n_dofs_per_cell());
        // ghost cells too: a node owned here may touch cells of other ranks
        for (const auto &cell : dof_handler->active_cell_iterators())
          if (cell->is_locally_owned() || cell->is_ghost())
            {
              const unsigned int e = entry_index(cell->material_id());
              fe_values.reinit(cell);
              cell->get_dof_indices(dofs);
              for (unsigned int i = 0; i < dofs.size(); ++i)
                if (locally_owned_dofs.is_element(dofs[i]))
                  {
                    const auto k = locally_owned_dofs.index_within_set(dofs[i]);
                    entries_at[k] |= std::uint32_t(1) << e;
                    point_of[k] = fe_values.quadrature_point(i);
                  }
            }
        for (unsigned int k = 0; k < n_owned; ++k)
          {
            double       sum   = 0.;
            unsigned int count = 0;
            for (unsigned int e = 0; e < functions.size(); ++e)
              if (entries_at[k] & (std::uint32_t(1) << e))
                {
                  sum += functions[e]->value(point_of[k]);
                  ++count;
                }
            distributed[locally_owned_dofs.nth_index_in_set(k)] =
              count == 1 ? sum : sum / count;
          }
        distributed.compress(VectorOperation::insert);
      }
    // the initial temperature everywhere, Dirichlet nodes included: the
    // boundary values act from the first step on. Holding them at t = 0
    // would add the heat of a boundary-layer hat function to the initial
    // data where they differ from it (a step at a heated edge); starting
    // from the initial temperature, the first backward Euler step equals
    // one from the L2 projection of the initial data onto the constrained
    // space (doc/cases/plate_transient-continuum.md)
    AffineConstraints<double> hanging_nodes;
    hanging_nodes.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(*dof_handler, hanging_nodes);
    hanging_nodes.close();
    hanging_nodes.distribute(distributed);
    make_constraints(parameters.time.start_time);
    if (hold_dirichlet)
      constraints.distribute(distributed);
    solution           = distributed;
    owned_solution     = distributed;
    owned_old_solution = distributed;
  }

  void
  HeatSolver::adapt_mesh(const bool transfer_solution)
  {
    auto &distributed_triangulation =
      dynamic_cast<parallel::distributed::Triangulation<2> &>(*triangulation);
    mark_cells_by_kelly(distributed_triangulation,
                        *mapping,
                        *dof_handler,
                        solution,
                        fe->degree,
                        parameters.adaptivity,
                        coarse_level);
    parallel::distributed::SolutionTransfer<2, TrilinosWrappers::MPI::Vector>
      transfer(*dof_handler);
    triangulation->prepare_coarsening_and_refinement();
    if (transfer_solution)
      transfer.prepare_for_coarsening_and_refinement(solution);
    triangulation->execute_coarsening_and_refinement();
    setup_dofs();
    compute_cell_matrices();
    if (transfer_solution)
      {
        TrilinosWrappers::MPI::Vector distributed(locally_owned_dofs,
                                                  communicator);
        transfer.interpolate(distributed);
        constraints.distribute(distributed);
        solution           = distributed;
        owned_solution     = distributed;
        owned_old_solution = distributed;
      }
  }

  // ------------------------------------------------------------ output
  void
  HeatSolver::write_output(const double time)
  {
    if (output_hook)
      output_hook(time);
    monitors->write(time, *mapping, *dof_handler, solution);
    if (!parameters.output.write_vtu)
      return;
    DataOut<2> data_out;
    data_out.attach_dof_handler(*dof_handler);
    data_out.add_data_vector(solution, "T");
    Vector<float> material(triangulation->n_active_cells()),
      subdomain(triangulation->n_active_cells());
    for (const auto &cell : triangulation->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          material(cell->active_cell_index())  = cell->material_id();
          subdomain(cell->active_cell_index()) = cell->subdomain_id();
        }
    data_out.add_data_vector(material, "material_id");
    data_out.add_data_vector(subdomain, "subdomain");
    data_out.build_patches(*mapping, uses_quadrilaterals() ? fe->degree : 1);
    solution_series->write(data_out, time);
  }

  void
  HeatSolver::write_summary(const unsigned long             steps,
                            const double                    end_time,
                            const double                    wall_time,
                            const HeatBalance              &balance,
                            const std::vector<std::string> &cycles) const
  {
    const bool steady =
      parameters.time.mode == TimeSteppingParameters::Mode::steady;
    JsonObject heat;
    JsonObject per_boundary;
    double     total_in = balance.source_heat;
    for (const auto &[id, value] : balance.boundary_heat_in)
      {
        per_boundary.add(std::to_string(id), value);
        total_in += value;
      }
    double scale =
      std::abs(balance.stored_heat) + std::abs(balance.source_heat);
    for (const auto &[id, value] : balance.boundary_heat_in)
      scale += std::abs(value);
    const double imbalance = balance.stored_heat - total_in;
    heat
      .add("units",
           std::string(steady ? "W/m (rates, per unit thickness)" :
                                "J/m (per unit thickness)"))
      .add("boundary_heat_in", per_boundary)
      .add("source_heat", balance.source_heat)
      .add("stored_heat", balance.stored_heat)
      .add("total_heat_in", total_in)
      .add("imbalance", imbalance)
      .add("relative_imbalance", scale > 0 ? std::abs(imbalance) / scale : 0.);

    std::vector<JsonObject> cycle_objects;
    for (const auto &cycle : cycles)
      {
        JsonObject         object;
        std::istringstream in(cycle);
        long long          cells, dofs, iterations;
        in >> cells >> dofs >> iterations;
        object.add("cells", cells)
          .add("dofs", dofs)
          .add("cg_iterations", iterations);
        cycle_objects.push_back(object);
      }

    JsonObject summary;
    summary.add("model", parameters.model)
      .add("prm_file", parameters.prm_file)
      .add("mpi_processes", Utilities::MPI::n_mpi_processes(communicator))
      .add("mode", std::string(steady ? "steady" : "transient"))
      .add("time_method", steady ? std::string("none") : parameters.time.method)
      .add("cells",
           static_cast<long long>(triangulation->n_global_active_cells()))
      .add("dofs", static_cast<long long>(dof_handler->n_dofs()))
      .add("steps", static_cast<long long>(steps))
      .add("end_time", end_time)
      .add("wall_time", wall_time)
      .add("element_steps_per_second",
           wall_time > 0 ?
             triangulation->n_global_active_cells() *
               static_cast<double>(std::max(steps, 1ul)) / wall_time :
             0.)
      .add("linear_iterations", static_cast<long long>(total_linear_iterations))
      .add("broken_joints", 0u)
      .add("cracks", 0u)
      .add("heat", heat);
    if (!cycle_objects.empty())
      summary.add("adaptive_cycles", cycle_objects);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_file_atomically(parameters.output.directory + "/summary.json",
                            summary.str() + "\n");
  }

  // ------------------------------------------------------------ drivers
  void
  HeatSolver::check_input()
  {
    make_mesh();
    setup_dofs();
    monitors = std::make_unique<Monitors>(parameters.monitors,
                                          parameters.output.directory,
                                          std::vector<std::string>{"T"},
                                          communicator);
    monitors->check_points(*mapping, *dof_handler);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      std::cout << mesh_report->to_string()
                << "  dofs: " << dof_handler->n_dofs() << " (after "
                << parameters.mesh.global_refinements << " global refinements: "
                << triangulation->n_global_active_cells() << " cells)\n";
  }

  void
  HeatSolver::run()
  {
    if (parameters.resume)
      throw InputError(
        "--resume: the continuum models do not write checkpoints; run the "
        "case again without --resume (SIGINT/SIGTERM stop them cleanly with "
        "the outputs so far). Checkpoints are for the discrete models.");
    check_input();
    solution_series =
      std::make_unique<SolutionSeries>(parameters.output.directory,
                                       "solution",
                                       communicator);
    if (parameters.time.mode == TimeSteppingParameters::Mode::steady)
      run_steady();
    else
      run_transient();
  }

  void
  HeatSolver::run_steady()
  {
    ProgressReporter   progress(parameters.output.progress_interval,
                              0.,
                              1.,
                              false);
    const unsigned int n_cycles =
      parameters.adaptivity.enable ? parameters.adaptivity.steady_cycles : 1;
    std::vector<std::string> cycles;
    HeatBalance              balance;
    const double             time = parameters.time.start_time;
    for (unsigned int cycle = 0; cycle < n_cycles; ++cycle)
      {
        if (cycle > 0)
          adapt_mesh(false);
        else
          compute_cell_matrices();
        make_constraints(time);
        owned_old_solution = 0;
        solution           = 0;
        assemble_matrix_and_lifting(time, 0., 1., true);
        assemble_rhs(time, time, true);
        const unsigned int iterations = solve(true);
        std::ostringstream record;
        record << triangulation->n_global_active_cells() << " "
               << dof_handler->n_dofs() << " " << iterations;
        cycles.push_back(record.str());
        if (Utilities::MPI::this_mpi_process(communicator) == 0)
          std::cout << "cycle " << cycle << ": "
                    << triangulation->n_global_active_cells() << " cells, "
                    << dof_handler->n_dofs() << " dofs, " << iterations
                    << " CG iterations" << std::endl;
      }
    accumulate_heat_balance(balance);
    write_output(time);
    write_summary(0, time, progress.elapsed(), balance, cycles);
  }

  // ------------------------------------------------------------ stepping
  void
  HeatSolver::start_stepping()
  {
    stepping                           = SteppingState();
    stepping.time                      = parameters.time.start_time;
    stepping.dirichlet_depends_on_time = false;
    for (const auto &functions : boundary_functions)
      stepping.dirichlet_depends_on_time |=
        functions.time_dependent_temperature;
  }

  bool
  HeatSolver::in_rannacher_start() const
  {
    return parameters.time.theta < 1. &&
           stepping.step < parameters.time.rannacher_steps;
  }

  void
  HeatSolver::advance(const double dt)
  {
    theta                 = in_rannacher_start() ? 1. : parameters.time.theta;
    const double time     = stepping.time;
    const double new_time = time + dt;
    const bool rebuild = !stepping.matrix_is_current || time_dependent_robin ||
                         std::abs(dt - stepping.last_dt) > 1e-12 * dt ||
                         theta != stepping.last_theta;
    if (stepping.dirichlet_depends_on_time)
      make_constraints(new_time);
    owned_old_solution = owned_solution;
    if (rebuild || stepping.dirichlet_depends_on_time)
      assemble_matrix_and_lifting(new_time, 1., theta * dt, rebuild);
    assemble_rhs(time, new_time, false);
    solve(rebuild);
    accumulate_heat_balance(stepping.balance);
    stepping.matrix_is_current = true;
    stepping.time              = new_time;
    stepping.last_dt           = dt;
    stepping.last_theta        = theta;
    ++stepping.step;
  }

  void
  HeatSolver::prepare_coupled_stepping()
  {
    if (parameters.time.mode != TimeSteppingParameters::Mode::transient)
      throw InputError("Time stepping/Mode = steady: the continuum heat as a "
                       "temperature source steps in time with the coupled "
                       "model; allowed is transient.");
    if (parameters.adaptivity.enable)
      throw InputError("Adaptive refinement/Enable = true: the continuum "
                       "heat as a temperature source keeps the mesh of the "
                       "coupled model; allowed is false.");
    make_mesh();
    setup_dofs();
    set_initial_condition(false);
    compute_cell_matrices();
    start_stepping();
  }

  void
  HeatSolver::restore_state(const double               time,
                            const unsigned long        steps,
                            const HeatBalance         &balance,
                            const std::vector<double> &values)
  {
    if (values.size() != dof_handler->n_dofs())
      throw InputError("checkpoint: " + std::to_string(values.size()) +
                       " continuum temperatures for " +
                       std::to_string(dof_handler->n_dofs()) +
                       " DoFs; resume with the mesh and Heat solver/Degree "
                       "of the run that wrote it.");
    for (const auto dof : locally_owned_dofs)
      owned_solution(dof) = values[dof];
    owned_solution.compress(VectorOperation::insert);
    owned_old_solution         = owned_solution;
    solution                   = owned_solution;
    stepping.time              = time;
    stepping.step              = steps;
    stepping.balance           = balance;
    stepping.matrix_is_current = false;
    stepping.last_dt           = -1.;
    stepping.last_theta        = -1.;
  }

  void
  HeatSolver::run_transient()
  {
    const auto  &time_parameters = parameters.time;
    const double start           = time_parameters.start_time,
                 end             = time_parameters.end_time;
    const double time_tolerance  = 1e-10 * std::max(1., std::abs(end));

    if (parameters.adaptivity.enable)
      for (unsigned int k = 0; k < parameters.adaptivity.initial_refinements;
           ++k)
        {
          set_initial_condition(true);
          adapt_mesh(false);
        }
    set_initial_condition(false);
    compute_cell_matrices();

    // output times: those listed, multiples of the interval, and the end
    std::vector<double> output_times;
    for (const double t : parameters.output.times)
      if (t > start + time_tolerance && t < end - time_tolerance)
        output_times.push_back(t);
    if (parameters.output.interval > 0)
      for (double t = start + parameters.output.interval;
           t < end - time_tolerance;
           t += parameters.output.interval)
        output_times.push_back(t);
    output_times.push_back(end);
    std::sort(output_times.begin(), output_times.end());
    output_times.erase(std::unique(output_times.begin(),
                                   output_times.end(),
                                   [&](const double a, const double b) {
                                     return std::abs(a - b) < time_tolerance;
                                   }),
                       output_times.end());

    ProgressReporter progress(parameters.output.progress_interval,
                              start,
                              end,
                              Utilities::MPI::this_mpi_process(communicator) ==
                                0);
    start_stepping();
    double &time = stepping.time;
    write_output(time);
    for (const double output_time : output_times)
      while (time < output_time - time_tolerance)
        {
          // Rannacher start of Crank-Nicolson: backward Euler half steps
          double dt = time_parameters.time_step;
          if (in_rannacher_start())
            dt *= 0.5;
          // land on the output time; never leave a sliver of a step
          if (time + dt > output_time - 1e-3 * dt)
            dt = output_time - time;
          advance(dt);
          if (std::abs(time - output_time) < time_tolerance)
            time = output_time;
          if (parameters.adaptivity.enable &&
              stepping.step % parameters.adaptivity.interval == 0)
            {
              adapt_mesh(true);
              make_constraints(time);
              stepping.matrix_is_current = false;
            }
          if (std::abs(time - output_time) < time_tolerance)
            write_output(output_time);
          progress.update(stepping.step, time);
          if (stop_requested_on_any_rank(communicator))
            {
              // finish cleanly: the state now as an extra output, the
              // summary so far (no checkpoint: continuum runs restart)
              if (std::abs(time - output_time) >= time_tolerance)
                write_output(time);
              write_summary(stepping.step,
                            time,
                            progress.elapsed(),
                            stepping.balance,
                            {});
              throw StopRequested(
                "stopped by " + stop_signal_name() +
                " at t = " + Utilities::to_string(time) + " s after step " +
                std::to_string(stepping.step) + "; outputs so far in " +
                parameters.output.directory +
                " (continuum runs cannot be resumed).");
            }
        }
    const unsigned long step    = stepping.step;
    const HeatBalance  &balance = stepping.balance;
    write_summary(step, time, progress.elapsed(), balance, {});
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      std::cout << "done: " << step << " steps to t = " << time << " s, "
                << triangulation->n_global_active_cells() << " cells, "
                << dof_handler->n_dofs() << " dofs, " << total_linear_iterations
                << " CG iterations, " << progress.elapsed() << " s wall"
                << std::endl;
  }
} // namespace tmfdem
