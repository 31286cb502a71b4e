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

#include <gtest/gtest.h>
#include <tmfdem/base/parameters.h>
#include <tmfdem/coupling/continuum_temperature_source.h>
#include <tmfdem/discrete/discrete_heat.h>
#include <tmfdem/discrete/discrete_model.h>

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
