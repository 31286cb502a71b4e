// Unit tests of the stress recovery (stress_recovery.h): the stress a
// boundary edge recovers from its traction and tangential stretch equals
// the stress of Eq. 44 of the homogeneous deformation it was taken from, at
// finite strain, with shear traction and thermal stretch; the patch
// polynomials reproduce quadratic fields; known tractions prescribe the
// boundary vertices' values.

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <array>
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

// The patch recovery (RecoveredStress) on a distorted triangle mesh of the
// rectangle (0, 2) x (0, 1).
namespace
{
  void
  distorted_rectangle(dealii::Triangulation<2> &triangulation)
  {
    dealii::GridGenerator::subdivided_hyper_rectangle_with_simplices(
      triangulation,
      {10, 6},
      dealii::Point<2>(0., 0.),
      dealii::Point<2>(2., 1.));
    // boundary ids: 0 left, 1 right, 2 bottom, 3 top
    // move interior vertices by up to 0.2 h so that no patch is symmetric
    std::mt19937                           random(3);
    std::uniform_real_distribution<double> u(-1., 1.);
    std::vector<bool> on_boundary(triangulation.n_vertices(), false);
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int f : cell->face_indices())
        if (cell->face(f)->at_boundary())
          {
            const dealii::Point<2> c = cell->face(f)->center();
            cell->face(f)->set_boundary_id(c[0] < 1e-9      ? 0 :
                                           c[0] > 2. - 1e-9 ? 1 :
                                           c[1] < 1e-9      ? 2 :
                                                              3);
            for (const unsigned int k : cell->face(f)->vertex_indices())
              on_boundary[cell->face(f)->vertex_index(k)] = true;
          }
    std::vector<dealii::Tensor<1, 2>> shift(triangulation.n_vertices());
    for (unsigned int v = 0; v < triangulation.n_vertices(); ++v)
      if (!on_boundary[v])
        {
          shift[v][0] = 0.2 * 0.2 * u(random);
          shift[v][1] = 0.2 * (1. / 6.) * u(random);
        }
    std::vector<bool> moved(triangulation.n_vertices(), false);
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const unsigned int k : cell->vertex_indices())
        if (!moved[cell->vertex_index(k)])
          {
            moved[cell->vertex_index(k)] = true;
            cell->vertex(k) += shift[cell->vertex_index(k)];
          }
  }

  /** The exploded model of distorted_rectangle(). */
  DiscreteModel
  model_on_distorted_rectangle()
  {
    dealii::Triangulation<2> triangulation;
    distorted_rectangle(triangulation);
    dealii::FE_SimplexDGP<2> fe(1);
    dealii::DoFHandler<2>    dof_handler(triangulation);
    dof_handler.distribute_dofs(fe);
    DiscreteModel model;
    model.build(dof_handler);
    return model;
  }
} // namespace

// A quadratic stress field given at the centroids is reproduced exactly
// everywhere (every vertex fits a quadratic, corners included: their
// patches widen to 14 triangles), by the samples' blend of the three
// vertices' polynomials too.
TEST(StressRecovery, PatchFitReproducesQuadraticField)
{
  DiscreteModel model = model_on_distorted_rectangle();
  const auto    field = [](const double x, const double y) {
    return std::array<double, 3>{
      {1. + 2. * x - 3. * y + 5. * x * x - 4. * x * y + 7. * y * y,
       -2. + x + y - x * x + 6. * x * y,
       0.5 - 3. * x + 2. * y * y}};
  };
  for (unsigned int e = 0; e < model.n_elements; ++e)
    {
      const double x =
        (model.x_ref[3 * e] + model.x_ref[3 * e + 1] + model.x_ref[3 * e + 2]) /
        3.;
      const double y =
        (model.y_ref[3 * e] + model.y_ref[3 * e + 1] + model.y_ref[3 * e + 2]) /
        3.;
      for (unsigned int c = 0; c < 3; ++c)
        model.stress[3 * e + c] = field(x, y)[c] * 1e6;
    }
  const RecoveredStress recovered(model, {});
  for (unsigned int v = 0; v < recovered.n_vertices(); ++v)
    EXPECT_EQ(recovered.degree(v), 2u) << "vertex " << v;
  std::mt19937                           random(11);
  std::uniform_real_distribution<double> u(0., 1.);
  for (unsigned int e = 0; e < model.n_elements; ++e)
    {
      double lambda[3] = {u(random), u(random), 0.};
      if (lambda[0] + lambda[1] > 1.)
        {
          lambda[0] = 1. - lambda[0];
          lambda[1] = 1. - lambda[1];
        }
      lambda[2] = 1. - lambda[0] - lambda[1];
      double x = 0., y = 0.;
      for (unsigned int k = 0; k < 3; ++k)
        {
          x += lambda[k] * model.x_ref[3 * e + k];
          y += lambda[k] * model.y_ref[3 * e + k];
        }
      const Stress2 s     = recovered.value(e, lambda);
      const auto    exact = field(x, y);
      EXPECT_NEAR(s.xx, 1e6 * exact[0], 1e-3);
      EXPECT_NEAR(s.yy, 1e6 * exact[1], 1e-3);
      EXPECT_NEAR(s.xy, 1e6 * exact[2], 1e-3);
    }
}

// A homogeneous finite uniaxial stretch along x (free top and bottom,
// the right and left edges loaded by the nominal traction that holds it,
// thermal stretch on): the boundary vertices take the stress their edges
// know (free corners and loaded corners included), the interior fits the
// constant element stresses, and the field is the homogeneous stress
// everywhere. The same with the element stresses perturbed by a smooth
// field that vanishes on the boundary: the boundary values stay exact.
TEST(StressRecovery, KnownTractionsPrescribeBoundaryValues)
{
  DiscreteModel       model = model_on_distorted_rectangle();
  const LameConstants lame =
    lame_constants(20e9, 0.2, Idealisation::plane_strain);
  const double s_T = 1.002, a = 1.01 * s_T;
  // b such that sigma_yy = 0 (bisection: sigma_yy increases with b)
  double low = 0.9 * s_T, high = 1.1 * s_T;
  for (unsigned int it = 0; it < 200; ++it)
    {
      const double mid = 0.5 * (low + high);
      (elastic_stress(matrix2(a, 0., 0., mid) / s_T, lame).yy > 0. ? high :
                                                                     low) = mid;
    }
  const double  b     = 0.5 * (low + high);
  const Stress2 sigma = elastic_stress(matrix2(a, 0., 0., b) / s_T, lame);
  ASSERT_NEAR(sigma.yy, 0., 1e-6 * sigma.xx);
  for (unsigned int n = 0; n < model.n_nodes; ++n)
    {
      model.x[n] = a * model.x_ref[n];
      model.y[n] = b * model.y_ref[n];
    }
  for (unsigned int e = 0; e < model.n_elements; ++e)
    model.thermal_stretch[e] = s_T;
  std::vector<BoundaryEdgeKnowledge> boundary(3 * model.n_elements);
  for (unsigned int i = 0; i < boundary.size(); ++i)
    {
      const auto id = model.edge_boundary[i];
      if (id == dealii::numbers::internal_face_boundary_id)
        continue;
      BoundaryEdgeKnowledge &edge = boundary[i];
      edge.kind                   = BoundaryEdgeKnowledge::Kind::traction;
      edge.lame                   = lame;
      edge.thermal_stretch        = s_T;
      // nominal traction (per reference length): sigma n times the
      // current over the reference length (b on the vertical edges)
      if (id == 0)
        edge.traction[0] = -sigma.xx * b;
      else if (id == 1)
        edge.traction[0] = sigma.xx * b;
    }
  for (const double perturbation : {0., 1.})
    {
      for (unsigned int e = 0; e < model.n_elements; ++e)
        {
          const double x = (model.x_ref[3 * e] + model.x_ref[3 * e + 1] +
                            model.x_ref[3 * e + 2]) /
                           3.;
          const double y = (model.y_ref[3 * e] + model.y_ref[3 * e + 1] +
                            model.y_ref[3 * e + 2]) /
                           3.;
          const double bump =
            perturbation * 0.1 * sigma.xx * x * (2. - x) * y * (1. - y);
          model.stress[3 * e]     = sigma.xx + bump;
          model.stress[3 * e + 1] = sigma.yy - bump;
          model.stress[3 * e + 2] = sigma.xy + 0.5 * bump;
        }
      const RecoveredStress recovered(model, boundary);
      std::vector<bool>     on_boundary(recovered.n_vertices(), false);
      for (unsigned int i = 0; i < boundary.size(); ++i)
        if (model.edge_boundary[i] !=
            dealii::numbers::internal_face_boundary_id)
          on_boundary[model.node_vertex[i]] =
            on_boundary[model.node_vertex[i - i % 3 + (i + 1) % 3]] = true;
      for (unsigned int v = 0; v < recovered.n_vertices(); ++v)
        if (perturbation == 0. || on_boundary[v])
          {
            const Stress2 s = recovered.vertex_value(v);
            EXPECT_NEAR(s.xx, sigma.xx, 1e-8 * sigma.xx) << "vertex " << v;
            EXPECT_NEAR(s.yy, sigma.yy, 1e-8 * sigma.xx) << "vertex " << v;
            EXPECT_NEAR(s.xy, sigma.xy, 1e-8 * sigma.xx) << "vertex " << v;
          }
      if (perturbation == 0.)
        for (unsigned int e = 0; e < model.n_elements; ++e)
          {
            const double  lambda[3] = {0.2, 0.3, 0.5};
            const Stress2 s         = recovered.value(e, lambda);
            EXPECT_NEAR(s.xx, sigma.xx, 1e-8 * sigma.xx);
            EXPECT_NEAR(s.yy, sigma.yy, 1e-8 * sigma.xx);
            EXPECT_NEAR(s.xy, sigma.xy, 1e-8 * sigma.xx);
          }
    }
}

// Patches that cannot determine a polynomial fall back, without NaNs: a
// square of two triangles (two centroids for every vertex) gives the mean
// of the two stresses everywhere (degree 0).
TEST(StressRecovery, UndeterminedPatchFallsBackToTheMean)
{
  dealii::Triangulation<2> triangulation;
  dealii::GridGenerator::subdivided_hyper_rectangle_with_simplices(
    triangulation,
    {1, 1},
    dealii::Point<2>(0., 0.),
    dealii::Point<2>(1., 1.));
  dealii::FE_SimplexDGP<2> fe(1);
  dealii::DoFHandler<2>    dof_handler(triangulation);
  dof_handler.distribute_dofs(fe);
  DiscreteModel model;
  model.build(dof_handler);
  ASSERT_EQ(model.n_elements, 2u);
  const double s[2][3] = {{1e6, -2e6, 3e5}, {3e6, 4e6, -1e5}};
  for (unsigned int e = 0; e < 2; ++e)
    for (unsigned int c = 0; c < 3; ++c)
      model.stress[3 * e + c] = s[e][c];
  const RecoveredStress recovered(model, {});
  for (unsigned int v = 0; v < recovered.n_vertices(); ++v)
    EXPECT_EQ(recovered.degree(v), 0u);
  const double lambda[3] = {0.6, 0.3, 0.1};
  for (unsigned int e = 0; e < 2; ++e)
    {
      const Stress2 r = recovered.value(e, lambda);
      EXPECT_NEAR(r.xx, 2e6, 1e-6);
      EXPECT_NEAR(r.yy, 1e6, 1e-6);
      EXPECT_NEAR(r.xy, 1e5, 1e-6);
    }
}
