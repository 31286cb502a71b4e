// Unit tests of the boundary stress recovery (stress_recovery.h): the
// stress a boundary edge recovers from its traction and tangential stretch
// equals the stress of Eq. 44 of the homogeneous deformation it was taken
// from, at finite strain, with shear traction and thermal stretch.

#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <tmfdem/discrete/solid.h>
#include <tmfdem/discrete/stress_recovery.h>

using namespace tmfdem::discrete;

TEST(StressRecovery, BoundaryEdgeReproducesHomogeneousDeformation)
{
  std::mt19937                           random(7);
  std::uniform_real_distribution<double> u(-1., 1.);
  for (const auto idealisation :
       {Idealisation::plane_stress, Idealisation::plane_strain})
    for (unsigned int trial = 0; trial < 50; ++trial)
      {
        BoundaryEdgeKnowledge edge;
        edge.kind            = BoundaryEdgeKnowledge::Kind::traction;
        edge.lame            = lame_constants(20e9, 0.2, idealisation);
        edge.thermal_stretch = 1. + 0.01 * u(random);
        // a finite homogeneous deformation (stretches up to 20 %, shear)
        // (drawn in this order: the entries of a braced list are evaluated
        // left to right, a function's arguments are not)
        const double  f[4]  = {1. + 0.2 * u(random),
                               0.2 * u(random),
                               0.2 * u(random),
                               1. + 0.2 * u(random)};
        const Matrix2 F     = matrix2(f[0], f[1], f[2], f[3]);
        const double  s     = edge.thermal_stretch;
        const Stress2 sigma = elastic_stress(F / s, edge.lame);
        // a reference edge of any direction and its image
        const double angle = M_PI * u(random), L0 = 0.01;
        const double X0 = 0.3, Y0 = -0.2;
        const double X1 = X0 + L0 * std::cos(angle),
                     Y1 = Y0 + L0 * std::sin(angle);
        const double x0 = F(0, 0) * X0 + F(0, 1) * Y0,
                     y0 = F(1, 0) * X0 + F(1, 1) * Y0;
        const double x1 = F(0, 0) * X1 + F(0, 1) * Y1,
                     y1 = F(1, 0) * X1 + F(1, 1) * Y1;
        // Cauchy traction on the current outward normal (dy, -dx)/L
        const double  L  = std::hypot(x1 - x0, y1 - y0);
        const double  nx = (y1 - y0) / L, ny = -(x1 - x0) / L;
        const double  tx = sigma.xx * nx + sigma.xy * ny;
        const double  ty = sigma.xy * nx + sigma.yy * ny;
        const Stress2 r =
          boundary_edge_stress(x0, y0, x1, y1, L0, tx, ty, edge);
        const double scale =
          std::abs(sigma.xx) + std::abs(sigma.yy) + std::abs(sigma.xy);
        EXPECT_NEAR(r.xx, sigma.xx, 1e-9 * scale);
        EXPECT_NEAR(r.yy, sigma.yy, 1e-9 * scale);
        EXPECT_NEAR(r.xy, sigma.xy, 1e-9 * scale);
      }
}

TEST(StressRecovery, FreeEdgeSmallStrainIsUniaxial)
{
  // a free edge along x stretched by eps (no thermal stretch): sigma_xx =
  // E' eps with E' = 4 mu (lambda + mu) / (lambda + 2 mu), the rest zero
  BoundaryEdgeKnowledge edge;
  edge.kind         = BoundaryEdgeKnowledge::Kind::traction;
  edge.lame         = lame_constants(20e9, 0.2, Idealisation::plane_strain);
  const double  eps = 1e-6;
  const Stress2 r =
    boundary_edge_stress(0., 0., 1. + eps, 0., 1., 0., 0., edge);
  const double mu = edge.lame.mu, lambda = edge.lame.lambda;
  const double E_eff = 4. * mu * (lambda + mu) / (lambda + 2. * mu);
  EXPECT_NEAR(r.xx, E_eff * eps, 1e-5 * E_eff * eps);
  EXPECT_NEAR(r.yy, 0., 1e-9 * E_eff * eps);
  EXPECT_NEAR(r.xy, 0., 1e-9 * E_eff * eps);
}
