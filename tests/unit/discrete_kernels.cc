// Unit tests of the discrete layer's kernels: the finite-strain triangle
// (Eq. 44 on F_e), the cohesive law's work to break, and the exact contact
// integrals, each against an independent evaluation.

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <iostream>
#include <random>
#include <tmfdem/discrete/cohesive_law.h>
#include <tmfdem/discrete/contact.h>
#include <tmfdem/discrete/contact_law.h>
#include <tmfdem/discrete/joint_kernel.h>
#include <tmfdem/discrete/solid.h>

using namespace tmfdem::discrete;

namespace
{
  const double E = 10e9, nu = 0.25;

  /** The constants of a joint of length @p h [m] with random strengths
   *  (f_t 1.5-4.5 MPa, c 4-12 MPa), phi 30 deg, G_I 120, G_II 600 J/m^2,
   *  penalties 10 E. */
  JointConstants
  random_joint_constants(std::mt19937      &random,
                         const SofteningLaw law,
                         const double       h)
  {
    std::uniform_real_distribution<double> unit(0., 1.);
    const double   tensile_strength = 3e6 * (0.5 + unit(random));
    const double   cohesion         = 8e6 * (0.5 + unit(random));
    JointConstants k;
    EXPECT_TRUE(make_joint_constants(tensile_strength,
                                     cohesion,
                                     30.,
                                     120.,
                                     600.,
                                     10 * E,
                                     10 * E,
                                     h,
                                     law,
                                     k));
    return k;
  }

  /** Minus the central difference of @p energy () in @p coordinate with
   *  the step @p step: the force it implies on that coordinate. */
  template <typename Energy>
  double
  minus_central_difference(double &coordinate, const double step, Energy energy)
  {
    coordinate += step;
    const double plus = energy();
    coordinate -= 2 * step;
    const double minus = energy();
    coordinate += step;
    return -(plus - minus) / (2 * step);
  }

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
      EXPECT_NEAR(f[2 * k + d],
                  minus_central_difference(d == 0 ? x[k] : y[k], h, energy),
                  1e-5 * E);
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

// A joint closed at one end and open at the other (a hinge): the penalty
// k_n o(u) over the closed part, against a fine midpoint rule of the same
// integrals (o linear along the edge); both ends in turn, closed parts from
// a sliver to the whole edge.
TEST(CohesiveLaw, ClosedPartOfAHingedJointIsIntegratedExactly)
{
  JointConstants k{};
  k.normal_stiffness  = 3e12; // [Pa/m]
  const double length = 0.007;
  for (const double closed : {-1e-5, -3e-7})
    for (const double open : {0., 2e-9, 1e-6, 4e-5})
      for (const bool at_start : {true, false})
        {
          const double       o0 = at_start ? closed : open;
          const double       o1 = at_start ? open : closed;
          const ClosedPart   c  = joint_closed_part(o0, o1, length, k);
          const unsigned int n  = 200000;
          double             f0 = 0., f1 = 0., energy = 0.;
          for (unsigned int i = 0; i < n; ++i)
            {
              const double u = (i + 0.5) / n;
              const double o = std::min(0., (1. - u) * o0 + u * o1);
              f0 += k.normal_stiffness * o * (1. - u) * length / n;
              f1 += k.normal_stiffness * o * u * length / n;
              energy += 0.5 * k.normal_stiffness * o * o * length / n;
            }
          // the midpoint rule's error near the kink at the closed part's
          // end: below 1e-6 of the total with 2e5 intervals
          EXPECT_NEAR(c.force_start, f0, 1e-6 * std::abs(f0 + f1));
          EXPECT_NEAR(c.force_end, f1, 1e-6 * std::abs(f0 + f1));
          EXPECT_NEAR(c.energy, energy, 1e-6 * energy);
          EXPECT_LT(c.force_start + c.force_end, 0.); // pushes apart
        }
}

namespace
{
  /**
   * joint_response() one joint at a time (double) and four per vector
   * (one joint per lane) on the same random joints: stretched, sheared,
   * compressed, hinged, past the peak and damaged (the lanes' softening
   * and square roots included, which the explicit loop's batches leave to
   * the one-at-a-time loop). Forces, softening displacements, the damage
   * written and the beyond-peak flag must be bitwise the same; and the
   * batches' instantiation (the rising branch only) must give the same
   * forces for every undamaged joint below its peak.
   */
  template <SofteningLaw law>
  void
  check_joint_lanes_match_one_joint_at_a_time()
  {
    using Lanes = LaneVector<4>::type;
    std::mt19937                           random(7);
    std::uniform_real_distribution<double> gap(-4e-6, 4e-6), unit(0., 1.);
    const double                           h = 0.004;
    std::vector<JointConstants>            k(4);
    // lanes met: below the peak, past it, closed at both ends, hinged
    unsigned int below = 0, past = 0, closed = 0, hinged = 0;
    // undamaged lanes below the peak compared with the rising branch only
    unsigned int rising_compared = 0;
    for (unsigned int round = 0; round < 400; ++round)
      {
        double x[4][4], y[4][4], damage[4][2];
        for (unsigned int l = 0; l < 4; ++l)
          {
            k[l] = random_joint_constants(random, law, h);
            // a0 = (0, 0), a1 = (h, 0); b0, b1 near them by the gaps
            x[0][l] = 0.;
            y[0][l] = 0.;
            x[1][l] = h;
            y[1][l] = 0.;
            // gaps from 4 nm (below the peak) to 4 um (far past it)
            const double scale = std::pow(10., -3. * unit(random));
            x[2][l]            = scale * gap(random);
            y[2][l]            = -scale * gap(random);
            x[3][l]            = h + scale * gap(random);
            y[3][l]            = -scale * gap(random);
            for (unsigned int q = 0; q < 2; ++q)
              damage[l][q] = unit(random) < 0.5 ? 0. : 0.9 * unit(random);
          }
        Lanes X[4], Y[4], D[2];
        for (unsigned int a = 0; a < 4; ++a)
          for (unsigned int l = 0; l < 4; ++l)
            {
              X[a][l] = x[a][l];
              Y[a][l] = y[a][l];
            }
        for (unsigned int q = 0; q < 2; ++q)
          for (unsigned int l = 0; l < 4; ++l)
            D[q][l] = damage[l][q];
        const JointConstantLanes<Lanes> kl(k.data());
        // the batches' instantiation: the rising branch only, undamaged
        Lanes                undamaged[2] = {};
        JointResponse<Lanes> rising;
        joint_response<law, false>(joint_frame(X, Y), kl, undamaged, rising);
        JointResponse<Lanes> fl;
        joint_response<law>(joint_frame(X, Y), kl, D, fl);
        for (unsigned int l = 0; l < 4; ++l)
          {
            const double xs[4]       = {x[0][l], x[1][l], x[2][l], x[3][l]};
            const double ys[4]       = {y[0][l], y[1][l], y[2][l], y[3][l]};
            const bool was_undamaged = damage[l][0] == 0. && damage[l][1] == 0.;
            JointResponse<double> f;
            joint_response<law>(joint_frame(xs, ys), k[l], damage[l], f);
            EXPECT_EQ(f.beyond_peak, rising.beyond_peak[l] != 0);
            if (was_undamaged && !f.beyond_peak)
              {
                ++rising_compared;
                EXPECT_EQ(f.a0x, rising.a0x[l]);
                EXPECT_EQ(f.a0y, rising.a0y[l]);
                EXPECT_EQ(f.a1x, rising.a1x[l]);
                EXPECT_EQ(f.a1y, rising.a1y[l]);
                EXPECT_EQ(f.frame_x, rising.frame_x[l]);
                EXPECT_EQ(f.frame_y, rising.frame_y[l]);
              }
            EXPECT_EQ(f.a0x, fl.a0x[l]);
            EXPECT_EQ(f.a0y, fl.a0y[l]);
            EXPECT_EQ(f.a1x, fl.a1x[l]);
            EXPECT_EQ(f.a1y, fl.a1y[l]);
            EXPECT_EQ(f.frame_x, fl.frame_x[l]);
            EXPECT_EQ(f.frame_y, fl.frame_y[l]);
            EXPECT_EQ(f.d_opening, fl.d_opening[l]);
            EXPECT_EQ(f.d_slip, fl.d_slip[l]);
            EXPECT_EQ(damage[l][0], D[0][l]);
            EXPECT_EQ(damage[l][1], D[1][l]);
            EXPECT_EQ(f.beyond_peak, fl.beyond_peak[l] != 0);
            const JointFrameT<double> g       = joint_frame(xs, ys);
            const double              o_start = g.d0x * g.nx + g.d0y * g.ny,
                         o_end                = g.d1x * g.nx + g.d1y * g.ny;
            (f.beyond_peak ? past : below) += 1;
            closed += o_start < 0. && o_end < 0.;
            hinged += (o_start < 0.) != (o_end < 0.);
          }
      }
    EXPECT_GT(below, 100u);
    EXPECT_GT(past, 100u);
    EXPECT_GT(closed, 100u);
    EXPECT_GT(hinged, 100u);
    EXPECT_GT(rising_compared, 100u);
  }
} // namespace

TEST(JointKernel, LanesMatchOneJointAtATimeBitwisePastThePeakToo)
{
  check_joint_lanes_match_one_joint_at_a_time<SofteningLaw::linear>();
  check_joint_lanes_match_one_joint_at_a_time<SofteningLaw::munjiza>();
}

namespace
{
  /**
   * A joint of length @p h at angle @p angle whose a0 sits at (x0, y0),
   * the B nodes displaced from the A nodes by the gaps @p gap (b0: 0, 1;
   * b1: 2, 3) [m]; positions in the order a0, a1, b0, b1.
   */
  void
  place_joint(const double  x0,
              const double  y0,
              const double  h,
              const double  angle,
              const double *gap,
              double       *x,
              double       *y)
  {
    x[0] = x0;
    y[0] = y0;
    x[1] = x0 + h * std::cos(angle);
    y[1] = y0 + h * std::sin(angle);
    x[2] = x[0] + gap[0];
    y[2] = y[0] + gap[1];
    x[3] = x[1] + gap[2];
    y[3] = y[1] + gap[3];
  }

  /** The four node forces of a joint response (JointResponse), in the
   *  order a0, a1, b0, b1 [N/m]. */
  void
  node_forces(const JointResponse<double> &f, double *fx, double *fy)
  {
    fx[0] = f.a0x + f.frame_x;
    fy[0] = f.a0y + f.frame_y;
    fx[1] = f.a1x - f.frame_x;
    fy[1] = f.a1y - f.frame_y;
    fx[2] = f.frame_x - f.a0x;
    fy[2] = f.frame_y - f.a0y;
    fx[3] = -f.a1x - f.frame_x;
    fy[3] = -f.a1y - f.frame_y;
  }
} // namespace

// A joint's forces are internal forces: they sum to zero and exert no net
// torque, whatever the joint's state, as the forces of a rigid-motion
// invariant law must. Random joints at random angles, sheared, open,
// closed, hinged, damaged and far past the peak (gaps up to 40 um on a
// 4 mm joint, the gaps of a crack opening): the torque about the origin
// relative to sum |x_i| |F_i| is round-off (the bound 1e-13 allows a few
// hundred ulps); a joint whose gap is not along its traction exerts the
// torque -(d0 x F0 + d1 x F1) without the frame force, 1e-9 to 1e-2 of
// that scale here.
TEST(JointKernel, ForcesKeepMomentumAndAngularMomentum)
{
  std::mt19937                           random(11);
  std::uniform_real_distribution<double> unit(0., 1.), sym(-1., 1.);
  const double                           h            = 0.004;
  unsigned int                           sheared_open = 0, damaged = 0;
  for (const auto law : {SofteningLaw::linear, SofteningLaw::munjiza})
    for (unsigned int round = 0; round < 2000; ++round)
      {
        const JointConstants k = random_joint_constants(random, law, h);
        // gaps from 4 nm to 40 um
        const double scale = 4e-9 * std::pow(10., 4. * unit(random));
        double       gap[4];
        for (double &g : gap)
          g = scale * sym(random);
        double x[4], y[4];
        place_joint(0.01 * sym(random),
                    0.01 * sym(random),
                    h,
                    6.283185307179586 * unit(random),
                    gap,
                    x,
                    y);
        double damage[2] = {unit(random) < 0.5 ? 0. : 0.95 * unit(random),
                            unit(random) < 0.5 ? 0. : 0.95 * unit(random)};
        JointResponse<double> f;
        if (law == SofteningLaw::linear)
          joint_response<SofteningLaw::linear>(joint_frame(x, y), k, damage, f);
        else
          joint_response<SofteningLaw::munjiza>(joint_frame(x, y),
                                                k,
                                                damage,
                                                f);
        double fx[4], fy[4];
        node_forces(f, fx, fy);
        double sum_x = 0., sum_y = 0., torque = 0., force_scale = 0.,
               torque_scale = 0.;
        for (unsigned int a = 0; a < 4; ++a)
          {
            sum_x += fx[a];
            sum_y += fy[a];
            torque += x[a] * fy[a] - y[a] * fx[a];
            const double force = std::hypot(fx[a], fy[a]);
            force_scale += force;
            torque_scale += std::hypot(x[a], y[a]) * force;
          }
        if (force_scale == 0.) // broken: no force
          continue;
        EXPECT_LE(std::abs(sum_x), 1e-14 * force_scale);
        EXPECT_LE(std::abs(sum_y), 1e-14 * force_scale);
        EXPECT_LE(std::abs(torque), 1e-13 * torque_scale)
          << "joint at gap scale " << scale << " m, damage " << damage[0]
          << ", " << damage[1];
        // without the frame force: the gaps' moment
        const JointFrameT<double> g = joint_frame(x, y);
        const double unbalanced     = std::abs(g.d0x * f.a0y - g.d0y * f.a0x +
                                           g.d1x * f.a1y - g.d1y * f.a1x);
        sheared_open += unbalanced > 1e-9 * torque_scale;
        damaged += damage[0] > 0. || damage[1] > 0.;
      }
  EXPECT_GT(sheared_open, 1000u);
  EXPECT_GT(damaged, 1000u);
}

// Below the peak, in tension, the joint's forces are minus the gradient of
// its stored energy (L / 2) sum_q phi(o_q, s_q) with the weight L frozen
// (stored_joint_energy(), an evaluation independent of the kernel): the
// opening and slip at the Gauss points differentiated through the gaps and
// through the turning normal and tangent. Central differences with a
// 1e-11 m step on joints at random angles, the bound 1e-7 of the largest
// force; the frame force is above ten times that bound in most of them (up
// to 1.2e-5 of the largest force), so that without it the test fails.
TEST(JointKernel, ForcesAreMinusTheGradientOfTheStoredEnergyBelowThePeak)
{
  std::mt19937                           random(5);
  std::uniform_real_distribution<double> unit(0., 1.), sym(-1., 1.);
  const double                           h        = 0.004;
  unsigned int                           compared = 0, turning = 0;
  for (unsigned int round = 0; round < 200; ++round)
    {
      JointConstants k;
      ASSERT_TRUE(make_joint_constants(3e6,
                                       8e6,
                                       30.,
                                       120.,
                                       600.,
                                       10 * E,
                                       10 * E,
                                       h,
                                       SofteningLaw::munjiza,
                                       k));
      const double o_peak = 2. * k.tensile_strength / k.normal_stiffness;
      const double s_peak = 2. * k.cohesion / k.tangential_stiffness;
      // gaps in the frame (opening 0.1 to 0.8 of its peak, slip within
      // +-0.8 of its peak) at both node pairs
      const double angle = 6.283185307179586 * unit(random);
      const double tx = std::cos(angle), ty = std::sin(angle);
      const double nx = ty, ny = -tx;
      double       gap[4];
      for (unsigned int p = 0; p < 2; ++p)
        {
          const double o = o_peak * (0.1 + 0.7 * unit(random));
          const double s = s_peak * 0.8 * sym(random);
          gap[2 * p]     = o * nx + s * tx;
          gap[2 * p + 1] = o * ny + s * ty;
        }
      double x[4], y[4];
      place_joint(0.01 * sym(random), 0.01 * sym(random), h, angle, gap, x, y);
      const double L      = joint_frame(x, y).L;
      auto         energy = [&]() {
        const JointFrameT<double> g = joint_frame(x, y);
        double                    e = 0.;
        for (const double u : joint_gauss_points)
          {
            const double dx = (1. - u) * g.d0x + u * g.d1x;
            const double dy = (1. - u) * g.d0y + u * g.d1y;
            e += 0.5 * L *
                 stored_joint_energy(dx * g.nx + dy * g.ny,
                                     dx * g.tx + dy * g.ty,
                                     k);
          }
        return e;
      };
      double                damage[2] = {0., 0.};
      JointResponse<double> f;
      joint_response<SofteningLaw::munjiza>(joint_frame(x, y), k, damage, f);
      ASSERT_FALSE(f.beyond_peak);
      double fx[4], fy[4];
      node_forces(f, fx, fy);
      double largest = 0.;
      for (unsigned int a = 0; a < 4; ++a)
        largest = std::max({largest, std::abs(fx[a]), std::abs(fy[a])});
      turning += std::hypot(f.frame_x, f.frame_y) > 1e-6 * largest;
      const double step = 1e-11;
      for (unsigned int a = 0; a < 4; ++a)
        for (unsigned int d = 0; d < 2; ++d)
          {
            EXPECT_NEAR(d == 0 ? fx[a] : fy[a],
                        minus_central_difference(d == 0 ? x[a] : y[a],
                                                 step,
                                                 energy),
                        1e-7 * largest);
            ++compared;
          }
    }
  EXPECT_EQ(compared, 1600u);
  EXPECT_GT(turning, 100u);
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

namespace
{
  /** The normal contact forces of a contactor triangle (nodes 0-2 of
   *  @p x, @p y) and a target (nodes 3-5) on each other, both pair
   *  directions, through PenaltyCoulombContact::edge_forces() and
   *  target_forces() (p_n = 1, no friction): f[0..5] on the contactor,
   *  f[6..11] on the target. @p potential_gradient_on_target: the target's
   *  share as the exact gradient (true) or at the contact points. */
  void
  pair_normal_forces(const double *x,
                     const double *y,
                     double       *f,
                     const bool    potential_gradient_on_target = true)
  {
    PenaltyCoulombContact law;
    law.normal_penalty               = 1.;
    law.potential_gradient_on_target = potential_gradient_on_target;
    const double v[6]                = {0., 0., 0., 0., 0., 0.};
    for (unsigned int i = 0; i < 12; ++i)
      f[i] = 0.;
    for (unsigned int pass = 0; pass < 2; ++pass)
      {
        const unsigned int c0 = pass == 0 ? 0 : 3, t0 = pass == 0 ? 3 : 0;
        double            *fc = f + 2 * c0, *ft = f + 2 * t0;
        for (unsigned int k = 0; k < 3; ++k)
          {
            const unsigned int     a = c0 + k, b = c0 + (k + 1) % 3;
            EdgePotentialIntegrals I;
            if (!edge_potential_integrals(x[a],
                                          y[a],
                                          x[b],
                                          y[b],
                                          x + t0,
                                          y + t0,
                                          I))
              continue;
            EdgeFriction slip;
            law.edge_forces(x,
                            y,
                            v,
                            v,
                            a,
                            b,
                            k,
                            (k + 1) % 3,
                            t0,
                            I,
                            1e-6,
                            slip,
                            fc,
                            ft);
          }
        // (the configurations of these tests always overlap)
        law.target_forces(x + c0, y + c0, x + t0, y + t0, ft);
      }
  }
} // namespace

// The normal contact force is minus the gradient of
// E = p int_S (phi_c + phi_t) dA (theory manual 5.5): the contactor's nodes
// get it from the edge integrals, the target's from
// add_target_potential_forces(). So it does no work around any closed path
// of the six nodes, up to the midpoint rule's O(1/N^2) over N steps per leg:
// rigid loops (rotations and translations of the contactor) and deforming
// loops (one node of either triangle around a square). Munjiza's rule
// (the target's share at the contact points) is conservative for the rigid
// loops only: its deforming-loop work is printed (0.04-0.7 % of the node's
// force times the loop's length), and asserted to be far above the bound,
// so that this test can tell the two apart.
TEST(Contact, NormalForceDoesNoWorkAroundClosedLoops)
{
  const double target_x[3] = {0., 1., 0.}, target_y[3] = {0., 0., 1.};
  const double c_x[3] = {0.3, 1.1, 0.5}, c_y[3] = {0.2, 0.5, 1.0};
  const double gx = (c_x[0] + c_x[1] + c_x[2]) / 3.;
  const double gy = (c_y[0] + c_y[1] + c_y[2]) / 3.;
  // the contactor after a rotation th about its centroid and a move (dx, dy)
  const auto place = [&](const double th,
                         const double dx,
                         const double dy,
                         double      *x,
                         double      *y) {
    for (unsigned int k = 0; k < 3; ++k)
      {
        const double rx = c_x[k] - gx, ry = c_y[k] - gy;
        x[k]     = gx + dx + std::cos(th) * rx - std::sin(th) * ry;
        y[k]     = gy + dy + std::sin(th) * rx + std::cos(th) * ry;
        x[3 + k] = target_x[k];
        y[3 + k] = target_y[k];
      }
  };
  // legs (rotation, move x, move y): rotate, move, rotate back, move back
  const double       legs[4][3] = {{0.3, 0., 0.},
                                   {0., 0.1, 0.05},
                                   {-0.3, 0., 0.},
                                   {0., -0.1, -0.05}};
  const unsigned int n          = 10000;
  double             work = 0., force_times_path = 0.;
  double             th = 0., dx = 0., dy = 0.;
  for (const auto &leg : legs)
    for (unsigned int s = 0; s < n; ++s)
      {
        double x0[6], y0[6], x1[6], y1[6], xm[6], ym[6], f[12];
        place(th, dx, dy, x0, y0);
        th += leg[0] / n;
        dx += leg[1] / n;
        dy += leg[2] / n;
        place(th, dx, dy, x1, y1);
        place(th - 0.5 * leg[0] / n,
              dx - 0.5 * leg[1] / n,
              dy - 0.5 * leg[2] / n,
              xm,
              ym);
        pair_normal_forces(xm, ym, f);
        for (unsigned int k = 0; k < 3; ++k)
          {
            work += f[2 * k] * (x1[k] - x0[k]) + f[2 * k + 1] * (y1[k] - y0[k]);
            force_times_path += std::hypot(f[2 * k], f[2 * k + 1]) *
                                std::hypot(x1[k] - x0[k], y1[k] - y0[k]);
          }
      }
  EXPECT_GT(force_times_path, 0.1); // the loop stays in contact
  EXPECT_LT(std::abs(work), 1e-9 * force_times_path);

  // deforming loops: one node of the contactor (or of the target) around a
  // square of side 0.05
  double largest_contact_point_work = 0.;
  for (const bool gradient : {true, false})
    for (unsigned int node = 0; node < 6; node += 1)
      {
        double x[6], y[6];
        place(0., 0., 0., x, y);
        const double a           = 0.05;
        const double moves[4][2] = {{a, 0.}, {0., a}, {-a, 0.}, {0., -a}};
        double       loop_work   = 0.;
        double       f0[12];
        pair_normal_forces(x, y, f0, gradient);
        // scale: the largest nodal force of the pair x the loop's length
        double largest_force = 0.;
        for (unsigned int k = 0; k < 6; ++k)
          largest_force =
            std::max(largest_force, std::hypot(f0[2 * k], f0[2 * k + 1]));
        const double force_times_perimeter = largest_force * 4. * a;
        for (const auto &move : moves)
          for (unsigned int s = 0; s < n; ++s)
            {
              double xm[6], ym[6], f[12];
              std::copy(x, x + 6, xm);
              std::copy(y, y + 6, ym);
              xm[node] += 0.5 * move[0] / n;
              ym[node] += 0.5 * move[1] / n;
              pair_normal_forces(xm, ym, f, gradient);
              loop_work +=
                f[2 * node] * move[0] / n + f[2 * node + 1] * move[1] / n;
              x[node] += move[0] / n;
              y[node] += move[1] / n;
            }
        std::cout << "  "
                  << (gradient ? "potential gradient" : "contact points")
                  << ", " << (node < 3 ? "contactor" : "target") << " node "
                  << node % 3 << " around a 0.05 x 0.05 loop: work "
                  << loop_work
                  << "; the pair's largest nodal force x the loop's length "
                  << force_times_perimeter << "\n";
        EXPECT_GT(force_times_perimeter, 1e-3); // in contact
        if (gradient)
          EXPECT_LT(std::abs(loop_work), 1e-8 * force_times_perimeter);
        else
          largest_contact_point_work =
            std::max(largest_contact_point_work,
                     std::abs(loop_work) / force_times_perimeter);
      }
  EXPECT_GT(largest_contact_point_work, 1e-5);
}

namespace
{
  /** Two random counter-clockwise triangles (nodes 0-2 and 3-5 of @p x,
   *  @p y) in [-1, 1]^2, the first shifted by 0.5 in x: often overlapping. */
  void
  random_pair(std::mt19937_64 &random, double *x, double *y)
  {
    std::uniform_real_distribution<double> u(-1., 1.);
    for (unsigned int k = 0; k < 6; ++k)
      {
        x[k] = u(random) + (k < 3 ? 0.5 : 0.);
        y[k] = u(random);
      }
    for (const unsigned int t0 : {0u, 3u})
      if ((x[t0 + 1] - x[t0]) * (y[t0 + 2] - y[t0]) -
            (y[t0 + 1] - y[t0]) * (x[t0 + 2] - x[t0]) <
          0.)
        {
          std::swap(x[t0 + 1], x[t0 + 2]);
          std::swap(y[t0 + 1], y[t0 + 2]);
        }
  }
} // namespace

// Both triangles' forces together: no net force and no net moment, for
// random overlapping pairs (E is invariant under rigid motions).
TEST(Contact, PotentialGradientForcesAreBalanced)
{
  std::mt19937_64 random(11);
  unsigned int    overlapping = 0;
  for (unsigned int trial = 0; trial < 500; ++trial)
    {
      double x[6], y[6];
      random_pair(random, x, y);
      double f[12];
      pair_normal_forces(x, y, f);
      double fx = 0., fy = 0., moment = 0., scale = 0.;
      for (unsigned int k = 0; k < 6; ++k)
        {
          fx += f[2 * k];
          fy += f[2 * k + 1];
          moment += x[k] * f[2 * k + 1] - y[k] * f[2 * k];
          scale += std::hypot(f[2 * k], f[2 * k + 1]);
        }
      if (scale == 0.)
        continue;
      ++overlapping;
      // round-off of terms of the size p L (p = 1, L ~ 1 the triangles'
      // size), however small the overlap's net force
      EXPECT_LT(std::hypot(fx, fy), 1e-12 * (scale + 1.));
      EXPECT_LT(std::abs(moment), 1e-12 * 4. * (scale + 1.));
    }
  EXPECT_GT(overlapping, 100u);
}



// The forces are minus the gradient of the energy E = p int_S (phi_c +
// phi_t) dA that add_target_potential_forces() returns (its two calls, one
// per pair direction): central differences over all twelve coordinates of
// random overlapping pairs. E is C1 (the force is continuous), so the
// differences agree to O(h) even across a change of the overlap's shape.
TEST(Contact, NormalForceIsMinusTheGradientOfTheContactEnergy)
{
  std::mt19937_64 random(5);
  const auto      energy = [](const double *x, const double *y) {
    double f[6];
    return add_target_potential_forces(x, y, x + 3, y + 3, 1., f) +
           add_target_potential_forces(x + 3, y + 3, x, y, 1., f);
  };
  unsigned int overlapping = 0;
  for (unsigned int trial = 0; trial < 300; ++trial)
    {
      double x[6], y[6];
      random_pair(random, x, y);
      if (!(energy(x, y) > 1e-6))
        continue;
      ++overlapping;
      double f[12];
      pair_normal_forces(x, y, f);
      const double h = 1e-7;
      for (unsigned int k = 0; k < 6; ++k)
        for (unsigned int d = 0; d < 2; ++d)
          {
            double      &c     = d == 0 ? x[k] : y[k];
            const double c0    = c;
            c                  = c0 + h;
            const double plus  = energy(x, y);
            c                  = c0 - h;
            const double minus = energy(x, y);
            c                  = c0;
            EXPECT_NEAR(f[2 * k + d], -(plus - minus) / (2. * h), 1e-5)
              << "trial " << trial << ", node " << k << ", direction " << d;
          }
    }
  EXPECT_GT(overlapping, 50u);
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

// The regularised friction law (theory manual 5.5, "Regularised friction"):
// plain Coulomb without a memory slip; otherwise the strength follows mu N
// as exp(-slip / L), stays put at rest, and the rate effect strengthens a
// sudden acceleration by a ln(v2 / v1) and vanishes in steady sliding.
TEST(RegularisedFriction, WithoutMemoryTheLimitIsMuN)
{
  PenaltyCoulombContact law;
  law.friction = 0.6;
  EdgeFriction history;
  EXPECT_EQ(law.friction_limit(123.4, 0.5, 1e-6, history), 123.4);
  EXPECT_EQ(history.strength, 0.);
  EXPECT_EQ(history.remembered_rate, 0.);
}

TEST(RegularisedFriction, StrengthFollowsTheNormalForceOverTheMemorySlip)
{
  PenaltyCoulombContact law;
  law.memory_slip = 1e-7;
  law.rate_effect = 0.01;
  const double v = 0.1, dt = 0.1 * law.memory_slip / v; // L / 10 per step
  EdgeFriction history;
  double       limit = 0.;
  // steady sliding over 30 L from a fresh contact: Coulomb's mu N
  for (unsigned int i = 0; i < 300; ++i)
    limit = law.friction_limit(100., v, dt, history);
  EXPECT_NEAR(limit, 100., 1e-9);
  // mu N doubles: after a slip of exactly L, 200 - 100 / e
  for (unsigned int i = 0; i < 10; ++i)
    limit = law.friction_limit(200., v, dt, history);
  EXPECT_NEAR(limit, 200. - 100. * std::exp(-1.), 1e-9);
  // at rest it keeps its strength, whatever mu N does
  const double strength = history.strength;
  for (unsigned int i = 0; i < 1000; ++i)
    law.friction_limit(50., 0., dt, history);
  EXPECT_EQ(history.strength, strength);
}

TEST(RegularisedFriction, RateEffectStrengthensASuddenAccelerationOnly)
{
  PenaltyCoulombContact law;
  law.memory_slip         = 1e-7;
  law.rate_effect         = 0.01;
  law.reference_slip_rate = 1e-6;
  EdgeFriction history;
  const double v1 = 1e-3, v2 = 1e-2, dt = 1e-5;
  for (unsigned int i = 0; i < 1000; ++i) // 100 L at v1
    law.friction_limit(100., v1, dt, history);
  // ten times faster over a slip of L / 1000: strength up by about
  // a ln(10) (the remembered rate has moved 0.1 % of the way)
  const double limit = law.friction_limit(100., v2, 1e-3 * 1e-7 / v2, history);
  EXPECT_GT(limit, 100. * (1. + 0.99 * 0.01 * std::log(10.)));
  EXPECT_LT(limit, 100. * (1. + 0.01 * std::log(10.)));
  // steady at v2 again after 30 L: Coulomb's
  double steady = 0.;
  for (unsigned int i = 0; i < 3000; ++i)
    steady = law.friction_limit(100., v2, 1e-7 / v2 / 100., history);
  EXPECT_NEAR(steady, 100., 1e-9);
}
