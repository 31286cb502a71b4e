// The thermoelastic solver's outputs: stress, strain and temperature in the
// vtu files, probes and lines, stress extremes and summary.json.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <cmath>
#include <limits>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/polar_stress.h>
#include <tmfdem/continuum/thermoelastic_solver.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/monitors.h>
#include <tmfdem/io/output_files.h>

namespace tmfdem
{
  namespace
  {
    /** The reference-cell coordinates of @p p in @p cell. */
    Point<2>
    unit_point_of(const Mapping<2>                             &mapping,
                  const Triangulation<2>::active_cell_iterator &cell,
                  const Point<2>                               &p)
    {
      if (cell->reference_cell() == ReferenceCells::Triangle)
        {
          const Tensor<1, 2> a = cell->vertex(1) - cell->vertex(0),
                             b = cell->vertex(2) - cell->vertex(0),
                             d = p - cell->vertex(0);
          const double det     = a[0] * b[1] - a[1] * b[0];
          return Point<2>((d[0] * b[1] - d[1] * b[0]) / det,
                          (a[0] * d[1] - a[1] * d[0]) / det);
        }
      return mapping.transform_real_to_unit_cell(cell, p);
    }

    /**
     * Stress (Cauchy, tension positive), strain and temperature for the vtu
     * files, computed from the displacement gradient at each output point.
     */
    class ThermoelasticPostprocessor : public DataPostprocessor<2>
    {
    public:
      ThermoelasticPostprocessor(
        const std::vector<ThermoelasticMaterial> &materials,
        const Mapping<2>                         &mapping,
        const std::function<
          std::vector<double>(const Triangulation<2>::active_cell_iterator &,
                              const std::vector<Point<2>> &,
                              const std::vector<Point<2>> &)> &temperatures,
        const bool                                             with_szz)
        : materials(materials)
        , mapping(mapping)
        , temperatures(temperatures)
        , with_szz(with_szz)
      {}

      std::vector<std::string>
      get_names() const override
      {
        std::vector<std::string> names = {"sxx", "syy", "sxy"};
        if (with_szz)
          names.push_back("szz");
        for (const char *name : {"exx", "eyy", "exy", "T"})
          names.push_back(name);
        return names;
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_gradients | update_quadrature_points;
      }

      void
      evaluate_vector_field(
        const DataPostprocessorInputs::Vector<2> &inputs,
        std::vector<Vector<double>>              &computed) const override
      {
        const auto dof_cell = inputs.template get_cell<2>();
        const Triangulation<2>::active_cell_iterator cell(
          &dof_cell->get_triangulation(),
          dof_cell->level(),
          dof_cell->index());
        const auto           &points = inputs.evaluation_points;
        std::vector<Point<2>> unit_points;
        for (const auto &p : points)
          unit_points.push_back(unit_point_of(mapping, cell, p));
        const std::vector<double> T = temperatures(cell, unit_points, points);
        const auto               &material = materials[cell->material_id()];
        for (unsigned int q = 0; q < points.size(); ++q)
          {
            Tensor<2, 2> grad_u;
            for (unsigned int c = 0; c < 2; ++c)
              grad_u[c] = inputs.solution_gradients[q][c];
            const Tensor<2, 2> sigma  = material.cauchy(grad_u, T[q]);
            const Tensor<2, 2> strain = material.strain(grad_u);
            unsigned int       k      = 0;
            computed[q](k++)          = sigma[0][0];
            computed[q](k++)          = sigma[1][1];
            computed[q](k++)          = sigma[0][1];
            if (with_szz)
              computed[q](k++) = material.out_of_plane_stress(sigma, T[q]);
            computed[q](k++) = strain[0][0];
            computed[q](k++) = strain[1][1];
            computed[q](k++) = strain[0][1];
            computed[q](k++) = T[q];
          }
      }

    private:
      const std::vector<ThermoelasticMaterial> &materials;
      const Mapping<2>                         &mapping;
      const std::function<
        std::vector<double>(const Triangulation<2>::active_cell_iterator &,
                            const std::vector<Point<2>> &,
                            const std::vector<Point<2>> &)>
                 temperatures;
      const bool with_szz;
    };

  } // namespace

  // ------------------------------------------------------------ output
  std::vector<double>
  ThermoelasticSolver::monitor_values(
    const DoFHandler<2>::active_cell_iterator &cell,
    const Point<2>                            &unit_point) const
  {
    const Quadrature<2> quadrature(std::vector<Point<2>>{unit_point});
    FEValues<2>         fe_values(*mapping,
                          *fe,
                          quadrature,
                          update_values | update_gradients |
                            update_quadrature_points);
    fe_values.reinit(cell);
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<1, 2>>        displacement(1);
    std::vector<Tensor<2, 2>>        grad_u(1);
    fe_values[u].get_function_values(solution, displacement);
    fe_values[u].get_function_gradients(solution, grad_u);
    const Triangulation<2>::active_cell_iterator tria_cell(triangulation,
                                                           cell->level(),
                                                           cell->index());
    const Point<2>            p = fe_values.quadrature_point(0);
    const std::vector<double> T = temperatures_at(tria_cell, {unit_point}, {p});
    const Tensor<2, 2>        sigma =
      materials[cell->material_id()].cauchy(grad_u[0], T[0]);
    std::vector<double> values = {T[0],
                                  displacement[0][0],
                                  displacement[0][1],
                                  sigma[0][0],
                                  sigma[1][1],
                                  sigma[0][1]};
    if (parameters.mechanics.polar_frame)
      {
        const Tensor<1, 2> radial = p - parameters.mechanics.polar_centre;
        const auto         polar  = polar_stress(sigma[0][0],
                                        sigma[1][1],
                                        sigma[0][1],
                                        radial[0],
                                        radial[1]);
        values.push_back(polar[0]);
        values.push_back(polar[1]);
      }
    return values;
  }

  void
  ThermoelasticSolver::write_output(const double time)
  {
    monitors->write(time,
                    *mapping,
                    *dof_handler,
                    [this](const DoFHandler<2>::active_cell_iterator &cell,
                           const Point<2> &unit_point) {
                      return monitor_values(cell, unit_point);
                    });

    // stress extremes over the quadrature points of the last solve
    const Quadrature<2> quadrature = cell_quadrature();
    FEValues<2>         fe_values(*mapping, *fe, quadrature, update_gradients);
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<2, 2>>        grad_u(quadrature.size());
    std::array<double, 5>            extremes = {{0.,
                                                  0.,
                                                  0.,
                                                  -std::numeric_limits<double>::max(),
                                                  std::numeric_limits<double>::max()}};
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[u].get_function_gradients(solution, grad_u);
          const auto &T = quadrature_temperatures[cell->active_cell_index()];
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const Tensor<2, 2> s =
                materials[cell->material_id()].cauchy(grad_u[q], T[q]);
              const double mean = 0.5 * (s[0][0] + s[1][1]);
              const double radius =
                std::hypot(0.5 * (s[0][0] - s[1][1]), s[0][1]);
              extremes[0] = std::max(extremes[0], std::abs(s[0][0]));
              extremes[1] = std::max(extremes[1], std::abs(s[1][1]));
              extremes[2] = std::max(extremes[2], std::abs(s[0][1]));
              extremes[3] = std::max(extremes[3], mean + radius);
              extremes[4] = std::min(extremes[4], mean - radius);
            }
        }
    for (unsigned int k = 0; k < 4; ++k)
      stress_extremes[k] = Utilities::MPI::max(extremes[k], communicator);
    stress_extremes[4] = Utilities::MPI::min(extremes[4], communicator);

    if (parameters.output.write_vtu)
      {
        const bool with_szz =
          parameters.mechanics.idealisation ==
            MechanicsParameters::Idealisation::plane_strain &&
          parameters.mechanics.strain_measure ==
            MechanicsParameters::StrainMeasure::small;
        const ThermoelasticPostprocessor postprocessor(
          materials,
          *mapping,
          [this](const Triangulation<2>::active_cell_iterator &cell,
                 const std::vector<Point<2>>                  &unit_points,
                 const std::vector<Point<2>>                  &points) {
            return temperatures_at(cell, unit_points, points);
          },
          with_szz);
        DataOut<2> data_out;
        data_out.attach_dof_handler(*dof_handler);
        const std::vector<
          DataComponentInterpretation::DataComponentInterpretation>
          vector_field(
            2,
            DataComponentInterpretation::component_is_part_of_vector);
        data_out.add_data_vector(solution,
                                 std::vector<std::string>(2, "displacement"),
                                 DataOut<2>::type_dof_data,
                                 vector_field);
        data_out.add_data_vector(solution, postprocessor);
        write_solution(data_out, time);
      }
    write_summary(time);
  }

  void
  ThermoelasticSolver::write_summary(const double time) const
  {
    const auto             &mechanics = parameters.mechanics;
    std::vector<JsonObject> history;
    for (const auto &record : newton_history)
      {
        JsonObject object;
        object.add("time", record.time)
          .add("iteration", record.iteration)
          .add("residual", record.residual)
          .add("step_length", record.step_length)
          .add("cg_iterations", record.linear_iterations);
        history.push_back(object);
      }
    JsonObject stress;
    stress.add("units", std::string("Pa, Cauchy, tension positive"))
      .add("max_abs_sxx", stress_extremes[0])
      .add("max_abs_syy", stress_extremes[1])
      .add("max_abs_sxy", stress_extremes[2])
      .add("max_principal", stress_extremes[3])
      .add("min_principal", stress_extremes[4]);
    const double wall_time = this->wall_time();
    JsonObject   summary   = summary_head();
    summary
      .add("idealisation",
           std::string(mechanics.idealisation ==
                           MechanicsParameters::Idealisation::plane_stress ?
                         "plane stress" :
                         "plane strain"))
      .add("strain_measure",
           std::string(mechanics.strain_measure ==
                           MechanicsParameters::StrainMeasure::small ?
                         "small" :
                         "finite"))
      .add("temperature_source",
           std::string(mechanics.temperature_source ==
                           MechanicsParameters::TemperatureSource::function ?
                         "function" :
                       mechanics.temperature_source ==
                           MechanicsParameters::TemperatureSource::heat_solver ?
                         "heat solver" :
                         "discrete heat"));
    add_run_entries(summary, solves, time, wall_time);
    summary
      .add("newton_iterations", static_cast<long long>(total_newton_iterations))
      .add("linear_iterations", static_cast<long long>(total_linear_iterations))
      .add("broken_joints", 0u)
      .add("cracks", 0u)
      .add("stress", stress)
      .add("newton_history", history);
    if (Utilities::MPI::this_mpi_process(communicator) == 0)
      write_file_atomically(parameters.output.directory + "/summary.json",
                            summary.str() + "\n");
  }

} // namespace tmfdem
