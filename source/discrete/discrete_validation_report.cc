/**
 * @file
 * What the discrete models tell `--validate` (io/validation_report.h): the
 * exploded mesh's sizes and smallest element, the mechanical and thermal
 * steps, and the memory of the model's state.
 */
#include <algorithm>
#include <cmath>
#include <limits>
#include <tmfdem/discrete/discrete_heat_solver.h>
#include <tmfdem/discrete/explicit_solver.h>
#include <tmfdem/io/validation_report.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      /** Bytes held by a vector. */
      template <typename T>
      double
      bytes(const std::vector<T> &vector)
      {
        return static_cast<double>(vector.capacity() * sizeof(T));
      }

      /** Shortest edge and smallest height over the triangles [m]. */
      std::pair<double, double>
      smallest_element(const DiscreteModel &model)
      {
        double min_edge   = std::numeric_limits<double>::max();
        double min_height = std::numeric_limits<double>::max();
        for (unsigned int e = 0; e < model.n_elements; ++e)
          {
            double longest = 0.;
            for (unsigned int k = 0; k < 3; ++k)
              {
                const unsigned int a = 3 * e + k, b = 3 * e + (k + 1) % 3;
                const double edge = std::hypot(model.x_ref[b] - model.x_ref[a],
                                               model.y_ref[b] - model.y_ref[a]);
                min_edge          = std::min(min_edge, edge);
                longest           = std::max(longest, edge);
              }
            const double area =
              0.5 * std::abs((model.x_ref[3 * e + 1] - model.x_ref[3 * e]) *
                               (model.y_ref[3 * e + 2] - model.y_ref[3 * e]) -
                             (model.x_ref[3 * e + 2] - model.x_ref[3 * e]) *
                               (model.y_ref[3 * e + 1] - model.y_ref[3 * e]));
            if (longest > 0.)
              min_height = std::min(min_height, 2. * area / longest);
          }
        return {min_edge, min_height};
      }

      /** Bytes of the per-element, per-node and per-joint state. */
      double
      model_bytes(const DiscreteModel &model)
      {
        return bytes(model.x) + bytes(model.y) + bytes(model.x_ref) +
               bytes(model.y_ref) + bytes(model.vx) + bytes(model.vy) +
               bytes(model.mass) + bytes(model.node_vertex) +
               bytes(model.inverse_basis) + bytes(model.reference_area) +
               bytes(model.material) + bytes(model.body) +
               bytes(model.thermal_stretch) + bytes(model.stress) +
               bytes(model.edge_joint) + bytes(model.edge_boundary) +
               bytes(model.joint_nodes) + bytes(model.joint_elements) +
               bytes(model.joint_constants) + bytes(model.joint_length) +
               bytes(model.joint_damage) + bytes(model.joint_status) +
               bytes(model.joint_break_time) + bytes(model.node_joint_force);
      }

      void
      describe_model(std::ostream &out, const DiscreteModel &model)
      {
        const auto [edge, height] = smallest_element(model);
        out << "discrete model: " << model.n_elements << " triangles, "
            << model.n_nodes << " nodes, " << model.n_joints << " joints\n"
            << "  smallest element: shortest edge " << edge
            << " m, smallest height " << height << " m\n";
      }

      /** Quasi-static coupling: thermal steps and the relaxations' cap
       *  (the number of mechanical steps depends on how fast each
       *  relaxation settles: only its bounds are known beforehand). */
      void
      describe_quasi_static_steps(std::ostream        &out,
                                  const DiscreteModel &model,
                                  const double         stable,
                                  const double         used,
                                  const unsigned int   cap,
                                  const Parameters    &parameters)
      {
        // a relaxation settles in a few transits of the slowest-decaying
        // mode across the body: the P wave over the body's largest extent
        double x_min = std::numeric_limits<double>::max(), x_max = -x_min,
               y_min = x_min, y_max = -x_min, wave_speed = 0.;
        for (unsigned int n = 0; n < model.n_nodes; ++n)
          {
            x_min = std::min(x_min, model.x_ref[n]);
            x_max = std::max(x_max, model.x_ref[n]);
            y_min = std::min(y_min, model.y_ref[n]);
            y_max = std::max(y_max, model.y_ref[n]);
          }
        // the inertia of the run: Mass scaling factor x density
        const double mass_scaling =
          parameters.get<DiscreteMechanicsParameters>().mass_scaling_factor;
        for (unsigned int e = 0; e < model.n_elements; ++e)
          {
            const MaterialProperties &m =
              parameters.materials[model.material[e]];
            const double nu = m.poisson_ratio, E = m.youngs_modulus;
            // the plane-strain P-wave modulus (the larger one)
            wave_speed =
              std::max(wave_speed,
                       std::sqrt(E * (1. - nu) / ((1. + nu) * (1. - 2. * nu)) /
                                 (mass_scaling * m.density)));
          }
        const double extent = std::max(x_max - x_min, y_max - y_min);
        const double transit_steps =
          wave_speed > 0. && used > 0. ? extent / wave_speed / used : 0.;
        const auto  &dh    = parameters.get<DiscreteHeatParameters>();
        const double start = parameters.time.start_time,
                     end   = parameters.time.end_time;
        // the thermal steps of the schedule alone (Time step x growth^n up
        // to Maximum thermal step); the step control adds shorter ones near
        // failure
        unsigned long long thermal_steps = 0;
        double             t = start, dt = parameters.time.time_step;
        while (t < end - 1e-9 * std::max(1., std::abs(end)) &&
               thermal_steps < 100000000ULL)
          {
            t += dt;
            ++thermal_steps;
            dt *= dh.thermal_step_growth;
            if (dh.maximum_thermal_step > 0.)
              dt = std::min(dt, dh.maximum_thermal_step);
          }
        out << "  mechanical time step: stable " << stable << " s, used "
            << used << " s (relaxation steps)\n"
            << "  quasi-static coupling: " << thermal_steps
            << " thermal steps to End time = " << end
            << " s by the schedule (Time step " << parameters.time.time_step
            << " s";
        if (dh.thermal_step_growth != 1.)
          out << " x " << dh.thermal_step_growth << "^n";
        if (dh.maximum_thermal_step > 0.)
          out << ", at most " << dh.maximum_thermal_step << " s";
        out << "; the step control adds shorter ones where joints approach "
               "their strength or break), each relaxed in at most "
            << cap << " mechanical steps: at most "
            << static_cast<double>(thermal_steps) * cap
            << " mechanical steps on the schedule";
        if (transit_steps > 0.)
          out << "; a P wave crosses the body (" << extent << " m at "
              << wave_speed << " m/s) in " << std::ceil(transit_steps)
              << " mechanical steps, the cap is " << cap / transit_steps
              << " transits (kinetic damping settles in about 5 to 10)";
        if (dh.fracture_event_duration > 0.)
          out << "; a fracture event runs "
              << static_cast<long long>(
                   std::ceil(dh.fracture_event_duration / used - 1e-9))
              << " mechanical steps";
        out << "\n";
      }
    } // namespace

    void
    ExplicitSolver::report_validation(std::ostream &out,
                                      const Parameters & /*parameters*/,
                                      MPI_Comm /*communicator*/) const
    {
      describe_model(out, model);
      const unsigned int cap = get_relaxation_cap();
      const double       mass_scaling =
        parameters.get<DiscreteMechanicsParameters>().mass_scaling_factor;
      if (mass_scaling != 1.)
        out << "  mass scaling: every mass " << mass_scaling
            << " x rho A / 3, the mechanics " << std::sqrt(mass_scaling)
            << " x slower than with the physical inertia\n";
      if (cap == 0)
        validation::describe_steps(out,
                                   "mechanical time step",
                                   get_stable_time_step(),
                                   get_time_step(),
                                   parameters);
      else
        describe_quasi_static_steps(out,
                                    model,
                                    get_stable_time_step(),
                                    get_time_step(),
                                    cap,
                                    parameters);
      if (const auto *source = get_temperature_source())
        out << "  temperature source: " << source->describe() << "\n";
      out << "  model state: " << model_bytes(model) / validation::mebibyte
          << " MiB (contact lists grow with fragmentation)\n";
    }

    void
    DiscreteHeatSolver::report_validation(std::ostream &out,
                                          const Parameters & /*parameters*/,
                                          MPI_Comm /*communicator*/) const
    {
      describe_model(out, model);
      validation::describe_steps(out,
                                 "thermal time step",
                                 get_stable_time_step(),
                                 get_time_step(),
                                 parameters);
      out << "  model state: " << model_bytes(model) / validation::mebibyte
          << " MiB\n";
    }
  } // namespace discrete
} // namespace tmfdem
