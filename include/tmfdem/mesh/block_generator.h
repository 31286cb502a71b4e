/**
 * @file
 * A seeded generator of block heaps (paper Sec. 5.2): a container (base
 * plate and two side walls) and convex polygonal blocks, the cells of a
 * Voronoi tessellation about random points of a region above the base, each
 * cell shrunk to leave a clear gap, written as a gmsh .geo script with
 * physical groups (blocks material id 1, container material id 2; boundary
 * ids 1 base, 2 side walls, 0 block faces).
 */
#ifndef tmfdem_mesh_block_generator_h
#define tmfdem_mesh_block_generator_h

#include <deal.II/base/point.h>

#include <array>
#include <string>
#include <tmfdem/base/parameters.h>
#include <vector>

namespace tmfdem
{
  /** A convex polygon, vertices counter-clockwise [m]. */
  using Polygon = std::vector<Point<2>>;

  /** The generated geometry. */
  struct BlockHeapGeometry
  {
    /** The blocks (material id 1). */
    std::vector<Polygon> blocks;
    /** Base plate, left wall, right wall (material id 2). */
    std::array<Polygon, 3> container;

    /** Total area of blocks and container [m^2]. */
    double
    area() const;
  };

  /** Material id of the blocks. */
  constexpr unsigned int block_heap_block_material = 1;
  /** Material id of the container (base plate and walls). */
  constexpr unsigned int block_heap_container_material = 2;
  /** Boundary id of the base plate (the heater). */
  constexpr unsigned int block_heap_base_boundary = 1;
  /** Boundary id of the side walls. */
  constexpr unsigned int block_heap_wall_boundary = 2;

  /**
   * Throws InputError naming the entry if the `Mesh/Block heap` entries of
   * @p parameters cannot make a heap: the blocks' region (height
   * N s^2 / W above Drop height) must fit under the walls, the gap must be
   * smaller than a fifth of the mean size, the element size at most half
   * of it.
   */
  void
  check_block_heap_parameters(const MeshParameters &parameters);

  /**
   * The heap of @p parameters (Source = block heap): deterministic for a
   * given seed (std::mt19937 with its standard output sequence, no library
   * distributions). Block edges shorter than half the element size are
   * removed (the polygon stays convex and inside its cell).
   */
  BlockHeapGeometry
  generate_block_heap(const MeshParameters &parameters);

  /** The gmsh .geo script meshing @p geometry with element size @p h. */
  std::string
  block_heap_gmsh_script(const BlockHeapGeometry &geometry, const double h);
} // namespace tmfdem

#endif
