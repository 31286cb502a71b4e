// Unit tests of the contact heat kernel (paper Sec. 3.4, Eqs. 28-36, with
// the driving term of physics-notes.md "Heat"): the overlap polygon against
// brute-force grid estimates and exact cases, the contact length of
// face-to-face contacts, exact conservation of the nodal heats, the
// direction of the flow, the isothermal-bodies exchange and the
// linearisation; the paper's literal term (Contact heat model = paper
// literal) against a hand-derived value and under contactor-target swap.

#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <tmfdem/discrete/contact_heat.h>
#include <vector>

using namespace tmfdem::discrete;

namespace
{
  struct Triangle
  {
    double x[3], y[3];
  };

  double
  area_of(const Triangle &t)
  {
    return 0.5 *
           twice_signed_area(t.x[0], t.y[0], t.x[1], t.y[1], t.x[2], t.y[2]);
  }

  /** A random counter-clockwise triangle in [x0, x0 + size]^2 whose area is
   * at least @p min_area_fraction of size^2. */
  Triangle
  random_triangle(std::mt19937_64 &rng,
                  const double     x0,
                  const double     size,
                  const double     min_area_fraction = 0.01)
  {
    std::uniform_real_distribution<double> u(0., 1.);
    while (true)
      {
        Triangle t;
        for (unsigned int k = 0; k < 3; ++k)
          {
            t.x[k] = x0 + size * u(rng);
            t.y[k] = x0 + size * u(rng);
          }
        double a = area_of(t);
        if (a < 0.)
          {
            std::swap(t.x[1], t.x[2]);
            std::swap(t.y[1], t.y[2]);
            a = -a;
          }
        if (a > min_area_fraction * size * size)
          return t;
      }
  }

  bool
  inside(const Triangle &t, const double px, const double py)
  {
    for (unsigned int k = 0; k < 3; ++k)
      if (twice_signed_area(t.x[k],
                            t.y[k],
                            t.x[(k + 1) % 3],
                            t.y[(k + 1) % 3],
                            px,
                            py) < 0.)
        return false;
    return true;
  }

  /** Overlap area and centroid by the midpoint rule on an n x n grid over
   * the bounding box of a. */
  void
  grid_estimate(const Triangle &a,
                const Triangle &b,
                const unsigned  n,
                double         &area,
                double         &gx,
                double         &gy,
                double         &spacing)
  {
    const double xmin = std::min({a.x[0], a.x[1], a.x[2]});
    const double xmax = std::max({a.x[0], a.x[1], a.x[2]});
    const double ymin = std::min({a.y[0], a.y[1], a.y[2]});
    const double ymax = std::max({a.y[0], a.y[1], a.y[2]});
    const double hx = (xmax - xmin) / n, hy = (ymax - ymin) / n;
    double       count = 0., sx = 0., sy = 0.;
    for (unsigned i = 0; i < n; ++i)
      for (unsigned j = 0; j < n; ++j)
        {
          const double px = xmin + (i + 0.5) * hx, py = ymin + (j + 0.5) * hy;
          if (inside(a, px, py) && inside(b, px, py))
            {
              count += 1.;
              sx += px;
              sy += py;
            }
        }
    area    = count * hx * hy;
    gx      = count > 0. ? sx / count : 0.;
    gy      = count > 0. ? sy / count : 0.;
    spacing = std::max(hx, hy);
  }

  double
  sum_of_nodal_heats(const ContactHeatTransfer &transfer)
  {
    return transfer.contactor_nodal_heat[0] + transfer.contactor_nodal_heat[1] +
           transfer.contactor_nodal_heat[2] + transfer.target_nodal_heat[0] +
           transfer.target_nodal_heat[1] + transfer.target_nodal_heat[2];
  }
} // namespace

TEST(ContactHeat, OverlapOfATriangleWithItselfIsTheTriangle)
{
  const Triangle t{{0.1, 1.3, 0.4}, {-0.2, 0.1, 0.9}};
  OverlapPolygon overlap;
  ASSERT_TRUE(triangle_overlap(t.x, t.y, t.x, t.y, overlap));
  EXPECT_EQ(overlap.n_vertices, 3u);
  EXPECT_NEAR(overlap.area, area_of(t), 1e-15);
  EXPECT_NEAR(overlap.centroid_x, (0.1 + 1.3 + 0.4) / 3., 1e-15);
  EXPECT_NEAR(overlap.centroid_y, (-0.2 + 0.1 + 0.9) / 3., 1e-15);
  // perimeter of the triangle itself
  EXPECT_NEAR(overlap.perimeter,
              std::hypot(1.2, 0.3) + std::hypot(0.9, 0.8) +
                std::hypot(0.3, 1.1),
              1e-14);
  // all edges on both boundaries: no crossing, no contact length
  for (unsigned int i = 0; i < overlap.n_vertices; ++i)
    EXPECT_EQ(overlap.edge_owner[i], OverlapEdgeOwner::both);
  EXPECT_EQ(overlap.contact_length, 0.);
}

TEST(ContactHeat, NestedTrianglesOverlapInTheSmallerOne)
{
  const Triangle big{{0., 4., 0.}, {0., 0., 4.}};
  const Triangle small{{0.5, 1.5, 0.7}, {0.5, 0.6, 1.8}};
  OverlapPolygon a_in_b, b_in_a;
  ASSERT_TRUE(triangle_overlap(small.x, small.y, big.x, big.y, a_in_b));
  ASSERT_TRUE(triangle_overlap(big.x, big.y, small.x, small.y, b_in_a));
  for (const OverlapPolygon *overlap : {&a_in_b, &b_in_a})
    {
      EXPECT_EQ(overlap->n_vertices, 3u);
      EXPECT_NEAR(overlap->area, area_of(small), 1e-14);
      EXPECT_NEAR(overlap->centroid_x, (0.5 + 1.5 + 0.7) / 3., 1e-14);
      EXPECT_NEAR(overlap->centroid_y, (0.5 + 0.6 + 1.8) / 3., 1e-14);
    }
  // the boundaries do not cross: the chord of the interpenetration is 0
  EXPECT_EQ(a_in_b.contact_length, 0.);
  EXPECT_EQ(b_in_a.contact_length, 0.);
  // nested with a shared vertex and two collinear edges
  const Triangle corner{{0., 1., 0.}, {0., 0., 1.}};
  ASSERT_TRUE(triangle_overlap(corner.x, corner.y, big.x, big.y, a_in_b));
  ASSERT_TRUE(triangle_overlap(big.x, big.y, corner.x, corner.y, b_in_a));
  EXPECT_NEAR(a_in_b.area, 0.5, 1e-15);
  EXPECT_NEAR(b_in_a.area, 0.5, 1e-15);
  EXPECT_NEAR(b_in_a.centroid_x, 1. / 3., 1e-15);
  EXPECT_NEAR(b_in_a.centroid_y, 1. / 3., 1e-15);
  EXPECT_EQ(a_in_b.contact_length, 0.);
  EXPECT_EQ(b_in_a.contact_length, 0.);
}

TEST(ContactHeat, DisjointAndTouchingTrianglesDoNotOverlap)
{
  const Triangle a{{0., 1., 0.}, {0., 0., 1.}};
  // candidates that share no area with a
  const std::vector<Triangle> others = {
    {{2., 3., 2.}, {2., 2., 3.}},      // disjoint, boxes apart
    {{0.6, 1.5, 1.5}, {0.6, 0.2, 1.}}, // disjoint, boxes overlap
    {{1., 1., 0.}, {0., 1., 1.}},      // exploded-mesh neighbour: shared edge
    {{1., 2., 1.}, {0., 0., 1.}},      // touching at a vertex
    {{0.5, 2., 0.5}, {0., 0., -1.}},   // collinear edges sharing a segment
    {{0.5, 1., 1.}, {0.5, 0.2, 1.}},   // vertex on a's hypotenuse
    {{0., 1., 0.}, {0., 0., 0.}},      // degenerate (zero area)
    {{0., 0., 1.}, {0., 1., 0.}},      // clockwise
  };
  for (const Triangle &b : others)
    for (const bool swapped : {false, true})
      {
        OverlapPolygon overlap;
        const bool     overlapping =
          swapped ? triangle_overlap(b.x, b.y, a.x, a.y, overlap) :
                        triangle_overlap(a.x, a.y, b.x, b.y, overlap);
        EXPECT_FALSE(overlapping);
        EXPECT_EQ(overlap.n_vertices, 0u);
        EXPECT_EQ(overlap.area, 0.);
        EXPECT_EQ(overlap.contact_length, 0.);
        // and no heat is exchanged
        const double        Tc[3] = {0., 0., 0.}, Tt[3] = {100., 100., 100.};
        ContactHeatTransfer transfer;
        contact_heat(a.x, a.y, Tc, b.x, b.y, Tt, 1e3, overlap, transfer);
        EXPECT_EQ(transfer.heat_flow, 0.);
        EXPECT_EQ(sum_of_nodal_heats(transfer), 0.);
      }
}

TEST(ContactHeat, AreaAndCentroidMatchAGridEstimate)
{
  std::mt19937_64 rng(20240605);
  unsigned int    n_overlapping = 0;
  for (unsigned int trial = 0; trial < 300; ++trial)
    {
      const Triangle a = random_triangle(rng, 0., 1.);
      const Triangle b = random_triangle(rng, 0.2, 1.);
      OverlapPolygon ab, ba;
      const bool     overlapping = triangle_overlap(a.x, a.y, b.x, b.y, ab);
      EXPECT_EQ(overlapping, triangle_overlap(b.x, b.y, a.x, a.y, ba));
      double grid_area, grid_gx, grid_gy, h;
      grid_estimate(a, b, 400, grid_area, grid_gx, grid_gy, h);
      if (!overlapping)
        {
          EXPECT_LE(grid_area, 4. * h);
          continue;
        }
      ++n_overlapping;
      EXPECT_LE(ab.n_vertices, 6u);
      // the polygon of a clipped by b and of b clipped by a are the same set
      EXPECT_NEAR(ab.area, ba.area, 1e-13);
      EXPECT_NEAR(ab.centroid_x, ba.centroid_x, 1e-12);
      EXPECT_NEAR(ab.centroid_y, ba.centroid_y, 1e-12);
      EXPECT_NEAR(ab.contact_length, ba.contact_length, 1e-10);
      // the crossing points lie on the convex overlap's boundary
      EXPECT_LE(ab.contact_length, 0.5 * ab.perimeter * (1. + 1e-12));
      // grid: error of order perimeter x spacing
      EXPECT_NEAR(ab.area, grid_area, ab.perimeter * h) << "trial " << trial;
      if (ab.area > 0.02)
        {
          EXPECT_NEAR(ab.centroid_x, grid_gx, ab.perimeter * h / ab.area);
          EXPECT_NEAR(ab.centroid_y, grid_gy, ab.perimeter * h / ab.area);
        }
      // the centroid lies in both triangles
      const auto Na = area_coordinates(a.x, a.y, ab.centroid_x, ab.centroid_y);
      const auto Nb = area_coordinates(b.x, b.y, ab.centroid_x, ab.centroid_y);
      for (unsigned int k = 0; k < 3; ++k)
        {
          EXPECT_GE(Na[k], 0.);
          EXPECT_GE(Nb[k], 0.);
        }
      EXPECT_NEAR(Na[0] + Na[1] + Na[2], 1., 1e-15);
    }
  EXPECT_GT(n_overlapping, 100u);
}

TEST(ContactHeat, DegenerateIntegerTrianglesMatchAGridEstimate)
{
  // vertices on a 5 x 5 integer lattice: shared vertices, collinear edges,
  // vertices on edges, identical triangles
  std::mt19937_64                    rng(7);
  std::uniform_int_distribution<int> lattice(0, 4);
  unsigned int                       n_overlapping = 0;
  for (unsigned int trial = 0; trial < 400; ++trial)
    {
      Triangle t[2];
      for (Triangle &tri : t)
        do
          {
            for (unsigned int k = 0; k < 3; ++k)
              {
                tri.x[k] = lattice(rng);
                tri.y[k] = lattice(rng);
              }
            if (area_of(tri) < 0.)
              {
                std::swap(tri.x[1], tri.x[2]);
                std::swap(tri.y[1], tri.y[2]);
              }
        } while (area_of(tri) == 0.);
      OverlapPolygon ab, ba;
      const bool     overlapping =
        triangle_overlap(t[0].x, t[0].y, t[1].x, t[1].y, ab);
      ASSERT_EQ(overlapping,
                triangle_overlap(t[1].x, t[1].y, t[0].x, t[0].y, ba));
      double grid_area, gx, gy, h;
      grid_estimate(t[0], t[1], 300, grid_area, gx, gy, h);
      if (!overlapping)
        {
          EXPECT_EQ(ab.area, 0.);
          EXPECT_LE(grid_area, 4. * h * h * 300) << "trial " << trial;
          continue;
        }
      ++n_overlapping;
      EXPECT_LE(ab.n_vertices, 6u);
      EXPECT_NEAR(ab.area, ba.area, 1e-13);
      EXPECT_NEAR(ab.centroid_x, ba.centroid_x, 1e-12);
      EXPECT_NEAR(ab.centroid_y, ba.centroid_y, 1e-12);
      EXPECT_NEAR(ab.area, grid_area, ab.perimeter * h) << "trial " << trial;
      // collinear edges and shared vertices: the chord is still symmetric
      EXPECT_NEAR(ab.contact_length, ba.contact_length, 1e-12)
        << "trial " << trial;
      // lattice triangles: twice the overlap area is rational, and for
      // nested or identical pairs an integer; at least check positivity
      EXPECT_GT(ab.area, 0.);
    }
  EXPECT_GT(n_overlapping, 50u);
}

TEST(ContactHeat, RectangularOverlapGivesTheTouchingLengthExactly)
{
  // contactor: y >= -delta, x <= s; target: y <= 0, x >= 0; their overlap is
  // the rectangle [0, s] x [-delta, 0]
  const double s = 0.7;
  for (const double delta : {1e-2, 1e-4, 1e-6, 1e-8})
    {
      const Triangle c{{-10., s, s}, {-delta, -delta, 10.}};
      const Triangle t{{0., 0., s + 10.}, {0., -10., 0.}};
      OverlapPolygon overlap;
      ASSERT_TRUE(triangle_overlap(c.x, c.y, t.x, t.y, overlap));
      EXPECT_NEAR(overlap.area, s * delta, 1e-14 * s);
      EXPECT_NEAR(overlap.centroid_x, s / 2., 1e-12);
      EXPECT_NEAR(overlap.centroid_y, -delta / 2., 1e-12);
      // the boundaries cross at (0, -delta) and (s, 0)
      EXPECT_NEAR(overlap.contact_length,
                  std::hypot(s, delta),
                  1e-15 * s * s / delta)
        << "delta " << delta;
      // half the perimeter is off by delta
      EXPECT_NEAR(overlap.perimeter / 2. - s, delta, 1e-15 * s / delta);
    }
}

TEST(ContactHeat, CornerPressedIntoAFaceGivesTheIndentationWidth)
{
  // the apex (0, -d) of the contactor pressed by d into the flat top y = 0
  // of the target: the chord is the indentation width 2 d / (1 + d)
  for (const double d : {0.3, 1e-2, 1e-5})
    {
      const Triangle c{{-1., 0., 1.}, {1., -d, 1.}};
      const Triangle t{{-5., -5., 5.}, {0., -5., 0.}};
      OverlapPolygon overlap;
      ASSERT_TRUE(triangle_overlap(c.x, c.y, t.x, t.y, overlap));
      EXPECT_NEAR(overlap.contact_length, 2. * d / (1. + d), 1e-14);
      EXPECT_NEAR(overlap.area, d * d / (1. + d), 1e-14);
      EXPECT_NEAR(overlap.centroid_y, -d / 3., 1e-14);
    }
}

TEST(ContactHeat, FaceToFaceRightTrianglesGiveTheTouchingSegment)
{
  // contactor (0,-delta) (s,-delta) (0,h) pressed by delta onto the target
  // (0,0) (0,-h) (s,0): their edges overlap along a segment of length s,
  // the overlap is a sliver whose far end tapers over s delta / h
  const double s = 0.3, h = 0.2;
  double       previous_error = 1.;
  for (const double delta : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6})
    {
      const Triangle c{{0., s, 0.}, {-delta, -delta, h}};
      const Triangle t{{0., 0., s}, {0., -h, 0.}};
      OverlapPolygon overlap;
      ASSERT_TRUE(triangle_overlap(c.x, c.y, t.x, t.y, overlap));
      const double error = std::abs(overlap.contact_length - s) / s;
      EXPECT_LT(error, delta / h) << "delta " << delta;
      EXPECT_LT(error, 0.2 * previous_error) << "delta " << delta;
      previous_error = error;
      EXPECT_NEAR(overlap.area,
                  s * delta * (1. - 0.75 * delta / h),
                  1e-3 * s * delta);
    }
}

TEST(ContactHeat, MeshedFaceToFaceContactSumsToTheTouchingLength)
{
  // Two rectangular bodies [0, s] x [-delta, H] (contactor) and
  // [0, s] x [-H, 0] (target) meshed with non-matching columns of two
  // triangles each; all contactor-target pairs together must give the
  // touching length s and, for isothermal bodies, the heat h_c s dT.
  const double s = 1., H = 0.25, h_c = 2e3, T_hot = 80., T_cold = 20.;
  const auto   mesh =
    [&](const std::vector<double> &columns, const double y0, const double y1) {
      std::vector<Triangle> triangles;
      for (unsigned int i = 0; i + 1 < columns.size(); ++i)
        {
          const double x0 = columns[i], x1 = columns[i + 1];
          triangles.push_back({{x0, x1, x1}, {y0, y0, y1}});
          triangles.push_back({{x0, x1, x0}, {y0, y1, y1}});
        }
      return triangles;
    };
  const std::vector<double> contactor_columns =
    {0., 0.13, 0.29, 0.4, 0.55, 0.71, 0.86, 1.};
  const std::vector<double> target_columns = {0., 0.21, 0.4, 0.58, 0.83, 1.};
  double                    previous_error = 1.;
  for (const double delta : {1e-3, 1e-4, 1e-5})
    {
      const auto contactor    = mesh(contactor_columns, -delta, H);
      const auto target       = mesh(target_columns, -H, 0.);
      double     total_length = 0., total_half_perimeter = 0., total_heat = 0.,
             total_contactor_heat = 0., total_target_heat = 0.;
      for (const Triangle &c : contactor)
        for (const Triangle &t : target)
          {
            const double        Tc[3] = {T_cold, T_cold, T_cold};
            const double        Tt[3] = {T_hot, T_hot, T_hot};
            OverlapPolygon      overlap;
            ContactHeatTransfer transfer;
            if (!contact_heat(c.x,
                              c.y,
                              Tc,
                              t.x,
                              t.y,
                              Tt,
                              h_c,
                              overlap,
                              transfer))
              continue;
            total_length += overlap.contact_length;
            total_half_perimeter += overlap.perimeter / 2.;
            total_heat += transfer.heat_flow;
            EXPECT_EQ(transfer.heat_flow,
                      h_c * overlap.contact_length * (T_hot - T_cold));
            for (unsigned int k = 0; k < 3; ++k)
              {
                total_contactor_heat += transfer.contactor_nodal_heat[k];
                total_target_heat += transfer.target_nodal_heat[k];
              }
          }
      const double error = std::abs(total_length - s) / s;
      // second order in delta / (element size) inside, order delta at the
      // two ends of the contact
      EXPECT_LT(error, 2. * delta / s) << "delta " << delta;
      EXPECT_LT(error, 0.2 * previous_error);
      previous_error = error;
      // half the perimeter is much worse: about delta per sliver end
      EXPECT_GT(std::abs(total_half_perimeter - s),
                10. * std::abs(total_length - s));
      EXPECT_NEAR(total_heat / (h_c * s * (T_hot - T_cold)),
                  1.,
                  2. * delta / s);
      EXPECT_NEAR(total_contactor_heat, total_heat, 1e-12 * total_heat);
      EXPECT_NEAR(total_target_heat, -total_heat, 1e-12 * total_heat);
    }
}

TEST(ContactHeat, NodalHeatsSumToExactlyZero)
{
  std::mt19937_64                        rng(42);
  std::uniform_real_distribution<double> u(0., 1.);
  unsigned int                           n_checked = 0;
  for (unsigned int trial = 0; trial < 20000; ++trial)
    {
      const double   scale = std::pow(10., -3. + 4. * u(rng));
      const Triangle c     = random_triangle(rng, 0., scale);
      const Triangle t     = random_triangle(rng, 0.3 * scale, scale);
      double         Tc[3], Tt[3];
      for (unsigned int k = 0; k < 3; ++k)
        {
          Tc[k] = 273.15 + 1000. * u(rng);
          Tt[k] = 273.15 + 1000. * u(rng);
        }
      const double        h_c = std::pow(10., 6. * u(rng));
      OverlapPolygon      overlap;
      ContactHeatTransfer transfer;
      if (!contact_heat(c.x, c.y, Tc, t.x, t.y, Tt, h_c, overlap, transfer))
        continue;
      ++n_checked;
      const auto &qc = transfer.contactor_nodal_heat;
      const auto &qt = transfer.target_nodal_heat;
      // exactly zero in several summation orders
      EXPECT_EQ(qc[0] + qc[1] + qc[2] + qt[0] + qt[1] + qt[2], 0.);
      EXPECT_EQ(qt[2] + qt[1] + qt[0] + qc[2] + qc[1] + qc[0], 0.);
      EXPECT_EQ((qc[0] + qt[0]) + (qc[1] + qt[1]) + (qc[2] + qt[2]), 0.);
      // and each share is Q N to round-off
      const double Q = transfer.heat_flow;
      for (unsigned int k = 0; k < 3; ++k)
        {
          EXPECT_NEAR(qc[k],
                      Q * transfer.contactor_shape[k],
                      4e-15 * std::abs(Q));
          EXPECT_NEAR(qt[k],
                      -Q * transfer.target_shape[k],
                      4e-15 * std::abs(Q));
        }
    }
  EXPECT_GT(n_checked, 5000u);
}

TEST(ContactHeat, HeatFlowsFromHotToCold)
{
  std::mt19937_64                        rng(3);
  std::uniform_real_distribution<double> u(0., 1.);
  for (unsigned int trial = 0; trial < 2000; ++trial)
    {
      const Triangle c = random_triangle(rng, 0., 1.);
      const Triangle t = random_triangle(rng, 0.3, 1.);
      // every target node hotter than every contactor node
      double Tc[3], Tt[3];
      for (unsigned int k = 0; k < 3; ++k)
        {
          Tc[k] = 10. + 20. * u(rng);
          Tt[k] = 31. + 20. * u(rng);
        }
      OverlapPolygon      overlap;
      ContactHeatTransfer transfer;
      if (!contact_heat(c.x, c.y, Tc, t.x, t.y, Tt, 500., overlap, transfer))
        continue;
      if (transfer.conductance == 0.) // nested: no crossing
        EXPECT_EQ(transfer.heat_flow, 0.);
      else
        EXPECT_GT(transfer.heat_flow, 0.);
      for (unsigned int k = 0; k < 3; ++k)
        {
          EXPECT_GE(transfer.contactor_nodal_heat[k], 0.);
          EXPECT_LE(transfer.target_nodal_heat[k], 0.);
        }
      // swapping the roles reverses the flow, same conductance
      ContactHeatTransfer reversed;
      OverlapPolygon      overlap_reversed;
      ASSERT_TRUE(contact_heat(t.x,
                               t.y,
                               Tt,
                               c.x,
                               c.y,
                               Tc,
                               500.,
                               overlap_reversed,
                               reversed));
      EXPECT_NEAR(reversed.conductance,
                  transfer.conductance,
                  1e-10 * transfer.conductance);
      EXPECT_NEAR(reversed.heat_flow,
                  -transfer.heat_flow,
                  1e-10 * std::abs(transfer.heat_flow));
    }
}

TEST(ContactHeat, IsothermalBodiesExchangeConductanceTimesTemperatureJump)
{
  const Triangle      c{{0., 1., 0.2}, {-0.01, -0.01, 0.8}};
  const Triangle      t{{0.1, 0.7, 1.2}, {0., -0.9, 0.}};
  const double        T1 = 293.15, T2 = 373.15, h_c = 1500.;
  const double        Tc[3] = {T1, T1, T1}, Tt[3] = {T2, T2, T2};
  OverlapPolygon      overlap;
  ContactHeatTransfer transfer;
  ASSERT_TRUE(contact_heat(c.x, c.y, Tc, t.x, t.y, Tt, h_c, overlap, transfer));
  EXPECT_GT(overlap.contact_length, 0.5);
  EXPECT_EQ(transfer.contactor_temperature, T1);
  EXPECT_EQ(transfer.target_temperature, T2);
  EXPECT_EQ(transfer.conductance, h_c * overlap.contact_length);
  EXPECT_EQ(transfer.heat_flow, h_c * overlap.contact_length * (T2 - T1));
  EXPECT_NEAR(transfer.contactor_nodal_heat[0] +
                transfer.contactor_nodal_heat[1] +
                transfer.contactor_nodal_heat[2],
              transfer.heat_flow,
              1e-15 * transfer.heat_flow);
  // equal temperatures: nothing flows
  ASSERT_TRUE(contact_heat(c.x, c.y, Tc, t.x, t.y, Tc, h_c, overlap, transfer));
  EXPECT_EQ(transfer.heat_flow, 0.);
  EXPECT_EQ(transfer.contactor_nodal_heat[0], 0.);
  EXPECT_EQ(transfer.target_nodal_heat[2], 0.);
}

TEST(ContactHeat, LinearisationMatchesFiniteDifferences)
{
  std::mt19937_64                        rng(11);
  std::uniform_real_distribution<double> u(0., 1.);
  unsigned int                           n_checked = 0;
  for (unsigned int trial = 0; trial < 200; ++trial)
    {
      const Triangle c = random_triangle(rng, 0., 1.);
      const Triangle t = random_triangle(rng, 0.3, 1.);
      double         T[6];
      for (double &value : T)
        value = 300. + 100. * u(rng);
      const double        h_c = 800.;
      OverlapPolygon      overlap;
      ContactHeatTransfer base;
      if (!contact_heat(c.x, c.y, T, t.x, t.y, T + 3, h_c, overlap, base))
        continue;
      ++n_checked;
      const auto jacobian = base.heat_jacobian();
      // linear in T: the nodal heats are exactly -K T up to round-off
      for (unsigned int i = 0; i < 6; ++i)
        {
          double       product = 0.;
          const double heat_i  = i < 3 ? base.contactor_nodal_heat[i] :
                                         base.target_nodal_heat[i - 3];
          for (unsigned int j = 0; j < 6; ++j)
            product += jacobian[i][j] * T[j];
          EXPECT_NEAR(heat_i, product, 1e-11 * base.conductance * 400.);
        }
      // central differences
      const double step = 0.5;
      for (unsigned int j = 0; j < 6; ++j)
        {
          double plus[6], minus[6];
          std::copy(T, T + 6, plus);
          std::copy(T, T + 6, minus);
          plus[j] += step;
          minus[j] -= step;
          ContactHeatTransfer up, down;
          contact_heat(c.x, c.y, plus, t.x, t.y, plus + 3, h_c, overlap, up);
          contact_heat(c.x,
                       c.y,
                       minus,
                       t.x,
                       t.y,
                       minus + 3,
                       h_c,
                       overlap,
                       down);
          for (unsigned int i = 0; i < 6; ++i)
            {
              const double derivative =
                i < 3 ?
                  (up.contactor_nodal_heat[i] - down.contactor_nodal_heat[i]) /
                    (2. * step) :
                  (up.target_nodal_heat[i - 3] -
                   down.target_nodal_heat[i - 3]) /
                    (2. * step);
              EXPECT_NEAR(derivative, jacobian[i][j], 1e-10 * base.conductance);
            }
        }
      // K is symmetric and its rows sum to zero (conservation)
      for (unsigned int i = 0; i < 6; ++i)
        {
          double row = 0.;
          for (unsigned int j = 0; j < 6; ++j)
            {
              row += jacobian[i][j];
              EXPECT_EQ(jacobian[i][j], jacobian[j][i]);
            }
          EXPECT_NEAR(row, 0., 1e-14 * base.conductance);
        }
    }
  EXPECT_GT(n_checked, 50u);
}

TEST(ContactHeat, ContactLengthIsInvariantUnderRigidMotions)
{
  std::mt19937_64                        rng(5);
  std::uniform_real_distribution<double> u(0., 1.);
  for (unsigned int trial = 0; trial < 200; ++trial)
    {
      const Triangle c = random_triangle(rng, 0., 1.);
      const Triangle t = random_triangle(rng, 0.3, 1.);
      OverlapPolygon overlap;
      if (!triangle_overlap(c.x, c.y, t.x, t.y, overlap))
        continue;
      const double angle = 6.283 * u(rng), dx = 5. * u(rng), dy = -3. * u(rng);
      Triangle     c_moved, t_moved;
      for (unsigned int k = 0; k < 3; ++k)
        {
          c_moved.x[k] =
            std::cos(angle) * c.x[k] - std::sin(angle) * c.y[k] + dx;
          c_moved.y[k] =
            std::sin(angle) * c.x[k] + std::cos(angle) * c.y[k] + dy;
          t_moved.x[k] =
            std::cos(angle) * t.x[k] - std::sin(angle) * t.y[k] + dx;
          t_moved.y[k] =
            std::sin(angle) * t.x[k] + std::cos(angle) * t.y[k] + dy;
        }
      OverlapPolygon moved;
      ASSERT_TRUE(
        triangle_overlap(c_moved.x, c_moved.y, t_moved.x, t_moved.y, moved));
      EXPECT_NEAR(moved.area, overlap.area, 1e-12);
      EXPECT_NEAR(moved.contact_length,
                  overlap.contact_length,
                  1e-10 * overlap.contact_length);
    }
}

TEST(ContactHeat, PaperLiteralTermTransfersNothingBetweenIsothermalBodies)
{
  // the named alternative of Eqs. 29-33 is driven by gradients only: two
  // isothermal bodies at 20 C and 100 C in contact exchange nothing, the
  // default driving term exchanges h_c L_c (T2 - T1)
  const Triangle      c{{0., 1., 0.2}, {-0.01, -0.01, 0.8}};
  const Triangle      t{{0.1, 0.7, 1.2}, {0., -0.9, 0.}};
  const double        Tc[3] = {20., 20., 20.}, Tt[3] = {100., 100., 100.};
  OverlapPolygon      overlap;
  ContactHeatTransfer literal, prescribed;
  ASSERT_TRUE(paper_literal_contact_heat(c.x,
                                         c.y,
                                         Tc,
                                         t.x,
                                         t.y,
                                         Tt,
                                         1e3,
                                         overlap,
                                         literal));
  EXPECT_EQ(literal.heat_flow, 0.);
  ASSERT_TRUE(
    contact_heat(c.x, c.y, Tc, t.x, t.y, Tt, 1e3, overlap, prescribed));
  EXPECT_GT(prescribed.heat_flow, 0.);
  // with gradients it does transfer something, conserved exactly
  const double Tg[3] = {20., 60., 30.};
  ASSERT_TRUE(paper_literal_contact_heat(c.x,
                                         c.y,
                                         Tg,
                                         t.x,
                                         t.y,
                                         Tt,
                                         1e3,
                                         overlap,
                                         literal));
  EXPECT_NE(literal.heat_flow, 0.);
  EXPECT_EQ(sum_of_nodal_heats(literal), 0.);
}

TEST(ContactHeat, PaperLiteralTermMatchesAHandDerivedValue)
{
  // two triangles pressed together by delta (tests/data/pressed_triangles):
  // the lower (0.05, 0), (0.1, 0.1), (0, 0.1) and its mirror image about
  // y = H - delta/2; overlap a hexagon of area w delta (1 - 3 delta/(4 H)),
  // centroids on x = w/2 so n = (0, 1). Linear fields T_c = 20 + 1000 y,
  // T_t = 120 + 3000 (y - 0.099): grad T_c + grad T_t = (0, 4000) K/m and
  // Q = h_c A 4000 into the contactor (the lower triangle).
  const double   w = 0.1, H = 0.1, delta = 1e-3, h_c = 1e4;
  const Triangle c{{0.05, 0.1, 0.}, {0., 0.1, 0.1}};
  const Triangle t{{0., 0.1, 0.05}, {0.099, 0.099, 0.199}};
  double         Tc[3], Tt[3];
  for (unsigned int k = 0; k < 3; ++k)
    {
      Tc[k] = 20. + 1000. * c.y[k];
      Tt[k] = 120. + 3000. * (t.y[k] - 0.099);
    }
  const double        area = w * delta * (1. - 3. * delta / (4. * H));
  OverlapPolygon      overlap;
  ContactHeatTransfer transfer;
  ASSERT_TRUE(contact_heat(ContactHeatModel::paper_literal,
                           c.x,
                           c.y,
                           Tc,
                           t.x,
                           t.y,
                           Tt,
                           h_c,
                           overlap,
                           transfer));
  EXPECT_NEAR(overlap.area, area, 1e-12 * area);
  EXPECT_NEAR(transfer.heat_flow,
              h_c * area * 4000.,
              1e-10 * h_c * area * 4000.);
  EXPECT_EQ(sum_of_nodal_heats(transfer), 0.);
  EXPECT_EQ(transfer.conductance, 0.);
  // the flow weights are dQ/dT: Q = sum_j a_j T_j
  double linear = 0.;
  for (unsigned int k = 0; k < 3; ++k)
    linear +=
      transfer.flow_weights[k] * Tc[k] + transfer.flow_weights[3 + k] * Tt[k];
  EXPECT_NEAR(linear, transfer.heat_flow, 1e-9 * std::abs(transfer.heat_flow));
  // the default on the same pair: h_c L_c (T_t(G) - T_c(G)),
  // G = (w/2, H - delta/2); the slanted sides of the two triangles cross at
  // y = H - delta/2, so all six vertices of the hexagon are crossings of the
  // two boundaries and L_c is half its perimeter: the two flat edges
  // w (1 - delta/H) and four slanted pieces (delta/2) sqrt(1 + (w/(2H))^2),
  // L_c = w (1 - delta/H) + delta sqrt(1 + w^2 / (4 H^2))
  ContactHeatTransfer prescribed;
  ASSERT_TRUE(contact_heat(ContactHeatModel::temperature_difference,
                           c.x,
                           c.y,
                           Tc,
                           t.x,
                           t.y,
                           Tt,
                           h_c,
                           overlap,
                           prescribed));
  const double G_y = H - delta / 2.;
  const double chord =
    w * (1. - delta / H) + delta * std::sqrt(1. + w * w / (4. * H * H));
  EXPECT_NEAR(overlap.contact_length, chord, 1e-12 * chord);
  const double expected =
    h_c * chord * ((120. + 3000. * (G_y - 0.099)) - (20. + 1000. * G_y));
  EXPECT_NEAR(prescribed.heat_flow, expected, 1e-10 * std::abs(expected));
}

TEST(ContactHeat, PaperLiteralTermDoesNotDependOnWhichTriangleIsTheContactor)
{
  // Q is odd under exchanging contactor and target: the heat each triangle
  // receives is the same whichever the search calls the contactor
  std::mt19937_64 rng(7);
  unsigned int    tested = 0;
  for (unsigned int trial = 0; trial < 2000 && tested < 100; ++trial)
    {
      const Triangle                         c = random_triangle(rng, 0., 1.);
      const Triangle                         t = random_triangle(rng, 0.3, 1.);
      double                                 Tc[3], Tt[3];
      std::uniform_real_distribution<double> u(0., 100.);
      for (unsigned int k = 0; k < 3; ++k)
        {
          Tc[k] = u(rng);
          Tt[k] = u(rng);
        }
      OverlapPolygon      overlap;
      ContactHeatTransfer forward, backward;
      if (!paper_literal_contact_heat(c.x,
                                      c.y,
                                      Tc,
                                      t.x,
                                      t.y,
                                      Tt,
                                      1e3,
                                      overlap,
                                      forward))
        continue;
      ASSERT_TRUE(paper_literal_contact_heat(t.x,
                                             t.y,
                                             Tt,
                                             c.x,
                                             c.y,
                                             Tc,
                                             1e3,
                                             overlap,
                                             backward));
      // the size of the terms of Q (h_c A |grad T|), not Q (cancellation)
      const auto   gc = temperature_gradient(c.x, c.y, Tc);
      const auto   gt = temperature_gradient(t.x, t.y, Tt);
      const double scale =
        1e3 * overlap.area *
        (std::hypot(gc[0], gc[1]) + std::hypot(gt[0], gt[1]));
      EXPECT_NEAR(backward.heat_flow, -forward.heat_flow, 1e-9 * scale);
      for (unsigned int k = 0; k < 3; ++k)
        {
          EXPECT_NEAR(backward.contactor_nodal_heat[k],
                      forward.target_nodal_heat[k],
                      1e-8 * scale);
          EXPECT_NEAR(backward.target_nodal_heat[k],
                      forward.contactor_nodal_heat[k],
                      1e-8 * scale);
        }
      ++tested;
    }
  EXPECT_EQ(tested, 100u);
}

TEST(ContactHeat, ModelDispatchGivesTheDefaultBitwise)
{
  EXPECT_STREQ(contact_heat_model_registry()[0].first,
               "temperature difference");
  EXPECT_EQ(contact_heat_model_registry()[0].second,
            ContactHeatModel::temperature_difference);
  EXPECT_STREQ(contact_heat_model_registry()[1].first, "paper literal");
  std::mt19937_64 rng(11);
  for (unsigned int trial = 0; trial < 200; ++trial)
    {
      const Triangle      c     = random_triangle(rng, 0., 1.);
      const Triangle      t     = random_triangle(rng, 0.3, 1.);
      const double        Tc[3] = {10., 20., 35.}, Tt[3] = {80., 60., 75.};
      OverlapPolygon      o1, o2;
      ContactHeatTransfer direct, dispatched;
      const bool a = contact_heat(c.x, c.y, Tc, t.x, t.y, Tt, 500., o1, direct);
      const bool b = contact_heat(ContactHeatModel::temperature_difference,
                                  c.x,
                                  c.y,
                                  Tc,
                                  t.x,
                                  t.y,
                                  Tt,
                                  500.,
                                  o2,
                                  dispatched);
      ASSERT_EQ(a, b);
      EXPECT_EQ(direct.heat_flow, dispatched.heat_flow);
      for (unsigned int k = 0; k < 3; ++k)
        {
          EXPECT_EQ(direct.contactor_nodal_heat[k],
                    dispatched.contactor_nodal_heat[k]);
          EXPECT_EQ(direct.target_nodal_heat[k],
                    dispatched.target_nodal_heat[k]);
        }
    }
}
