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
                         const BoundaryEdgeKnowledge &knowledge)
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
      const double q = t_s * l / mu;
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
      const double J = p * l;
      const double s_ss =
        mu * (q * q + l * l - 1.) / J + 0.5 * lambda * (J - 1. / J);
      return {t_n * nx * nx + 2. * t_s * nx * sx + s_ss * sx * sx,
              t_n * ny * ny + 2. * t_s * ny * sy + s_ss * sy * sy,
              t_n * nx * ny + t_s * (nx * sy + ny * sx) + s_ss * sx * sy};
    }

    std::vector<double>
    recover_vertex_stress(const DiscreteModel                      &model,
                          const std::vector<BoundaryEdgeKnowledge> &boundary)
    {
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
      std::vector<double> vertex_stress(3 * n_vertices, 0.);
      std::vector<double> vertex_x(n_vertices), vertex_y(n_vertices);
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        {
          vertex_x[model.node_vertex[n]] = model.x_ref[n];
          vertex_y[model.node_vertex[n]] = model.y_ref[n];
        }

      // 1. everywhere: linear least-squares fit to the centroid stresses
      // over the patch (widened by the neighbours' patches where it has
      // fewer than six triangles), evaluated at the vertex
      std::vector<unsigned int> elements;
      for (unsigned int v = 0; v < n_vertices; ++v)
        {
          elements.assign(patch.begin() + patch_start[v],
                          patch.begin() + patch_start[v + 1]);
          if (elements.size() < 6)
            {
              const std::size_t own = elements.size();
              for (std::size_t i = 0; i < own; ++i)
                for (unsigned int k = 0; k < 3; ++k)
                  {
                    const unsigned int w =
                      model.node_vertex[3 * elements[i] + k];
                    elements.insert(elements.end(),
                                    patch.begin() + patch_start[w],
                                    patch.begin() + patch_start[w + 1]);
                  }
              std::sort(elements.begin(), elements.end());
              elements.erase(std::unique(elements.begin(), elements.end()),
                             elements.end());
            }
          // normal equations of sigma = c0 + c1 (x - xv) + c2 (y - yv)
          double A[3][3]   = {{0., 0., 0.}, {0., 0., 0.}, {0., 0., 0.}};
          double rhs[3][3] = {{0., 0., 0.}, {0., 0., 0.}, {0., 0., 0.}};
          for (const unsigned int e : elements)
            {
              const double px[3] = {
                1.,
                (model.x_ref[3 * e] + model.x_ref[3 * e + 1] +
                 model.x_ref[3 * e + 2]) /
                    3. -
                  vertex_x[v],
                (model.y_ref[3 * e] + model.y_ref[3 * e + 1] +
                 model.y_ref[3 * e + 2]) /
                    3. -
                  vertex_y[v]};
              for (unsigned int i = 0; i < 3; ++i)
                {
                  for (unsigned int j = 0; j < 3; ++j)
                    A[i][j] += px[i] * px[j];
                  for (unsigned int c = 0; c < 3; ++c)
                    rhs[c][i] += px[i] * model.stress[3 * e + c];
                }
            }
          const double det = A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                             A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                             A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
          const double scale = A[1][1] + A[2][2];
          for (unsigned int c = 0; c < 3; ++c)
            {
              if (elements.size() >= 3 &&
                  std::abs(det) > 1e-12 * scale * scale * A[0][0])
                // c0 by Cramer's rule: the value at the vertex
                vertex_stress[3 * v + c] =
                  (rhs[c][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                   A[0][1] * (rhs[c][1] * A[2][2] - A[1][2] * rhs[c][2]) +
                   A[0][2] * (rhs[c][1] * A[2][1] - A[1][1] * rhs[c][2])) /
                  det;
              else
                vertex_stress[3 * v + c] = rhs[c][0] / A[0][0]; // mean
            }
        }
      if (boundary.empty())
        return vertex_stress;

      // 2. boundary vertices: the edges' known tractions and stretches
      struct EdgeValue
      {
        double  nx, ny, tx, ty; // current outward normal, Cauchy traction
        Stress2 sigma;          // full tensor at the midpoint
      };
      std::vector<EdgeValue>             known;
      std::vector<std::array<double, 4>> components; // nx, ny, axis, value
      for (unsigned int v = 0; v < n_vertices; ++v)
        {
          known.clear();
          components.clear();
          for (unsigned int i = patch_start[v]; i < patch_start[v + 1]; ++i)
            {
              const unsigned int e = patch[i];
              for (unsigned int k = 0; k < 3; ++k)
                {
                  const unsigned int a = 3 * e + k, b = 3 * e + (k + 1) % 3;
                  if (model.edge_boundary[a] ==
                        numbers::internal_face_boundary_id ||
                      (model.node_vertex[a] != v && model.node_vertex[b] != v))
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
                  const double nx = dy / length, ny = -dx / length;
                  // nominal (per reference length) to Cauchy traction
                  const double ratio = reference_length / length;
                  if (edge.kind == BoundaryEdgeKnowledge::Kind::traction)
                    {
                      EdgeValue value;
                      value.nx    = nx;
                      value.ny    = ny;
                      value.tx    = edge.traction[0] * ratio;
                      value.ty    = edge.traction[1] * ratio;
                      value.sigma = boundary_edge_stress(model.x[a],
                                                         model.y[a],
                                                         model.x[b],
                                                         model.y[b],
                                                         reference_length,
                                                         value.tx,
                                                         value.ty,
                                                         edge);
                      known.push_back(value);
                    }
                  else
                    components.push_back(
                      {{nx,
                        ny,
                        static_cast<double>(edge.component),
                        edge.traction[edge.component] * ratio}});
                }
            }
          double *sigma = &vertex_stress[3 * v];
          if (!known.empty())
            {
              bool corner = false;
              for (std::size_t i = 0; i < known.size(); ++i)
                for (std::size_t j = i + 1; j < known.size(); ++j)
                  corner |=
                    known[i].nx * known[j].nx + known[i].ny * known[j].ny <
                    0.86602540378443865 /* cos 30 deg */;
              bool solved = false;
              if (corner)
                {
                  // least squares of sigma n_i = t_i over the known edges:
                  // rows (nx, 0, ny) and (0, ny, nx) on (xx, yy, xy)
                  double A[3][3] = {{0., 0., 0.}, {0., 0., 0.}, {0., 0., 0.}};
                  double r[3]    = {0., 0., 0.};
                  for (const EdgeValue &ev : known)
                    {
                      const double rows[2][3] = {{ev.nx, 0., ev.ny},
                                                 {0., ev.ny, ev.nx}};
                      const double t[2]       = {ev.tx, ev.ty};
                      for (unsigned int row = 0; row < 2; ++row)
                        for (unsigned int i = 0; i < 3; ++i)
                          {
                            r[i] += rows[row][i] * t[row];
                            for (unsigned int j = 0; j < 3; ++j)
                              A[i][j] += rows[row][i] * rows[row][j];
                          }
                    }
                  const double det =
                    A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
                    A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
                    A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
                  if (std::abs(det) > 1e-6)
                    {
                      for (unsigned int c = 0; c < 3; ++c)
                        {
                          double M[3][3];
                          for (unsigned int i = 0; i < 3; ++i)
                            for (unsigned int j = 0; j < 3; ++j)
                              M[i][j] = j == c ? r[i] : A[i][j];
                          sigma[c] =
                            (M[0][0] * (M[1][1] * M[2][2] - M[1][2] * M[2][1]) -
                             M[0][1] * (M[1][0] * M[2][2] - M[1][2] * M[2][0]) +
                             M[0][2] *
                               (M[1][0] * M[2][1] - M[1][1] * M[2][0])) /
                            det;
                        }
                      solved = true;
                    }
                }
              if (!solved)
                {
                  // smooth boundary: mean of the edges' components in their
                  // own frames (n_i, s_i), composed in the vertex frame
                  // (n = normalised sum of the n_i): on a polygon that
                  // approximates a curve the stress follows the boundary
                  double nx = 0., ny = 0., nn = 0., ns = 0., ss = 0.;
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
                      nx += ev.nx;
                      ny += ev.ny;
                    }
                  const double norm = std::hypot(nx, ny);
                  if (norm > 0.5)
                    {
                      nx /= norm;
                      ny /= norm;
                      nn /= known.size();
                      ns /= known.size();
                      ss /= known.size();
                      const double sx = -ny, sy = nx;
                      sigma[0] =
                        nn * nx * nx + 2. * ns * nx * sx + ss * sx * sx;
                      sigma[1] =
                        nn * ny * ny + 2. * ns * ny * sy + ss * sy * sy;
                      sigma[2] =
                        nn * nx * ny + ns * (nx * sy + ny * sx) + ss * sx * sy;
                    }
                  else // normals nearly opposite (a sliver): Cartesian mean
                    {
                      sigma[0] = sigma[1] = sigma[2] = 0.;
                      for (const EdgeValue &ev : known)
                        {
                          sigma[0] += ev.sigma.xx / known.size();
                          sigma[1] += ev.sigma.yy / known.size();
                          sigma[2] += ev.sigma.xy / known.size();
                        }
                    }
                }
            }
          // one known component (sigma n)_i = t_i: the closest tensor
          // (in xx, yy, xy) that satisfies it
          for (const auto &c : components)
            {
              const double g[3] = {c[2] == 0. ? c[0] : 0.,
                                   c[2] == 0. ? 0. : c[1],
                                   c[2] == 0. ? c[1] : c[0]};
              const double gg = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
              const double misfit =
                c[3] - (g[0] * sigma[0] + g[1] * sigma[1] + g[2] * sigma[2]);
              if (gg > 0.)
                for (unsigned int i = 0; i < 3; ++i)
                  sigma[i] += misfit * g[i] / gg;
            }
        }
      return vertex_stress;
    }
  } // namespace discrete
} // namespace tmfdem
