#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/mesh/block_generator.h>

namespace tmfdem
{
  namespace
  {
    /** Signed area of @p polygon (positive counter-clockwise) [m^2]. */
    double
    signed_area(const Polygon &polygon)
    {
      double twice = 0.;
      for (unsigned int i = 0; i < polygon.size(); ++i)
        {
          const Point<2> &a = polygon[i];
          const Point<2> &b = polygon[(i + 1) % polygon.size()];
          twice += a[0] * b[1] - b[0] * a[1];
        }
      return 0.5 * twice;
    }

    /** The part of @p polygon where n . x <= c (Sutherland-Hodgman). */
    Polygon
    clip(const Polygon &polygon, const Tensor<1, 2> &n, const double c)
    {
      Polygon result;
      for (unsigned int i = 0; i < polygon.size(); ++i)
        {
          const Point<2> &a  = polygon[i];
          const Point<2> &b  = polygon[(i + 1) % polygon.size()];
          const double    da = n * a - c, db = n * b - c;
          if (da <= 0.)
            result.push_back(a);
          if ((da < 0. && db > 0.) || (da > 0. && db < 0.))
            result.push_back(a + (da / (da - db)) * (b - a));
        }
      return result;
    }

    /** A uniform number in [0, 1) from the standard mt19937 sequence. */
    double
    uniform(std::mt19937 &engine)
    {
      return engine() / 4294967296.;
    }

    Polygon
    rectangle(const double x0, const double y0, const double x1, double y1)
    {
      return {Point<2>(x0, y0),
              Point<2>(x1, y0),
              Point<2>(x1, y1),
              Point<2>(x0, y1)};
    }

    /** Removes vertices until no edge is shorter than @p min_edge (or a
     *  triangle is left): of the two ends of the shortest edge the one
     *  whose removal loses less area goes. */
    void
    remove_short_edges(Polygon &polygon, const double min_edge)
    {
      while (polygon.size() > 3)
        {
          const unsigned int n        = polygon.size();
          unsigned int       shortest = 0;
          for (unsigned int i = 1; i < n; ++i)
            if (polygon[i].distance(polygon[(i + 1) % n]) <
                polygon[shortest].distance(polygon[(shortest + 1) % n]))
              shortest = i;
          if (polygon[shortest].distance(polygon[(shortest + 1) % n]) >=
              min_edge)
            return;
          // area lost by removing vertex v: the triangle (v-1, v, v+1)
          auto loss = [&](const unsigned int v) {
            return std::abs(signed_area(
              {polygon[(v + n - 1) % n], polygon[v], polygon[(v + 1) % n]}));
          };
          const unsigned int a = shortest, b = (shortest + 1) % n;
          polygon.erase(polygon.begin() + (loss(a) <= loss(b) ? a : b));
        }
    }

    /** The blocks' region: 0 < x < W, y0 < y < y0 + height [m]. */
    double
    region_height(const MeshParameters::BlockHeap &p)
    {
      return p.n_blocks * p.mean_size * p.mean_size / p.container_width;
    }
  } // namespace

  double
  BlockHeapGeometry::area() const
  {
    double sum = 0.;
    for (const auto &b : blocks)
      sum += signed_area(b);
    for (const auto &c : container)
      sum += signed_area(c);
    return sum;
  }

  void
  check_block_heap_parameters(const MeshParameters &parameters)
  {
    const auto       &p    = parameters.block_heap;
    const std::string name = "Mesh/Block heap/";
    const double      s    = p.mean_size;
    auto              text = [](const double v) {
      std::ostringstream out; // 6 significant digits: 0.07, not 0.07000..
      out << v;
      return out.str();
    };
    if (!(p.container_width > 0.) || !(p.container_height > 0.) ||
        !(p.wall_thickness > 0.) || !(s > 0.))
      throw InputError(name + "Container width, Container height, Wall "
                              "thickness and Mean block size must be > 0 [m].");
    if (!(p.gap < 0.2 * s))
      throw InputError(name + "Gap = " + text(p.gap) +
                       " m: allowed is 0 <= Gap < Mean block size / 5 = " +
                       text(0.2 * s) + " m.");
    if (!(s < 0.5 * p.container_width))
      throw InputError(name + "Mean block size = " + text(s) +
                       " m: allowed is less than half the Container width (" +
                       text(0.5 * p.container_width) + " m).");
    const double top = p.drop_height + region_height(p);
    if (!(top <= p.container_height))
      throw InputError(
        name + "Number of blocks = " + std::to_string(p.n_blocks) +
        " of Mean block size " + text(s) + " m fill a region " +
        text(region_height(p)) + " m high; with Drop height " +
        text(p.drop_height) + " m it reaches y = " + text(top) +
        " m, above Container height = " + text(p.container_height) +
        " m; allowed are fewer or smaller blocks, or a higher container.");
    if (!(parameters.element_size <= 0.5 * s))
      throw InputError(
        name + "Mean block size = " + text(s) +
        " m with Mesh/Element size = " + text(parameters.element_size) +
        " m: allowed is Element size <= Mean block size / 2 "
        "(a few triangles per block edge).");
  }

  BlockHeapGeometry
  generate_block_heap(const MeshParameters &parameters)
  {
    check_block_heap_parameters(parameters);
    const auto        &p = parameters.block_heap;
    const double       W = p.container_width, H = p.container_height;
    const double       t = p.wall_thickness, s = p.mean_size, g = p.gap;
    const double       y0 = p.drop_height, y1 = y0 + region_height(p);
    const unsigned int n = p.n_blocks;

    // seeds: random sequential addition with a minimum distance, relaxed
    // whenever 1000 tries in a row fail
    std::mt19937          engine(p.seed);
    std::vector<Point<2>> seeds;
    double                min_distance = 0.6 * s;
    unsigned int          failures     = 0;
    while (seeds.size() < n)
      {
        const double   x = W * uniform(engine);
        const double   y = y0 + (y1 - y0) * uniform(engine);
        const Point<2> candidate(x, y);
        bool           free = true;
        for (const auto &q : seeds)
          if (q.distance(candidate) < min_distance)
            {
              free = false;
              break;
            }
        if (free)
          {
            seeds.push_back(candidate);
            failures = 0;
          }
        else if (++failures == 1000)
          {
            min_distance *= 0.9;
            failures = 0;
          }
      }

    // Voronoi cells clipped to the region less g/2 at the walls' sides,
    // every bisector moved by g/2 towards the cell's seed
    BlockHeapGeometry geometry;
    for (unsigned int i = 0; i < n; ++i)
      {
        Polygon cell = rectangle(0.5 * g, y0, W - 0.5 * g, y1);
        for (unsigned int j = 0; j < n && cell.size() >= 3; ++j)
          if (j != i)
            {
              const Tensor<1, 2> d      = seeds[j] - seeds[i];
              const double       length = d.norm();
              const Tensor<1, 2> normal = d / length;
              const Point<2>     mid    = seeds[i] + 0.5 * d;
              cell = clip(cell, normal, normal * mid - 0.5 * g);
            }
        remove_short_edges(cell, 0.5 * parameters.element_size);
        if (cell.size() < 3 || signed_area(cell) < 0.01 * s * s)
          throw InputError(
            "Mesh/Block heap: block " + std::to_string(i + 1) + " of seed " +
            std::to_string(p.seed) +
            " is degenerate (its cell is smaller than (s/10)^2 after the "
            "gap is cut); allowed are a smaller Gap or another Seed.");
        geometry.blocks.push_back(cell);
      }
    geometry.container[0] = rectangle(-t, -t, W + t, 0.);
    // the walls stand g/2 above the base so that they do not touch it
    geometry.container[1] = rectangle(-t, 0.5 * g, 0., H);
    geometry.container[2] = rectangle(W, 0.5 * g, W + t, H);
    return geometry;
  }

  std::string
  block_heap_gmsh_script(const BlockHeapGeometry &geometry, const double h)
  {
    std::ostringstream geo;
    geo.precision(17);
    geo << "// block heap written by tmfdem (Mesh/Source = block heap)\n"
        << "h = " << h << ";\n";
    unsigned int                             point = 0, curve = 0, surface = 0;
    std::vector<unsigned int>                block_surfaces, container_surfaces;
    std::array<std::vector<unsigned int>, 3> container_curves;
    auto add_polygon = [&](const Polygon &polygon) {
      const unsigned int first_point = point + 1, first_curve = curve + 1;
      for (const auto &v : polygon)
        geo << "Point(" << ++point << ") = {" << v[0] << ", " << v[1]
            << ", 0, h};\n";
      const unsigned int m = polygon.size();
      for (unsigned int k = 0; k < m; ++k)
        geo << "Line(" << ++curve << ") = {" << first_point + k << ", "
            << first_point + (k + 1) % m << "};\n";
      geo << "Curve Loop(" << ++surface << ") = {";
      for (unsigned int k = 0; k < m; ++k)
        geo << (k > 0 ? ", " : "") << first_curve + k;
      geo << "};\nPlane Surface(" << surface << ") = {" << surface << "};\n";
      return first_curve;
    };
    for (const auto &block : geometry.blocks)
      {
        add_polygon(block);
        block_surfaces.push_back(surface);
      }
    for (unsigned int c = 0; c < 3; ++c)
      {
        const unsigned int first = add_polygon(geometry.container[c]);
        container_surfaces.push_back(surface);
        for (unsigned int k = 0; k < geometry.container[c].size(); ++k)
          container_curves[c].push_back(first + k);
      }
    auto list = [](const std::vector<unsigned int> &ids) {
      std::string text;
      for (unsigned int i = 0; i < ids.size(); ++i)
        text += (i > 0 ? ", " : "") + std::to_string(ids[i]);
      return text;
    };
    std::vector<unsigned int> walls = container_curves[1];
    walls.insert(walls.end(),
                 container_curves[2].begin(),
                 container_curves[2].end());
    geo << "Physical Surface(" << block_heap_block_material << ") = {"
        << list(block_surfaces) << "};\n"
        << "Physical Surface(" << block_heap_container_material << ") = {"
        << list(container_surfaces) << "};\n"
        << "Physical Curve(" << block_heap_base_boundary << ") = {"
        << list(container_curves[0]) << "};\n"
        << "Physical Curve(" << block_heap_wall_boundary << ") = {"
        << list(walls) << "};\n"
        << "Mesh.Algorithm = 6;\n"
        << "Mesh.MeshSizeMin = h;\nMesh.MeshSizeMax = h;\n"
        << "Mesh.MeshSizeFromPoints = 0;\n"
        << "Mesh.MeshSizeExtendFromBoundary = 0;\n"
        << "Mesh.RandomSeed = 1;\n";
    return geo.str();
  }
} // namespace tmfdem
