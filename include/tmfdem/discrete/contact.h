/**
 * @file
 * Contact between triangles (paper Sec. 2.3, theory manual "Contact"):
 * Munjiza's potential phi = 3 min(lambda_0, lambda_1, lambda_2) (paper
 * Eq. 4, 1 at the centroid, 0 on the edges), the distributed force
 * p grad(phi_c - phi_t) dA (Eq. 5) turned by the divergence theorem into
 * integrals of phi_t along the contactor's edges inside the target (and vice
 * versa), integrated exactly: phi is piecewise linear along an edge, the
 * shape functions are linear, so Simpson's rule on each linear piece is
 * exact. The broad phase is a linked-cell grid (NBS type). The forces
 * these integrals give, with Coulomb friction (Eq. 6), are the contact law
 * of contact_law.h; when the search runs again (the accumulated travel
 * passes half the buffer) is decided by ContactSystem (contact_system.h).
 */
#ifndef tmfdem_discrete_contact_h
#define tmfdem_discrete_contact_h

#include <algorithm>
#include <array>
#include <cmath>
#include <tmfdem/base/threads.h>
#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    /**
     * Integrals along a contactor edge P->Q of the target's potential,
     * u in [0, 1] the edge parameter (multiply by the edge length to get
     * lengths): phi_start = int phi (1-u) du, phi_end = int phi u du,
     * phi_target[k] = int phi lambda_k du.
     */
    struct EdgePotentialIntegrals
    {
      double                phi_start = 0., phi_end = 0.;
      std::array<double, 3> phi_target{{0., 0., 0.}};
      double                clipped_length_fraction = 0.;

      double
      total() const
      {
        return phi_start + phi_end;
      }
    };

    /**
     * Exact integrals of the target triangle's potential (nodes
     * @p tx, @p ty, counter-clockwise) along the segment (px,py)->(qx,qy).
     * Returns false if the segment does not enter the target.
     */
    inline bool
    edge_potential_integrals(const double            px,
                             const double            py,
                             const double            qx,
                             const double            qy,
                             const double           *tx,
                             const double           *ty,
                             EdgePotentialIntegrals &result)
    {
      const double det =
        (ty[1] - ty[2]) * (tx[0] - tx[2]) + (tx[2] - tx[1]) * (ty[0] - ty[2]);
      if (!(det > 0.))
        return false;
      const double inv = 1. / det;
      // barycentric coordinates of P and Q
      double lp[3], lq[3];
      lp[0] =
        ((ty[1] - ty[2]) * (px - tx[2]) + (tx[2] - tx[1]) * (py - ty[2])) * inv;
      lp[1] =
        ((ty[2] - ty[0]) * (px - tx[2]) + (tx[0] - tx[2]) * (py - ty[2])) * inv;
      lp[2] = 1. - lp[0] - lp[1];
      lq[0] =
        ((ty[1] - ty[2]) * (qx - tx[2]) + (tx[2] - tx[1]) * (qy - ty[2])) * inv;
      lq[1] =
        ((ty[2] - ty[0]) * (qx - tx[2]) + (tx[0] - tx[2]) * (qy - ty[2])) * inv;
      lq[2] = 1. - lq[0] - lq[1];
      // quick rejection: both ends outside the same edge
      for (unsigned int k = 0; k < 3; ++k)
        if (lp[k] <= 0. && lq[k] <= 0.)
          return false;
      double a[3], b[3];
      double u0 = 0., u1 = 1.;
      for (unsigned int k = 0; k < 3; ++k)
        {
          a[k] = lp[k];
          b[k] = lq[k] - lp[k];
          if (b[k] > 0.)
            u0 = std::max(u0, -a[k] / b[k]);
          else if (b[k] < 0.)
            u1 = std::min(u1, -a[k] / b[k]);
          else if (a[k] < 0.)
            return false;
        }
      if (!(u1 > u0))
        return false;
      // breakpoints of min(lambda) inside (u0, u1)
      double       knots[5];
      unsigned int n_knots = 0;
      knots[n_knots++]     = u0;
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int j = i + 1; j < 3; ++j)
          {
            const double db = b[i] - b[j];
            if (db != 0.)
              {
                const double u = (a[j] - a[i]) / db;
                if (u > u0 && u < u1)
                  knots[n_knots++] = u;
              }
          }
      knots[n_knots++] = u1;
      // sort the (at most three) interior breakpoints: insertion sort
      for (unsigned int i = 2; i + 1 < n_knots; ++i)
        for (unsigned int k = i; k > 1 && knots[k] < knots[k - 1]; --k)
          std::swap(knots[k], knots[k - 1]);

      result                         = EdgePotentialIntegrals();
      result.clipped_length_fraction = u1 - u0;
      auto add_point = [&](const double u, const double weight) {
        const double l0  = a[0] + b[0] * u;
        const double l1  = a[1] + b[1] * u;
        const double l2  = a[2] + b[2] * u;
        double       phi = std::min(l0, std::min(l1, l2));
        phi              = 3. * std::max(phi, 0.) * weight;
        result.phi_start += phi * (1. - u);
        result.phi_end += phi * u;
        result.phi_target[0] += phi * l0;
        result.phi_target[1] += phi * l1;
        result.phi_target[2] += phi * l2;
      };
      for (unsigned int piece = 0; piece + 1 < n_knots; ++piece)
        {
          const double ua = knots[piece], ub = knots[piece + 1];
          const double w = (ub - ua) / 6.;
          add_point(ua, w);
          add_point(0.5 * (ua + ub), 4. * w);
          add_point(ub, w);
        }
      return true;
    }

    namespace contact_internal
    {
      /** Room for the vertices of a clipped polygon: a triangle cut by five
       *  lines has at most 8 in exact arithmetic; the rest for round-off. */
      constexpr unsigned int max_clipped_vertices = 16;

      /**
       * Sutherland-Hodgman step: the part of the convex polygon (@p px,
       * @p py [m], @p n vertices) where g = @p a x + @p b y + @p c >= 0,
       * written to (@p qx, @p qy). An intersection point is inserted where
       * an edge crosses g = 0 strictly. Returns the number of vertices
       * written (at most max_clipped_vertices).
       */
      inline unsigned int
      clip_polygon(const double      *px,
                   const double      *py,
                   const unsigned int n,
                   const double       a,
                   const double       b,
                   const double       c,
                   double            *qx,
                   double            *qy)
      {
        double g[max_clipped_vertices];
        for (unsigned int i = 0; i < n; ++i)
          g[i] = a * px[i] + b * py[i] + c;
        unsigned int m = 0;
        for (unsigned int i = 0; i < n && m < max_clipped_vertices; ++i)
          {
            const unsigned int j = i + 1 == n ? 0 : i + 1;
            if (g[i] >= 0.)
              {
                qx[m] = px[i];
                qy[m] = py[i];
                ++m;
              }
            if (((g[i] > 0. && g[j] < 0.) || (g[i] < 0. && g[j] > 0.)) &&
                m < max_clipped_vertices)
              {
                const double t = g[i] / (g[i] - g[j]);
                qx[m]          = px[i] + t * (px[j] - px[i]);
                qy[m]          = py[i] + t * (py[j] - py[i]);
                ++m;
              }
          }
        return m < 3 ? 0 : m;
      }
    } // namespace contact_internal

    /**
     * The forces on the target's nodes of the normal contact energy
     * E_t = p int_S phi_t dA (S the overlap of contactor and target,
     * phi_t the target's potential) [N/m]: exactly minus its gradient with
     * respect to the target's nodes, added to @p ft (six components).
     * Together with the contactor's forces from the edge integrals
     * (edge_potential_integrals(), which are exactly minus the gradient of
     * E_t with respect to the contactor's nodes) the pair's normal force is
     * conservative for any motion of the six nodes, deformation included
     * (theory manual 5.5).
     *
     * In the part S_k of S where phi_t = 3 lambda_k (lambda_k the smallest
     * barycentric coordinate), moving target node j by dv changes phi_t by
     * -3 lambda_j grad(lambda_k) . dv at a fixed point, and the target's
     * moving boundary adds nothing (phi_t = 0 there), so
     *
     *   f_j = 3 p sum_k grad(lambda_k) int_{S_k} lambda_j dA,
     *
     * exact with the area and first moments of the polygons S_k (the
     * contactor clipped by the target's three edges and by the two lines
     * through the target's centroid that bound S_k). @p cx, @p cy: the
     * contactor's nodes, @p tx, @p ty: the target's (counter-clockwise)
     * [m]; @p penalty: p [Pa]. Returns E_t [J/m], 3 p sum_k int_{S_k}
     * lambda_k dA.
     */
    inline double
    add_target_potential_forces(const double *cx,
                                const double *cy,
                                const double *tx,
                                const double *ty,
                                const double  penalty,
                                double       *ft)
    {
      using contact_internal::clip_polygon;
      using contact_internal::max_clipped_vertices;
      const double det =
        (ty[1] - ty[2]) * (tx[0] - tx[2]) + (tx[2] - tx[1]) * (ty[0] - ty[2]);
      if (!(det > 0.))
        return 0.;
      const double inv = 1. / det;
      // lambda_k = alpha_k x + beta_k y + gamma_k in coordinates relative to
      // the target's node 0 (smaller numbers, less round-off)
      const double ox = tx[0], oy = ty[0];
      double       alpha[3], beta[3], gamma[3];
      for (unsigned int k = 0; k < 3; ++k)
        {
          const unsigned int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
          alpha[k] = (ty[k1] - ty[k2]) * inv;
          beta[k]  = (tx[k2] - tx[k1]) * inv;
          gamma[k] = -(alpha[k] * (tx[k1] - ox) + beta[k] * (ty[k1] - oy));
        }
      // S: the contactor inside the three edges (lambda_k >= 0)
      double       sx[max_clipped_vertices], sy[max_clipped_vertices];
      double       wx[max_clipped_vertices], wy[max_clipped_vertices];
      unsigned int n = 3;
      for (unsigned int k = 0; k < 3; ++k)
        {
          sx[k] = cx[k] - ox;
          sy[k] = cy[k] - oy;
        }
      for (unsigned int k = 0; k < 3 && n > 0; ++k)
        {
          n = clip_polygon(sx, sy, n, alpha[k], beta[k], gamma[k], wx, wy);
          std::copy(wx, wx + n, sx);
          std::copy(wy, wy + n, sy);
        }
      if (n == 0)
        return 0.;
      double energy = 0.;
      for (unsigned int k = 0; k < 3; ++k)
        {
          // S_k: where lambda_k <= lambda_k1 and lambda_k <= lambda_k2
          const unsigned int k1 = (k + 1) % 3, k2 = (k + 2) % 3;
          double             px[max_clipped_vertices], py[max_clipped_vertices];
          unsigned int       m = clip_polygon(sx,
                                        sy,
                                        n,
                                        alpha[k1] - alpha[k],
                                        beta[k1] - beta[k],
                                        gamma[k1] - gamma[k],
                                        wx,
                                        wy);
          m                    = clip_polygon(wx,
                           wy,
                           m,
                           alpha[k2] - alpha[k],
                           beta[k2] - beta[k],
                           gamma[k2] - gamma[k],
                           px,
                           py);
          if (m == 0)
            continue;
          // area and first moments, int dA, int x dA, int y dA
          double area = 0., moment_x = 0., moment_y = 0.;
          for (unsigned int i = 0; i < m; ++i)
            {
              const unsigned int j     = i + 1 == m ? 0 : i + 1;
              const double       cross = px[i] * py[j] - px[j] * py[i];
              area += cross;
              moment_x += (px[i] + px[j]) * cross;
              moment_y += (py[i] + py[j]) * cross;
            }
          // (a contactor numbered clockwise gives the same polygon
          // clockwise: the integrals do not depend on its orientation)
          const double orientation = area < 0. ? -1. : 1.;
          area *= 0.5 * orientation;
          moment_x *= orientation / 6.;
          moment_y *= orientation / 6.;
          if (!(area > 0.))
            continue;
          const double gx = 3. * penalty * alpha[k],
                       gy = 3. * penalty * beta[k];
          for (unsigned int j = 0; j < 3; ++j)
            {
              const double lambda_integral =
                alpha[j] * moment_x + beta[j] * moment_y + gamma[j] * area;
              ft[2 * j] += gx * lambda_integral;
              ft[2 * j + 1] += gy * lambda_integral;
              if (j == k)
                energy += 3. * penalty * lambda_integral;
            }
        }
      return energy;
    }

    /**
     * The friction history of one contactor edge inside one target
     * (PenaltyCoulombContact::edge_forces()): its elastic slip, and with the
     * regularised law the friction strength and the slip rate it remembers.
     */
    struct EdgeFriction
    {
      /** Elastic slip of the tangential spring, scaled by the clipped length
       *  fraction when it was loaded [m]. */
      double slip = 0.;
      /** Friction strength S that follows mu N over the memory slip (Coulomb
       *  law: unused, 0) [N/m]. */
      double strength = 0.;
      /** Slip rate that the rate effect compares with, following the slip
       *  rate over the memory slip (Coulomb law: unused, 0) [m/s]. */
      double remembered_rate = 0.;
    };

    /** Two triangles that may touch: their indices (first < second) and the
     *  friction history of each edge of each as the contactor in the other
     *  (entry 3 direction + edge; direction 0: first in second). */
    struct ContactPair
    {
      unsigned int                first, second;
      std::array<EdgeFriction, 6> friction{};
    };

    /** The doubles of a pair's friction history, as messages carry it. */
    constexpr unsigned int friction_history_values =
      sizeof(ContactPair::friction) / sizeof(double);
    static_assert(sizeof(EdgeFriction) == 3 * sizeof(double),
                  "EdgeFriction is three doubles, copied as such");

    /**
     * The search box of a simplex of dimension @p dim whose node coordinates
     * are @p coordinates[d][k] (direction d, node k of dim + 1): its bounding
     * box enlarged by half the @p buffer on every side, written to @p box as
     * the dim minima, then the dim maxima [m]. Two simplices are candidates
     * when their search boxes overlap (closed intervals: boxes_overlap()).
     * The one expression the search and the exchange of candidates between
     * ranks (partition.h) use, so both agree bitwise.
     */
    template <int dim>
    inline void
    search_box(const double *const (&coordinates)[dim],
               const double buffer,
               double      *box)
    {
      for (unsigned int d = 0; d < dim; ++d)
        {
          const double *c  = coordinates[d];
          double        lo = c[dim], hi = c[dim];
          for (unsigned int k = dim; k-- > 0;)
            {
              lo = std::min(c[k], lo);
              hi = std::max(c[k], hi);
            }
          box[d]       = lo - 0.5 * buffer;
          box[dim + d] = hi + 0.5 * buffer;
        }
    }

    /** The search box of a triangle with node coordinates @p xe, @p ye
     *  (three each), as xmin, ymin, xmax, ymax [m]. */
    inline void
    search_box(const double *xe,
               const double *ye,
               const double  buffer,
               double       *box)
    {
      const double *const coordinates[2] = {xe, ye};
      search_box<2>(coordinates, buffer, box);
    }

    /** Whether boxes @p a and @p b (dim minima, then dim maxima) overlap or
     *  touch. */
    template <int dim = 2>
    inline bool
    boxes_overlap(const double *a, const double *b)
    {
      for (unsigned int d = 0; d < dim; ++d)
        if (a[d] > b[dim + d] || b[d] > a[dim + d])
          return false;
      return true;
    }

    /**
     * The extent of a linked-cell grid: the hull of the search boxes of all
     * active elements, the largest box side and their number. The grid,
     * and hence the pair list, follows from these alone; a rank that bins
     * only some of the active elements (partition.h) passes the extent of
     * all of them to get the grid one rank makes.
     */
    template <int dim>
    struct SearchExtentT
    {
      double      lo[dim], hi[dim]; ///< corners of the hull [m]
      double      largest    = 0.;  ///< largest box side [m]
      std::size_t n_elements = 0;   ///< active elements in all

      SearchExtentT()
      {
        std::fill(lo, lo + dim, 1e300);
        std::fill(hi, hi + dim, -1e300);
      }

      /** Takes in one search @p box. */
      void
      add(const double *box)
      {
        for (unsigned int d = 0; d < dim; ++d)
          {
            largest = std::max(largest, box[dim + d] - box[d]);
            lo[d]   = std::min(lo[d], box[d]);
            hi[d]   = std::max(hi[d], box[dim + d]);
          }
      }
    };

    /** The extent of a grid of triangles. */
    using SearchExtent = SearchExtentT<2>;

    /**
     * Linked-cell broad phase: candidate pairs of active simplices (dim + 1
     * nodes each) whose bounding boxes, enlarged by the buffer, overlap. A
     * pair is a @p Pair: its elements `first` < `second` and a `friction`
     * history that a new search keeps for the pairs found again.
     */
    template <int dim, typename Pair>
    class LinkedCellSearchT
    {
    public:
      /**
       * Rebuilds @p pairs (sorted by (first, second)) from the node
       * coordinates @p coordinates[d] of direction d (node (dim + 1) e + k
       * is node k of element e), the list of active elements, and the
       * predicate @p excluded(i, j) (intact joint between i and j). Friction
       * history of pairs present in the old list is kept. The pair search
       * runs in @p arena over fixed chunks of the active elements; the list
       * does not depend on the thread count. @p excluded must be safe to
       * call from several threads. Only pairs whose first element lies in
       * [@p first_begin, @p first_end) are made (one MPI rank's share,
       * partition.h); the default is all. With @p extent, the grid is made
       * for that extent (the active elements of all ranks) instead of that
       * of @p active_elements.
       */
      template <typename Excluded>
      void
      rebuild(const std::vector<double> *const (&coordinates)[dim],
              const std::vector<unsigned int> &active_elements,
              const double                     buffer,
              const Excluded                  &excluded,
              std::vector<Pair>               &pairs,
              tbb::task_arena                 &arena,
              const unsigned int               first_begin = 0,
              const unsigned int first_end     = static_cast<unsigned int>(-1),
              const SearchExtentT<dim> *extent = nullptr);

      /** The same for triangles, from their x and y coordinates. */
      template <typename Excluded>
      void
      rebuild(const std::vector<double>       &x,
              const std::vector<double>       &y,
              const std::vector<unsigned int> &active_elements,
              const double                     buffer,
              const Excluded                  &excluded,
              std::vector<Pair>               &pairs,
              tbb::task_arena                 &arena,
              const unsigned int               first_begin = 0,
              const unsigned int first_end     = static_cast<unsigned int>(-1),
              const SearchExtentT<dim> *extent = nullptr)
      {
        static_assert(dim == 2, "x and y: triangles");
        const std::vector<double> *const coordinates[dim] = {&x, &y};
        rebuild(coordinates,
                active_elements,
                buffer,
                excluded,
                pairs,
                arena,
                first_begin,
                first_end,
                extent);
      }

      /** The same on one thread. */
      template <typename Excluded>
      void
      rebuild(const std::vector<double>       &x,
              const std::vector<double>       &y,
              const std::vector<unsigned int> &active_elements,
              const double                     buffer,
              const Excluded                  &excluded,
              std::vector<Pair>               &pairs)
      {
        rebuild(x, y, active_elements, buffer, excluded, pairs, arena_for(1));
      }

    private:
      std::vector<double>       box;        // 2 dim per active element
      std::vector<unsigned int> cell_start; // counting sort
      std::vector<unsigned int> cell_items;
      std::vector<unsigned int> item_cell;
      std::vector<Pair>         new_pairs;
      /// pairs found per chunk of active elements, joined in chunk order
      std::vector<std::vector<Pair>> chunk_pairs;
    };

    /** The broad phase of the triangles. */
    using LinkedCellSearch = LinkedCellSearchT<2, ContactPair>;

    template <int dim, typename Pair>
    template <typename Excluded>
    void
    LinkedCellSearchT<dim, Pair>::rebuild(
      const std::vector<double> *const (&coordinates)[dim],
      const std::vector<unsigned int> &active,
      const double                     buffer,
      const Excluded                  &excluded,
      std::vector<Pair>               &pairs,
      tbb::task_arena                 &arena,
      const unsigned int               first_begin,
      const unsigned int               first_end,
      const SearchExtentT<dim>        *extent)
    {
      constexpr unsigned int nodes = dim + 1, width = 2 * dim;
      const std::size_t      n = active.size();
      new_pairs.clear();
      if (n < 2)
        {
          pairs.swap(new_pairs);
          return;
        }
      box.resize(width * n);
      SearchExtentT<dim> local;
      local.n_elements = n;
      for (std::size_t i = 0; i < n; ++i)
        {
          const unsigned int e = active[i];
          const double      *c[dim];
          for (unsigned int d = 0; d < dim; ++d)
            c[d] = &(*coordinates[d])[nodes * e];
          search_box<dim>(c, buffer, &box[width * i]);
          local.add(&box[width * i]);
        }
      const SearchExtentT<dim>    &g    = extent != nullptr ? *extent : local;
      double                       cell = g.largest;
      std::array<std::size_t, dim> nc;
      auto                         set_dims = [&](const double c) {
        std::size_t product = 1;
        for (unsigned int d = 0; d < dim; ++d)
          {
            nc[d] = static_cast<std::size_t>((g.hi[d] - g.lo[d]) / c) + 1;
            product *= nc[d];
          }
        return product;
      };
      // keep the grid at most 4 cells per element (bodies far apart)
      std::size_t n_cells = set_dims(cell);
      while (n_cells > 4 * g.n_elements + 16)
        {
          cell *= 2.;
          n_cells = set_dims(cell);
        }
      cell_start.assign(n_cells + 1, 0);
      item_cell.resize(n);
      for (std::size_t i = 0; i < n; ++i)
        {
          std::size_t index = 0;
          for (unsigned int d = dim; d-- > 0;)
            index = index * nc[d] + static_cast<std::size_t>(
                                      (box[width * i + d] - g.lo[d]) / cell);
          item_cell[i] = static_cast<unsigned int>(index);
          ++cell_start[item_cell[i] + 1];
        }
      for (std::size_t c = 0; c + 1 < cell_start.size(); ++c)
        cell_start[c + 1] += cell_start[c];
      cell_items.resize(n);
      {
        std::vector<unsigned int> fill(cell_start.begin(),
                                       cell_start.end() - 1);
        for (std::size_t i = 0; i < n; ++i)
          cell_items[fill[item_cell[i]]++] = static_cast<unsigned int>(i);
      }
      // boxes start in their own cell (lower corner) and span at most two
      // cells per direction: look at the cell and its 3^dim - 1 neighbours.
      // Pairs (active[i], active[j] > active[i]) of item i, sorted by the
      // second element: with ascending active elements the pairs of
      // consecutive items joined in order are sorted by (first, second).
      const bool ascending = std::is_sorted(active.begin(), active.end());
      // the items whose pairs are made: all, or (ascending) those with the
      // first element in [first_begin, first_end)
      std::size_t item_begin = 0, item_end = n;
      if (ascending)
        {
          item_begin =
            std::lower_bound(active.begin(), active.end(), first_begin) -
            active.begin();
          item_end = std::lower_bound(active.begin(), active.end(), first_end) -
                     active.begin();
        }
      unsigned int neighbourhood = 1;
      for (unsigned int d = 0; d < dim; ++d)
        neighbourhood *= 3;
      constexpr std::size_t chunk = 256;
      const std::size_t n_chunks  = (item_end - item_begin + chunk - 1) / chunk;
      if (chunk_pairs.size() < n_chunks)
        chunk_pairs.resize(n_chunks);
      for_each_chunk(
        arena,
        item_end - item_begin,
        chunk,
        [&](const std::size_t begin,
            const std::size_t end,
            const std::size_t c) {
          std::vector<Pair> &found = chunk_pairs[c];
          found.clear();
          for (std::size_t i = item_begin + begin; i < item_begin + end; ++i)
            {
              if (active[i] < first_begin || active[i] >= first_end)
                continue; // (not ascending) another rank's pairs
              const std::size_t first = found.size();
              long long         own[dim];
              {
                std::size_t rest = item_cell[i];
                for (unsigned int d = 0; d < dim; ++d)
                  {
                    own[d] = static_cast<long long>(rest % nc[d]);
                    rest /= nc[d];
                  }
              }
              for (unsigned int offset = 0; offset < neighbourhood; ++offset)
                {
                  std::size_t  cell_index = 0;
                  bool         inside     = true;
                  unsigned int rest       = offset;
                  std::size_t  stride     = 1;
                  for (unsigned int d = 0; d < dim; ++d)
                    {
                      const long long neighbour =
                        own[d] + static_cast<long long>(rest % 3) - 1;
                      rest /= 3;
                      if (neighbour < 0 ||
                          neighbour >= static_cast<long long>(nc[d]))
                        inside = false;
                      cell_index += stride * static_cast<std::size_t>(
                                               std::max(neighbour, 0LL));
                      stride *= nc[d];
                    }
                  if (!inside)
                    continue;
                  for (unsigned int p = cell_start[cell_index];
                       p < cell_start[cell_index + 1];
                       ++p)
                    {
                      const unsigned int j = cell_items[p];
                      if (active[j] <= active[i])
                        continue;
                      if (!boxes_overlap<dim>(&box[width * i], &box[width * j]))
                        continue;
                      if (excluded(active[i], active[j]))
                        continue;
                      Pair pair;
                      pair.first  = active[i];
                      pair.second = active[j];
                      found.push_back(pair);
                    }
                }
              std::sort(found.begin() + first,
                        found.end(),
                        [](const Pair &a, const Pair &b) {
                          return a.second < b.second;
                        });
            }
        });
      std::size_t total = 0;
      for (std::size_t c = 0; c < n_chunks; ++c)
        total += chunk_pairs[c].size();
      new_pairs.reserve(total);
      for (std::size_t c = 0; c < n_chunks; ++c)
        new_pairs.insert(new_pairs.end(),
                         chunk_pairs[c].begin(),
                         chunk_pairs[c].end());
      if (!ascending)
        std::sort(new_pairs.begin(),
                  new_pairs.end(),
                  [](const Pair &a, const Pair &b) {
                    return a.first < b.first ||
                           (a.first == b.first && a.second < b.second);
                  });
      // keep the friction history of surviving pairs (both lists sorted)
      std::size_t old = 0;
      for (Pair &p : new_pairs)
        {
          while (old < pairs.size() &&
                 (pairs[old].first < p.first || (pairs[old].first == p.first &&
                                                 pairs[old].second < p.second)))
            ++old;
          if (old < pairs.size() && pairs[old].first == p.first &&
              pairs[old].second == p.second)
            p.friction = pairs[old].friction;
        }
      pairs.swap(new_pairs);
    }
  } // namespace discrete
} // namespace tmfdem

#endif
