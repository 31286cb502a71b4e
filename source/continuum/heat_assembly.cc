// The heat solver's assembly: cell matrices, Robin terms, loads, the theta
// system and right-hand side, the linear solve and the heat balance (the
// rest of HeatSolver is in heat_solver.cc).
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/continuum/heat_solver.h>

namespace tmfdem
{
  template <int dim>
  void
  HeatSolver<dim>::compute_cell_matrices()
  {
    const unsigned int    n          = fe->n_dofs_per_cell();
    const Quadrature<dim> quadrature = cell_quadrature();
    FEValues<dim>         fe_values(*mapping,
                            *fe,
                            quadrature,
                            update_values | update_gradients |
                              update_JxW_values);
    const unsigned int    n_cells = triangulation->n_active_cells();
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
          const bool           anisotropic = material.anisotropic_conductivity;
          const Tensor<2, dim> K = material.template conductivity_tensor<dim>();
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
      add_robin_terms(parameters.time.start_time,
                      conduction_matrix,
                      robin_weights);
    capacity_matrix.compress(VectorOperation::add);
    conduction_matrix.compress(VectorOperation::add);

    // M 1: row sums of the capacity matrix
    work = 1.;
    capacity_matrix.vmult(capacity_row_sums, work);

    assemble_loads(parameters.time.start_time, false, constant_loads);
    for (auto &level : variable_loads)
      level.valid = false;
  }

  template <int dim>
  const typename HeatSolver<dim>::BoundaryFunctions *
  HeatSolver<dim>::robin_functions(
    const typename DoFHandler<dim>::active_cell_iterator &cell,
    const unsigned int                                    face) const
  {
    if (!cell->at_boundary(face))
      return nullptr;
    const auto condition = condition_of.find(cell->face(face)->boundary_id());
    if (condition == condition_of.end() ||
        parameters.thermal_boundary.conditions[condition->second].type !=
          ThermalBoundaryCondition::Type::robin)
      return nullptr;
    return &boundary_functions[condition->second];
  }

  template <int dim>
  void
  HeatSolver<dim>::robin_face_matrix(
    const typename DoFHandler<dim>::active_cell_iterator &cell,
    const unsigned int                                    face,
    const BoundaryFunctions                              &functions,
    const double                                          time,
    const double                                          weight,
    FEFaceValues<dim>                                    &fe_face_values,
    FullMatrix<double>                                   &matrix) const
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

  template <int dim>
  void
  HeatSolver<dim>::assemble_loads(const double time,
                                  const bool   time_dependent,
                                  Loads       &level)
  {
    const unsigned int        n               = fe->n_dofs_per_cell();
    const Quadrature<dim>     quadrature      = cell_quadrature();
    const Quadrature<dim - 1> face_quadrature = face_quadrature_rule();
    FEValues<dim>             fe_values(*mapping,
                            *fe,
                            quadrature,
                            update_values | update_quadrature_points |
                              update_JxW_values);
    FEFaceValues<dim>         fe_face_values(*mapping,
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
                const Point<dim> &x = fe_face_values.quadrature_point(q);
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

  template <int dim>
  const typename HeatSolver<dim>::Loads &
  HeatSolver<dim>::time_dependent_loads(const double time)
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

  template <int dim>
  void
  HeatSolver<dim>::assemble_robin(
    const double                                time,
    std::map<types::boundary_id, RobinWeights> &weights)
  {
    robin_matrix = 0;
    add_robin_terms(time, robin_matrix, weights);
    robin_matrix.compress(VectorOperation::add);
  }

  template <int dim>
  void
  HeatSolver<dim>::add_robin_terms(
    const double                                time,
    TrilinosWrappers::SparseMatrix             &matrix,
    std::map<types::boundary_id, RobinWeights> &weights)
  {
    const unsigned int        n               = fe->n_dofs_per_cell();
    const Quadrature<dim - 1> face_quadrature = face_quadrature_rule();
    FEFaceValues<dim>         fe_face_values(*mapping,
                                     *fe,
                                     face_quadrature,
                                     update_values | update_JxW_values |
                                       update_quadrature_points);
    FullMatrix<double>        robin(n, n);
    std::vector<types::global_dof_index> dof_indices(n);
    // every Robin id on every process, for the collective compress
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
            const BoundaryFunctions *functions = robin_functions(cell, f);
            if (!functions)
              continue;
            robin_face_matrix(cell,
                              f,
                              *functions,
                              time,
                              1.,
                              fe_face_values,
                              robin);
            cell->get_dof_indices(dof_indices);
            matrix.add(dof_indices, robin);
            Vector<double> row_sums(n);
            for (unsigned int i = 0; i < n; ++i)
              for (unsigned int j = 0; j < n; ++j)
                row_sums(i) += robin(i, j);
            weights[cell->face(f)->boundary_id()].add(dof_indices, row_sums);
          }
    for (auto &[id, w] : weights)
      w.compress(VectorOperation::add);
  }

  // ------------------------------------------------------------ assemble
  template <int dim>
  void
  HeatSolver<dim>::assemble_matrix_and_lifting(const double new_time,
                                               const double mass_weight,
                                               const double stiffness_weight,
                                               const bool   assemble_matrix)
  {
    const unsigned int        n               = fe->n_dofs_per_cell();
    const Quadrature<dim - 1> face_quadrature = face_quadrature_rule();
    FEFaceValues<dim>         fe_face_values(*mapping,
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
            const BoundaryFunctions *functions = robin_functions(cell, f);
            if (!functions)
              continue;
            robin_face_matrix(cell,
                              f,
                              *functions,
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

  template <int dim>
  void
  HeatSolver<dim>::assemble_rhs(const double old_time,
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

    // condense onto the unconstrained DoFs, add the Dirichlet lifting.
    // Own elimination rather than AffineConstraints::condense(ghosted,
    // output), which in deal.II 9.4 mixes insert and add on a Trilinos
    // vector without a compress() between them (a Debug assertion; wrong
    // results with constraints across ranks are reported in deal.II issue
    // 11195): each constrained row i this rank owns adds a_ij b_i to its
    // DoFs j (some owned by other ranks) and becomes zero.
    system_rhs        = full_rhs;
    condense_transfer = 0.;
    std::vector<types::global_dof_index> columns;
    std::vector<double>                  values;
    for (const auto &line : homogeneous_constraints.get_lines())
      if (locally_owned_dofs.is_element(line.index))
        {
          const double b = full_rhs[line.index];
          for (const auto &[column, weight] : line.entries)
            {
              columns.push_back(column);
              values.push_back(weight * b);
            }
        }
    condense_transfer.add(columns, values);
    condense_transfer.compress(VectorOperation::add);
    system_rhs += condense_transfer;
    for (const auto &line : homogeneous_constraints.get_lines())
      if (locally_owned_dofs.is_element(line.index))
        system_rhs[line.index] = 0.;
    system_rhs.compress(VectorOperation::insert);
    system_rhs += lifting;
  }

  template <int dim>
  unsigned int
  HeatSolver<dim>::solve(const bool rebuild_preconditioner)
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

  template <int dim>
  void
  HeatSolver<dim>::accumulate_heat_balance(HeatBalance &balance)
  {
    const unsigned int n    = fe->n_dofs_per_cell();
    const double new_weight = last_new_weight, old_weight = last_old_weight;
    std::map<types::boundary_id, double> heat_in;
    for (const auto id : mesh_boundary_ids)
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

  // the members defined in this file (heat_solver.cc instantiates the rest)
  template class HeatSolver<2>;
  template class HeatSolver<3>;
} // namespace tmfdem
