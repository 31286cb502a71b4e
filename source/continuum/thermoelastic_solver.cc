#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/thread_local_storage.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/vector_tools.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/function_expression.h>
#include <tmfdem/continuum/thermoelastic_solver.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/monitors.h>
#include <tmfdem/io/output_files.h>
#include <tmfdem/mesh/mesh_checks.h>

namespace tmfdem
{
  namespace
  {
    using Condition = MechanicalBoundaryCondition;
  } // namespace

  // ------------------------------------------------------------ set up
  template <int dim>
  ThermoelasticSolver<dim>::ThermoelasticSolver(const Parameters &parameters,
                                                MPI_Comm          communicator)
    : ContinuumModel<dim>(parameters, communicator)
    , wall_start(std::chrono::steady_clock::now())
  {
    for (const auto &properties : parameters.materials.materials)
      materials.emplace_back(properties, parameters.mechanics);
    parameters.mechanics.check_dimension(dim);
    if (dim != 2 && parameters.mechanics.temperature_source ==
                      MechanicsParameters::TemperatureSource::discrete_heat)
      throw InputError(
        "Mechanics/Temperature source = discrete heat: the continuum stress "
        "takes the discrete layer's temperatures in 2D only; with "
        "Mesh/Dimension = 3 allowed are function and heat solver (or Model = "
        "discrete thermo-mechanics).");
    temperature_function =
      make_expression_function<dim>(parameters.mechanics.temperature,
                                    "Mechanics/Temperature");
    temperature_field =
      [this](const typename Triangulation<dim>::active_cell_iterator &,
             const std::vector<Point<dim>> &,
             const std::vector<Point<dim>> &points,
             std::vector<double>           &temperatures) {
        for (unsigned int q = 0; q < points.size(); ++q)
          temperatures[q] = temperature_function->value(points[q]);
      };
    const char *axes[] = {"x", "y", "z"};
    for (const auto &condition : parameters.mechanical_boundary.conditions)
      {
        std::array<std::unique_ptr<FunctionParser<dim>>, dim> displacement,
          traction;
        for (unsigned int d = 0; d < dim; ++d)
          {
            displacement[d] =
              make_expression_function<dim>(condition.displacement[d],
                                            condition.name + "/Displacement " +
                                              axes[d]);
            traction[d] =
              make_expression_function<dim>(condition.traction[d],
                                            condition.name + "/Traction " +
                                              axes[d]);
          }
        displacement_functions.push_back(std::move(displacement));
        traction_functions.push_back(std::move(traction));
      }
  }

  template <int dim>
  ThermoelasticSolver<dim>::~ThermoelasticSolver()
  {
    mesh_change_connection.disconnect();
  }

  template <int dim>
  double
  ThermoelasticSolver<dim>::wall_time() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() -
                                         wall_start)
      .count();
  }

  template <int dim>
  const TrilinosWrappers::MPI::Vector &
  ThermoelasticSolver<dim>::get_displacement() const
  {
    return solution;
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::set_temperature(const TemperatureField &field)
  {
    temperature_field = field;
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::set_temperature(
    const DoFHandler<dim>               &temperature_dofs,
    const Mapping<dim>                  &temperature_mapping,
    const TrilinosWrappers::MPI::Vector &temperature)
  {
    // FEValues cached for the last set of unit points (the quadrature
    // points during assembly), rebuilt when they change; one cache per
    // thread: assembly and DataOut's postprocessor call this from TBB tasks
    struct Cache
    {
      std::vector<Point<dim>>        unit_points;
      std::unique_ptr<FEValues<dim>> fe_values;
    };
    auto caches = std::make_shared<Threads::ThreadLocalStorage<Cache>>();
    temperature_field =
      [&temperature_dofs,
       &temperature_mapping,
       &temperature,
       caches](const typename Triangulation<dim>::active_cell_iterator &cell,
               const std::vector<Point<dim>> &unit_points,
               const std::vector<Point<dim>> &,
               std::vector<double> &temperatures) {
        Cache &cache = caches->get();
        if (!cache.fe_values || cache.unit_points != unit_points)
          {
            cache.unit_points = unit_points;
            cache.fe_values =
              std::make_unique<FEValues<dim>>(temperature_mapping,
                                              temperature_dofs.get_fe(),
                                              Quadrature<dim>(unit_points),
                                              update_values);
          }
        const typename DoFHandler<dim>::active_cell_iterator temperature_cell(
          &cell->get_triangulation(),
          cell->level(),
          cell->index(),
          &temperature_dofs);
        cache.fe_values->reinit(temperature_cell);
        cache.fe_values->get_function_values(temperature, temperatures);
      };
  }

  template <int dim>
  std::vector<double>
  ThermoelasticSolver<dim>::temperatures_at(
    const typename Triangulation<dim>::active_cell_iterator &cell,
    const std::vector<Point<dim>>                           &unit_points,
    const std::vector<Point<dim>>                           &points) const
  {
    std::vector<double> temperatures(points.size());
    temperature_field(cell, unit_points, points, temperatures);
    return temperatures;
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::check_boundary_conditions() const
  {
    for (const auto &condition : parameters.mechanical_boundary.conditions)
      {
        if (condition.type == Condition::Type::velocity)
          throw InputError(
            condition.name +
            "/Type = velocity: prescribed velocities are for the discrete "
            "layer only; the continuum thermoelastic solver is quasi-static "
            "and accepts fixed, roller x, roller y, roller z (3D), "
            "displacement and traction.");
        check_boundary_ids(condition.name, condition.boundary_ids);
      }
    check_material_ids();
    check_adaptivity();
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::setup(parallel::TriangulationBase<dim> *external)
  {
    if (external != nullptr)
      use_mesh(*external);
    else
      {
        create_mesh();
        if (Utilities::MPI::this_mpi_process(communicator) == 0)
          std::cout << mesh_report->to_string();
      }
    mesh_change_connection.disconnect();
    mesh_change_connection = triangulation->signals.any_change.connect(
      [this]() { mesh_changed = true; });

    const unsigned int degree = parameters.mechanics.degree;
    create_fe(degree, dim);
    check_boundary_conditions();
    setup_dofs();
    domain_area = GridTools::volume(*triangulation, *mapping);

    std::vector<std::string> fields =
      dim == 2 ?
        std::vector<std::string>{"T", "ux", "uy", "sxx", "syy", "sxy"} :
        std::vector<std::string>{"T",
                                 "ux",
                                 "uy",
                                 "uz",
                                 "sxx",
                                 "syy",
                                 "szz",
                                 "sxy",
                                 "syz",
                                 "sxz"};
    if (parameters.mechanics.polar_frame)
      {
        fields.push_back("srr");
        fields.push_back("stt");
      }
    monitors = std::make_unique<Monitors<dim>>(parameters.monitors,
                                               parameters.output.directory,
                                               fields,
                                               communicator);
    monitors->check_points(*mapping, *dof_handler);
    open_solution_series();
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      std::cout << "thermoelastic: " << triangulation->n_global_active_cells()
                << " cells, " << dof_handler->n_dofs()
                << " displacement dofs (degree " << degree << ")" << std::endl;
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::setup_dofs()
  {
    distribute_dofs();
    hanging_node_constraints.clear();
    hanging_node_constraints.reinit(locally_relevant_dofs);
    DoFTools::make_hanging_node_constraints(*dof_handler,
                                            hanging_node_constraints);
    hanging_node_constraints.close();
    find_pinned_dofs();

    // the sparsity pattern with every DoF that may be constrained kept free
    const DynamicSparsityPattern pattern =
      distributed_sparsity(&hanging_node_constraints);
    system_matrix.reinit(locally_owned_dofs,
                         locally_owned_dofs,
                         pattern,
                         communicator);
    system_rhs.reinit(locally_owned_dofs, communicator);
    solution.reinit(locally_owned_dofs, locally_relevant_dofs, communicator);
    mesh_changed = false;
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::find_pinned_dofs()
  {
    pinned_dofs.clear();
    const unsigned int dofs_per_vertex = fe->n_dofs_per_vertex();
    std::vector<types::global_dof_index> cell_dofs(fe->n_dofs_per_cell());
    for (const auto &point : parameters.mechanics.pinned_points)
      {
        double           found = 0.;
        const Point<dim> location =
          MeshParameters::in_dimension<dim>(point.location);
        for (const auto &cell : dof_handler->active_cell_iterators())
          if (!cell->is_artificial())
            for (const auto v : cell->vertex_indices())
              if (cell->vertex(v).distance(location) < 1e-6 * cell->diameter())
                {
                  found = 1.;
                  cell->get_dof_indices(cell_dofs);
                  for (unsigned int i = 0; i < dofs_per_vertex; ++i)
                    {
                      const unsigned int local = v * dofs_per_vertex + i;
                      const unsigned int component =
                        fe->system_to_component_index(local).first;
                      if ((component == 0 && point.fix_x) ||
                          (component == 1 && point.fix_y) ||
                          (component == 2 && point.fix_z))
                        pinned_dofs.push_back(cell_dofs[local]);
                    }
                }
        if (Utilities::MPI::max(found, communicator) == 0.)
          throw InputError("Mechanics/Pinned points: the point in '" +
                           point.text +
                           "' is not a vertex of the mesh; allowed are mesh "
                           "vertices (e.g. where a circle meets an axis).");
      }
    std::sort(pinned_dofs.begin(), pinned_dofs.end());
    pinned_dofs.erase(std::unique(pinned_dofs.begin(), pinned_dofs.end()),
                      pinned_dofs.end());
  }

  // ------------------------------------------------------------ AMR
  template <int dim>
  void
  ThermoelasticSolver<dim>::adapt_mesh()
  {
    TrilinosWrappers::MPI::Vector distributed;
    refine_mesh_by_kelly(
      solution,
      [this]() { setup_dofs(); },
      &distributed);
    hanging_node_constraints.distribute(distributed);
    solution = distributed;
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::follow_mesh_change()
  {
    if (!mesh_changed)
      return;
    // the owner of the mesh adapted it: start from rest
    setup_dofs();
    solution = 0;
  }

  // ------------------------------------------------------------ drivers
  template <int dim>
  void
  ThermoelasticSolver<dim>::check_initial_conditions() const
  {
    if (parameters.initial.stress_free)
      throw InputError(
        "Initial conditions/Stress free = true: the continuum thermoelastic "
        "model measures the thermal strain from each material's Reference "
        "temperature; allowed is false (set the Reference temperature "
        "instead).");
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::check_input()
  {
    check_initial_conditions();
    // Temperature source = heat solver: coupling::ContinuumThermomechanics
    // sets up this solver on the heat solver's mesh
    setup();
    if (parameters.mechanics.temperature_source ==
        MechanicsParameters::TemperatureSource::discrete_heat)
      {
        if (parameters.adaptivity.enable)
          throw InputError(
            "Adaptive refinement/Enable = true: Mechanics/Temperature "
            "source = discrete heat keeps the mesh; allowed is false.");
        if constexpr (dim == 2)
          create_temperature_field_source("discrete heat",
                                          parameters,
                                          *triangulation,
                                          communicator);
      }
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::run()
  {
    refuse_resume();
    run_with_temperature_function();
    report_done();
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::report_done() const
  {
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      std::cout << "done: " << solves << " solves, " << total_newton_iterations
                << " Newton iterations, " << total_linear_iterations
                << " CG iterations, " << triangulation->n_global_active_cells()
                << " cells, " << dof_handler->n_dofs() << " dofs, "
                << wall_time() << " s wall" << std::endl;
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::run_with_temperature_function()
  {
    setup();
    // Temperature source = discrete heat: the discrete layer's heat on this
    // mesh, advanced to the time of every solve
    std::unique_ptr<TemperatureFieldSource> field_source;
    if constexpr (dim == 2)
      if (parameters.mechanics.temperature_source ==
          MechanicsParameters::TemperatureSource::discrete_heat)
        {
          field_source = create_temperature_field_source("discrete heat",
                                                         parameters,
                                                         *triangulation,
                                                         communicator);
          set_temperature(field_source->field());
        }
    const auto solve_at = [&](const double time) {
      if (field_source)
        field_source->advance_to(time);
      solve(time);
    };
    const auto &time_parameters = parameters.time;
    if (time_parameters.mode == TimeSteppingParameters::Mode::steady)
      {
        const double       time     = time_parameters.start_time;
        const unsigned int n_cycles = parameters.adaptivity.enable ?
                                        parameters.adaptivity.steady_cycles :
                                        1;
        for (unsigned int cycle = 0; cycle < n_cycles; ++cycle)
          {
            if (cycle > 0)
              adapt_mesh();
            solve_at(time);
            if (Utilities::MPI::this_mpi_process(communicator) == 0)
              std::cout << "cycle " << cycle << ": "
                        << triangulation->n_global_active_cells() << " cells, "
                        << dof_handler->n_dofs() << " dofs" << std::endl;
          }
        write_output(time);
        return;
      }

    // quasi-static load steps at every time step; outputs at the output
    // times (the step is shortened to land on them) and at the end
    const double start            = time_parameters.start_time,
                 end              = time_parameters.end_time;
    const OutputSchedule schedule = output_schedule();
    ProgressReporter     progress(parameters.output.progress_interval,
                              start,
                              end,
                              Utilities::MPI::this_mpi_process(communicator) ==
                                0);
    double               time = start;
    unsigned long        step = 0;
    solve_at(time);
    write_output(time);
    for (const double output_time : schedule.times())
      while (time < output_time - schedule.tolerance())
        {
          const double dt =
            OutputSchedule::step_towards(time,
                                         output_time,
                                         time_parameters.time_step);
          time =
            schedule.reached(time + dt, output_time) ? output_time : time + dt;
          solve_at(time);
          ++step;
          const bool at_output = schedule.reached(time, output_time);
          if (at_output)
            write_output(output_time);
          if (parameters.adaptivity.enable &&
              step % parameters.adaptivity.interval == 0 &&
              time < end - schedule.tolerance())
            adapt_mesh();
          progress.update(step, time);
          stop_if_requested(time, step, [&]() {
            if (!at_output)
              write_output(time);
          });
        }
  }

  template class ThermoelasticSolver<2>;
  template class ThermoelasticSolver<3>;
} // namespace tmfdem
