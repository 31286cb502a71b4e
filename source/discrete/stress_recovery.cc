#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>
#include <deal.II/base/types.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <tmfdem/discrete/stress_recovery.h>

namespace tmfdem
{
  namespace discrete
  {
    Stress2
    boundary_edge_stress(const double                 x0,
                         const double                 y0,
                         const double                 x1,
                         const double                 y1,
                         const double                 reference_length,
                         const double                 tx,
                         const double                 ty,
                         const BoundaryEdgeKnowledge &knowledge,
                         const double                 reference_dx,
                         const double                 reference_dy)
    {
      const double length = std::hypot(x1 - x0, y1 - y0);
      const double sx = (x1 - x0) / length, sy = (y1 - y0) / length;
      const double nx = sy, ny = -sx; // outward for a counter-clockwise edge
      const double t_n = tx * nx + ty * ny, t_s = tx * sx + ty * sy;
      const double mu = knowledge.lame.mu, lambda = knowledge.lame.lambda;
      // elastic F_e in the edge frame (current n, s; reference N, S):
      // F_e N = p n + q s, F_e S = l s, so B_nn = p^2, B_ns = p q,
      // B_ss = q^2 + l^2, J = p l; Eq. 44 then gives sigma_ns = mu q / l and
      // sigma_nn(p), increasing in p, solved for t_n by Newton's method
      const double l = length / reference_length / knowledge.thermal_stretch;
      double       q = t_s * l / mu;
      double       p = 1.;
      for (unsigned int it = 0; it < 50; ++it)
        {
          const double J = p * l;
          const double g =
            mu * (p * p - 1.) / J + 0.5 * lambda * (J - 1. / J) - t_n;
          const double dg = mu * (1. / l + 1. / (p * p * l)) +
                            0.5 * lambda * (l + 1. / (p * p * l));
          double next = p - g / dg;
          if (!(next > 0.))
            next = 0.5 * p;
          const bool converged = std::abs(next - p) < 1e-14 * p;
          p                    = next;
          if (converged)
            break;
        }
      double J    = p * l;
      double s_ss = mu * (q * q + l * l - 1.) / J + 0.5 * lambda * (J - 1. / J);
      const auto &dC = knowledge.anisotropy;
      if (std::any_of(dC.begin(), dC.end(), [](const double c) {
            return c != 0.;
          }))
        {
          // with the anisotropic correction the reference direction of the
          // edge enters: F_e = (p n + q s) N^T + l s S^T in global
          // coordinates; Newton on (p, q) for the traction (t_n, t_s), from
          // the isotropic solution, with a finite-difference Jacobian
          const double L0 = std::hypot(reference_dx, reference_dy);
          const double Sx = reference_dx / L0, Sy = reference_dy / L0;
          const double Nx = Sy, Ny = -Sx;
          auto         stress = [&](const double pp, const double qq) {
            const double  ax = pp * nx + qq * sx, ay = pp * ny + qq * sy;
            const Matrix2 Fe    = matrix2(ax * Nx + l * sx * Sx,
                                       ax * Ny + l * sx * Sy,
                                       ay * Nx + l * sy * Sx,
                                       ay * Ny + l * sy * Sy);
            Stress2       sigma = elastic_stress(Fe, knowledge.lame);
            const Stress2 extra = anisotropic_stress(Fe, dC.data());
            sigma.xx += extra.xx;
            sigma.yy += extra.yy;
            sigma.xy += extra.xy;
            return sigma;
          };
          auto residual = [&](const double pp,
                              const double qq,
                              double      &r_n,
                              double      &r_s,
                              double      &ss) {
            const Stress2 g   = stress(pp, qq);
            const double  gnx = g.xx * nx + g.xy * ny;
            const double  gny = g.xy * nx + g.yy * ny;
            r_n               = gnx * nx + gny * ny - t_n;
            r_s               = gnx * sx + gny * sy - t_s;
            ss = sx * (g.xx * sx + g.xy * sy) + sy * (g.xy * sx + g.yy * sy);
          };
          double r_n, r_s;
          residual(p, q, r_n, r_s, s_ss);
          const double scale = mu + std::abs(t_n) + std::abs(t_s);
          for (unsigned int it = 0;
               it < 30 && std::abs(r_n) + std::abs(r_s) > 1e-13 * scale;
               ++it)
            {
              const double h = 1e-7;
              double       a_n, a_s, b_n, b_s, unused;
              residual(p + h, q, a_n, a_s, unused);
              residual(p, q + h, b_n, b_s, unused);
              const double j00 = (a_n - r_n) / h, j10 = (a_s - r_s) / h;
              const double j01 = (b_n - r_n) / h, j11 = (b_s - r_s) / h;
              const double det = j00 * j11 - j01 * j10;
              if (!(std::abs(det) > 0.))
                break;
              p -= (j11 * r_n - j01 * r_s) / det;
              q -= (j00 * r_s - j10 * r_n) / det;
              if (!(p > 0.))
                p = 1e-3;
              residual(p, q, r_n, r_s, s_ss);
            }
        }
      return {t_n * nx * nx + 2. * t_s * nx * sx + s_ss * sx * sx,
              t_n * ny * ny + 2. * t_s * ny * sy + s_ss * sy * sy,
              t_n * nx * ny + t_s * (nx * sy + ny * sx) + s_ss * sx * sy};
    }

    namespace
    {
      /**
       * Solves the symmetric positive definite n x n system @p A x = @p b
       * (row stride 6) by Cholesky; false where a pivot falls below 1e-3
       * of the largest diagonal entry: a patch that does not determine the
       * polynomial well (in the local coordinates scaled by h, regular
       * patches have pivots above 1e-2 of it; the centroids of a fan of a
       * few triangles around one vertex, as in a small Voronoi block, lie
       * near a circle, which leaves x^2 + y^2 at about 2e-4).
       */
      bool
      solve_spd(const unsigned int n,
                const double       A[6][6],
                const double      *b,
                double            *x)
      {
        double L[6][6];
        double largest = 0.;
        for (unsigned int i = 0; i < n; ++i)
          largest = std::max(largest, A[i][i]);
        if (!(largest > 0.))
          return false;
        for (unsigned int j = 0; j < n; ++j)
          {
            double d = A[j][j];
            for (unsigned int k = 0; k < j; ++k)
              d -= L[j][k] * L[j][k];
            if (!(d > 1e-3 * largest))
              return false;
            L[j][j] = std::sqrt(d);
            for (unsigned int i = j + 1; i < n; ++i)
              {
                double a = A[i][j];
                for (unsigned int k = 0; k < j; ++k)
                  a -= L[i][k] * L[j][k];
                L[i][j] = a / L[j][j];
              }
          }
        double y[6];
        for (unsigned int i = 0; i < n; ++i)
          {
            double a = b[i];
            for (unsigned int k = 0; k < i; ++k)
              a -= L[i][k] * y[k];
            y[i] = a / L[i][i];
          }
        for (unsigned int i = n; i-- > 0;)
          {
            double a = y[i];
            for (unsigned int k = i + 1; k < n; ++k)
              a -= L[k][i] * x[k];
            x[i] = a / L[i][i];
          }
        return true;
      }

      /** The terms 1, x, y, x^2, x y, y^2 at local (x, y). */
      inline void
      terms(const double x, const double y, double *p)
      {
        p[0] = 1.;
        p[1] = x;
        p[2] = y;
        p[3] = x * x;
        p[4] = x * y;
        p[5] = y * y;
      }

      /** Number of terms of degree 2, 1, 0. */
      constexpr unsigned int terms_of_degree[3] = {1, 3, 6};

      /** A prescribed linear combination g . s = value of the vertex value
       *  s = (xx, yy, sqrt 2 xy) (the Frobenius metric). */
      struct Prescription
      {
        double g[3];
        double value;
      };
    } // namespace

    RecoveredStress::RecoveredStress(
      const DiscreteModel                      &model,
      const std::vector<BoundaryEdgeKnowledge> &boundary)
      : model(&model)
    {
      const double root2      = std::sqrt(2.);
      unsigned int n_vertices = 0;
      for (const auto v : model.node_vertex)
        n_vertices = std::max(n_vertices, v + 1);
      // patch of each vertex: the elements with a node on it
      std::vector<unsigned int> patch_start(n_vertices + 1, 0), patch;
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        ++patch_start[model.node_vertex[n] + 1];
      for (unsigned int v = 0; v < n_vertices; ++v)
        patch_start[v + 1] += patch_start[v];
      patch.resize(model.n_nodes);
      {
        std::vector<unsigned int> fill(patch_start.begin(),
                                       patch_start.end() - 1);
        for (unsigned int n = 0; n < model.n_nodes; ++n)
          patch[fill[model.node_vertex[n]]++] = n / 3;
      }
      vertex_x.assign(n_vertices, 0.);
      vertex_y.assign(n_vertices, 0.);
      inverse_scale.assign(n_vertices, 0.);
      coefficients.assign(3 * n_terms * n_vertices, 0.);
      vertex_degree.assign(n_vertices, 0);
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        {
          vertex_x[model.node_vertex[n]] = model.x_ref[n];
          vertex_y[model.node_vertex[n]] = model.y_ref[n];
        }

      std::vector<unsigned int> elements, mark(model.n_elements, n_vertices);
      std::vector<Prescription> prescribed;
      struct EdgeValue
      {
        double  nx, ny, tx, ty; // current outward normal, Cauchy traction
        Stress2 sigma;          // full tensor at the midpoint
      };
      std::vector<EdgeValue> known;
      for (unsigned int v = 0; v < n_vertices; ++v)
        {
          // 1. the patch, widened by one ring, and by more (at most three)
          // while it has fewer than 14 triangles
          elements.assign(patch.begin() + patch_start[v],
                          patch.begin() + patch_start[v + 1]);
          for (const unsigned int e : elements)
            mark[e] = v;
          for (unsigned int ring = 0; ring < 4; ++ring)
            {
              if (ring > 0 && elements.size() >= 14)
                break;
              const std::size_t before = elements.size();
              for (std::size_t i = 0; i < before; ++i)
                for (unsigned int k = 0; k < 3; ++k)
                  {
                    const unsigned int w =
                      model.node_vertex[3 * elements[i] + k];
                    for (unsigned int j = patch_start[w];
                         j < patch_start[w + 1];
                         ++j)
                      if (mark[patch[j]] != v)
                        {
                          mark[patch[j]] = v;
                          elements.push_back(patch[j]);
                        }
                  }
              if (elements.size() == before)
                break;
            }
          double area = 0.;
          for (const unsigned int e : elements)
            area += model.reference_area[e];
          const double h   = std::sqrt(area / elements.size());
          inverse_scale[v] = h > 0. ? 1. / h : 0.;

          // 2. normal equations of the fit in local coordinates, data in
          // the Frobenius metric (xx, yy, sqrt 2 xy)
          double A[6][6] = {}, R[6][3] = {};
          for (const unsigned int e : elements)
            {
              double p[6];
              terms(((model.x_ref[3 * e] + model.x_ref[3 * e + 1] +
                      model.x_ref[3 * e + 2]) /
                       3. -
                     vertex_x[v]) *
                      inverse_scale[v],
                    ((model.y_ref[3 * e] + model.y_ref[3 * e + 1] +
                      model.y_ref[3 * e + 2]) /
                       3. -
                     vertex_y[v]) *
                      inverse_scale[v],
                    p);
              const double s[3] = {model.stress[3 * e],
                                   model.stress[3 * e + 1],
                                   root2 * model.stress[3 * e + 2]};
              for (unsigned int i = 0; i < 6; ++i)
                {
                  for (unsigned int j = 0; j < 6; ++j)
                    A[i][j] += p[i] * p[j];
                  for (unsigned int c = 0; c < 3; ++c)
                    R[i][c] += p[i] * s[c];
                }
            }

          // 3. what the boundary prescribes at the vertex
          prescribed.clear();
          known.clear();
          if (!boundary.empty())
            for (unsigned int i = patch_start[v]; i < patch_start[v + 1]; ++i)
              {
                const unsigned int e = patch[i];
                for (unsigned int k = 0; k < 3; ++k)
                  {
                    const unsigned int a = 3 * e + k, b = 3 * e + (k + 1) % 3;
                    if (model.edge_boundary[a] ==
                          numbers::internal_face_boundary_id ||
                        (model.node_vertex[a] != v &&
                         model.node_vertex[b] != v))
                      continue;
                    const BoundaryEdgeKnowledge &edge = boundary[a];
                    if (edge.kind == BoundaryEdgeKnowledge::Kind::unknown)
                      continue;
                    const double dx     = model.x[b] - model.x[a];
                    const double dy     = model.y[b] - model.y[a];
                    const double length = std::hypot(dx, dy);
                    const double reference_length =
                      std::hypot(model.x_ref[b] - model.x_ref[a],
                                 model.y_ref[b] - model.y_ref[a]);
                    if (!(length > 0.) || !(reference_length > 0.))
                      continue;
                    const double nx = dy / length, ny = -dx / length;
                    // nominal (per reference length) to Cauchy traction
                    const double ratio = reference_length / length;
                    if (edge.kind == BoundaryEdgeKnowledge::Kind::traction)
                      {
                        EdgeValue value;
                        value.nx = nx;
                        value.ny = ny;
                        value.tx = edge.traction[0] * ratio;
                        value.ty = edge.traction[1] * ratio;
                        value.sigma =
                          boundary_edge_stress(model.x[a],
                                               model.y[a],
                                               model.x[b],
                                               model.y[b],
                                               reference_length,
                                               value.tx,
                                               value.ty,
                                               edge,
                                               model.x_ref[b] - model.x_ref[a],
                                               model.y_ref[b] - model.y_ref[a]);
                        known.push_back(value);
                      }
                    else
                      {
                        // (sigma n)_i = t_i: g on (xx, yy, xy), unit length
                        // in the Frobenius metric
                        const bool   x    = edge.component == 0;
                        const double g[3] = {x ? nx : 0.,
                                             x ? 0. : ny,
                                             (x ? ny : nx) / root2};
                        const double norm =
                          std::sqrt(g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
                        if (norm > 0.)
                          prescribed.push_back(
                            {{g[0] / norm, g[1] / norm, g[2] / norm},
                             edge.traction[edge.component] * ratio / norm});
                      }
                  }
              }
          if (!known.empty())
            {
              bool corner = false;
              for (std::size_t i = 0; i < known.size(); ++i)
                for (std::size_t j = i + 1; j < known.size(); ++j)
                  corner |=
                    known[i].nx * known[j].nx + known[i].ny * known[j].ny <
                    0.86602540378443865 /* cos 30 deg */;
              double nx = 0., ny = 0.;
              for (const EdgeValue &ev : known)
                {
                  nx += ev.nx;
                  ny += ev.ny;
                }
              const double norm = std::hypot(nx, ny);
              if (corner)
                // sigma n_i = t_i on every known edge: the rows
                // (nx, 0, ny / sqrt 2) and (0, ny, nx / sqrt 2)
                for (const EdgeValue &ev : known)
                  {
                    prescribed.push_back({{ev.nx, 0., ev.ny / root2}, ev.tx});
                    prescribed.push_back({{0., ev.ny, ev.nx / root2}, ev.ty});
                  }
              else if (norm > 0.5)
                {
                  // smooth boundary: mean of the edges' components in their
                  // own frames (n_i, s_i), prescribed in the vertex frame
                  // (n = normalised sum of the n_i): on a polygon that
                  // approximates a curve the stress follows the boundary
                  double nn = 0., ns = 0., ss = 0.;
                  for (const EdgeValue &ev : known)
                    {
                      const double sx = -ev.ny, sy = ev.nx;
                      const double sn[2] = {ev.sigma.xx * ev.nx +
                                              ev.sigma.xy * ev.ny,
                                            ev.sigma.xy * ev.nx +
                                              ev.sigma.yy * ev.ny};
                      nn += sn[0] * ev.nx + sn[1] * ev.ny;
                      ns += sn[0] * sx + sn[1] * sy;
                      ss += ev.sigma.xx * sx * sx + 2. * ev.sigma.xy * sx * sy +
                            ev.sigma.yy * sy * sy;
                    }
                  nx /= norm;
                  ny /= norm;
                  const double sx = -ny, sy = nx;
                  const double count = known.size();
                  // n n, sym(n s) sqrt 2 and s s: orthonormal
                  prescribed.push_back(
                    {{nx * nx, ny * ny, root2 * nx * ny}, nn / count});
                  prescribed.push_back(
                    {{root2 * nx * sx, root2 * ny * sy, nx * sy + ny * sx},
                     root2 * ns / count});
                  prescribed.push_back(
                    {{sx * sx, sy * sy, root2 * sx * sy}, ss / count});
                }
              else // normals nearly opposite (a sliver): Cartesian mean
                {
                  double mean[3] = {0., 0., 0.};
                  for (const EdgeValue &ev : known)
                    {
                      mean[0] += ev.sigma.xx / known.size();
                      mean[1] += ev.sigma.yy / known.size();
                      mean[2] += root2 * ev.sigma.xy / known.size();
                    }
                  prescribed.push_back({{1., 0., 0.}, mean[0]});
                  prescribed.push_back({{0., 1., 0.}, mean[1]});
                  prescribed.push_back({{0., 0., 1.}, mean[2]});
                }
            }

          // 4. directions u_j (orthonormal in the Frobenius metric) and the
          // prescribed value of u_j . s where the prescriptions determine
          // it: eigenvectors of M = sum g g^T, u_j . s = u_j . b / mu_j
          // with b = sum g value (least squares over the prescriptions)
          std::array<Tensor<1, 3>, 3> direction;
          std::array<bool, 3>         fixed    = {{false, false, false}};
          std::array<double, 3>       constant = {{0., 0., 0.}};
          for (unsigned int j = 0; j < 3; ++j)
            {
              direction[j]    = Tensor<1, 3>();
              direction[j][j] = 1.;
            }
          if (!prescribed.empty())
            {
              SymmetricTensor<2, 3> M;
              Tensor<1, 3>          b;
              for (const Prescription &p : prescribed)
                for (unsigned int i = 0; i < 3; ++i)
                  {
                    b[i] += p.g[i] * p.value;
                    for (unsigned int j = i; j < 3; ++j)
                      M[i][j] += p.g[i] * p.g[j];
                  }
              // Jacobi: the QL default of deal.II fails to converge on some
              // of these small matrices (plates with a floor body)
              const auto eigen =
                eigenvectors(M, SymmetricTensorEigenvectorMethod::jacobi);
              for (unsigned int j = 0; j < 3; ++j)
                {
                  direction[j] = eigen[j].second;
                  if (eigen[j].first > 1e-8 * eigen[0].first)
                    {
                      fixed[j]    = true;
                      constant[j] = direction[j] * b / eigen[j].first;
                    }
                }
            }

          // 5. per direction: the fit (quadratic, else linear, else mean),
          // with the constant term fixed where prescribed
          unsigned int degree = 2;
          double       c[3][6];
          for (;; --degree)
            {
              const unsigned int n      = terms_of_degree[degree];
              bool               solved = true;
              for (unsigned int j = 0; j < 3 && solved; ++j)
                {
                  double r[6];
                  for (unsigned int i = 0; i < n; ++i)
                    r[i] = R[i][0] * direction[j][0] +
                           R[i][1] * direction[j][1] +
                           R[i][2] * direction[j][2];
                  for (unsigned int i = 0; i < 6; ++i)
                    c[j][i] = 0.;
                  if (fixed[j])
                    {
                      c[j][0] = constant[j];
                      if (n > 1)
                        {
                          double A1[6][6], r1[6];
                          for (unsigned int i = 1; i < n; ++i)
                            {
                              for (unsigned int k = 1; k < n; ++k)
                                A1[i - 1][k - 1] = A[i][k];
                              r1[i - 1] = r[i] - A[i][0] * constant[j];
                            }
                          solved = solve_spd(n - 1, A1, r1, &c[j][1]);
                        }
                    }
                  else
                    solved = solve_spd(n, A, r, c[j]);
                }
              if (solved || degree == 0)
                break;
            }
          vertex_degree[v] = degree;
          // back to (xx, yy, xy)
          double *coefficient = &coefficients[3 * n_terms * v];
          for (unsigned int j = 0; j < 3; ++j)
            for (unsigned int i = 0; i < n_terms; ++i)
              {
                coefficient[i] += c[j][i] * direction[j][0];
                coefficient[n_terms + i] += c[j][i] * direction[j][1];
                coefficient[2 * n_terms + i] +=
                  c[j][i] * direction[j][2] / root2;
              }
        }
    }

    Stress2
    RecoveredStress::value(const unsigned int element,
                           const double      *lambda) const
    {
      const unsigned int n = 3 * element;
      const double       x = lambda[0] * model->x_ref[n] +
                       lambda[1] * model->x_ref[n + 1] +
                       lambda[2] * model->x_ref[n + 2];
      const double y = lambda[0] * model->y_ref[n] +
                       lambda[1] * model->y_ref[n + 1] +
                       lambda[2] * model->y_ref[n + 2];
      Stress2 sigma;
      for (unsigned int k = 0; k < 3; ++k)
        {
          const unsigned int v = model->node_vertex[n + k];
          double             p[n_terms];
          terms((x - vertex_x[v]) * inverse_scale[v],
                (y - vertex_y[v]) * inverse_scale[v],
                p);
          const double *c    = &coefficients[3 * n_terms * v];
          double        s[3] = {0., 0., 0.};
          for (unsigned int i = 0; i < n_terms; ++i)
            for (unsigned int d = 0; d < 3; ++d)
              s[d] += c[n_terms * d + i] * p[i];
          sigma.xx += lambda[k] * s[0];
          sigma.yy += lambda[k] * s[1];
          sigma.xy += lambda[k] * s[2];
        }
      return sigma;
    }

    Stress2
    RecoveredStress::vertex_value(const unsigned int vertex) const
    {
      const double *c = &coefficients[3 * n_terms * vertex];
      return {c[0], c[n_terms], c[2 * n_terms]};
    }

    std::vector<double>
    recover_vertex_stress(const DiscreteModel                      &model,
                          const std::vector<BoundaryEdgeKnowledge> &boundary)
    {
      const RecoveredStress recovered(model, boundary);
      std::vector<double>   vertex_stress(3 * recovered.n_vertices());
      for (unsigned int v = 0; v < recovered.n_vertices(); ++v)
        {
          const Stress2 s          = recovered.vertex_value(v);
          vertex_stress[3 * v]     = s.xx;
          vertex_stress[3 * v + 1] = s.yy;
          vertex_stress[3 * v + 2] = s.xy;
        }
      return vertex_stress;
    }
  } // namespace discrete
} // namespace tmfdem
