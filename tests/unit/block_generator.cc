// The block heap generator in 3D (mesh/block_generator.h): the convex hull
// of a small point set, and the heap's blocks: convex, disjoint with the
// requested gap between every two of them, inside the container, none with
// an edge shorter than the element size, the same for the same seed.

#include <gtest/gtest.h>
#include <random>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/base/parameters.h>
#include <tmfdem/mesh/block_generator.h>

using namespace dealii;
using namespace tmfdem;

namespace
{
  /** The Mesh entries of a 3D heap: 20 blocks of 0.07 m in a 0.3 m box. */
  MeshParameters
  heap_parameters(const unsigned int seed)
  {
    MeshParameters p;
    p.dimension                   = 3;
    p.source                      = MeshParameters::Source::block_heap;
    p.element_size                = 0.035;
    p.block_heap.container_width  = 0.3;
    p.block_heap.container_height = 0.35;
    p.block_heap.wall_thickness   = 0.03;
    p.block_heap.n_blocks         = 20;
    p.block_heap.mean_size        = 0.07;
    p.block_heap.gap              = 0.005;
    p.block_heap.drop_height      = 0.02;
    p.block_heap.seed             = seed;
    return p;
  }

  /** The gap between blocks @p a and @p b of @p heap along their seeds'
   *  bisector: the construction's guarantee [m]. */
  double
  separation(const BlockHeapGeometry3D &heap,
             const unsigned int         a,
             const unsigned int         b)
  {
    const Tensor<1, 3> d = heap.seeds[b] - heap.seeds[a];
    const Tensor<1, 3> n = d / d.norm();
    const Point<3>     mid(heap.seeds[a] + 0.5 * d);
    double             a_far = -std::numeric_limits<double>::max(),
           b_near            = std::numeric_limits<double>::max();
    for (const auto &v : heap.blocks[a].vertices)
      a_far = std::max(a_far, n * (v - mid));
    for (const auto &v : heap.blocks[b].vertices)
      b_near = std::min(b_near, n * (v - mid));
    return b_near - a_far;
  }
} // namespace

TEST(BlockHeap3D, HullOfACubeWithInnerAndEdgePoints)
{
  std::vector<Point<3>> points;
  for (unsigned int k = 0; k < 8; ++k)
    points.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  points.emplace_back(0.5, 0.5, 0.5); // inside
  points.emplace_back(0.5, 0., 0.);   // on an edge
  points.emplace_back(0.5, 0.5, 0.);  // on a face
  points.emplace_back(1., 1., 1.);    // a duplicate
  const Polyhedron hull = convex_hull(points);
  EXPECT_EQ(hull.vertices.size(), 8u);
  ASSERT_EQ(hull.faces.size(), 6u);
  for (const auto &face : hull.faces)
    EXPECT_EQ(face.size(), 4u);
  EXPECT_NEAR(hull.volume(), 1., 1e-14); // > 0: faces counter-clockwise
  EXPECT_NEAR(hull.shortest_edge(), 1., 1e-14);
  EXPECT_THROW(convex_hull({Point<3>(0, 0, 0),
                            Point<3>(1, 0, 0),
                            Point<3>(0, 1, 0),
                            Point<3>(1, 1, 0)}),
               RunError);
}

TEST(BlockHeap3D, HullOfPointsOnASphere)
{
  // 200 random points on the unit sphere, all of them corners: the hull is
  // convex with every point on or behind every face, triangulated (Euler:
  // V - E + F = 2) and inscribed (volume below 4 pi / 3)
  std::mt19937                     engine(3);
  std::normal_distribution<double> normal;
  std::vector<Point<3>>            points;
  for (unsigned int i = 0; i < 200; ++i)
    {
      Tensor<1, 3> r({normal(engine), normal(engine), normal(engine)});
      points.emplace_back(r / r.norm());
    }
  const Polyhedron hull = convex_hull(points);
  EXPECT_EQ(hull.vertices.size(), 200u);
  unsigned int edges = 0;
  for (const auto &face : hull.faces)
    {
      EXPECT_EQ(face.size(), 3u);
      edges += face.size();
      const Point<3>    &p0 = hull.vertices[face[0]];
      const Tensor<1, 3> n  = cross_product_3d(hull.vertices[face[1]] - p0,
                                              hull.vertices[face[2]] - p0);
      for (const auto &p : points)
        EXPECT_LE(n * (p - p0) / n.norm(), 1e-12);
    }
  EXPECT_EQ(hull.vertices.size() - edges / 2 + hull.faces.size(), 2u);
  EXPECT_GT(hull.volume(), 0.);
  EXPECT_LT(hull.volume(), 4. / 3. * numbers::PI);
}

TEST(BlockHeap3D, BlocksAreDisjointInsideAndReproducible)
{
  const MeshParameters      p    = heap_parameters(1);
  const BlockHeapGeometry3D heap = generate_block_heap_3d(p);
  ASSERT_EQ(heap.blocks.size(), 20u);
  const double W = 0.3, g = 0.005, z0 = 0.02,
               z1     = z0 + 20 * std::pow(0.07, 3) / (W * W);
  double block_volume = 0.;
  for (unsigned int i = 0; i < heap.blocks.size(); ++i)
    {
      const Polyhedron &block = heap.blocks[i];
      block_volume += block.volume();
      EXPECT_GE(block.shortest_edge(), p.element_size) << "block " << i;
      EXPECT_GT(block.volume(), 1e-3 * std::pow(0.07, 3)) << "block " << i;
      for (const auto &v : block.vertices)
        {
          EXPECT_GE(v[0], 0.5 * g - 1e-12);
          EXPECT_LE(v[0], W - 0.5 * g + 1e-12);
          EXPECT_GE(v[1], 0.5 * g - 1e-12);
          EXPECT_LE(v[1], W - 0.5 * g + 1e-12);
          EXPECT_GE(v[2], z0 - 1e-12);
          EXPECT_LE(v[2], z1 + 1e-12);
        }
      // convex: every vertex behind every face
      for (const auto &face : block.faces)
        {
          const Point<3>    &p0 = block.vertices[face[0]];
          const Tensor<1, 3> n  = cross_product_3d(block.vertices[face[1]] - p0,
                                                  block.vertices[face[2]] - p0);
          for (const auto &v : block.vertices)
            EXPECT_LE(n * (v - p0) / n.norm(), 1e-12);
        }
      for (unsigned int j = 0; j < i; ++j)
        EXPECT_GE(separation(heap, j, i), g - 1e-9)
          << "blocks " << i << " and " << j;
    }
  // the cells fill the region less the gaps; blocks lose at most the
  // corners cut off with their short edges
  EXPECT_LT(block_volume, W * W * (z1 - z0));
  EXPECT_GT(block_volume, 0.5 * W * W * (z1 - z0));
  // the container: base plate and four walls, each a box of 6 faces
  for (const auto &part : heap.container)
    EXPECT_EQ(part.faces.size(), 6u);
  EXPECT_NEAR(heap.container[0].volume(),
              (W + 0.06) * (W + 0.06) * 0.03,
              1e-12);

  const BlockHeapGeometry3D again = generate_block_heap_3d(p);
  const BlockHeapGeometry3D other = generate_block_heap_3d(heap_parameters(2));
  EXPECT_EQ(block_heap_gmsh_script(heap, 0.035),
            block_heap_gmsh_script(again, 0.035));
  EXPECT_NE(block_heap_gmsh_script(heap, 0.035),
            block_heap_gmsh_script(other, 0.035));
}

TEST(BlockHeap3D, BadEntriesAreRefusedWithTheirNames)
{
  MeshParameters p      = heap_parameters(1);
  p.block_heap.n_blocks = 400; // the region rises above the walls
  try
    {
      generate_block_heap_3d(p);
      FAIL() << "a heap above its walls was accepted";
    }
  catch (const InputError &e)
    {
      EXPECT_NE(std::string(e.what()).find("Number of blocks = 400"),
                std::string::npos);
      EXPECT_NE(std::string(e.what()).find("reaches z ="), std::string::npos);
    }
  p              = heap_parameters(1);
  p.element_size = 0.05; // more than s / 2
  EXPECT_THROW(generate_block_heap_3d(p), InputError);
}
