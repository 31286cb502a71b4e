#include <deal.II/base/utilities.h>
#include <deal.II/grid/manifold.h>
#include <deal.II/grid/reference_cell.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <memory>
#include <numeric>
#include <set>
#include <tmfdem/mesh/cell_order.h>
#include <utility>

namespace tmfdem
{
  namespace
  {
    /** A face or edge (@p object: dim_object-dimensional, at the boundary or
     *  with a curved manifold) as the SubCellData entry that
     *  create_triangulation() takes, its vertices renumbered by
     *  @p new_vertex. */
    template <int dim_object, typename Iterator>
    CellData<dim_object>
    sub_cell(const Iterator                  &object,
             const bool                       at_boundary,
             const std::vector<unsigned int> &new_vertex)
    {
      CellData<dim_object> data(object->n_vertices());
      for (unsigned int k = 0; k < object->n_vertices(); ++k)
        data.vertices[k] = new_vertex[object->vertex_index(k)];
      data.boundary_id = at_boundary ? object->boundary_id() :
                                       numbers::internal_face_boundary_id;
      data.manifold_id = object->manifold_id();
      return data;
    }
  } // namespace

  template <int dim>
  std::vector<unsigned int>
  order_cells_along_hilbert_curve(Triangulation<dim> &triangulation)
  {
    const unsigned int        n_cells = triangulation.n_active_cells();
    std::vector<unsigned int> previous(n_cells);
    std::iota(previous.begin(), previous.end(), 0u);
    if (n_cells < 2)
      return previous;

    // the cells as a flat description, in the previous order
    const std::vector<Point<dim>> &vertices = triangulation.get_vertices();
    const std::vector<bool>       &used     = triangulation.get_used_vertices();
    std::vector<unsigned int>      new_vertex(vertices.size(),
                                         numbers::invalid_unsigned_int);
    std::vector<Point<dim>>        kept_vertices;
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (used[v])
        {
          new_vertex[v] = kept_vertices.size();
          kept_vertices.push_back(vertices[v]);
        }
    constexpr unsigned int     n_corners = dim + 1;
    std::vector<CellData<dim>> cells(n_cells, CellData<dim>(n_corners));
    std::vector<Point<dim>>    centroids(n_cells);
    SubCellData                sub_cells;
    std::set<unsigned int>     faces_seen, lines_seen;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        const unsigned int c = cell->active_cell_index();
        AssertThrow(cell->reference_cell() ==
                      ReferenceCells::get_simplex<dim>(),
                    ExcMessage("order_cells_along_hilbert_curve: cell " +
                               std::to_string(c) + " is not a " +
                               (dim == 2 ? "triangle." : "tetrahedron.")));
        Point<dim> centroid;
        for (unsigned int k = 0; k < n_corners; ++k)
          {
            cells[c].vertices[k] = new_vertex[cell->vertex_index(k)];
            centroid += cell->vertex(k);
          }
        centroids[c]         = centroid / double(n_corners);
        cells[c].material_id = cell->material_id();
        cells[c].manifold_id = cell->manifold_id();
        // the faces that carry a boundary id or a curved manifold, and in
        // 3D the edges that do
        for (const auto &face : cell->face_iterators())
          if ((face->at_boundary() ||
               face->manifold_id() != numbers::flat_manifold_id) &&
              faces_seen.insert(face->index()).second)
            {
              if constexpr (dim == 2)
                sub_cells.boundary_lines.push_back(
                  sub_cell<1>(face, face->at_boundary(), new_vertex));
              else
                sub_cells.boundary_quads.push_back(
                  sub_cell<2>(face, face->at_boundary(), new_vertex));
            }
        if constexpr (dim == 3)
          for (unsigned int l = 0; l < cell->n_lines(); ++l)
            {
              const auto line = cell->line(l);
              if ((line->at_boundary() ||
                   line->manifold_id() != numbers::flat_manifold_id) &&
                  lines_seen.insert(line->index()).second)
                sub_cells.boundary_lines.push_back(
                  sub_cell<1>(line, line->at_boundary(), new_vertex));
            }
      }

    // the Hilbert curve through the centroids; ties keep the previous order
    const auto keys =
      Utilities::inverse_Hilbert_space_filling_curve(centroids, 30);
    std::stable_sort(previous.begin(),
                     previous.end(),
                     [&keys](const unsigned int a, const unsigned int b) {
                       return std::lexicographical_compare(keys[a].begin(),
                                                           keys[a].end(),
                                                           keys[b].begin(),
                                                           keys[b].end());
                     });
    std::vector<CellData<dim>> ordered(n_cells);
    for (unsigned int c = 0; c < n_cells; ++c)
      ordered[c] = cells[previous[c]];

    // rebuild, keeping the manifolds
    std::vector<std::pair<types::manifold_id, std::unique_ptr<Manifold<dim>>>>
      manifolds;
    for (const auto id : triangulation.get_manifold_ids())
      if (id != numbers::flat_manifold_id)
        manifolds.emplace_back(id, triangulation.get_manifold(id).clone());
    triangulation.clear();
    triangulation.create_triangulation(kept_vertices, ordered, sub_cells);
    for (const auto &[id, manifold] : manifolds)
      triangulation.set_manifold(id, *manifold);
    return previous;
  }

  template std::vector<unsigned int>
  order_cells_along_hilbert_curve(Triangulation<2> &);
  template std::vector<unsigned int>
  order_cells_along_hilbert_curve(Triangulation<3> &);
} // namespace tmfdem
