#include <algorithm>
#include <tmfdem/continuum/heat_solver.h>
#include <tmfdem/continuum/thermoelastic_solver.h>
#include <tmfdem/coupling/continuum_thermomechanics.h>
#include <tmfdem/io/output_files.h>
#include <tmfdem/io/output_schedule.h>

namespace tmfdem
{
  namespace coupling
  {
    namespace
    {
      // the model: the stress from a temperature function or the discrete
      // heat is ThermoelasticSolver alone, from the heat solver this loop
      const bool registered = register_simulation(
        "continuum thermoelastic",
        "quasi-static thermal stress with deal.II in 2D or 3D: small or "
        "finite strain, plane stress, plane strain or 3D, temperature from a "
        "function or the continuum heat solver (Newton, AMR on "
        "quadrilaterals and hexahedra, MPI)",
        {{"Mesh",
          "Materials",
          "Initial conditions",
          "Time stepping",
          "Adaptive refinement",
          "Mechanics",
          "Mechanical boundary conditions",
          "Output",
          "Monitors",
          "Checkpoint"},
         {{"Mechanics/Temperature source = heat solver",
           {"Thermal boundary conditions", "Heat solver"},
           [](const Parameters &parameters) {
             return parameters.mechanics.temperature_source ==
                    MechanicsParameters::TemperatureSource::heat_solver;
           }},
          {"Mechanics/Temperature source = discrete heat",
           {"Thermal boundary conditions",
            "Discrete heat",
            "Discrete mechanics",
            "Discrete bodies"},
           [](const Parameters &parameters) {
             return parameters.mechanics.temperature_source ==
                    MechanicsParameters::TemperatureSource::discrete_heat;
           }}}},
        [](const Parameters &parameters,
           MPI_Comm          communicator) -> std::unique_ptr<Simulation> {
          const bool from_heat_solver =
            parameters.mechanics.temperature_source ==
            MechanicsParameters::TemperatureSource::heat_solver;
          if (parameters.mesh.dimension == 3)
            {
              if (from_heat_solver)
                return std::make_unique<ContinuumThermomechanics<3>>(
                  parameters,
                  communicator);
              return std::make_unique<ThermoelasticSolver<3>>(parameters,
                                                              communicator);
            }
          if (from_heat_solver)
            return std::make_unique<ContinuumThermomechanics<2>>(parameters,
                                                                 communicator);
          return std::make_unique<ThermoelasticSolver<2>>(parameters,
                                                          communicator);
        },
        {2, 3});

      /** The heat solver's parameters: outputs in <directory>/heat. */
      Parameters
      heat_parameters(const Parameters &parameters)
      {
        Parameters heat       = parameters;
        heat.model            = "continuum heat";
        heat.output.directory = parameters.output.directory + "/heat";
        return heat;
      }
    } // namespace

    template <int dim>
    ContinuumThermomechanics<dim>::ContinuumThermomechanics(
      const Parameters &parameters,
      MPI_Comm          communicator)
      : parameters(parameters)
      , communicator(communicator)
      , heat(std::make_unique<HeatSolver<dim>>(heat_parameters(parameters),
                                               communicator))
      , mechanics(
          std::make_unique<ThermoelasticSolver<dim>>(parameters, communicator))
    {}

    template <int dim>
    ContinuumThermomechanics<dim>::~ContinuumThermomechanics()
    {
      // the mechanics' DoFs live on the heat solver's mesh
      mechanics.reset();
    }

    template <int dim>
    void
    ContinuumThermomechanics<dim>::check_input()
    {
      mechanics->check_initial_conditions();
      heat->check_input();
      create_output_folder(parameters.output.directory, communicator);
      mechanics->setup(&heat->get_triangulation());
      mechanics_set_up = true;
    }

    template <int dim>
    void
    ContinuumThermomechanics<dim>::run()
    {
      mechanics->refuse_resume();
      create_output_folder(parameters.output.directory, communicator);
      heat->check_input();
      if (parameters.time.mode == TimeSteppingParameters::Mode::steady)
        run_steady();
      else
        run_transient();
      mechanics->report_done();
    }

    template <int dim>
    void
    ContinuumThermomechanics<dim>::solve_mechanics(const double time)
    {
      if (!mechanics_set_up)
        {
          mechanics->setup(&heat->get_triangulation());
          mechanics_set_up = true;
        }
      else
        mechanics->follow_mesh_change();
      mechanics->set_temperature(heat->get_dof_handler(),
                                 heat->get_mapping(),
                                 heat->get_temperature());
      mechanics->solve(time);
    }

    template <int dim>
    void
    ContinuumThermomechanics<dim>::write_outputs(const double time)
    {
      mechanics->write_output(time);
      heat->write_output(time);
    }

    template <int dim>
    void
    ContinuumThermomechanics<dim>::run_steady()
    {
      ProgressReporter progress(parameters.output.progress_interval,
                                0.,
                                1.,
                                false);
      heat->solve_steady();
      const double time = heat->current_time();
      solve_mechanics(time);
      write_outputs(time);
      heat->write_summary(time, progress.elapsed(), false);
    }

    // The loop: heat steps land on every coupling time; there the
    // mechanics takes the temperature and is solved; at output times both
    // write. With Coupling interval = 0 the coupling times are the output
    // times.
    template <int dim>
    void
    ContinuumThermomechanics<dim>::run_transient()
    {
      const double start = parameters.time.start_time,
                   end   = parameters.time.end_time;
      const OutputSchedule outputs(parameters.output, start, end);
      const OutputSchedule coupling(outputs.times(),
                                    parameters.mechanics.coupling_interval,
                                    start,
                                    end,
                                    outputs.tolerance());
      const double         tolerance = coupling.tolerance();
      const auto           is_output = [&](const double time) {
        return std::any_of(outputs.times().begin(),
                           outputs.times().end(),
                           [&](const double t) {
                             return outputs.reached(time, t);
                           });
      };

      heat->prepare_transient();
      ProgressReporter progress(parameters.output.progress_interval,
                                start,
                                end,
                                Utilities::MPI::this_mpi_process(
                                  communicator) == 0);
      solve_mechanics(start);
      write_outputs(start);
      for (const double coupling_time : coupling.times())
        while (heat->current_time() < coupling_time - tolerance)
          {
            heat->step_towards(coupling_time, tolerance);
            const double time        = heat->current_time();
            const bool   at_coupling = coupling.reached(time, coupling_time);
            if (at_coupling)
              {
                solve_mechanics(coupling_time);
                if (is_output(coupling_time))
                  write_outputs(coupling_time);
              }
            progress.update(heat->steps_taken(), time);
            // a stop between output times writes the state now as well
            heat->stop_if_requested(time, heat->steps_taken(), [&]() {
              if (!at_coupling || !is_output(coupling_time))
                {
                  if (!at_coupling)
                    solve_mechanics(time);
                  write_outputs(time);
                }
              heat->write_summary(time, progress.elapsed(), false);
            });
          }
      heat->write_summary(heat->current_time(), progress.elapsed(), true);
    }

    template class ContinuumThermomechanics<2>;
    template class ContinuumThermomechanics<3>;
  } // namespace coupling
} // namespace tmfdem
