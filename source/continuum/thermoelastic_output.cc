// The thermoelastic solver's outputs: stress, strain and temperature in the
// vtu files, probes and lines, stress extremes and summary.json.
#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/symmetric_tensor.h>
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
    /** The reference-cell coordinates of @p p in @p cell (affine inverse
     *  on simplices, the mapping's inverse otherwise). */
    template <int dim>
    Point<dim>
    unit_point_of(const Mapping<dim> &mapping,
                  const typename Triangulation<dim>::active_cell_iterator &cell,
                  const Point<dim>                                        &p)
    {
      if (cell->reference_cell().is_simplex())
        {
          if constexpr (dim == 2)
            {
              const Tensor<1, 2> a = cell->vertex(1) - cell->vertex(0),
                                 b = cell->vertex(2) - cell->vertex(0),
                                 d = p - cell->vertex(0);
              const double det     = a[0] * b[1] - a[1] * b[0];
              return Point<2>((d[0] * b[1] - d[1] * b[0]) / det,
                              (a[0] * d[1] - a[1] * d[0]) / det);
            }
          else
            {
              Tensor<2, dim> edges;
              for (unsigned int v = 1; v <= dim; ++v)
                for (unsigned int d = 0; d < dim; ++d)
                  edges[d][v - 1] = cell->vertex(v)[d] - cell->vertex(0)[d];
              return Point<dim>(invert(edges) * (p - cell->vertex(0)));
            }
        }
      return mapping.transform_real_to_unit_cell(cell, p);
    }

    /** Names of the symmetric tensor components: xx, yy, xy in 2D; xx, yy,
     *  zz, xy, yz, xz in 3D. */
    template <int dim>
    std::vector<std::pair<std::string, std::array<unsigned int, 2>>>
    tensor_components()
    {
      if (dim == 2)
        return {{"xx", {{0, 0}}}, {"yy", {{1, 1}}}, {"xy", {{0, 1}}}};
      return {{"xx", {{0, 0}}},
              {"yy", {{1, 1}}},
              {"zz", {{2, 2}}},
              {"xy", {{0, 1}}},
              {"yz", {{1, 2}}},
              {"xz", {{0, 2}}}};
    }

    /**
     * Stress (Cauchy, tension positive), strain and temperature for the vtu
     * files, computed from the displacement gradient at each output point.
     */
    template <int dim>
    class ThermoelasticPostprocessor : public DataPostprocessor<dim>
    {
    public:
      using Temperatures = std::function<std::vector<double>(
        const typename Triangulation<dim>::active_cell_iterator &,
        const std::vector<Point<dim>> &,
        const std::vector<Point<dim>> &)>;

      ThermoelasticPostprocessor(
        const std::vector<ThermoelasticMaterial<dim>> &materials,
        const Mapping<dim>                            &mapping,
        const Temperatures                            &temperatures,
        const bool                                     with_szz)
        : materials(materials)
        , mapping(mapping)
        , temperatures(temperatures)
        , with_szz(with_szz)
      {}

      std::vector<std::string>
      get_names() const override
      {
        std::vector<std::string> names;
        for (const auto &component : tensor_components<dim>())
          names.push_back("s" + component.first);
        if (with_szz)
          names.push_back("szz");
        for (const auto &component : tensor_components<dim>())
          names.push_back("e" + component.first);
        names.push_back("T");
        return names;
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_gradients | update_quadrature_points;
      }

      void
      evaluate_vector_field(
        const DataPostprocessorInputs::Vector<dim> &inputs,
        std::vector<Vector<double>>                &computed) const override
      {
        const auto dof_cell = inputs.template get_cell<dim>();
        const typename Triangulation<dim>::active_cell_iterator cell(
          &dof_cell->get_triangulation(),
          dof_cell->level(),
          dof_cell->index());
        const auto             &points = inputs.evaluation_points;
        std::vector<Point<dim>> unit_points;
        for (const auto &p : points)
          unit_points.push_back(unit_point_of<dim>(mapping, cell, p));
        const std::vector<double> T = temperatures(cell, unit_points, points);
        const auto               &material = materials[cell->material_id()];
        for (unsigned int q = 0; q < points.size(); ++q)
          {
            Tensor<2, dim> grad_u;
            for (unsigned int c = 0; c < dim; ++c)
              grad_u[c] = inputs.solution_gradients[q][c];
            const Tensor<2, dim> sigma  = material.cauchy(grad_u, T[q]);
            const Tensor<2, dim> strain = material.strain(grad_u);
            unsigned int         k      = 0;
            for (const auto &component : tensor_components<dim>())
              computed[q](k++) =
                sigma[component.second[0]][component.second[1]];
            if (with_szz)
              computed[q](k++) = material.out_of_plane_stress(sigma, T[q]);
            for (const auto &component : tensor_components<dim>())
              computed[q](k++) =
                strain[component.second[0]][component.second[1]];
            computed[q](k++) = T[q];
          }
      }

    private:
      const std::vector<ThermoelasticMaterial<dim>> &materials;
      const Mapping<dim>                            &mapping;
      const Temperatures                             temperatures;
      const bool                                     with_szz;
    };

  } // namespace

  // ------------------------------------------------------------ output
  template <int dim>
  std::vector<double>
  ThermoelasticSolver<dim>::monitor_values(
    const typename DoFHandler<dim>::active_cell_iterator &cell,
    const Point<dim>                                     &unit_point) const
  {
    const Quadrature<dim> quadrature(std::vector<Point<dim>>{unit_point});
    FEValues<dim>         fe_values(*mapping,
                            *fe,
                            quadrature,
                            update_values | update_gradients |
                              update_quadrature_points);
    fe_values.reinit(cell);
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<1, dim>>      displacement(1);
    std::vector<Tensor<2, dim>>      grad_u(1);
    fe_values[u].get_function_values(solution, displacement);
    fe_values[u].get_function_gradients(solution, grad_u);
    const typename Triangulation<dim>::active_cell_iterator
                     tria_cell(triangulation, cell->level(), cell->index());
    const Point<dim> p          = fe_values.quadrature_point(0);
    const std::vector<double> T = temperatures_at(tria_cell, {unit_point}, {p});
    const Tensor<2, dim>      sigma =
      materials[cell->material_id()].cauchy(grad_u[0], T[0]);
    std::vector<double> values = {T[0]};
    for (unsigned int d = 0; d < dim; ++d)
      values.push_back(displacement[0][d]);
    for (const auto &component : tensor_components<dim>())
      values.push_back(sigma[component.second[0]][component.second[1]]);
    if (parameters.mechanics.polar_frame)
      {
        // in 3D cylindrical about the axis parallel to z through the
        // centre: its radial direction is the in-plane one, so srr and stt
        // come from sxx, syy, sxy as in 2D
        const Tensor<1, dim> radial =
          p - MeshParameters::in_dimension<dim>(
                Point<3>(parameters.mechanics.polar_centre[0],
                         parameters.mechanics.polar_centre[1],
                         0.));
        const auto polar = polar_stress(sigma[0][0],
                                        sigma[1][1],
                                        sigma[0][1],
                                        radial[0],
                                        radial[1]);
        values.push_back(polar[0]);
        values.push_back(polar[1]);
      }
    return values;
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::write_output(const double time)
  {
    monitors->write(
      time,
      *mapping,
      *dof_handler,
      [this](const typename DoFHandler<dim>::active_cell_iterator &cell,
             const Point<dim>                                     &unit_point) {
        return monitor_values(cell, unit_point);
      });

    // stress extremes over the quadrature points of the last solve: the
    // largest |sigma_ij| per component, the largest and smallest principal
    // stress
    const auto            components   = tensor_components<dim>();
    const unsigned int    n_components = components.size();
    const Quadrature<dim> quadrature   = cell_quadrature();
    FEValues<dim> fe_values(*mapping, *fe, quadrature, update_gradients);
    const FEValuesExtractors::Vector u(0);
    std::vector<Tensor<2, dim>>      grad_u(quadrature.size());
    std::vector<double>              extremes(n_components, 0.);
    double largest_principal  = -std::numeric_limits<double>::max();
    double smallest_principal = std::numeric_limits<double>::max();
    for (const auto &cell : dof_handler->active_cell_iterators())
      if (cell->is_locally_owned())
        {
          fe_values.reinit(cell);
          fe_values[u].get_function_gradients(solution, grad_u);
          const auto &T = quadrature_temperatures[cell->active_cell_index()];
          for (unsigned int q = 0; q < quadrature.size(); ++q)
            {
              const Tensor<2, dim> s =
                materials[cell->material_id()].cauchy(grad_u[q], T[q]);
              for (unsigned int k = 0; k < n_components; ++k)
                extremes[k] = std::max(
                  extremes[k],
                  std::abs(
                    s[components[k].second[0]][components[k].second[1]]));
              if constexpr (dim == 2)
                {
                  const double mean = 0.5 * (s[0][0] + s[1][1]);
                  const double radius =
                    std::hypot(0.5 * (s[0][0] - s[1][1]), s[0][1]);
                  largest_principal =
                    std::max(largest_principal, mean + radius);
                  smallest_principal =
                    std::min(smallest_principal, mean - radius);
                }
              else
                {
                  const std::array<double, dim> principal =
                    eigenvalues(symmetrize(s)); // descending
                  largest_principal = std::max(largest_principal, principal[0]);
                  smallest_principal =
                    std::min(smallest_principal, principal[dim - 1]);
                }
            }
        }
    stress_extremes.resize(n_components + 2);
    for (unsigned int k = 0; k < n_components; ++k)
      stress_extremes[k] = Utilities::MPI::max(extremes[k], communicator);
    stress_extremes[n_components] =
      Utilities::MPI::max(largest_principal, communicator);
    stress_extremes[n_components + 1] =
      Utilities::MPI::min(smallest_principal, communicator);

    if (parameters.output.write_vtu)
      {
        const bool with_szz =
          dim == 2 &&
          parameters.mechanics.idealisation ==
            MechanicsParameters::Idealisation::plane_strain &&
          parameters.mechanics.strain_measure ==
            MechanicsParameters::StrainMeasure::small;
        const ThermoelasticPostprocessor<dim> postprocessor(
          materials,
          *mapping,
          [this](const typename Triangulation<dim>::active_cell_iterator &cell,
                 const std::vector<Point<dim>> &unit_points,
                 const std::vector<Point<dim>> &points) {
            return temperatures_at(cell, unit_points, points);
          },
          with_szz);
        DataOut<dim> data_out;
        data_out.attach_dof_handler(*dof_handler);
        const std::vector<
          DataComponentInterpretation::DataComponentInterpretation>
          vector_field(
            dim,
            DataComponentInterpretation::component_is_part_of_vector);
        data_out.add_data_vector(solution,
                                 std::vector<std::string>(dim, "displacement"),
                                 DataOut<dim>::type_dof_data,
                                 vector_field);
        data_out.add_data_vector(solution, postprocessor);
        write_solution(data_out, time);
      }
    write_summary(time);
  }

  template <int dim>
  void
  ThermoelasticSolver<dim>::write_summary(const double time) const
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
    stress.add("units", std::string("Pa, Cauchy, tension positive"));
    // zeros before the first output (a failed first solve)
    const auto          components = tensor_components<dim>();
    std::vector<double> extremes   = stress_extremes;
    extremes.resize(components.size() + 2, 0.);
    for (unsigned int k = 0; k < components.size(); ++k)
      stress.add("max_abs_s" + components[k].first, extremes[k]);
    stress.add("max_principal", extremes[components.size()])
      .add("min_principal", extremes[components.size() + 1]);
    const double wall_time = this->wall_time();
    JsonObject   summary   = summary_head();
    summary
      .add("idealisation",
           std::string(mechanics.idealisation ==
                           MechanicsParameters::Idealisation::plane_stress ?
                         "plane stress" :
                       mechanics.idealisation ==
                           MechanicsParameters::Idealisation::plane_strain ?
                         "plane strain" :
                         "3D"))
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

  template class ThermoelasticSolver<2>;
  template class ThermoelasticSolver<3>;
} // namespace tmfdem
