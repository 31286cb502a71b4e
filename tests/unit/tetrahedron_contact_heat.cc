// Unit tests of the contact heat between tetrahedra
// (include/tmfdem/discrete/tetrahedron_contact_heat.h): the contact area of
// a pressed slab is the area of its section, G lies on it, isothermal
// tetrahedra exchange h_c A dT with nodal heats that sum to exactly zero, a
// temperature field continuous across the contact drives nothing, the
// result does not depend on which tetrahedron comes first, pairs that only
// touch or are apart exchange nothing, and the paper literal form is the
// closed form h_c V (grad T_0 + grad T_1) . n_0.

#include <cmath>
#include <gtest/gtest.h>
#include <tmfdem/discrete/tetrahedron_contact_heat.h>

using namespace tmfdem::discrete;

namespace
{
  /** Every face of both free (a boundary face or a broken joint's). */
  const unsigned char all_free[2] = {0xF, 0xF};

  /** The contactor: its face (0,0), (1,0), (0,1) at z = -depth (area 0.5
   *  m^2), the apex above; the target: a large tetrahedron whose top face
   *  z = 0 covers that face, its apex below. They overlap in a slab of
   *  thickness depth under z = 0. */
  void
  pressed_pair(const double depth, double (&x)[2][4][3])
  {
    const double c[4][3] = {{0., 0., -depth},
                            {1., 0., -depth},
                            {0., 1., -depth},
                            {0.2, 0.2, 1.}};
    const double t[4][3] = {{-1., -1., 0.},
                            {3., -1., 0.},
                            {0.3, 0.3, -3.},
                            {-1., 3., 0.}};
    for (unsigned int k = 0; k < 4; ++k)
      for (unsigned int i = 0; i < 3; ++i)
        {
          x[0][k][i] = c[k][i];
          x[1][k][i] = t[k][i];
        }
    for (unsigned int side = 0; side < 2; ++side)
      {
        TetrahedronCoordinates check;
        if (!check.set(x[side]))
          for (unsigned int i = 0; i < 3; ++i)
            std::swap(x[side][1][i], x[side][2][i]);
      }
  }

  void
  swap_sides(double (&x)[2][4][3])
  {
    for (unsigned int k = 0; k < 4; ++k)
      for (unsigned int i = 0; i < 3; ++i)
        std::swap(x[0][k][i], x[1][k][i]);
  }

  /** The point with barycentric coordinates @p N in tetrahedron @p t. */
  std::array<double, 3>
  point_of(const double (&t)[4][3], const std::array<double, 4> &N)
  {
    std::array<double, 3> p{{0., 0., 0.}};
    for (unsigned int k = 0; k < 4; ++k)
      for (unsigned int i = 0; i < 3; ++i)
        p[i] += N[k] * t[k][i];
    return p;
  }
} // namespace

TEST(TetrahedronContactHeat, PressedSlabHasTheFaceArea)
{
  // A_c: the vector area of the target's top face inside the contactor,
  // the contactor's section at z = 0, 0.5 (1 - d / H)^2 m^2 (H = 1 + d the
  // apex's height over the pressed face), and minus that of the
  // contactor's surface inside the target (its pressed face and the slab's
  // slanted sides)
  const double d = 1e-6, H = 1. + d;
  double       x[2][4][3];
  pressed_pair(d, x);
  TetrahedronContactInterface interface;
  ASSERT_TRUE(tetrahedron_contact_interface(x, all_free, false, interface));
  EXPECT_NEAR(interface.area, 0.5 * std::pow(1. - d / H, 2), 1e-13);
  // G: the centroid of the pressed face, in both tetrahedra
  for (unsigned int side = 0; side < 2; ++side)
    {
      const auto G = point_of(x[side], interface.shape[side]);
      EXPECT_NEAR(G[0], 1. / 3., 1e-5);
      EXPECT_NEAR(G[1], 1. / 3., 1e-5);
      EXPECT_NEAR(G[2], 0., 1e-5);
    }
}

TEST(TetrahedronContactHeat, IsothermalPairExchangesConductanceTimesJump)
{
  double x[2][4][3];
  pressed_pair(1e-6, x);
  TetrahedronContactInterface interface;
  ASSERT_TRUE(tetrahedron_contact_interface(x, all_free, false, interface));
  const double           T0[4] = {10., 10., 10., 10.};
  const double           T1[4] = {30., 30., 30., 30.};
  const double           h_c   = 250.;
  TetrahedronContactHeat transfer;
  tetrahedron_contact_heat(ContactHeatModel::temperature_difference,
                           interface,
                           T0,
                           T1,
                           h_c,
                           transfer);
  EXPECT_DOUBLE_EQ(transfer.conductance, h_c * interface.area);
  EXPECT_DOUBLE_EQ(transfer.heat_flow, h_c * interface.area * 20.);
  double sum = 0., into_0 = 0.;
  for (unsigned int k = 0; k < 4; ++k)
    {
      sum += transfer.contactor_nodal_heat[k] + transfer.target_nodal_heat[k];
      into_0 += transfer.contactor_nodal_heat[k];
      EXPECT_NEAR(transfer.contactor_nodal_heat[k],
                  transfer.heat_flow * interface.shape[0][k],
                  1e-14 * transfer.heat_flow);
    }
  EXPECT_EQ(sum, 0.);
  EXPECT_NEAR(into_0, transfer.heat_flow, 1e-14 * transfer.heat_flow);
  // the conductance matrix: rows sum to zero, symmetric
  const auto J = transfer.heat_jacobian();
  for (unsigned int i = 0; i < 8; ++i)
    {
      double row = 0.;
      for (unsigned int j = 0; j < 8; ++j)
        {
          row += J[i][j];
          EXPECT_EQ(J[i][j], J[j][i]);
        }
      EXPECT_NEAR(row, 0., 1e-12 * transfer.conductance);
    }
}

TEST(TetrahedronContactHeat, ContinuousFieldDrivesNothing)
{
  double x[2][4][3];
  pressed_pair(1e-4, x);
  TetrahedronContactInterface interface;
  ASSERT_TRUE(tetrahedron_contact_interface(x, all_free, false, interface));
  double T[2][4];
  for (unsigned int side = 0; side < 2; ++side)
    for (unsigned int k = 0; k < 4; ++k)
      T[side][k] =
        5. + 2. * x[side][k][0] - 3. * x[side][k][1] + 7. * x[side][k][2];
  TetrahedronContactHeat transfer;
  tetrahedron_contact_heat(ContactHeatModel::temperature_difference,
                           interface,
                           T[0],
                           T[1],
                           100.,
                           transfer);
  EXPECT_NEAR(transfer.heat_flow, 0., 1e-12 * 100. * interface.area * 30.);
}

TEST(TetrahedronContactHeat, OrderOfThePairDoesNotMatter)
{
  double x[2][4][3];
  pressed_pair(1e-3, x);
  const double T0[4] = {10., 12., 9., 11.}, T1[4] = {40., 35., 30., 31.};
  for (const ContactHeatModel model : {ContactHeatModel::temperature_difference,
                                       ContactHeatModel::paper_literal})
    {
      const bool literal = model == ContactHeatModel::paper_literal;
      TetrahedronContactInterface forward, backward;
      ASSERT_TRUE(tetrahedron_contact_interface(x, all_free, literal, forward));
      swap_sides(x);
      ASSERT_TRUE(
        tetrahedron_contact_interface(x, all_free, literal, backward));
      swap_sides(x);
      EXPECT_NEAR(forward.area, backward.area, 1e-13 * forward.area);
      TetrahedronContactHeat a, b;
      tetrahedron_contact_heat(model, forward, T0, T1, 100., a);
      tetrahedron_contact_heat(model, backward, T1, T0, 100., b);
      EXPECT_NEAR(a.heat_flow, -b.heat_flow, 1e-12 * std::abs(a.heat_flow));
      EXPECT_NE(a.heat_flow, 0.);
      for (unsigned int k = 0; k < 4; ++k)
        {
          EXPECT_NEAR(a.contactor_nodal_heat[k],
                      b.target_nodal_heat[k],
                      1e-12 * std::abs(a.heat_flow));
          EXPECT_NEAR(a.target_nodal_heat[k],
                      b.contactor_nodal_heat[k],
                      1e-12 * std::abs(a.heat_flow));
        }
    }
}

TEST(TetrahedronContactHeat, TouchingOrApartExchangesNothing)
{
  for (const double depth : {0., -1e-3})
    {
      double x[2][4][3];
      pressed_pair(depth, x);
      TetrahedronContactInterface interface;
      EXPECT_FALSE(tetrahedron_contact_interface(x, all_free, true, interface));
      EXPECT_EQ(interface.area, 0.);
      const double           T0[4] = {0., 0., 0., 0.};
      const double           T1[4] = {50., 50., 50., 50.};
      TetrahedronContactHeat transfer;
      tetrahedron_contact_heat(ContactHeatModel::temperature_difference,
                               interface,
                               T0,
                               T1,
                               100.,
                               transfer);
      EXPECT_EQ(transfer.heat_flow, 0.);
    }
}

TEST(TetrahedronContactHeat, PaperLiteralIsTheGradientForm)
{
  double x[2][4][3];
  pressed_pair(1e-3, x);
  TetrahedronContactInterface interface;
  ASSERT_TRUE(tetrahedron_contact_interface(x, all_free, true, interface));
  // the overlap: the contactor's slab under z = 0, a frustum of height d
  // over the face of area 0.5 towards the apex at height 1 + d
  const double d = 1e-3, H = 1. + d;
  const double frustum = 0.5 * H / 3. * (1. - std::pow(1. - d / H, 3));
  EXPECT_NEAR(interface.overlap_volume, frustum, 1e-12);
  const double h_c = 100.;
  // isothermal: nothing
  {
    const double           T0[4] = {10., 10., 10., 10.};
    const double           T1[4] = {30., 30., 30., 30.};
    TetrahedronContactHeat transfer;
    tetrahedron_contact_heat(ContactHeatModel::paper_literal,
                             interface,
                             T0,
                             T1,
                             h_c,
                             transfer);
    EXPECT_EQ(transfer.heat_flow, 0.);
  }
  // T = a . x in both: Q = h_c V 2 a . n_0, n_0 between the centroids
  const double a[3] = {2., -3., 7.};
  double       T[2][4], centroid[2][3] = {};
  for (unsigned int side = 0; side < 2; ++side)
    for (unsigned int k = 0; k < 4; ++k)
      {
        T[side][k] =
          a[0] * x[side][k][0] + a[1] * x[side][k][1] + a[2] * x[side][k][2];
        for (unsigned int i = 0; i < 3; ++i)
          centroid[side][i] += 0.25 * x[side][k][i];
      }
  double n[3], length = 0.;
  for (unsigned int i = 0; i < 3; ++i)
    {
      n[i] = centroid[1][i] - centroid[0][i];
      length += n[i] * n[i];
    }
  length = std::sqrt(length);
  const double expected =
    h_c * frustum * 2. * (a[0] * n[0] + a[1] * n[1] + a[2] * n[2]) / length;
  TetrahedronContactHeat transfer;
  tetrahedron_contact_heat(ContactHeatModel::paper_literal,
                           interface,
                           T[0],
                           T[1],
                           h_c,
                           transfer);
  EXPECT_NEAR(transfer.heat_flow, expected, 1e-9 * std::abs(expected));
  EXPECT_EQ(transfer.conductance, 0.);
}

TEST(TetrahedronContactHeat, PressedPairWithParallelEdgesOverlaps)
{
  // the pressed face's edges are parallel to the target's top edges: a
  // zero edge-edge axis must not count as separating (the pair overlaps,
  // its contact force pushes the contactor up, +z)
  double x[2][4][3];
  pressed_pair(1e-3, x);
  TetrahedronCoordinates coordinates[2];
  EXPECT_TRUE(tetrahedra_overlap(x, coordinates));
  const double          v[2][4][3] = {};
  PenaltyCoulombContact law;
  law.normal_penalty = 1e9;
  TetrahedronPairFriction friction;
  double                  force[24] = {};
  add_pair_forces_3d(x, v, law, 1e-6, friction, force);
  double up = 0., total = 0.;
  for (unsigned int k = 0; k < 4; ++k)
    {
      up += force[3 * k + 2];
      total += force[3 * k + 2] + force[12 + 3 * k + 2];
    }
  EXPECT_GT(up, 0.);
  EXPECT_NEAR(total, 0., 1e-9 * up);
}
