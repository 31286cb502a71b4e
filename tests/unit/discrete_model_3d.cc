// Unit tests of the exploded tetrahedral mesh of the discrete layer in 3D
// (DiscreteModel::build on a DoFHandler<3>): nodes owned per tetrahedron in
// the DoF numbering of FE_SimplexDGP(1), a joint on every interior
// triangular face with its node pairs coinciding and its face oriented out
// of element A, volumes, inverse bases, boundary ids, cracks.

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_simplex_p.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <cmath>
#include <gtest/gtest.h>
#include <map>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/vertex_continuity.h>

using namespace dealii;
using namespace tmfdem;
using namespace tmfdem::discrete;

namespace
{
  /** A box [0, 2] x [0, 1] x [0, 1.5] of 2 x 2 x 3 hexahedra, each split
   *  into tetrahedra, boundary ids 0-5 by face (colorize). */
  void
  tetrahedral_box(Triangulation<3> &triangulation)
  {
    Triangulation<3> hexahedra;
    GridGenerator::subdivided_hyper_rectangle(hexahedra,
                                              {2, 2, 3},
                                              Point<3>(0., 0., 0.),
                                              Point<3>(2., 1., 1.5),
                                              true);
    GridGenerator::convert_hypercube_to_simplex_mesh(hexahedra, triangulation);
  }
} // namespace

// Every tetrahedron owns its four nodes at its vertices; the volumes sum to
// the box's 3 m^3; F_i^-1 is the inverse of the reference basis; every
// interior face carries one joint whose three node pairs coincide, whose
// face (a1 - a0) x (a2 - a0) points from A into B, and which both elements
// list on the face they share; boundary faces keep the box's ids.
TEST(DiscreteModel3D, ExplodedTetrahedraWithAJointOnEveryInteriorFace)
{
  Triangulation<3> triangulation;
  tetrahedral_box(triangulation);
  const FE_SimplexDGP<3> fe(1);
  DoFHandler<3>          dof_handler(triangulation);
  dof_handler.distribute_dofs(fe);
  DiscreteModel m;
  m.build(dof_handler);

  EXPECT_EQ(m.dim, 3u);
  EXPECT_EQ(m.n_elements, triangulation.n_active_cells());
  EXPECT_EQ(m.n_nodes, 4 * m.n_elements);
  unsigned int interior_faces = 0, boundary_faces = 0;
  for (const auto &cell : triangulation.active_cell_iterators())
    for (const auto f : cell->face_indices())
      (cell->face(f)->at_boundary() ? boundary_faces : interior_faces) += 1;
  EXPECT_EQ(m.n_joints, interior_faces / 2);
  EXPECT_EQ(m.joint_damage.size(), 3 * m.n_joints);

  double volume = 0.;
  for (unsigned int e = 0; e < m.n_elements; ++e)
    {
      volume += m.reference_area[e];
      EXPECT_GT(m.reference_area[e], 0.);
      // F_i^-1 B = I
      for (unsigned int i = 0; i < 3; ++i)
        for (unsigned int k = 0; k < 3; ++k)
          {
            double sum = 0.;
            for (unsigned int l = 0; l < 3; ++l)
              {
                const std::vector<double> &c =
                  l == 0 ? m.x_ref : (l == 1 ? m.y_ref : m.z_ref);
                sum += m.inverse_basis[9 * e + 3 * i + l] *
                       (c[4 * e + k + 1] - c[4 * e]);
              }
            EXPECT_NEAR(sum, i == k ? 1. : 0., 1e-12);
          }
    }
  EXPECT_NEAR(volume, 3., 1e-12);

  std::map<types::boundary_id, unsigned int> ids;
  for (unsigned int e = 0; e < m.n_elements; ++e)
    for (unsigned int f = 0; f < 4; ++f)
      {
        const int code = m.edge_joint[4 * e + f];
        if (code < 0)
          {
            ++ids[m.edge_boundary[4 * e + f]];
            continue;
          }
        const unsigned int j = code / 2;
        EXPECT_EQ(m.joint_elements[2 * j + code % 2], e);
      }
  EXPECT_EQ(ids.size(), 6u);
  unsigned int n_boundary = 0;
  for (const auto &[id, n] : ids)
    {
      EXPECT_LT(id, 6u);
      n_boundary += n;
    }
  EXPECT_EQ(n_boundary, boundary_faces);

  double joint_area = 0.;
  for (unsigned int j = 0; j < m.n_joints; ++j)
    {
      const unsigned int *p  = &m.joint_nodes[6 * j];
      const unsigned int  ea = m.joint_elements[2 * j];
      const unsigned int  eb = m.joint_elements[2 * j + 1];
      double centre_a[3] = {}, centre_b[3] = {}, a0[3], e1[3], e2[3];
      for (unsigned int i = 0; i < 3; ++i)
        {
          const std::vector<double> &c =
            i == 0 ? m.x_ref : (i == 1 ? m.y_ref : m.z_ref);
          for (unsigned int k = 0; k < 3; ++k)
            {
              EXPECT_EQ(c[p[k]], c[p[3 + k]]);
              EXPECT_EQ(p[k] / 4, ea);
              EXPECT_EQ(p[3 + k] / 4, eb);
            }
          for (unsigned int k = 0; k < 4; ++k)
            {
              centre_a[i] += 0.25 * c[4 * ea + k];
              centre_b[i] += 0.25 * c[4 * eb + k];
            }
          a0[i] = c[p[0]];
          e1[i] = c[p[1]] - c[p[0]];
          e2[i] = c[p[2]] - c[p[0]];
        }
      const double n[3]   = {e1[1] * e2[2] - e1[2] * e2[1],
                             e1[2] * e2[0] - e1[0] * e2[2],
                             e1[0] * e2[1] - e1[1] * e2[0]};
      double       into_b = 0., out_of_a = 0.;
      for (unsigned int i = 0; i < 3; ++i)
        {
          into_b += n[i] * (centre_b[i] - a0[i]);
          out_of_a += n[i] * (a0[i] - centre_a[i]);
        }
      EXPECT_GT(into_b, 0.);
      EXPECT_GT(out_of_a, 0.);
      EXPECT_NEAR(m.joint_area[j], 0.5 * std::hypot(n[0], n[1], n[2]), 1e-14);
      EXPECT_GT(m.joint_length[j], 0.);
      joint_area += m.joint_area[j];
    }
  // the joints' area is the interior faces' area: the cells' total face
  // area less the box's 13 m^2 of surface, halved
  double total = 0.;
  for (const auto &cell : triangulation.active_cell_iterators())
    for (const auto f : cell->face_indices())
      total += cell->face(f)->measure();
  EXPECT_NEAR(joint_area, 0.5 * (total - 13.), 1e-11);

  // nothing broken or damaged yet; one broken joint is one crack
  EXPECT_EQ(m.n_broken_joints(), 0u);
  EXPECT_EQ(m.n_damaged_joints(), 0u);
  m.joint_status[0] = JointStatus::mode_I;
  m.joint_damage[2] = 1.;
  EXPECT_EQ(m.n_broken_joints(), 1u);
  EXPECT_EQ(m.n_damaged_joints(), 1u);
  EXPECT_EQ(m.n_cracks(), 1u);
  // an intact neighbour across every joined face
  const unsigned int ea = m.joint_elements[2], eb = m.joint_elements[3];
  EXPECT_TRUE(m.joined(ea, eb));
  EXPECT_FALSE(m.joined(m.joint_elements[0], m.joint_elements[1]));
}

// In an intact box every two tetrahedra that share a vertex or an edge are
// one piece of material around it, and face neighbours are left to their
// joint. Breaking every joint in the plane x = 1 parts the stars of the
// vertices on that plane: pairs with a tetrahedron on each side are no
// longer continuous, pairs on one side still are.
TEST(VertexContinuity, ACrackPartsTheStarsOfItsVertices)
{
  Triangulation<3> triangulation;
  tetrahedral_box(triangulation);
  const FE_SimplexDGP<3> fe(1);
  DoFHandler<3>          dof_handler(triangulation);
  dof_handler.distribute_dofs(fe);
  DiscreteModel m;
  m.build(dof_handler);

  const auto shared_vertices = [&](const unsigned int a, const unsigned int b) {
    unsigned int shared = 0;
    for (unsigned int k = 0; k < 4; ++k)
      for (unsigned int l = 0; l < 4; ++l)
        shared += m.node_vertex[4 * a + k] == m.node_vertex[4 * b + l];
    return shared;
  };
  const auto side = [&](const unsigned int e) {
    double x = 0.;
    for (unsigned int k = 0; k < 4; ++k)
      x += 0.25 * m.x_ref[4 * e + k];
    return x < 1.;
  };

  VertexContinuity continuity;
  continuity.update(m);
  unsigned int vertex_pairs = 0;
  for (unsigned int a = 0; a < m.n_elements; ++a)
    for (unsigned int b = a + 1; b < m.n_elements; ++b)
      {
        const unsigned int shared = shared_vertices(a, b);
        EXPECT_EQ(continuity.continuous(a, b), shared == 1 || shared == 2)
          << a << " " << b;
        vertex_pairs += shared == 1 || shared == 2;
      }
  EXPECT_GT(vertex_pairs, m.n_elements);

  unsigned int broken = 0;
  for (unsigned int j = 0; j < m.n_joints; ++j)
    {
      bool on_plane = true;
      for (unsigned int i = 0; i < 3; ++i)
        on_plane =
          on_plane && std::abs(m.x_ref[m.joint_nodes[6 * j + i]] - 1.) < 1e-12;
      if (on_plane)
        {
          m.joint_status[j] = JointStatus::mode_I;
          ++broken;
        }
    }
  EXPECT_GT(broken, 0u);
  continuity.update(m);
  unsigned int parted = 0;
  for (unsigned int a = 0; a < m.n_elements; ++a)
    for (unsigned int b = a + 1; b < m.n_elements; ++b)
      {
        const unsigned int shared      = shared_vertices(a, b);
        const bool         vertex_pair = shared == 1 || shared == 2;
        EXPECT_EQ(continuity.continuous(a, b),
                  vertex_pair && side(a) == side(b))
          << a << " " << b;
        parted += vertex_pair && side(a) != side(b);
      }
  EXPECT_GT(parted, 0u);
}
