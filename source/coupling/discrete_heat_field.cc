#include <deal.II/base/mpi.h>

#include <cmath>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/coupling/discrete_heat_field.h>
#include <tmfdem/discrete/discrete_heat.h>

namespace tmfdem
{
  namespace coupling
  {
    namespace
    {
      const bool registered = register_temperature_field_source(
        "discrete heat",
        [](const Parameters       &parameters,
           const Triangulation<2> &triangulation,
           MPI_Comm                communicator) {
          return std::make_unique<DiscreteHeatField>(parameters,
                                                     triangulation,
                                                     communicator);
        });
    } // namespace

    DiscreteHeatField::DiscreteHeatField(const Parameters       &parameters,
                                         const Triangulation<2> &triangulation,
                                         MPI_Comm                communicator)
      : parameters(parameters)
      , fe(1)
      , dof_handler(triangulation)
    {
      if (Utilities::MPI::n_mpi_processes(communicator) > 1)
        throw InputError("Mechanics/Temperature source = discrete heat runs "
                         "on one MPI process (the discrete layer's heat); "
                         "run it without mpirun -np > 1.");
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->reference_cell() != ReferenceCells::Triangle)
          throw InputError(
            "Mechanics/Temperature source = discrete heat needs a triangle "
            "mesh (Mesh/Element type = triangles); the discrete heat lives "
            "on exploded triangles.");
      if (parameters.time.mode == TimeSteppingParameters::Mode::steady)
        throw InputError("Mechanics/Temperature source = discrete heat steps "
                         "in time; allowed is Time stepping/Mode = "
                         "transient.");
      dof_handler.distribute_dofs(fe);
      model.build(dof_handler);
      heat = std::make_unique<discrete::DiscreteHeat>(parameters, model);
      time = parameters.time.start_time;
      heat->initialise(time);
    }

    DiscreteHeatField::~DiscreteHeatField()
    {
      heat.reset();
      dof_handler.clear();
    }

    void
    DiscreteHeatField::advance_to(const double target)
    {
      const double step      = parameters.time.time_step;
      const double tolerance = 1e-10 * std::max(1., std::abs(target));
      while (time < target - tolerance)
        {
          double dt = std::min(step, target - time);
          // never leave a sliver of a step
          if (target - (time + dt) < 1e-3 * step)
            dt = target - time;
          heat->update_contact_pairs();
          heat->step(time, dt);
          time = std::abs(time + dt - target) < tolerance ? target : time + dt;
        }
    }

    TemperatureField
    DiscreteHeatField::field() const
    {
      return [this](const Triangulation<2>::active_cell_iterator &cell,
                    const std::vector<Point<2>>                  &unit_points,
                    const std::vector<Point<2>> &,
                    std::vector<double> &temperatures) {
        // node 3e+k is vertex k of element e (discrete_model.h)
        const unsigned int    e = cell->active_cell_index();
        const Vector<double> &T = heat->temperature();
        for (unsigned int q = 0; q < unit_points.size(); ++q)
          {
            const double x = unit_points[q][0], y = unit_points[q][1];
            temperatures[q] =
              T[3 * e] * (1. - x - y) + T[3 * e + 1] * x + T[3 * e + 2] * y;
          }
      };
    }

    double
    DiscreteHeatField::relative_imbalance() const
    {
      const auto &b = heat->balance();
      return std::abs(b.imbalance()) / b.scale();
    }
  } // namespace coupling
} // namespace tmfdem
