// Unit tests of the contact kernel between tetrahedra
// (include/tmfdem/discrete/tetrahedron_contact.h): the forces on all eight
// nodes are minus the gradient of the pair's energy (central finite
// differences), they keep linear and angular momentum, and the energy of a
// contactor that coincides with its target is the closed form p V / 4.

#include <cmath>
#include <gtest/gtest.h>
#include <random>
#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/tetrahedron_contact.h>
#include <tmfdem/discrete/tetrahedron_contact_system.h>

using namespace tmfdem::discrete;

namespace
{
  using Nodes = double[4][3];

  /** The pair's energy E_t + E_c [J] (each tetrahedron the contactor in
   *  the other). */
  double
  pair_energy(const Nodes &a, const Nodes &b, const double p)
  {
    TetrahedronCoordinates ta, tb;
    if (!ta.set(a) || !tb.set(b))
      return 0.;
    return contact_energy_3d(a, tb, p) + contact_energy_3d(b, ta, p);
  }

  /** The pair's forces: f[0..11] on a, f[12..23] on b [N]. */
  void
  pair_forces(const Nodes &a, const Nodes &b, const double p, double *f)
  {
    std::fill(f, f + 24, 0.);
    TetrahedronCoordinates ta, tb;
    ASSERT_TRUE(ta.set(a) && tb.set(b));
    std::array<FacePotentialIntegrals, 4> integrals;
    // a the contactor in b, then b in a
    add_contactor_potential_forces_3d(a, tb, p, f, integrals);
    add_target_potential_forces_3d(a, tb, p, f + 12);
    add_contactor_potential_forces_3d(b, ta, p, f + 12, integrals);
    add_target_potential_forces_3d(b, ta, p, f);
  }

  void
  positive(Nodes &t)
  {
    TetrahedronCoordinates c;
    if (!c.set(t))
      for (unsigned int i = 0; i < 3; ++i)
        std::swap(t[1][i], t[2][i]);
  }

  /** Two random tetrahedra of size ~1 m whose centroids are @p distance
   *  apart. */
  void
  random_pair(std::mt19937 &rng, const double distance, Nodes &a, Nodes &b)
  {
    std::uniform_real_distribution<double> u(-0.5, 0.5);
    for (unsigned int k = 0; k < 4; ++k)
      for (unsigned int i = 0; i < 3; ++i)
        {
          a[k][i] = u(rng) + (k == i + 1 ? 1. : 0.);
          b[k][i] = u(rng) + (k == i + 1 ? 1. : 0.) + (i == 0 ? distance : 0.);
        }
    positive(a);
    positive(b);
  }
} // namespace

TEST(TetrahedronContact, EnergyOfCoincidentTetrahedraIsPVolumeOverFour)
{
  // int_t 4 min(lambda) dV = 4 * 4 (V / 4) (1 / 16) = V / 4 per direction
  Nodes t = {{0.1, -0.2, 0.3},
             {1.3, 0.1, 0.2},
             {0.2, 0.9, -0.1},
             {0.4, 0.3, 1.1}};
  positive(t);
  TetrahedronCoordinates c;
  ASSERT_TRUE(c.set(t));
  const double p = 7.;
  EXPECT_NEAR(contact_energy_3d(t, c, p),
              p * c.volume / 4.,
              1e-12 * p * c.volume);
}

TEST(TetrahedronContact, ForcesAreMinusTheGradientOfTheEnergy)
{
  std::mt19937 rng(11);
  const double p      = 3.;
  unsigned int tested = 0;
  for (unsigned int trial = 0; trial < 200 && tested < 20; ++trial)
    {
      Nodes a, b;
      random_pair(rng, 0.6, a, b);
      const double E = pair_energy(a, b, p);
      if (!(E > 1e-4))
        continue;
      ++tested;
      double f[24];
      pair_forces(a, b, p, f);
      double largest = 0.;
      for (double v : f)
        largest = std::max(largest, std::abs(v));
      const double h = 1e-6;
      for (unsigned int q = 0; q < 24; ++q)
        {
          Nodes       &t  = q < 12 ? a : b;
          double      &x  = t[(q % 12) / 3][q % 3];
          const double x0 = x;
          x               = x0 + h;
          const double Ep = pair_energy(a, b, p);
          x               = x0 - h;
          const double Em = pair_energy(a, b, p);
          x               = x0;
          EXPECT_NEAR(f[q], -(Ep - Em) / (2. * h), 1e-5 * largest)
            << "trial " << trial << " component " << q;
        }
    }
  EXPECT_GE(tested, 10u);
}

TEST(TetrahedronContact, ForcesKeepLinearAndAngularMomentum)
{
  std::mt19937 rng(5);
  const double p      = 1e9;
  unsigned int tested = 0;
  for (unsigned int trial = 0; trial < 200 && tested < 30; ++trial)
    {
      Nodes a, b;
      random_pair(rng, 0.5, a, b);
      if (!(pair_energy(a, b, p) > 0.))
        continue;
      ++tested;
      double f[24];
      pair_forces(a, b, p, f);
      double sum[3] = {0., 0., 0.}, torque[3] = {0., 0., 0.}, largest = 0.;
      for (unsigned int n = 0; n < 8; ++n)
        {
          const double *x  = n < 4 ? a[n] : b[n - 4];
          const double *fn = &f[3 * n];
          for (unsigned int i = 0; i < 3; ++i)
            {
              sum[i] += fn[i];
              largest = std::max(largest, std::abs(fn[i]));
            }
          torque[0] += x[1] * fn[2] - x[2] * fn[1];
          torque[1] += x[2] * fn[0] - x[0] * fn[2];
          torque[2] += x[0] * fn[1] - x[1] * fn[0];
        }
      ASSERT_GT(largest, 0.);
      for (unsigned int i = 0; i < 3; ++i)
        {
          EXPECT_LT(std::abs(sum[i]), 1e-10 * largest) << "trial " << trial;
          EXPECT_LT(std::abs(torque[i]), 1e-10 * largest) << "trial " << trial;
        }
    }
  EXPECT_GE(tested, 10u);
}

TEST(TetrahedronContact, SeparatedTetrahedraHaveNoForce)
{
  Nodes  a = {{0., 0., 0.}, {1., 0., 0.}, {0., 1., 0.}, {0., 0., 1.}};
  Nodes  b = {{2., 0., 0.}, {3., 0., 0.}, {2., 1., 0.}, {2., 0., 1.}};
  double f[24];
  pair_forces(a, b, 1., f);
  for (double v : f)
    EXPECT_EQ(v, 0.);
  EXPECT_EQ(pair_energy(a, b, 1.), 0.);
}

TEST(TetrahedronContact, FrictionSticksElasticallyThenSlidesAtMuN)
{
  // a contactor pressed into a target, its face sliding along x
  Nodes t = {{0., 0., 0.}, {1., 0., 0.}, {0., 1., 0.}, {0., 0., 1.}};
  Nodes c = {{0.1, 0.1, 0.95},
             {0.6, 0.1, 0.95},
             {0.1, 0.6, 0.95},
             {0.2, 0.2, 0.1}};
  positive(t);
  positive(c);
  TetrahedronCoordinates target;
  ASSERT_TRUE(target.set(t));
  const double          p = 1e9, p_t = 1e9, mu = 0.5, dt = 1e-6;
  PenaltyCoulombContact law; // plain Coulomb
  law.normal_penalty     = p;
  law.tangential_penalty = p_t;
  law.friction           = mu;
  law.memory_slip        = 0.;
  Nodes  vc = {}, vt = {};
  double g[4][3];
  scaled_gradients(c, g);
  for (auto &v : vc)
    v[0] = 1.; // 1 m/s along x
  unsigned int tested = 0;
  for (unsigned int f = 0; f < 4; ++f)
    {
      FacePotentialIntegrals I;
      if (!face_potential_integrals(c, g, f, target, I))
        continue;
      ++tested;
      FaceFriction h;
      double       fc[12] = {}, ft[12] = {};
      // one step: elastic, force -k v dt along x
      const double w1 =
        add_face_friction_3d(g, vc, vt, f, I, law, dt, h, fc, ft);
      EXPECT_EQ(w1, 0.);
      double sum[3] = {0., 0., 0.}, contactor_x = 0.;
      for (unsigned int n = 0; n < 4; ++n)
        {
          contactor_x += fc[3 * n];
          for (unsigned int i = 0; i < 3; ++i)
            sum[i] += fc[3 * n + i] + ft[3 * n + i];
        }
      EXPECT_LT(contactor_x, 0.) << "face " << f;
      for (double s : sum)
        EXPECT_LT(std::abs(s), 1e-12 * std::abs(contactor_x));
      // both act at the centroid of the normal force: no torque
      double torque[3] = {0., 0., 0.};
      for (unsigned int n = 0; n < 8; ++n)
        {
          const double *x  = n < 4 ? c[n] : t[n - 4];
          const double *fn = n < 4 ? &fc[3 * n] : &ft[3 * (n - 4)];
          torque[0] += x[1] * fn[2] - x[2] * fn[1];
          torque[1] += x[2] * fn[0] - x[0] * fn[2];
          torque[2] += x[0] * fn[1] - x[1] * fn[0];
        }
      for (double m : torque)
        EXPECT_LT(std::abs(m), 1e-12 * std::abs(contactor_x)) << "face " << f;
      // many steps: sliding, the force is mu N
      double dissipated = 0.;
      for (unsigned int step = 0; step < 1000; ++step)
        {
          std::fill(fc, fc + 12, 0.);
          std::fill(ft, ft + 12, 0.);
          dissipated +=
            add_face_friction_3d(g, vc, vt, f, I, law, 1e-3, h, fc, ft);
        }
      // (the contactor's whole tangential force; the face may be slanted
      // to x)
      double force[3] = {0., 0., 0.};
      for (unsigned int n = 0; n < 4; ++n)
        for (unsigned int i = 0; i < 3; ++i)
          force[i] += fc[3 * n + i];
      const double magnitude = std::sqrt(
        force[0] * force[0] + force[1] * force[1] + force[2] * force[2]);
      EXPECT_LT(force[0], 0.);
      EXPECT_NEAR(magnitude, mu * p * I.total(), 1e-9 * mu * p * I.total())
        << "face " << f;
      EXPECT_GT(dissipated, 0.);
    }
  EXPECT_GE(tested, 1u);
}

TEST(TetrahedronContact, RegularisedFrictionSlidesAtMuNAndResistsAcceleration)
{
  // the contactor of the test above sliding steadily along x at 1 m/s with
  // the regularised law: after many memory slips the strength is mu N and
  // the rate term 1 (Coulomb in steady sliding); a jump to 2 m/s over a
  // slip of L / 50 raises the cap to S (1 + a ln((v0 + 2) / (v0 + V))),
  // V the remembered rate after that slip (theory manual 5.5)
  Nodes t = {{0., 0., 0.}, {1., 0., 0.}, {0., 1., 0.}, {0., 0., 1.}};
  Nodes c = {{0.1, 0.1, 0.95},
             {0.6, 0.1, 0.95},
             {0.1, 0.6, 0.95},
             {0.2, 0.2, 0.1}};
  positive(t);
  positive(c);
  TetrahedronCoordinates target;
  ASSERT_TRUE(target.set(t));
  PenaltyCoulombContact law;
  law.normal_penalty = 1e9;
  // a stiff spring: every step below reaches the cap, the jump's slip of
  // L / 50 included (k L / 50 above the rise of the cap)
  law.tangential_penalty  = 1e17;
  law.friction            = 0.6;
  law.memory_slip         = 1e-7;
  law.rate_effect         = 0.01;
  law.reference_slip_rate = 1e-6;
  double g[4][3];
  scaled_gradients(c, g);
  Nodes vc = {}, vt = {};
  for (auto &v : vc)
    v[0] = 1.;
  unsigned int tested = 0;
  for (unsigned int f = 0; f < 4; ++f)
    {
      FacePotentialIntegrals I;
      if (!face_potential_integrals(c, g, f, target, I))
        continue;
      ++tested;
      const double coulomb = law.friction * law.normal_penalty * I.total();
      FaceFriction h;
      double       fc[12], ft[12];
      auto         contactor_force = [&]() {
        double force[3] = {0., 0., 0.};
        for (unsigned int n = 0; n < 4; ++n)
          for (unsigned int i = 0; i < 3; ++i)
            force[i] += fc[3 * n + i];
        return std::sqrt(force[0] * force[0] + force[1] * force[1] +
                         force[2] * force[2]);
      };
      // the face's tangential speed (the face may be slanted to x)
      double n[3];
      outward_face_normal(g, f, n);
      const double speed = std::sqrt(1. - n[0] * n[0]);
      // 1000 steps of 1 ms, 1 m/s: 1e7 memory slips
      for (unsigned int step = 0; step < 1000; ++step)
        {
          std::fill(fc, fc + 12, 0.);
          std::fill(ft, ft + 12, 0.);
          add_face_friction_3d(g, vc, vt, f, I, law, 1e-3, h, fc, ft);
        }
      EXPECT_NEAR(contactor_force(), coulomb, 1e-9 * coulomb) << "face " << f;
      EXPECT_NEAR(h.strength, coulomb, 1e-12 * coulomb);
      EXPECT_NEAR(h.remembered_rate, speed, 1e-12);
      // a jump to 2 m/s for L / 50 of slip
      for (auto &v : vc)
        v[0] = 2.;
      const double dt       = law.memory_slip / 50. / (2. * speed);
      const double keep     = std::exp(-1. / 50.);
      const double remember = 2. * speed + (speed - 2. * speed) * keep;
      const double expected =
        coulomb * (1. + law.rate_effect *
                          std::log((law.reference_slip_rate + 2. * speed) /
                                   (law.reference_slip_rate + remember)));
      std::fill(fc, fc + 12, 0.);
      std::fill(ft, ft + 12, 0.);
      add_face_friction_3d(g, vc, vt, f, I, law, dt, h, fc, ft);
      EXPECT_GT(expected, 1.001 * coulomb);
      EXPECT_NEAR(contactor_force(), expected, 1e-9 * coulomb) << "face " << f;
      for (auto &v : vc)
        v[0] = 1.;
    }
  EXPECT_GE(tested, 1u);
}

TEST(TetrahedronContact, PairKernelWithoutFrictionIsTheGradientForces)
{
  // add_pair_forces_3d(), the solver's pair kernel, without friction gives
  // the forces of the test above (minus the gradient of E_t + E_c) to
  // round-off, with the target's share as the exact gradient
  std::mt19937 rng(23);
  for (unsigned int trial = 0; trial < 20; ++trial)
    {
      double x[2][4][3], v[2][4][3] = {};
      random_pair(rng, 0.5, x[0], x[1]);
      PenaltyCoulombContact law;
      law.normal_penalty     = 1e9;
      law.tangential_penalty = 1e9;
      law.friction           = 0.;
      TetrahedronPairFriction history{};
      double                  kernel[24] = {}, reference[24];
      EXPECT_EQ(add_pair_forces_3d(x, v, law, 1e-6, history, kernel), 0.);
      pair_forces(x[0], x[1], law.normal_penalty, reference);
      double largest = 0.;
      for (const double f : reference)
        largest = std::max(largest, std::abs(f));
      for (unsigned int i = 0; i < 24; ++i)
        EXPECT_NEAR(kernel[i], reference[i], 1e-12 * largest)
          << "trial " << trial << ", component " << i;
      EXPECT_NEAR(pair_contact_energy_3d(x, law.normal_penalty),
                  pair_energy(x[0], x[1], law.normal_penalty),
                  1e-14 * law.normal_penalty);
    }
}

TEST(TetrahedronContact, LinkedCellsFindEveryPairOfOverlappingBoxes)
{
  // 1000 small random tetrahedra in a unit cube: the 3D linked cells give
  // exactly the pairs whose boxes (enlarged by half the buffer) overlap,
  // sorted, on one and on two threads
  std::mt19937                           rng(3);
  std::uniform_real_distribution<double> where(0., 1.), size(0.02, 0.1);
  const unsigned int                     n = 1000;
  std::vector<double>                    x(4 * n), y(4 * n), z(4 * n);
  std::vector<unsigned int>              active;
  for (unsigned int e = 0; e < n; ++e)
    {
      const double c[3] = {where(rng), where(rng), where(rng)};
      for (unsigned int k = 0; k < 4; ++k)
        {
          x[4 * e + k] = c[0] + size(rng);
          y[4 * e + k] = c[1] + size(rng);
          z[4 * e + k] = c[2] + size(rng);
        }
      if (e % 5 != 0) // some inactive
        active.push_back(e);
    }
  const double                                       buffer = 0.01;
  std::vector<std::pair<unsigned int, unsigned int>> expected;
  for (const unsigned int a : active)
    for (const unsigned int b : active)
      {
        if (b <= a)
          continue;
        double              box_a[6], box_b[6];
        const double *const ca[3] = {&x[4 * a], &y[4 * a], &z[4 * a]};
        const double *const cb[3] = {&x[4 * b], &y[4 * b], &z[4 * b]};
        search_box<3>(ca, buffer, box_a);
        search_box<3>(cb, buffer, box_b);
        bool overlap = true;
        for (unsigned int d = 0; d < 3; ++d)
          overlap =
            overlap && box_a[d] <= box_b[3 + d] && box_b[d] <= box_a[3 + d];
        if (overlap)
          expected.emplace_back(a, b);
      }
  ASSERT_GT(expected.size(), 50u);
  const std::vector<double> *const coordinates[3] = {&x, &y, &z};
  for (const unsigned int threads : {1u, 2u})
    {
      LinkedCellSearchT<3, TetrahedronContactPair> search;
      std::vector<TetrahedronContactPair>          pairs;
      search.rebuild(
        coordinates,
        active,
        buffer,
        [](unsigned int, unsigned int) { return false; },
        pairs,
        tmfdem::arena_for(threads));
      ASSERT_EQ(pairs.size(), expected.size()) << threads << " threads";
      for (std::size_t p = 0; p < pairs.size(); ++p)
        {
          EXPECT_EQ(pairs[p].first, expected[p].first);
          EXPECT_EQ(pairs[p].second, expected[p].second);
        }
    }
}

TEST(TetrahedronContact, BrokenFacesTakeOverTheJointsCompressionEnergy)
{
  // two tetrahedra joined on the face z = 0 (area 1/2); the upper one
  // pressed into the lower by o: a joint of normal stiffness k_n stores
  // k_n / 2 o^2 A; the contact of the two faces once the joint broke, with
  // the penalty scaled by face_penalty_factor(), must store the same up to
  // the O(o / H) of a slab that is not a prism
  const double A = 0.5, p = 1e10, k_n = 1e10;
  Nodes        a = {{0., 0., 0.}, {1., 0., 0.}, {0., 1., 0.}, {0.2, 0.3, -0.8}};
  Nodes        b = {{0., 0., 0.}, {1., 0., 0.}, {0., 1., 0.}, {0.3, 0.2, 0.9}};
  positive(a);
  positive(b);
  TetrahedronCoordinates ca, cb;
  ASSERT_TRUE(ca.set(a) && cb.set(b));
  DiscreteModel model;
  model.allocate(3, 2);
  model.n_joints = 1;
  model.edge_joint.assign(8, -1);
  model.edge_joint[4 * 0 + 3] = 0; // joint 0, side A
  model.edge_joint[4 * 1 + 3] = 1; // joint 0, side B
  model.joint_elements        = {0, 1};
  model.joint_area            = {A};
  model.reference_area        = {ca.volume, cb.volume};
  JointConstants constants{};
  constants.normal_stiffness = k_n;
  model.joint_constants      = {constants};
  const double factor =
    TetrahedronContactSystem::face_penalty_factor(model, 0, 1, p);
  const double H_a = 3. * ca.volume / A, H_b = 3. * cb.volume / A;
  EXPECT_NEAR(factor, k_n / (4. * p * (1. / H_a + 1. / H_b)), 1e-15);
  ASSERT_LT(factor, 1.);
  for (const double o : {1e-3, 1e-4})
    {
      double x[2][4][3];
      for (unsigned int k = 0; k < 4; ++k)
        for (unsigned int i = 0; i < 3; ++i)
          {
            x[0][k][i] = a[k][i];
            x[1][k][i] = b[k][i] - (i == 2 ? o : 0.);
          }
      const double contact = pair_contact_energy_3d(x, factor * p);
      const double joint   = 0.5 * k_n * o * o * A;
      EXPECT_NEAR(contact / joint, 1., 20. * o / std::min(H_a, H_b))
        << "overlap " << o << " m";
    }
}

// The search's margin test: two corner tetrahedra whose parallel faces are
// a known distance apart along (1, 1, 1) while their boxes overlap, and two
// whose nearest features are crossing edges (only an edge-edge axis, z,
// separates them). The gap found is the distance between them: apart by
// more than slightly less, not by slightly more.
TEST(TetrahedronContact, MarginTestFindsTheGapAlongFaceAndEdgeAxes)
{
  const double t              = 1.2; // boxes [0, 1]^3 and [t - 1, t]^3 overlap
  double       faces[2][4][3] = {
          {{0., 0., 0.}, {1., 0., 0.}, {0., 1., 0.}, {0., 0., 1.}},
          {{t, t, t}, {t - 1., t, t}, {t, t - 1., t}, {t, t, t - 1.}}};
  const double face_gap = (3. * t - 2.) / std::sqrt(3.);
  EXPECT_TRUE(tetrahedron_boxes_overlap(faces));
  EXPECT_TRUE(tetrahedra_apart_by_more_than(faces, 0.99 * face_gap));
  EXPECT_FALSE(tetrahedra_apart_by_more_than(faces, 1.01 * face_gap));

  const double g              = 0.5;
  double       edges[2][4][3] = {
          {{-1., 0., 0.}, {1., 0., 0.}, {0., -1., -1.}, {0., 1., -1.}},
          {{0., -1., g}, {0., 1., g}, {-1., 0., g + 1.}, {1., 0., g + 1.}}};
  EXPECT_TRUE(tetrahedra_apart_by_more_than(edges, 0.99 * g));
  EXPECT_FALSE(tetrahedra_apart_by_more_than(edges, 1.01 * g));

  // overlapping: no gap at all
  double overlapping[2][4][3] = {
    {{0., 0., 0.}, {1., 0., 0.}, {0., 1., 0.}, {0., 0., 1.}},
    {{0.1, 0.1, 0.1}, {1.1, 0.1, 0.1}, {0.1, 1.1, 0.1}, {0.1, 0.1, 1.1}}};
  EXPECT_FALSE(tetrahedra_apart_by_more_than(overlapping, 0.));
}
