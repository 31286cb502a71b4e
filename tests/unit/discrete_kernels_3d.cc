// Unit tests of the discrete layer's kernels in 3D: the finite-strain
// tetrahedron (element_response<3>) and the cohesive joint on a triangular
// face (face_joint_response()), each against an independent evaluation: a
// strain energy and a joint energy differentiated numerically, Eq. 44 by
// hand, the balance of momentum and angular momentum, and the work to break
// a joint against G times its area.

#include <algorithm>
#include <array>
#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <tmfdem/discrete/cohesive_law.h>
#include <tmfdem/discrete/element_kernel.h>
#include <tmfdem/discrete/heat_kernel.h>
#include <tmfdem/discrete/joint_kernel.h>

using namespace tmfdem::discrete;

namespace
{
  const double E = 10e9, nu = 0.25;
  const double mu     = E / (2 * (1 + nu));
  const double lambda = E * nu / ((1 + nu) * (1 - 2 * nu));

  using Matrix3 = std::array<std::array<double, 3>, 3>;

  double
  det3(const Matrix3 &A)
  {
    return A[0][0] * (A[1][1] * A[2][2] - A[1][2] * A[2][1]) -
           A[0][1] * (A[1][0] * A[2][2] - A[1][2] * A[2][0]) +
           A[0][2] * (A[1][0] * A[2][1] - A[1][1] * A[2][0]);
  }

  /** A^-1 by Cramer's rule. */
  Matrix3
  inverse3(const Matrix3 &A)
  {
    const double d = det3(A);
    Matrix3      G;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        {
          Matrix3 M = A;
          for (int k = 0; k < 3; ++k)
            M[k][i] = k == j ? 1. : 0.;
          G[i][j] = det3(M) / d;
        }
    return G;
  }

  Matrix3
  product(const Matrix3 &A, const Matrix3 &B)
  {
    Matrix3 C{};
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        for (int k = 0; k < 3; ++k)
          C[i][j] += A[i][k] * B[k][j];
    return C;
  }

  /** The basis [x1 - x0, x2 - x0, x3 - x0] (columns) of nodes x[i][a]. */
  Matrix3
  basis(const double (&x)[3][4])
  {
    Matrix3 B;
    for (int i = 0; i < 3; ++i)
      for (int k = 0; k < 3; ++k)
        B[i][k] = x[i][k + 1] - x[i][0];
    return B;
  }

  /** A tetrahedron of size about @p h, positively oriented, randomly
   *  perturbed from the corner one. */
  void
  random_tetrahedron(std::mt19937 &random, const double h, double (&X)[3][4])
  {
    std::uniform_real_distribution<double> sym(-1., 1.);
    const double corner[4][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        X[i][a] = h * (corner[a][i] + 0.2 * sym(random));
  }

  /** A random deformation gradient near the identity, det > 0. */
  Matrix3
  random_deformation(std::mt19937 &random, const double amplitude)
  {
    std::uniform_real_distribution<double> sym(-1., 1.);
    Matrix3                                F;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        F[i][j] = (i == j ? 1. : 0.) + amplitude * sym(random);
    return F;
  }

  /** The rotation by @p angle about the unit axis @p n (Rodrigues). */
  Matrix3
  rotation(const double (&n)[3], const double angle)
  {
    const double c = std::cos(angle), s = std::sin(angle);
    Matrix3      R;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        R[i][j] = (i == j ? c : 0.) + (1 - c) * n[i] * n[j];
    R[0][1] -= s * n[2];
    R[0][2] += s * n[1];
    R[1][0] += s * n[2];
    R[1][2] -= s * n[0];
    R[2][0] -= s * n[1];
    R[2][1] += s * n[0];
    return R;
  }

  /** Nodes x = F X (+ a translation). */
  void
  deform(const Matrix3 &F, const double (&X)[3][4], double (&x)[3][4])
  {
    for (int a = 0; a < 4; ++a)
      for (int i = 0; i < 3; ++i)
        {
          x[i][a] = 0.3 * (i + 1);
          for (int j = 0; j < 3; ++j)
            x[i][a] += F[i][j] * X[j][a];
        }
  }

  /** Row-major inverse of the reference basis. */
  void
  inverse_basis(const double (&X)[3][4], double *ib)
  {
    const Matrix3 G = inverse3(basis(X));
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        ib[3 * i + j] = G[i][j];
  }

  /** element_response<3, double> of nodes @p x, velocities @p v. */
  ElementResponse<3, double>
  tetrahedron_response(const double (&x)[3][4],
                       const double (&v)[3][4],
                       const double *ib,
                       const double  stretch,
                       const double  eta)
  {
    const double *const        nodes[3]      = {x[0], x[1], x[2]};
    const double *const        velocities[3] = {v[0], v[1], v[2]};
    ElementResponse<3, double> r;
    element_response<3, double>(nodes,
                                velocities,
                                ib,
                                1. / stretch,
                                mu,
                                lambda,
                                nullptr,
                                eta,
                                r);
    return r;
  }

  /** The strain energy whose derivative is Eq. 44, per unit volume of the
   *  stress-free configuration [J/m^3], by hand. */
  double
  energy_density(const Matrix3 &Fe)
  {
    const double J  = det3(Fe);
    double       I1 = 0.;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        I1 += Fe[i][j] * Fe[i][j];
    return 0.5 * mu * (I1 - 3.) - mu * std::log(J) +
           0.25 * lambda * (J * J - 1.) - 0.5 * lambda * std::log(J);
  }
} // namespace

// Eq. 44 in 3D by hand: sigma = mu / J (F F^T - I) + lambda / 2 (J - 1/J) I
// for random finite deformations (up to 30 % strain) with and without a
// thermal stretch; the kernel's stress to round-off (1e-12 of E).
TEST(Tetrahedron, StressIsEquation44OnTheElasticPartByHand)
{
  std::mt19937 random(3);
  for (int round = 0; round < 200; ++round)
    {
      double X[3][4], x[3][4], v[3][4] = {}, ib[9];
      random_tetrahedron(random, 0.01, X);
      inverse_basis(X, ib);
      const Matrix3 F = random_deformation(random, 0.3);
      deform(F, X, x);
      const double s = round % 2 ? 1. : 1.02;
      const auto   r = tetrahedron_response(x, v, ib, s, 0.);
      Matrix3      Fe;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          Fe[i][j] = F[i][j] / s;
      const double J = det3(Fe);
      EXPECT_NEAR(r.det, det3(F), 1e-12);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          {
            double b = 0.;
            for (int k = 0; k < 3; ++k)
              b += Fe[i][k] * Fe[j][k];
            const double expected =
              mu / J * (b - (i == j)) + (i == j) * 0.5 * lambda * (J - 1 / J);
            EXPECT_NEAR(r.stress[i][j], expected, 1e-12 * E);
            EXPECT_EQ(r.stress[i][j], r.stress[j][i]);
          }
    }
}

// The nodal forces are minus the gradient of the element's strain energy
// W = V s^3 psi(F / s) (V the reference volume, s the thermal stretch):
// central differences of W by hand against the kernel, 1e-6 of the force
// scale (the differences' truncation is 1e-9 here).
TEST(Tetrahedron, NodalForcesAreMinusTheGradientOfTheStrainEnergy)
{
  std::mt19937 random(5);
  for (int round = 0; round < 50; ++round)
    {
      double       X[3][4], x[3][4], v[3][4] = {}, ib[9];
      const double h = 0.01;
      random_tetrahedron(random, h, X);
      inverse_basis(X, ib);
      deform(random_deformation(random, 0.2), X, x);
      const double  s      = round % 2 ? 1. : 0.97;
      const double  volume = det3(basis(X)) / 6.;
      const auto    r      = tetrahedron_response(x, v, ib, s, 0.);
      const Matrix3 G      = inverse3(basis(X));
      const auto    W      = [&]() {
        Matrix3 Fe = product(basis(x), G);
        for (auto &row : Fe)
          for (auto &f : row)
            f /= s;
        return volume * s * s * s * energy_density(Fe);
      };
      const double scale = E * h * h;
      for (int a = 0; a < 4; ++a)
        for (int i = 0; i < 3; ++i)
          {
            const double step = 1e-7 * h;
            x[i][a] += step;
            const double plus = W();
            x[i][a] -= 2 * step;
            const double minus = W();
            x[i][a] += step;
            EXPECT_NEAR(r.f_elastic[a][i],
                        -(plus - minus) / (2 * step),
                        1e-6 * scale)
              << "node " << a << " component " << i;
          }
    }
}

// Internal forces: they sum to zero and exert no torque (the stress is
// symmetric), elastic and viscous, for random deformations and velocities;
// the sums relative to sum |x| |f| are round-off.
TEST(Tetrahedron, ForcesKeepMomentumAndAngularMomentum)
{
  std::mt19937                           random(7);
  std::uniform_real_distribution<double> sym(-1., 1.);
  for (int round = 0; round < 200; ++round)
    {
      double X[3][4], x[3][4], v[3][4], ib[9];
      random_tetrahedron(random, 0.01, X);
      inverse_basis(X, ib);
      deform(random_deformation(random, 0.3), X, x);
      for (auto &row : v)
        for (auto &c : row)
          c = sym(random);
      const auto r = tetrahedron_response(x, v, ib, 1., 1e3);
      for (const auto *f : {&r.f_elastic, &r.f_viscous})
        {
          double sum[3] = {}, torque[3] = {}, scale = 0.;
          for (int a = 0; a < 4; ++a)
            {
              const double *p = (*f)[a];
              for (int i = 0; i < 3; ++i)
                sum[i] += p[i];
              torque[0] += x[1][a] * p[2] - x[2][a] * p[1];
              torque[1] += x[2][a] * p[0] - x[0][a] * p[2];
              torque[2] += x[0][a] * p[1] - x[1][a] * p[0];
              scale += std::hypot(x[0][a], x[1][a], x[2][a]) *
                       std::hypot(p[0], p[1], p[2]);
            }
          for (int i = 0; i < 3; ++i)
            {
              EXPECT_LT(std::abs(sum[i]), 1e-13 * scale);
              EXPECT_LT(std::abs(torque[i]), 1e-13 * scale);
            }
        }
    }
}

// A rigid rotation of 90 degrees about an oblique axis is stress free, and
// a rigid spin has no viscous stress: both to round-off of E and of eta /
// time. A uniform stretch rate D has the viscous stress 2 eta D.
TEST(Tetrahedron, RigidMotionsAreStressFreeAndStretchRatesViscous)
{
  std::mt19937 random(9);
  double       X[3][4], x[3][4], v[3][4], ib[9];
  random_tetrahedron(random, 0.01, X);
  inverse_basis(X, ib);
  const double  axis[3] = {1 / std::sqrt(3.),
                           1 / std::sqrt(3.),
                           1 / std::sqrt(3.)};
  const Matrix3 R       = rotation(axis, M_PI / 2);
  deform(R, X, x);
  // spin about the same axis at 100 rad/s: v = w x (x - c)
  const double w[3] = {100 * axis[0], 100 * axis[1], 100 * axis[2]};
  for (int a = 0; a < 4; ++a)
    {
      v[0][a] = w[1] * x[2][a] - w[2] * x[1][a];
      v[1][a] = w[2] * x[0][a] - w[0] * x[2][a];
      v[2][a] = w[0] * x[1][a] - w[1] * x[0][a];
    }
  const double eta = 1e3;
  auto         r   = tetrahedron_response(x, v, ib, 1., eta);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      {
        EXPECT_LT(std::abs(r.stress[i][j]), 1e-12 * E);
        EXPECT_LT(std::abs(r.viscous[i][j]), 1e-12 * eta * 100);
      }
  // the stretch rate D = diag(1, -2, 3) + shear 0.5 in xz, on the rotated
  // element (the rate is spatial)
  const double D[3][3] = {{1., 0., 0.5}, {0., -2., 0.}, {0.5, 0., 3.}};
  for (int a = 0; a < 4; ++a)
    for (int i = 0; i < 3; ++i)
      {
        v[i][a] = 0.;
        for (int j = 0; j < 3; ++j)
          v[i][a] += D[i][j] * x[j][a];
      }
  r = tetrahedron_response(x, v, ib, 1., eta);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      EXPECT_NEAR(r.viscous[i][j], 2 * eta * D[i][j], 1e-10 * eta);
}

// The vector batches: element_response<3> on four lanes gives every lane
// bitwise the result of the element-by-element call, with and without the
// anisotropic correction.
TEST(Tetrahedron, LanesMatchOneElementAtATimeBitwise)
{
  using Lanes = LaneVector<4>::type;
  std::mt19937                           random(13);
  std::uniform_real_distribution<double> sym(-1., 1.);
  double X[4][3][4], x[4][3][4], v[4][3][4], ib[4][9];
  Lanes  xl[3][4], vl[3][4], ibl[9];
  for (int l = 0; l < 4; ++l)
    {
      random_tetrahedron(random, 0.01, X[l]);
      inverse_basis(X[l], ib[l]);
      deform(random_deformation(random, 0.3), X[l], x[l]);
      for (int i = 0; i < 3; ++i)
        for (int a = 0; a < 4; ++a)
          {
            v[l][i][a]  = sym(random);
            xl[i][a][l] = x[l][i][a];
            vl[i][a][l] = v[l][i][a];
          }
      for (int k = 0; k < 9; ++k)
        ibl[k][l] = ib[l][k];
    }
  const Lanes inverse_stretch      = {1., 1. / 1.01, 1., 1. / 0.99};
  const Lanes mu_l                 = {mu, mu, mu, mu},
              lambda_l             = {lambda, lambda, lambda, lambda};
  const Lanes        eta_l         = {0., 1e3, 2e3, 0.};
  const Lanes *const nodes[3]      = {xl[0], xl[1], xl[2]};
  const Lanes *const velocities[3] = {vl[0], vl[1], vl[2]};
  // the anisotropic correction of joint compliance compensation: none, or
  // 21 values per lane
  double dC[4][21];
  Lanes  dCl[21];
  for (int k = 0; k < 21; ++k)
    for (int l = 0; l < 4; ++l)
      dCl[k][l] = dC[l][k] = 1e9 * sym(random);
  for (const bool anisotropic : {false, true})
    {
      ElementResponse<3, Lanes> rl;
      element_response<3, Lanes>(nodes,
                                 velocities,
                                 ibl,
                                 inverse_stretch,
                                 mu_l,
                                 lambda_l,
                                 anisotropic ? dCl : nullptr,
                                 eta_l,
                                 rl);
      for (int l = 0; l < 4; ++l)
        {
          const double *const        n[3] = {x[l][0], x[l][1], x[l][2]};
          const double *const        w[3] = {v[l][0], v[l][1], v[l][2]};
          ElementResponse<3, double> r;
          element_response<3, double>(n,
                                      w,
                                      ib[l],
                                      inverse_stretch[l],
                                      mu,
                                      lambda,
                                      anisotropic ? dC[l] : nullptr,
                                      eta_l[l],
                                      r);
          EXPECT_EQ(r.det, rl.det[l]);
          for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
              {
                EXPECT_EQ(r.stress[i][j], rl.stress[i][j][l]);
                EXPECT_EQ(r.viscous[i][j], rl.viscous[i][j][l]);
              }
          for (int a = 0; a < 4; ++a)
            for (int i = 0; i < 3; ++i)
              {
                EXPECT_EQ(r.f_elastic[a][i], rl.f_elastic[a][i][l]);
                EXPECT_EQ(r.f_viscous[a][i], rl.f_viscous[a][i][l]);
              }
        }
    }
}

namespace
{
  /** The constants of a face joint of size @p h: f_t 3, c 8 MPa, phi 30
   *  deg, G_I 120, G_II 600 J/m^2, penalties 10 E. */
  JointConstants
  face_joint_constants(const SofteningLaw law, const double h)
  {
    JointConstants k;
    EXPECT_TRUE(make_joint_constants(3e6,
                                     8e6,
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

  /** Nodes of a face joint: a0, a1, a2 of a triangle in the plane through
   *  @p origin with in-plane edges @p e1, @p e2, and b_k = a_k + gap[k];
   *  x[i][node] in the order a0, a1, a2, b0, b1, b2. */
  void
  place_face_joint(const double (&origin)[3],
                   const double (&e1)[3],
                   const double (&e2)[3],
                   const double (&gap)[3][3],
                   double (&x)[3][6])
  {
    for (int i = 0; i < 3; ++i)
      {
        x[i][0] = origin[i];
        x[i][1] = origin[i] + e1[i];
        x[i][2] = origin[i] + e2[i];
        for (int k = 0; k < 3; ++k)
          x[i][3 + k] = x[i][k] + gap[k][i];
      }
  }

  /** The six node forces f[node][i] of a face joint response. */
  void
  face_node_forces(const FaceJointResponse<double> &r, double (&f)[6][3])
  {
    for (int k = 0; k < 3; ++k)
      for (int i = 0; i < 3; ++i)
        {
          f[k][i]     = r.a[k][i] + r.frame[k][i];
          f[3 + k][i] = -r.a[k][i] + r.frame[k][i];
        }
  }

  template <SofteningLaw law>
  FaceJointResponse<double>
  face_response(const double (&x)[3][6],
                const JointConstants &k,
                double               *damage)
  {
    const double *const       nodes[3] = {x[0], x[1], x[2]};
    FaceJointResponse<double> r;
    face_joint_response<law>(face_joint_frame<double>(nodes), k, damage, r);
    return r;
  }

  /**
   * The work [J] to break a face joint of an oblique triangle (area about
   * 3.5 mm^2) by moving its B face rigidly along @p direction (unit; A held)
   * until every Gauss point is broken, by the trapezoidal rule over 40 000
   * increments.
   */
  template <SofteningLaw law>
  double
  face_work_to_break(const JointConstants &k,
                     const double (&direction)[3],
                     const double (&e1)[3],
                     const double (&e2)[3],
                     const double reach)
  {
    const double origin[3] = {0.01, -0.02, 0.03};
    double       damage[3] = {0., 0., 0.};
    const int    n         = 40000;
    double       work = 0., previous = 0.;
    for (int step = 0; step <= n; ++step)
      {
        const double delta = reach * step / n;
        double       gap[3][3];
        for (int c = 0; c < 3; ++c)
          for (int i = 0; i < 3; ++i)
            gap[c][i] = delta * direction[i];
        double x[3][6];
        place_face_joint(origin, e1, e2, gap, x);
        const auto r = face_response<law>(x, k, damage);
        double     f[6][3];
        face_node_forces(r, f);
        // the force the B face resists the motion with, along it
        double resisting = 0.;
        for (int c = 0; c < 3; ++c)
          for (int i = 0; i < 3; ++i)
            resisting -= f[3 + c][i] * direction[i];
        if (step > 0)
          work += 0.5 * (previous + resisting) * reach / n;
        previous = resisting;
      }
    EXPECT_EQ(damage[0], 1.);
    EXPECT_EQ(damage[1], 1.);
    EXPECT_EQ(damage[2], 1.);
    return work;
  }

  double
  norm(const double (&a)[3])
  {
    return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  }
} // namespace

// Mode I and Mode II on a face: the work to break a joint on an oblique
// triangle, pulled along its normal or slid along an in-plane direction
// that is parallel to no edge, equals G_I (G_II) times the face area, for
// both softening laws: 1e-3 (the trapezoidal rule over the softening
// curve's kink at the peak is below 1e-6; the bound is that of the 2D law's
// test).
TEST(FaceJoint, WorkToBreakIsFractureEnergyTimesAreaInModeIAndII)
{
  const double e1[3] = {2e-3, 0.5e-3, -1e-3}, e2[3] = {0.3e-3, 2.5e-3, 0.8e-3};
  double       c[3] = {e1[1] * e2[2] - e1[2] * e2[1],
                       e1[2] * e2[0] - e1[0] * e2[2],
                       e1[0] * e2[1] - e1[1] * e2[0]};
  const double area = 0.5 * norm(c);
  const double n[3] = {c[0] / (2 * area), c[1] / (2 * area), c[2] / (2 * area)};
  // an in-plane direction: e1 + 0.7 e2 with its normal part removed
  double t[3];
  for (int i = 0; i < 3; ++i)
    t[i] = e1[i] + 0.7 * e2[i];
  const double tn = t[0] * n[0] + t[1] * n[1] + t[2] * n[2];
  for (int i = 0; i < 3; ++i)
    t[i] -= tn * n[i];
  const double tl = norm(t);
  for (auto &ti : t)
    ti /= tl;
  const double h = 0.002;
  for (const auto law : {SofteningLaw::munjiza, SofteningLaw::linear})
    {
      const JointConstants k = face_joint_constants(law, h);
      const double         reach_I =
        1.2 * (2 * 3e6 / k.normal_stiffness + k.softening_width_I);
      const double reach_II =
        1.2 * (2 * 8e6 / k.tangential_stiffness + k.softening_width_II);
      const double wI =
        law == SofteningLaw::linear ?
          face_work_to_break<SofteningLaw::linear>(k, n, e1, e2, reach_I) :
          face_work_to_break<SofteningLaw::munjiza>(k, n, e1, e2, reach_I);
      const double wII =
        law == SofteningLaw::linear ?
          face_work_to_break<SofteningLaw::linear>(k, t, e1, e2, reach_II) :
          face_work_to_break<SofteningLaw::munjiza>(k, t, e1, e2, reach_II);
      EXPECT_NEAR(wI / (120. * area), 1., 1e-3);
      EXPECT_NEAR(wII / (600. * area), 1., 1e-3);
    }
}

// A face joint's forces are internal forces: zero sum and zero torque
// whatever its state. Random oblique faces with random gaps (opening,
// closing, shear in any direction, up to 40 um on a 2 mm face: damaged and
// broken Gauss points too); the torque about the origin relative to
// sum |x_i| |F_i| is round-off. The frame forces matter: without them the
// torque of a sheared, open joint is 1e-9 to 1e-2 of that scale.
TEST(FaceJoint, ForcesKeepMomentumAndAngularMomentum)
{
  std::mt19937                           random(17);
  std::uniform_real_distribution<double> sym(-1., 1.), unit(0., 1.);
  const double                           h             = 0.002;
  unsigned int                           frame_matters = 0;
  for (const auto law : {SofteningLaw::linear, SofteningLaw::munjiza})
    for (int round = 0; round < 2000; ++round)
      {
        const JointConstants k = face_joint_constants(law, h);
        double               origin[3], e1[3], e2[3], gap[3][3];
        for (int i = 0; i < 3; ++i)
          {
            origin[i] = 0.05 * sym(random);
            e1[i]     = h * sym(random);
            e2[i]     = h * sym(random);
          }
        const double size = std::pow(10., -9. + 4.3 * unit(random));
        for (auto &g : gap)
          for (auto &c : g)
            c = size * sym(random);
        double x[3][6];
        place_face_joint(origin, e1, e2, gap, x);
        double damage[3] = {0., 0., 0.};
        if (round % 3 == 0)
          for (auto &d : damage)
            d = 0.9 * unit(random);
        const auto r = law == SofteningLaw::linear ?
                         face_response<SofteningLaw::linear>(x, k, damage) :
                         face_response<SofteningLaw::munjiza>(x, k, damage);
        double     f[6][3];
        face_node_forces(r, f);
        double sum[3] = {}, torque[3] = {}, torque_without[3] = {}, scale = 0.;
        for (int p = 0; p < 6; ++p)
          {
            const int     side = p < 3 ? 1 : -1;
            const double *fa   = r.a[p % 3];
            double        g[3];
            for (int i = 0; i < 3; ++i)
              {
                sum[i] += f[p][i];
                g[i] = side * fa[i];
              }
            torque[0] += x[1][p] * f[p][2] - x[2][p] * f[p][1];
            torque[1] += x[2][p] * f[p][0] - x[0][p] * f[p][2];
            torque[2] += x[0][p] * f[p][1] - x[1][p] * f[p][0];
            torque_without[0] += x[1][p] * g[2] - x[2][p] * g[1];
            torque_without[1] += x[2][p] * g[0] - x[0][p] * g[2];
            torque_without[2] += x[0][p] * g[1] - x[1][p] * g[0];
            scale += std::hypot(x[0][p], x[1][p], x[2][p]) *
                     std::hypot(f[p][0], f[p][1], f[p][2]);
          }
        if (scale == 0.)
          continue;
        for (int i = 0; i < 3; ++i)
          {
            EXPECT_LT(std::abs(sum[i]), 1e-13 * scale);
            EXPECT_LT(std::abs(torque[i]), 1e-13 * scale)
              << "round " << round << " gap size " << size;
          }
        if (std::hypot(torque_without[0],
                       torque_without[1],
                       torque_without[2]) > 1e-9 * scale)
          ++frame_matters;
      }
  // the test has teeth: most states need the frame force
  EXPECT_GT(frame_matters, 1000u);
}

namespace
{
  /** The energy stored in an undamaged face joint below its peaks with
   *  the area held at @p area [J]: the three Gauss points' stored energy
   *  (stored_joint_energy() of o and |s|), each over a third of it. */
  double
  stored_face_energy(const double (&x)[3][6],
                     const JointConstants &k,
                     const double          area)
  {
    const double *const nodes[3] = {x[0], x[1], x[2]};
    const auto          g        = face_joint_frame<double>(nodes);
    double              energy   = 0.;
    for (int q = 0; q < 3; ++q)
      {
        double d[3];
        for (int i = 0; i < 3; ++i)
          d[i] = face_joint_gauss_points[q][0] * g.d[0][i] +
                 face_joint_gauss_points[q][1] * g.d[1][i] +
                 face_joint_gauss_points[q][2] * g.d[2][i];
        const double o = d[0] * g.n[0] + d[1] * g.n[1] + d[2] * g.n[2];
        double       s[3];
        for (int i = 0; i < 3; ++i)
          s[i] = d[i] - o * g.n[i];
        energy += area / 3. * stored_joint_energy(o, norm(s), k);
      }
    return energy;
  }
} // namespace

// Below the peak, in tension, a face joint is elastic: its forces are
// minus the gradient of its stored energy (the area held, as the kernel
// weighs with it), the normal's turn included. Random oblique faces, each
// node pair opened by 0.1 to 0.8 of the peak opening and slid within 0.55
// of the peak slip in a random in-plane direction: central differences
// (step 1e-4 of the peak opening) against the kernel to 1e-7 of the largest
// force. The frame force exceeds that bound in most of them, so that
// without it the test fails.
TEST(FaceJoint, ForcesAreMinusTheGradientOfTheStoredEnergyBelowThePeak)
{
  std::mt19937                           random(19);
  std::uniform_real_distribution<double> sym(-1., 1.), unit(0., 1.);
  const double                           h = 0.002;
  const JointConstants k      = face_joint_constants(SofteningLaw::munjiza, h);
  const double         o_peak = 2 * k.tensile_strength / k.normal_stiffness;
  const double         s_peak = 2 * k.cohesion / k.tangential_stiffness;
  unsigned int         compared = 0, turning = 0;
  for (int round = 0; round < 200; ++round)
    {
      double origin[3], e1[3], e2[3], gap[3][3];
      for (int i = 0; i < 3; ++i)
        {
          origin[i] = 1e-3 * sym(random);
          e1[i]     = h * sym(random);
          e2[i]     = h * sym(random);
        }
      // the face's normal and an in-plane basis t1 = e1 / |e1|, t2 = n x t1
      double       c[3] = {e1[1] * e2[2] - e1[2] * e2[1],
                           e1[2] * e2[0] - e1[0] * e2[2],
                           e1[0] * e2[1] - e1[1] * e2[0]};
      const double cl   = norm(c);
      if (cl < 0.1 * h * h)
        continue; // a sliver
      double n[3], t1[3], t2[3];
      for (int i = 0; i < 3; ++i)
        {
          n[i]  = c[i] / cl;
          t1[i] = e1[i] / norm(e1);
        }
      t2[0] = n[1] * t1[2] - n[2] * t1[1];
      t2[1] = n[2] * t1[0] - n[0] * t1[2];
      t2[2] = n[0] * t1[1] - n[1] * t1[0];
      for (auto &g : gap)
        {
          const double o = o_peak * (0.1 + 0.7 * unit(random));
          const double a = 6.283185307179586 * unit(random);
          const double s = 0.55 * s_peak * unit(random);
          for (int i = 0; i < 3; ++i)
            g[i] = o * n[i] + s * (std::cos(a) * t1[i] + std::sin(a) * t2[i]);
        }
      double x[3][6];
      place_face_joint(origin, e1, e2, gap, x);
      double     damage[3] = {0., 0., 0.};
      const auto r         = face_response<SofteningLaw::munjiza>(x, k, damage);
      ASSERT_FALSE(r.beyond_peak);
      double f[6][3];
      face_node_forces(r, f);
      const double *const nodes[3] = {x[0], x[1], x[2]};
      const double        area     = face_joint_frame<double>(nodes).area;
      double              largest = 0., largest_frame = 0.;
      for (int p = 0; p < 6; ++p)
        for (int i = 0; i < 3; ++i)
          {
            largest = std::max(largest, std::abs(f[p][i]));
            largest_frame =
              std::max(largest_frame, std::abs(r.frame[p % 3][i]));
          }
      turning += largest_frame > 1e-6 * largest;
      for (int p = 0; p < 6; ++p)
        for (int i = 0; i < 3; ++i)
          {
            const double step = 1e-4 * o_peak;
            x[i][p] += step;
            const double plus = stored_face_energy(x, k, area);
            x[i][p] -= 2 * step;
            const double minus = stored_face_energy(x, k, area);
            x[i][p] += step;
            EXPECT_NEAR(f[p][i], -(plus - minus) / (2 * step), 1e-7 * largest)
              << "round " << round << " node " << p << " component " << i;
            ++compared;
          }
    }
  EXPECT_GT(compared, 100u * 18u);
  EXPECT_GT(turning, 100u);
}

// The vector batches: face_joint_response() on four lanes gives every lane
// bitwise the forces and damage of the joint-by-joint call, past the peak
// too.
TEST(FaceJoint, LanesMatchOneJointAtATimeBitwise)
{
  using Lanes = LaneVector<4>::type;
  std::mt19937                           random(23);
  std::uniform_real_distribution<double> sym(-1., 1.);
  const double                           h = 0.002;
  JointConstants                         k[4];
  double                                 x[4][3][6];
  Lanes                                  xl[3][6];
  double                                 damage[4][3];
  Lanes                                  damage_l[3];
  for (int l = 0; l < 4; ++l)
    {
      k[l] = face_joint_constants(SofteningLaw::munjiza, h * (1 + 0.1 * l));
      double origin[3], e1[3], e2[3], gap[3][3];
      for (int i = 0; i < 3; ++i)
        {
          origin[i] = 0.01 * sym(random);
          e1[i]     = h * sym(random);
          e2[i]     = h * sym(random);
        }
      for (auto &g : gap)
        for (auto &c : g)
          c = std::pow(10., -7. + l) * 1e-1 * sym(random);
      place_face_joint(origin, e1, e2, gap, x[l]);
      for (int i = 0; i < 3; ++i)
        for (int p = 0; p < 6; ++p)
          xl[i][p][l] = x[l][i][p];
      for (int q = 0; q < 3; ++q)
        damage_l[q][l] = damage[l][q] = l == 2 ? 0.3 : 0.;
    }
  const Lanes *const              nodes[3] = {xl[0], xl[1], xl[2]};
  const JointConstantLanes<Lanes> kl(k);
  FaceJointResponse<Lanes>        rl;
  face_joint_response<SofteningLaw::munjiza>(face_joint_frame<Lanes>(nodes),
                                             kl,
                                             damage_l,
                                             rl);
  for (int l = 0; l < 4; ++l)
    {
      const auto r =
        face_response<SofteningLaw::munjiza>(x[l], k[l], damage[l]);
      for (int a = 0; a < 3; ++a)
        for (int i = 0; i < 3; ++i)
          {
            EXPECT_EQ(r.a[a][i], rl.a[a][i][l]);
            EXPECT_EQ(r.frame[a][i], rl.frame[a][i][l]);
          }
      for (int q = 0; q < 3; ++q)
        EXPECT_EQ(damage[l][q], damage_l[q][l]);
      EXPECT_EQ(r.d_opening, rl.d_opening[l]);
      EXPECT_EQ(r.d_slip, rl.d_slip[l]);
    }
}

// Discrete heat/Conduction matrix = M-matrix: an obtuse tetrahedron's
// positive couplings go onto the diagonal; row sums, symmetry, the
// Gershgorin row bound and positive semi-definiteness are kept, the
// quadratic form only grows, and a tetrahedron without obtuse angles keeps
// its matrix bit for bit.
TEST(ConductionMatrix, MMatrixMovesPositiveCouplingsOntoTheDiagonal)
{
  const auto matrix = [](const double(&corners)[4][3], double(&K)[4][4]) {
    double x[3][4];
    for (unsigned int a = 0; a < 4; ++a)
      for (unsigned int i = 0; i < 3; ++i)
        x[i][a] = corners[a][i];
    const double *const X[3] = {x[0], x[1], x[2]};
    conductivity_matrix<3, double>(X, 2.5, K);
  };
  // a flat tetrahedron: node 3 just above the middle of the face 0-1-2,
  // whose faces meet at obtuse angles
  const double obtuse[4][3] = {{0., 0., 0.},
                               {1., 0., 0.},
                               {0., 1., 0.},
                               {0.3, 0.3, 0.05}};
  double       K[4][4], M[4][4];
  matrix(obtuse, K);
  std::copy(&K[0][0], &K[0][0] + 16, &M[0][0]);
  make_conduction_m_matrix(M);
  unsigned int n_positive = 0;
  for (unsigned int a = 0; a < 4; ++a)
    for (unsigned int b = 0; b < 4; ++b)
      if (a != b)
        n_positive += K[a][b] > 0.;
  ASSERT_GT(n_positive, 0u) << "the test tetrahedron has no obtuse angle";
  const double scale = K[0][0] + K[1][1] + K[2][2] + K[3][3];
  for (unsigned int a = 0; a < 4; ++a)
    {
      double row = 0., row_abs = 0., row_abs_k = 0.;
      for (unsigned int b = 0; b < 4; ++b)
        {
          row += M[a][b];
          row_abs += std::abs(M[a][b]);
          row_abs_k += std::abs(K[a][b]);
          EXPECT_EQ(M[a][b], M[b][a]);
          if (a != b)
            {
              EXPECT_LE(M[a][b], 0.);
              EXPECT_EQ(M[a][b], std::min(K[a][b], 0.));
            }
        }
      EXPECT_NEAR(row, 0., 1e-14 * scale) << "row " << a;
      EXPECT_NEAR(row_abs, row_abs_k, 1e-14 * scale) << "row " << a;
    }
  // x^T M x = x^T K x + sum over the moved pairs of K_ab (x_a - x_b)^2 >= it
  std::mt19937                           engine(3);
  std::uniform_real_distribution<double> u(-1., 1.);
  for (unsigned int trial = 0; trial < 100; ++trial)
    {
      double x[4], qK = 0., qM = 0.;
      for (double &v : x)
        v = u(engine);
      for (unsigned int a = 0; a < 4; ++a)
        for (unsigned int b = 0; b < 4; ++b)
          {
            qK += x[a] * K[a][b] * x[b];
            qM += x[a] * M[a][b] * x[b];
          }
      EXPECT_GE(qK, -1e-14 * scale);
      EXPECT_GE(qM, qK - 1e-14 * scale);
    }
  // the corner of a cube: every angle between faces at most 90 degrees
  const double right[4][3] = {{0., 0., 0.},
                              {1., 0., 0.},
                              {0., 1., 0.},
                              {0., 0., 1.}};
  matrix(right, K);
  std::copy(&K[0][0], &K[0][0] + 16, &M[0][0]);
  make_conduction_m_matrix(M);
  for (unsigned int a = 0; a < 4; ++a)
    for (unsigned int b = 0; b < 4; ++b)
      EXPECT_EQ(M[a][b], K[a][b]);
}
