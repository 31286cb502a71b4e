#include <deal.II/base/exceptions.h>
#include <deal.II/base/mpi.h>
#include <deal.II/distributed/shared_tria.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/grid_in.h>
#include <deal.II/grid/manifold_lib.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <sys/wait.h>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/mesh/block_generator.h>
#include <tmfdem/mesh/mesh_generator.h>
#include <unistd.h>

namespace tmfdem
{
  namespace
  {
    /** Manifold id of curved boundary faces of generated meshes. */
    constexpr types::manifold_id circle_manifold_id = 1;

    std::string
    gmsh_point(const unsigned int tag, const double x, const double y)
    {
      std::ostringstream text;
      text.precision(17);
      text << "Point(" << tag << ") = {" << x << ", " << y << ", 0, h};\n";
      return text.str();
    }

    /**
     * Four quarter arcs of a circle of radius @p radius about point
     * @p center_tag; points @p first_point ... +3, curves @p first_curve ...
     */
    std::string
    gmsh_circle(const Point<2>    &center,
                const double       radius,
                const unsigned int center_tag,
                const unsigned int first_point,
                const unsigned int first_curve)
    {
      std::string  text;
      const double dx[4] = {1, 0, -1, 0}, dy[4] = {0, 1, 0, -1};
      for (unsigned int i = 0; i < 4; ++i)
        text += gmsh_point(first_point + i,
                           center[0] + radius * dx[i],
                           center[1] + radius * dy[i]);
      for (unsigned int i = 0; i < 4; ++i)
        text += "Circle(" + std::to_string(first_curve + i) + ") = {" +
                std::to_string(first_point + i) + ", " +
                std::to_string(center_tag) + ", " +
                std::to_string(first_point + (i + 1) % 4) + "};\n";
      return text;
    }

    /** The .geo script of a generated triangle mesh. */
    std::string
    gmsh_script(const MeshParameters &p)
    {
      std::ostringstream geo;
      geo.precision(17);
      geo << "// written by tmfdem from the Mesh subsection of the prm file\n"
          << "h = " << p.element_size << ";\n";
      using Source = MeshParameters::Source;
      if (p.source == Source::rectangle)
        {
          // boundary ids as GridGenerator's colorize: 0 left (no physical
          // group: deal.II gives unlisted boundary faces id 0), 1 right,
          // 2 bottom, 3 top
          geo << gmsh_point(1, p.lower_left[0], p.lower_left[1])
              << gmsh_point(2, p.upper_right[0], p.lower_left[1])
              << gmsh_point(3, p.upper_right[0], p.upper_right[1])
              << gmsh_point(4, p.lower_left[0], p.upper_right[1])
              << "Line(1) = {1, 2};\nLine(2) = {2, 3};\n"
              << "Line(3) = {3, 4};\nLine(4) = {4, 1};\n"
              << "Curve Loop(1) = {1, 2, 3, 4};\nPlane Surface(1) = {1};\n"
              << "Physical Curve(1) = {2};\nPhysical Curve(2) = {1};\n"
              << "Physical Curve(3) = {3};\n";
        }
      else if (p.source == Source::annulus)
        {
          // inner boundary id 0 (no physical group), outer 1
          geo << gmsh_point(1, p.center[0], p.center[1])
              << gmsh_circle(MeshParameters::in_dimension<2>(p.center),
                             p.inner_radius,
                             1,
                             2,
                             1)
              << gmsh_circle(MeshParameters::in_dimension<2>(p.center),
                             p.outer_radius,
                             1,
                             6,
                             5)
              << "Curve Loop(1) = {5, 6, 7, 8};\n"
              << "Curve Loop(2) = {1, 2, 3, 4};\n"
              << "Plane Surface(1) = {1, 2};\n"
              << "Physical Curve(1) = {5, 6, 7, 8};\n";
        }
      else
        {
          geo << gmsh_point(1, p.center[0], p.center[1])
              << gmsh_circle(MeshParameters::in_dimension<2>(p.center),
                             p.outer_radius,
                             1,
                             2,
                             1)
              << "Curve Loop(1) = {1, 2, 3, 4};\n"
              << "Plane Surface(1) = {1};\n";
        }
      geo << "Physical Surface(1) = {1};\n"
          << "Mesh.Algorithm = 6;\n"
          << "Mesh.MeshSizeMin = h;\nMesh.MeshSizeMax = h;\n"
          << "Mesh.MeshSizeFromPoints = 0;\n"
          << "Mesh.MeshSizeExtendFromBoundary = 0;\n"
          << "Mesh.RandomSeed = 1;\n";
      return geo.str();
    }

    /** The "Error" lines of gmsh's log @p log_file, without its summary,
     *  at most 4, joined by "; ". */
    std::string
    gmsh_errors(const std::string &log_file)
    {
      std::ifstream log(log_file);
      std::string   errors;
      unsigned int  n = 0;
      for (std::string line; std::getline(log, line) && n < 4;)
        {
          if (line.rfind("Error", 0) != 0)
            continue;
          const auto        colon = line.find(':');
          const std::string text  = Utilities::trim(
            colon == std::string::npos ? line : line.substr(colon + 1));
          if (text.empty() || text.find("------") == 0 ||
              text.find("error summary") != std::string::npos)
            break;
          errors += (errors.empty() ? "" : "; ") + text;
          ++n;
        }
      return errors;
    }

    /**
     * Meshes @p geo_file with gmsh into @p msh_file, stopping gmsh after
     * @p time_limit seconds (Mesh/Gmsh time limit). With an empty @p script
     * the .geo file is the user's own: gmsh's errors in it and a mesh that
     * takes longer than the limit are bad input (InputError with gmsh's
     * own error lines); with a script of tmfdem's they are failures
     * (RunError).
     */
    void
    run_gmsh(const std::string &script,
             const std::string &geo_file,
             const std::string &work_folder,
             const std::string &msh_file,
             const double       time_limit,
             MPI_Comm           communicator,
             const unsigned int dim = 2)
    {
      std::string error;
      bool        bad_input = false;
      if (Utilities::MPI::this_mpi_process(communicator) == 0)
        {
          if (!script.empty())
            {
              std::ofstream geo(geo_file);
              geo << script;
              if (!geo)
                error = "cannot write " + geo_file;
            }
          if (error.empty())
            {
              std::filesystem::remove(msh_file);
              const std::string  log = work_folder + "/gmsh.log";
              std::ostringstream limit;
              limit << std::setprecision(17) << time_limit;
              // timeout(1): TERM at the limit, KILL 5 s later
              const std::string command =
                "command -v gmsh > /dev/null 2>&1 || exit 127; timeout -k 5 " +
                limit.str() + " gmsh \"" + geo_file + "\" -" +
                std::to_string(dim) + " -format msh22 -nt 1 -v 2 -o \"" +
                msh_file + "\" > \"" + log + "\" 2>&1";
              const int         status = std::system(command.c_str());
              const int         code   = status == -1 ?
                                           -1 :
                                           (WIFEXITED(status) ? WEXITSTATUS(status) :
                                                                128 + WTERMSIG(status));
              const std::string errors = gmsh_errors(log);
              if (code == 127)
                error = "gmsh is not installed (not on PATH), which Mesh "
                        "needs to mesh " +
                        geo_file + " (apt-get install gmsh).";
              else if (code == 124 || code == 137)
                {
                  bad_input = true;
                  error     = "gmsh did not finish meshing " + geo_file +
                          " within Mesh/Gmsh time limit = " + limit.str() +
                          " s and was stopped (log: " + log +
                          "). Coarsen the mesh (Mesh/Element size or the "
                          "sizes in the .geo file) or raise Mesh/Gmsh time "
                          "limit.";
                }
              else if (code != 0 || !std::filesystem::exists(msh_file))
                {
                  bad_input = script.empty();
                  error = "gmsh failed to mesh " + geo_file + " (exit status " +
                          std::to_string(code) + ")" +
                          (errors.empty() ? std::string() : ": " + errors) +
                          " (full log: " + log + ")";
                }
            }
        }
      error     = Utilities::MPI::broadcast(communicator, error, 0);
      bad_input = Utilities::MPI::broadcast(communicator, bad_input, 0);
      if (!error.empty() && bad_input)
        throw InputError(error);
      if (!error.empty())
        throw RunError(error);
    }

    /** Largest physical tag of a .msh element: it becomes a material id
     *  (cells) or a boundary id (lines). */
    constexpr long long max_physical_tag = 65535;

    /** @p text as a whole integer, or false. */
    bool
    parse_integer(const std::string &text, long long &value)
    {
      if (text.empty() || text.size() > 18)
        return false;
      std::size_t used = 0;
      try
        {
          value = std::stoll(text, &used);
        }
      catch (const std::exception &)
        {
          return false;
        }
      return used == text.size();
    }

    /**
     * Checks the $Nodes and $Elements sections of the gmsh 2.x ASCII file
     * @p file_name before deal.II reads it (its reader trusts the counts
     * and tags: a negative count allocates without bound, a negative or
     * huge physical tag crashes): each count a non-negative integer equal
     * to the lines of its section, each node "id x y z" with finite
     * coordinates, each element "id type n_tags tags... nodes" with
     * 0 <= physical tag <= max_physical_tag. InputError naming the file,
     * the line and what is allowed.
     */
    void
    check_msh2_sections(const std::string &file_name)
    {
      std::ifstream in(file_name);
      const auto fail = [&](const std::size_t line, const std::string &what) {
        throw InputError("Mesh file '" + file_name + "' cannot be read: line " +
                         std::to_string(line) + ": " + what);
      };
      std::vector<std::string> lines;
      for (std::string line; std::getline(in, line);)
        {
          if (!line.empty() && line.back() == '\r')
            line.pop_back();
          lines.push_back(line);
        }
      const auto tokens = [](const std::string &line) {
        std::vector<std::string> result;
        std::istringstream       text(line);
        for (std::string token; text >> token;)
          result.push_back(token);
        return result;
      };
      for (std::size_t i = 0; i < lines.size(); ++i)
        {
          const std::string section = Utilities::trim(lines[i]);
          if (section != "$Nodes" && section != "$Elements")
            continue;
          const bool        nodes = section == "$Nodes";
          const std::string end   = nodes ? "$EndNodes" : "$EndElements";
          std::size_t       last  = i + 2;
          while (last < lines.size() && Utilities::trim(lines[last]) != end)
            ++last;
          if (last >= lines.size())
            fail(i + 1, section + " has no " + end + ".");
          const std::size_t present = last - (i + 2);
          const auto        count =
            tokens(i + 1 < lines.size() ? lines[i + 1] : std::string());
          long long n = -1;
          if (count.size() != 1 || !parse_integer(count[0], n) || n < 0 ||
              static_cast<std::size_t>(n) != present)
            fail(i + 2,
                 "the number of " + std::string(nodes ? "nodes" : "elements") +
                   " '" + Utilities::trim(lines[i + 1]) + "' after " + section +
                   " is not allowed: it must be a non-negative "
                   "integer equal to the lines up to " +
                   end + " (" + std::to_string(present) + ").");
          for (std::size_t l = i + 2; l < last; ++l)
            {
              const auto t = tokens(lines[l]);
              long long  id;
              if (t.empty() || !parse_integer(t[0], id) || id < 1)
                fail(l + 1,
                     std::string(nodes ? "node" : "element") + " number '" +
                       (t.empty() ? "" : t[0]) +
                       "': allowed are integers >= 1.");
              if (nodes)
                {
                  bool finite = t.size() == 4;
                  for (unsigned int k = 1; finite && k < 4; ++k)
                    {
                      char  *stop = nullptr;
                      double x    = std::strtod(t[k].c_str(), &stop);
                      finite      = *stop == '\0' && std::isfinite(x);
                    }
                  if (!finite)
                    fail(l + 1,
                         "node " + t[0] +
                           ": expected 'number x y z' with finite "
                           "coordinates; got '" +
                           Utilities::trim(lines[l]) + "'.");
                  continue;
                }
              long long type = -1, n_tags = -1;
              if (t.size() < 3 || !parse_integer(t[1], type) || type < 1 ||
                  !parse_integer(t[2], n_tags) || n_tags < 0 || n_tags > 64 ||
                  t.size() < 3 + static_cast<std::size_t>(n_tags) + 1)
                fail(l + 1,
                     "element " + t[0] +
                       ": expected 'number type n_tags tags... nodes' with "
                       "0 <= n_tags <= 64; got '" +
                       Utilities::trim(lines[l]) + "'.");
              for (long long k = 0; k < n_tags && k < 2; ++k)
                {
                  long long tag = -1;
                  if (!parse_integer(t[3 + k], tag) || tag < 0 ||
                      (k == 0 && tag > max_physical_tag) ||
                      (k == 1 && tag > 2147483647LL))
                    fail(l + 1,
                         "element " + t[0] + ": " +
                           (k == 0 ? "physical" : "elementary") + " tag '" +
                           t[3 + k] + "' is not allowed: allowed are 0 ... " +
                           (k == 0 ? std::to_string(max_physical_tag) +
                                       " (it becomes the material id of a "
                                       "cell or the boundary id of a line)" :
                                     std::string("2147483647")) +
                           ".");
                }
              for (std::size_t k = 3 + n_tags; k < t.size(); ++k)
                {
                  long long node = -1;
                  if (!parse_integer(t[k], node) || node < 1)
                    fail(l + 1,
                         "element " + t[0] + ": node number '" + t[k] +
                           "': allowed are the numbers of $Nodes (>= 1).");
                }
            }
          i = last;
        }
    }

    void
    attach_circle_manifold(Triangulation<2> &triangulation,
                           const Point<2>   &center)
    {
      for (const auto &cell : triangulation.active_cell_iterators())
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            face->set_manifold_id(circle_manifold_id);
      triangulation.set_manifold(circle_manifold_id,
                                 SphericalManifold<2>(center));
    }

    /** Mesh/Circular boundaries: the edges of each named boundary id follow
     *  a circle about its centre on refinement (a manifold id of its own
     *  per entry, from 10 on; 1 is the generated meshes' circle). */
    void
    attach_circular_boundaries(const MeshParameters &parameters,
                               Triangulation<2>     &triangulation)
    {
      types::manifold_id manifold = 10;
      for (const auto &[id, centre] : parameters.circular_boundaries)
        {
          double smallest = std::numeric_limits<double>::max(), largest = 0.;
          unsigned int edges = 0;
          for (const auto &cell : triangulation.active_cell_iterators())
            for (const auto &face : cell->face_iterators())
              if (face->at_boundary() && face->boundary_id() == id)
                {
                  face->set_manifold_id(manifold);
                  ++edges;
                  for (unsigned int v = 0; v < 2; ++v)
                    {
                      const double r = face->vertex(v).distance(centre);
                      smallest       = std::min(smallest, r);
                      largest        = std::max(largest, r);
                    }
                }
          const std::string entry = "Mesh/Circular boundaries: boundary id " +
                                    std::to_string(id) + " about (" +
                                    Utilities::to_string(centre[0]) + ", " +
                                    Utilities::to_string(centre[1]) + ")";
          if (edges == 0)
            throw InputError(entry + ": no boundary edge of the mesh file '" +
                             parameters.file_name +
                             "' has this id; allowed are the ids of its "
                             "boundary edges (gmsh Physical Curve tags).");
          if (!(smallest > 0.) || largest > 1.01 * smallest)
            throw InputError(
              entry + ": the " + std::to_string(edges) + " edges' ends lie " +
              Utilities::to_string(smallest) + " to " +
              Utilities::to_string(largest) +
              " m from the centre; allowed are edges on one circle (radii "
              "within 1 %): is the centre right?");
          triangulation.set_manifold(manifold, SphericalManifold<2>(centre));
          ++manifold;
        }
    }
  } // namespace

  template <int dim>
  void
  read_gmsh_file(const std::string  &file_name,
                 Triangulation<dim> &triangulation)
  {
    std::ifstream in(file_name);
    if (!in)
      throw InputError("Mesh/File name: cannot open '" + file_name +
                       "' (missing or unreadable).");
    std::string first_word, version, file_type;
    in >> first_word >> version >> file_type;
    if (first_word != "$MeshFormat")
      throw InputError("Mesh file '" + file_name +
                       "' is not an ASCII gmsh .msh file: it must start with "
                       "$MeshFormat (gmsh -format msh22 or msh4, ASCII).");
    if (file_type != "0")
      throw InputError("Mesh file '" + file_name +
                       "' is a binary gmsh file (file-type " + file_type +
                       "); allowed are ASCII files (gmsh -format msh22).");
    if (version.rfind("4.", 0) == 0)
      {
        // deal.II 9.4's format-4 reader does not check its reads (a bad
        // token corrupts memory): let gmsh check and convert it to 2.2
        const std::string converted =
          (std::filesystem::temp_directory_path() /
           ("tmfdem-msh22-" + std::to_string(::getpid()) + ".msh"))
            .string();
        const std::string command = "timeout 60 gmsh -0 \"" + file_name +
                                    "\" -format msh22 -v 0 -o \"" + converted +
                                    "\" > /dev/null 2>&1";
        std::filesystem::remove(converted);
        const int status = std::system(command.c_str());
        if (status != 0 || !std::filesystem::exists(converted))
          {
            std::filesystem::remove(converted);
            throw InputError(
              "Mesh file '" + file_name + "' (gmsh format " + version +
              ") cannot be read: gmsh rejected it (exit status " +
              std::to_string(status) + ").");
          }
        try
          {
            read_gmsh_file(converted, triangulation);
          }
        catch (const InputError &error)
          {
            std::filesystem::remove(converted);
            throw InputError("Mesh file '" + file_name +
                             "' (converted by gmsh " + "from format " +
                             version + "): " + error.what());
          }
        std::filesystem::remove(converted);
        return;
      }
    if (version.rfind("2.", 0) != 0)
      throw InputError("Mesh file '" + file_name +
                       "' has gmsh format version '" + version +
                       "'; allowed are 2.x and 4.x (ASCII).");
    check_msh2_sections(file_name);
    in.seekg(0);
    GridIn<dim> grid_in;
    grid_in.attach_triangulation(triangulation);
    try
      {
        grid_in.read_msh(in);
      }
    catch (const ExceptionBase &exception)
      {
        std::ostringstream info;
        exception.print_info(info);
        throw InputError("Mesh file '" + file_name +
                         "' cannot be read: " + info.str());
      }
    catch (const std::exception &exception)
      {
        throw InputError("Mesh file '" + file_name +
                         "' cannot be read: " + exception.what());
      }
    if (triangulation.n_active_cells() == 0)
      throw InputError("Mesh file '" + file_name + "' holds no " +
                       std::to_string(dim) + "D cells (are the " +
                       (dim == 2 ? "surfaces" : "volumes") +
                       " in a physical group?).");
  }

  template <int dim>
  void
  read_mesh_file(const MeshParameters &parameters,
                 const std::string    &work_folder,
                 Triangulation<dim>   &triangulation,
                 MPI_Comm              communicator)
  {
    const std::string &name = parameters.file_name;
    if (name.size() > 4 && name.substr(name.size() - 4) == ".geo")
      {
        if (!std::filesystem::exists(name))
          throw InputError("Mesh/File name: cannot open '" + name +
                           "' (missing or unreadable).");
        const std::string msh_file = work_folder + "/mesh.msh";
        run_gmsh("",
                 name,
                 work_folder,
                 msh_file,
                 parameters.gmsh_time_limit,
                 communicator,
                 dim);
        read_gmsh_file(msh_file, triangulation);
      }
    else
      read_gmsh_file(name, triangulation);
  }

  void
  create_coarse_mesh(const MeshParameters &parameters,
                     const std::string    &work_folder,
                     Triangulation<2>     &triangulation,
                     MPI_Comm              communicator)
  {
    using Source = MeshParameters::Source;
    const bool triangles =
      parameters.element_type == MeshParameters::ElementType::triangles;
    const double h = parameters.element_size;
    if (parameters.source != Source::file)
      {
        // refuse absurd sizes before gmsh or GridGenerator try them
        const double area            = domain_area(parameters);
        const double estimated_cells = area / (0.43 * h * h);
        if (!std::isfinite(area) || !(area > 0.) ||
            !std::isfinite(estimated_cells) || estimated_cells > 2e7)
          throw InputError(
            "Mesh: a domain of area " + Utilities::to_string(area) +
            " m^2 with Element size = " + Utilities::to_string(h) +
            " m would have about " + Utilities::to_string(estimated_cells) +
            " cells; allowed are finite domains and at most 2e7 cells (then "
            "Mesh/Global refinements).");
      }

    if (parameters.source == Source::file)
      {
        read_mesh_file(parameters, work_folder, triangulation, communicator);
        attach_circular_boundaries(parameters, triangulation);
        return;
      }

    if (parameters.source == Source::block_heap)
      {
        if (!triangles)
          throw InputError("Mesh/Source = block heap makes triangles only; "
                           "allowed is Mesh/Element type = triangles.");
        const std::string msh_file = work_folder + "/mesh.msh";
        run_gmsh(block_heap_gmsh_script(generate_block_heap(parameters), h),
                 work_folder + "/mesh.geo",
                 work_folder,
                 msh_file,
                 parameters.gmsh_time_limit,
                 communicator);
        read_gmsh_file(msh_file, triangulation);
        return;
      }

    if (triangles)
      {
        const std::string msh_file = work_folder + "/mesh.msh";
        run_gmsh(gmsh_script(parameters),
                 work_folder + "/mesh.geo",
                 work_folder,
                 msh_file,
                 parameters.gmsh_time_limit,
                 communicator);
        read_gmsh_file(msh_file, triangulation);
        for (const auto &cell : triangulation.active_cell_iterators())
          cell->set_material_id(parameters.material_id);
        if (parameters.source != Source::rectangle)
          attach_circle_manifold(triangulation,
                                 MeshParameters::in_dimension<2>(
                                   parameters.center));
        return;
      }

    // structured quadrilaterals, flat (level 0) so that p4est can copy them
    if (parameters.source == Source::rectangle)
      {
        const Tensor<1, 3> extent =
          parameters.upper_right - parameters.lower_left;
        const std::vector<unsigned int> repetitions = {
          std::max(1u,
                   static_cast<unsigned int>(std::ceil(extent[0] / h - 1e-9))),
          std::max(1u,
                   static_cast<unsigned int>(std::ceil(extent[1] / h - 1e-9)))};
        GridGenerator::subdivided_hyper_rectangle(
          triangulation,
          repetitions,
          MeshParameters::in_dimension<2>(parameters.lower_left),
          MeshParameters::in_dimension<2>(parameters.upper_right),
          true);
      }
    else
      {
        const double   a = parameters.inner_radius, b = parameters.outer_radius;
        const Point<2> center =
          MeshParameters::in_dimension<2>(parameters.center);
        if (parameters.source == Source::annulus)
          {
            // one layer of cells of radial width h ... (b-a) each: the
            // shell is built ring by ring so the mesh stays flat
            const unsigned int n_rings =
              std::max(1u,
                       static_cast<unsigned int>(
                         std::ceil((b - a) / h - 1e-9)));
            const unsigned int n_around =
              std::max(8u,
                       4 *
                         static_cast<unsigned int>(std::ceil(
                           2. * numbers::PI * 0.5 * (a + b) / h / 4. - 1e-9)));
            std::vector<Point<2>>    vertices;
            std::vector<CellData<2>> cells;
            for (unsigned int ring = 0; ring <= n_rings; ++ring)
              {
                // uniform, or graded towards the inner circle
                const double p = parameters.radial_grading;
                const double r =
                  p == 1. ?
                    a + (b - a) * ring / n_rings :
                    a + (b - a) *
                          std::pow(static_cast<double>(ring) / n_rings, p);
                for (unsigned int k = 0; k < n_around; ++k)
                  {
                    const double phi = 2. * numbers::PI * k / n_around;
                    vertices.emplace_back(center[0] + r * std::cos(phi),
                                          center[1] + r * std::sin(phi));
                  }
              }
            for (unsigned int ring = 0; ring < n_rings; ++ring)
              for (unsigned int k = 0; k < n_around; ++k)
                {
                  CellData<2>        cell;
                  const unsigned int k1 = (k + 1) % n_around;
                  // local x radial, local y counterclockwise
                  cell.vertices    = {ring * n_around + k,
                                      (ring + 1) * n_around + k,
                                      ring * n_around + k1,
                                      (ring + 1) * n_around + k1};
                  cell.material_id = parameters.material_id;
                  cells.push_back(cell);
                }
            SubCellData boundary;
            for (unsigned int k = 0; k < n_around; ++k)
              {
                CellData<1> inner, outer;
                inner.vertices    = {k, (k + 1) % n_around};
                inner.boundary_id = 0;
                outer.vertices    = {n_rings * n_around + k,
                                     n_rings * n_around + (k + 1) % n_around};
                outer.boundary_id = 1;
                boundary.boundary_lines.push_back(inner);
                boundary.boundary_lines.push_back(outer);
              }
            triangulation.create_triangulation(vertices, cells, boundary);
            // every cell follows the circles: new vertices land on them
            triangulation.set_all_manifold_ids(circle_manifold_id);
            triangulation.set_manifold(circle_manifold_id,
                                       SphericalManifold<2>(center));
          }
        else
          {
            GridGenerator::hyper_ball_balanced(triangulation, center, b);
            // refine, then flatten, so the coarse mesh has size ~h
            unsigned int n = 0;
            while (b / std::pow(2., n + 1) > h * 1.01 && n < 10)
              ++n;
            triangulation.refine_global(n);
            Triangulation<2> flat;
            GridGenerator::flatten_triangulation(triangulation, flat);
            triangulation.clear();
            triangulation.copy_triangulation(flat);
            for (const auto &cell : triangulation.active_cell_iterators())
              for (const auto &face : cell->face_iterators())
                if (face->at_boundary())
                  face->set_manifold_id(circle_manifold_id);
            triangulation.set_manifold(circle_manifold_id,
                                       SphericalManifold<2>(center));
          }
      }
    // (GridGenerator's colorize also numbers the cells' material ids)
    for (const auto &cell : triangulation.active_cell_iterators())
      cell->set_material_id(parameters.material_id);
  }

  void
  create_block_heap_mesh(const MeshParameters &parameters,
                         const std::string    &work_folder,
                         Triangulation<3>     &triangulation,
                         MPI_Comm              communicator)
  {
    if (parameters.element_type != MeshParameters::ElementType::triangles)
      throw InputError("Mesh/Source = block heap makes tetrahedra only; "
                       "allowed is Mesh/Element type = triangles (tetrahedra "
                       "in 3D).");
    const std::string msh_file = work_folder + "/mesh.msh";
    run_gmsh(block_heap_gmsh_script(generate_block_heap_3d(parameters),
                                    parameters.element_size),
             work_folder + "/mesh.geo",
             work_folder,
             msh_file,
             parameters.gmsh_time_limit,
             communicator,
             3);
    read_gmsh_file(msh_file, triangulation);
  }

  double
  domain_area(const MeshParameters &p)
  {
    switch (p.source)
      {
        case MeshParameters::Source::rectangle:
          return (p.upper_right[0] - p.lower_left[0]) *
                 (p.upper_right[1] - p.lower_left[1]);
        case MeshParameters::Source::annulus:
          return numbers::PI * (p.outer_radius * p.outer_radius -
                                p.inner_radius * p.inner_radius);
        case MeshParameters::Source::disc:
          return numbers::PI * p.outer_radius * p.outer_radius;
        case MeshParameters::Source::block_heap:
          return generate_block_heap(p).area();
        default:
          return p.expected_area;
      }
  }

  template <int dim>
  std::unique_ptr<parallel::TriangulationBase<dim>>
  create_continuum_triangulation(const MeshParameters &parameters,
                                 const std::string    &work_folder,
                                 MPI_Comm              communicator,
                                 MeshReport           &report)
  {
    if (parameters.dimension != dim)
      throw std::logic_error(
        "create_continuum_triangulation<" + std::to_string(dim) +
        "> for Mesh/Dimension = " + std::to_string(parameters.dimension));
    Triangulation<dim> coarse;
    create_coarse_mesh(parameters, work_folder, coarse, communicator);
    const std::string source =
      parameters.source == MeshParameters::Source::file ?
        "mesh file '" + parameters.file_name + "'" :
        "generated mesh";
    const bool curved =
      parameters.source == MeshParameters::Source::annulus ||
      parameters.source == MeshParameters::Source::disc ||
      parameters.source == MeshParameters::Source::ball ||
      parameters.source == MeshParameters::Source::spherical_shell ||
      parameters.source == MeshParameters::Source::cylinder ||
      parameters.source == MeshParameters::Source::hollow_cylinder;
    report =
      check_mesh(coarse,
                 source,
                 dim == 2 ? domain_area(parameters) : domain_volume(parameters),
                 curved);
    const unsigned int n_simplices =
      dim == 2 ? report.n_triangles : report.n_tetrahedra;
    const unsigned int n_hypercubes =
      dim == 2 ? report.n_quadrilaterals : report.n_hexahedra;
    if (n_simplices > 0 && n_hypercubes > 0)
      throw InputError(source + " mixes " +
                       (dim == 2 ? "triangles and quadrilaterals" :
                                   "tetrahedra and hexahedra") +
                       "; allowed are meshes of one cell shape.");
    std::unique_ptr<parallel::TriangulationBase<dim>> triangulation;
    if (n_hypercubes > 0)
      triangulation =
        std::make_unique<parallel::distributed::Triangulation<dim>>(
          communicator,
          typename Triangulation<dim>::MeshSmoothing(
            Triangulation<dim>::smoothing_on_refinement |
            Triangulation<dim>::smoothing_on_coarsening));
    else
      triangulation =
        std::make_unique<parallel::shared::Triangulation<dim>>(communicator);
    triangulation->copy_triangulation(coarse);
    triangulation->refine_global(parameters.global_refinements);
    return triangulation;
  }

  template void
  read_mesh_file<2>(const MeshParameters &,
                    const std::string &,
                    Triangulation<2> &,
                    MPI_Comm);
  template void
  read_mesh_file<3>(const MeshParameters &,
                    const std::string &,
                    Triangulation<3> &,
                    MPI_Comm);
  template void
  read_gmsh_file<2>(const std::string &, Triangulation<2> &);
  template void
  read_gmsh_file<3>(const std::string &, Triangulation<3> &);
  template std::unique_ptr<parallel::TriangulationBase<2>>
  create_continuum_triangulation<2>(const MeshParameters &,
                                    const std::string &,
                                    MPI_Comm,
                                    MeshReport &);
  template std::unique_ptr<parallel::TriangulationBase<3>>
  create_continuum_triangulation<3>(const MeshParameters &,
                                    const std::string &,
                                    MPI_Comm,
                                    MeshReport &);
} // namespace tmfdem
