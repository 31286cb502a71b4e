#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <tmfdem/base/parameters.h>
#include <tmfdem/base/polar_stress.h>
#include <tmfdem/discrete/discrete_output.h>
#include <tmfdem/discrete/temperature_source.h>
#include <tmfdem/io/checkpoint.h>
#include <tmfdem/io/output_files.h>
#include <type_traits>
#include <zlib.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      /** Appends the shortest text that reads back as exactly @p value. */
      template <typename T>
      void
      append_number(std::string &out, const T value)
      {
        char       text[32];
        const auto result = std::to_chars(text, text + sizeof(text), value);
        out.append(text, result.ptr);
      }

      /** The VTK type name of the C++ type @p Stored. */
      template <typename Stored>
      constexpr const char *
      vtk_type_name()
      {
        if constexpr (std::is_same_v<Stored, float>)
          return "Float32";
        else if constexpr (std::is_same_v<Stored, double>)
          return "Float64";
        else if constexpr (std::is_same_v<Stored, std::int64_t>)
          return "Int64";
        else if constexpr (std::is_same_v<Stored, std::int32_t>)
          return "Int32";
        else
          {
            static_assert(std::is_same_v<Stored, std::uint8_t>,
                          "a vtu array of a type without a VTK name");
            return "UInt8";
          }
      }

      /**
       * Appends one DataArray's block of appended raw data as VTK's XML
       * readers expect it with compressor="vtkZLibDataCompressor" and
       * header_type="UInt64": the header [number of blocks, block size,
       * size of the last block, compressed size of each block] and the
       * zlib-compressed values (level vtu_zlib_level), as raw bytes. Always
       * one block, also for an empty array (header [1, 0, 0, size of an
       * empty zlib stream]: meshio cannot read a header without blocks).
       */
      void
      append_compressed(std::string &out, const void *data, const std::size_t n)
      {
        uLongf            size = compressBound(n);
        const std::size_t at   = out.size();
        out.resize(at + 4 * sizeof(std::uint64_t) + size);
        const int status = compress2(reinterpret_cast<Bytef *>(
                                       &out[at + 4 * sizeof(std::uint64_t)]),
                                     &size,
                                     static_cast<const Bytef *>(data),
                                     n,
                                     vtu_zlib_level);
        if (status != Z_OK)
          throw std::runtime_error("zlib failed to compress a vtu array (" +
                                   std::to_string(n) + " bytes, zlib status " +
                                   std::to_string(status) + ")");
        const std::uint64_t header[4] = {1, n, n, size};
        std::memcpy(&out[at], header, sizeof(header));
        out.resize(at + sizeof(header) + size);
      }

      /**
       * One VTK XML UnstructuredGrid piece written as text: every DataArray
       * either ascii (the shortest text that reads back as the same stored
       * value, 9 values a line) or binary (a declaration with its offset in
       * the appended raw data, append_compressed()), the same arrays,
       * names, types and values in either.
       */
      class VtuText
      {
      public:
        explicit VtuText(const VtuEncoding &encoding)
          : encoding(encoding)
        {}

        /** A DataArray of @p values converted to the C++ type @p Stored
         *  (float, double, std::int64_t, std::int32_t, std::uint8_t; real
         *  values rounded to the nearest), of that type's VTK type. */
        template <typename Stored, typename T>
        void
        data_array(const std::string    &name,
                   const unsigned int    components,
                   const std::vector<T> &values)
        {
          text +=
            std::string("<DataArray type=\"") + vtk_type_name<Stored>() + "\"";
          if (!name.empty())
            text += " Name=\"" + name + "\"";
          text += " NumberOfComponents=\"" + std::to_string(components) + "\"";
          if (encoding.binary)
            {
              // the offset counts from the byte after the mark '_'
              text += " format=\"appended\" offset=\"" +
                      std::to_string(appended.size()) + "\"/>\n";
              const std::vector<Stored> stored(values.begin(), values.end());
              append_compressed(appended,
                                stored.data(),
                                stored.size() * sizeof(Stored));
              return;
            }
          text += " format=\"ascii\">\n";
          for (std::size_t i = 0; i < values.size(); ++i)
            {
              // UInt8 as a number, not as a character
              if constexpr (sizeof(Stored) == 1)
                append_number(text, static_cast<int>(values[i]));
              else
                append_number(text, static_cast<Stored>(values[i]));
              text += (i + 1) % 9 == 0 ? '\n' : ' ';
            }
          text += "\n</DataArray>\n";
        }

        /** A DataArray of real @p values: Float32 (each rounded to the
         *  nearest float) or Float64, as the encoding's precision says. */
        void
        real_array(const std::string         &name,
                   const unsigned int         components,
                   const std::vector<double> &values)
        {
          if (encoding.single_precision)
            data_array<float>(name, components, values);
          else
            data_array<double>(name, components, values);
        }

        void
        add(const std::string &markup)
        {
          text += markup;
        }

        /** The document, the header naming the compressor and the appended
         *  raw data (after the mark '_', a line break after it) if
         *  binary. */
        std::string
        document() const
        {
          // binary values are the machine's bytes
          const std::uint16_t one = 1;
          const bool          little_endian =
            *reinterpret_cast<const unsigned char *>(&one) == 1;
          std::string out =
            std::string("<?xml version=\"1.0\"?>\n<VTKFile "
                        "type=\"UnstructuredGrid\" version=\"1.0\" "
                        "byte_order=\"") +
            (little_endian ? "LittleEndian" : "BigEndian") + "\"" +
            (encoding.binary ? " header_type=\"UInt64\" "
                               "compressor=\"vtkZLibDataCompressor\"" :
                               "") +
            ">\n<UnstructuredGrid>\n";
          out.reserve(out.size() + text.size() + appended.size() + 64);
          out += text;
          out += "</UnstructuredGrid>\n";
          if (encoding.binary)
            {
              out += "<AppendedData encoding=\"raw\">\n_";
              out += appended;
              out += "\n</AppendedData>\n";
            }
          out += "</VTKFile>\n";
          return out;
        }

      private:
        VtuEncoding encoding;
        std::string text;
        /** The appended raw data of the binary arrays so far. */
        std::string appended;
      };

      /** The point and cell data arrays of a piece: added to a VtuText in
       *  order. */
      using ArrayWriter = std::function<void(VtuText &)>;

      /** A piece of @p n_cells cells of VTK type @p vtk_type with
       *  @p nodes_per_cell nodes each; @p point_dim coordinates per point
       *  in @p points_in (2: z = 0). */
      std::string
      grid(const VtuEncoding               &encoding,
           const std::vector<double>       &points_in,
           const std::vector<unsigned int> &connectivity,
           const std::size_t                n_cells,
           const unsigned int               nodes_per_cell,
           const unsigned int               vtk_type,
           const ArrayWriter               &point_data,
           const ArrayWriter               &cell_data,
           const unsigned int               point_dim = 2)
      {
        const std::size_t n_points = points_in.size() / point_dim;
        VtuText           out(encoding);
        out.add("<Piece NumberOfPoints=\"" + std::to_string(n_points) +
                "\" NumberOfCells=\"" + std::to_string(n_cells) +
                "\">\n<Points>\n");
        std::vector<double> points(3 * n_points, 0.);
        for (std::size_t i = 0; i < n_points; ++i)
          for (unsigned int d = 0; d < point_dim; ++d)
            points[3 * i + d] = points_in[point_dim * i + d];
        out.real_array("", 3, points);
        out.add("</Points>\n<Cells>\n");
        out.data_array<std::int64_t>("connectivity", 1, connectivity);
        std::vector<std::size_t>  offsets(n_cells);
        std::vector<unsigned int> types(n_cells, vtk_type);
        for (std::size_t c = 0; c < n_cells; ++c)
          offsets[c] = (c + 1) * nodes_per_cell;
        out.data_array<std::int64_t>("offsets", 1, offsets);
        out.data_array<std::uint8_t>("types", 1, types);
        out.add("</Cells>\n<PointData>\n");
        if (point_data)
          point_data(out);
        out.add("</PointData>\n<CellData>\n");
        cell_data(out);
        out.add("</CellData>\n</Piece>\n");
        return out.document();
      }
    } // namespace

    VtuEncoding
    vtu_encoding(const OutputParameters &output)
    {
      return {output.binary_vtu, output.single_precision_vtu};
    }

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
              "version=\"1.0\" byte_order=\"LittleEndian\">\n"
              "<PUnstructuredGrid GhostLevel=\"0\">\n<PPointData>\n"
           << parallel_declarations(piece_text, "<PointData>", "</PointData>")
           << "</PPointData>\n<PCellData>\n"
           << parallel_declarations(piece_text, "<CellData>", "</CellData>")
           << "</PCellData>\n<PPoints>\n"
           << parallel_declarations(piece_text, "<Points>", "</Points>")
           << "</PPoints>\n";
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
    VtuSeries::save_records(CheckpointWriter &out) const
    {
      out.put<std::uint64_t>(records.size());
      for (const auto &[t, name] : records)
        {
          out.put(t);
          out.put(name);
        }
    }

    std::vector<std::pair<double, std::string>>
    VtuSeries::load_records(CheckpointReader &in)
    {
      std::uint64_t n = 0;
      in.get(n);
      if (n > 100000000)
        throw InputError("the checkpoint '" + in.name() +
                         "' is corrupt (output record count).");
      std::vector<std::pair<double, std::string>> saved(n);
      for (auto &[t, name] : saved)
        {
          in.get(t);
          in.get(name);
        }
      return saved;
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

    namespace
    {
      /** discrete_solution_vtu() of a tetrahedral model (dim = 3). */
      std::string
      tetrahedra_solution_vtu(
        const DiscreteModel &model,
        const VtuEncoding   &encoding,
        const std::vector<std::pair<std::string, const std::vector<double> *>>
          &extra_point_fields)
      {
        const unsigned int  n_cells = model.n_elements, n_points = 4 * n_cells;
        std::vector<double> points(3 * n_points), displacement(3 * n_points),
          velocity(3 * n_points);
        std::vector<unsigned int> connectivity(n_points);
        for (unsigned int n = 0; n < n_points; ++n)
          {
            points[3 * n]           = model.x[n];
            points[3 * n + 1]       = model.y[n];
            points[3 * n + 2]       = model.z[n];
            connectivity[n]         = n;
            displacement[3 * n]     = model.x[n] - model.x_ref[n];
            displacement[3 * n + 1] = model.y[n] - model.y_ref[n];
            displacement[3 * n + 2] = model.z[n] - model.z_ref[n];
            velocity[3 * n]         = model.vx[n];
            velocity[3 * n + 1]     = model.vy[n];
            velocity[3 * n + 2]     = model.vz[n];
          }
        const auto point_data = [&](VtuText &out) {
          out.real_array("displacement", 3, displacement);
          out.real_array("velocity", 3, velocity);
          for (const auto &[name, values] : extra_point_fields)
            out.real_array(name, 1, *values);
        };
        // the six stress components, the largest joint damage of the faces
        const char *names[6] = {"sxx", "syy", "szz", "sxy", "syz", "sxz"};
        std::vector<std::vector<double>> stress(6,
                                                std::vector<double>(n_cells));
        std::vector<double>              damage(n_cells, 0.);
        std::vector<int>                 material(n_cells), body(n_cells);
        for (unsigned int e = 0; e < n_cells; ++e)
          {
            for (unsigned int i = 0; i < 6; ++i)
              stress[i][e] = model.stress[6 * e + i];
            material[e] = model.material[e];
            body[e]     = model.body[e] == no_body ?
                            -1 :
                            static_cast<int>(model.body_number[model.body[e]]);
            for (unsigned int f = 0; f < 4; ++f)
              {
                const int code = model.edge_joint[4 * e + f];
                if (code < 0)
                  continue;
                const unsigned int j = code / 2;
                double             d = 1.;
                if (model.joint_status[j] == JointStatus::intact)
                  d = std::max({model.joint_damage[3 * j],
                                model.joint_damage[3 * j + 1],
                                model.joint_damage[3 * j + 2]});
                damage[e] = std::max(damage[e], d);
              }
          }
        const auto cell_data = [&](VtuText &out) {
          for (unsigned int i = 0; i < 6; ++i)
            out.real_array(names[i], 1, stress[i]);
          out.real_array("joint_damage", 1, damage);
          out.data_array<std::int32_t>("material_id", 1, material);
          out.data_array<std::int32_t>("body", 1, body);
        };
        // VTK_TETRA = 10
        return grid(encoding,
                    points,
                    connectivity,
                    n_cells,
                    4,
                    10,
                    point_data,
                    cell_data,
                    3);
      }
    } // namespace

    std::string
    discrete_solution_vtu(
      const DiscreteModel &model,
      const VtuEncoding   &encoding,
      const std::vector<std::pair<std::string, const std::vector<double> *>>
                                  &extra_point_fields,
      const unsigned int           first_element,
      const unsigned int           end_element,
      const std::array<double, 2> *polar_centre)
    {
      if (model.dim == 3)
        return tetrahedra_solution_vtu(model, encoding, extra_point_fields);
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
      const auto point_data = [&](VtuText &out) {
        out.real_array("displacement", 3, displacement);
        out.real_array("velocity", 3, velocity);
        for (const auto &[name, values] : extra_point_fields)
          out.real_array(name,
                         1,
                         std::vector<double>(values->begin() + node0,
                                             values->begin() + node0 +
                                               n_points));
      };

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
          body[c]              = model.body[e] == no_body ?
                                   -1 :
                                   static_cast<int>(model.body_number[model.body[e]]);
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
      const auto cell_data = [&](VtuText &out) {
        out.real_array("sxx", 1, sxx);
        out.real_array("syy", 1, syy);
        out.real_array("sxy", 1, sxy);
        out.real_array("joint_damage", 1, damage);
        out.data_array<std::int32_t>("material_id", 1, material);
        out.data_array<std::int32_t>("body", 1, body);
        if (polar_centre)
          {
            std::vector<double> srr(n_cells), stt(n_cells);
            for (unsigned int c = 0; c < n_cells; ++c)
              {
                const unsigned int e = first + c, n = 3 * e;
                const double       dx =
                  (model.x[n] + model.x[n + 1] + model.x[n + 2]) / 3. -
                  (*polar_centre)[0];
                const double dy =
                  (model.y[n] + model.y[n + 1] + model.y[n + 2]) / 3. -
                  (*polar_centre)[1];
                const auto polar = polar_stress(sxx[c], syy[c], sxy[c], dx, dy);
                srr[c]           = polar[0];
                stt[c]           = polar[1];
              }
            out.real_array("srr", 1, srr);
            out.real_array("stt", 1, stt);
          }
        if (!model.expansion_factor.empty())
          out.real_array(
            "expansion_factor",
            1,
            std::vector<double>(model.expansion_factor.begin() + first,
                                model.expansion_factor.begin() + end));
      };
      return grid(encoding,
                  points,
                  connectivity,
                  n_cells,
                  3,
                  5,
                  point_data,
                  cell_data);
    }

    std::string
    crack_vtu(const DiscreteModel &model,
              const VtuEncoding   &encoding,
              const unsigned int   first_joint,
              const unsigned int   end_joint)
    {
      std::vector<double>       points;
      std::vector<unsigned int> connectivity;
      std::vector<int>          mode;
      std::vector<double>       break_time;
      // broken faces of tetrahedra: triangles at the mean of their node
      // pairs (VTK_TRIANGLE = 5)
      const unsigned int dim = model.dim;
      for (unsigned int j = first_joint;
           j < std::min(end_joint, model.n_joints);
           ++j)
        if (dim == 3 && model.joint_status[j] != JointStatus::intact)
          {
            const unsigned int *n = &model.joint_nodes[6 * j];
            for (unsigned int k = 0; k < 3; ++k)
              {
                connectivity.push_back(points.size() / 3);
                points.push_back(0.5 * (model.x[n[k]] + model.x[n[3 + k]]));
                points.push_back(0.5 * (model.y[n[k]] + model.y[n[3 + k]]));
                points.push_back(0.5 * (model.z[n[k]] + model.z[n[3 + k]]));
              }
            mode.push_back(static_cast<int>(model.joint_status[j]));
            break_time.push_back(model.joint_break_time[j]);
          }
        else if (model.joint_status[j] != JointStatus::intact)
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
      // no broken joint: one placeholder cell, a poly-vertex (VTK type 2)
      // of no points, mode 0 (intact), break time NaN. meshio reads no vtu
      // without cells (nor VTK_EMPTY_CELL); it skips this type with a
      // warning, and ParaView draws nothing for it
      const bool none = mode.empty();
      if (none)
        {
          mode.push_back(static_cast<int>(JointStatus::intact));
          break_time.push_back(std::numeric_limits<double>::quiet_NaN());
        }
      const auto cell_data = [&](VtuText &out) {
        out.data_array<std::int32_t>("failure_mode", 1, mode);
        out.real_array("break_time", 1, break_time);
      };
      return grid(encoding,
                  points,
                  connectivity,
                  mode.size(),
                  none ? 0 : dim,
                  none ? 2 : (dim == 3 ? 5 : 3),
                  {},
                  cell_data,
                  dim);
    }

    std::string
    deformed_mesh_msh(const DiscreteModel &model)
    {
      const unsigned int dim        = model.dim;
      const unsigned int corners    = dim + 1; // nodes (and edges/faces) each
      unsigned int       n_vertices = 0;
      for (const unsigned int v : model.node_vertex)
        n_vertices = std::max(n_vertices, v + 1);
      std::vector<double> x(n_vertices, 0.), y(n_vertices, 0.),
        z(n_vertices, 0.);
      std::vector<unsigned int> copies(n_vertices, 0);
      for (unsigned int i = 0; i < model.n_nodes; ++i)
        {
          const unsigned int v = model.node_vertex[i];
          x[v] += model.x[i];
          y[v] += model.y[i];
          if (dim == 3)
            z[v] += model.z[i];
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
              << ' ' << z[v] / copies[v] << '\n';
      out << "$EndNodes\n";
      // the nodes of edge k (2D: k, k + 1) or face k (3D: deal.II's face k
      // of a tetrahedron, opposite node 3 - k)
      const auto side_nodes = [&](const unsigned int e, const unsigned int k) {
        std::vector<unsigned int> nodes;
        if (dim == 2)
          nodes = {3 * e + k, 3 * e + (k + 1) % 3};
        else
          for (unsigned int m = 0; m < 4; ++m)
            if (m != 3 - k)
              nodes.push_back(4 * e + m);
        return nodes;
      };
      // gmsh element types: line 1, triangle 2, tetrahedron 4
      const unsigned int side_type = dim == 2 ? 1 : 2,
                         cell_type = dim == 2 ? 2 : 4;
      std::ostringstream elements;
      unsigned int       n_elements = 0;
      for (unsigned int e = 0; e < model.n_elements; ++e)
        for (unsigned int k = 0; k < corners; ++k)
          {
            const types::boundary_id id = model.edge_boundary[corners * e + k];
            if (model.edge_joint[corners * e + k] < 0 && id > 0 &&
                id != numbers::internal_face_boundary_id)
              {
                elements << ++n_elements << ' ' << side_type << " 2 " << id
                         << ' ' << id;
                for (const unsigned int node : side_nodes(e, k))
                  elements << ' ' << number[model.node_vertex[node]];
                elements << '\n';
              }
          }
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          const unsigned int m = model.material[e];
          elements << ++n_elements << ' ' << cell_type << " 2 " << m << ' '
                   << m;
          for (unsigned int k = 0; k < corners; ++k)
            elements << ' ' << number[model.node_vertex[corners * e + k]];
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
      return heat_balance_summary(source.balance(),
                                  source.last_boundary_rate());
    }

    JsonObject
    heat_balance_summary(const HeatBalance                          &b,
                         const std::map<types::boundary_id, double> &last_rates)
    {
      JsonObject boundary;
      for (const auto &[id, q] : b.boundary_heat_in)
        boundary.add(std::to_string(id), q);
      JsonObject rates;
      for (const auto &[id, q] : last_rates)
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
