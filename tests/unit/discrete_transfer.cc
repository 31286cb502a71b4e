// Continuum <-> discrete temperature transfer on one triangle mesh: a
// continuous P1 field survives interpolation to the exploded mesh and
// averaging back exactly, and the node numbering of the discrete layer is
// the DoF numbering of FE_SimplexDGP(1).

#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/full_matrix.h>

#include <cmath>
#include <gtest/gtest.h>
#include <tmfdem/base/parameters.h>
#include <tmfdem/coupling/continuum_temperature_source.h>
#include <tmfdem/discrete/discrete_heat.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/discrete_parameters.h>

using namespace dealii;
using namespace tmfdem;

TEST(DiscreteTransfer, VertexFieldRoundTripAndDoFNumbering)
{
  Triangulation<2> triangulation;
  GridGenerator::subdivided_hyper_rectangle_with_simplices(triangulation,
                                                           {4, 3},
                                                           Point<2>(0., 0.),
                                                           Point<2>(2., 1.));
  FE_SimplexDGP<2> fe(1);
  DoFHandler<2>    dof_handler(triangulation);
  dof_handler.distribute_dofs(fe);
  discrete::DiscreteModel model;
  model.build(dof_handler);
  EXPECT_EQ(model.n_nodes, 3 * triangulation.n_active_cells());
  // every interior edge carries a joint: E_interior = (3 N_cells - E_boundary)
  // / 2
  EXPECT_EQ(model.n_joints,
            (3 * triangulation.n_active_cells() - 2 * (4 + 3)) / 2);

  Parameters             parameters;
  discrete::DiscreteHeat heat(parameters, model);
  std::vector<double>    vertex_values(triangulation.n_vertices());
  for (unsigned int v = 0; v < triangulation.n_vertices(); ++v)
    vertex_values[v] = 3. + triangulation.get_vertices()[v][0] -
                       2. * triangulation.get_vertices()[v][1];
  heat.interpolate_from_vertices(vertex_values);
  for (unsigned int n = 0; n < model.n_nodes; ++n)
    EXPECT_DOUBLE_EQ(heat.temperature()[n],
                     3. + model.x_ref[n] - 2. * model.y_ref[n]);
  const std::vector<double> back = heat.average_to_vertices();
  for (unsigned int v = 0; v < triangulation.n_vertices(); ++v)
    EXPECT_NEAR(back[v], vertex_values[v], 1e-14);
}

// The continuum -> discrete transfer: the L2 projection of a FE_SimplexP
// field onto the linear field of the triangle. Degree 1: the identity (the
// nodes take the vertex values). Degree 2: the projection of a quadratic
// keeps its mean and first moments (checked on the reference triangle with
// a rule exact for cubics) and reproduces linear fields at the vertices.
TEST(DiscreteTransfer, ContinuumProjectionToLinear)
{
  const FullMatrix<double> p1 =
    coupling::ContinuumTemperatureSource::projection_to_linear(1);
  for (unsigned int i = 0; i < 3; ++i)
    for (unsigned int j = 0; j < 3; ++j)
      EXPECT_NEAR(p1(i, j), i == j ? 1. : 0., 1e-14);

  const FullMatrix<double> p2 =
    coupling::ContinuumTemperatureSource::projection_to_linear(2);
  ASSERT_EQ(p2.n(), 6u);
  const FE_SimplexP<2> quadratic(2), linear(1);
  const auto           f = [](const Point<2> &p) {
    return 1. + 2. * p[0] - 3. * p[1] + 5. * p[0] * p[0] - 4. * p[0] * p[1] +
           7. * p[1] * p[1];
  };
  Vector<double> values(6), vertex(3);
  for (unsigned int j = 0; j < 6; ++j)
    values[j] = f(quadratic.get_unit_support_points()[j]);
  p2.vmult(vertex, values);
  const QGaussSimplex<2> rule(3);
  double mean = 0., mean_p = 0., mx = 0., mx_p = 0., my = 0., my_p = 0.;
  for (unsigned int q = 0; q < rule.size(); ++q)
    {
      const Point<2> &p = rule.point(q);
      double          g = 0.;
      for (unsigned int k = 0; k < 3; ++k)
        g += vertex[k] * linear.shape_value(k, p);
      mean += rule.weight(q) * f(p);
      mean_p += rule.weight(q) * g;
      mx += rule.weight(q) * f(p) * p[0];
      mx_p += rule.weight(q) * g * p[0];
      my += rule.weight(q) * f(p) * p[1];
      my_p += rule.weight(q) * g * p[1];
    }
  EXPECT_NEAR(mean_p, mean, 1e-13);
  EXPECT_NEAR(mx_p, mx, 1e-13);
  EXPECT_NEAR(my_p, my, 1e-13);
  for (unsigned int j = 0; j < 6; ++j)
    values[j] = 3. + quadratic.get_unit_support_points()[j][0] -
                2. * quadratic.get_unit_support_points()[j][1];
  p2.vmult(vertex, values);
  for (unsigned int k = 0; k < 3; ++k)
    EXPECT_NEAR(vertex[k],
                3. + linear.get_unit_support_points()[k][0] -
                  2. * linear.get_unit_support_points()[k][1],
                1e-13);
}

// Anisotropic conduction in the discrete layer is objective: the tensor is
// given in the reference configuration and turns with each triangle, so a
// rigidly rotated copy of a plate with the same nodal temperatures gets the
// same explicit temperature increments (joints use the reference n.D.n).
// With the tensor held fixed in space the increments would differ by O(1).
TEST(DiscreteHeatAnisotropy, RigidRotationGivesTheSameIncrements)
{
  Triangulation<2> triangulation;
  GridGenerator::subdivided_hyper_rectangle_with_simplices(triangulation,
                                                           {4, 3},
                                                           Point<2>(0., 0.),
                                                           Point<2>(2., 1.));
  FE_SimplexDGP<2> fe(1);
  DoFHandler<2>    dof_handler(triangulation);
  dof_handler.distribute_dofs(fe);

  Parameters parameters;
  auto      &m               = parameters.materials.materials[0];
  m.anisotropic_conductivity = true;
  m.conductivity_along       = 4.;
  m.conductivity_across      = 1.;
  m.conductivity_direction   = 30.;
  parameters.get<DiscreteHeatParameters>().time_integration =
    DiscreteHeatParameters::TimeIntegration::explicit_euler;
  parameters.get<DiscreteHeatParameters>().contact_conductance = 0.;

  std::vector<double> increments[2];
  for (unsigned int rotated = 0; rotated < 2; ++rotated)
    {
      discrete::DiscreteModel model;
      model.build(dof_handler);
      const double phi = rotated ? 0.7 : 0.;
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        {
          model.x[n] =
            std::cos(phi) * model.x_ref[n] - std::sin(phi) * model.y_ref[n];
          model.y[n] =
            std::sin(phi) * model.x_ref[n] + std::cos(phi) * model.y_ref[n];
        }
      discrete::DiscreteHeat heat(parameters, model);
      heat.initialise(0.);
      // a field that differs from node to node (joints conduct too)
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        heat.temperature()[n] = 10. * model.x_ref[n] * model.x_ref[n] +
                                3. * model.y_ref[n] + 0.1 * (n % 3);
      const Vector<double> before = heat.temperature();
      heat.step(0., 0.5 * heat.stable_time_step());
      for (unsigned int n = 0; n < model.n_nodes; ++n)
        increments[rotated].push_back(heat.temperature()[n] - before[n]);
    }
  double largest = 0.;
  for (const double d : increments[0])
    largest = std::max(largest, std::abs(d));
  ASSERT_GT(largest, 1e-3);
  for (unsigned int n = 0; n < increments[0].size(); ++n)
    EXPECT_NEAR(increments[1][n], increments[0][n], 1e-12 * largest);
}
