#include <deal.II/base/utilities.h>
#include <deal.II/grid/grid_tools.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/mesh/mesh_checks.h>

namespace tmfdem
{
  namespace
  {
    double
    cross(const Tensor<1, 2> &a, const Tensor<1, 2> &b)
    {
      return a[0] * b[1] - a[1] * b[0];
    }

    template <int dim>
    std::string
    describe_cell(const typename Triangulation<dim>::cell_iterator &cell)
    {
      std::ostringstream text;
      text << "cell " << cell->index() << " (vertices";
      for (const unsigned int v : cell->vertex_indices())
        text << " " << cell->vertex_index(v) << " (" << cell->vertex(v) << ")";
      text << ")";
      return text.str();
    }

    /** Number of connected pieces of @p triangulation (cells joined
     *  through faces). */
    template <int dim>
    unsigned int
    count_connected_pieces(const Triangulation<dim> &triangulation)
    {
      unsigned int              n_pieces = 0;
      std::vector<unsigned int> piece(triangulation.n_active_cells(),
                                      numbers::invalid_unsigned_int);
      for (const auto &seed : triangulation.active_cell_iterators())
        if (piece[seed->active_cell_index()] == numbers::invalid_unsigned_int)
          {
            std::vector<typename Triangulation<dim>::active_cell_iterator>
              stack                          = {seed};
            piece[seed->active_cell_index()] = n_pieces;
            while (!stack.empty())
              {
                const auto cell = stack.back();
                stack.pop_back();
                for (const unsigned int f : cell->face_indices())
                  if (!cell->at_boundary(f) && cell->neighbor(f)->is_active())
                    {
                      const auto neighbor = cell->neighbor(f);
                      if (piece[neighbor->active_cell_index()] ==
                          numbers::invalid_unsigned_int)
                        {
                          piece[neighbor->active_cell_index()] = n_pieces;
                          stack.push_back(neighbor);
                        }
                    }
              }
            ++n_pieces;
          }
      return n_pieces;
    }

    /** Refuses @p cell when a cell in @p cells_by_vertices has the same
     *  vertices; records it otherwise. */
    template <int dim>
    void
    refuse_duplicate(
      const typename Triangulation<dim>::active_cell_iterator &cell,
      std::map<std::vector<unsigned int>, unsigned int> &cells_by_vertices,
      const std::string                                 &source)
    {
      std::vector<unsigned int> key;
      for (const unsigned int v : cell->vertex_indices())
        key.push_back(cell->vertex_index(v));
      std::sort(key.begin(), key.end());
      const auto inserted = cells_by_vertices.emplace(key, cell->index());
      if (!inserted.second)
        throw InputError(source + ": " + describe_cell<dim>(cell) +
                         " duplicates cell " +
                         std::to_string(inserted.first->second) +
                         " (same vertices). Allowed are meshes whose cells "
                         "overlap nowhere.");
    }
  } // namespace

  std::string
  MeshReport::to_string() const
  {
    std::ostringstream text;
    if (dimension == 3)
      text << "mesh: " << n_cells << " cells (" << n_tetrahedra
           << " tetrahedra, " << n_hexahedra << " hexahedra), " << n_vertices
           << " vertices, " << n_connected_pieces << " connected piece(s)\n"
           << "  volume " << area << " m^3, edge length min " << min_edge;
    else
      text << "mesh: " << n_cells << " cells (" << n_triangles << " triangles, "
           << n_quadrilaterals << " quadrilaterals), " << n_vertices
           << " vertices, " << n_connected_pieces << " connected piece(s)\n"
           << "  area " << area << " m^2, edge length min " << min_edge;
    text << " mean " << mean_edge << " max " << max_edge << " m\n"
         << "  boundary ids:";
    for (const auto id : boundary_ids)
      text << " " << id;
    text << "\n  material ids:";
    for (const auto id : material_ids)
      text << " " << static_cast<unsigned int>(id);
    text << "\n";
    return text.str();
  }

  MeshReport
  check_mesh(const Triangulation<2> &triangulation,
             const std::string      &source,
             const double            expected_area,
             const bool              curved_boundary)
  {
    MeshReport report;
    report.n_cells        = triangulation.n_active_cells();
    report.n_vertices     = triangulation.n_used_vertices();
    report.min_edge       = std::numeric_limits<double>::max();
    double       edge_sum = 0;
    unsigned int n_edges  = 0;

    std::map<std::vector<unsigned int>, unsigned int> cells_by_vertices;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        report.material_ids.insert(cell->material_id());
        double longest = 0;
        for (const auto &face : cell->face_iterators())
          {
            const double length = (face->vertex(1) - face->vertex(0)).norm();
            longest             = std::max(longest, length);
            report.min_edge     = std::min(report.min_edge, length);
            report.max_edge     = std::max(report.max_edge, length);
            edge_sum += length;
            ++n_edges;
            if (face->at_boundary())
              report.boundary_ids.insert(face->boundary_id());
          }

        // signed area at each corner: with deal.II's vertex numbering all
        // corner Jacobians of a valid cell are positive
        double min_jacobian = std::numeric_limits<double>::max();
        double area         = 0;
        if (cell->reference_cell() == ReferenceCells::Triangle)
          {
            ++report.n_triangles;
            area         = 0.5 * cross(cell->vertex(1) - cell->vertex(0),
                               cell->vertex(2) - cell->vertex(0));
            min_jacobian = 2. * area;
          }
        else
          {
            ++report.n_quadrilaterals;
            // lexicographic quad: 0 (0,0), 1 (1,0), 2 (0,1), 3 (1,1)
            const unsigned int neighbours[4][2] = {{1, 2},
                                                   {3, 0},
                                                   {0, 3},
                                                   {2, 1}};
            for (unsigned int v = 0; v < 4; ++v)
              min_jacobian =
                std::min(min_jacobian,
                         cross(cell->vertex(neighbours[v][0]) - cell->vertex(v),
                               cell->vertex(neighbours[v][1]) -
                                 cell->vertex(v)));
            area = 0.5 * (cross(cell->vertex(1) - cell->vertex(0),
                                cell->vertex(3) - cell->vertex(0)) +
                          cross(cell->vertex(3) - cell->vertex(0),
                                cell->vertex(2) - cell->vertex(0)));
          }
        if (std::abs(min_jacobian) <= 1e-10 * longest * longest)
          throw InputError(source + ": degenerate " + describe_cell<2>(cell) +
                           ": its area is zero or nearly so. Allowed are "
                           "cells with a positive area.");
        if (min_jacobian < 0)
          throw InputError(source + ": inverted " + describe_cell<2>(cell) +
                           ": negative Jacobian (vertices in clockwise "
                           "order, or a non-convex quadrilateral).");
        report.area += area;

        refuse_duplicate<2>(cell, cells_by_vertices, source);
      }
    report.mean_edge = n_edges > 0 ? edge_sum / n_edges : 0.;

    // The boundary encloses (outer boundaries counterclockwise, holes
    // clockwise) exactly the area of the cells unless cells fold over or
    // overlap: deal.II silently reorders clockwise cells, so a folded
    // (inverted) cell shows up here.
    double enclosed_area = 0.;
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          {
            Point<2> start = face->vertex(0), end = face->vertex(1);
            if (cross(end - start, cell->center() - start) < 0)
              std::swap(start, end);
            enclosed_area += 0.5 * (start[0] * end[1] - start[1] * end[0]);
          }
    if (std::abs(enclosed_area - report.area) > 1e-9 * report.area)
      throw InputError(source + ": the cells cover " +
                       Utilities::to_string(report.area) +
                       " m^2 but the boundary encloses " +
                       Utilities::to_string(enclosed_area) +
                       " m^2: some cells are inverted (folded over their "
                       "neighbours) or overlap. Allowed are meshes whose "
                       "cells overlap nowhere.");

    // connected pieces through shared faces
    report.n_connected_pieces = count_connected_pieces(triangulation);

    if (expected_area > 0)
      {
        // a polygon of edge h inscribed in a circle misses about pi h^2 / 6
        // of its area, whatever the radius; more than that (and 2 %) is a
        // hole or an overlap. Straight boundaries must match to 0.1 %.
        const double miss = std::abs(report.area - expected_area);
        const double tolerance =
          curved_boundary ?
            0.02 * expected_area + 2. * report.max_edge * report.max_edge :
            1e-3 * expected_area;
        if (miss > tolerance)
          throw InputError(
            source + ": the cells cover " + Utilities::to_string(report.area) +
            " m^2 of a domain of " + Utilities::to_string(expected_area) +
            " m^2: part of the domain is not meshed (or cells "
            "overlap).");
      }
    return report;
  }
  MeshReport
  check_mesh(const Triangulation<3> &triangulation,
             const std::string      &source,
             const double            expected_volume,
             const bool              curved_boundary)
  {
    MeshReport report;
    report.dimension      = 3;
    report.n_cells        = triangulation.n_active_cells();
    report.n_vertices     = triangulation.n_used_vertices();
    report.min_edge       = std::numeric_limits<double>::max();
    double       edge_sum = 0, boundary_area = 0;
    unsigned int n_edges = 0;

    std::map<std::vector<unsigned int>, unsigned int> cells_by_vertices;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        report.material_ids.insert(cell->material_id());
        double longest = 0;
        for (unsigned int l = 0; l < cell->n_lines(); ++l)
          {
            const auto   line   = cell->line(l);
            const double length = (line->vertex(1) - line->vertex(0)).norm();
            longest             = std::max(longest, length);
            report.min_edge     = std::min(report.min_edge, length);
            report.max_edge     = std::max(report.max_edge, length);
            edge_sum += length;
            ++n_edges;
          }
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              report.boundary_ids.insert(face->boundary_id());
              boundary_area += face->measure();
            }

        // the smallest Jacobian determinant at a vertex, and the volume
        double min_jacobian = std::numeric_limits<double>::max();
        double volume       = 0;
        if (cell->reference_cell() == ReferenceCells::Tetrahedron)
          {
            ++report.n_tetrahedra;
            Tensor<2, 3> edges;
            for (unsigned int d = 0; d < 3; ++d)
              edges[d] = cell->vertex(d + 1) - cell->vertex(0);
            min_jacobian = determinant(edges);
            volume       = min_jacobian / 6.;
          }
        else if (cell->reference_cell() == ReferenceCells::Hexahedron)
          {
            ++report.n_hexahedra;
            // vertex v = i + 2 j + 4 k: its neighbours along the three
            // reference directions are v ^ 1, v ^ 2, v ^ 4
            for (unsigned int v = 0; v < 8; ++v)
              {
                Tensor<2, 3> edges;
                double       sign = 1.;
                for (unsigned int d = 0; d < 3; ++d)
                  {
                    edges[d] = cell->vertex(v ^ (1u << d)) - cell->vertex(v);
                    if (v & (1u << d))
                      sign = -sign;
                  }
                min_jacobian =
                  std::min(min_jacobian, sign * determinant(edges));
              }
            volume = cell->measure();
          }
        else
          throw InputError(source + ": " + describe_cell<3>(cell) +
                           " is neither a tetrahedron nor a hexahedron; "
                           "allowed in 3D are these two.");
        if (std::abs(min_jacobian) <= 1e-10 * longest * longest * longest)
          throw InputError(source + ": degenerate " + describe_cell<3>(cell) +
                           ": its volume is zero or nearly so. Allowed are "
                           "cells with a positive volume.");
        if (min_jacobian < 0)
          throw InputError(source + ": inverted " + describe_cell<3>(cell) +
                           ": negative Jacobian (vertices in the wrong "
                           "order, or a non-convex hexahedron).");
        report.area += volume;

        refuse_duplicate<3>(cell, cells_by_vertices, source);
      }
    report.mean_edge          = n_edges > 0 ? edge_sum / n_edges : 0.;
    report.n_connected_pieces = count_connected_pieces(triangulation);

    if (expected_volume > 0)
      {
        const double miss = std::abs(report.area - expected_volume);
        // a curved surface cut by flat faces: at most a layer of the
        // longest edge's thickness over the surface
        const double tolerance =
          curved_boundary ?
            0.02 * expected_volume + boundary_area * report.max_edge :
            1e-3 * expected_volume;
        if (miss > tolerance)
          throw InputError(
            source + ": the cells cover " + Utilities::to_string(report.area) +
            " m^3 of a domain of " + Utilities::to_string(expected_volume) +
            " m^3: part of the domain is not meshed (or cells overlap).");
      }
    return report;
  }
} // namespace tmfdem
