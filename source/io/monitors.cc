#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/vector.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/io/monitors.h>

namespace tmfdem
{
  namespace
  {
    /** Is @p p (reference coordinates) in the cell, up to 1e-6? */
    template <int dim>
    bool
    inside_reference_cell(const ReferenceCell &reference, const Point<dim> &p)
    {
      const double tolerance = 1e-6;
      double       sum       = 0.;
      for (unsigned int d = 0; d < dim; ++d)
        {
          if (p[d] < -tolerance)
            return false;
          sum += p[d];
        }
      if (reference.is_simplex())
        return sum <= 1. + tolerance;
      for (unsigned int d = 0; d < dim; ++d)
        if (p[d] > 1. + tolerance)
          return false;
      return true;
    }
  } // namespace

  template <int dim>
  Monitors<dim>::Monitors(const MonitorParameters        &parameters,
                          const std::string              &folder,
                          const std::vector<std::string> &field_names,
                          MPI_Comm                        communicator)
    : n_components(field_names.size())
    , communicator(communicator)
  {
    for (const auto &probe : parameters.probes)
      points.push_back(
        {probe.name, MeshParameters::in_dimension<dim>(probe.location), false});
    for (const auto &line : parameters.lines)
      for (unsigned int i = 0; i < line.n_points; ++i)
        {
          const double s = static_cast<double>(i) / (line.n_points - 1);
          points.push_back({line.name,
                            MeshParameters::in_dimension<dim>(
                              line.start + s * (line.end - line.start)),
                            true});
        }
    std::string header = dim == 2 ? "time,name,x,y" : "time,name,x,y,z";
    for (const auto &name : field_names)
      header += "," + name;
    if (!parameters.probes.empty())
      probes_csv = CsvSeries(folder + "/probes.csv", header, communicator);
    if (!parameters.lines.empty())
      lines_csv = CsvSeries(folder + "/lines.csv", header, communicator);
  }

  template <int dim>
  std::vector<std::vector<double>>
  Monitors<dim>::evaluate(const Mapping<dim>    &mapping,
                          const DoFHandler<dim> &dof_handler,
                          const PointEvaluator  *evaluator) const
  {
    const unsigned int  n_values = n_components + 1; // last: found count
    std::vector<double> local(points.size() * n_values, 0.);
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        // search this rank's cells (bounding box first, then the exact
        // inverse map: affine for triangles, the mapping's for quads);
        // deal.II 9.4's point search tests simplices as if they were squares
        std::vector<
          std::pair<typename DoFHandler<dim>::active_cell_iterator, Point<dim>>>
                          candidates;
        const Point<dim> &p = points[i].location;
        for (const auto &cell : dof_handler.active_cell_iterators())
          {
            if (!cell->is_locally_owned())
              continue;
            const auto box = cell->bounding_box();
            // tolerance from the box's size (cheaper than the diameter,
            // which measures every vertex pair: this loop runs over all
            // cells for every point at every output)
            double extent = 0.;
            for (unsigned int d = 0; d < dim; ++d)
              extent =
                std::max(extent, box.upper_bound(d) - box.lower_bound(d));
            const double margin  = 1e-6 * extent;
            bool         outside = false;
            for (unsigned int d = 0; d < dim; ++d)
              outside = outside || p[d] < box.lower_bound(d) - margin ||
                        p[d] > box.upper_bound(d) + margin;
            if (outside)
              continue;
            Point<dim> unit_point;
            if (cell->reference_cell().is_simplex() && dim == 2)
              {
                const Tensor<1, dim> a = cell->vertex(1) - cell->vertex(0),
                                     b = cell->vertex(2) - cell->vertex(0),
                                     d = p - cell->vertex(0);
                const double det       = a[0] * b[1] - a[1] * b[0];
                unit_point[0]          = (d[0] * b[1] - d[1] * b[0]) / det;
                unit_point[1]          = (a[0] * d[1] - a[1] * d[0]) / det;
              }
            else if (cell->reference_cell().is_simplex())
              {
                // the affine map of the tetrahedron, inverted
                Tensor<2, dim> jacobian;
                for (unsigned int v = 0; v < dim; ++v)
                  for (unsigned int d = 0; d < dim; ++d)
                    jacobian[d][v] =
                      cell->vertex(v + 1)[d] - cell->vertex(0)[d];
                const Tensor<1, dim> local =
                  invert(jacobian) * (p - cell->vertex(0));
                for (unsigned int d = 0; d < dim; ++d)
                  unit_point[d] = local[d];
              }
            else
              try
                {
                  unit_point = mapping.transform_real_to_unit_cell(cell, p);
                }
              catch (const ExceptionBase &)
                {
                  continue;
                }
            candidates.emplace_back(cell, unit_point);
            if (inside_reference_cell(cell->reference_cell(), unit_point))
              break;
          }
        for (const auto &[cell, unit_point] : candidates)
          {
            if (!cell->is_locally_owned() ||
                !inside_reference_cell(cell->reference_cell(), unit_point))
              continue;
            local[i * n_values + n_components] = 1.;
            if (evaluator != nullptr)
              {
                const std::vector<double> values =
                  (*evaluator)(cell, unit_point);
                for (unsigned int c = 0; c < n_components; ++c)
                  local[i * n_values + c] = values[c];
              }
            break;
          }
      }
    std::vector<double> global(local.size());
    MPI_Allreduce(local.data(),
                  global.data(),
                  static_cast<int>(local.size()),
                  MPI_DOUBLE,
                  MPI_SUM,
                  communicator);
    std::vector<std::vector<double>> result(points.size(),
                                            std::vector<double>(n_values));
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        const double count = global[i * n_values + n_components];
        for (unsigned int c = 0; c < n_components; ++c)
          result[i][c] = count > 0 ? global[i * n_values + c] / count :
                                     std::numeric_limits<double>::quiet_NaN();
        result[i][n_components] = count;
      }
    return result;
  }

  template <int dim>
  void
  Monitors<dim>::check_points(const Mapping<dim>    &mapping,
                              const DoFHandler<dim> &dof_handler) const
  {
    const auto values = evaluate(mapping, dof_handler, nullptr);
    for (unsigned int i = 0; i < points.size(); ++i)
      if (values[i][n_components] == 0.)
        {
          std::ostringstream message;
          message << "Monitors/" << (points[i].from_line ? "Lines" : "Probes")
                  << ": " << (points[i].from_line ? "line '" : "probe '")
                  << points[i].name << "' has the point (" << points[i].location
                  << ") outside the domain. Allowed are points inside the "
                     "mesh or on its boundary.";
          throw InputError(message.str());
        }
  }

  template <int dim>
  void
  Monitors<dim>::write(const double                         time,
                       const Mapping<dim>                  &mapping,
                       const DoFHandler<dim>               &dof_handler,
                       const TrilinosWrappers::MPI::Vector &solution)
  {
    const unsigned int   n_fe_components = n_components;
    const PointEvaluator field_values =
      [&](const typename DoFHandler<dim>::active_cell_iterator &cell,
          const Point<dim>                                     &unit_point) {
        const Quadrature<dim> quadrature(std::vector<Point<dim>>{unit_point});
        FEValues<dim>         fe_values(mapping,
                                dof_handler.get_fe(),
                                quadrature,
                                update_values);
        fe_values.reinit(cell);
        std::vector<Vector<double>> values(1, Vector<double>(n_fe_components));
        fe_values.get_function_values(solution, values);
        return std::vector<double>(values[0].begin(), values[0].end());
      };
    write(time, mapping, dof_handler, field_values);
  }

  template <int dim>
  void
  Monitors<dim>::write(const double           time,
                       const Mapping<dim>    &mapping,
                       const DoFHandler<dim> &dof_handler,
                       const PointEvaluator  &evaluator)
  {
    if (points.empty())
      return;
    const auto         values = evaluate(mapping, dof_handler, &evaluator);
    std::ostringstream probe_rows, line_rows;
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        std::ostringstream &rows = points[i].from_line ? line_rows : probe_rows;
        rows << std::setprecision(12) << time << "," << points[i].name << ","
             << points[i].location[0] << "," << points[i].location[1];
        if (dim == 3)
          rows << "," << points[i].location[2];
        for (unsigned int c = 0; c < n_components; ++c)
          rows << "," << values[i][c];
        rows << "\n";
      }
    probes_csv.append(probe_rows.str());
    lines_csv.append(line_rows.str());
  }

  template class Monitors<2>;
  template class Monitors<3>;
} // namespace tmfdem
