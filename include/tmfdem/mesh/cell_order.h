/**
 * @file
 * The order of a triangulation's cells: the discrete layer numbers its
 * triangles (tetrahedra in 3D) along a Hilbert curve through their centroids,
 * so that a range of triangle indices is a compact region. A rank of the
 * discrete layer owns such a range (discrete/partition.h): its halo, and the
 * ghosts it receives every step, grow with the region's perimeter, not with how
 * the mesh generator happened to number the cells; and triangles near in space
 * are near in memory.
 */
#ifndef tmfdem_mesh_cell_order_h
#define tmfdem_mesh_cell_order_h

#include <deal.II/grid/tria.h>

#include <vector>

namespace tmfdem
{
  using namespace dealii;

  /**
   * Rebuilds the serial @p triangulation of triangles or tetrahedra (active
   * cells only, no hierarchy)
   * with its cells in the order of their centroids along a Hilbert curve
   * (deal.II's Utilities::inverse_Hilbert_space_filling_curve over the
   * centroids' bounding box, 30 bits per coordinate; ties by the previous
   * order). Each cell keeps its vertices in their order, its material and
   * manifold id; boundary faces (and in 3D boundary edges) keep their
   * boundary and manifold ids, and so do interior ones on a curved
   * manifold; the manifolds stay attached. Vertices used by no cell are
   * dropped.
   *
   * Returns, for each cell of the new order, its previous active cell index.
   */
  template <int dim>
  std::vector<unsigned int>
  order_cells_along_hilbert_curve(Triangulation<dim> &triangulation);
} // namespace tmfdem

#endif
