#include <deal.II/base/symmetric_tensor.h>
#include <deal.II/base/tensor.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <tmfdem/discrete/joint_compliance.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      using Matrix3 = dealii::Tensor<2, 3>;

      /** The isotropic stiffness of @p lame as a Mandel matrix. */
      Matrix3
      isotropic_stiffness(const LameConstants &lame)
      {
        Matrix3 C;
        C[0][0] = C[1][1] = lame.lambda + 2. * lame.mu;
        C[0][1] = C[1][0] = lame.lambda;
        C[2][2]           = 2. * lame.mu;
        return C;
      }

      /** C(lame)^(power) for power +-1/2: the Mandel matrix of an isotropic
       *  stiffness has the eigenvalues 2K (bulk, (1, 1, 0) / sqrt 2) and
       *  2 mu (the rest). */
      Matrix3
      isotropic_stiffness_power(const LameConstants &lame, const double power)
      {
        const double bulk  = std::pow(2. * (lame.lambda + lame.mu), power);
        const double shear = std::pow(2. * lame.mu, power);
        Matrix3      P;
        for (unsigned int i = 0; i < 3; ++i)
          P[i][i] = shear;
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            P[i][j] += 0.5 * (bulk - shear);
        return P;
      }

      /** The largest eigenvalue of the symmetric part of @p A. */
      double
      largest_eigenvalue(const Matrix3 &A)
      {
        return dealii::eigenvalues(dealii::symmetrize(A))[0];
      }

      using Matrix6 = Eigen::Matrix<double, 6, 6>;
      using Vector6 = Eigen::Matrix<double, 6, 1>;

      /** The Mandel vector (mandel_pair<3>()) of the symmetric part of the
       *  3x3 tensor @p t. */
      Vector6
      mandel_vector(const double (&t)[3][3])
      {
        Vector6 m;
        for (int k = 0; k < 6; ++k)
          {
            const auto [i, j] = mandel_pair<3>(k);
            m[k] = i == j ? t[i][i] : mandel_sqrt2 * 0.5 * (t[i][j] + t[j][i]);
          }
        return m;
      }

      /** C(lame)^(power) of the 3D isotropic stiffness as a Mandel matrix:
       *  the eigenvalues 3K (on (1, 1, 1, 0, 0, 0) / sqrt 3) and 2 mu (the
       *  rest); power 1 is C itself. */
      Matrix6
      isotropic_stiffness_power_3d(const LameConstants &lame,
                                   const double         power)
      {
        const double bulk  = std::pow(3. * lame.lambda + 2. * lame.mu, power);
        const double shear = std::pow(2. * lame.mu, power);
        Matrix6      P     = shear * Matrix6::Identity();
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            P(i, j) += (bulk - shear) / 3.;
        return P;
      }

      /** The largest eigenvalue of the symmetric part of @p A. */
      double
      largest_eigenvalue(const Matrix6 &A)
      {
        const Matrix6 symmetric = 0.5 * (A + A.transpose());
        return Eigen::SelfAdjointEigenSolver<Matrix6>(symmetric,
                                                      Eigen::EigenvaluesOnly)
          .eigenvalues()
          .maxCoeff();
      }

      /** The Mandel algebra of the anisotropic compensation: 2D (3x3,
       *  deal.II tensors) and 3D (6x6, Eigen matrices). */
      template <int dim>
      struct MandelAlgebra;

      template <>
      struct MandelAlgebra<2>
      {
        using Matrix = Matrix3;
        static Matrix
        stiffness(const LameConstants &lame)
        {
          return isotropic_stiffness(lame);
        }
        static Matrix
        compliance(const LameConstants &lame)
        {
          return dealii::invert(isotropic_stiffness(lame));
        }
        static Matrix
        power(const LameConstants &lame, const double p)
        {
          return isotropic_stiffness_power(lame, p);
        }
        static Matrix
        inverse(const Matrix &m)
        {
          return dealii::invert(m);
        }
        static double
        entry(const Matrix &m, const int i, const int j)
        {
          return m[i][j];
        }
      };

      template <>
      struct MandelAlgebra<3>
      {
        using Matrix = Matrix6;
        static Matrix
        stiffness(const LameConstants &lame)
        {
          return isotropic_stiffness_power_3d(lame, 1.);
        }
        static Matrix
        compliance(const LameConstants &lame)
        {
          return isotropic_stiffness_power_3d(lame, -1.);
        }
        static Matrix
        power(const LameConstants &lame, const double p)
        {
          return isotropic_stiffness_power_3d(lame, p);
        }
        static Matrix
        inverse(const Matrix &m)
        {
          return m.inverse();
        }
        static double
        entry(const Matrix &m, const int i, const int j)
        {
          return m(i, j);
        }
      };

      /**
       * The joints' compliance tensor @p SJ (Mandel) removed from the
       * material's compliance S = C(lame)^-1, written once for triangles
       * and tetrahedra: the joints' share of S in its worst direction (the
       * largest eigenvalue of C^1/2 S_J C^1/2) into result.share, S_J
       * scaled down to @p max_share where it is larger, C_e = (S - S_J)^-1
       * less the isotropic C(result.lame) into result.anisotropy, and the
       * factor f with C_e <= f C(result.lame) (the largest eigenvalue of
       * C(lame_e)^-1/2 C_e C(lame_e)^-1/2) into
       * result.stiffness_bound_factor.
       */
      template <int dim>
      void
      remove_joint_compliance(typename MandelAlgebra<dim>::Matrix SJ,
                              const LameConstants                &lame,
                              const double                        max_share,
                              CompensatedElement                 &result)
      {
        using Algebra       = MandelAlgebra<dim>;
        using Matrix        = typename Algebra::Matrix;
        const Matrix root_C = Algebra::power(lame, 0.5);
        const double share  = largest_eigenvalue(root_C * SJ * root_C);
        result.share        = std::max(result.share, share);
        if (share > max_share)
          {
            result.capped = true;
            SJ *= max_share / share;
          }
        const Matrix Ce    = Algebra::inverse(Algebra::compliance(lame) - SJ);
        const Matrix delta = Ce - Algebra::stiffness(result.lame);
        for (int i = 0; i < mandel_size<dim>; ++i)
          for (int j = i; j < mandel_size<dim>; ++j)
            result.anisotropy[anisotropy_index<dim>(i, j)] =
              i == j ? Algebra::entry(delta, i, i) :
                       0.5 * (Algebra::entry(delta, i, j) +
                              Algebra::entry(delta, j, i));
        const Matrix inverse_root = Algebra::power(result.lame, -0.5);
        result.stiffness_bound_factor =
          std::max(1., largest_eigenvalue(inverse_root * Ce * inverse_root));
      }

      void
      anisotropic_compensation(const std::array<double, 3> &x,
                               const std::array<double, 3> &y,
                               const double                 area,
                               const LameConstants         &lame,
                               const std::array<double, 3> &normal_penalty,
                               const std::array<double, 3> &tangential_penalty,
                               const double                 max_share,
                               CompensatedElement          &result)
      {
        // the joints' compliance tensor S_J (Mandel)
        Matrix3 SJ;
        for (unsigned int k = 0; k < 3; ++k)
          {
            const double pn = normal_penalty[k], pt = tangential_penalty[k];
            if (!(pn > 0.) || !(pt > 0.))
              continue;
            const unsigned int b  = (k + 1) % 3;
            const double       ex = x[b] - x[k], ey = y[b] - y[k];
            const double       L2 = ex * ex + ey * ey;
            const double       L  = std::sqrt(L2);
            const double       tx = ex / L, ty = ey / L;
            const double       nx = ty, ny = -tx;
            const double       w = L2 / (2. * area);
            const double mn[3]   = {nx * nx, ny * ny, mandel_sqrt2 * nx * ny};
            const double mt[3]   = {tx * nx,
                                    ty * ny,
                                    mandel_sqrt2 * 0.5 * (tx * ny + ty * nx)};
            for (unsigned int i = 0; i < 3; ++i)
              for (unsigned int j = 0; j < 3; ++j)
                SJ[i][j] += w * (mn[i] * mn[j] / pn + mt[i] * mt[j] / pt);
          }
        remove_joint_compliance<2>(SJ, lame, max_share, result);
      }

      /**
       * The anisotropic compensation of a tetrahedron (the 3D counterpart of
       * anisotropic_compensation()): the compliance tensor of its face
       * joints, S_J = sum_k w_k (m_n m_n^T / p_n + (m_t1 m_t1^T +
       * m_t2 m_t2^T) / p_t) with m the Mandel vectors of n n, sym(t1 n),
       * sym(t2 n) (t1, t2 orthonormal in the face), removed from the
       * material's compliance: C_e = (S - S_J)^-1, capped as in 2D.
       */
      void
      anisotropic_compensation(const double (&p)[4][3],
                               const double                 volume,
                               const LameConstants         &lame,
                               const std::array<double, 4> &normal_penalty,
                               const std::array<double, 4> &tangential_penalty,
                               const double                 max_share,
                               CompensatedElement          &result)
      {
        Matrix6 SJ = Matrix6::Zero();
        for (int k = 0; k < 4; ++k)
          {
            const double pn = normal_penalty[k], pt = tangential_penalty[k];
            if (!(pn > 0.) || !(pt > 0.))
              continue;
            const int a = (k + 1) % 4, b = (k + 2) % 4, d = (k + 3) % 4;
            dealii::Tensor<1, 3> f1, f2, f3;
            for (int i = 0; i < 3; ++i)
              {
                f1[i] = p[b][i] - p[a][i];
                f2[i] = p[d][i] - p[a][i];
                f3[i] = p[d][i] - p[b][i];
              }
            const dealii::Tensor<1, 3> c    = dealii::cross_product_3d(f1, f2);
            const double               area = 0.5 * c.norm();
            const double h = (f1.norm() + f2.norm() + f3.norm()) / 3.;
            const double w = area * h / (2. * volume);
            const dealii::Tensor<1, 3> n  = c / c.norm();
            const dealii::Tensor<1, 3> t1 = f1 / f1.norm();
            const dealii::Tensor<1, 3> t2 = dealii::cross_product_3d(n, t1);
            double                     nn[3][3], t1n[3][3], t2n[3][3];
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j)
                {
                  nn[i][j]  = n[i] * n[j];
                  t1n[i][j] = t1[i] * n[j];
                  t2n[i][j] = t2[i] * n[j];
                }
            const Vector6 mn = mandel_vector(nn), mt1 = mandel_vector(t1n),
                          mt2 = mandel_vector(t2n);
            SJ += w * (mn * mn.transpose() / pn +
                       (mt1 * mt1.transpose() + mt2 * mt2.transpose()) / pt);
          }
        remove_joint_compliance<3>(SJ, lame, max_share, result);
      }

      /**
       * The isotropic compensation of an element in @p dim dimensions whose
       * joints add the bulk compliance @p bulk (to 1/K) and the shear
       * compliance @p shear (to 1/mu) [1/Pa]: the joints' shares of the
       * material's compliance (K = lambda + 2 mu / dim), capped at
       * @p max_share, into @p result (share, capped, lame).
       */
      void
      compensate_isotropic(const unsigned int   dim,
                           const double         bulk,
                           const double         shear,
                           const LameConstants &lame,
                           const double         max_share,
                           CompensatedElement  &result)
      {
        const double K =
          dim == 2 ? lame.lambda + lame.mu : lame.lambda + 2. * lame.mu / 3.;
        const double mu = lame.mu;
        // shares of the target compliance 1/K and 1/mu taken by the joints
        double share_bulk = bulk * K, share_shear = shear * mu;
        result.share = std::max(share_bulk, share_shear);
        if (result.share > max_share)
          {
            result.capped = true;
            share_bulk    = std::min(share_bulk, max_share);
            share_shear   = std::min(share_shear, max_share);
          }
        const double K_e   = K / (1. - share_bulk),
                     mu_e  = mu / (1. - share_shear);
        result.lame.mu     = mu_e;
        result.lame.lambda = dim == 2 ? K_e - mu_e : K_e - 2. * mu_e / 3.;
      }
    } // namespace

    CompensatedElement
    compensate_joint_compliance(const std::array<double, 3> &x,
                                const std::array<double, 3> &y,
                                const LameConstants         &lame,
                                const std::array<double, 3> &normal_penalty,
                                const std::array<double, 3> &tangential_penalty,
                                const double                 max_share,
                                const bool                   anisotropic)
    {
      CompensatedElement result;
      result.lame       = lame;
      const double area = 0.5 * std::abs((x[1] - x[0]) * (y[2] - y[0]) -
                                         (x[2] - x[0]) * (y[1] - y[0]));
      if (!(area > 0.))
        return result;
      // the joints' bulk (1/K) and shear (1/mu) compliances
      double bulk = 0., shear = 0.; // [1/Pa]
      for (unsigned int k = 0; k < 3; ++k)
        {
          const double pn = normal_penalty[k], pt = tangential_penalty[k];
          if (!(pn > 0.) || !(pt > 0.))
            continue;
          const unsigned int b = (k + 1) % 3;
          const double       L2 =
            (x[b] - x[k]) * (x[b] - x[k]) + (y[b] - y[k]) * (y[b] - y[k]);
          const double w = L2 / (2. * area);
          result.weight += w;
          bulk += w / pn;
          shear += w * (1. / pn + 1. / pt) / 2.;
        }
      if (result.weight == 0.)
        return result;
      compensate_isotropic(2, bulk, shear, lame, max_share, result);
      if (anisotropic)
        anisotropic_compensation(x,
                                 y,
                                 area,
                                 lame,
                                 normal_penalty,
                                 tangential_penalty,
                                 max_share,
                                 result);
      return result;
    }

    CompensatedElement
    compensate_joint_compliance(const std::array<double, 4> &x,
                                const std::array<double, 4> &y,
                                const std::array<double, 4> &z,
                                const LameConstants         &lame,
                                const std::array<double, 4> &normal_penalty,
                                const std::array<double, 4> &tangential_penalty,
                                const double                 max_share,
                                const bool                   anisotropic)
    {
      CompensatedElement result;
      result.lame          = lame;
      const double p[4][3] = {{x[0], y[0], z[0]},
                              {x[1], y[1], z[1]},
                              {x[2], y[2], z[2]},
                              {x[3], y[3], z[3]}};
      const auto   edge    = [&](const int a, const int b, double *e) {
        for (int i = 0; i < 3; ++i)
          e[i] = p[b][i] - p[a][i];
      };
      const auto cross = [](const double *a, const double *b, double *c) {
        c[0] = a[1] * b[2] - a[2] * b[1];
        c[1] = a[2] * b[0] - a[0] * b[2];
        c[2] = a[0] * b[1] - a[1] * b[0];
      };
      double e1[3], e2[3], e3[3], c[3];
      edge(0, 1, e1);
      edge(0, 2, e2);
      edge(0, 3, e3);
      cross(e1, e2, c);
      const double volume =
        std::abs(c[0] * e3[0] + c[1] * e3[1] + c[2] * e3[2]) / 6.;
      if (!(volume > 0.))
        return result;
      // the joints' bulk (1/K) and shear (1/mu) compliances [1/Pa]
      double bulk = 0., shear = 0.;
      for (int k = 0; k < 4; ++k)
        {
          const double pn = normal_penalty[k], pt = tangential_penalty[k];
          if (!(pn > 0.) || !(pt > 0.))
            continue;
          // face k: the three nodes other than k
          const int a = (k + 1) % 4, b = (k + 2) % 4, d = (k + 3) % 4;
          double    f1[3], f2[3], f3[3], n[3];
          edge(a, b, f1);
          edge(a, d, f2);
          edge(b, d, f3);
          cross(f1, f2, n);
          const double area =
            0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
          const auto length = [](const double *e) {
            return std::sqrt(e[0] * e[0] + e[1] * e[1] + e[2] * e[2]);
          };
          // the face's size h (the mean edge: joint penalties k = p / h)
          const double h = (length(f1) + length(f2) + length(f3)) / 3.;
          const double w = area * h / (2. * volume);
          result.weight += w;
          bulk += w / pn;
          shear += w * (4. / pn + 6. / pt) / 15.;
        }
      if (result.weight == 0.)
        return result;
      compensate_isotropic(3, bulk, shear, lame, max_share, result);
      if (anisotropic)
        anisotropic_compensation(p,
                                 volume,
                                 lame,
                                 normal_penalty,
                                 tangential_penalty,
                                 max_share,
                                 result);
      return result;
    }
  } // namespace discrete
} // namespace tmfdem
