// The Hilbert-curve numbering of the discrete layer's triangles and
// tetrahedra (mesh/cell_order.h): every cell keeps its vertices (in their
// order), its material and its boundary faces; contiguous index ranges, which
// is what an MPI rank owns, are compact regions; and the random joint strengths
// follow the mesh, not the numbering.

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
  /** A box [0, 1]^dim of n^dim cells split into simplices (boundary ids
   *  0 .. 2 dim - 1 by the face's side, material 1 where x < 1/2), its
   *  cells in a random order: a mesh generator's numbering at its worst. */
  template <int dim>
  void
  shuffled_box(const unsigned int n, Triangulation<dim> &triangulation)
  {
    Triangulation<dim> ordered;
    GridGenerator::subdivided_hyper_rectangle_with_simplices(
      ordered,
      std::vector<unsigned int>(dim, n),
      Point<dim>(),
      dim == 2 ? Point<dim>(1., 1.) : Point<dim>(1., 1., 1.));

    std::vector<CellData<dim>> cells;
    SubCellData                faces;
    for (const auto &cell : ordered.active_cell_iterators())
      {
        CellData<dim> data(dim + 1);
        for (unsigned int k = 0; k <= dim; ++k)
          data.vertices[k] = cell->vertex_index(k);
        data.material_id = cell->center()[0] < 0.5 ? 1 : 0;
        cells.push_back(data);
        for (const auto &face : cell->face_iterators())
          if (face->at_boundary())
            {
              CellData<dim - 1> entry(dim);
              for (unsigned int k = 0; k < dim; ++k)
                entry.vertices[k] = face->vertex_index(k);
              const Point<dim> m = face->center();
              for (unsigned int d = 0; d < dim; ++d)
                if (m[d] < 1e-12 || m[d] > 1. - 1e-12)
                  entry.boundary_id = 2 * d + (m[d] > 0.5);
              if constexpr (dim == 2)
                faces.boundary_lines.push_back(entry);
              else
                faces.boundary_quads.push_back(entry);
            }
      }
    std::mt19937 engine(7);
    std::shuffle(cells.begin(), cells.end(), engine);
    triangulation.create_triangulation(ordered.get_vertices(), cells, faces);
  }

  /** Interior faces whose two cells lie in different ranges when the cells
   *  are split into @p n_parts contiguous ranges of nearly equal size. */
  template <int dim>
  unsigned int
  faces_cut(const Triangulation<dim> &triangulation, const unsigned int n_parts)
  {
    const unsigned int n    = triangulation.n_active_cells();
    auto               part = [&](const unsigned int c) {
      return static_cast<unsigned int>(std::uint64_t(c) * n_parts / n);
    };
    unsigned int cut = 0;
    for (const auto &cell : triangulation.active_cell_iterators())
      for (unsigned int f = 0; f < cell->n_faces(); ++f)
        if (!cell->at_boundary(f) &&
            part(cell->active_cell_index()) !=
              part(cell->neighbor(f)->active_cell_index()))
          ++cut;
    return cut / 2;
  }

  /** Vertex coordinates (in the cell's order) and material of a cell. */
  template <int dim>
  std::vector<double>
  cell_signature(const typename Triangulation<dim>::active_cell_iterator &cell)
  {
    std::vector<double> signature;
    for (unsigned int k = 0; k <= dim; ++k)
      for (unsigned int d = 0; d < dim; ++d)
        signature.push_back(cell->vertex(k)[d]);
    signature.push_back(cell->material_id());
    return signature;
  }

  template <int dim>
  std::map<std::vector<double>, unsigned int>
  boundary_ids_by_midpoint(const Triangulation<dim> &triangulation)
  {
    std::map<std::vector<double>, unsigned int> ids;
    for (const auto &cell : triangulation.active_cell_iterators())
      for (const auto &face : cell->face_iterators())
        if (face->at_boundary())
          {
            const Point<dim> m = face->center();
            ids[std::vector<double>(m.begin_raw(), m.end_raw())] =
              face->boundary_id();
          }
    return ids;
  }

  /**
   * Renumbers a shuffled box of n^dim cells and checks that every cell
   * keeps its vertices and material, every boundary face its id, and that
   * P contiguous ranges cut few faces. The bound is from the geometry,
   * fixed before any run: P compact parts of the box have interfaces of
   * about dim P^(1/dim) / 2 planes across the box, each crossing
   * n^(dim-1) squares of the box's cells, each square s simplex faces
   * (s = 1 in 2D, 2 in 3D); allow four times that. The shuffled numbering
   * fails it.
   */
  template <int dim>
  void
  check_renumbering(const unsigned int n)
  {
    Triangulation<dim> triangulation;
    shuffled_box<dim>(n, triangulation);
    const unsigned int               n_cells = triangulation.n_active_cells();
    std::vector<std::vector<double>> before(n_cells);
    for (const auto &cell : triangulation.active_cell_iterators())
      before[cell->active_cell_index()] = cell_signature<dim>(cell);
    const auto boundary_before = boundary_ids_by_midpoint(triangulation);

    const unsigned int        parts[] = {2, 3, 4, 8};
    std::vector<unsigned int> shuffled_cut;
    for (const unsigned int n_parts : parts)
      shuffled_cut.push_back(faces_cut(triangulation, n_parts));

    const std::vector<unsigned int> previous =
      order_cells_along_hilbert_curve(triangulation);

    ASSERT_EQ(triangulation.n_active_cells(), n_cells);
    ASSERT_EQ(previous.size(), n_cells);
    std::vector<unsigned int> sorted = previous;
    std::sort(sorted.begin(), sorted.end());
    for (unsigned int c = 0; c < n_cells; ++c)
      ASSERT_EQ(sorted[c], c) << "not a permutation";
    for (const auto &cell : triangulation.active_cell_iterators())
      EXPECT_EQ(cell_signature<dim>(cell),
                before[previous[cell->active_cell_index()]])
        << "cell " << cell->active_cell_index();
    EXPECT_EQ(boundary_ids_by_midpoint(triangulation), boundary_before);

    // simplex faces per cell face of the box's cells
    const double faces_per_square = dim == 2 ? 1. : 2.;
    for (unsigned int i = 0; i < 4; ++i)
      {
        const double bound = 4. * dim * std::pow(double(parts[i]), 1. / dim) *
                             faces_per_square * std::pow(n, dim - 1) / 2.;
        const unsigned int cut = faces_cut(triangulation, parts[i]);
        EXPECT_LE(cut, bound) << parts[i] << " ranges";
        // the shuffled numbering fails the same bound: the check can fail
        EXPECT_GT(shuffled_cut[i], bound) << parts[i] << " ranges, shuffled";
      }
  }
} // namespace

TEST(CellOrder, KeepsEveryCellAndMakesCompactRanges)
{
  check_renumbering<2>(48); // 4608 triangles
}

TEST(CellOrder, KeepsEveryTetrahedronAndMakesCompactRanges)
{
  check_renumbering<3>(12);
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
      shuffled_box<2>(12, triangulation);
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
