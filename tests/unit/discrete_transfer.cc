// Continuum <-> discrete temperature transfer on one triangle mesh: a
// continuous P1 field survives interpolation to the exploded mesh and
// averaging back exactly, and the node numbering of the discrete layer is
// the DoF numbering of FE_SimplexDGP(1).

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

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
