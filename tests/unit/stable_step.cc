// Unit tests of the explicit stable step (stable_step.h) against the exact
// critical step of small assemblies: one triangle, two and four triangles
// joined by cohesive joints, at joint penalties 10 E ... 1000 E and damping
// ratios 0 ... 2. The exact step is the largest dt for which the spectral
// radius of the scheme's amplification matrix stays 1: the scheme
//   v+ = v - dt M^-1 (K x + C v),  x+ = x + dt v+
// with K, C and M assembled here independently of the bound: K_e and C_e by
// differentiating the production kernels of solid.h (the element force and
// the viscous stress 2 eta sym(grad v)), the joints from their energy
// 1/2 int (k_n d_n^2 + k_t d_t^2) ds with the two-point Gauss rule of the
// joint force.

#include <deal.II/lac/lapack_full_matrix.h>

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <tmfdem/discrete/solid.h>
#include <tmfdem/discrete/stable_step.h>
#include <vector>

using namespace tmfdem::discrete;

namespace
{
  const double E = 10e9, nu = 0.25, rho = 2700.;

  struct Joint
  {
    // element, local edge (nodes k, k+1) of side A and side B; B's edge runs
    // the other way
    unsigned int ea, ka, eb, kb;
  };

  struct Assembly
  {
    std::vector<std::array<double, 3>> x, y;
    std::vector<Joint>                 joints;
  };

  // element force of solid.h at node positions xs, ys (reference X, Y)
  void
  element_force(const double        *xs,
                const double        *ys,
                const double        *X,
                const double        *Y,
                const LameConstants &lame,
                double              *f)
  {
    const Matrix2 F =
      element_basis(xs[0], ys[0], xs[1], ys[1], xs[2], ys[2]) *
      element_basis(X[0], Y[0], X[1], Y[1], X[2], Y[2]).inverse();
    nodal_forces(elastic_stress(F, lame),
                 xs[0],
                 ys[0],
                 xs[1],
                 ys[1],
                 xs[2],
                 ys[2],
                 f);
  }

  // viscous force of the production loop for velocities vx, vy
  void
  viscous_force(const double *vx,
                const double *vy,
                const double *X,
                const double *Y,
                const double  eta,
                double       *f)
  {
    const Matrix2 Fi_inv =
      element_basis(X[0], Y[0], X[1], Y[1], X[2], Y[2]).inverse();
    const Matrix2 L =
      element_basis(vx[0], vy[0], vx[1], vy[1], vx[2], vy[2]) * Fi_inv;
    const Stress2 s{2. * eta * L(0, 0),
                    2. * eta * L(1, 1),
                    eta * (L(0, 1) + L(1, 0))};
    nodal_forces(s, X[0], Y[0], X[1], Y[1], X[2], Y[2], f);
  }

  struct Result
  {
    double computed, exact;
  };

  Result
  compare(const Assembly &a,
          const double    penalty_factor,
          const double    tangential_ratio,
          const double    damping_ratio)
  {
    const LameConstants lame =
      lame_constants(E, nu, Idealisation::plane_strain);
    const unsigned int            n_el = a.x.size(), N = 6 * n_el;
    std::vector<double>           K(N * N, 0.), C(N * N, 0.), mass(N, 0.);
    std::vector<ElementStepInput> inputs(n_el);
    for (unsigned int e = 0; e < n_el; ++e)
      {
        const double *X = a.x[e].data(), *Y = a.y[e].data();
        const double  area =
          0.5 * ((X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]));
        const double m = rho * area / 3.;
        const double eta =
          damping_ratio > 0. ?
            damping_ratio /
              highest_mode_damping_per_viscosity(a.x[e], a.y[e], lame, m) :
            0.;
        inputs[e].x         = a.x[e];
        inputs[e].y         = a.y[e];
        inputs[e].lame      = lame;
        inputs[e].viscosity = eta;
        inputs[e].node_mass = m;
        for (unsigned int i = 0; i < 6; ++i)
          mass[6 * e + i] = m;
        const double h = 1e-7 * std::sqrt(area);
        for (unsigned int j = 0; j < 6; ++j)
          {
            double xp[3], yp[3], xm[3], ym[3], fp[6], fm[6];
            for (unsigned int k = 0; k < 3; ++k)
              {
                xp[k] = xm[k] = X[k];
                yp[k] = ym[k] = Y[k];
              }
            (j % 2 == 0 ? xp : yp)[j / 2] += h;
            (j % 2 == 0 ? xm : ym)[j / 2] -= h;
            element_force(xp, yp, X, Y, lame, fp);
            element_force(xm, ym, X, Y, lame, fm);
            double vx[3] = {0., 0., 0.}, vy[3] = {0., 0., 0.}, fv[6];
            (j % 2 == 0 ? vx : vy)[j / 2] = 1.;
            viscous_force(vx, vy, X, Y, eta, fv);
            for (unsigned int i = 0; i < 6; ++i)
              {
                K[(6 * e + i) * N + 6 * e + j] = -(fp[i] - fm[i]) / (2. * h);
                C[(6 * e + i) * N + 6 * e + j] = -fv[i];
              }
          }
      }
    const double g[2] = {0.21132486540518713, 0.78867513459481287};
    for (const Joint &j : a.joints)
      {
        // side A runs from node ka to ka+1, side B from kb+1 to kb
        const unsigned int a0 = 6 * j.ea + 2 * j.ka,
                           a1 = 6 * j.ea + 2 * ((j.ka + 1) % 3);
        const unsigned int b0 = 6 * j.eb + 2 * ((j.kb + 1) % 3),
                           b1 = 6 * j.eb + 2 * j.kb;
        const double dx       = a.x[j.ea][(j.ka + 1) % 3] - a.x[j.ea][j.ka];
        const double dy       = a.y[j.ea][(j.ka + 1) % 3] - a.y[j.ea][j.ka];
        const double L        = std::hypot(dx, dy);
        const double t[2] = {dx / L, dy / L}, n[2] = {t[1], -t[0]};
        const double k_n = penalty_factor * E / L;
        const double k_t = tangential_ratio * k_n;
        for (unsigned int q = 0; q < 2; ++q)
          for (unsigned int dir = 0; dir < 2; ++dir)
            {
              const double       *d = dir == 0 ? n : t;
              const double        k = dir == 0 ? k_n : k_t;
              std::vector<double> v(N, 0.);
              for (unsigned int c = 0; c < 2; ++c)
                {
                  v[b0 + c] += (1. - g[q]) * d[c];
                  v[a0 + c] -= (1. - g[q]) * d[c];
                  v[b1 + c] += g[q] * d[c];
                  v[a1 + c] -= g[q] * d[c];
                }
              for (unsigned int r = 0; r < N; ++r)
                for (unsigned int c = 0; c < N; ++c)
                  K[r * N + c] += 0.5 * L * k * v[r] * v[c];
            }
        inputs[j.ea].edge_joint_normal_stiffness[j.ka]     = k_n;
        inputs[j.ea].edge_joint_tangential_stiffness[j.ka] = k_t;
        inputs[j.eb].edge_joint_normal_stiffness[j.kb]     = k_n;
        inputs[j.eb].edge_joint_tangential_stiffness[j.kb] = k_t;
      }
    double computed = 1e300;
    for (const auto &in : inputs)
      computed = std::min(computed, critical_time_step(in));

    const auto radius = [&](const double dt) {
      dealii::LAPACKFullMatrix<double> A(2 * N, 2 * N);
      for (unsigned int r = 0; r < N; ++r)
        for (unsigned int c = 0; c < N; ++c)
          {
            // v+ = (I - dt M^-1 C) v - dt M^-1 K x
            const double Bv = (r == c ? 1. : 0.) - dt * C[r * N + c] / mass[r];
            const double Bx = -dt * K[r * N + c] / mass[r];
            A(r, c)         = Bv;
            A(r, N + c)     = Bx;
            A(N + r, c)     = dt * Bv;
            A(N + r, N + c) = (r == c ? 1. : 0.) + dt * Bx;
          }
      A.compute_eigenvalues();
      double rho_max = 0.;
      for (unsigned int i = 0; i < 2 * N; ++i)
        rho_max = std::max(rho_max, std::abs(A.eigenvalue(i)));
      return rho_max;
    };
    const double tol = 1e-6;
    // scan up from well below the bound, then bisect the first crossing
    double lo = 0.2 * computed, hi = lo;
    while (radius(hi) <= 1. + tol)
      {
        lo = hi;
        hi *= 1.02;
        if (hi > 100. * computed)
          break;
      }
    for (unsigned int i = 0; i < 40; ++i)
      {
        const double mid                    = 0.5 * (lo + hi);
        (radius(mid) <= 1. + tol ? lo : hi) = mid;
      }
    return {computed, lo};
  }

  const double s3 = std::sqrt(3.) / 2.;
  const double h  = 0.01; // element size [m]

  Assembly
  one_triangle(const std::array<double, 3> &x, const std::array<double, 3> &y)
  {
    return {{x}, {y}, {}};
  }

  Assembly
  two_triangles()
  {
    // the square [0, h]^2 split along its diagonal; A's edge 2 runs from
    // (h, h) to (0, 0), B's edge 0 from (0, 0) to (h, h)
    return {{{{0., h, h}}, {{0., h, 0.}}},
            {{{0., 0., h}}, {{0., h, h}}},
            {{0, 2, 1, 0}}};
  }

  Assembly
  four_triangles()
  {
    // the square [0, h]^2 split by both diagonals: element k is
    // (corner k, corner k+1, centre); edge 1 of k meets edge 2 of k+1
    const double cx[4] = {0., h, h, 0.}, cy[4] = {0., 0., h, h};
    Assembly     a;
    for (unsigned int k = 0; k < 4; ++k)
      {
        a.x.push_back({{cx[k], cx[(k + 1) % 4], 0.5 * h}});
        a.y.push_back({{cy[k], cy[(k + 1) % 4], 0.5 * h}});
        a.joints.push_back({k, 1, (k + 1) % 4, 2});
      }
    return a;
  }

  void
  check(const char     *name,
        const Assembly &a,
        const double    penalty,
        const double    tangential_ratio,
        const double    zeta)
  {
    const Result r = compare(a, penalty, tangential_ratio, zeta);
    std::printf("%-16s penalty %6.0f E  k_t/k_n %4.2f  zeta %4.2f: computed "
                "%.5e s, exact %.5e s, ratio %.4f\n",
                name,
                penalty,
                tangential_ratio,
                zeta,
                r.computed,
                r.exact,
                r.computed / r.exact);
    EXPECT_LE(r.computed, r.exact) << name;
    EXPECT_GE(r.computed, 0.8 * r.exact) << name;
  }
} // namespace

TEST(StableStep, OneTriangle)
{
  for (const double zeta : {0., 0.25, 0.5, 1., 2.})
    {
      check("equilateral",
            one_triangle({{0., h, 0.5 * h}}, {{0., 0., s3 * h}}),
            0.,
            1.,
            zeta);
      check("right", one_triangle({{0., h, 0.}}, {{0., 0., h}}), 0., 1., zeta);
      check("obtuse",
            one_triangle({{0., h, 0.8 * h}}, {{0., 0., 0.25 * h}}),
            0.,
            1.,
            zeta);
    }
}

TEST(StableStep, JoinedTriangles)
{
  for (const double penalty : {10., 100., 1000.})
    for (const double zeta : {0., 0.25, 0.5, 1., 2.})
      for (const double ratio : {1., 0.1})
        {
          check("two triangles", two_triangles(), penalty, ratio, zeta);
          check("four triangles", four_triangles(), penalty, ratio, zeta);
        }
}

TEST(StableStep, DampingRatioIsModal)
{
  // Damping ratio 1 damps the highest free mode of the element critically:
  // its pair of eigenvalues of the continuous system M s^2 + C s + K
  // coincides. Checked on the equilateral triangle, whose highest mode is
  // not shared with C's other modes: zeta = phi^T C phi / (2 m omega).
  const LameConstants lame = lame_constants(E, nu, Idealisation::plane_strain);
  const std::array<double, 3> x = {{0., h, 0.5 * h}}, y = {{0., 0., s3 * h}};
  const double                m = rho * 0.5 * h * s3 * h / 3.;
  const double zeta1 = highest_mode_damping_per_viscosity(x, y, lame, m);
  Matrix6      K, C1;
  element_matrices(x, y, lame, K, C1);
  std::array<double, 6> w2;
  Matrix6               modes;
  symmetric_eigen(K, w2, modes);
  // the highest mode of K is also an eigenvector of C_1 for this triangle
  double Cphi_norm = 0., phiCphi = 0.;
  for (unsigned int r = 0; r < 6; ++r)
    {
      double s = 0.;
      for (unsigned int c = 0; c < 6; ++c)
        s += C1[r][c] * modes[c][5];
      phiCphi += modes[r][5] * s;
      Cphi_norm += s * s;
    }
  EXPECT_NEAR(std::sqrt(Cphi_norm), std::abs(phiCphi), 1e-9 * phiCphi);
  const double omega = std::sqrt(w2[5] / m);
  EXPECT_NEAR(zeta1, phiCphi / (2. * m * omega), 1e-12 * zeta1);
  // the old convention eta = 2 h sqrt(E rho), h = sqrt(2 A), gave zeta ~ 3.6
  const double eta_old =
    2. * std::sqrt(2. * 0.5 * h * s3 * h) * std::sqrt(E * rho);
  EXPECT_GT(eta_old * zeta1, 3.5);
  EXPECT_LT(eta_old * zeta1, 3.7);
}
