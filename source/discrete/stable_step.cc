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
      /** The node coordinates of a simplex by component, X[i][a] [m]. */
      template <int dim>
      using Coordinates = std::array<std::array<double, dim + 1>, dim>;

      Coordinates<2>
      coordinates(const ElementStepInputT<2> &e)
      {
        return {{e.x, e.y}};
      }

      Coordinates<3>
      coordinates(const ElementStepInputT<3> &e)
      {
        return {{e.x, e.y, e.z}};
      }

      /** The signed area (2D) or volume (3D) of a simplex [m^dim]. */
      template <int dim>
      double
      signed_measure(const Coordinates<dim> &X)
      {
        if constexpr (dim == 2)
          {
            const auto &x = X[0], &y = X[1];
            return 0.5 * ((x[1] - x[0]) * (y[2] - y[0]) -
                          (x[2] - x[0]) * (y[1] - y[0]));
          }
        else
          {
            // (x1 - x0) . ((x2 - x0) x (x3 - x0)) / 6
            double e[3][3];
            for (unsigned int k = 0; k < 3; ++k)
              for (unsigned int i = 0; i < 3; ++i)
                e[k][i] = X[i][k + 1] - X[i][0];
            return (e[0][0] * (e[1][1] * e[2][2] - e[1][2] * e[2][1]) +
                    e[0][1] * (e[1][2] * e[2][0] - e[1][0] * e[2][2]) +
                    e[0][2] * (e[1][0] * e[2][1] - e[1][1] * e[2][0])) /
                   6.;
          }
      }

      /** True when the symmetric @p a is positive definite (Cholesky). */
      template <std::size_t N>
      bool
      positive_definite(std::array<std::array<double, N>, N> a)
      {
        for (unsigned int j = 0; j < N; ++j)
          {
            double d = a[j][j];
            for (unsigned int k = 0; k < j; ++k)
              d -= a[j][k] * a[j][k];
            if (!(d > 0.))
              return false;
            const double l = std::sqrt(d);
            a[j][j]        = l;
            for (unsigned int i = j + 1; i < N; ++i)
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
      template <std::size_t N>
      double
      row_sum_norm(const std::array<std::array<double, N>, N> &a)
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

      /**
       * K_e and C_e (eta = 1) of a simplex with nodes @p X: B^T D B and
       * B^T D_v B times the area or volume, strains in Voigt order (xx, yy,
       * xy) in 2D, (xx, yy, zz, xy, yz, xz) in 3D, engineering shear.
       */
      template <int dim>
      void
      simplex_matrices(const Coordinates<dim> &X,
                       const LameConstants    &lame,
                       ElementMatrix<dim>     &stiffness,
                       ElementMatrix<dim>     &unit_viscosity)
      {
        constexpr unsigned int n_dofs   = simplex_dofs<dim>;
        constexpr unsigned int n_strain = dim * (dim + 1) / 2;
        const double           measure  = signed_measure<dim>(X);
        // grad N_a of the linear shape functions [1/m]
        double grad[dim + 1][dim];
        if constexpr (dim == 2)
          {
            const auto &x = X[0], &y = X[1];
            for (unsigned int i = 0; i < 3; ++i)
              {
                const unsigned int j = (i + 1) % 3, k = (i + 2) % 3;
                grad[i][0] = (y[j] - y[k]) / (2. * measure);
                grad[i][1] = (x[k] - x[j]) / (2. * measure);
              }
          }
        else
          {
            // node a: (x_p - x_o) x (x_q - x_o) over the opposite face
            // (o, p, q), divided by 6 V
            constexpr unsigned int face[4][3] = {{1, 3, 2},
                                                 {0, 2, 3},
                                                 {0, 3, 1},
                                                 {0, 1, 2}};
            for (unsigned int a = 0; a < 4; ++a)
              {
                const unsigned int o = face[a][0], p = face[a][1],
                                   q = face[a][2];
                double e[3], f[3];
                for (unsigned int i = 0; i < 3; ++i)
                  {
                    e[i] = X[i][p] - X[i][o];
                    f[i] = X[i][q] - X[i][o];
                  }
                grad[a][0] = (e[1] * f[2] - e[2] * f[1]) / (6. * measure);
                grad[a][1] = (e[2] * f[0] - e[0] * f[2]) / (6. * measure);
                grad[a][2] = (e[0] * f[1] - e[1] * f[0]) / (6. * measure);
              }
          }
        // the shear strains' component pairs: xy (2D); xy, yz, xz (3D)
        constexpr unsigned int shear[3][2] = {{0, 1}, {1, 2}, {0, 2}};
        // B = strain-displacement matrix
        double B[n_strain][n_dofs] = {};
        for (unsigned int a = 0; a <= dim; ++a)
          {
            for (unsigned int p = 0; p < dim; ++p)
              B[p][dim * a + p] = grad[a][p];
            for (unsigned int s = 0; s < n_strain - dim; ++s)
              {
                const unsigned int i = shear[s][0], j = shear[s][1];
                B[dim + s][dim * a + i] = grad[a][j];
                B[dim + s][dim * a + j] = grad[a][i];
              }
          }
        double D[n_strain][n_strain] = {}, Dv[n_strain];
        for (unsigned int p = 0; p < n_strain; ++p)
          {
            if (p < dim)
              for (unsigned int q = 0; q < dim; ++q)
                D[p][q] = p == q ? lame.lambda + 2. * lame.mu : lame.lambda;
            else
              D[p][p] = lame.mu;
            Dv[p] = p < dim ? 2. : 1.;
          }
        const double weight = std::abs(measure);
        for (unsigned int r = 0; r < n_dofs; ++r)
          for (unsigned int c = 0; c < n_dofs; ++c)
            {
              double k = 0., v = 0.;
              for (unsigned int p = 0; p < n_strain; ++p)
                {
                  v += B[p][r] * Dv[p] * B[p][c];
                  for (unsigned int q = 0; q < n_strain; ++q)
                    k += B[p][r] * D[p][q] * B[q][c];
                }
              stiffness[r][c]      = weight * k;
              unit_viscosity[r][c] = weight * v;
            }
      }

      /**
       * Adds twice the one-sided matrix G of the element's joints to @p K:
       * per joined edge (2D) L / 6 [[2, 1], [1, 2]] (x) (k_n n n^T +
       * k_t t t^T), per joined face (3D) A / 12 [[2, 1, 1], [1, 2, 1],
       * [1, 1, 2]] (x) (k_n n n^T + k_t (I - n n^T)).
       */
      void
      add_joints(const ElementStepInputT<2> &e, Matrix6 &K)
      {
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
      }

      void
      add_joints(const ElementStepInputT<3> &e, Matrix12 &K)
      {
        const Coordinates<3> X = coordinates(e);
        for (unsigned int face = 0; face < 4; ++face)
          {
            const double kn = e.face_joint_normal_stiffness[face];
            const double kt = e.face_joint_tangential_stiffness[face];
            if (!(kn > 0.) && !(kt > 0.))
              continue;
            // the face opposite node `face`
            const unsigned int node[3] = {(face + 1) % 4,
                                          (face + 2) % 4,
                                          (face + 3) % 4};
            double             e1[3], e2[3];
            for (unsigned int i = 0; i < 3; ++i)
              {
                e1[i] = X[i][node[1]] - X[i][node[0]];
                e2[i] = X[i][node[2]] - X[i][node[0]];
              }
            const double c[3] = {e1[1] * e2[2] - e1[2] * e2[1],
                                 e1[2] * e2[0] - e1[0] * e2[2],
                                 e1[0] * e2[1] - e1[1] * e2[0]};
            const double twice_area =
              std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
            if (!(twice_area > 0.))
              continue;
            const double area = 0.5 * twice_area;
            const double n[3] = {c[0] / twice_area,
                                 c[1] / twice_area,
                                 c[2] / twice_area};
            // 2 G: area / 3 on the diagonal blocks, area / 6 off them
            for (unsigned int d = 0; d < 3; ++d)
              for (unsigned int f = 0; f < 3; ++f)
                {
                  const double k =
                    kn * n[d] * n[f] + kt * ((d == f ? 1. : 0.) - n[d] * n[f]);
                  for (unsigned int p = 0; p < 3; ++p)
                    for (unsigned int q = 0; q < 3; ++q)
                      K[3 * node[p] + d][3 * node[q] + f] +=
                        k * area / (p == q ? 3. : 6.);
                }
          }
      }

      /**
       * M^-1 (K_e + 2 sum G + R) and M^-1 C_e of the element (M = m I);
       * false for a degenerate element or massless nodes.
       */
      template <int dim>
      bool
      scaled_matrices(const ElementStepInputT<dim> &e,
                      ElementMatrix<dim>           &K,
                      ElementMatrix<dim>           &C)
      {
        constexpr unsigned int n_dofs  = simplex_dofs<dim>;
        const Coordinates<dim> X       = coordinates(e);
        const double           measure = signed_measure<dim>(X);
        if (!(measure > 0.) || !(e.node_mass > 0.))
          return false;
        simplex_matrices<dim>(X, e.lame, K, C);
        // joints, twice their one-sided matrix
        add_joints(e, K);
        for (unsigned int i = 0; i < n_dofs; ++i)
          K[i][i] += e.node_contact_stiffness;
        const double inv_m = 1. / e.node_mass;
        for (unsigned int r = 0; r < n_dofs; ++r)
          for (unsigned int c = 0; c < n_dofs; ++c)
            {
              K[r][c] *= inv_m;
              C[r][c] *= e.viscosity * inv_m;
            }
        return true;
      }

      /** 4 I - 2 dt C - dt^2 K positive definite (K, C scaled by 1/m). */
      template <int dim>
      bool
      stable_with(const ElementMatrix<dim> &K,
                  const ElementMatrix<dim> &C,
                  const double              dt)
      {
        constexpr unsigned int n_dofs = simplex_dofs<dim>;
        ElementMatrix<dim>     A;
        for (unsigned int r = 0; r < n_dofs; ++r)
          for (unsigned int c = 0; c < n_dofs; ++c)
            A[r][c] =
              (r == c ? 4. : 0.) - 2. * dt * C[r][c] - dt * dt * K[r][c];
        return positive_definite(A);
      }

      /** highest_mode_damping_per_viscosity() of a simplex. */
      template <int dim>
      double
      highest_mode_damping(const Coordinates<dim> &X,
                           const LameConstants    &lame,
                           const double            node_mass)
      {
        constexpr int      n_dofs = simplex_dofs<dim>;
        ElementMatrix<dim> K, C;
        simplex_matrices<dim>(X, lame, K, C);
        std::array<double, n_dofs> omega2;
        ElementMatrix<dim>         modes;
        symmetric_eigen(K, omega2, modes);
        const double top = omega2[n_dofs - 1];
        if (!(top > 0.))
          return 0.;
        // average over a (numerically) repeated highest eigenvalue
        double       sum = 0.;
        unsigned int n   = 0;
        for (int i = n_dofs - 1; i >= 0 && omega2[i] >= top * (1. - 1e-8);
             --i, ++n)
          for (int r = 0; r < n_dofs; ++r)
            for (int c = 0; c < n_dofs; ++c)
              sum += modes[r][i] * C[r][c] * modes[c][i];
        const double omega = std::sqrt(top / node_mass);
        return sum / n / (2. * node_mass * omega);
      }
    } // namespace

    void
    element_matrices(const std::array<double, 3> &x,
                     const std::array<double, 3> &y,
                     const LameConstants         &lame,
                     Matrix6                     &stiffness,
                     Matrix6                     &unit_viscosity)
    {
      simplex_matrices<2>({{x, y}}, lame, stiffness, unit_viscosity);
    }

    void
    element_matrices(const std::array<double, 4> &x,
                     const std::array<double, 4> &y,
                     const std::array<double, 4> &z,
                     const LameConstants         &lame,
                     Matrix12                    &stiffness,
                     Matrix12                    &unit_viscosity)
    {
      simplex_matrices<3>({{x, y, z}}, lame, stiffness, unit_viscosity);
    }

    template <int dim>
    bool
    stable_at(const ElementStepInputT<dim> &e, const double dt)
    {
      ElementMatrix<dim> K, C;
      return scaled_matrices(e, K, C) && stable_with<dim>(K, C, dt);
    }

    template <int dim>
    double
    critical_time_step(const ElementStepInputT<dim> &e)
    {
      ElementMatrix<dim> K, C;
      if (!scaled_matrices(e, K, C))
        return 0.;
      const auto stable = [&](const double dt) {
        return stable_with<dim>(K, C, dt);
      };
      const double k_norm = row_sum_norm(K), c_norm = row_sum_norm(C);
      if (!(k_norm > 0.) && !(c_norm > 0.))
        return std::numeric_limits<double>::infinity();
      // a sure lower bound from the norms: 2 dt |C| + dt^2 |K| <= 4
      double lo =
        k_norm > 0. ?
          (-c_norm + std::sqrt(c_norm * c_norm + 4. * k_norm)) / k_norm :
          2. / c_norm;
      // the same root without cancellation where |C|^2 >> |K| (the form
      // above rounds to 0 there, and the bisection would not end)
      if (lo == 0.)
        lo = 2. / (c_norm + std::sqrt(c_norm * c_norm + 4. * k_norm));
      if (lo == 0.)
        return 0.;
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

    template <std::size_t N>
    void
    symmetric_eigen(const std::array<std::array<double, N>, N> &matrix,
                    std::array<double, N>                      &values,
                    std::array<std::array<double, N>, N>       &vectors)
    {
      using Matrix = std::array<std::array<double, N>, N>;
      Matrix a     = matrix;
      for (unsigned int r = 0; r < N; ++r)
        for (unsigned int c = 0; c < N; ++c)
          vectors[r][c] = r == c ? 1. : 0.;
      double scale = 0.;
      for (unsigned int r = 0; r < N; ++r)
        scale = std::max(scale, std::abs(a[r][r]));
      for (unsigned int sweep = 0; sweep < 50; ++sweep)
        {
          double off = 0.;
          for (unsigned int p = 0; p < N; ++p)
            for (unsigned int q = p + 1; q < N; ++q)
              off = std::max(off, std::abs(a[p][q]));
          if (off <= 1e-15 * scale || off == 0.)
            break;
          for (unsigned int p = 0; p < N; ++p)
            for (unsigned int q = p + 1; q < N; ++q)
              {
                if (a[p][q] == 0.)
                  continue;
                // rotation that zeroes a[p][q]
                const double theta = (a[q][q] - a[p][p]) / (2. * a[p][q]);
                const double t =
                  (theta >= 0. ? 1. : -1.) /
                  (std::abs(theta) + std::sqrt(theta * theta + 1.));
                const double c = 1. / std::sqrt(t * t + 1.), s = t * c;
                for (unsigned int k = 0; k < N; ++k)
                  {
                    const double akp = a[k][p], akq = a[k][q];
                    a[k][p] = c * akp - s * akq;
                    a[k][q] = s * akp + c * akq;
                  }
                for (unsigned int k = 0; k < N; ++k)
                  {
                    const double apk = a[p][k], aqk = a[q][k];
                    a[p][k] = c * apk - s * aqk;
                    a[q][k] = s * apk + c * aqk;
                  }
                for (unsigned int k = 0; k < N; ++k)
                  {
                    const double vkp = vectors[k][p], vkq = vectors[k][q];
                    vectors[k][p] = c * vkp - s * vkq;
                    vectors[k][q] = s * vkp + c * vkq;
                  }
              }
        }
      // sort ascending, columns with their values
      std::array<unsigned int, N> order;
      for (unsigned int i = 0; i < N; ++i)
        order[i] = i;
      std::sort(order.begin(),
                order.end(),
                [&](unsigned int i, unsigned int j) {
                  return a[i][i] < a[j][j];
                });
      const Matrix v = vectors;
      for (unsigned int c = 0; c < N; ++c)
        {
          values[c] = a[order[c]][order[c]];
          for (unsigned int r = 0; r < N; ++r)
            vectors[r][c] = v[r][order[c]];
        }
    }

    double
    highest_mode_damping_per_viscosity(const std::array<double, 3> &x,
                                       const std::array<double, 3> &y,
                                       const LameConstants         &lame,
                                       const double                 node_mass)
    {
      return highest_mode_damping<2>({{x, y}}, lame, node_mass);
    }

    double
    highest_mode_damping_per_viscosity(const std::array<double, 4> &x,
                                       const std::array<double, 4> &y,
                                       const std::array<double, 4> &z,
                                       const LameConstants         &lame,
                                       const double                 node_mass)
    {
      return highest_mode_damping<3>({{x, y, z}}, lame, node_mass);
    }

    template double
    critical_time_step<2>(const ElementStepInputT<2> &);
    template double
    critical_time_step<3>(const ElementStepInputT<3> &);
    template bool
    stable_at<2>(const ElementStepInputT<2> &, const double);
    template bool
    stable_at<3>(const ElementStepInputT<3> &, const double);
    template void
    symmetric_eigen<6>(const Matrix6 &, std::array<double, 6> &, Matrix6 &);
    template void
    symmetric_eigen<12>(const Matrix12 &, std::array<double, 12> &, Matrix12 &);
  } // namespace discrete
} // namespace tmfdem
