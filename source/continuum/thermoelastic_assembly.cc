// The thermoelastic solver's assembly and Newton solve: temperatures at
// the quadrature points, constraints of each Newton iteration, residual and
// tangent, the CG + AMG solve and the line search (the rest of
// ThermoelasticSolver is in thermoelastic_solver.cc and
// thermoelastic_output.cc).
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/numerics/vector_tools.h>

#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/continuum/thermoelastic_solver.h>

namespace tmfdem
{
  namespace
  {
    using Condition = MechanicalBoundaryCondition;

    /** dim parsed expressions as one vector-valued function. */
    template <int dim>
    class VectorExpression : public Function<dim>
    {
    public:
      VectorExpression(
        const std::array<std::unique_ptr<FunctionParser<dim>>, dim> &components,
        const double                                                 time)
        : Function<dim>(dim, time)
        , components(components)
      {}
      double
      value(const Point<dim> &p, const unsigned int component) const override
      {
        components[component]->set_time(this->get_time());
        return components[component]->value(p);
      }

    private:
      const std::array<std::unique_ptr<FunctionParser<dim>>, dim> &components;
    };

  } // namespace

  // ------------------------------------------------------------ assembly
  template <int dim>
  void
  ThermoelasticSolver<dim>::compute_quadrature_temperatures()
  {
    const Quadrature<dim> quadrature = cell_quadrature();
    FEValues<dim>         fe_values(*mapping,
                            *fe,
                            quadrature,
                            update_quadrature_points);
    quadrature_temperatures.assign(triangulation->n_active_cells(), {});
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          const typename Triangulation<dim>::active_cell_iterator
                tria_cell(triangulation, cell->level(), cell->index());
          auto &T = quadrature_temperatures[cell->active_cell_index()];
          T       = temperatures_at(tria_cell,
                              quadrature.get_points(),
                              fe_values.get_quadrature_points());
          const auto &material = materials[cell->material_id()];
          for (const double value : T)
            if (!(material.thermal_stretch(value) > 0.) ||
                !std::isfinite(value))
              {
                std::ostringstream message;
                message << "thermoelastic solver: temperature " << value
                        << " C at a quadrature point of the cell at "
                        << cell->center()
                        << " gives a thermal stretch 1 + beta dT <= 0 (or is "
                           "not a number); check Mechanics/Temperature or "
                           "the heat solution.";
                throw RunError(message.str());
              }
        }
  }

  template <int dim>
  double
  ThermoelasticSolver<dim>::make_newton_constraints(const double time)
  {
    std::map<types::global_dof_index, double> prescribed;
    const Functions::ZeroFunction<dim>        zero(dim);
    const auto                                only = [](const unsigned int d) {
      std::vector<bool> mask(dim, false);
      mask[d] = true;
      return ComponentMask(mask);
    };
    const ComponentMask x_only = only(0), y_only = only(1),
                        z_only = only(dim - 1), all(dim, true);
    for (unsigned int n = 0;
         n < parameters.mechanical_boundary.conditions.size();
         ++n)
      {
        const auto &condition = parameters.mechanical_boundary.conditions[n];
        if (condition.type == Condition::Type::traction)
          continue;
        const VectorExpression<dim> displacement(displacement_functions[n],
                                                 time);
        const Function<dim>        &values =
          condition.type == Condition::Type::displacement ?
                   static_cast<const Function<dim> &>(displacement) :
                   static_cast<const Function<dim> &>(zero);
        const ComponentMask &mask =
          condition.type == Condition::Type::roller_x ? x_only :
          condition.type == Condition::Type::roller_y ? y_only :
          condition.type == Condition::Type::roller_z ? z_only :
                                                        all;
        for (const auto id : condition.boundary_ids)
          VectorTools::interpolate_boundary_values(*mapping,
                                                   *dof_handler,
                                                   id,
                                                   values,
                                                   prescribed,
                                                   mask);
      }
    for (const auto dof : pinned_dofs)
      prescribed[dof] = 0.;

    newton_constraints.clear();
    newton_constraints.reinit(locally_relevant_dofs);
    newton_constraints.merge(hanging_node_constraints);
    residual_constraints.clear();
    residual_constraints.reinit(locally_relevant_dofs);
    residual_constraints.merge(hanging_node_constraints);
    double largest_increment = 0.;
    for (const auto &[dof, value] : prescribed)
      if (locally_relevant_dofs.is_element(dof) &&
          !hanging_node_constraints.is_constrained(dof))
        {
          const double increment = value - solution(dof);
          newton_constraints.add_line(dof);
          newton_constraints.set_inhomogeneity(dof, increment);
          residual_constraints.add_line(dof);
          largest_increment = std::max(largest_increment, std::abs(increment));
        }
    newton_constraints.close();
    residual_constraints.close();
    return Utilities::MPI::max(largest_increment, communicator);
  }

  template <int dim>
  bool
  ThermoelasticSolver<dim>::assemble(
    const TrilinosWrappers::MPI::Vector &displacement,
    const AffineConstraints<double>     &constraints_used,
    const bool                           with_matrix)
  {
    const Quadrature<dim>            quadrature      = cell_quadrature();
    const Quadrature<dim - 1>        face_quadrature = face_quadrature_rule();
    FEValues<dim>                    fe_values(*mapping,
                            *fe,
                            quadrature,
                            update_gradients | update_JxW_values);
    FEFaceValues<dim>                fe_face_values(*mapping,
                                     *fe,
                                     face_quadrature,
                                     update_values | update_quadrature_points |
                                       update_JxW_values);
    const unsigned int               n_dofs = fe->n_dofs_per_cell();
    const unsigned int               n_q    = quadrature.size();
    const FEValuesExtractors::Vector u(0);
    FullMatrix<double>               cell_matrix(n_dofs, n_dofs);
    Vector<double>                   cell_rhs(n_dofs);
    std::vector<types::global_dof_index> dof_indices(n_dofs);
    std::vector<Tensor<2, dim>>          grad_u(n_q);
    std::vector<Tensor<2, dim>>          shape_gradients(n_dofs);
    std::vector<Tensor<2, dim>>          tangent_times_gradient(n_dofs);
    std::vector<unsigned int>            component(n_dofs);
    for (unsigned int i = 0; i < n_dofs; ++i)
      component[i] = fe->system_to_component_index(i).first;

    std::vector<int> traction_condition(256, -1);
    for (unsigned int n = 0;
         n < parameters.mechanical_boundary.conditions.size();
         ++n)
      {
        const auto &condition = parameters.mechanical_boundary.conditions[n];
        if (condition.type == Condition::Type::traction)
          for (const auto id : condition.boundary_ids)
            if (id < traction_condition.size())
              traction_condition[id] = n;
      }

    if (with_matrix)
      system_matrix = 0;
    system_rhs        = 0;
    double admissible = 1.;
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          cell_matrix = 0;
          cell_rhs    = 0;
          fe_values[u].get_function_gradients(displacement, grad_u);
          const auto &material = materials[cell->material_id()];
          const auto &T = quadrature_temperatures[cell->active_cell_index()];
          for (unsigned int q = 0; q < n_q; ++q)
            {
              if (!material.admissible(grad_u[q], T[q]))
                {
                  admissible = 0.;
                  continue;
                }
              const double         JxW = fe_values.JxW(q);
              const Tensor<2, dim> P   = material.first_piola(grad_u[q], T[q]);
              // the gradient of vector shape function i is nonzero only in
              // its component's row: the contractions skip the zero rows
              // (the same sums, in the same order, as the full ones)
              for (unsigned int i = 0; i < n_dofs; ++i)
                {
                  shape_gradients[i]     = fe_values[u].gradient(i, q);
                  const unsigned int c   = component[i];
                  double             P_G = P[c][0] * shape_gradients[i][c][0];
                  for (unsigned int J = 1; J < dim; ++J)
                    P_G += P[c][J] * shape_gradients[i][c][J];
                  cell_rhs(i) -= P_G * JxW;
                }
              if (with_matrix)
                {
                  const Tensor<4, dim> A = material.tangent(grad_u[q], T[q]);
                  for (unsigned int j = 0; j < n_dofs; ++j)
                    {
                      const unsigned int c = component[j];
                      for (unsigned int a = 0; a < dim; ++a)
                        for (unsigned int b = 0; b < dim; ++b)
                          {
                            double sum = 0.;
                            for (unsigned int l = 0; l < dim; ++l)
                              sum += A[a][b][c][l] * shape_gradients[j][c][l];
                            tangent_times_gradient[j][a][b] = sum;
                          }
                    }
                  for (unsigned int i = 0; i < n_dofs; ++i)
                    {
                      const unsigned int c = component[i];
                      for (unsigned int j = 0; j < n_dofs; ++j)
                        {
                          double G_A_G = shape_gradients[i][c][0] *
                                         tangent_times_gradient[j][c][0];
                          for (unsigned int J = 1; J < dim; ++J)
                            G_A_G += shape_gradients[i][c][J] *
                                     tangent_times_gradient[j][c][J];
                          cell_matrix(i, j) += G_A_G * JxW;
                        }
                    }
                }
            }
          for (const auto f : cell->face_indices())
            if (cell->face(f)->at_boundary() &&
                cell->face(f)->boundary_id() < traction_condition.size() &&
                traction_condition[cell->face(f)->boundary_id()] >= 0)
              {
                const auto &functions = traction_functions
                  [traction_condition[cell->face(f)->boundary_id()]];
                fe_face_values.reinit(cell, f);
                for (unsigned int q = 0; q < face_quadrature.size(); ++q)
                  {
                    const Point<dim> &p = fe_face_values.quadrature_point(q);
                    Tensor<1, dim>    traction;
                    for (unsigned int d = 0; d < dim; ++d)
                      traction[d] = functions[d]->value(p);
                    for (unsigned int i = 0; i < n_dofs; ++i)
                      cell_rhs(i) += traction * fe_face_values[u].value(i, q) *
                                     fe_face_values.JxW(q);
                  }
              }
          cell->get_dof_indices(dof_indices);
          if (with_matrix)
            constraints_used.distribute_local_to_global(cell_matrix,
                                                        cell_rhs,
                                                        dof_indices,
                                                        system_matrix,
                                                        system_rhs);
          else
            constraints_used.distribute_local_to_global(cell_rhs,
                                                        dof_indices,
                                                        system_rhs);
        }
    if (with_matrix)
      system_matrix.compress(VectorOperation::add);
    system_rhs.compress(VectorOperation::add);
    return Utilities::MPI::min(admissible, communicator) > 0.;
  }

  template <int dim>
  double
  ThermoelasticSolver<dim>::residual_norm(
    const TrilinosWrappers::MPI::Vector &displacement)
  {
    if (!assemble(displacement, residual_constraints, false))
      return std::numeric_limits<double>::infinity();
    return system_rhs.l2_norm();
  }

  template <int dim>
  unsigned int
  ThermoelasticSolver<dim>::solve_linear_system(
    TrilinosWrappers::MPI::Vector &update)
  {
    update                = 0;
    const double rhs_norm = system_rhs.l2_norm();
    if (rhs_norm == 0.)
      return 0;
    TrilinosWrappers::PreconditionAMG                 amg;
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    std::vector<std::vector<bool>>                    constant_modes;
    DoFTools::extract_constant_modes(*dof_handler,
                                     ComponentMask(dim, true),
                                     constant_modes);
    data.constant_modes        = constant_modes;
    data.elliptic              = true;
    data.higher_order_elements = fe->degree > 1;
    data.smoother_sweeps       = 2;
    data.aggregation_threshold = 0.02;
    // the translations only: with the three rotations as well (six
    // near-null-space vectors) ML needs fewer CG iterations on 3D
    // elasticity (the spherical shell's Q3 system: 90 instead of 115) but
    // builds larger coarse levels: 1.6 times the wall time, 1.7 times the
    // memory
    amg.initialize(system_matrix, data);
    SolverControl control(
      parameters.mechanics.linear_max_iterations,
      std::max(parameters.mechanics.linear_tolerance * rhs_norm, 1e-300));
    SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
    try
      {
        cg.solve(system_matrix, update, system_rhs, amg);
      }
    catch (const SolverControl::NoConvergence &failure)
      {
        std::ostringstream message;
        message << "thermoelastic solver: CG did not converge in "
                << failure.last_step << " iterations (residual "
                << failure.last_residual << ", target " << control.tolerance()
                << "). Raise Mechanics/Linear solver maximum iterations, "
                   "loosen Mechanics/Linear solver tolerance, or check that "
                   "the boundary conditions remove the rigid-body motions "
                   "(Mechanics/Pinned points).";
        throw RunError(message.str());
      }
    total_linear_iterations += control.last_step();
    return control.last_step();
  }

  // ------------------------------------------------------------ Newton
  template <int dim>
  void
  ThermoelasticSolver<dim>::solve(const double time)
  {
    const bool root = Utilities::MPI::this_mpi_process(communicator) == 0;
    temperature_function->set_time(time);
    for (auto &functions : traction_functions)
      for (auto &function : functions)
        function->set_time(time);
    compute_quadrature_temperatures();

    double largest_modulus = 0.;
    for (const auto &material : materials)
      largest_modulus = std::max(largest_modulus, material.mu());
    // 1e-13 E times the size of the domain's boundary (a length in 2D, an
    // area in 3D): round-off of the nodal forces [N/m in 2D, N in 3D]
    const double boundary_size =
      dim == 2 ? std::sqrt(domain_area) : std::pow(domain_area, 2. / 3.);
    const double round_off  = 1e-13 * 3. * largest_modulus * boundary_size;
    const char  *force_unit = dim == 2 ? " N/m" : " N";

    make_newton_constraints(time);
    double residual  = residual_norm(solution);
    double reference = std::isfinite(residual) ? residual : 0.;
    newton_history.push_back({time, 0, residual, 0., 0});
    if (root)
      std::cerr << "newton t = " << time << ": iteration 0, |R| = " << residual
                << force_unit << std::endl;

    TrilinosWrappers::MPI::Vector update(locally_owned_dofs, communicator),
      trial(locally_owned_dofs, communicator);
    TrilinosWrappers::MPI::Vector trial_ghosted(locally_owned_dofs,
                                                locally_relevant_dofs,
                                                communicator);
    bool                          converged = false;
    for (unsigned int iteration = 1;
         iteration <= parameters.mechanics.newton_max_iterations;
         ++iteration)
      {
        const double boundary_increment = make_newton_constraints(time);
        if (!assemble(solution, newton_constraints, true))
          throw RunError("thermoelastic solver: an element is inverted (J <= "
                         "0) at t = " +
                         Utilities::to_string(time) +
                         " s; use smaller load steps (Time stepping/Time "
                         "step).");
        const unsigned int linear_iterations = solve_linear_system(update);
        newton_constraints.distribute(update);

        // backtracking: halve the step until the residual decreases (or,
        // while boundary values are still being applied, until no element
        // is inverted)
        double       step           = 1.;
        double       trial_residual = 0.;
        const double previous       = residual;
        for (unsigned int halving = 0; halving <= 10; ++halving)
          {
            trial = solution;
            trial.add(step, update);
            trial_ghosted  = trial;
            trial_residual = residual_norm(trial_ghosted);
            const bool acceptable =
              std::isfinite(trial_residual) &&
              (!parameters.mechanics.line_search || boundary_increment > 0. ||
               trial_residual < previous || trial_residual <= round_off);
            if (acceptable)
              break;
            if (halving == 10 || !parameters.mechanics.line_search)
              {
                if (!std::isfinite(trial_residual))
                  throw RunError(
                    "thermoelastic solver: every Newton step inverts an "
                    "element at t = " +
                    Utilities::to_string(time) +
                    " s; use smaller load steps (Time stepping/Time step).");
                break;
              }
            step *= 0.5;
          }
        solution  = trial_ghosted;
        residual  = trial_residual;
        reference = std::max(reference, residual);
        ++total_newton_iterations;
        newton_history.push_back(
          {time, iteration, residual, step, linear_iterations});
        if (root)
          std::cerr << "newton t = " << time << ": iteration " << iteration
                    << ", |R| = " << residual << force_unit << ", step " << step
                    << ", " << linear_iterations << " CG iterations"
                    << std::endl;
        const bool boundary_reached = boundary_increment == 0. || step == 1.;
        if (boundary_reached &&
            (residual <= parameters.mechanics.newton_tolerance * reference ||
             residual <= round_off))
          {
            converged = true;
            break;
          }
      }
    ++solves;
    if (!converged)
      {
        write_summary(time);
        std::ostringstream message;
        message << "thermoelastic solver: Newton did not converge at t = "
                << time << " s within Mechanics/Newton maximum iterations = "
                << parameters.mechanics.newton_max_iterations << " (residual "
                << residual << force_unit << ", target "
                << std::max(parameters.mechanics.newton_tolerance * reference,
                            round_off)
                << force_unit
                << "). Raise the iteration limit, or use smaller load "
                   "steps (Time stepping/Time step).";
        throw RunError(message.str());
      }
  }

  template class ThermoelasticSolver<2>;
  template class ThermoelasticSolver<3>;
} // namespace tmfdem
