/**
 * @file
 * The heat of the discrete layer in 3D and its coupling to the mechanics
 * of the tetrahedra (models `discrete heat` and `discrete thermo-mechanics`
 * with Mesh/Dimension = 3), the multi-rate loop of 2D: one thermal step of
 * TetrahedralHeat every n mechanical steps over the same time, at the
 * current geometry and joints (M -> T), then the new thermal stretch
 * F_T = s I of every tetrahedron from its mean temperature (T -> M). The
 * strain energy each new stretch changes at fixed geometry is the thermal
 * work of the energy balance.
 */
#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/threads.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/tetrahedral_heat.h>
#include <tmfdem/discrete/tetrahedral_solver.h>

namespace tmfdem
{
  namespace discrete
  {
    void
    TetrahedralSolver::setup_heat()
    {
      const auto &dh = parameters.get<DiscreteHeatParameters>();
      heat           = std::make_unique<TetrahedralHeat>(parameters, model);
      heat->set_threads(n_threads);
      heat->initialise(parameters.time.start_time);
      thermal_time    = parameters.time.start_time;
      n_thermal_steps = 0;
      if (!with_mechanics())
        {
          // the heat alone marches at Time stepping/Time step
          time_step = parameters.time.time_step;
          if (!heat->implicit() && time_step > heat->stable_time_step())
            throw InputError(
              "Time stepping/Time step = " + Utilities::to_string(time_step) +
              " s exceeds the stable explicit thermal step " +
              Utilities::to_string(heat->stable_time_step()) +
              " s of this mesh (lumped capacity, joint conductance, Robin "
              "coefficients); allowed is at most the stable step, or "
              "Discrete heat/Time integration = implicit.");
          return;
        }
      // the multi-rate cadence, as in 2D
      const unsigned int n = dh.mechanical_steps_per_thermal_step;
      if (n > 0)
        steps_per_thermal_step = n;
      else if (heat->implicit())
        steps_per_thermal_step =
          std::max(1., std::floor(parameters.time.time_step / time_step + 0.5));
      else
        steps_per_thermal_step =
          std::max(1.,
                   std::floor(dh.safety_factor * heat->stable_time_step() /
                              time_step));
      const double thermal_step = steps_per_thermal_step * time_step;
      if (!heat->implicit() && thermal_step > heat->stable_time_step())
        throw InputError("Discrete heat/Mechanical steps per thermal step = " +
                         std::to_string(steps_per_thermal_step) +
                         " makes the thermal step " +
                         Utilities::to_string(thermal_step) +
                         " s, above the stable explicit thermal step " +
                         Utilities::to_string(heat->stable_time_step()) +
                         " s; allowed is at most " +
                         std::to_string(static_cast<unsigned long>(
                           heat->stable_time_step() / time_step)) +
                         ", or 0 (automatic), or implicit heat.");
      // the stress-free temperature of each tetrahedron
      reference_temperature.resize(model.n_elements);
      for (unsigned int e = 0; e < model.n_elements; ++e)
        reference_temperature[e] =
          parameters.initial.stress_free ?
            heat->element_temperature(e) :
            parameters.materials[model.material[e]].reference_temperature;
      update_thermal_stretch();
    }

    void
    TetrahedralSolver::thermal_step()
    {
      if (!(time > thermal_time))
        return;
      heat->step(thermal_time, time - thermal_time);
      thermal_time = time;
      ++n_thermal_steps;
      if (with_mechanics())
        update_thermal_stretch();
    }

    void
    TetrahedralSolver::update_thermal_stretch()
    {
      const std::size_t n_chunks =
        (model.n_elements + chunk_size - 1) / chunk_size;
      std::vector<double> work(n_chunks, 0.);
      for_each_chunk(arena_for(n_threads),
                     model.n_elements,
                     chunk_size,
                     [&](const std::size_t begin,
                         const std::size_t end,
                         const std::size_t c) {
                       for (std::size_t e = begin; e < end; ++e)
                         {
                           const MaterialProperties &m =
                             parameters.materials[model.material[e]];
                           const double alpha =
                             model.expansion_factor.empty() ?
                               m.thermal_expansion :
                               m.thermal_expansion * model.expansion_factor[e];
                           const double s_new = constitutive::thermal_stretch(
                             alpha,
                             m.poisson_ratio,
                             heat->element_temperature(e) -
                               reference_temperature[e],
                             Idealisation::solid_3d);
                           const double s_old = model.thermal_stretch[e];
                           if (s_new == s_old)
                             continue;
                           work[c] += element_strain_energy(e, s_new) -
                                      element_strain_energy(e, s_old);
                           model.thermal_stretch[e] = s_new;
                         }
                     });
      for (const double w : work)
        energies.thermal_work += w;
    }
  } // namespace discrete
} // namespace tmfdem
