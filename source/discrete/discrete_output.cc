#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>
#include <tmfdem/discrete/discrete_output.h>
#include <tmfdem/discrete/temperature_source.h>
#include <tmfdem/io/output_files.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      /** A DataArray element with @p values written with 9 digits. */
      template <typename T>
      void
      data_array(std::ostringstream   &out,
                 const std::string    &type,
                 const std::string    &name,
                 const unsigned int    components,
                 const std::vector<T> &values)
      {
        out << "<DataArray type=\"" << type << "\" Name=\"" << name
            << "\" NumberOfComponents=\"" << components
            << "\" format=\"ascii\">\n";
        for (std::size_t i = 0; i < values.size(); ++i)
          out << values[i] << ((i + 1) % 9 == 0 ? '\n' : ' ');
        out << "\n</DataArray>\n";
      }

      std::string
      grid(const std::vector<double>       &points_xy,
           const std::vector<unsigned int> &connectivity,
           const unsigned int               nodes_per_cell,
           const unsigned int               vtk_type,
           const std::string               &point_data,
           const std::string               &cell_data)
      {
        const std::size_t  n_points = points_xy.size() / 2;
        const std::size_t  n_cells  = connectivity.size() / nodes_per_cell;
        std::ostringstream out;
        out << std::setprecision(9);
        out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" "
               "version=\"0.1\" byte_order=\"LittleEndian\">\n"
               "<UnstructuredGrid>\n<Piece NumberOfPoints=\""
            << n_points << "\" NumberOfCells=\"" << n_cells << "\">\n";
        out << "<Points>\n<DataArray type=\"Float64\" NumberOfComponents=\"3\" "
               "format=\"ascii\">\n";
        for (std::size_t i = 0; i < n_points; ++i)
          out << points_xy[2 * i] << ' ' << points_xy[2 * i + 1] << " 0\n";
        out << "</DataArray>\n</Points>\n<Cells>\n";
        data_array(out, "Int64", "connectivity", 1, connectivity);
        std::vector<unsigned int> offsets(n_cells), types(n_cells, vtk_type);
        for (std::size_t c = 0; c < n_cells; ++c)
          offsets[c] = (c + 1) * nodes_per_cell;
        data_array(out, "Int64", "offsets", 1, offsets);
        data_array(out, "UInt8", "types", 1, types);
        out << "</Cells>\n<PointData>\n"
            << point_data << "</PointData>\n<CellData>\n"
            << cell_data << "</CellData>\n</Piece>\n</UnstructuredGrid>\n"
            << "</VTKFile>\n";
        return out.str();
      }
    } // namespace

    VtuSeries::VtuSeries(const std::string &folder,
                         const std::string &base_name)
      : folder(folder)
      , base_name(base_name)
    {}

    std::string
    VtuSeries::next_stem() const
    {
      char number[16];
      std::snprintf(number,
                    sizeof(number),
                    "%05u",
                    static_cast<unsigned int>(records.size()));
      return base_name + "_" + number;
    }

    void
    VtuSeries::write(const double time, const std::string &vtu_text)
    {
      const std::string file = next_stem() + ".vtu";
      write_file_atomically(folder + "/" + file, vtu_text);
      records.emplace_back(time, file);
      write_pvd();
    }

    namespace
    {
      std::string
      piece_name(const std::string &stem, const unsigned int rank)
      {
        char number[16];
        std::snprintf(number, sizeof(number), ".%04u.vtu", rank);
        return stem + number;
      }

      /** The `<DataArray ...>` declarations between @p open and @p close
       *  in @p piece, as `<PDataArray .../>` lines. */
      std::string
      parallel_declarations(const std::string &piece,
                            const std::string &open,
                            const std::string &close)
      {
        std::string  out;
        const auto   begin = piece.find(open);
        const auto   end   = piece.find(close);
        const auto   tag   = std::string("<DataArray ");
        const size_t stop  = end == std::string::npos ? piece.size() : end;
        for (auto at = begin == std::string::npos ? stop :
                                                    piece.find(tag, begin);
             at < stop;
             at = piece.find(tag, at + 1))
          {
            // the attributes up to format="...": type, Name, components
            const auto format = piece.find(" format=", at);
            out += "<PDataArray " +
                   piece.substr(at + tag.size(), format - at - tag.size()) +
                   "/>\n";
          }
        return out;
      }
    } // namespace

    void
    VtuSeries::write_piece(const unsigned int rank,
                           const std::string &vtu_text) const
    {
      write_file_atomically(folder + "/" + piece_name(next_stem(), rank),
                            vtu_text);
    }

    void
    VtuSeries::write_parallel_record(const double       time,
                                     const unsigned int n_ranks,
                                     const std::string &piece_text)
    {
      const std::string  stem = next_stem();
      std::ostringstream pvtu;
      pvtu << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" "
              "version=\"0.1\" byte_order=\"LittleEndian\">\n"
              "<PUnstructuredGrid GhostLevel=\"0\">\n<PPointData>\n"
           << parallel_declarations(piece_text, "<PointData>", "</PointData>")
           << "</PPointData>\n<PCellData>\n"
           << parallel_declarations(piece_text, "<CellData>", "</CellData>")
           << "</PCellData>\n<PPoints>\n<PDataArray type=\"Float64\" "
              "NumberOfComponents=\"3\"/>\n</PPoints>\n";
      for (unsigned int r = 0; r < n_ranks; ++r)
        pvtu << "<Piece Source=\"" << piece_name(stem, r) << "\"/>\n";
      pvtu << "</PUnstructuredGrid>\n</VTKFile>\n";
      write_file_atomically(folder + "/" + stem + ".pvtu", pvtu.str());
      records.emplace_back(time, stem + ".pvtu");
      write_pvd();
    }

    void
    VtuSeries::add_parallel_record(const double time)
    {
      records.emplace_back(time, next_stem() + ".pvtu");
    }

    void
    VtuSeries::restore(const std::vector<std::pair<double, std::string>> &saved,
                       const bool                                         write)
    {
      records = saved;
      if (write)
        write_pvd();
    }

    void
    VtuSeries::write_pvd() const
    {
      std::ostringstream pvd;
      pvd << std::setprecision(12)
          << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" "
             "version=\"0.1\">\n<Collection>\n";
      for (const auto &[t, name] : records)
        pvd << "  <DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << name
            << "\"/>\n";
      pvd << "</Collection>\n</VTKFile>\n";
      write_file_atomically(folder + "/" + base_name + ".pvd", pvd.str());
    }

    std::string
    discrete_solution_vtu(
      const DiscreteModel &model,
      const std::vector<std::pair<std::string, const std::vector<double> *>>
                        &extra_point_fields,
      const unsigned int first_element,
      const unsigned int end_element)
    {
      // triangles [first, end) own the nodes [3 first, 3 end)
      const unsigned int  first    = std::min(first_element, model.n_elements);
      const unsigned int  end      = std::min(end_element, model.n_elements);
      const unsigned int  n_cells  = end > first ? end - first : 0;
      const unsigned int  n_points = 3 * n_cells, node0 = 3 * first;
      std::vector<double> points(2 * n_points);
      std::vector<unsigned int> connectivity(n_points);
      std::vector<double> displacement(3 * n_points), velocity(3 * n_points);
      for (unsigned int i = 0; i < n_points; ++i)
        {
          const unsigned int n    = node0 + i;
          points[2 * i]           = model.x[n];
          points[2 * i + 1]       = model.y[n];
          connectivity[i]         = i;
          displacement[3 * i]     = model.x[n] - model.x_ref[n];
          displacement[3 * i + 1] = model.y[n] - model.y_ref[n];
          displacement[3 * i + 2] = 0.;
          velocity[3 * i]         = model.vx[n];
          velocity[3 * i + 1]     = model.vy[n];
          velocity[3 * i + 2]     = 0.;
        }
      std::ostringstream point_data;
      point_data << std::setprecision(9);
      data_array(point_data, "Float64", "displacement", 3, displacement);
      data_array(point_data, "Float64", "velocity", 3, velocity);
      for (const auto &[name, values] : extra_point_fields)
        data_array(point_data,
                   "Float64",
                   name,
                   1,
                   std::vector<double>(values->begin() + node0,
                                       values->begin() + node0 + n_points));

      std::vector<double> sxx(n_cells), syy(n_cells), sxy(n_cells),
        damage(n_cells, 0.);
      std::vector<int> material(n_cells), body(n_cells);
      for (unsigned int c = 0; c < n_cells; ++c)
        {
          const unsigned int e = first + c;
          sxx[c]               = model.stress[3 * e];
          syy[c]               = model.stress[3 * e + 1];
          sxy[c]               = model.stress[3 * e + 2];
          material[c]          = model.material[e];
          body[c]              = model.body[e] == no_body ? -1 : model.body[e];
          for (unsigned int k = 0; k < 3; ++k)
            {
              const int code = model.edge_joint[3 * e + k];
              if (code >= 0)
                {
                  const unsigned int j = code / 2;
                  const double       d =
                    model.joint_status[j] != JointStatus::intact ?
                            1. :
                            std::max(model.joint_damage[2 * j],
                               model.joint_damage[2 * j + 1]);
                  damage[c] = std::max(damage[c], d);
                }
            }
        }
      std::ostringstream cell_data;
      cell_data << std::setprecision(9);
      data_array(cell_data, "Float64", "sxx", 1, sxx);
      data_array(cell_data, "Float64", "syy", 1, syy);
      data_array(cell_data, "Float64", "sxy", 1, sxy);
      data_array(cell_data, "Float64", "joint_damage", 1, damage);
      data_array(cell_data, "Int32", "material_id", 1, material);
      data_array(cell_data, "Int32", "body", 1, body);
      if (!model.expansion_factor.empty())
        data_array(cell_data,
                   "Float64",
                   "expansion_factor",
                   1,
                   std::vector<double>(model.expansion_factor.begin() + first,
                                       model.expansion_factor.begin() + end));
      return grid(points,
                  connectivity,
                  3,
                  5,
                  point_data.str(),
                  cell_data.str());
    }

    std::string
    crack_vtu(const DiscreteModel &model,
              const unsigned int   first_joint,
              const unsigned int   end_joint)
    {
      std::vector<double>       points;
      std::vector<unsigned int> connectivity;
      std::vector<int>          mode;
      std::vector<double>       break_time;
      for (unsigned int j = first_joint;
           j < std::min(end_joint, model.n_joints);
           ++j)
        if (model.joint_status[j] != JointStatus::intact)
          {
            const unsigned int *n = &model.joint_nodes[4 * j];
            for (unsigned int end = 0; end < 2; ++end)
              {
                connectivity.push_back(points.size() / 2);
                points.push_back(0.5 * (model.x[n[end]] + model.x[n[2 + end]]));
                points.push_back(0.5 * (model.y[n[end]] + model.y[n[2 + end]]));
              }
            mode.push_back(static_cast<int>(model.joint_status[j]));
            break_time.push_back(model.joint_break_time[j]);
          }
      std::ostringstream cell_data;
      cell_data << std::setprecision(9);
      data_array(cell_data, "Int32", "failure_mode", 1, mode);
      data_array(cell_data, "Float64", "break_time", 1, break_time);
      return grid(points, connectivity, 2, 3, "", cell_data.str());
    }

    std::string
    deformed_mesh_msh(const DiscreteModel &model)
    {
      unsigned int n_vertices = 0;
      for (const unsigned int v : model.node_vertex)
        n_vertices = std::max(n_vertices, v + 1);
      std::vector<double>       x(n_vertices, 0.), y(n_vertices, 0.);
      std::vector<unsigned int> copies(n_vertices, 0);
      for (unsigned int i = 0; i < model.n_nodes; ++i)
        {
          const unsigned int v = model.node_vertex[i];
          x[v] += model.x[i];
          y[v] += model.y[i];
          ++copies[v];
        }
      // renumber the vertices that some element uses, from 1
      std::vector<unsigned int> number(n_vertices, 0);
      unsigned int              n_used = 0;
      for (unsigned int v = 0; v < n_vertices; ++v)
        if (copies[v] > 0)
          number[v] = ++n_used;
      std::ostringstream out;
      out << std::setprecision(17);
      out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n" << n_used << '\n';
      for (unsigned int v = 0; v < n_vertices; ++v)
        if (copies[v] > 0)
          out << number[v] << ' ' << x[v] / copies[v] << ' ' << y[v] / copies[v]
              << " 0\n";
      out << "$EndNodes\n";
      std::ostringstream elements;
      unsigned int       n_elements = 0;
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int k = 0; k < 3; ++k)
          {
            const types::boundary_id id = model.edge_boundary[3 * e + k];
            if (model.edge_joint[3 * e + k] < 0 && id > 0 &&
                id != numbers::internal_face_boundary_id)
              elements << ++n_elements << " 1 2 " << id << ' ' << id << ' '
                       << number[model.node_vertex[3 * e + k]] << ' '
                       << number[model.node_vertex[3 * e + (k + 1) % 3]]
                       << '\n';
          }
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          const unsigned int m = model.material[e];
          elements << ++n_elements << " 2 2 " << m << ' ' << m;
          for (unsigned int k = 0; k < 3; ++k)
            elements << ' ' << number[model.node_vertex[3 * e + k]];
          elements << '\n';
        }
      out << "$Elements\n"
          << n_elements << '\n'
          << elements.str() << "$EndElements\n";
      return out.str();
    }
    JsonObject
    heat_balance_summary(const TemperatureSource &source)
    {
      const HeatBalance &b = source.balance();
      JsonObject         boundary;
      for (const auto &[id, q] : b.boundary_heat_in)
        boundary.add(std::to_string(id), q);
      JsonObject rates;
      for (const auto &[id, q] : source.last_boundary_rate())
        rates.add(std::to_string(id), q);
      JsonObject balance;
      balance.add("boundary_heat_in", boundary)
        .add("source_heat", b.source_heat)
        .add("contact_heat", b.contact_heat)
        .add("contact_exchange", b.contact_exchange)
        .add("stored_heat", b.stored_heat)
        .add("boundary_heat_rate_last_step", rates)
        .add("imbalance", b.imbalance())
        .add("relative_imbalance", std::abs(b.imbalance()) / b.scale());
      return balance;
    }
  } // namespace discrete
} // namespace tmfdem
