// Continuum <-> discrete temperature transfer on one triangle mesh: a
// continuous P1 field survives interpolation to the exploded mesh and
// averaging back exactly, and the node numbering of the discrete layer is
// the DoF numbering of FE_SimplexDGP(1).

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <cmath>
#include <gtest/gtest.h>
#include <tmfdem/base/parameters.h>
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
  auto      &m                              = parameters.materials.materials[0];
  m.anisotropic_conductivity                = true;
  m.conductivity_along                      = 4.;
  m.conductivity_across                     = 1.;
  m.conductivity_direction                  = 30.;
  parameters.discrete_heat.time_integration = "explicit";
  parameters.discrete_heat.contact_conductance = 0.;

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
