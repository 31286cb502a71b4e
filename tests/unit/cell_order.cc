// The Hilbert-curve numbering of the discrete layer's triangles
// (mesh/cell_order.h): every cell keeps its vertices (in their order), its
// material and its boundary edges; contiguous index ranges, which is what an
// MPI rank owns, are compact regions; and the random joint strengths follow
// the mesh, not the numbering.

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <numeric>
#include <random>
#include <tmfdem/base/parameters.h>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/joints.h>
#include <tmfdem/mesh/cell_order.h>

using namespace dealii;
using namespace tmfdem;

namespace
{
  /** A square of n x n cells of two triangles each (boundary ids 0-3,
   *  material 1 in the left half), its cells in a random order: a mesh
   *  generator's numbering at its worst. */
  void
  shuffled_square(const unsigned int n, Triangulation<2> &triangulation)
  {
    Triangulation<2> ordered;
    GridGenerator::subdivided_hyper_rectangle_with_simplices(ordered,
                                                             {n, n},
                                                             Point<2>(0., 0.),
                                                             Point<2>(1., 1.));

    std::vector<CellData<2>> cells;
    SubCellData              edges;
    for (const auto &cell : ordered.active_cell_iterators())
      {
        CellData<2> data(3);
        for (unsigned int k = 0; k < 3; ++k)
          data.vertices[k] = cell->vertex_index(k);
        data.material_id = cell->center()[0] < 0.5 ? 1 : 0;
        cells.push_back(data);
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              CellData<1> edge(2);
              edge.vertices[0] = face->vertex_index(0);
              edge.vertices[1] = face->vertex_index(1);
              const Point<2> m = face->center();
              edge.boundary_id = m[0] < 1e-12      ? 0 :
                                 m[0] > 1. - 1e-12 ? 1 :
                                 m[1] < 1e-12      ? 2 :
                                                     3;
              edges.boundary_lines.push_back(edge);
            }
      }
    std::mt19937 engine(7);
    std::shuffle(cells.begin(), cells.end(), engine);
    triangulation.create_triangulation(ordered.get_vertices(), cells, edges);
  }

  /** Interior edges whose two cells lie in different ranges when the cells
   *  are split into @p n_parts contiguous ranges of nearly equal size. */
  unsigned int
  edges_cut(const Triangulation<2> &triangulation, const unsigned int n_parts)
  {
    const unsigned int n    = triangulation.n_active_cells();
    auto               part = [&](const unsigned int c) {
      return static_cast<unsigned int>(std::uint64_t(c) * n_parts / n);
    };
    unsigned int cut = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      for (unsigned int f = 0; f < 3; ++f)
        if (!cell->at_boundary(f) &&
            part(cell->active_cell_index()) !=
              part(cell->neighbor(f)->active_cell_index()))
          ++cut;
    return cut / 2;
  }

  /** Vertex coordinates (in the cell's order) and material of a cell. */
  std::vector<double>
  cell_signature(const Triangulation<2>::active_cell_iterator &cell)
  {
    std::vector<double> signature;
    for (unsigned int k = 0; k < 3; ++k)
      {
        signature.push_back(cell->vertex(k)[0]);
        signature.push_back(cell->vertex(k)[1]);
      }
    signature.push_back(cell->material_id());
    return signature;
  }

  std::map<std::pair<double, double>, unsigned int>
  boundary_ids_by_midpoint(const Triangulation<2> &triangulation)
  {
    std::map<std::pair<double, double>, unsigned int> ids;
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          ids[{face->center()[0], face->center()[1]}] = face->boundary_id();
    return ids;
  }
} // namespace

TEST(CellOrder, KeepsEveryCellAndMakesCompactRanges)
{
  const unsigned int n = 48; // 4608 triangles
  Triangulation<2>   triangulation;
  shuffled_square(n, triangulation);
  const unsigned int               n_cells = triangulation.n_active_cells();
  std::vector<std::vector<double>> before(n_cells);
  for (const auto &cell : triangulation.active_cell_iterators())
    before[cell->active_cell_index()] = cell_signature(cell);
  const auto boundary_before = boundary_ids_by_midpoint(triangulation);

  // a bound from the geometry, fixed before any run: P compact parts of a
  // square of N triangles (N / 2 cells of side 1 / n) cut about
  // sqrt(P) n edges at best (P = 4: two lines of n cell edges); allow four
  // times that
  std::vector<unsigned int> shuffled_cut;
  for (const unsigned int n_parts : {2u, 3u, 4u, 8u})
    shuffled_cut.push_back(edges_cut(triangulation, n_parts));

  const std::vector<unsigned int> previous =
    order_cells_along_hilbert_curve(triangulation);

  ASSERT_EQ(triangulation.n_active_cells(), n_cells);
  ASSERT_EQ(previous.size(), n_cells);
  std::vector<unsigned int> sorted = previous;
  std::sort(sorted.begin(), sorted.end());
  for (unsigned int c = 0; c < n_cells; ++c)
    ASSERT_EQ(sorted[c], c) << "not a permutation";
  for (const auto &cell : triangulation.active_cell_iterators())
    EXPECT_EQ(cell_signature(cell), before[previous[cell->active_cell_index()]])
      << "cell " << cell->active_cell_index();
  EXPECT_EQ(boundary_ids_by_midpoint(triangulation), boundary_before);

  const unsigned int parts[] = {2, 3, 4, 8};
  for (unsigned int i = 0; i < 4; ++i)
    {
      const double       bound = 4. * std::sqrt(double(parts[i])) * n;
      const unsigned int cut   = edges_cut(triangulation, parts[i]);
      EXPECT_LE(cut, bound) << parts[i] << " ranges";
      // the shuffled numbering fails the same bound: the check can fail
      EXPECT_GT(shuffled_cut[i], bound) << parts[i] << " ranges, shuffled";
    }
}

TEST(CellOrder, RandomJointStrengthsFollowTheMeshNotTheNumbering)
{
  Parameters parameters;
  auto      &dm      = parameters.get<DiscreteMechanicsParameters>();
  dm.heterogeneity   = DiscreteMechanicsParameters::Heterogeneity::weibull;
  dm.weibull_modulus = 5.;

  // strength of each joint by its midpoint, as meshed and renumbered
  std::map<std::pair<double, double>, double> strength[2];
  for (unsigned int renumbered = 0; renumbered < 2; ++renumbered)
    {
      Triangulation<2> triangulation;
      shuffled_square(12, triangulation);
      std::vector<unsigned int> mesh_index;
      if (renumbered)
        mesh_index = order_cells_along_hilbert_curve(triangulation);
      FE_SimplexDGP<2> fe(1);
      DoFHandler<2>    dof_handler(triangulation);
      dof_handler.distribute_dofs(fe);
      discrete::DiscreteModel model;
      model.build(dof_handler);
      if (renumbered)
        model.mesh_index = mesh_index;
      discrete::setup_joint_constants(parameters,
                                      discrete::SofteningLaw::munjiza,
                                      model);
      for (unsigned int j = 0; j < model.n_joints; ++j)
        {
          const unsigned int a0 = model.joint_nodes[4 * j];
          const unsigned int a1 = model.joint_nodes[4 * j + 1];
          strength[renumbered][{0.5 * (model.x_ref[a0] + model.x_ref[a1]),
                                0.5 * (model.y_ref[a0] + model.y_ref[a1])}] =
            model.joint_constants[j].tensile_strength;
        }
      dof_handler.clear();
    }
  ASSERT_EQ(strength[0].size(), strength[1].size());
  unsigned int n_distinct = 0;
  double       first      = strength[0].begin()->second;
  for (const auto &[midpoint, value] : strength[0])
    {
      EXPECT_EQ(value, strength[1].at(midpoint))
        << "joint at (" << midpoint.first << ", " << midpoint.second << ")";
      n_distinct += value != first;
    }
  EXPECT_GT(n_distinct, strength[0].size() / 2) << "no heterogeneity drawn";
}
