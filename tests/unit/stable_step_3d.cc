// Unit tests of the explicit stable step of a tetrahedron (stable_step.h,
// dim = 3) against the exact critical step of small assemblies: one free
// tetrahedron, two and four tetrahedra joined by cohesive face joints, at
// joint penalties 10 E ... 1000 E and damping ratios 0 ... 2. Everything
// the bound is compared with is assembled here independently of it: K_e
// and C_e from the shape-function gradients of the inverse of [1 x y z] (the
// Lame form V (lambda g_a g_b^T + mu (g_a . g_b I + g_b g_a^T)) and the
// viscous V eta (g_a . g_b I + g_b g_a^T)), the joints from their energy
// 1/2 int (k_n o^2 + k_t |s|^2) dA with the three-point rule of the face
// joint force, the lumped mass rho V / 4, the modes from Eigen's
// eigensolvers. The exact step of an undamped assembly is 2 / omega_max
// (M^-1 K); with damping it is the largest dt at which the spectral radius
// of the scheme's one-step amplification matrix stays 1:
//   v+ = v - dt M^-1 (K x + C v),  x+ = x + dt v+.
// Also: the 2D instantiation gives bitwise the numbers of the triangle code
// it replaced (values recorded from that code).

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <gtest/gtest.h>
#include <limits>
#include <tmfdem/discrete/stable_step.h>
#include <vector>

using namespace tmfdem::discrete;

namespace
{
  const double E = 10e9, nu = 0.25, rho = 2700.;
  const double h = 0.01; // element size [m]

  LameConstants
  lame_3d()
  {
    LameConstants l;
    l.mu     = E / (2. * (1. + nu));
    l.lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
    return l;
  }

  using Vec3 = Eigen::Vector3d;
  using Tet  = std::array<Vec3, 4>;

  struct FaceJoint
  {
    // element and local face (the face opposite that node) of side A and B
    unsigned int ea, fa, eb, fb;
  };

  struct Assembly
  {
    std::vector<Tet>       tets;
    std::vector<FaceJoint> joints;
  };

  double
  volume(const Tet &t)
  {
    return (t[1] - t[0]).dot((t[2] - t[0]).cross(t[3] - t[0])) / 6.;
  }

  // grad N_a (columns) from the inverse of the rows [1 x_a y_a z_a]
  Eigen::Matrix<double, 3, 4>
  gradients(const Tet &t)
  {
    Eigen::Matrix4d P;
    for (unsigned int a = 0; a < 4; ++a)
      P.row(a) << 1., t[a](0), t[a](1), t[a](2);
    const Eigen::Matrix4d coefficients = P.inverse();
    return coefficients.bottomRows<3>();
  }

  // K_e and C_e (eta = 1) in the Lame form
  void
  reference_matrices(const Tet           &t,
                     const LameConstants &l,
                     Eigen::MatrixXd     &K,
                     Eigen::MatrixXd     &C)
  {
    const auto   g = gradients(t);
    const double V = std::abs(volume(t));
    K.setZero(12, 12);
    C.setZero(12, 12);
    for (unsigned int a = 0; a < 4; ++a)
      for (unsigned int b = 0; b < 4; ++b)
        {
          const Vec3   ga = g.col(a), gb = g.col(b);
          const double dot = ga.dot(gb);
          for (unsigned int i = 0; i < 3; ++i)
            for (unsigned int j = 0; j < 3; ++j)
              {
                const double sym = (i == j ? dot : 0.) + ga(j) * gb(i);
                K(3 * a + i, 3 * b + j) =
                  V * (l.lambda * ga(i) * gb(j) + l.mu * sym);
                C(3 * a + i, 3 * b + j) = V * sym;
              }
        }
  }

  struct Modes
  {
    double          omega2; // largest eigenvalue of M^-1 K [1/s^2]
    Eigen::MatrixXd top;    // its eigenvectors (columns, M-orthonormal)
  };

  // the highest modes of K phi = omega^2 M phi, M = diag(mass)
  Modes
  highest_modes(const Eigen::MatrixXd &K, const Eigen::VectorXd &mass)
  {
    const Eigen::VectorXd s = mass.cwiseSqrt().cwiseInverse();
    const Eigen::MatrixXd A = s.asDiagonal() * K * s.asDiagonal();
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 *
                                                       (A + A.transpose()));
    const Eigen::VectorXd                         &w   = eig.eigenvalues();
    const unsigned int                             n   = w.size();
    const double                                   top = w(n - 1);
    unsigned int                                   m   = 1;
    while (m < n && w(n - 1 - m) >= top * (1. - 1e-8))
      ++m;
    return {top, s.asDiagonal() * eig.eigenvectors().rightCols(m)};
  }

  // damping ratio of the highest modes per unit viscosity:
  // phi^T C_1 phi / (2 omega) for M-orthonormal phi (= phi^T C_1 phi /
  // (2 m omega) for phi normalised to 1), averaged over repeated ones
  double
  reference_damping_per_viscosity(const Eigen::MatrixXd &K,
                                  const Eigen::MatrixXd &C1,
                                  const Eigen::VectorXd &mass)
  {
    const Modes m = highest_modes(K, mass);
    double      s = 0.;
    for (int c = 0; c < m.top.cols(); ++c)
      s += m.top.col(c).dot(C1 * m.top.col(c));
    return s / m.top.cols() / (2. * std::sqrt(m.omega2));
  }

  struct System
  {
    Eigen::MatrixXd                   K, C;
    Eigen::VectorXd                   mass;
    std::vector<TetrahedronStepInput> inputs;
  };

  // the assembly's K, C, M and the bound's inputs; viscosity per element
  // for the damping ratio zeta of its highest free mode (the reference's
  // modes); joint stiffness k_n = penalty E / h, k_t = ratio k_n
  System
  assemble(const Assembly &a,
           const double    penalty,
           const double    tangential_ratio,
           const double    zeta)
  {
    const LameConstants lame = lame_3d();
    const unsigned int  n_el = a.tets.size(), N = 12 * n_el;
    System              s;
    s.K.setZero(N, N);
    s.C.setZero(N, N);
    s.mass.setZero(N);
    s.inputs.resize(n_el);
    for (unsigned int e = 0; e < n_el; ++e)
      {
        const Tet      &t = a.tets[e];
        Eigen::MatrixXd Ke, C1;
        reference_matrices(t, lame, Ke, C1);
        const double    m = rho * volume(t) / 4.;
        Eigen::VectorXd me(12);
        me.setConstant(m);
        const double eta =
          zeta > 0. ? zeta / reference_damping_per_viscosity(Ke, C1, me) : 0.;
        s.K.block(12 * e, 12 * e, 12, 12) = Ke;
        s.C.block(12 * e, 12 * e, 12, 12) = eta * C1;
        s.mass.segment(12 * e, 12).setConstant(m);
        TetrahedronStepInput &in = s.inputs[e];
        for (unsigned int k = 0; k < 4; ++k)
          {
            in.x[k] = t[k](0);
            in.y[k] = t[k](1);
            in.z[k] = t[k](2);
          }
        in.lame      = lame;
        in.viscosity = eta;
        in.node_mass = m;
      }
    const double w[3][3] = {{2. / 3., 1. / 6., 1. / 6.},
                            {1. / 6., 2. / 3., 1. / 6.},
                            {1. / 6., 1. / 6., 2. / 3.}};
    for (const FaceJoint &j : a.joints)
      {
        const Tet &A = a.tets[j.ea], &B = a.tets[j.eb];
        // A's face nodes and the B nodes at the same places
        unsigned int na[3], nb[3];
        for (unsigned int k = 0; k < 3; ++k)
          {
            na[k] = (j.fa + 1 + k) % 4;
            nb[k] = 4;
            for (unsigned int b = 0; b < 4; ++b)
              if (b != j.fb && (B[b] - A[na[k]]).norm() < 1e-12 * h)
                nb[k] = b;
            if (nb[k] == 4)
              {
                ADD_FAILURE() << "the faces of a joint do not match";
                return s;
              }
          }
        const Vec3   c    = (A[na[1]] - A[na[0]]).cross(A[na[2]] - A[na[0]]);
        const double area = 0.5 * c.norm();
        const Vec3   n    = c.normalized();
        // an orthonormal basis (t1, t2) of the face plane
        const Vec3   t1  = (A[na[1]] - A[na[0]]).normalized();
        const Vec3   t2  = n.cross(t1);
        const double k_n = penalty * E / h, k_t = tangential_ratio * k_n;
        for (unsigned int q = 0; q < 3; ++q)
          for (unsigned int dir = 0; dir < 3; ++dir)
            {
              const Vec3     &d = dir == 0 ? n : dir == 1 ? t1 : t2;
              const double    k = dir == 0 ? k_n : k_t;
              Eigen::VectorXd v = Eigen::VectorXd::Zero(N);
              for (unsigned int p = 0; p < 3; ++p)
                for (unsigned int i = 0; i < 3; ++i)
                  {
                    v(12 * j.eb + 3 * nb[p] + i) += w[q][p] * d(i);
                    v(12 * j.ea + 3 * na[p] + i) -= w[q][p] * d(i);
                  }
              s.K += (area / 3.) * k * v * v.transpose();
            }
        s.inputs[j.ea].face_joint_normal_stiffness[j.fa]     = k_n;
        s.inputs[j.ea].face_joint_tangential_stiffness[j.fa] = k_t;
        s.inputs[j.eb].face_joint_normal_stiffness[j.fb]     = k_n;
        s.inputs[j.eb].face_joint_tangential_stiffness[j.fb] = k_t;
      }
    return s;
  }

  double
  bound(const System &s)
  {
    double dt = std::numeric_limits<double>::infinity();
    for (const auto &in : s.inputs)
      dt = std::min(dt, critical_time_step(in));
    return dt;
  }

  // spectral radius of the scheme's one-step map, in the variables
  // (x, w = dt v) (a similarity transform of (x, v): O(1) entries):
  //   w+ = (I - dt M^-1 C) w - dt^2 M^-1 K x,  x+ = x + w+
  double
  spectral_radius(const System &s, const double dt)
  {
    const unsigned int    N     = s.mass.size();
    const Eigen::VectorXd inv_m = s.mass.cwiseInverse();
    const Eigen::MatrixXd Bw =
      Eigen::MatrixXd::Identity(N, N) - dt * inv_m.asDiagonal() * s.C;
    const Eigen::MatrixXd Bx = -dt * dt * inv_m.asDiagonal() * s.K;
    Eigen::MatrixXd       A(2 * N, 2 * N);
    A.topLeftCorner(N, N)     = Bw;
    A.topRightCorner(N, N)    = Bx;
    A.bottomLeftCorner(N, N)  = Bw;
    A.bottomRightCorner(N, N) = Eigen::MatrixXd::Identity(N, N) + Bx;
    Eigen::EigenSolver<Eigen::MatrixXd> eig(A, false);
    return eig.eigenvalues().cwiseAbs().maxCoeff();
  }

  const double radius_tolerance = 1e-6;

  // the largest dt with spectral radius <= 1 + tolerance near @p guess:
  // scan by 1 % up from it (or halve down where it is unstable), then
  // bisect the crossing to 1e-8
  double
  exact_damped_step(const System &s, const double guess)
  {
    const auto stable = [&](const double dt) {
      return spectral_radius(s, dt) <= 1. + radius_tolerance;
    };
    double lo = guess, hi = guess;
    if (stable(guess))
      do
        {
          lo = hi;
          hi *= 1.01;
      } while (stable(hi) && hi < 10. * guess);
    else
      do
        {
          hi = lo;
          lo *= 0.5;
      } while (!stable(lo) && lo > 1e-3 * guess);
    for (unsigned int i = 0; i < 20; ++i)
      {
        const double mid        = 0.5 * (lo + hi);
        (stable(mid) ? lo : hi) = mid;
      }
    return lo;
  }

  // the exact critical step of an undamped assembly, 2 / omega_max
  double
  exact_undamped_step(const System &s)
  {
    return 2. / std::sqrt(highest_modes(s.K, s.mass).omega2);
  }

  Tet
  tet(const Vec3 &a, const Vec3 &b, const Vec3 &c, const Vec3 &d)
  {
    return {{a, b, c, d}};
  }

  // the regular tetrahedron of edge h, positively oriented
  Tet
  regular()
  {
    return tet(Vec3(0., 0., 0.),
               Vec3(h, 0., 0.),
               Vec3(0.5 * h, std::sqrt(3.) / 2. * h, 0.),
               Vec3(0.5 * h, std::sqrt(3.) / 6. * h, std::sqrt(2. / 3.) * h));
  }

  Tet
  corner()
  {
    return tet(Vec3(0., 0., 0.),
               Vec3(h, 0., 0.),
               Vec3(0., h, 0.),
               Vec3(0., 0., h));
  }

  Tet
  skewed()
  {
    return tet(Vec3(0., 0., 0.),
               Vec3(h, 0.1 * h, 0.),
               Vec3(0.8 * h, 0.3 * h, 0.05 * h),
               Vec3(0.3 * h, 0.2 * h, 0.4 * h));
  }

  // two tetrahedra on the equilateral face (p0, p1, p2), apexes above and
  // below it (above the centroid: the regular triangular bipyramid; else
  // shifted); the face is face 3 of both
  Assembly
  two_tetrahedra(const bool shifted)
  {
    const Vec3 p0(0., 0., 0.), p1(h, 0., 0.),
      p2(0.5 * h, std::sqrt(3.) / 2. * h, 0.);
    const Vec3   centroid = (p0 + p1 + p2) / 3.;
    const double height   = std::sqrt(2. / 3.) * h;
    const Vec3   up       = centroid + Vec3(shifted ? 0.3 * h : 0., 0., height);
    const Vec3   down =
      centroid +
      Vec3(0., shifted ? -0.2 * h : 0., -(shifted ? 0.6 : 1.) * height);
    Assembly a;
    a.tets.push_back(tet(p0, p1, p2, up));
    a.tets.push_back(tet(p0, p2, p1, down));
    a.joints.push_back({0, 3, 1, 3});
    return a;
  }

  // the regular octahedron of edge sqrt(2) h split around its axis S N into
  // four tetrahedra (S, N, e_k, e_k+1), e_k on the equator: element k's face
  // 2 (S, N, e_k+1) is element k+1's face 3; the joints form one cycle of
  // four, so alternate elements can move every joined face against its
  // neighbour (the 3D counterpart of the four triangles of the 2D test)
  Assembly
  four_around_an_edge()
  {
    const Vec3 N(0., 0., h), S(0., 0., -h);
    Vec3       e[4];
    for (unsigned int k = 0; k < 4; ++k)
      e[k] = Vec3(h * std::cos(k * M_PI / 2.), h * std::sin(k * M_PI / 2.), 0.);
    Assembly a;
    for (unsigned int k = 0; k < 4; ++k)
      {
        a.tets.push_back(tet(S, N, e[k], e[(k + 1) % 4]));
        EXPECT_GT(volume(a.tets.back()), 0.);
        a.joints.push_back({k, 2, (k + 1) % 4, 3});
      }
    return a;
  }

  // the regular tetrahedron split at its centroid into four tetrahedra,
  // each joined to the three others (six face joints); element k is the
  // regular one's face k (opposite corner k) and the centroid as node k
  Assembly
  four_tetrahedra()
  {
    const Tet  r = regular();
    const Vec3 g = (r[0] + r[1] + r[2] + r[3]) / 4.;
    Assembly   a;
    for (unsigned int k = 0; k < 4; ++k)
      {
        Tet t = r;
        t[k]  = g;
        EXPECT_GT(volume(t), 0.);
        a.tets.push_back(t);
      }
    // elements k and l share the centroid and the corners other than k, l:
    // the face of k opposite corner l, the face of l opposite corner k
    for (unsigned int k = 0; k < 4; ++k)
      for (unsigned int l = k + 1; l < 4; ++l)
        a.joints.push_back({k, l, l, k});
    return a;
  }

  struct Comparison
  {
    double computed, exact;
  };

  Comparison
  compare(const Assembly &a,
          const double    penalty,
          const double    ratio,
          const double    zeta)
  {
    const System s        = assemble(a, penalty, ratio, zeta);
    const double computed = bound(s);
    const double exact =
      zeta > 0. ? exact_damped_step(s, computed) : exact_undamped_step(s);
    return {computed, exact};
  }
} // namespace

TEST(StableStep3D, ElementMatricesAreTheLameForm)
{
  // K_e, C_e of element_matrices() against the Lame form above
  const LameConstants lame = lame_3d();
  for (const Tet &t : {regular(), corner(), skewed()})
    {
      std::array<double, 4> x, y, z;
      for (unsigned int k = 0; k < 4; ++k)
        {
          x[k] = t[k](0);
          y[k] = t[k](1);
          z[k] = t[k](2);
        }
      Matrix12 K, C;
      element_matrices(x, y, z, lame, K, C);
      Eigen::MatrixXd Kr, Cr;
      reference_matrices(t, lame, Kr, Cr);
      const double k_scale = Kr.cwiseAbs().maxCoeff();
      const double c_scale = Cr.cwiseAbs().maxCoeff();
      for (unsigned int r = 0; r < 12; ++r)
        for (unsigned int c = 0; c < 12; ++c)
          {
            EXPECT_NEAR(K[r][c], Kr(r, c), 1e-12 * k_scale);
            EXPECT_NEAR(C[r][c], Cr(r, c), 1e-12 * c_scale);
          }
    }
}

TEST(StableStep3D, OneTetrahedron)
{
  // undamped: 2 / omega_max of M^-1 K, to the bisection's 1e-4 below it
  for (const Tet &t : {regular(), corner(), skewed()})
    {
      const System s        = assemble({{t}, {}}, 0., 1., 0.);
      const double computed = bound(s);
      const double exact    = exact_undamped_step(s);
      std::printf("one tetrahedron, zeta 0: computed %.6e s, 2 / omega_max "
                  "%.6e s, ratio %.6f\n",
                  computed,
                  exact,
                  computed / exact);
      EXPECT_LE(computed, exact * (1. + 1e-12));
      EXPECT_GE(computed, exact * (1. - 1.0001e-4));
      // the scheme itself: stable just below, unstable just above
      EXPECT_LE(spectral_radius(s, 0.999 * exact), 1. + radius_tolerance);
      EXPECT_GT(spectral_radius(s, 1.001 * exact), 1. + radius_tolerance);
    }
}

TEST(StableStep3D, OneDampedTetrahedron)
{
  // The regular tetrahedron's highest mode is also a mode of C (its
  // symmetry), so the damped scheme's critical step is exactly
  // omega dt = 2 (sqrt(1 + zeta^2) - zeta) for the highest mode: checked
  // on the assembled update (spectral radius just below and just above),
  // and the bound reaches it to the bisection's 1e-4.
  for (const double zeta : {0.25, 0.5, 1., 2.})
    {
      const System s     = assemble({{regular()}, {}}, 0., 1., zeta);
      const Modes  modes = highest_modes(s.K, s.mass);
      const double omega = std::sqrt(modes.omega2);
      // phi^T C phi / (2 omega) of the M-orthonormal modes is zeta, and
      // C phi lies in the span of M phi (a mode of C as well)
      for (int c = 0; c < modes.top.cols(); ++c)
        {
          const Eigen::VectorXd phi  = modes.top.col(c);
          const Eigen::VectorXd Cphi = s.C * phi;
          const double          z    = phi.dot(Cphi) / (2. * omega);
          EXPECT_NEAR(z, zeta, 1e-9 * zeta);
          EXPECT_NEAR(Cphi.norm(),
                      (s.mass.asDiagonal() * phi * (2. * z * omega)).norm(),
                      1e-8 * Cphi.norm());
        }
      const double formula  = 2. * (std::sqrt(1. + zeta * zeta) - zeta) / omega;
      const double computed = bound(s);
      const double below    = spectral_radius(s, 0.999 * formula);
      const double above    = spectral_radius(s, 1.001 * formula);
      std::printf("regular tetrahedron, zeta %4.2f: computed %.6e s, "
                  "formula %.6e s, ratio %.6f; spectral radius %.8f at "
                  "0.999, %.8f at 1.001\n",
                  zeta,
                  computed,
                  formula,
                  computed / formula,
                  below,
                  above);
      EXPECT_LE(below, 1. + radius_tolerance);
      EXPECT_GT(above, 1. + radius_tolerance);
      EXPECT_LE(computed, formula * (1. + 1e-12));
      EXPECT_GE(computed, formula * (1. - 1.0001e-4));
    }
  // tetrahedra whose highest mode is not one of C: a lower bound of the
  // exact step of the assembled update
  for (const Tet &t : {corner(), skewed()})
    for (const double zeta : {0.25, 1., 2.})
      {
        const Comparison r = compare({{t}, {}}, 0., 1., zeta);
        std::printf("irregular tetrahedron, zeta %4.2f: computed %.6e s, "
                    "exact %.6e s, ratio %.4f\n",
                    zeta,
                    r.computed,
                    r.exact,
                    r.computed / r.exact);
        EXPECT_LE(r.computed, r.exact);
        EXPECT_GE(r.computed, 0.8 * r.exact);
      }
}

TEST(StableStep3D, JoinedTetrahedra)
{
  // A lower bound always. Where the stiff joints' highest mode moves the
  // joined faces against each other (penalty 1000 E) the bound's ratio to
  // the exact step is that of the joint alone: a joint between nodal masses
  // m_A >= m_B has omega^2 = k (1 / m_A + 1 / m_B), the bound 2 k / m_B,
  // so the ratio is sqrt((1 + m_B / m_A) / 2): 1 for equal elements,
  // sqrt(0.8) for the shifted pair (volumes 1 : 0.6). The regular
  // tetrahedron split at its centroid has no such mode: its four elements
  // are joined pairwise, and no pattern moves each of three mutually joined
  // copies of a node against both others, so the bound of its isotropic
  // joints (k_t = k_n) stays below the exact step there (ratio 0 below:
  // the lower bound only).
  const struct
  {
    const char *name;
    Assembly    assembly;
    double      stiff_joint_ratio;
  } assemblies[] = {{"two tetrahedra", two_tetrahedra(false), 1.},
                    {"two shifted", two_tetrahedra(true), std::sqrt(0.8)},
                    {"four on an edge", four_around_an_edge(), 1.},
                    {"four in a tet", four_tetrahedra(), 0.}};
  for (const auto &a : assemblies)
    for (const double penalty : {10., 100., 1000.})
      for (const double ratio : {1., 0.1})
        for (const double zeta : {0., 0.5, 2.})
          {
            const Comparison r = compare(a.assembly, penalty, ratio, zeta);
            std::printf("%-16s penalty %5.0f E  k_t/k_n %4.2f  zeta %4.2f: "
                        "computed %.5e s, exact %.5e s, ratio %.4f\n",
                        a.name,
                        penalty,
                        ratio,
                        zeta,
                        r.computed,
                        r.exact,
                        r.computed / r.exact);
            EXPECT_LE(r.computed, r.exact * (1. + 1e-9)) << a.name;
            EXPECT_GE(r.computed, 0.8 * r.exact) << a.name;
            if (penalty == 1000. && a.stiff_joint_ratio > 0.)
              {
                EXPECT_NEAR(r.computed / r.exact, a.stiff_joint_ratio, 0.01)
                  << a.name;
              }
          }
}

TEST(StableStep3D, DampingRatioIsModal)
{
  // highest_mode_damping_per_viscosity() against phi^T C_1 phi / (2 m
  // omega) of the reference's own modes (averaged over the regular
  // tetrahedron's repeated highest frequency)
  const LameConstants lame = lame_3d();
  for (const Tet &t : {regular(), corner(), skewed()})
    {
      std::array<double, 4> x, y, z;
      for (unsigned int k = 0; k < 4; ++k)
        {
          x[k] = t[k](0);
          y[k] = t[k](1);
          z[k] = t[k](2);
        }
      const double    m = rho * volume(t) / 4.;
      Eigen::MatrixXd K, C1;
      reference_matrices(t, lame, K, C1);
      Eigen::VectorXd mass(12);
      mass.setConstant(m);
      const double reference = reference_damping_per_viscosity(K, C1, mass);
      const double zeta1 = highest_mode_damping_per_viscosity(x, y, z, lame, m);
      std::printf("damping ratio per viscosity: %.10e 1/(Pa s), reference "
                  "%.10e\n",
                  zeta1,
                  reference);
      EXPECT_NEAR(zeta1, reference, 1e-8 * reference);
    }
}

TEST(StableStep3D, ViscousLimit)
{
  // |C|^2 >> |K|: the norm bound's root without cancellation (the former
  // form rounded to 0 and the bisection did not end): a finite step that
  // stable_at() accepts, and not 1 % above it
  TetrahedronStepInput in;
  const Tet            t = regular();
  for (unsigned int k = 0; k < 4; ++k)
    {
      in.x[k] = t[k](0);
      in.y[k] = t[k](1);
      in.z[k] = t[k](2);
    }
  in.lame         = lame_3d();
  in.node_mass    = rho * volume(t) / 4.;
  in.viscosity    = 1e20;
  const double dt = critical_time_step(in);
  EXPECT_GT(dt, 0.);
  EXPECT_TRUE(stable_at(in, dt));
  EXPECT_FALSE(stable_at(in, 1.01 * dt));
  ElementStepInput tri;
  tri.x            = {{0., h, 0.5 * h}};
  tri.y            = {{0., 0., h}};
  tri.lame         = in.lame;
  tri.node_mass    = rho * 0.5 * h * h / 3.;
  tri.viscosity    = 1e20;
  const double dt2 = critical_time_step(tri);
  EXPECT_GT(dt2, 0.);
  EXPECT_TRUE(stable_at(tri, dt2));
  EXPECT_FALSE(stable_at(tri, 1.01 * dt2));
}

namespace
{
  // deterministic pseudo-random numbers in [0, 1) (exact: integer state)
  struct Lcg
  {
    std::uint64_t state;
    double
    operator()()
    {
      state = state * 6364136223846793005ULL + 1442695040888963407ULL;
      return static_cast<double>(state >> 11) * 0x1.0p-53;
    }
  };

  // the 2D cases of the bitwise check: triangles of all shapes and sizes,
  // with and without joints, viscosity and contact
  std::vector<ElementStepInput>
  triangle_cases()
  {
    std::vector<ElementStepInput> cases;
    Lcg                           r{12345};
    for (unsigned int c = 0; c < 24; ++c)
      {
        ElementStepInput in;
        const double     h  = 1e-3 * (1. + 99. * r());
        const double     x0 = 10. * (r() - 0.5), y0 = 10. * (r() - 0.5);
        const double     a = 0.1 + 0.9 * r();
        in.x               = {{x0, x0 + h, x0 + h * (r() - 0.3)}};
        in.y               = {{y0, y0 + 0.2 * h * (r() - 0.5), y0 + a * h}};
        const double E     = 1e9 * (1. + 99. * r());
        const double nu    = 0.45 * r();
        in.lame.mu         = E / (2. * (1. + nu));
        in.lame.lambda     = E * nu / ((1. + nu) * (1. - 2. * nu));
        const double area  = 0.5 * ((in.x[1] - in.x[0]) * (in.y[2] - in.y[0]) -
                                   (in.x[2] - in.x[0]) * (in.y[1] - in.y[0]));
        in.node_mass       = 2700. * area / 3.;
        in.viscosity = c % 3 == 0 ? 0. : 1e3 * r() * h * std::sqrt(E * 2700.);
        for (unsigned int k = 0; k < 3; ++k)
          if ((c >> k) & 1)
            {
              in.edge_joint_normal_stiffness[k] = 1000. * r() * E / h;
              in.edge_joint_tangential_stiffness[k] =
                r() * in.edge_joint_normal_stiffness[k];
            }
        in.node_contact_stiffness = c % 4 == 1 ? 30. * r() * E : 0.;
        cases.push_back(in);
      }
    // a massless, a degenerate and an unloaded element
    ElementStepInput massless = cases[0];
    massless.node_mass        = 0.;
    cases.push_back(massless);
    ElementStepInput flat = cases[1];
    flat.y[2] = flat.y[0] + (flat.y[1] - flat.y[0]) * (flat.x[2] - flat.x[0]) /
                              (flat.x[1] - flat.x[0]);
    flat.viscosity = 0.;
    cases.push_back(flat);
    ElementStepInput inverted = cases[2];
    std::swap(inverted.x[1], inverted.x[2]);
    std::swap(inverted.y[1], inverted.y[2]);
    cases.push_back(inverted);
    ElementStepInput free = cases[3];
    free.lame.mu = free.lame.lambda = 0.;
    free.viscosity                  = 0.;
    cases.push_back(free);
    ElementStepInput unloaded = cases[0];
    unloaded.lame.mu = unloaded.lame.lambda = 0.;
    cases.push_back(unloaded);
    return cases;
  }

  // FNV-1a of the bits of a matrix's entries
  template <typename Matrix>
  std::uint64_t
  bits_hash(const Matrix &m, std::uint64_t h = 14695981039346656037ULL)
  {
    for (const auto &row : m)
      for (const double v : row)
        {
          std::uint64_t b;
          std::memcpy(&b, &v, sizeof b);
          for (unsigned int k = 0; k < 8; ++k)
            {
              h ^= (b >> (8 * k)) & 0xffu;
              h *= 1099511628211ULL;
            }
        }
    return h;
  }

  struct Recorded
  {
    double        critical_time_step, damping_per_viscosity;
    std::uint64_t matrices_hash, eigen_hash;
    int           stable_at; // at 0.5, 1, 1 + 2e-4 times the step: bits
  };
} // namespace

TEST(StableStep3D, TrianglesBitwiseUnchanged)
{
  // the 2D instantiation against values recorded from the triangle-only
  // code it replaced (hexadecimal, bitwise): critical_time_step(),
  // stable_at(), element_matrices(), symmetric_eigen() and
  // highest_mode_damping_per_viscosity()
  const double   infinity   = std::numeric_limits<double>::infinity();
  const Recorded recorded[] = {
    {0x1.593bcc3f30535p-20,
     0x1.21d5fc444e5f2p-16,
     0xb62cbe97015adc1fULL,
     0xb100dabd333e564cULL,
     3},
    {0x1.9b9e82f65b3a5p-29,
     0x1.ad7294950e746p-19,
     0x7f46f97d4ea23339ULL,
     0xdd77508f20ab6fb9ULL,
     3},
    {0x1.79dc54ae57ebep-33,
     0x1.fd03d76765fcep-15,
     0x59c0c25e50d9f376ULL,
     0x8609bb4a15087588ULL,
     3},
    {0x1.d075882cd366p-25,
     0x1.b841925852fb2p-14,
     0x28ba7f3f5c48f8eaULL,
     0xac480662ed670399ULL,
     3},
    {0x1.f7f1134f2b744p-34,
     0x1.8cd5be399e6e4p-16,
     0x8e48a1582a2456f2ULL,
     0x66755bd3d03ebffbULL,
     3},
    {0x1.daf920040b7bp-33,
     0x1.29af21869515p-15,
     0x88eabd2a749e69c1ULL,
     0xcfea2ba6d84cd4adULL,
     3},
    {0x1.796e8a65a47fcp-25,
     0x1.15b508e2834e2p-14,
     0x483f30435bbf41d2ULL,
     0x8b91ab76fec1b7cbULL,
     3},
    {0x1.4e5cfd85240cep-31,
     0x1.7f916aa1f1eb5p-18,
     0x2b9ff6ca42edfdbeULL,
     0x1f45293e54cdb48cULL,
     3},
    {0x1.682d9424ebec9p-31,
     0x1.26529cca244a6p-15,
     0x241314123e9588a7ULL,
     0x99bc0b214ff533d1ULL,
     3},
    {0x1.6e66cfc4e0b58p-19,
     0x1.61cd590bbf9acp-17,
     0x5900c4539f82768aULL,
     0x580bc465b404821eULL,
     3},
    {0x1.041b7d6691823p-30,
     0x1.a0e2dd67aadeep-17,
     0x3e356ecc0e89e32cULL,
     0x4feddd3f0388bfb7ULL,
     3},
    {0x1.9ddca36908effp-29,
     0x1.16022bc79b959p-19,
     0x3780c9e6adafaae5ULL,
     0xc9b748d4892bb15cULL,
     3},
    {0x1.1decbc645ccc9p-20,
     0x1.b9dd6ec5e9d78p-17,
     0xfd85d297b2de979cULL,
     0x904af0def5c0eb9cULL,
     3},
    {0x1.829210cb1b3b4p-30,
     0x1.8b337c44c0279p-19,
     0xc6f79202b4833feeULL,
     0x59cb90245a9184b3ULL,
     3},
    {0x1.9969bdbe229b4p-27,
     0x1.21ac94ba80c05p-16,
     0x98d58a7295df024dULL,
     0x7e801c02d0cc0800ULL,
     3},
    {0x1.a21ca99da24bp-22,
     0x1.8b3cd33158e52p-16,
     0x20bf8d82a441bc81ULL,
     0x15f31d114e665a5bULL,
     3},
    {0x1.0b6c86cb175e4p-31,
     0x1.a3fc7c63f3d12p-15,
     0x07a1c5c509b6e898ULL,
     0x1e15b368b82e0d21ULL,
     3},
    {0x1.5ff1f62c2bf64p-32,
     0x1.477a220f3c709p-17,
     0xf93bed0bf6ac3a04ULL,
     0xe14f97759c574284ULL,
     3},
    {0x1.79cffd61ba8acp-21,
     0x1.38dc9a3562a7bp-16,
     0x62981f636cf19778ULL,
     0x16a2231233841c34ULL,
     3},
    {0x1.1ddc95ba2750ap-30,
     0x1.a717126fcaf5ap-18,
     0x31359a1b89acfb7eULL,
     0x43b2d2cea5f73526ULL,
     3},
    {0x1.1446ce92773a4p-31,
     0x1.9083c4645ef6ap-16,
     0xfb83d8d20f2bd9a5ULL,
     0xa8654f47e56fbf60ULL,
     3},
    {0x1.2ca488da39f54p-22,
     0x1.7c4ab9e81cd67p-18,
     0xa2133f78d6366a33ULL,
     0xc67a0af9a383dd86ULL,
     3},
    {0x1.14887a6ffc352p-29,
     0x1.4af5c074ee44ap-17,
     0x6ded7f5b650d926dULL,
     0x3914794dffb9b9d1ULL,
     3},
    {0x1.453ccd26fcdc6p-21,
     0x1.b16c0735f2734p-19,
     0xebda95403424d84bULL,
     0xe6f0378ec560cc65ULL,
     3},
    {0x0p+0,
     0x1.0cf0c78106156p-18,
     0xb62cbe97015adc1fULL,
     0xb100dabd333e564cULL,
     0},
    {0x1.4d2242841ec9p-41,
     0x1.0908d115fd9e3p+6,
     0x9e53ac045c709e83ULL,
     0x97e1e64d78f33829ULL,
     3},
    {0x0p+0,
     0x1.fd03d76765fcbp-15,
     0xb6f929fb0b19a0deULL,
     0x611d023d23daa8e1ULL,
     0},
    {0x1.d0bac930da031p-25,
     0x0p+0,
     0x9d50245658b8595cULL,
     0xf92fdb692e0c7645ULL,
     3},
    {infinity, 0x0p+0, 0xcf6b47c9b1cc2640ULL, 0xf92fdb692e0c7645ULL, 0},
  };
  const auto cases = triangle_cases();
  ASSERT_EQ(cases.size(), sizeof(recorded) / sizeof(recorded[0]));
  for (unsigned int i = 0; i < cases.size(); ++i)
    {
      const ElementStepInput &in = cases[i];
      const Recorded         &r  = recorded[i];
      const double            dt = critical_time_step(in);
      EXPECT_EQ(std::memcmp(&dt, &r.critical_time_step, sizeof dt), 0)
        << "case " << i << ": " << dt << " instead of " << r.critical_time_step;
      Matrix6 K, C;
      element_matrices(in.x, in.y, in.lame, K, C);
      EXPECT_EQ(bits_hash(C, bits_hash(K)), r.matrices_hash) << "case " << i;
      std::array<double, 6> w;
      Matrix6               V;
      symmetric_eigen(K, w, V);
      const std::array<std::array<double, 6>, 1> wa{{w}};
      EXPECT_EQ(bits_hash(V, bits_hash(wa)), r.eigen_hash) << "case " << i;
      const double z =
        in.lame.mu > 0. ?
          highest_mode_damping_per_viscosity(in.x,
                                             in.y,
                                             in.lame,
                                             in.node_mass > 0. ? in.node_mass :
                                                                 1.) :
          0.;
      EXPECT_EQ(std::memcmp(&z, &r.damping_per_viscosity, sizeof z), 0)
        << "case " << i;
      const int s = (stable_at(in, 0.5 * dt) ? 1 : 0) +
                    (stable_at(in, dt) ? 2 : 0) +
                    (stable_at(in, dt * (1. + 2e-4)) ? 4 : 0);
      EXPECT_EQ(s, r.stable_at) << "case " << i;
    }
}
