/**
 * @file
 * A seeded generator of block heaps (paper Sec. 5.2): a container (base
 * plate and two side walls; in 3D four) and convex polygonal (3D:
 * polyhedral) blocks, the cells of a Voronoi tessellation about random points
 * of a region above the base, each cell shrunk to leave a clear gap, written
 * as a gmsh .geo script with physical groups (blocks material id 1, container
 * material id 2; boundary ids 1 base, 2 side walls, 0 block faces).
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

  /** A convex polyhedron: its vertices [m] and its faces, each a list of
   *  vertex indices counter-clockwise seen from outside. */
  struct Polyhedron
  {
    std::vector<Point<3>>                  vertices;
    std::vector<std::vector<unsigned int>> faces;

    /** Volume [m^3]. */
    double
    volume() const;
    /** Length of the shortest edge [m]. */
    double
    shortest_edge() const;
  };

  /**
   * The convex hull of @p points as a Polyhedron (faces of any number of
   * vertices; points inside the hull or on its edges are left out).
   * Brute force over the triples of points, meant for the few tens of
   * vertices of a block. Throws RunError if the points span no volume.
   */
  Polyhedron
  convex_hull(const std::vector<Point<3>> &points);

  /** The generated geometry in 3D. */
  struct BlockHeapGeometry3D
  {
    /** The blocks (material id 1). */
    std::vector<Polyhedron> blocks;
    /** The Voronoi seed of each block [m]: blocks i and j lie on either
     *  side of their seeds' bisector, Gap / 2 from it. */
    std::vector<Point<3>> seeds;
    /** Base plate, walls at x = 0 and x = W, walls at y = 0 and y = W
     *  (material id 2). */
    std::array<Polyhedron, 5> container;

    /** Total volume of blocks and container [m^3]. */
    double
    volume() const;
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
   * N s^2 / W above Drop height; 3D: N s^3 / W^2) must fit under the walls,
   * the gap must be smaller than a fifth of the mean size, the element size
   * at most half of it.
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

  /**
   * The heap of @p parameters in 3D (Source = block heap, Dimension = 3):
   * the Voronoi cells of seeds in 0 < x, y < W, Drop height < z < Drop
   * height + N s^3 / W^2, each face moved by Gap / 2 towards its seed; a
   * base plate under z = 0 and four walls standing Gap / 2 above it. Block
   * edges shorter than the element size are removed by dropping one of
   * their vertices (the block stays convex and inside its cell; shorter
   * edges would leave slivers that set the explicit step).
   * Deterministic for a given seed.
   */
  BlockHeapGeometry3D
  generate_block_heap_3d(const MeshParameters &parameters);

  /** The gmsh .geo script meshing @p geometry with element size @p h. */
  std::string
  block_heap_gmsh_script(const BlockHeapGeometry &geometry, const double h);

  /** The gmsh .geo script meshing @p geometry with tetrahedra of size @p h
   *  (the container's boxes structured, at most 2 h). */
  std::string
  block_heap_gmsh_script(const BlockHeapGeometry3D &geometry, const double h);
} // namespace tmfdem

#endif
