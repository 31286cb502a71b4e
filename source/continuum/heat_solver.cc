#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <regex>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>
#include <tmfdem/continuum/heat_solver.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/monitors.h>
#include <tmfdem/io/output_files.h>
#include <tmfdem/mesh/mesh_checks.h>

namespace tmfdem
{
  namespace
  {
    const bool registered = register_simulation(
      "continuum heat",
      "transient or steady heat conduction with deal.II in 2D or 3D (theta "
      "scheme, AMR on quadrilaterals and hexahedra, MPI)",
      {{"Mesh",
        "Materials",
        "Thermal boundary conditions",
        "Initial conditions",
        "Time stepping",
        "Adaptive refinement",
        "Heat solver",
        "Output",
        "Monitors",
        "Checkpoint"},
       {}},
      [](const Parameters &parameters,
         MPI_Comm          communicator) -> std::unique_ptr<Simulation> {
        if (parameters.mesh.dimension == 3)
          return std::make_unique<HeatSolver<3>>(parameters, communicator);
        return std::make_unique<HeatSolver<2>>(parameters, communicator);
      },
      {2, 3});

    /** Does @p expression use the variable t? */
    bool
    depends_on_time(const std::string &expression)
    {
      static const std::regex time_variable(
        "(^|[^A-Za-z0-9_])t([^A-Za-z0-9_]|$)");
      return std::regex_search(expression, time_variable);
    }
  } // namespace

  template <int dim>
  HeatSolver<dim>::HeatSolver(const Parameters &parameters,
                              MPI_Comm          communicator)
    : ContinuumModel<dim>(parameters, communicator)
    , theta(parameters.time.theta)
  {
    for (unsigned int id = 0; id < MaterialParameters::max_materials; ++id)
      {
        const std::string expression =
          parameters.materials.materials[id].heat_source;
        heat_sources.push_back(
          make_expression_function<dim>(expression,
                                        "Materials/Material " +
                                          std::to_string(id) +
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
          make_expression_function<dim>(condition.temperature,
                                        condition.name + "/Temperature");
        functions.heat_flux =
          make_expression_function<dim>(condition.heat_flux,
                                        condition.name + "/Heat flux");
        functions.heat_transfer_coefficient =
          make_expression_function<dim>(condition.heat_transfer_coefficient,
                                        condition.name +
                                          "/Heat transfer coefficient");
        functions.ambient_temperature =
          make_expression_function<dim>(condition.ambient_temperature,
                                        condition.name +
                                          "/Ambient temperature");
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
      make_expression_function<dim>(parameters.initial.temperature,
                                    "Initial conditions/Temperature");
  }

  template <int dim>
  HeatSolver<dim>::~HeatSolver() = default;

  template <int dim>
  const TrilinosWrappers::MPI::Vector &
  HeatSolver<dim>::get_temperature() const
  {
    return solution;
  }

  template <int dim>
  double
  HeatSolver<dim>::memory_estimate() const
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
  template <int dim>
  void
  HeatSolver<dim>::make_mesh()
  {
    create_mesh();
    create_fe(parameters.heat_solver.degree, 1);
    for (const auto &condition : parameters.thermal_boundary.conditions)
      check_boundary_ids(condition.name, condition.boundary_ids);
    check_material_ids();
    check_adaptivity();
  }

  // ------------------------------------------------------------ set up
  template <int dim>
  void
  HeatSolver<dim>::setup_dofs()
  {
    distribute_dofs();

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

    const DynamicSparsityPattern sparsity = distributed_sparsity(&constraints);
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

    const DynamicSparsityPattern full_sparsity = distributed_sparsity(nullptr);
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
    // owned entries plus writable entries of the relevant DoFs of other
    // ranks (the condensation adds into them, heat_assembly.cc)
    condense_transfer.reinit(locally_owned_dofs,
                             locally_relevant_dofs,
                             communicator,
                             true);
    for (auto &level : variable_loads)
      level.valid = false;
    reaction_rows.clear();
    reaction_columns.clear();
    reaction_values.clear();
  }

  template <int dim>
  void
  HeatSolver<dim>::make_constraints(const double time)
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

  // ------------------------------------------------------------ initial
  template <int dim>
  void
  HeatSolver<dim>::set_initial_condition(const bool hold_dirichlet)
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
        std::vector<std::unique_ptr<FunctionParser<dim>>> functions;
        std::map<std::string, unsigned int>               index_of_entry;
        std::map<types::material_id, unsigned int>        entry_of_material;
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
                make_expression_function<dim>(entry.expression, entry.entry));
              functions.back()->set_time(parameters.time.start_time);
            }
          entry_of_material[id] = it->second;
          return it->second;
        };
        const unsigned int         n_owned = locally_owned_dofs.n_elements();
        std::vector<std::uint32_t> entries_at(n_owned, 0); // bit per entry
        std::vector<Point<dim>>    point_of(n_owned);
        FEValues<dim>              fe_values(*mapping,
                                *fe,
                                Quadrature<dim>(fe->get_unit_support_points()),
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
    set_state(distributed);
  }

  template <int dim>
  void
  HeatSolver<dim>::set_state(const TrilinosWrappers::MPI::Vector &temperature)
  {
    solution           = temperature;
    owned_solution     = temperature;
    owned_old_solution = temperature;
  }

  template <int dim>
  void
  HeatSolver<dim>::adapt_mesh(const bool transfer_solution)
  {
    TrilinosWrappers::MPI::Vector distributed;
    refine_mesh_by_kelly(
      solution,
      [this]() {
        setup_dofs();
        compute_cell_matrices();
      },
      transfer_solution ? &distributed : nullptr);
    if (transfer_solution)
      {
        constraints.distribute(distributed);
        set_state(distributed);
      }
  }

  // ------------------------------------------------------------ output
  template <int dim>
  void
  HeatSolver<dim>::write_output(const double time)
  {
    monitors->write(time, *mapping, *dof_handler, solution);
    if (!parameters.output.write_vtu)
      return;
    DataOut<dim> data_out;
    data_out.attach_dof_handler(*dof_handler);
    data_out.add_data_vector(solution, "T");
    write_solution(data_out, time);
  }

  template <int dim>
  void
  HeatSolver<dim>::write_summary(const double end_time,
                                 const double wall_time,
                                 const bool   report_done) const
  {
    const unsigned long steps   = stepping.step;
    const HeatBalance  &balance = stepping.balance;
    const bool          steady =
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
           std::string(dim == 3 ? (steady ? "W (rates)" : "J") :
                       steady   ? "W/m (rates, per unit thickness)" :
                                  "J/m (per unit thickness)"))
      .add("boundary_heat_in", per_boundary)
      .add("source_heat", balance.source_heat)
      .add("stored_heat", balance.stored_heat)
      .add("total_heat_in", total_in)
      .add("imbalance", imbalance)
      .add("relative_imbalance", scale > 0 ? std::abs(imbalance) / scale : 0.);

    std::vector<JsonObject> cycle_objects;
    for (const auto &cycle : adaptive_cycles)
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

    JsonObject summary = summary_head();
    summary.add("mode", std::string(steady ? "steady" : "transient"))
      .add("time_method",
           steady ? std::string("none") : parameters.time.method);
    add_run_entries(summary, steps, end_time, wall_time);
    summary
      .add("linear_iterations", static_cast<long long>(total_linear_iterations))
      .add("broken_joints", 0u)
      .add("cracks", 0u)
      .add("heat", heat);
    if (!cycle_objects.empty())
      summary.add("adaptive_cycles", cycle_objects);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_file_atomically(parameters.output.directory + "/summary.json",
                            summary.str() + "\n");
    if (report_done && Utilities::MPI::this_mpi_process(communicator) == 0)
      std::cout << "done: " << steps << " steps to t = " << end_time << " s, "
                << triangulation->n_global_active_cells() << " cells, "
                << dof_handler->n_dofs() << " dofs, " << total_linear_iterations
                << " CG iterations, " << wall_time << " s wall" << std::endl;
  }

  // ------------------------------------------------------------ drivers
  template <int dim>
  void
  HeatSolver<dim>::check_input()
  {
    make_mesh();
    setup_dofs();
    monitors = std::make_unique<Monitors<dim>>(parameters.monitors,
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

  template <int dim>
  void
  HeatSolver<dim>::report_validation(std::ostream     &out,
                                     const Parameters &run_parameters,
                                     MPI_Comm          run_communicator) const
  {
    double smallest = std::numeric_limits<double>::max();
    for (const auto &cell : triangulation->active_cell_iterators())
      if (cell->is_locally_owned())
        smallest = std::min(smallest, cell->minimum_vertex_distance());
    smallest = Utilities::MPI::min(smallest, run_communicator);
    out << "continuum heat: smallest cell " << smallest << " m\n";
    if (run_parameters.time.mode == TimeSteppingParameters::Mode::transient)
      validation::describe_steps(out,
                                 "time step",
                                 0.,
                                 run_parameters.time.time_step,
                                 run_parameters);
    out << "  matrices, element matrices and vectors: about "
        << Utilities::MPI::sum(memory_estimate(), run_communicator) /
             validation::mebibyte
        << " MiB (before adaptive refinement)\n";
  }

  template <int dim>
  void
  HeatSolver<dim>::run()
  {
    refuse_resume();
    check_input();
    if (parameters.time.mode == TimeSteppingParameters::Mode::steady)
      run_steady();
    else
      run_transient();
  }

  template <int dim>
  void
  HeatSolver<dim>::run_steady()
  {
    ProgressReporter progress(parameters.output.progress_interval,
                              0.,
                              1.,
                              false);
    solve_steady();
    write_output(stepping.time);
    write_summary(stepping.time, progress.elapsed(), false);
  }

  template <int dim>
  void
  HeatSolver<dim>::solve_steady()
  {
    open_solution_series();
    stepping      = SteppingState();
    stepping.time = parameters.time.start_time;
    adaptive_cycles.clear();
    const unsigned int n_cycles =
      parameters.adaptivity.enable ? parameters.adaptivity.steady_cycles : 1;
    const double time = stepping.time;
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
        adaptive_cycles.push_back(record.str());
        if (Utilities::MPI::this_mpi_process(communicator) == 0)
          std::cout << "cycle " << cycle << ": "
                    << triangulation->n_global_active_cells() << " cells, "
                    << dof_handler->n_dofs() << " dofs, " << iterations
                    << " CG iterations" << std::endl;
      }
    accumulate_heat_balance(stepping.balance);
  }

  // ------------------------------------------------------------ stepping
  template <int dim>
  void
  HeatSolver<dim>::start_stepping()
  {
    stepping                           = SteppingState();
    stepping.time                      = parameters.time.start_time;
    stepping.dirichlet_depends_on_time = false;
    for (const auto &functions : boundary_functions)
      stepping.dirichlet_depends_on_time |=
        functions.time_dependent_temperature;
  }

  template <int dim>
  bool
  HeatSolver<dim>::in_rannacher_start() const
  {
    return parameters.time.theta < 1. &&
           stepping.step < parameters.time.rannacher_steps;
  }

  template <int dim>
  void
  HeatSolver<dim>::advance(const double dt)
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

  template <int dim>
  void
  HeatSolver<dim>::prepare_coupled_stepping()
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

  template <int dim>
  void
  HeatSolver<dim>::restore_state(const double               time,
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

  template <int dim>
  void
  HeatSolver<dim>::prepare_transient()
  {
    open_solution_series();
    if (parameters.adaptivity.enable)
      for (unsigned int k = 0; k < parameters.adaptivity.initial_refinements;
           ++k)
        {
          set_initial_condition(true);
          adapt_mesh(false);
        }
    set_initial_condition(false);
    compute_cell_matrices();
    start_stepping();
  }

  template <int dim>
  void
  HeatSolver<dim>::step_towards(const double target, const double tolerance)
  {
    // Rannacher start of Crank-Nicolson: backward Euler half steps
    double dt = parameters.time.time_step;
    if (in_rannacher_start())
      dt *= 0.5;
    advance(OutputSchedule::step_towards(stepping.time, target, dt));
    if (std::abs(stepping.time - target) < tolerance)
      stepping.time = target;
    if (parameters.adaptivity.enable &&
        stepping.step % parameters.adaptivity.interval == 0)
      {
        adapt_mesh(true);
        make_constraints(stepping.time);
        stepping.matrix_is_current = false;
      }
  }

  template <int dim>
  void
  HeatSolver<dim>::run_transient()
  {
    prepare_transient();
    const OutputSchedule schedule = output_schedule();
    ProgressReporter     progress(parameters.output.progress_interval,
                              parameters.time.start_time,
                              parameters.time.end_time,
                              Utilities::MPI::this_mpi_process(communicator) ==
                                0);
    const double        &time = stepping.time;
    write_output(time);
    for (const double output_time : schedule.times())
      while (time < output_time - schedule.tolerance())
        {
          step_towards(output_time, schedule.tolerance());
          const bool at_output = schedule.reached(time, output_time);
          if (at_output)
            write_output(output_time);
          progress.update(stepping.step, time);
          // finish cleanly: the state now as an extra output, the summary
          // so far (no checkpoint: continuum runs restart)
          stop_if_requested(time, stepping.step, [&]() {
            if (!at_output)
              write_output(time);
            write_summary(time, progress.elapsed(), false);
          });
        }
    write_summary(time, progress.elapsed(), true);
  }
  template class HeatSolver<2>;
  template class HeatSolver<3>;
} // namespace tmfdem
