#include <algorithm>
#include <cmath>
#include <limits>
#include <tmfdem/discrete/stable_step.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      /** True when the symmetric @p a is positive definite (Cholesky). */
      bool
      positive_definite(Matrix6 a)
      {
        for (unsigned int j = 0; j < 6; ++j)
          {
            double d = a[j][j];
            for (unsigned int k = 0; k < j; ++k)
              d -= a[j][k] * a[j][k];
            if (!(d > 0.))
              return false;
            const double l = std::sqrt(d);
            a[j][j]        = l;
            for (unsigned int i = j + 1; i < 6; ++i)
              {
                double s = a[i][j];
                for (unsigned int k = 0; k < j; ++k)
                  s -= a[i][k] * a[j][k];
                a[i][j] = s / l;
              }
          }
        return true;
      }

      /** max_i sum_j |a_ij|, an upper bound of the largest eigenvalue. */
      double
      row_sum_norm(const Matrix6 &a)
      {
        double norm = 0.;
        for (const auto &row : a)
          {
            double s = 0.;
            for (const double v : row)
              s += std::abs(v);
            norm = std::max(norm, s);
          }
        return norm;
      }
    } // namespace

    void
    element_matrices(const std::array<double, 3> &x,
                     const std::array<double, 3> &y,
                     const LameConstants         &lame,
                     Matrix6                     &stiffness,
                     Matrix6                     &unit_viscosity)
    {
      const double area =
        0.5 * ((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]));
      // B = strain-displacement matrix (exx, eyy, gamma_xy) of the CST
      double B[3][6] = {};
      for (unsigned int i = 0; i < 3; ++i)
        {
          const unsigned int j = (i + 1) % 3, k = (i + 2) % 3;
          const double       b = (y[j] - y[k]) / (2. * area);
          const double       c = (x[k] - x[j]) / (2. * area);
          B[0][2 * i]          = b;
          B[1][2 * i + 1]      = c;
          B[2][2 * i]          = c;
          B[2][2 * i + 1]      = b;
        }
      const double D[3][3] = {{lame.lambda + 2. * lame.mu, lame.lambda, 0.},
                              {lame.lambda, lame.lambda + 2. * lame.mu, 0.},
                              {0., 0., lame.mu}};
      const double Dv[3]   = {2., 2., 1.};
      const double weight  = std::abs(area);
      for (unsigned int r = 0; r < 6; ++r)
        for (unsigned int c = 0; c < 6; ++c)
          {
            double k = 0., v = 0.;
            for (unsigned int p = 0; p < 3; ++p)
              {
                v += B[p][r] * Dv[p] * B[p][c];
                for (unsigned int q = 0; q < 3; ++q)
                  k += B[p][r] * D[p][q] * B[q][c];
              }
            stiffness[r][c]      = weight * k;
            unit_viscosity[r][c] = weight * v;
          }
    }

    namespace
    {
      /**
       * M^-1 (K_e + 2 sum G + R) and M^-1 C_e of the element (M = m I);
       * false for a degenerate element or massless nodes.
       */
      bool
      scaled_matrices(const ElementStepInput &e, Matrix6 &K, Matrix6 &C)
      {
        const double area = 0.5 * ((e.x[1] - e.x[0]) * (e.y[2] - e.y[0]) -
                                   (e.x[2] - e.x[0]) * (e.y[1] - e.y[0]));
        if (!(area > 0.) || !(e.node_mass > 0.))
          return false;
        element_matrices(e.x, e.y, e.lame, K, C);
        // joints, twice their one-sided matrix
        // L / 6 [[2, 1], [1, 2]] (x) (k_n n n^T + k_t t t^T)
        for (unsigned int edge = 0; edge < 3; ++edge)
          {
            const double kn = e.edge_joint_normal_stiffness[edge];
            const double kt = e.edge_joint_tangential_stiffness[edge];
            if (!(kn > 0.) && !(kt > 0.))
              continue;
            const unsigned int a = edge, b = (edge + 1) % 3;
            const double       L = std::hypot(e.x[b] - e.x[a], e.y[b] - e.y[a]);
            const double t[2] = {(e.x[b] - e.x[a]) / L, (e.y[b] - e.y[a]) / L};
            const double n[2] = {t[1], -t[0]};
            for (unsigned int d = 0; d < 2; ++d)
              for (unsigned int f = 0; f < 2; ++f)
                {
                  const double k = kn * n[d] * n[f] + kt * t[d] * t[f];
                  K[2 * a + d][2 * a + f] += 2. * k * L / 3.;
                  K[2 * b + d][2 * b + f] += 2. * k * L / 3.;
                  K[2 * a + d][2 * b + f] += k * L / 3.;
                  K[2 * b + d][2 * a + f] += k * L / 3.;
                }
          }
        for (unsigned int i = 0; i < 6; ++i)
          K[i][i] += e.node_contact_stiffness;
        const double inv_m = 1. / e.node_mass;
        for (unsigned int r = 0; r < 6; ++r)
          for (unsigned int c = 0; c < 6; ++c)
            {
              K[r][c] *= inv_m;
              C[r][c] *= e.viscosity * inv_m;
            }
        return true;
      }

      /** 4 I - 2 dt C - dt^2 K positive definite (K, C scaled by 1/m). */
      bool
      stable_with(const Matrix6 &K, const Matrix6 &C, const double dt)
      {
        Matrix6 A;
        for (unsigned int r = 0; r < 6; ++r)
          for (unsigned int c = 0; c < 6; ++c)
            A[r][c] =
              (r == c ? 4. : 0.) - 2. * dt * C[r][c] - dt * dt * K[r][c];
        return positive_definite(A);
      }
    } // namespace

    bool
    stable_at(const ElementStepInput &e, const double dt)
    {
      Matrix6 K, C;
      return scaled_matrices(e, K, C) && stable_with(K, C, dt);
    }

    double
    critical_time_step(const ElementStepInput &e)
    {
      Matrix6 K, C;
      if (!scaled_matrices(e, K, C))
        return 0.;
      const auto stable = [&](const double dt) {
        return stable_with(K, C, dt);
      };
      const double k_norm = row_sum_norm(K), c_norm = row_sum_norm(C);
      if (!(k_norm > 0.) && !(c_norm > 0.))
        return std::numeric_limits<double>::infinity();
      // a sure lower bound from the norms: 2 dt |C| + dt^2 |K| <= 4
      double lo =
        k_norm > 0. ?
          (-c_norm + std::sqrt(c_norm * c_norm + 4. * k_norm)) / k_norm :
          2. / c_norm;
      lo *= 1. - 1e-12;
      double hi = 2. * lo;
      while (stable(hi))
        {
          lo = hi;
          hi *= 2.;
        }
      while (hi - lo > 1e-4 * lo)
        {
          const double mid        = 0.5 * (lo + hi);
          (stable(mid) ? lo : hi) = mid;
        }
      return lo;
    }

    void
    symmetric_eigen(const Matrix6         &matrix,
                    std::array<double, 6> &values,
                    Matrix6               &vectors)
    {
      Matrix6 a = matrix;
      for (unsigned int r = 0; r < 6; ++r)
        for (unsigned int c = 0; c < 6; ++c)
          vectors[r][c] = r == c ? 1. : 0.;
      double scale = 0.;
      for (unsigned int r = 0; r < 6; ++r)
        scale = std::max(scale, std::abs(a[r][r]));
      for (unsigned int sweep = 0; sweep < 50; ++sweep)
        {
          double off = 0.;
          for (unsigned int p = 0; p < 6; ++p)
            for (unsigned int q = p + 1; q < 6; ++q)
              off = std::max(off, std::abs(a[p][q]));
          if (off <= 1e-15 * scale || off == 0.)
            break;
          for (unsigned int p = 0; p < 6; ++p)
            for (unsigned int q = p + 1; q < 6; ++q)
              {
                if (a[p][q] == 0.)
                  continue;
                // rotation that zeroes a[p][q]
                const double theta = (a[q][q] - a[p][p]) / (2. * a[p][q]);
                const double t =
                  (theta >= 0. ? 1. : -1.) /
                  (std::abs(theta) + std::sqrt(theta * theta + 1.));
                const double c = 1. / std::sqrt(t * t + 1.), s = t * c;
                for (unsigned int k = 0; k < 6; ++k)
                  {
                    const double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                  }
                for (unsigned int k = 0; k < 6; ++k)
                  {
                    const double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                  }
                for (unsigned int k = 0; k < 6; ++k)
                  {
                    const double vkp = vectors[k][p], vkq = vectors[k][q];
                    vectors[k][p] = c * vkp - s * vkq;
                    vectors[k][q] = s * vkp + c * vkq;
                  }
              }
        }
      // sort ascending, columns with their values
      std::array<unsigned int, 6> order = {{0, 1, 2, 3, 4, 5}};
      std::sort(order.begin(),
                order.end(),
                [&](unsigned int i, unsigned int j) {
                  return a[i][i] < a[j][j];
                });
      const Matrix6 v = vectors;
      for (unsigned int c = 0; c < 6; ++c)
        {
          values[c] = a[order[c]][order[c]];
          for (unsigned int r = 0; r < 6; ++r)
            vectors[r][c] = v[r][order[c]];
        }
    }

    double
    highest_mode_damping_per_viscosity(const std::array<double, 3> &x,
                                       const std::array<double, 3> &y,
                                       const LameConstants         &lame,
                                       const double                 node_mass)
    {
      Matrix6 K, C;
      element_matrices(x, y, lame, K, C);
      std::array<double, 6> omega2;
      Matrix6               modes;
      symmetric_eigen(K, omega2, modes);
      const double top = omega2[5];
      if (!(top > 0.))
        return 0.;
      // average over a (numerically) repeated highest eigenvalue
      double       sum = 0.;
      unsigned int n   = 0;
      for (int i = 5; i >= 0 && omega2[i] >= top * (1. - 1e-8); --i, ++n)
        for (unsigned int r = 0; r < 6; ++r)
          for (unsigned int c = 0; c < 6; ++c)
            sum += modes[r][i] * C[r][c] * modes[c][i];
      const double omega = std::sqrt(top / node_mass);
      return sum / n / (2. * node_mass * omega);
    }
  } // namespace discrete
} // namespace tmfdem
