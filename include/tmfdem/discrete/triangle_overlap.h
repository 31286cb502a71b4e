/**
 * @file
 * The overlap of two triangles of the discrete layer, the geometry of
 * contact heat transfer (contact_heat.h; paper Sec. 3.4, Eqs. 28-33): the
 * contactor clipped by the three half-planes of the target
 * (Sutherland-Hodgman), giving the overlap polygon (at most 6 vertices), its
 * area, centroid, central second moments, perimeter and contact length, the
 * chord of the interpenetration.
 *
 * Header-only, inline and allocation-free: it runs once per contact pair
 * per thermal step.
 */
#ifndef tmfdem_discrete_triangle_overlap_h
#define tmfdem_discrete_triangle_overlap_h

#include <algorithm>
#include <array>
#include <cmath>

namespace tmfdem
{
  namespace discrete
  {
    /** Which triangle's boundary an edge of the overlap polygon lies on. */
    enum class OverlapEdgeOwner : unsigned char
    {
      /** the boundary of the first triangle (the contactor) only */
      first,
      /** the boundary of the second triangle (the target) only */
      second,
      /** both: collinear edges of the two triangles (e.g. the aligned side
       * faces of neighbouring elements) */
      both
    };

    /**
     * The overlap polygon of two triangles and its geometric properties.
     *
     * Contact length L_c [m]: the chord of the interpenetration. The
     * polygon's boundary consists of runs of edges on the first triangle's
     * boundary (inside the second) and runs on the second's boundary (inside
     * the first); consecutive runs meet at the crossing points of the two
     * boundaries (where a run of collinear edges, on both boundaries,
     * separates a run of the first from one of the second, the crossing is
     * the midpoint of that collinear run). L_c is half the perimeter of the
     * polygon of the crossing points: with the usual two crossings, the
     * straight distance between them. With no crossing (one triangle inside
     * the other, identical triangles) L_c = 0, the limit of the chord as a
     * small triangle sinks into a larger one.
     *
     * Why the chord:
     *  - a flat face-to-face contact with penetration delta over a segment
     *    of length s gives L_c = s (exactly when the ends are cut by aligned
     *    edges, sqrt(s^2 + delta^2) when by edges of different triangles),
     *    so Q = h_c L_c dT is a flux h_c dT per unit contact length;
     *  - in a meshed face-to-face contact, neighbouring pairs share their
     *    crossing points (a mesh edge crossing the contact layer is the end
     *    of the two slivers on either side, a small wedge cut off at a face
     *    vertex included), so the chords of all pairs add up to the touching
     *    length to second order in delta / (element size), up to O(delta)
     *    at the two ends of the contact;
     *  - it is symmetric in the pair and invariant under rigid motions.
     * Polygon-only measures cannot do this: half the perimeter adds about
     * delta per sliver end, and the equivalent-rectangle length
     * sqrt(12 I_max / A) gives a small wedge its height delta instead of its
     * width along the face (both kept as diagnostics: perimeter and the
     * second moments). The chord jumps where the number of crossings
     * changes (a vertex of one triangle passing through the other), like any
     * switch-on of contact conduction.
     */
    struct OverlapPolygon
    {
      /** Room for the vertices: 6 in exact arithmetic; 3 more so that
       * vertices created by round-off in degenerate configurations can never
       * overflow the arrays. */
      static constexpr unsigned int max_vertices = 9;

      /** Number of vertices (counter-clockwise), 0 if there is no overlap. */
      unsigned int n_vertices = 0;

      /** Vertex coordinates [m]. */
      std::array<double, max_vertices> x{}, y{};

      /** Owner of edge i, from vertex i to vertex i + 1 (mod n_vertices). */
      std::array<OverlapEdgeOwner, max_vertices> edge_owner{};

      /** Area [m^2] (0 if there is no overlap). */
      double area = 0.;

      /** Centroid G [m]. */
      double centroid_x = 0., centroid_y = 0.;

      /** Central second moments of area [m^4]: int (x - G_x)^2 dA,
       * int (y - G_y)^2 dA and int (x - G_x)(y - G_y) dA (diagnostic). */
      double second_moment_xx = 0., second_moment_yy = 0.,
             second_moment_xy = 0.;

      /** Contact length L_c [m]: chord of the interpenetration, see above. */
      double contact_length = 0.;

      /** Perimeter [m] (diagnostic only). */
      double perimeter = 0.;
    };

    /**
     * Twice the signed area [m^2] of the triangle (a, b, p): positive if
     * p lies to the left of the directed line a->b.
     */
    inline double
    twice_signed_area(const double ax,
                      const double ay,
                      const double bx,
                      const double by,
                      const double px,
                      const double py)
    {
      return (bx - ax) * (py - ay) - (by - ay) * (px - ax);
    }

    namespace contact_heat_internal
    {
      /**
       * Sutherland-Hodgman step: clips the polygon (@p px, @p py [m],
       * @p owner of each edge, @p n vertices) by the closed half-plane to
       * the left of the directed line (ex0, ey0)->(ex1, ey1) [m], an edge of
       * the second triangle, and writes the result to (@p qx, @p qy,
       * @p q_owner). Points on the line count as inside; an intersection
       * point is inserted only where an edge crosses the line strictly.
       * Edges created along the line belong to the second triangle, edges
       * of the first triangle lying on the line to both. Exactly repeated
       * vertices are merged. Returns the number of vertices written (at
       * most @p capacity).
       */
      inline unsigned int
      clip_by_half_plane(const double           *px,
                         const double           *py,
                         const OverlapEdgeOwner *owner,
                         const unsigned int      n,
                         const double            ex0,
                         const double            ey0,
                         const double            ex1,
                         const double            ey1,
                         double                 *qx,
                         double                 *qy,
                         OverlapEdgeOwner       *q_owner,
                         const unsigned int      capacity)
      {
        double side[OverlapPolygon::max_vertices];
        for (unsigned int i = 0; i < n; ++i)
          side[i] = twice_signed_area(ex0, ey0, ex1, ey1, px[i], py[i]);

        unsigned int m = 0;
        auto         emit =
          [&](const double x, const double y, const OverlapEdgeOwner edge) {
            if (m > 0 && qx[m - 1] == x && qy[m - 1] == y)
              {
                // zero-length edge: the merged vertex starts the new edge
                q_owner[m - 1] = edge;
                return;
              }
            if (m < capacity)
              {
                qx[m]      = x;
                qy[m]      = y;
                q_owner[m] = edge;
                ++m;
              }
          };
        for (unsigned int i = 0; i < n; ++i)
          {
            const unsigned int j = (i + 1 == n) ? 0 : i + 1;
            if (side[i] >= 0.)
              {
                if (side[j] < 0.)
                  {
                    // leaving: the boundary continues along the line
                    if (side[i] > 0.)
                      {
                        emit(px[i], py[i], owner[i]);
                        const double s = side[i] / (side[i] - side[j]);
                        emit(px[i] + s * (px[j] - px[i]),
                             py[i] + s * (py[j] - py[i]),
                             OverlapEdgeOwner::second);
                      }
                    else
                      emit(px[i], py[i], OverlapEdgeOwner::second);
                  }
                else if (side[i] == 0. && side[j] == 0. &&
                         owner[i] != OverlapEdgeOwner::second)
                  emit(px[i], py[i], OverlapEdgeOwner::both);
                else
                  emit(px[i], py[i], owner[i]);
              }
            else if (side[j] > 0.)
              {
                // entering: the rest of the edge keeps its owner
                const double s = side[i] / (side[i] - side[j]);
                emit(px[i] + s * (px[j] - px[i]),
                     py[i] + s * (py[j] - py[i]),
                     owner[i]);
              }
          }
        if (m > 1 && qx[m - 1] == qx[0] && qy[m - 1] == qy[0])
          --m;
        return m;
      }

      /**
       * Contact length [m] of the closed polygon (@p x, @p y [m], @p owner
       * of each edge, @p n vertices): half the perimeter of the polygon of
       * its crossing points, i.e. the chord between the two crossings in the
       * usual case. A crossing is a vertex where the owner changes from one
       * triangle to the other, or, where the change happens across a run of
       * edges owned by both (collinear edges), the midpoint (by arc length)
       * of that run. No crossing (one triangle inside the other, identical
       * triangles) gives 0.
       */
      inline double
      chord_of_crossings(const double           *x,
                         const double           *y,
                         const OverlapEdgeOwner *edge_owner,
                         const unsigned int      n)
      {
        auto edge_length = [&](const unsigned int i) {
          const unsigned int j = (i + 1 == n) ? 0 : i + 1;
          return std::hypot(x[j] - x[i], y[j] - y[i]);
        };
        // Runs of one owner shorter than the round-off of the intersection
        // points (e.g. a vertex of one triangle computed 1e-17 off the edge
        // of the other) would add a spurious pair of crossings: they count
        // as owned by both.
        OverlapEdgeOwner owner[OverlapPolygon::max_vertices];
        double           scale = 0.;
        for (unsigned int i = 0; i < n; ++i)
          {
            owner[i] = edge_owner[i];
            scale += edge_length(i);
            scale = std::max({scale, std::abs(x[i]), std::abs(y[i])});
          }
        const double negligible_length = 1e-9 * scale;
        for (unsigned int i = 0; i < n; ++i)
          {
            const unsigned int previous = (i == 0) ? n - 1 : i - 1;
            if (owner[i] == OverlapEdgeOwner::both ||
                owner[previous] == owner[i])
              continue;
            // edge i starts a run: measure it
            unsigned int end        = i;
            double       run_length = 0.;
            unsigned int count      = 0;
            while (count < n && owner[end] == owner[i])
              {
                run_length += edge_length(end);
                end = (end + 1) % n;
                ++count;
              }
            if (count < n && run_length <= negligible_length)
              for (unsigned int k = i, c = 0; c < count; k = (k + 1) % n, ++c)
                owner[k] = OverlapEdgeOwner::both;
          }

        unsigned int start = n;
        for (unsigned int i = 0; i < n; ++i)
          if (owner[i] != OverlapEdgeOwner::both)
            {
              start = i;
              break;
            }
        if (start == n)
          return 0.;

        double           crossing_x[OverlapPolygon::max_vertices];
        double           crossing_y[OverlapPolygon::max_vertices];
        unsigned int     n_crossings    = 0;
        OverlapEdgeOwner previous_owner = owner[start];
        bool             in_shared_run  = false;
        unsigned int     shared_begin   = 0;
        for (unsigned int step = 1; step <= n; ++step)
          {
            const unsigned int i = (start + step) % n;
            if (owner[i] == OverlapEdgeOwner::both)
              {
                if (!in_shared_run)
                  {
                    in_shared_run = true;
                    shared_begin  = i;
                  }
                continue;
              }
            if (owner[i] != previous_owner &&
                n_crossings < OverlapPolygon::max_vertices)
              {
                if (in_shared_run)
                  {
                    // midpoint of the shared run from vertex shared_begin
                    // to vertex i
                    double run_length = 0.;
                    for (unsigned int k = shared_begin; k != i; k = (k + 1) % n)
                      run_length += edge_length(k);
                    double       remaining = 0.5 * run_length;
                    unsigned int k         = shared_begin;
                    while (edge_length(k) < remaining && (k + 1) % n != i)
                      {
                        remaining -= edge_length(k);
                        k = (k + 1) % n;
                      }
                    const unsigned int k_next = (k + 1) % n;
                    const double       length = edge_length(k);
                    const double       s =
                      length > 0. ? std::min(remaining / length, 1.) : 0.;
                    crossing_x[n_crossings] = x[k] + s * (x[k_next] - x[k]);
                    crossing_y[n_crossings] = y[k] + s * (y[k_next] - y[k]);
                  }
                else
                  {
                    crossing_x[n_crossings] = x[i];
                    crossing_y[n_crossings] = y[i];
                  }
                ++n_crossings;
              }
            in_shared_run  = false;
            previous_owner = owner[i];
          }
        if (n_crossings < 2)
          return 0.;
        double perimeter = 0.;
        for (unsigned int k = 0; k < n_crossings; ++k)
          {
            const unsigned int l = (k + 1 == n_crossings) ? 0 : k + 1;
            perimeter += std::hypot(crossing_x[l] - crossing_x[k],
                                    crossing_y[l] - crossing_y[k]);
          }
        return 0.5 * perimeter;
      }
    } // namespace contact_heat_internal

    /**
     * Overlap of two triangles with counter-clockwise nodes (@p ax, @p ay)
     * and (@p bx, @p by) [m]: clips A by the three half-planes of B and
     * fills @p overlap with the polygon, the owners of its edges, its area
     * [m^2], centroid [m], central second moments [m^4], contact length [m]
     * and perimeter [m].
     *
     * Returns false, with @p overlap reset to an empty polygon of zero area,
     * if the triangles do not overlap with positive area: disjoint, touching
     * along an edge or at a point (e.g. the coincident faces of two
     * neighbours of the exploded mesh), an overlap area below 1e-12 of the
     * smaller triangle's area (round-off level), or a triangle that is not
     * counter-clockwise with positive area.
     */
    inline bool
    triangle_overlap(const double   *ax,
                     const double   *ay,
                     const double   *bx,
                     const double   *by,
                     OverlapPolygon &overlap)
    {
      overlap = OverlapPolygon();
      const double twice_area_a =
        twice_signed_area(ax[0], ay[0], ax[1], ay[1], ax[2], ay[2]);
      const double twice_area_b =
        twice_signed_area(bx[0], by[0], bx[1], by[1], bx[2], by[2]);
      if (!(twice_area_a > 0.) || !(twice_area_b > 0.))
        return false;

      // bounding-box rejection
      const double a_xmin = std::min({ax[0], ax[1], ax[2]});
      const double a_xmax = std::max({ax[0], ax[1], ax[2]});
      const double a_ymin = std::min({ay[0], ay[1], ay[2]});
      const double a_ymax = std::max({ay[0], ay[1], ay[2]});
      if (std::max({bx[0], bx[1], bx[2]}) <= a_xmin ||
          std::min({bx[0], bx[1], bx[2]}) >= a_xmax ||
          std::max({by[0], by[1], by[2]}) <= a_ymin ||
          std::min({by[0], by[1], by[2]}) >= a_ymax)
        return false;

      constexpr unsigned int capacity = OverlapPolygon::max_vertices;
      double                 buffer_x[2][capacity], buffer_y[2][capacity];
      OverlapEdgeOwner       buffer_owner[2][capacity];
      double                *from_x = buffer_x[0], *from_y = buffer_y[0];
      double                *to_x = buffer_x[1], *to_y = buffer_y[1];
      OverlapEdgeOwner      *from_owner = buffer_owner[0],
                       *to_owner        = buffer_owner[1];
      unsigned int n                    = 3;
      for (unsigned int k = 0; k < 3; ++k)
        {
          from_x[k]     = ax[k];
          from_y[k]     = ay[k];
          from_owner[k] = OverlapEdgeOwner::first;
        }
      for (unsigned int edge = 0; edge < 3 && n > 0; ++edge)
        {
          const unsigned int next = (edge + 1) % 3;
          n = contact_heat_internal::clip_by_half_plane(from_x,
                                                        from_y,
                                                        from_owner,
                                                        n,
                                                        bx[edge],
                                                        by[edge],
                                                        bx[next],
                                                        by[next],
                                                        to_x,
                                                        to_y,
                                                        to_owner,
                                                        capacity);
          std::swap(from_x, to_x);
          std::swap(from_y, to_y);
          std::swap(from_owner, to_owner);
        }
      if (n < 3)
        return false;

      // area and centroid relative to the first vertex (less cancellation)
      const double x0 = from_x[0], y0 = from_y[0];
      double       twice_area = 0., moment_x = 0., moment_y = 0.;
      for (unsigned int i = 0; i < n; ++i)
        {
          const unsigned int j  = (i + 1 == n) ? 0 : i + 1;
          const double       xi = from_x[i] - x0, yi = from_y[i] - y0;
          const double       xj = from_x[j] - x0, yj = from_y[j] - y0;
          const double       cross = xi * yj - xj * yi;
          twice_area += cross;
          moment_x += (xi + xj) * cross;
          moment_y += (yi + yj) * cross;
        }
      const double area = 0.5 * twice_area;
      if (!(area > 0.5e-12 * std::min(twice_area_a, twice_area_b)))
        return false;
      const double gx = moment_x / (3. * twice_area);
      const double gy = moment_y / (3. * twice_area);

      // central second moments and perimeter, relative to G
      double ixx = 0., iyy = 0., ixy = 0., perimeter = 0.;
      for (unsigned int i = 0; i < n; ++i)
        {
          const unsigned int j  = (i + 1 == n) ? 0 : i + 1;
          const double       xi = from_x[i] - x0 - gx, yi = from_y[i] - y0 - gy;
          const double       xj = from_x[j] - x0 - gx, yj = from_y[j] - y0 - gy;
          const double       cross = xi * yj - xj * yi;
          ixx += (xi * xi + xi * xj + xj * xj) * cross;
          iyy += (yi * yi + yi * yj + yj * yj) * cross;
          ixy += (xi * yj + 2. * xi * yi + 2. * xj * yj + xj * yi) * cross;
          perimeter += std::hypot(xj - xi, yj - yi);
        }

      overlap.n_vertices = n;
      for (unsigned int i = 0; i < n; ++i)
        {
          overlap.x[i]          = from_x[i];
          overlap.y[i]          = from_y[i];
          overlap.edge_owner[i] = from_owner[i];
        }
      overlap.area             = area;
      overlap.centroid_x       = x0 + gx;
      overlap.centroid_y       = y0 + gy;
      overlap.second_moment_xx = ixx / 12.;
      overlap.second_moment_yy = iyy / 12.;
      overlap.second_moment_xy = ixy / 24.;
      overlap.contact_length =
        contact_heat_internal::chord_of_crossings(from_x,
                                                  from_y,
                                                  from_owner,
                                                  n);
      overlap.perimeter = perimeter;
      return true;
    }

  } // namespace discrete
} // namespace tmfdem

#endif
