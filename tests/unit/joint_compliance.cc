// Unit tests of the joint compliance compensation (joint_compliance.h): an
// element in series with its share of its joints must have the material's
// compliance. The joints' compliance is summed here directly from the
// opening of each joint under a uniform stress, [u] = L (sigma_nn / p_n n +
// sigma_nt / p_t t), and its average strain L^2 / (2 A) sym([u] n) per joint
// (half of each joint to the element), independently of the closed form.

#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <tmfdem/discrete/joint_compliance.h>

using namespace tmfdem::discrete;

namespace
{
  // strain {xx, yy, xy} of the 2D law with lame under stress {xx, yy, xy}
  std::array<double, 3>
  element_strain(const LameConstants &c, const std::array<double, 3> &s)
  {
    const double K = c.lambda + c.mu;
    const double m = 0.5 * (s[0] + s[1]); // sigma_m
    // eps = sigma_m / (2 K) I + dev(sigma) / (2 mu)
    return {{m / (2. * K) + (s[0] - m) / (2. * c.mu),
             m / (2. * K) + (s[1] - m) / (2. * c.mu),
             s[2] / (2. * c.mu)}};
  }

  // the joints' average strain over the element
  std::array<double, 3>
  joint_strain(const std::array<double, 3> &x,
               const std::array<double, 3> &y,
               const double                 pn,
               const double                 pt,
               const std::array<double, 3> &s,
               const std::array<bool, 3>   &jointed = {{true, true, true}})
  {
    const double area =
      0.5 * ((x[1] - x[0]) * (y[2] - y[0]) - (x[2] - x[0]) * (y[1] - y[0]));
    std::array<double, 3> eps = {{0., 0., 0.}};
    for (unsigned int k = 0; k < 3; ++k)
      {
        if (!jointed[k])
          continue;
        const unsigned int b  = (k + 1) % 3;
        const double       L  = std::hypot(x[b] - x[k], y[b] - y[k]);
        const double       t0 = (x[b] - x[k]) / L, t1 = (y[b] - y[k]) / L;
        const double       n0 = t1, n1 = -t0;
        const double       sn0 = s[0] * n0 + s[2] * n1;
        const double       sn1 = s[2] * n0 + s[1] * n1;
        const double       snn = n0 * sn0 + n1 * sn1;
        const double       snt = t0 * sn0 + t1 * sn1;
        const double       u0  = L * (snn / pn * n0 + snt / pt * t0);
        const double       u1  = L * (snn / pn * n1 + snt / pt * t1);
        const double       w   = L / (2. * area); // (L / 2) / A
        eps[0] += w * u0 * n0;
        eps[1] += w * u1 * n1;
        eps[2] += w * 0.5 * (u0 * n1 + u1 * n0);
      }
    return eps;
  }

  // strain {xx, yy, xy} of the anisotropic element C(lame) + Delta C
  // (Mandel, joint_compliance.h) under stress {xx, yy, xy}: Cramer's rule
  std::array<double, 3>
  anisotropic_element_strain(const CompensatedElement    &c,
                             const std::array<double, 3> &s)
  {
    const double r2 = std::sqrt(2.), l = c.lame.lambda, m = c.lame.mu;
    const auto  &d       = c.anisotropy;
    const double C[3][3] = {{l + 2. * m + d[0], l + d[3], d[4]},
                            {l + d[3], l + 2. * m + d[1], d[5]},
                            {d[4], d[5], 2. * m + d[2]}};
    const double b[3]    = {s[0], s[1], r2 * s[2]};
    auto         det     = [](const double A[3][3]) {
      return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
             A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
             A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
    };
    const double          D = det(C);
    std::array<double, 3> e;
    for (unsigned int k = 0; k < 3; ++k)
      {
        double A[3][3];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            A[i][j] = j == k ? b[i] : C[i][j];
        e[k] = det(A) / D;
      }
    return {{e[0], e[1], e[2] / r2}};
  }
} // namespace

TEST(JointCompliance, AnisotropicElementWithSomeJointsHasTheMaterialsCompliance)
{
  // a triangle of no particular shape with joints on all, two or one of
  // its edges (a triangle on a free edge has none along it): the element
  // and its joints in series have the material's compliance under every
  // stress; the isotropic compensation alone misses along the free edge
  const double E = 10e9, nu = 0.25;
  for (const auto ideal :
       {Idealisation::plane_stress, Idealisation::plane_strain})
    for (const double ratio_t : {1., 0.3})
      for (const std::array<bool, 3> jointed :
           {std::array<bool, 3>{{true, true, true}},
            std::array<bool, 3>{{false, true, true}},
            std::array<bool, 3>{{true, false, false}}})
        {
          const LameConstants         lame = lame_constants(E, nu, ideal);
          const double                pn = 10. * E, pt = ratio_t * pn;
          const std::array<double, 3> x = {{0., 1., 0.35}},
                                      y = {{0., 0.05, 0.8}};
          std::array<double, 3> normal{}, tangential{};
          for (unsigned int k = 0; k < 3; ++k)
            if (jointed[k])
              {
                normal[k]     = pn;
                tangential[k] = pt;
              }
          const CompensatedElement c = compensate_joint_compliance(x,
                                                                   y,
                                                                   lame,
                                                                   normal,
                                                                   tangential,
                                                                   0.75,
                                                                   true);
          ASSERT_FALSE(c.capped);
          EXPECT_GE(c.stiffness_bound_factor, 1.);
          double worst_isotropic = 0.;
          for (const std::array<double, 3> s :
               {std::array<double, 3>{{1., 0., 0.}},
                std::array<double, 3>{{0., 1., 0.}},
                std::array<double, 3>{{0., 0., 1.}},
                std::array<double, 3>{{1., 1., 0.}},
                std::array<double, 3>{{0.3, -0.7, 0.4}},
                std::array<double, 3>{{-0.2, 0.5, -0.9}}})
            {
              const auto target = element_strain(lame, s);
              const auto e      = anisotropic_element_strain(c, s);
              const auto j      = joint_strain(x, y, pn, pt, s, jointed);
              const auto iso    = element_strain(c.lame, s);
              for (unsigned int i = 0; i < 3; ++i)
                {
                  EXPECT_NEAR(e[i] + j[i], target[i], 1e-12 / E)
                    << "component " << i;
                  worst_isotropic =
                    std::max(worst_isotropic,
                             std::abs(iso[i] + j[i] - target[i]) * E);
                }
            }
          if (!jointed[0])
            {
              EXPECT_GT(worst_isotropic, 0.01) << "the isotropic part misses";
            }
        }
}

TEST(JointCompliance, AnisotropicStressIsTheDerivativeOfItsEnergy)
{
  // sigma = F (Delta C : E) F^T / J against the numerical derivative of
  // psi = E : Delta C : E / 2: P = d psi / d F, sigma = P F^T / J
  const double  dC[6] = {3e9, 1e9, 2e9, -0.5e9, 0.7e9, -0.3e9};
  const Matrix2 F     = matrix2(1.02, 0.03, -0.05, 0.97);
  const Stress2 sigma = anisotropic_stress(F, dC);
  double        P[2][2];
  for (unsigned int i = 0; i < 2; ++i)
    for (unsigned int j = 0; j < 2; ++j)
      {
        const double h  = 1e-6;
        Matrix2      Fp = F, Fm = F;
        Fp(i, j) += h;
        Fm(i, j) -= h;
        P[i][j] = (anisotropic_energy_density(Fp, dC) -
                   anisotropic_energy_density(Fm, dC)) /
                  (2. * h);
      }
  const double J    = F.determinant();
  const double s_xx = (P[0][0] * F(0, 0) + P[0][1] * F(0, 1)) / J;
  const double s_yy = (P[1][0] * F(1, 0) + P[1][1] * F(1, 1)) / J;
  const double s_xy = (P[0][0] * F(1, 0) + P[0][1] * F(1, 1)) / J;
  EXPECT_NEAR(sigma.xx, s_xx, 1e-6 * 3e9 * 0.05);
  EXPECT_NEAR(sigma.yy, s_yy, 1e-6 * 3e9 * 0.05);
  EXPECT_NEAR(sigma.xy, s_xy, 1e-6 * 3e9 * 0.05);
  // and in the small-strain limit Delta C : eps
  const double  eps   = 1e-7;
  const Stress2 small = anisotropic_stress(matrix2(1. + eps, 0., 0., 1.), dC);
  EXPECT_NEAR(small.xx, dC[0] * eps, 1e-6 * dC[0] * eps);
  EXPECT_NEAR(small.yy, dC[3] * eps, 1e-6 * dC[0] * eps);
  EXPECT_NEAR(small.xy, dC[4] * eps / std::sqrt(2.), 1e-6 * dC[0] * eps);
}

TEST(JointCompliance, EquilateralElementWithJointsHasTheMaterialsStiffness)
{
  const double E = 370e9, nu = 0.22, h = 0.4e-3;
  for (const auto ideal :
       {Idealisation::plane_stress, Idealisation::plane_strain})
    for (const double factor : {1., 10., 20., 1000.})
      for (const double ratio_t : {1., 0.1})
        {
          const LameConstants lame = lame_constants(E, nu, ideal);
          const double        pn = factor * E, pt = ratio_t * factor * E;
          // rotated by 0.3 rad: nothing depends on the orientation
          const double                a = 0.3;
          std::array<double, 3>       x, y;
          const std::array<double, 3> X = {{0., h, 0.5 * h}},
                                      Y = {{0., 0., 0.5 * std::sqrt(3.) * h}};
          for (unsigned int k = 0; k < 3; ++k)
            {
              x[k] = std::cos(a) * X[k] - std::sin(a) * Y[k];
              y[k] = std::sin(a) * X[k] + std::cos(a) * Y[k];
            }
          const CompensatedElement c =
            compensate_joint_compliance(x,
                                        y,
                                        lame,
                                        {{pn, pn, pn}},
                                        {{pt, pt, pt}},
                                        0.99);
          EXPECT_NEAR(c.weight, 2. * std::sqrt(3.), 1e-12);
          if (c.capped)
            continue; // factor 1: the joints alone are softer than E
          for (const std::array<double, 3> s :
               {std::array<double, 3>{{1., 1., 0.}},
                std::array<double, 3>{{1., 0., 0.}},
                std::array<double, 3>{{0., 1., 0.}},
                std::array<double, 3>{{0., 0., 1.}},
                std::array<double, 3>{{0.3, -0.7, 0.4}}})
            {
              const auto target = element_strain(lame, s);
              const auto e      = element_strain(c.lame, s);
              const auto j      = joint_strain(x, y, pn, pt, s);
              for (unsigned int i = 0; i < 3; ++i)
                EXPECT_NEAR(e[i] + j[i], target[i], 1e-12 / E)
                  << "p_n = " << factor << " E, component " << i;
            }
        }
}

TEST(JointCompliance, AnyShapeHasTheMaterialsAreaStiffness)
{
  // under an isotropic stress the trace of the element's and its joints'
  // strain is the material's, whatever the shape
  const double        E = 10e9, nu = 0.25, p = 20. * E;
  const LameConstants lame = lame_constants(E, nu, Idealisation::plane_stress);
  const std::array<double, 3> x = {{0., 1., 0.2}}, y = {{0., 0.1, 0.6}};
  const CompensatedElement    c =
    compensate_joint_compliance(x, y, lame, {{p, p, p}}, {{p, p, p}}, 0.75);
  EXPECT_FALSE(c.capped);
  const std::array<double, 3> s      = {{-2., -2., 0.}};
  const auto                  target = element_strain(lame, s);
  const auto                  e      = element_strain(c.lame, s);
  const auto                  j      = joint_strain(x, y, p, p, s);
  EXPECT_NEAR(e[0] + e[1] + j[0] + j[1], target[0] + target[1], 1e-12 / E);
}

TEST(JointCompliance, NoJointsNoChangeAndCap)
{
  const double        E = 10e9, nu = 0.25;
  const LameConstants lame = lame_constants(E, nu, Idealisation::plane_stress);
  const std::array<double, 3> x = {{0., 1., 0.}}, y = {{0., 0., 1.}};
  const CompensatedElement    free = compensate_joint_compliance(x,
                                                              y,
                                                              lame,
                                                              {{0., 0., 0.}},
                                                              {{0., 0., 0.}},
                                                              0.75);
  EXPECT_EQ(free.lame.mu, lame.mu);
  EXPECT_EQ(free.lame.lambda, lame.lambda);
  EXPECT_EQ(free.weight, 0.);
  // one joint on the hypotenuse (L^2 / (2 A) = 2): W K / p_n = 2 K / p_n
  const double             p = 10. * E;
  const CompensatedElement one =
    compensate_joint_compliance(x, y, lame, {{0., p, 0.}}, {{0., p, 0.}}, 0.75);
  EXPECT_NEAR(one.weight, 2., 1e-14);
  const double K = lame.lambda + lame.mu;
  EXPECT_NEAR(1. / (one.lame.lambda + one.lame.mu), 1. / K - 2. / p, 1e-14 / E);
  EXPECT_NEAR(1. / one.lame.mu, 1. / lame.mu - 2. * (2. / p) / 2., 1e-14 / E);
  // a penalty of 0.1 E: the joints would take more than the element can
  // give; the stiffening stops at 1 / (1 - 0.75) = 4
  const CompensatedElement soft =
    compensate_joint_compliance(x,
                                y,
                                lame,
                                {{0., 0.1 * E, 0.}},
                                {{0., 0.1 * E, 0.}},
                                0.75);
  EXPECT_TRUE(soft.capped);
  EXPECT_GT(soft.share, 1.);
  EXPECT_NEAR(soft.lame.mu, 4. * lame.mu, 1e-6 * lame.mu);
  EXPECT_NEAR(soft.lame.lambda + soft.lame.mu, 4. * K, 1e-6 * K);
}

namespace
{
  using Tensor3 = std::array<std::array<double, 3>, 3>;

  // strain of the 3D isotropic law with lame under stress s:
  // eps = sigma_m / (3 K) I + dev(sigma) / (2 mu)
  Tensor3
  element_strain_3d(const LameConstants &c, const Tensor3 &s)
  {
    const double K = c.lambda + 2. * c.mu / 3.;
    const double m = (s[0][0] + s[1][1] + s[2][2]) / 3.;
    Tensor3      e;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        e[i][j] = (s[i][j] - (i == j ? m : 0.)) / (2. * c.mu) +
                  (i == j ? m / (3. * K) : 0.);
    return e;
  }

  // the face joints' average strain over a tetrahedron: face k (opposite
  // node k) of area a and size h (mean edge) opens by [u] = h (sigma_nn /
  // p_n n + (sigma n - sigma_nn n) / p_t); half of it to the element:
  // a sym([u] n) / (2 V)
  Tensor3
  face_joint_strain(const double (&p)[4][3],
                    const std::array<double, 4> &pn,
                    const std::array<double, 4> &pt,
                    const Tensor3               &s)
  {
    auto sub = [&](int a, int b, double *e) {
      for (int i = 0; i < 3; ++i)
        e[i] = p[b][i] - p[a][i];
    };
    auto cross = [](const double *a, const double *b, double *c) {
      c[0] = a[1] * b[2] - a[2] * b[1];
      c[1] = a[2] * b[0] - a[0] * b[2];
      c[2] = a[0] * b[1] - a[1] * b[0];
    };
    auto norm = [](const double *a) {
      return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    };
    double e1[3], e2[3], e3[3], c[3];
    sub(0, 1, e1);
    sub(0, 2, e2);
    sub(0, 3, e3);
    cross(e1, e2, c);
    const double V = std::abs(c[0] * e3[0] + c[1] * e3[1] + c[2] * e3[2]) / 6.;
    Tensor3      eps{};
    for (int k = 0; k < 4; ++k)
      {
        if (!(pn[k] > 0.))
          continue;
        const int a = (k + 1) % 4, b = (k + 2) % 4, d = (k + 3) % 4;
        double    f1[3], f2[3], f3[3], n[3];
        sub(a, b, f1);
        sub(a, d, f2);
        sub(b, d, f3);
        cross(f1, f2, n);
        const double area = 0.5 * norm(n);
        const double h    = (norm(f1) + norm(f2) + norm(f3)) / 3.;
        for (double &ni : n)
          ni /= 2. * area;
        double sn[3], snn = 0.;
        for (int i = 0; i < 3; ++i)
          {
            sn[i] = s[i][0] * n[0] + s[i][1] * n[1] + s[i][2] * n[2];
            snn += n[i] * sn[i];
          }
        double u[3];
        for (int i = 0; i < 3; ++i)
          u[i] = h * (snn / pn[k] * n[i] + (sn[i] - snn * n[i]) / pt[k]);
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            eps[i][j] += area / (2. * V) * 0.5 * (u[i] * n[j] + u[j] * n[i]);
      }
    return eps;
  }

  // the stress of C(lame) + Delta C (21 stored Mandel components) on the
  // small strain eps, by the anisotropic correction at F = I + eps
  Tensor3
  anisotropic_element_stress(const CompensatedElement &c, const Tensor3 &eps)
  {
    const double l = c.lame.lambda, m = c.lame.mu;
    const double tr = eps[0][0] + eps[1][1] + eps[2][2];
    Tensor3      s;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        s[i][j] = 2. * m * eps[i][j] + (i == j ? l * tr : 0.);
    // Delta C : eps in Mandel components, by hand
    const double r2   = std::sqrt(2.);
    const double e[6] = {eps[0][0],
                         eps[1][1],
                         eps[2][2],
                         r2 * eps[0][1],
                         r2 * eps[0][2],
                         r2 * eps[1][2]};
    const auto  &d    = c.anisotropy;
    auto         D    = [&](int i, int j) {
      if (i == j)
        return d[i];
      const int r = std::min(i, j), q = std::max(i, j);
      // row r of the entries above the diagonal: (0,1..5) 6-10, (1,2..5)
      // 11-14, (2,3..5) 15-17, (3,4..5) 18-19, (4,5) 20
      const int start[5] = {6, 11, 15, 18, 20};
      return d[start[r] + q - r - 1];
    };
    double ds[6];
    for (int i = 0; i < 6; ++i)
      {
        ds[i] = 0.;
        for (int j = 0; j < 6; ++j)
          ds[i] += D(i, j) * e[j];
      }
    s[0][0] += ds[0];
    s[1][1] += ds[1];
    s[2][2] += ds[2];
    s[0][1] += ds[3] / r2;
    s[0][2] += ds[4] / r2;
    s[1][2] += ds[5] / r2;
    s[1][0] = s[0][1];
    s[2][0] = s[0][2];
    s[2][1] = s[1][2];
    return s;
  }
} // namespace

TEST(JointCompliance,
     AnisotropicTetrahedronWithSomeJointsHasTheMaterialsCompliance)
{
  // a tetrahedron of no particular shape with joints on all, three or one
  // of its faces: under every uniform stress, the element (C(lame) +
  // Delta C) and half of each of its face joints in series strain as the
  // material; the isotropic compensation alone misses
  const double          E = 10e9, nu = 0.25;
  const double          p[4][3] = {{0., 0., 0.},
                                   {1., 0.1, -0.05},
                                   {0.3, 0.9, 0.1},
                                   {0.2, 0.25, 0.85}};
  std::array<double, 4> x, y, z;
  for (int k = 0; k < 4; ++k)
    {
      x[k] = p[k][0];
      y[k] = p[k][1];
      z[k] = p[k][2];
    }
  const LameConstants lame = lame_constants(E, nu, Idealisation::solid_3d);
  const double        stresses[4][3][3] = {
           {{1., 0., 0.}, {0., 0., 0.}, {0., 0., 0.}},
           {{0., 0., 0.}, {0., 0., 0.}, {0., 0., 1.}},
           {{0., 0.4, 0.}, {0.4, 0., 0.}, {0., 0., 0.}},
           {{0.3, -0.2, 0.5}, {-0.2, -0.7, 0.1}, {0.5, 0.1, 0.4}}};
  for (const double ratio_t : {1., 0.3})
    for (const std::array<bool, 4> jointed :
         {std::array<bool, 4>{{true, true, true, true}},
          std::array<bool, 4>{{false, true, true, true}},
          std::array<bool, 4>{{false, false, true, false}}})
      {
        const double          pn = 20. * E, pt = ratio_t * pn;
        std::array<double, 4> normal{}, tangential{};
        for (int k = 0; k < 4; ++k)
          if (jointed[k])
            {
              normal[k]     = pn;
              tangential[k] = pt;
            }
        const CompensatedElement c   = compensate_joint_compliance(x,
                                                                 y,
                                                                 z,
                                                                 lame,
                                                                 normal,
                                                                 tangential,
                                                                 0.75,
                                                                 true);
        const CompensatedElement iso = compensate_joint_compliance(x,
                                                                   y,
                                                                   z,
                                                                   lame,
                                                                   normal,
                                                                   tangential,
                                                                   0.75,
                                                                   false);
        ASSERT_FALSE(c.capped);
        EXPECT_GE(c.stiffness_bound_factor, 1.);
        double worst_isotropic = 0.;
        for (const auto &stress : stresses)
          {
            Tensor3 s;
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j)
                s[i][j] = stress[i][j];
            // the element's share of the strain, eps_e = S s - eps_J, must
            // carry the stress s: C_e eps_e = s
            const Tensor3 target = element_strain_3d(lame, s);
            const Tensor3 joint  = face_joint_strain(p, normal, tangential, s);
            Tensor3       eps_e;
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j)
                eps_e[i][j] = target[i][j] - joint[i][j];
            const Tensor3 back     = anisotropic_element_stress(c, eps_e);
            const Tensor3 back_iso = anisotropic_element_stress(iso, eps_e);
            for (int i = 0; i < 3; ++i)
              for (int j = 0; j < 3; ++j)
                {
                  EXPECT_NEAR(back[i][j], s[i][j], 1e-9)
                    << "component " << i << j;
                  worst_isotropic =
                    std::max(worst_isotropic,
                             std::abs(back_iso[i][j] - s[i][j]));
                }
          }
        EXPECT_GT(worst_isotropic, 0.01) << "the isotropic part misses";
      }
}

TEST(JointCompliance, AnisotropicStressIsTheDerivativeOfItsEnergy3D)
{
  // sigma = F (Delta C : E) F^T / J against the numerical derivative of
  // psi = E : Delta C : E / 2 (21 components), P = d psi / d F,
  // sigma = P F^T / J
  double dC[21];
  for (int k = 0; k < 21; ++k)
    dC[k] = (k < 6 ? 3e9 : 0.) + 1e9 * std::sin(1.7 * k + 0.3);
  const double F[3][3] = {{1.02, 0.03, -0.01},
                          {-0.05, 0.97, 0.04},
                          {0.02, -0.03, 1.05}};
  double       sigma[3][3];
  anisotropic_stress<3>(F, dC, sigma);
  double P[3][3];
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      {
        const double h = 1e-6;
        double       Fp[3][3], Fm[3][3];
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            Fp[a][b] = Fm[a][b] = F[a][b];
        Fp[i][j] += h;
        Fm[i][j] -= h;
        P[i][j] = (anisotropic_energy_density<3>(Fp, dC) -
                   anisotropic_energy_density<3>(Fm, dC)) /
                  (2. * h);
      }
  const double J = tmfdem::constitutive::determinant<3>(F);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      {
        double s = 0.;
        for (int k = 0; k < 3; ++k)
          s += P[i][k] * F[j][k];
        EXPECT_NEAR(sigma[i][j], s / J, 1e-6 * 3e9 * 0.05)
          << "component " << i << j;
      }
}
