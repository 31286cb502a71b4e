#include <tmfdem/base/exceptions.h>
#include <tmfdem/io/monitors.h>

#include <deal.II/base/mpi.h>
#include <deal.II/base/quadrature.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/grid/grid_tools.h>
#include <deal.II/lac/vector.h>

#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>

namespace tmfdem
{
  Monitors::Monitors(const MonitorParameters        &parameters,
                     const std::string              &folder,
                     const std::vector<std::string> &field_names,
                     MPI_Comm                        communicator)
    : n_components(field_names.size())
    , communicator(communicator)
  {
    for (const auto &probe : parameters.probes)
      points.push_back({probe.name, probe.location, false});
    for (const auto &line : parameters.lines)
      for (unsigned int i = 0; i < line.n_points; ++i)
        {
          const double s = static_cast<double>(i) / (line.n_points - 1);
          points.push_back(
            {line.name, line.start + s * (line.end - line.start), true});
        }
    std::string header = "time,name,x,y";
    for (const auto &name : field_names)
      header += "," + name;
    if (!parameters.probes.empty())
      probes_csv = CsvSeries(folder + "/probes.csv", header, communicator);
    if (!parameters.lines.empty())
      lines_csv = CsvSeries(folder + "/lines.csv", header, communicator);
  }

  std::vector<std::vector<double>>
  Monitors::evaluate(const Mapping<2>                    &mapping,
                     const DoFHandler<2>                 &dof_handler,
                     const TrilinosWrappers::MPI::Vector *solution) const
  {
    const unsigned int  n_values = n_components + 1; // last: found count
    std::vector<double> local(points.size() * n_values, 0.);
    // candidates: vertices of locally owned cells, so that the search stays
    // in this rank's part of the mesh
    std::vector<bool> marked(dof_handler.get_triangulation().n_vertices(),
                             false);
    for (const auto &cell : dof_handler.active_cell_iterators())
      if (cell->is_locally_owned())
        for (const unsigned int v : cell->vertex_indices())
          marked[cell->vertex_index(v)] = true;

    for (unsigned int i = 0; i < points.size(); ++i)
      {
        try
          {
            const auto cell_and_point =
              GridTools::find_active_cell_around_point(
                mapping, dof_handler, points[i].location, marked, 1e-8);
            const auto &cell = cell_and_point.first;
            if (!cell->is_locally_owned())
              continue;
            local[i * n_values + n_components] = 1.;
            if (solution == nullptr)
              continue;
            const Quadrature<2> quadrature(
              std::vector<Point<2>>{cell_and_point.second});
            FEValues<2> fe_values(mapping,
                                  dof_handler.get_fe(),
                                  quadrature,
                                  update_values);
            fe_values.reinit(cell);
            std::vector<Vector<double>> values(1, Vector<double>(n_components));
            fe_values.get_function_values(*solution, values);
            for (unsigned int c = 0; c < n_components; ++c)
              local[i * n_values + c] = values[0][c];
          }
        catch (const ExceptionBase &) // the point is not in this part
          {}
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

  void
  Monitors::check_points(const Mapping<2>    &mapping,
                         const DoFHandler<2> &dof_handler) const
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

  void
  Monitors::write(const double                         time,
                  const Mapping<2>                    &mapping,
                  const DoFHandler<2>                 &dof_handler,
                  const TrilinosWrappers::MPI::Vector &solution)
  {
    if (points.empty())
      return;
    const auto         values = evaluate(mapping, dof_handler, &solution);
    std::ostringstream probe_rows, line_rows;
    for (unsigned int i = 0; i < points.size(); ++i)
      {
        std::ostringstream &rows = points[i].from_line ? line_rows : probe_rows;
        rows << std::setprecision(12) << time << "," << points[i].name << ","
             << points[i].location[0] << "," << points[i].location[1];
        for (unsigned int c = 0; c < n_components; ++c)
          rows << "," << values[i][c];
        rows << "\n";
      }
    probes_csv.append(probe_rows.str());
    lines_csv.append(line_rows.str());
  }
} // namespace tmfdem
