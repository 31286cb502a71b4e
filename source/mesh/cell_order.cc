#include <deal.II/base/utilities.h>
#include <deal.II/grid/manifold.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <memory>
#include <numeric>
#include <set>
#include <tmfdem/mesh/cell_order.h>
#include <utility>

namespace tmfdem
{
  std::vector<unsigned int>
  order_cells_along_hilbert_curve(Triangulation<2> &triangulation)
  {
    const unsigned int        n_cells = triangulation.n_active_cells();
    std::vector<unsigned int> previous(n_cells);
    std::iota(previous.begin(), previous.end(), 0u);
    if (n_cells < 2)
      return previous;

    // the cells as a flat description, in the previous order
    const std::vector<Point<2>> &vertices = triangulation.get_vertices();
    const std::vector<bool>     &used     = triangulation.get_used_vertices();
    std::vector<unsigned int>    new_vertex(vertices.size(),
                                         numbers::invalid_unsigned_int);
    std::vector<Point<2>>        kept_vertices;
    for (unsigned int v = 0; v < vertices.size(); ++v)
      if (used[v])
        {
          new_vertex[v] = kept_vertices.size();
          kept_vertices.push_back(vertices[v]);
        }
    std::vector<CellData<2>> cells(n_cells, CellData<2>(3));
    std::vector<Point<2>>    centroids(n_cells);
    SubCellData              edges;
    std::set<unsigned int>   edges_seen;
    for (const auto &cell : triangulation.active_cell_iterators())
      {
        const unsigned int c = cell->active_cell_index();
        AssertThrow(cell->n_vertices() == 3,
                    ExcMessage("order_cells_along_hilbert_curve: cell " +
                               std::to_string(c) + " is not a triangle."));
        Point<2> centroid;
        for (unsigned int k = 0; k < 3; ++k)
          {
            cells[c].vertices[k] = new_vertex[cell->vertex_index(k)];
            centroid += cell->vertex(k);
          }
        centroids[c]         = centroid / 3.;
        cells[c].material_id = cell->material_id();
        cells[c].manifold_id = cell->manifold_id();
        for (const auto &face : cell->face_iterators())
          if ((face->at_boundary() ||
               face->manifold_id() != numbers::flat_manifold_id) &&
              edges_seen.insert(face->index()).second)
            {
              CellData<1> edge(2);
              edge.vertices[0] = new_vertex[face->vertex_index(0)];
              edge.vertices[1] = new_vertex[face->vertex_index(1)];
              edge.boundary_id = face->at_boundary() ?
                                   face->boundary_id() :
                                   numbers::internal_face_boundary_id;
              edge.manifold_id = face->manifold_id();
              edges.boundary_lines.push_back(edge);
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
    std::vector<CellData<2>> ordered(n_cells);
    for (unsigned int c = 0; c < n_cells; ++c)
      ordered[c] = cells[previous[c]];

    // rebuild, keeping the manifolds
    std::vector<std::pair<types::manifold_id, std::unique_ptr<Manifold<2>>>>
      manifolds;
    for (const auto id : triangulation.get_manifold_ids())
      if (id != numbers::flat_manifold_id)
        manifolds.emplace_back(id, triangulation.get_manifold(id).clone());
    triangulation.clear();
    triangulation.create_triangulation(kept_vertices, ordered, edges);
    for (const auto &[id, manifold] : manifolds)
      triangulation.set_manifold(id, *manifold);
    return previous;
  }
} // namespace tmfdem
