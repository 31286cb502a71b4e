// Unit tests of the discrete layer's kernels: the finite-strain triangle
// (Eq. 44 on F_e), the cohesive law's work to break, and the exact contact
// integrals, each against an independent evaluation.

#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <tmfdem/discrete/cohesive_law.h>
#include <tmfdem/discrete/contact.h>
#include <tmfdem/discrete/solid.h>

using namespace tmfdem::discrete;

namespace
{
  const double E = 10e9, nu = 0.25;

  Stress2
  stress_of(const double        *x,
            const double        *y,
            const double        *X,
            const double        *Y,
            const LameConstants &lame,
            const double         thermal_stretch = 1.)
  {
    const Matrix2 F =
      element_basis(x[0], y[0], x[1], y[1], x[2], y[2]) *
      element_basis(X[0], Y[0], X[1], Y[1], X[2], Y[2]).inverse();
    const double s = thermal_stretch;
    return elastic_stress(F / s, lame);
  }
} // namespace

TEST(Solid, UniaxialStretchMatchesEquation44ByHand)
{
  const LameConstants lame = lame_constants(E, nu, Idealisation::plane_stress);
  const double        X[3] = {0., 1., 0.}, Y[3] = {0., 0., 1.};
  const double        stretch = 1.1;
  const double        x[3] = {0., stretch, 0.}, y[3] = {0., 0., 1.};
  const Stress2       s = stress_of(x, y, X, Y, lame);
  // Eq. 44: T = 2 mu / J E + lambda/2 (J - 1/J) I, E = (B - I)/2,
  // J = 1.1, B = diag(1.21, 1)
  const double mu = E / (2 * (1 + nu)), lambda = E * nu / (1 - nu * nu);
  const double J = stretch;
  EXPECT_NEAR(s.xx,
              2 * mu / J * 0.5 * (1.21 - 1.) + lambda / 2 * (J - 1 / J),
              1e-6 * E);
  EXPECT_NEAR(s.yy, lambda / 2 * (J - 1 / J), 1e-6 * E);
  EXPECT_NEAR(s.xy, 0., 1e-9 * E);
}

TEST(Solid, SmallStrainLimitIsLinearElasticity)
{
  for (const auto idealisation :
       {Idealisation::plane_stress, Idealisation::plane_strain})
    {
      const LameConstants lame = lame_constants(E, nu, idealisation);
      const double        eps  = 1e-7;
      const double        X[3] = {0., 1., 0.}, Y[3] = {0., 0., 1.};
      const double        x[3] = {0., 1. + eps, 0.}, y[3] = {0., 0., 1.};
      const Stress2       s       = stress_of(x, y, X, Y, lame);
      const double        modulus = idealisation == Idealisation::plane_stress ?
                                      E / (1 - nu * nu) :
                                      E * (1 - nu) / ((1 + nu) * (1 - 2 * nu));
      EXPECT_NEAR(s.xx / (modulus * eps), 1., 1e-5);
    }
}

TEST(Solid, RigidRotationOf90DegreesGivesNoStress)
{
  const LameConstants lame = lame_constants(E, nu, Idealisation::plane_strain);
  const double        X[3] = {0.1, 0.7, 0.2}, Y[3] = {0.05, 0.1, 0.6};
  double              x[3], y[3];
  for (unsigned int k = 0; k < 3; ++k)
    {
      x[k] = 3. - Y[k]; // rotation by +90 degrees plus a translation
      y[k] = -1. + X[k];
    }
  const Stress2 s = stress_of(x, y, X, Y, lame);
  EXPECT_LT(std::abs(s.xx) + std::abs(s.yy) + std::abs(s.xy), 1e-12 * E);
}

TEST(Solid, PatchUnderUniformStrainHasUniformStressAndBalancedInteriorNode)
{
  // a square split into four triangles around its centre (node 4)
  const double X[5] = {0., 1., 1., 0., 0.45}, Y[5] = {0., 0., 1., 1., 0.55};
  const unsigned int triangles[4][3] = {{0, 1, 4},
                                        {1, 2, 4},
                                        {2, 3, 4},
                                        {3, 0, 4}};
  const double A[4] = {1.02, 0.03, -0.01, 0.97}; // affine map, finite strain
  const LameConstants lame = lame_constants(E, nu, Idealisation::plane_stress);
  double              centre_force[2] = {0., 0.};
  Stress2             first;
  for (unsigned int t = 0; t < 4; ++t)
    {
      double Xe[3], Ye[3], xe[3], ye[3];
      for (unsigned int k = 0; k < 3; ++k)
        {
          const unsigned int n = triangles[t][k];
          Xe[k]                = X[n];
          Ye[k]                = Y[n];
          xe[k]                = A[0] * X[n] + A[1] * Y[n] + 0.3;
          ye[k]                = A[2] * X[n] + A[3] * Y[n] - 0.2;
        }
      const Stress2 s = stress_of(xe, ye, Xe, Ye, lame);
      if (t == 0)
        first = s;
      EXPECT_NEAR(s.xx, first.xx, 1e-9 * E);
      EXPECT_NEAR(s.yy, first.yy, 1e-9 * E);
      EXPECT_NEAR(s.xy, first.xy, 1e-9 * E);
      double f[6];
      nodal_forces(s, xe[0], ye[0], xe[1], ye[1], xe[2], ye[2], f);
      centre_force[0] += f[4];
      centre_force[1] += f[5];
    }
  EXPECT_LT(std::hypot(centre_force[0], centre_force[1]), 1e-9 * E);
}

TEST(Solid, NodalForcesAreMinusTheGradientOfTheStrainEnergy)
{
  const LameConstants lame = lame_constants(E, nu, Idealisation::plane_strain);
  const double        X[3] = {0., 1., 0.2}, Y[3] = {0., 0.1, 0.9};
  double              x[3] = {0.01, 1.1, 0.15}, y[3] = {-0.02, 0.12, 0.95};
  const double        s = 1.02; // with a thermal stretch
  const double        area0 =
    0.5 * element_basis(X[0], Y[0], X[1], Y[1], X[2], Y[2]).determinant();
  auto energy = [&]() {
    const Matrix2 F =
      element_basis(x[0], y[0], x[1], y[1], x[2], y[2]) *
      element_basis(X[0], Y[0], X[1], Y[1], X[2], Y[2]).inverse();
    return area0 * s * s * strain_energy_density(Matrix2(F / s), lame);
  };
  double f[6];
  nodal_forces(stress_of(x, y, X, Y, lame, s),
               x[0],
               y[0],
               x[1],
               y[1],
               x[2],
               y[2],
               f);
  const double h = 1e-7;
  for (unsigned int k = 0; k < 3; ++k)
    for (unsigned int d = 0; d < 2; ++d)
      {
        double &c = d == 0 ? x[k] : y[k];
        c += h;
        const double plus = energy();
        c -= 2 * h;
        const double minus = energy();
        c += h;
        EXPECT_NEAR(f[2 * k + d], -(plus - minus) / (2 * h), 1e-5 * E);
      }
}

namespace
{
  /** Work of the law along a monotone path (o(t), s(t)) until broken. */
  template <SofteningLaw law>
  double
  work_to_break(const JointConstants &k,
                const double          o_rate,
                const double          s_rate)
  {
    double        damage = 0., work = 0.;
    double        o = 0., s = 0.;
    JointTraction previous = cohesive_traction<law>(o, s, k, damage);
    const double  total =
      1.5 * (k.softening_width_I + 2 * k.tensile_strength / k.normal_stiffness +
             k.softening_width_II + 2 * k.cohesion / k.tangential_stiffness);
    const unsigned int n = 400000;
    for (unsigned int i = 1; i <= n && damage < 1.; ++i)
      {
        const double do_ = o_rate * total / n, ds = s_rate * total / n;
        o += do_;
        s += ds;
        const JointTraction t = cohesive_traction<law>(o, s, k, damage);
        work += 0.5 * (t.normal + previous.normal) * do_ +
                0.5 * (t.shear + previous.shear) * ds;
        previous = t;
      }
    EXPECT_GE(damage, 1.);
    return work;
  }
} // namespace

TEST(CohesiveLaw, WorkToBreakEqualsFractureEnergyInModeIAndII)
{
  const double GI = 120., GII = 600., h = 0.01;
  for (const auto law : {SofteningLaw::munjiza, SofteningLaw::linear})
    {
      JointConstants k;
      ASSERT_TRUE(make_joint_constants(3e6,
                                       8e6,
                                       30.,
                                       GI,
                                       GII,
                                       10 * E,
                                       10 * E,
                                       h,
                                       law,
                                       k));
      const double wI  = law == SofteningLaw::linear ?
                           work_to_break<SofteningLaw::linear>(k, 1., 0.) :
                           work_to_break<SofteningLaw::munjiza>(k, 1., 0.);
      const double wII = law == SofteningLaw::linear ?
                           work_to_break<SofteningLaw::linear>(k, 0., 1.) :
                           work_to_break<SofteningLaw::munjiza>(k, 0., 1.);
      EXPECT_NEAR(wI / GI, 1., 1e-3);
      EXPECT_NEAR(wII / GII, 1., 1e-3);
    }
  EXPECT_NEAR(softening_integral(SofteningLaw::munjiza), 0.3863, 5e-4);
  EXPECT_NEAR(softening_integral(SofteningLaw::linear), 0.5, 1e-12);
}

TEST(CohesiveLaw, PenaltyTooSoftForTheFractureEnergyIsRefused)
{
  JointConstants k;
  // pre-peak work 4/3 f^2 h / p = 4/3 * 1e12 * 1 / 1e10 = 133 J/m^2 > G
  EXPECT_FALSE(make_joint_constants(1e6,
                                    1e6,
                                    30.,
                                    100.,
                                    1000.,
                                    1e10,
                                    1e10,
                                    1.,
                                    SofteningLaw::linear,
                                    k));
}

TEST(CohesiveLaw, MohrCoulombShearStrengthGrowsWithCompression)
{
  JointConstants k;
  ASSERT_TRUE(make_joint_constants(3e6,
                                   8e6,
                                   30.,
                                   100.,
                                   500.,
                                   10 * E,
                                   10 * E,
                                   0.01,
                                   SofteningLaw::linear,
                                   k));
  double       damage  = 0.;
  const double o       = -1e-7; // compression sigma = k_n o
  const double sigma_n = k.normal_stiffness * o;
  const double slip_peak =
    2 * (k.cohesion - sigma_n * std::tan(M_PI / 6)) / k.tangential_stiffness;
  const JointTraction t =
    cohesive_traction<SofteningLaw::linear>(o, slip_peak, k, damage);
  EXPECT_NEAR(t.shear,
              k.cohesion - sigma_n * std::tan(M_PI / 6),
              1e-6 * k.cohesion);
  EXPECT_EQ(damage, 0.);
}

TEST(Contact, EdgeIntegralsAreExact)
{
  std::mt19937_64                        random(7);
  std::uniform_real_distribution<double> u(-1., 1.);
  const double tx[3] = {0., 1., 0.2}, ty[3] = {0., 0.1, 0.9};
  const double det =
    (ty[1] - ty[2]) * (tx[0] - tx[2]) + (tx[2] - tx[1]) * (ty[0] - ty[2]);
  unsigned int entered = 0;
  for (unsigned int trial = 0; trial < 200; ++trial)
    {
      const double px = 0.4 + 0.6 * u(random), py = 0.3 + 0.6 * u(random);
      const double qx = 0.4 + 0.6 * u(random), qy = 0.3 + 0.6 * u(random);
      EdgePotentialIntegrals I;
      const bool inside = edge_potential_integrals(px, py, qx, qy, tx, ty, I);
      // brute force: midpoint rule with 2e5 points
      const unsigned int n     = 200000;
      double             start = 0., end = 0., target[3] = {0., 0., 0.};
      for (unsigned int i = 0; i < n; ++i)
        {
          const double s = (i + 0.5) / n;
          const double x = px + s * (qx - px), y = py + s * (qy - py);
          const double l0 =
            ((ty[1] - ty[2]) * (x - tx[2]) + (tx[2] - tx[1]) * (y - ty[2])) /
            det;
          const double l1 =
            ((ty[2] - ty[0]) * (x - tx[2]) + (tx[0] - tx[2]) * (y - ty[2])) /
            det;
          const double l2  = 1. - l0 - l1;
          const double phi = 3. * std::max(0., std::min(l0, std::min(l1, l2)));
          start += phi * (1 - s) / n;
          end += phi * s / n;
          target[0] += phi * l0 / n;
          target[1] += phi * l1 / n;
          target[2] += phi * l2 / n;
        }
      if (!inside)
        {
          EXPECT_LT(start + end, 1e-12);
          continue;
        }
      ++entered;
      EXPECT_NEAR(I.phi_start, start, 1e-6);
      EXPECT_NEAR(I.phi_end, end, 1e-6);
      for (unsigned int k = 0; k < 3; ++k)
        EXPECT_NEAR(I.phi_target[k], target[k], 1e-6);
      // the reaction is distributed without loss: sum of target weights
      EXPECT_NEAR(I.phi_target[0] + I.phi_target[1] + I.phi_target[2],
                  I.total(),
                  1e-12);
    }
  EXPECT_GT(entered, 50u);
}

TEST(Contact, LinkedCellsFindAllOverlappingBoxes)
{
  // a row of 50 unit triangles; compare with the brute-force pair list
  std::vector<double>                    x, y;
  std::mt19937_64                        random(3);
  std::uniform_real_distribution<double> u(0., 10.);
  const unsigned int                     n = 300;
  for (unsigned int e = 0; e < n; ++e)
    {
      const double cx = u(random), cy = u(random);
      x.insert(x.end(), {cx, cx + 0.4, cx});
      y.insert(y.end(), {cy, cy, cy + 0.4});
    }
  std::vector<unsigned int> active(n);
  for (unsigned int e = 0; e < n; ++e)
    active[e] = e;
  std::vector<ContactPair> pairs;
  LinkedCellSearch         search;
  search.rebuild(
    x,
    y,
    active,
    0.05,
    [](unsigned, unsigned) { return false; },
    pairs);
  unsigned int expected = 0;
  for (unsigned int i = 0; i < n; ++i)
    for (unsigned int j = i + 1; j < n; ++j)
      {
        const double xi = x[3 * i], yi = y[3 * i], xj = x[3 * j], yj = y[3 * j];
        if (std::abs(xi - xj) <= 0.45 && std::abs(yi - yj) <= 0.45)
          ++expected;
      }
  EXPECT_EQ(pairs.size(), expected);
}
