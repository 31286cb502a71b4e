#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
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

    /** The blocks' region: 0 < x < W, y0 < y < y0 + height (3D: 0 < x, y
     *  < W, z0 < z < z0 + height) [m]. */
    double
    region_height(const MeshParameters::BlockHeap &p, const unsigned int dim)
    {
      return dim == 3 ?
               p.n_blocks * std::pow(p.mean_size, 3) /
                 (p.container_width * p.container_width) :
               p.n_blocks * p.mean_size * p.mean_size / p.container_width;
    }

    /**
     * @p n seeds uniform in the box [@p lower, @p upper] by random
     * sequential addition with a minimum distance of 0.6 @p s, relaxed by
     * 0.9 whenever 1000 tries in a row fail. Each candidate draws its
     * coordinates in the order x, y (, z).
     */
    template <int dim>
    std::vector<Point<dim>>
    random_seeds(const unsigned int n,
                 const Point<dim>  &lower,
                 const Point<dim>  &upper,
                 const double       s,
                 std::mt19937      &engine)
    {
      std::vector<Point<dim>> seeds;
      double                  min_distance = 0.6 * s;
      unsigned int            failures     = 0;
      while (seeds.size() < n)
        {
          Point<dim> candidate;
          for (unsigned int d = 0; d < dim; ++d)
            candidate[d] = lower[d] + (upper[d] - lower[d]) * uniform(engine);
          bool free = true;
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
      return seeds;
    }

    /** The checked entries' seeds: the region 0 < x (, y) < W above Drop
     *  height, its height from region_height(). */
    template <int dim>
    std::vector<Point<dim>>
    heap_seeds(const MeshParameters &parameters)
    {
      check_block_heap_parameters(parameters);
      const auto &p = parameters.block_heap;
      Point<dim>  lower, upper;
      for (unsigned int d = 0; d + 1 < dim; ++d)
        upper[d] = p.container_width;
      lower[dim - 1] = p.drop_height;
      upper[dim - 1] = p.drop_height + region_height(p, dim);
      std::mt19937 engine(p.seed);
      return random_seeds(p.n_blocks, lower, upper, p.mean_size, engine);
    }

    /** The comma-separated list of @p ids. */
    std::string
    id_list(const std::vector<unsigned int> &ids)
    {
      std::string text;
      for (unsigned int i = 0; i < ids.size(); ++i)
        text += (i > 0 ? ", " : "") + std::to_string(ids[i]);
      return text;
    }

    /** The physical groups of a heap's .geo script in @p dim dimensions:
     *  the blocks' and the container's cells (material ids), the base's
     *  and the walls' sides (boundary ids). */
    void
    write_physical_groups(std::ostream                    &geo,
                          const unsigned int               dim,
                          const std::vector<unsigned int> &blocks,
                          const std::vector<unsigned int> &container,
                          const std::vector<unsigned int> &base,
                          const std::vector<unsigned int> &walls)
    {
      const std::string cell = dim == 3 ? "Volume" : "Surface",
                        side = dim == 3 ? "Surface" : "Curve";
      geo << "Physical " << cell << "(" << block_heap_block_material << ") = {"
          << id_list(blocks) << "};\n"
          << "Physical " << cell << "(" << block_heap_container_material
          << ") = {" << id_list(container) << "};\n"
          << "Physical " << side << "(" << block_heap_base_boundary << ") = {"
          << id_list(base) << "};\n"
          << "Physical " << side << "(" << block_heap_wall_boundary << ") = {"
          << id_list(walls) << "};\n";
    }

    /** A box [@p lower, @p upper] as a Polyhedron. */
    Polyhedron
    box(const Point<3> &lower, const Point<3> &upper)
    {
      std::vector<Point<3>> corners;
      for (unsigned int k = 0; k < 8; ++k)
        corners.emplace_back(k & 1 ? upper[0] : lower[0],
                             k & 2 ? upper[1] : lower[1],
                             k & 4 ? upper[2] : lower[2]);
      return convex_hull(corners);
    }

    /** A half-space n . x <= c [-, m]. */
    struct HalfSpace
    {
      Tensor<1, 3> n;
      double       c;
    };

    /**
     * The vertices of the convex polytope that @p planes bound: the
     * intersections of three planes inside all others (within @p tolerance
     * [m]).
     */
    std::vector<Point<3>>
    polytope_vertices(const std::vector<HalfSpace> &planes,
                      const double                  tolerance)
    {
      std::vector<Point<3>> vertices;
      const unsigned int    m = planes.size();
      for (unsigned int a = 0; a < m; ++a)
        for (unsigned int b = a + 1; b < m; ++b)
          for (unsigned int c = b + 1; c < m; ++c)
            {
              const Tensor<1, 3> &na = planes[a].n, &nb = planes[b].n,
                                 &nc = planes[c].n;
              const Tensor<1, 3> bc  = cross_product_3d(nb, nc);
              const double       det = na * bc;
              if (std::abs(det) < 1e-10)
                continue;
              // Cramer: x = (c_a (nb x nc) + c_b (nc x na) + c_c (na x nb))
              // / det
              const Point<3> x((planes[a].c * bc +
                                planes[b].c * cross_product_3d(nc, na) +
                                planes[c].c * cross_product_3d(na, nb)) /
                               det);
              bool           inside = true;
              for (const HalfSpace &h : planes)
                if (h.n * x > h.c + tolerance)
                  {
                    inside = false;
                    break;
                  }
              if (inside)
                vertices.push_back(x);
            }
      return vertices;
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
    const unsigned int dim = parameters.dimension;
    const double       top = p.drop_height + region_height(p, dim);
    if (!(top <= p.container_height))
      throw InputError(
        name + "Number of blocks = " + std::to_string(p.n_blocks) +
        " of Mean block size " + text(s) + " m fill a region " +
        text(region_height(p, dim)) + " m high; with Drop height " +
        text(p.drop_height) + " m it reaches " + (dim == 3 ? "z" : "y") +
        " = " + text(top) +
        " m, above Container height = " + text(p.container_height) +
        " m; allowed are fewer or smaller blocks, or a higher container.");
    if (!(parameters.element_size <= 0.5 * s))
      throw InputError(
        name + "Mean block size = " + text(s) +
        " m with Mesh/Element size = " + text(parameters.element_size) +
        " m: allowed is Element size <= Mean block size / 2 "
        "(a few elements per block edge).");
  }

  BlockHeapGeometry
  generate_block_heap(const MeshParameters &parameters)
  {
    const std::vector<Point<2>> seeds = heap_seeds<2>(parameters);
    const auto                 &p     = parameters.block_heap;
    const double                W = p.container_width, H = p.container_height;
    const double       t = p.wall_thickness, s = p.mean_size, g = p.gap;
    const double       y0 = p.drop_height, y1 = y0 + region_height(p, 2);
    const unsigned int n = p.n_blocks;

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
    std::vector<unsigned int> walls = container_curves[1];
    walls.insert(walls.end(),
                 container_curves[2].begin(),
                 container_curves[2].end());
    write_physical_groups(geo,
                          2,
                          block_surfaces,
                          container_surfaces,
                          container_curves[0],
                          walls);
    geo << "Mesh.Algorithm = 6;\n"
        << "Mesh.MeshSizeMin = h;\nMesh.MeshSizeMax = h;\n"
        << "Mesh.MeshSizeFromPoints = 0;\n"
        << "Mesh.MeshSizeExtendFromBoundary = 0;\n"
        << "Mesh.RandomSeed = 1;\n";
    return geo.str();
  }
} // namespace tmfdem

namespace tmfdem
{
  double
  Polyhedron::volume() const
  {
    Point<3> centre;
    for (const auto &v : vertices)
      centre += v / static_cast<double>(vertices.size());
    double sum = 0.;
    for (const auto &face : faces)
      for (unsigned int k = 1; k + 1 < face.size(); ++k)
        sum += ((vertices[face[0]] - centre) *
                cross_product_3d(vertices[face[k]] - centre,
                                 vertices[face[k + 1]] - centre)) /
               6.;
    return sum;
  }

  double
  Polyhedron::shortest_edge() const
  {
    double shortest = std::numeric_limits<double>::max();
    for (const auto &face : faces)
      for (unsigned int k = 0; k < face.size(); ++k)
        shortest = std::min(shortest,
                            vertices[face[k]].distance(
                              vertices[face[(k + 1) % face.size()]]));
    return shortest;
  }

  Polyhedron
  convex_hull(const std::vector<Point<3>> &points)
  {
    // the size of the set and the tolerances relative to it
    Point<3> lower = points.empty() ? Point<3>() : points[0], upper = lower;
    for (const auto &p : points)
      for (unsigned int d = 0; d < 3; ++d)
        {
          lower[d] = std::min(lower[d], p[d]);
          upper[d] = std::max(upper[d], p[d]);
        }
    const double size      = lower.distance(upper);
    const double tolerance = 1e-9 * size;
    // distinct points
    std::vector<Point<3>> p;
    for (const auto &q : points)
      if (std::none_of(p.begin(), p.end(), [&](const Point<3> &r) {
            return r.distance(q) <= tolerance;
          }))
        p.push_back(q);
    const unsigned int n = p.size();

    struct Plane
    {
      Tensor<1, 3> normal;
      double       offset;
    };
    std::vector<Plane>                     planes;
    std::vector<std::vector<unsigned int>> faces;
    for (unsigned int i = 0; i < n; ++i)
      for (unsigned int j = i + 1; j < n; ++j)
        for (unsigned int k = j + 1; k < n; ++k)
          {
            Tensor<1, 3> normal = cross_product_3d(p[j] - p[i], p[k] - p[i]);
            const double norm   = normal.norm();
            if (!(norm > 1e-12 * size * size))
              continue;
            normal /= norm;
            double       offset = normal * p[i];
            unsigned int above = 0, below = 0;
            for (unsigned int m = 0; m < n; ++m)
              {
                const double distance = normal * p[m] - offset;
                above += distance > tolerance;
                below += distance < -tolerance;
              }
            if (above > 0 && below > 0)
              continue;
            if (above > 0)
              {
                normal = -normal;
                offset = -offset;
              }
            if (std::any_of(planes.begin(), planes.end(), [&](const Plane &q) {
                  return q.normal * normal > 1. - 1e-9 &&
                         std::abs(q.offset - offset) <= tolerance;
                }))
              continue;
            planes.push_back({normal, offset});
            // the face: the corners of the points on the plane (their
            // convex hull in the plane, Andrew's monotone chain; points on
            // an edge or inside are no corners), counter-clockwise about
            // the outward normal
            std::vector<unsigned int> face;
            for (unsigned int m = 0; m < n; ++m)
              if (std::abs(normal * p[m] - offset) <= tolerance)
                face.push_back(m);
            Tensor<1, 3> e1 = p[face[1]] - p[face[0]];
            e1 /= e1.norm();
            const Tensor<1, 3> e2 = cross_product_3d(normal, e1);
            auto               u  = [&](const unsigned int m) {
              return std::make_pair(e1 * p[m], e2 * p[m]);
            };
            std::sort(face.begin(),
                      face.end(),
                      [&](const unsigned int a, const unsigned int b) {
                        return u(a) < u(b);
                      });
            // > 0: a -> b -> c turns counter-clockwise
            auto turn = [&](const unsigned int a,
                            const unsigned int b,
                            const unsigned int c) {
              return normal * cross_product_3d(p[b] - p[a], p[c] - p[b]);
            };
            std::vector<unsigned int> corners;
            for (unsigned int pass = 0; pass < 2; ++pass)
              {
                const std::size_t start = corners.size();
                for (unsigned int q = 0; q < face.size(); ++q)
                  {
                    const unsigned int m =
                      pass == 0 ? face[q] : face[face.size() - 1 - q];
                    while (corners.size() >= start + 2 &&
                           turn(corners[corners.size() - 2],
                                corners.back(),
                                m) <= 1e-9 * size * size)
                      corners.pop_back();
                    corners.push_back(m);
                  }
                corners.pop_back(); // the first point of the other chain
              }
            faces.push_back(corners);
          }
    if (faces.size() < 4)
      throw RunError("convex_hull: the " + std::to_string(n) +
                     " points span no volume.");
    // keep the corners only, numbered in order
    Polyhedron                hull;
    std::vector<unsigned int> number(n, numbers::invalid_unsigned_int);
    for (auto &face : faces)
      {
        for (unsigned int &m : face)
          {
            if (number[m] == numbers::invalid_unsigned_int)
              {
                number[m] = hull.vertices.size();
                hull.vertices.push_back(p[m]);
              }
            m = number[m];
          }
        hull.faces.push_back(face);
      }
    return hull;
  }

  double
  BlockHeapGeometry3D::volume() const
  {
    double sum = 0.;
    for (const auto &b : blocks)
      sum += b.volume();
    for (const auto &c : container)
      sum += c.volume();
    return sum;
  }

  BlockHeapGeometry3D
  generate_block_heap_3d(const MeshParameters &parameters)
  {
    const std::vector<Point<3>> seeds = heap_seeds<3>(parameters);
    const auto                 &p     = parameters.block_heap;
    const double                W = p.container_width, H = p.container_height;
    const double       t = p.wall_thickness, s = p.mean_size, g = p.gap;
    const double       z0 = p.drop_height, z1 = z0 + region_height(p, 3);
    const unsigned int n = p.n_blocks;

    // Voronoi cells clipped to the region less g/2 at the walls' sides,
    // every bisector moved by g/2 towards the cell's seed. A cell is cut
    // from the bisectors of its nearest seeds, then checked against all.
    const double        tolerance = 1e-9 * s;
    BlockHeapGeometry3D geometry;
    geometry.seeds = seeds;
    const Tensor<1, 3> ex({1., 0., 0.}), ey({0., 1., 0.}), ez({0., 0., 1.});
    for (unsigned int i = 0; i < n; ++i)
      {
        std::vector<HalfSpace> region = {{-ex, -0.5 * g},
                                         {ex, W - 0.5 * g},
                                         {-ey, -0.5 * g},
                                         {ey, W - 0.5 * g},
                                         {-ez, -z0},
                                         {ez, z1}};
        std::vector<HalfSpace> bisectors;
        for (unsigned int j = 0; j < n; ++j)
          if (j != i)
            {
              const Tensor<1, 3> d      = seeds[j] - seeds[i];
              const Tensor<1, 3> normal = d / d.norm();
              bisectors.push_back(
                {normal, normal * (seeds[i] + 0.5 * d) - 0.5 * g});
            }
        // the distance of a bisector from seed i
        const auto distance = [&](const HalfSpace &h) {
          return h.c - h.n * seeds[i];
        };
        const auto nearer = [&](const HalfSpace &a, const HalfSpace &b) {
          return distance(a) < distance(b);
        };
        std::vector<Point<3>> vertices;
        for (std::size_t nearest = 40;; nearest *= 2)
          {
            // the nearest bisectors first (O(n) each try, no full sort: a
            // heap of 10000 blocks stays O(n^2) in all)
            nearest = std::min(nearest, bisectors.size());
            std::nth_element(bisectors.begin(),
                             bisectors.begin() + nearest,
                             bisectors.end(),
                             nearer);
            std::sort(bisectors.begin(), bisectors.begin() + nearest, nearer);
            std::vector<HalfSpace> planes = region;
            planes.insert(planes.end(),
                          bisectors.begin(),
                          bisectors.begin() + nearest);
            vertices = polytope_vertices(planes, tolerance);
            // a bisector farther from the seed than every vertex cuts
            // nothing; the others must hold every vertex
            double radius = 0.;
            for (const auto &x : vertices)
              radius = std::max(radius, x.distance(seeds[i]));
            const bool complete =
              nearest >= bisectors.size() ||
              std::all_of(bisectors.begin() + nearest,
                          bisectors.end(),
                          [&](const HalfSpace &h) {
                            return distance(h) > radius ||
                                   std::all_of(vertices.begin(),
                                               vertices.end(),
                                               [&](const Point<3> &x) {
                                                 return h.n * x <=
                                                        h.c + tolerance;
                                               });
                          });
            if (complete)
              break;
          }
        auto degenerate = [&]() {
          return InputError(
            "Mesh/Block heap: block " + std::to_string(i + 1) + " of seed " +
            std::to_string(p.seed) +
            " is degenerate (its cell is smaller than (s/10)^3 after the "
            "gap is cut); allowed are a smaller Gap or another Seed.");
        };
        if (vertices.size() < 4)
          throw degenerate();
        Polyhedron cell;
        try
          {
            cell = convex_hull(vertices);
          }
        catch (const RunError &)
          {
            throw degenerate();
          }
        // drop vertices until no edge is shorter than h (in 3D, shorter
        // edges leave slivers that set the explicit step): of the two ends
        // of the shortest edge the one whose removal loses less volume
        const double min_edge = parameters.element_size;
        while (cell.vertices.size() > 4 && cell.shortest_edge() < min_edge)
          {
            unsigned int a = 0, b = 0;
            double       shortest = std::numeric_limits<double>::max();
            for (const auto &face : cell.faces)
              for (unsigned int k = 0; k < face.size(); ++k)
                {
                  const unsigned int u = face[k],
                                     v = face[(k + 1) % face.size()];
                  const double length =
                    cell.vertices[u].distance(cell.vertices[v]);
                  if (length < shortest)
                    {
                      shortest = length;
                      a        = u;
                      b        = v;
                    }
                }
            // the hull of the other vertices (none if they span no
            // volume: the block is then degenerate)
            auto without = [&](const unsigned int v) {
              std::vector<Point<3>> rest = cell.vertices;
              rest.erase(rest.begin() + v);
              try
                {
                  return convex_hull(rest);
                }
              catch (const RunError &)
                {
                  throw degenerate();
                }
            };
            Polyhedron without_a = without(a), without_b = without(b);
            cell = without_a.volume() >= without_b.volume() ?
                     std::move(without_a) :
                     std::move(without_b);
          }
        if (cell.volume() < 1e-3 * s * s * s)
          throw degenerate();
        geometry.blocks.push_back(std::move(cell));
      }
    geometry.container[0] =
      box(Point<3>(-t, -t, -t), Point<3>(W + t, W + t, 0.));
    // the walls stand g/2 above the base so that they do not touch it; the
    // walls at y = 0 and y = W stop g/2 short of the others
    geometry.container[1] =
      box(Point<3>(-t, -t, 0.5 * g), Point<3>(0., W + t, H));
    geometry.container[2] =
      box(Point<3>(W, -t, 0.5 * g), Point<3>(W + t, W + t, H));
    geometry.container[3] =
      box(Point<3>(0.5 * g, -t, 0.5 * g), Point<3>(W - 0.5 * g, 0., H));
    geometry.container[4] =
      box(Point<3>(0.5 * g, W, 0.5 * g), Point<3>(W - 0.5 * g, W + t, H));
    return geometry;
  }

  std::string
  block_heap_gmsh_script(const BlockHeapGeometry3D &geometry, const double h)
  {
    std::ostringstream geo;
    geo.precision(17);
    geo << "// block heap written by tmfdem (Mesh/Source = block heap, "
           "Dimension = 3)\n"
        << "h = " << h << ";\n";
    unsigned int              point = 0, curve = 0, surface = 0, volume = 0;
    std::vector<unsigned int> blocks, container, base_surfaces, wall_surfaces;
    // one polyhedron: points, its edges once, a plane surface per face;
    // the container's boxes structured (transfinite: one thin layer of
    // free tetrahedra across a wall would be slivers)
    auto add_polyhedron = [&](const Polyhedron          &polyhedron,
                              std::vector<unsigned int> *surfaces) {
      const bool         structured  = surfaces != nullptr;
      const unsigned int first_point = point + 1;
      for (const auto &v : polyhedron.vertices)
        geo << "Point(" << ++point << ") = {" << v[0] << ", " << v[1] << ", "
            << v[2] << ", h};\n";
      std::map<std::pair<unsigned int, unsigned int>, unsigned int> lines;
      std::vector<unsigned int> loop_surfaces;
      for (const auto &face : polyhedron.faces)
        {
          std::vector<int> loop;
          for (unsigned int k = 0; k < face.size(); ++k)
            {
              const unsigned int a = face[k], b = face[(k + 1) % face.size()];
              const auto key  = std::make_pair(std::min(a, b), std::max(a, b));
              auto       line = lines.find(key);
              if (line == lines.end())
                {
                  line = lines.emplace(key, ++curve).first;
                  geo << "Line(" << curve << ") = {" << first_point + key.first
                      << ", " << first_point + key.second << "};\n";
                  if (structured)
                    geo << "Transfinite Curve{" << curve << "} = "
                        << 1 +
                             std::max(1.,
                                      std::ceil(polyhedron.vertices[a].distance(
                                                  polyhedron.vertices[b]) /
                                                  (2. * h) -
                                                1e-9))
                        << ";\n";
                }
              loop.push_back(a == key.first ? static_cast<int>(line->second) :
                                              -static_cast<int>(line->second));
            }
          geo << "Curve Loop(" << ++surface << ") = {";
          for (unsigned int k = 0; k < loop.size(); ++k)
            geo << (k > 0 ? ", " : "") << loop[k];
          geo << "};\nPlane Surface(" << surface << ") = {" << surface
              << "};\n";
          if (structured)
            geo << "Transfinite Surface{" << surface << "};\n";
          loop_surfaces.push_back(surface);
          if (surfaces != nullptr)
            surfaces->push_back(surface);
        }
      geo << "Surface Loop(" << ++volume << ") = {";
      for (unsigned int k = 0; k < loop_surfaces.size(); ++k)
        geo << (k > 0 ? ", " : "") << loop_surfaces[k];
      geo << "};\nVolume(" << volume << ") = {" << volume << "};\n";
      if (structured)
        geo << "Transfinite Volume{" << volume << "};\n";
      return volume;
    };
    for (const auto &block : geometry.blocks)
      blocks.push_back(add_polyhedron(block, nullptr));
    container.push_back(add_polyhedron(geometry.container[0], &base_surfaces));
    for (unsigned int c = 1; c < geometry.container.size(); ++c)
      container.push_back(
        add_polyhedron(geometry.container[c], &wall_surfaces));
    write_physical_groups(geo,
                          3,
                          blocks,
                          container,
                          base_surfaces,
                          wall_surfaces);
    geo << "Mesh.MeshSizeMin = h / 2;\nMesh.MeshSizeMax = h;\n"
        << "Mesh.MeshSizeExtendFromBoundary = 1;\n"
        // MeshAdapt on the faces, Delaunay inside, every tetrahedron of
        // quality below 0.6 optimised: gmsh's defaults (frontal-Delaunay,
        // threshold 0.3) leave slivers (quality 0.008-0.07 on five seeds
        // against 0.05-0.09) that set the explicit step. Not HXT: its mesh
        // depends on the memory layout (the length of the file names), so
        // one seed would give other meshes in other folders
        << "Mesh.Algorithm = 1;\nMesh.Algorithm3D = 1;\n"
        << "Mesh.OptimizeThreshold = 0.6;\n"
        << "Mesh.RandomSeed = 1;\n";
    return geo.str();
  }
} // namespace tmfdem
