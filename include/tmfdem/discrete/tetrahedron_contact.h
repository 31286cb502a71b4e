/**
 * @file
 * Contact between tetrahedra: Munjiza's potential in 3D (theory manual 5.13),
 * phi = 4 min(lambda_0, ..., lambda_3) (1 at the centroid, 0 on the faces),
 * and the normal contact energy of a contactor c in a target t,
 *
 *   E_t = p int_{c cap t} phi_t dV,
 *
 * whose exact gradient gives the forces on all eight nodes:
 *  - on the contactor's nodes, f_a = -p int_{dc cap t} phi_t N_a n dA over
 *    its faces inside the target (n the face's outward normal, N_a the
 *    face's shape functions): moving a contactor node moves only that part
 *    of the overlap's boundary (Munjiza's force, Eq. 5 by the divergence
 *    theorem);
 *  - on the target's nodes, f_j = 4 p sum_m grad(lambda_m) int_{V_m}
 *    lambda_j dV, V_m the part of the overlap where lambda_m is the
 *    smallest (the sub-tetrahedron of the target's centroid and face m):
 *    moving target node j changes lambda_m at a fixed point by
 *    -lambda_j grad(lambda_m), and the target's moving boundary adds
 *    nothing (phi_t = 0 there).
 * The pair's energy is E_t + E_c (each tetrahedron once the contactor), so
 * the normal force is conservative for any motion of the eight nodes,
 * deformation included; it keeps linear and angular momentum (E does not
 * change under rigid motions of the pair).
 *
 * Every integrand is a polynomial of degree at most two on a polygon or a
 * polyhedron where the potential is linear, integrated exactly: the face
 * clipped by the four planes of a sub-tetrahedron (Sutherland-Hodgman with
 * the linear functions carried at the vertices, the edge-midpoint rule on
 * a fan of triangles), the contactor clipped by the same planes as a set
 * of tetrahedra (one plane cuts a tetrahedron into at most three).
 *
 * Header-only, allocation-free (fixed arrays on the stack), double only:
 * it runs per contact pair per step, on the solver's threads.
 */
#ifndef tmfdem_discrete_tetrahedron_contact_h
#define tmfdem_discrete_tetrahedron_contact_h

#include <algorithm>
#include <array>
#include <cmath>
#include <tmfdem/discrete/contact_law.h>
#include <tmfdem/discrete/solid.h>

namespace tmfdem
{
  namespace discrete
  {
    /**
     * 6 V grad(lambda_k) of the tetrahedron with nodes @p t (t[k][i]:
     * component i of node k) [m^2]: solid.h's scaled_shape_gradients() on
     * this layout. g[k] is twice the area vector of the face opposite node
     * k, pointing into a positively oriented tetrahedron.
     */
    inline void
    scaled_gradients(const double (&t)[4][3], double (&g)[4][3])
    {
      double by_component[3][4];
      for (unsigned int k = 0; k < 4; ++k)
        for (unsigned int i = 0; i < 3; ++i)
          by_component[i][k] = t[k][i];
      const double *const x[3] = {by_component[0],
                                  by_component[1],
                                  by_component[2]};
      scaled_shape_gradients<3, double>(x, g);
    }

    /**
     * The barycentric coordinates of a tetrahedron as linear functions of
     * position, lambda_k(x) = g_k . (x - o) + c_k, with o its node 0.
     */
    struct TetrahedronCoordinates
    {
      double gradient[4][3]; ///< grad(lambda_k) [1/m]
      double offset[4];      ///< lambda_k at the origin o [-]
      double origin[3];      ///< node 0 [m]
      double volume = 0.;    ///< [m^3]

      /**
       * From the nodes @p t (t[k][i]: component i of node k) [m]. Returns
       * false for a degenerate or inverted tetrahedron (volume <= 0).
       */
      bool
      set(const double (&t)[4][3])
      {
        double g[4][3];
        scaled_gradients(t, g);
        // 6 V = (x3 - x0) . (x1 - x0) x (x2 - x0), g[3] the cross product
        const double det = g[3][0] * (t[3][0] - t[0][0]) +
                           g[3][1] * (t[3][1] - t[0][1]) +
                           g[3][2] * (t[3][2] - t[0][2]);
        if (!(det > 0.))
          return false;
        volume           = det / 6.;
        const double inv = 1. / det;
        for (unsigned int k = 0; k < 4; ++k)
          for (unsigned int i = 0; i < 3; ++i)
            gradient[k][i] = g[k][i] * inv;
        for (unsigned int i = 0; i < 3; ++i)
          origin[i] = t[0][i];
        offset[0] = 1.;
        offset[1] = offset[2] = offset[3] = 0.;
        return true;
      }

      /** lambda_k at the point @p x [m]. */
      double
      operator()(const unsigned int k, const double *x) const
      {
        return gradient[k][0] * (x[0] - origin[0]) +
               gradient[k][1] * (x[1] - origin[1]) +
               gradient[k][2] * (x[2] - origin[2]) + offset[k];
      }
    };

    /**
     * The potential integrals of one contactor face inside one target:
     * I_a = int phi_t N_a dA over the part of the face inside the target
     * (a = 0, 1, 2: the face's nodes) [m^2], J_k = int phi_t lambda_k dA
     * (k = 0..3: the target's nodes) [m^2], and the area of that part
     * [m^2].
     */
    struct FacePotentialIntegrals
    {
      std::array<double, 3> face{{0., 0., 0.}};
      std::array<double, 4> target{{0., 0., 0., 0.}};
      double                clipped_area = 0.;

      /** int phi_t dA [m^2]. */
      double
      total() const
      {
        return face[0] + face[1] + face[2];
      }
    };

    namespace tetrahedron_contact_internal
    {
      /** A vertex of a clipped face: the face's shape functions and the
       *  target's barycentric coordinates there (all linear in position,
       *  so an intersection interpolates them all). */
      struct FaceVertex
      {
        double value[7]; // N_0, N_1, N_2, lambda_0..3
      };

      /** Room for a face clipped by four planes: 7 vertices in exact
       *  arithmetic, the rest for round-off. */
      constexpr unsigned int max_face_vertices = 12;

      /**
       * Sutherland-Hodgman step on a convex polygon of @p n FaceVertex:
       * keeps the part where g = value[i] - value[j] >= 0 (@p j = 7: g =
       * value[i]). Returns the number of vertices written to @p out (0 if
       * fewer than three).
       */
      inline unsigned int
      clip_face(const FaceVertex  *in,
                const unsigned int n,
                const unsigned int i,
                const unsigned int j,
                FaceVertex        *out)
      {
        double g[max_face_vertices];
        for (unsigned int v = 0; v < n; ++v)
          g[v] = in[v].value[i] - (j < 7 ? in[v].value[j] : 0.);
        unsigned int m = 0;
        for (unsigned int v = 0; v < n && m < max_face_vertices; ++v)
          {
            const unsigned int w = v + 1 == n ? 0 : v + 1;
            if (g[v] >= 0.)
              out[m++] = in[v];
            if (((g[v] > 0. && g[w] < 0.) || (g[v] < 0. && g[w] > 0.)) &&
                m < max_face_vertices)
              {
                const double s = g[v] / (g[v] - g[w]);
                for (unsigned int q = 0; q < 7; ++q)
                  out[m].value[q] =
                    in[v].value[q] + s * (in[w].value[q] - in[v].value[q]);
                ++m;
              }
          }
        return m < 3 ? 0 : m;
      }

      /** Area [m^2] of the fan triangle (@p p0, @p p1, @p p2) of a clipped
       *  face of area @p face_area [m^2], from their face coordinates N_1,
       *  N_2 (value[1], value[2]). */
      inline double
      fan_triangle_area(const double *p0,
                        const double *p1,
                        const double *p2,
                        const double  face_area)
      {
        return face_area * std::abs((p1[1] - p0[1]) * (p2[2] - p0[2]) -
                                    (p1[2] - p0[2]) * (p2[1] - p0[1]));
      }

      /** A tetrahedron of a clipped polyhedron: positions and the target's
       *  barycentric coordinates at its four vertices. */
      struct SoupTetrahedron
      {
        double value[4][7]; // vertex: x, y, z, lambda_0..3
      };

      /** Room for the contactor cut by four planes (at most three pieces
       *  per plane and piece: 81). */
      constexpr unsigned int max_soup = 81;

      /** The point on the edge from @p a to @p b where g = 0. */
      inline void
      soup_point(const double *a,
                 const double *b,
                 const double  ga,
                 const double  gb,
                 double       *out)
      {
        const double s = ga / (ga - gb);
        for (unsigned int q = 0; q < 7; ++q)
          out[q] = a[q] + s * (b[q] - a[q]);
      }

      /**
       * The part of the tetrahedra @p in (@p n of them) where g =
       * value[i] - value[j] >= 0 (@p j = 7: g = value[i]) as tetrahedra in
       * @p out; returns their number. A tetrahedron with one vertex inside
       * gives one, with two or three inside a prism, split into three.
       */
      inline unsigned int
      clip_soup(const SoupTetrahedron *in,
                const unsigned int     n,
                const unsigned int     i,
                const unsigned int     j,
                SoupTetrahedron       *out)
      {
        unsigned int m = 0;
        for (unsigned int t = 0; t < n; ++t)
          {
            const SoupTetrahedron &T = in[t];
            double                 g[4];
            unsigned int           inside[4], outside[4], n_in = 0, n_out = 0;
            for (unsigned int v = 0; v < 4; ++v)
              {
                g[v] = T.value[v][i] - (j < 7 ? T.value[v][j] : 0.);
                if (g[v] >= 0.)
                  inside[n_in++] = v;
                else
                  outside[n_out++] = v;
              }
            if (n_in == 0)
              continue;
            if (n_in == 4)
              {
                if (m < max_soup)
                  out[m++] = T;
                continue;
              }
            // the prism of bottom (p0, p1, p2) and top (q0, q1, q2) with
            // edges p_k q_k, as three tetrahedra
            auto add_prism = [&](const double *p0,
                                 const double *p1,
                                 const double *p2,
                                 const double *q0,
                                 const double *q1,
                                 const double *q2) {
              const double *pieces[3][4] = {{p0, p1, p2, q0},
                                            {p1, p2, q0, q1},
                                            {p2, q0, q1, q2}};
              for (const auto &piece : pieces)
                if (m < max_soup)
                  {
                    for (unsigned int v = 0; v < 4; ++v)
                      std::copy(piece[v], piece[v] + 7, out[m].value[v]);
                    ++m;
                  }
            };
            if (n_in == 1)
              {
                const unsigned int a = inside[0];
                if (m < max_soup)
                  {
                    std::copy(T.value[a], T.value[a] + 7, out[m].value[0]);
                    for (unsigned int k = 0; k < 3; ++k)
                      soup_point(T.value[a],
                                 T.value[outside[k]],
                                 g[a],
                                 g[outside[k]],
                                 out[m].value[k + 1]);
                    ++m;
                  }
              }
            else if (n_in == 3)
              {
                // the corner of the one outside vertex d cut off
                const unsigned int d = outside[0];
                double             cut[3][7];
                for (unsigned int k = 0; k < 3; ++k)
                  soup_point(T.value[inside[k]],
                             T.value[d],
                             g[inside[k]],
                             g[d],
                             cut[k]);
                add_prism(T.value[inside[0]],
                          T.value[inside[1]],
                          T.value[inside[2]],
                          cut[0],
                          cut[1],
                          cut[2]);
              }
            else
              {
                // inside a, b; the wedge of (a, ac, ad) and (b, bc, bd)
                const unsigned int a = inside[0], b = inside[1];
                const unsigned int c = outside[0], d = outside[1];
                double             ac[7], ad[7], bc[7], bd[7];
                soup_point(T.value[a], T.value[c], g[a], g[c], ac);
                soup_point(T.value[a], T.value[d], g[a], g[d], ad);
                soup_point(T.value[b], T.value[c], g[b], g[c], bc);
                soup_point(T.value[b], T.value[d], g[b], g[d], bd);
                add_prism(T.value[a], ac, ad, T.value[b], bc, bd);
              }
          }
        return m;
      }

      /**
       * The part of @p base (@p n_base items: a face polygon of FaceVertex
       * or a set of SoupTetrahedron, the target's coordinates at index
       * 3 + k of their values) inside the target's sub-tetrahedron @p m
       * (lambda_m >= 0, lambda_j >= lambda_m), cut with @p clip
       * (clip_face() or clip_soup()) through the two @p buffers. Returns
       * the number of items and points @p result at them.
       */
      template <typename Item, std::size_t room, typename Clip>
      inline unsigned int
      clip_to_subtetrahedron(const Item        *base,
                             const unsigned int n_base,
                             const unsigned int m,
                             Item (&buffers)[2][room],
                             const Clip  &clip,
                             const Item *&result)
      {
        unsigned int n       = clip(base, n_base, 3 + m, 7, buffers[0]);
        unsigned int current = 0;
        for (unsigned int j = 0; j < 4 && n > 0; ++j)
          if (j != m)
            {
              n = clip(buffers[current], n, 3 + j, 3 + m, buffers[1 - current]);
              current = 1 - current;
            }
        result = buffers[current];
        return n;
      }

      /** |volume| of a soup tetrahedron [m^3]. */
      inline double
      soup_volume(const SoupTetrahedron &T)
      {
        double e[3][3];
        for (unsigned int k = 0; k < 3; ++k)
          for (unsigned int i = 0; i < 3; ++i)
            e[k][i] = T.value[k + 1][i] - T.value[0][i];
        const double det = e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) -
                           e[0][1] * (e[1][0] * e[2][2] - e[1][2] * e[2][0]) +
                           e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0]);
        return std::abs(det) / 6.;
      }

      /** Overlaps shallower than this fraction of the tetrahedra's size
       *  count as touching (no force): the round-off of coincident nodes.
       *  Their force would be below p A 1e-12 [N]. */
      constexpr double touching_tolerance = 1e-12;

      /** Whether the tetrahedron @p c (nodes c[k]) and the target overlap
       *  in no volume: all its nodes on the outside of one face's plane or
       *  on it (a shared vertex, edge or face: the overlap lies in the
       *  plane, its energy and forces are zero). */
      inline bool
      separated(const TetrahedronCoordinates &target, const double (&c)[4][3])
      {
        for (unsigned int k = 0; k < 4; ++k)
          if (target(k, c[0]) <= touching_tolerance &&
              target(k, c[1]) <= touching_tolerance &&
              target(k, c[2]) <= touching_tolerance &&
              target(k, c[3]) <= touching_tolerance)
            return true;
        return false;
      }

      /** Whether a plane along the cross product of an edge of @p a and an
       *  edge of @p b (nodes [k][i]) separates them, touching counted as
       *  separated (the edge-edge axes of the separating-axis theorem; the
       *  face planes are separated()'s). */
      inline bool
      separated_by_edge_pair(const double (&a)[4][3], const double (&b)[4][3])
      {
        static constexpr unsigned int edges[6][2] =
          {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
        for (const auto &ea : edges)
          {
            const double u[3] = {a[ea[1]][0] - a[ea[0]][0],
                                 a[ea[1]][1] - a[ea[0]][1],
                                 a[ea[1]][2] - a[ea[0]][2]};
            for (const auto &eb : edges)
              {
                const double w[3] = {b[eb[1]][0] - b[eb[0]][0],
                                     b[eb[1]][1] - b[eb[0]][1],
                                     b[eb[1]][2] - b[eb[0]][2]};
                const double n[3] = {u[1] * w[2] - u[2] * w[1],
                                     u[2] * w[0] - u[0] * w[2],
                                     u[0] * w[1] - u[1] * w[0]};
                // parallel edges give no axis (the face planes cover that
                // direction); a zero axis would project both to one point
                const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
                const double uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2];
                const double ww = w[0] * w[0] + w[1] * w[1] + w[2] * w[2];
                if (!(nn > 1e-24 * uu * ww))
                  continue;
                double lo_a = 1e300, hi_a = -1e300, lo_b = 1e300, hi_b = -1e300;
                for (unsigned int k = 0; k < 4; ++k)
                  {
                    const double pa =
                      n[0] * a[k][0] + n[1] * a[k][1] + n[2] * a[k][2];
                    const double pb =
                      n[0] * b[k][0] + n[1] * b[k][1] + n[2] * b[k][2];
                    lo_a = std::min(lo_a, pa);
                    hi_a = std::max(hi_a, pa);
                    lo_b = std::min(lo_b, pb);
                    hi_b = std::max(hi_b, pb);
                  }
                const double tolerance =
                  touching_tolerance * (hi_a - lo_a + hi_b - lo_b);
                if (hi_a <= lo_b + tolerance || hi_b <= lo_a + tolerance)
                  return true;
              }
          }
        return false;
      }

      /** The contactor @p c (nodes [k][i]) as one soup tetrahedron carrying
       *  the target's barycentric coordinates at its vertices. */
      inline SoupTetrahedron
      contactor_soup(const double (&c)[4][3],
                     const TetrahedronCoordinates &target)
      {
        SoupTetrahedron base;
        for (unsigned int v = 0; v < 4; ++v)
          {
            for (unsigned int i = 0; i < 3; ++i)
              base.value[v][i] = c[v][i];
            for (unsigned int k = 0; k < 4; ++k)
              base.value[v][3 + k] = target(k, c[v]);
          }
        return base;
      }
    } // namespace tetrahedron_contact_internal

    /** The three nodes of the face of a tetrahedron opposite node @p f,
     *  in ascending order. */
    inline std::array<unsigned int, 3>
    tetrahedron_face_nodes(const unsigned int f)
    {
      static constexpr unsigned int faces[4][3] = {{1, 2, 3},
                                                   {0, 2, 3},
                                                   {0, 1, 3},
                                                   {0, 1, 2}};
      return {{faces[f][0], faces[f][1], faces[f][2]}};
    }

    /** The face opposite node @p f of the tetrahedron @p c (nodes [k][i])
     *  as three vertices for clipping: the face's shape functions and the
     *  barycentric coordinates of @p target at its nodes. */
    inline void
    face_vertices(const double (&c)[4][3],
                  const unsigned int            f,
                  const TetrahedronCoordinates &target,
                  tetrahedron_contact_internal::FaceVertex (&base)[3])
    {
      const std::array<unsigned int, 3> face = tetrahedron_face_nodes(f);
      for (unsigned int v = 0; v < 3; ++v)
        {
          for (unsigned int a = 0; a < 3; ++a)
            base[v].value[a] = a == v ? 1. : 0.;
          for (unsigned int k = 0; k < 4; ++k)
            base[v].value[3 + k] = target(k, c[face[v]]);
        }
    }

    /**
     * The unit outward normal @p n of the face opposite node @p f of a
     * positively oriented tetrahedron with scaled gradients @p g
     * (scaled_gradients()); returns the face's area [m^2].
     */
    inline double
    outward_face_normal(const double (&g)[4][3],
                        const unsigned int f,
                        double            *n)
    {
      const double length =
        std::sqrt(g[f][0] * g[f][0] + g[f][1] * g[f][1] + g[f][2] * g[f][2]);
      for (unsigned int i = 0; i < 3; ++i)
        n[i] = -g[f][i] / length;
      return 0.5 * length;
    }

    /**
     * The potential integrals of the face opposite node @p f of the
     * contactor @p c (nodes c[k][i]) [m], scaled gradients @p g
     * (scaled_gradients()), inside the target of coordinates
     * @p target (FacePotentialIntegrals). Returns false if the face does
     * not enter the target.
     */
    inline bool
    face_potential_integrals(const double (&c)[4][3],
                             const double (&g)[4][3],
                             const unsigned int            f,
                             const TetrahedronCoordinates &target,
                             FacePotentialIntegrals       &result)
    {
      using namespace tetrahedron_contact_internal;
      FaceVertex base[3];
      face_vertices(c, f, target, base);
      // quick rejection: the whole face outside one target face
      for (unsigned int k = 0; k < 4; ++k)
        if (base[0].value[3 + k] <= 0. && base[1].value[3 + k] <= 0. &&
            base[2].value[3 + k] <= 0.)
          return false;
      const double face_area =
        0.5 *
        std::sqrt(g[f][0] * g[f][0] + g[f][1] * g[f][1] + g[f][2] * g[f][2]);
      result       = FacePotentialIntegrals();
      bool entered = false;
      for (unsigned int m = 0; m < 4; ++m)
        {
          // the sub-tetrahedron of face m: lambda_m >= 0, lambda_j >=
          // lambda_m
          FaceVertex         buffer[2][max_face_vertices];
          const FaceVertex  *P = nullptr;
          const unsigned int n =
            clip_to_subtetrahedron(base, 3, m, buffer, clip_face, P);
          if (n == 0)
            continue;
          // fan from vertex 0; the area from the face coordinates N_1, N_2
          for (unsigned int v = 1; v + 1 < n; ++v)
            {
              const double *p0 = P[0].value, *p1 = P[v].value,
                           *p2  = P[v + 1].value;
              const double area = fan_triangle_area(p0, p1, p2, face_area);
              if (!(area > 0.))
                continue;
              entered = true;
              result.clipped_area += area;
              // edge midpoints: exact for the quadratic phi N
              const double *ends[3][2] = {{p0, p1}, {p1, p2}, {p2, p0}};
              for (const auto &edge : ends)
                {
                  double mid[7];
                  for (unsigned int q = 0; q < 7; ++q)
                    mid[q] = 0.5 * (edge[0][q] + edge[1][q]);
                  const double phi = 4. * std::max(mid[3 + m], 0.) * area / 3.;
                  for (unsigned int a = 0; a < 3; ++a)
                    result.face[a] += phi * mid[a];
                  for (unsigned int k = 0; k < 4; ++k)
                    result.target[k] += phi * mid[3 + k];
                }
            }
        }
      return entered;
    }

    /**
     * Adds to @p ft (twelve components, node k component i at 3 k + i) the
     * forces on the target's nodes of the normal contact energy E_t = p
     * int_{c cap t} phi_t dV of the contactor @p c in the target @p t
     * (nodes [k][i], positively oriented) [m], @p penalty p [Pa]: exactly
     * minus its gradient with respect to the target's nodes [N]. Returns
     * E_t [J].
     */
    inline double
    add_target_potential_forces_3d(const double (&c)[4][3],
                                   const TetrahedronCoordinates &target,
                                   const double                  penalty,
                                   double                       *ft)
    {
      using namespace tetrahedron_contact_internal;
      if (separated(target, c))
        return 0.;
      const SoupTetrahedron base   = contactor_soup(c, target);
      double                energy = 0.;
      for (unsigned int m = 0; m < 4; ++m)
        {
          SoupTetrahedron        buffer[2][max_soup];
          const SoupTetrahedron *pieces = nullptr;
          const unsigned int     n =
            clip_to_subtetrahedron(&base, 1, m, buffer, clip_soup, pieces);
          if (n == 0)
            continue;
          // int_{V_m} lambda_k dV: volume times the mean at the vertices
          double lambda_integral[4] = {0., 0., 0., 0.};
          for (unsigned int t = 0; t < n; ++t)
            {
              const SoupTetrahedron &T = pieces[t];
              const double           w = 0.25 * soup_volume(T);
              for (unsigned int k = 0; k < 4; ++k)
                lambda_integral[k] +=
                  w * (T.value[0][3 + k] + T.value[1][3 + k] +
                       T.value[2][3 + k] + T.value[3][3 + k]);
            }
          const double g = 4. * penalty;
          for (unsigned int j = 0; j < 4; ++j)
            for (unsigned int i = 0; i < 3; ++i)
              ft[3 * j + i] += g * target.gradient[m][i] * lambda_integral[j];
          energy += g * lambda_integral[m];
        }
      return energy;
    }

    /**
     * The volume of the overlap of the tetrahedron @p c (nodes [k][i]) [m]
     * and the target of coordinates @p target [m^3]: @p c clipped by the
     * target's four face planes (exact).
     */
    inline double
    overlap_volume_3d(const double (&c)[4][3],
                      const TetrahedronCoordinates &target)
    {
      using namespace tetrahedron_contact_internal;
      if (separated(target, c))
        return 0.;
      const SoupTetrahedron  base = contactor_soup(c, target);
      SoupTetrahedron        buffers[2][max_soup];
      const SoupTetrahedron *pieces = &base;
      unsigned int           n      = 1;
      for (unsigned int k = 0; k < 4 && n > 0; ++k)
        {
          n      = clip_soup(pieces, n, 3 + k, 7, buffers[k % 2]);
          pieces = buffers[k % 2];
        }
      double volume = 0.;
      for (unsigned int t = 0; t < n; ++t)
        volume += soup_volume(pieces[t]);
      return volume;
    }

    /**
     * The normal contact energy p int_{c cap t} phi_t dV of the contactor
     * @p c in the target @p t [J] (@p penalty [Pa], nodes [m]), computed
     * as add_target_potential_forces_3d() computes it.
     */
    inline double
    contact_energy_3d(const double (&c)[4][3],
                      const TetrahedronCoordinates &target,
                      const double                  penalty)
    {
      double unused[12] = {};
      return add_target_potential_forces_3d(c, target, penalty, unused);
    }

    /**
     * Adds to @p fc (twelve components) the normal force -p n_f I_a on the
     * nodes a of the face opposite node @p f of the contactor of scaled
     * gradients @p g, whose integrals inside the target are @p integrals
     * (face_potential_integrals()), @p penalty p [Pa] [N].
     */
    inline void
    add_face_normal_forces_3d(const double (&g)[4][3],
                              const unsigned int            f,
                              const FacePotentialIntegrals &integrals,
                              const double                  penalty,
                              double                       *fc)
    {
      const std::array<unsigned int, 3> face = tetrahedron_face_nodes(f);
      double                            n[3];
      outward_face_normal(g, f, n);
      for (unsigned int a = 0; a < 3; ++a)
        for (unsigned int i = 0; i < 3; ++i)
          fc[3 * face[a] + i] -= penalty * integrals.face[a] * n[i];
    }

    /**
     * Adds to @p fc (twelve components) the normal forces on the
     * contactor's nodes of E_t = p int_{c cap t} phi_t dV: for each face of
     * @p c, -p n_f I_a on its node a (face_potential_integrals()) [N].
     * The face integrals go to @p integrals (one per face, zero where the
     * face does not enter) for the friction and the target's reaction.
     */
    inline void
    add_contactor_potential_forces_3d(
      const double (&c)[4][3],
      const TetrahedronCoordinates          &target,
      const double                           penalty,
      double                                *fc,
      std::array<FacePotentialIntegrals, 4> &integrals)
    {
      double g[4][3];
      scaled_gradients(c, g);
      for (unsigned int f = 0; f < 4; ++f)
        {
          if (!face_potential_integrals(c, g, f, target, integrals[f]))
            {
              integrals[f] = FacePotentialIntegrals();
              continue;
            }
          add_face_normal_forces_3d(g, f, integrals[f], penalty, fc);
        }
    }

    /**
     * The friction history of one contactor face inside one target
     * (add_face_friction_3d()): its elastic slip vector, and with the
     * regularised law the friction strength and the slip rate it remembers
     * (PenaltyCoulombContact::friction_limit(), as EdgeFriction in 2D).
     */
    struct FaceFriction
    {
      /** Elastic slip of the tangential spring, in the face's plane [m]. */
      double slip[3] = {0., 0., 0.};
      /** Friction strength S that follows mu N over the memory slip (plain
       *  Coulomb: unused, 0) [N]. */
      double strength = 0.;
      /** Slip rate that the rate effect compares with (plain Coulomb:
       *  unused, 0) [m/s]. */
      double remembered_rate = 0.;
    };

    /**
     * Friction of the face opposite node @p f of the contactor of scaled
     * gradients @p g (scaled_gradients()) inside the target (@p integrals of
     * that face, face_potential_integrals()) with the law @p law: a
     * tangential spring of stiffness p_t A_clipped / sqrt(A_face) [N/m] on
     * the elastic slip of @p history (projected onto the current face plane,
     * advanced by the tangential relative velocity over @p dt [s]), capped
     * at PenaltyCoulombContact::friction_limit() of mu times the normal
     * force p int phi_t dA (plain Coulomb, or the regularised law with its
     * strength and remembered rate in @p history). The velocities are those
     * of the contactor's face (@p vc, weights I_a / sum I) and of the target
     * (@p vt, weights J_k / sum J) at the centroid of the normal force,
     * where both tangential forces act (no torque). Adds the forces to @p fc
     * and @p ft (twelve components each) [N]; returns the energy dissipated
     * over the step [J].
     */
    inline double
    add_face_friction_3d(const double (&g)[4][3],
                         const double (&vc)[4][3],
                         const double (&vt)[4][3],
                         const unsigned int            f,
                         const FacePotentialIntegrals &integrals,
                         const PenaltyCoulombContact  &law,
                         const double                  dt,
                         FaceFriction                 &history,
                         double                       *fc,
                         double                       *ft)
    {
      const double total = integrals.total();
      if (!(total > 0.) || !(law.friction > 0.))
        {
          history = FaceFriction();
          return 0.;
        }
      const std::array<unsigned int, 3> face = tetrahedron_face_nodes(f);
      double                            n[3];
      const double face_area = outward_face_normal(g, f, n);
      double       u[3], l[4];
      for (unsigned int a = 0; a < 3; ++a)
        u[a] = integrals.face[a] / total;
      const double target_total = integrals.target[0] + integrals.target[1] +
                                  integrals.target[2] + integrals.target[3];
      for (unsigned int k = 0; k < 4; ++k)
        l[k] = integrals.target[k] / target_total;
      double relative[3] = {0., 0., 0.};
      for (unsigned int i = 0; i < 3; ++i)
        {
          for (unsigned int a = 0; a < 3; ++a)
            relative[i] += u[a] * vc[face[a]][i];
          for (unsigned int k = 0; k < 4; ++k)
            relative[i] -= l[k] * vt[k][i];
        }
      // trial slip: the old one projected onto the plane, plus the
      // tangential relative motion of the step
      double       trial[3], tangential_rate[3];
      const double old_normal = history.slip[0] * n[0] +
                                history.slip[1] * n[1] + history.slip[2] * n[2];
      const double rate_normal =
        relative[0] * n[0] + relative[1] * n[1] + relative[2] * n[2];
      for (unsigned int i = 0; i < 3; ++i)
        {
          tangential_rate[i] = relative[i] - rate_normal * n[i];
          trial[i] =
            history.slip[i] - old_normal * n[i] + tangential_rate[i] * dt;
        }
      const double trial_length = std::sqrt(
        trial[0] * trial[0] + trial[1] * trial[1] + trial[2] * trial[2]);
      const double slip_rate =
        std::sqrt(tangential_rate[0] * tangential_rate[0] +
                  tangential_rate[1] * tangential_rate[1] +
                  tangential_rate[2] * tangential_rate[2]);
      const double stiffness =
        law.tangential_penalty * integrals.clipped_area / std::sqrt(face_area);
      const double limit =
        law.friction_limit(law.friction * law.normal_penalty * total,
                           slip_rate,
                           dt,
                           history);
      double scale      = 1.;
      double dissipated = 0.;
      if (stiffness * trial_length > limit)
        {
          scale      = limit / (stiffness * trial_length);
          dissipated = limit * (1. - scale) * trial_length;
        }
      for (unsigned int i = 0; i < 3; ++i)
        {
          history.slip[i]         = scale * trial[i];
          const double tangential = -stiffness * history.slip[i];
          for (unsigned int a = 0; a < 3; ++a)
            fc[3 * face[a] + i] += u[a] * tangential;
          for (unsigned int k = 0; k < 4; ++k)
            ft[3 * k + i] -= l[k] * tangential;
        }
      return dissipated;
    }

    /**
     * Whether a plane separates the tetrahedra @p x[0] and @p x[1] (nodes
     * [k][i]) [m] with a gap wider than @p gap [m] between them: along the
     * normal of a face of either, or along the cross product of an edge of
     * each (the axes of the separating-axis theorem, each made a unit
     * vector). The contact search drops such pairs: while every node moves
     * less than half the search buffer, two tetrahedra more than the
     * buffer apart along a fixed direction cannot meet.
     */
    inline bool
    tetrahedra_apart_by_more_than(const double (&x)[2][4][3], const double gap)
    {
      static constexpr unsigned int edges[6][2] =
        {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
      // the gap between the projections onto the axis n (any length)
      const auto apart_along = [&](const double(&n)[3]) {
        const double nn = n[0] * n[0] + n[1] * n[1] + n[2] * n[2];
        if (!(nn > 0.))
          return false;
        double lo[2] = {1e300, 1e300}, hi[2] = {-1e300, -1e300};
        for (unsigned int side = 0; side < 2; ++side)
          for (unsigned int k = 0; k < 4; ++k)
            {
              const double p = n[0] * x[side][k][0] + n[1] * x[side][k][1] +
                               n[2] * x[side][k][2];
              lo[side] = std::min(lo[side], p);
              hi[side] = std::max(hi[side], p);
            }
        const double width = gap * std::sqrt(nn);
        return lo[1] - hi[0] > width || lo[0] - hi[1] > width;
      };
      const auto edge =
        [&](const unsigned int side, const unsigned int e, double(&u)[3]) {
          for (unsigned int i = 0; i < 3; ++i)
            u[i] = x[side][edges[e][1]][i] - x[side][edges[e][0]][i];
        };
      const auto cross =
        [](const double(&u)[3], const double(&w)[3], double(&n)[3]) {
          n[0] = u[1] * w[2] - u[2] * w[1];
          n[1] = u[2] * w[0] - u[0] * w[2];
          n[2] = u[0] * w[1] - u[1] * w[0];
        };
      // face normals: edges (0,1) x (0,2), (0,1) x (0,3), (0,2) x (0,3),
      // (1,2) x (1,3)
      static constexpr unsigned int faces[4][2] = {{0, 1},
                                                   {0, 2},
                                                   {1, 2},
                                                   {3, 4}};
      double                        u[3], w[3], n[3];
      for (unsigned int side = 0; side < 2; ++side)
        for (const auto &f : faces)
          {
            edge(side, f[0], u);
            edge(side, f[1], w);
            cross(u, w, n);
            if (apart_along(n))
              return true;
          }
      for (unsigned int ea = 0; ea < 6; ++ea)
        {
          edge(0, ea, u);
          for (unsigned int eb = 0; eb < 6; ++eb)
            {
              edge(1, eb, w);
              cross(u, w, n);
              if (apart_along(n))
                return true;
            }
        }
      return false;
    }

    /** Whether the axis-aligned boxes of the tetrahedra @p x[0] and
     *  @p x[1] (nodes [k][i]) [m] overlap (touching counted as apart). */
    inline bool
    tetrahedron_boxes_overlap(const double (&x)[2][4][3])
    {
      for (unsigned int i = 0; i < 3; ++i)
        {
          double lo[2], hi[2];
          for (unsigned int side = 0; side < 2; ++side)
            {
              lo[side] = hi[side] = x[side][0][i];
              for (unsigned int k = 1; k < 4; ++k)
                {
                  lo[side] = std::min(lo[side], x[side][k][i]);
                  hi[side] = std::max(hi[side], x[side][k][i]);
                }
            }
          if (hi[0] <= lo[1] || hi[1] <= lo[0])
            return false;
        }
      return true;
    }

    /**
     * Whether the tetrahedra @p x[0] and @p x[1] (nodes [k][i], positively
     * oriented) [m] overlap in a volume: false if their boxes do not
     * overlap (tetrahedron_boxes_overlap()), if either is degenerate, or if a
     * plane separates them (a face plane of either, or a plane along an edge of
     * each: the separating-axis theorem for two convex polyhedra), touching
     * counted as separated (touching_tolerance). Sets @p coordinates to their
     * barycentric coordinates where it gets that far.
     */
    inline bool
    tetrahedra_overlap(const double (&x)[2][4][3],
                       TetrahedronCoordinates (&coordinates)[2])
    {
      using tetrahedron_contact_internal::separated;
      if (!tetrahedron_boxes_overlap(x))
        return false;
      return coordinates[0].set(x[0]) && coordinates[1].set(x[1]) &&
             !separated(coordinates[1], x[0]) &&
             !separated(coordinates[0], x[1]) &&
             !tetrahedron_contact_internal::separated_by_edge_pair(x[0], x[1]);
    }

    /** The friction history of a pair of tetrahedra: entry 4 direction +
     *  face, direction 0 the first tetrahedron the contactor. */
    using TetrahedronPairFriction = std::array<FaceFriction, 8>;

    /**
     * All contact forces of a pair of tetrahedra with the law @p law: each
     * tetrahedron once the contactor in the other (direction 0: @p x[0] in
     * @p x[1]), the normal forces of the energy E_t + E_c (the contactor's
     * face forces, and on the target minus the gradient of E_t, or with
     * PenaltyCoulombContact::potential_gradient_on_target = false the
     * reaction of each face's force with the weights J_k), and the
     * friction of every contactor face inside its target
     * (add_face_friction_3d(), the histories in @p friction, reset where a
     * face leaves). @p x, @p v: nodes [m] and velocities [m/s] of the two
     * (x[side][k][i], positively oriented), which overlap:
     * tetrahedra_overlap() has returned true and set their barycentric
     * @p coordinates. Adds the forces to @p force
     * (the first's twelve components, then the second's) [N]; returns the
     * energy friction dissipated over the step @p dt [s] [J].
     */
    inline double
    add_overlapping_pair_forces_3d(
      const double (&x)[2][4][3],
      const TetrahedronCoordinates (&coordinates)[2],
      const double (&v)[2][4][3],
      const PenaltyCoulombContact &law,
      const double                 dt,
      TetrahedronPairFriction     &friction,
      double                      *force)
    {
      double dissipated = 0.;
      for (unsigned int direction = 0; direction < 2; ++direction)
        {
          const unsigned int c = direction, t = 1 - direction;
          double            *fc = force + 12 * c, *ft = force + 12 * t;
          const TetrahedronCoordinates &target = coordinates[t];
          double                        g[4][3];
          scaled_gradients(x[c], g);
          for (unsigned int f = 0; f < 4; ++f)
            {
              FaceFriction          &history = friction[4 * direction + f];
              FacePotentialIntegrals integrals;
              if (!face_potential_integrals(x[c], g, f, target, integrals))
                {
                  history = FaceFriction(); // the face left the target
                  continue;
                }
              add_face_normal_forces_3d(g,
                                        f,
                                        integrals,
                                        law.normal_penalty,
                                        fc);
              if (!law.potential_gradient_on_target)
                {
                  double n[3];
                  outward_face_normal(g, f, n);
                  for (unsigned int k = 0; k < 4; ++k)
                    for (unsigned int i = 0; i < 3; ++i)
                      ft[3 * k + i] +=
                        law.normal_penalty * integrals.target[k] * n[i];
                }
              dissipated += add_face_friction_3d(g,
                                                 v[c],
                                                 v[t],
                                                 f,
                                                 integrals,
                                                 law,
                                                 dt,
                                                 history,
                                                 fc,
                                                 ft);
            }
          // the target's share, also where it lies inside the contactor
          // with no face of the contactor entering it
          if (law.potential_gradient_on_target)
            add_target_potential_forces_3d(x[c],
                                           target,
                                           law.normal_penalty,
                                           ft);
        }
      return dissipated;
    }

    /**
     * add_overlapping_pair_forces_3d() for a pair that may not overlap: no
     * force, and the friction history reset, where tetrahedra_overlap()
     * finds the pair apart or touching.
     */
    inline double
    add_pair_forces_3d(const double (&x)[2][4][3],
                       const double (&v)[2][4][3],
                       const PenaltyCoulombContact &law,
                       const double                 dt,
                       TetrahedronPairFriction     &friction,
                       double                      *force)
    {
      TetrahedronCoordinates coordinates[2];
      if (!tetrahedra_overlap(x, coordinates))
        {
          friction = TetrahedronPairFriction();
          return 0.;
        }
      return add_overlapping_pair_forces_3d(x,
                                            coordinates,
                                            v,
                                            law,
                                            dt,
                                            friction,
                                            force);
    }

    /** The normal contact energy E_t + E_c of a pair of tetrahedra (nodes
     *  @p x as in add_pair_forces_3d()) with the penalty @p penalty [Pa]
     *  [J]. */
    inline double
    pair_contact_energy_3d(const double (&x)[2][4][3], const double penalty)
    {
      double energy = 0.;
      for (unsigned int direction = 0; direction < 2; ++direction)
        {
          TetrahedronCoordinates target;
          if (target.set(x[1 - direction]))
            energy += contact_energy_3d(x[direction], target, penalty);
        }
      return energy;
    }
  } // namespace discrete
} // namespace tmfdem

#endif
