// Unit tests of the vector batches of the 3D explicit loop
// (tetrahedral_update.h): every instruction set this processor has gives
// bitwise the tetrahedra's stresses, the nodes' velocities and positions,
// the works and guards, and the face joints' forces, damage and breaks of
// the one-at-a-time evaluation (the kernels called on one tetrahedron or
// joint at a time, as TetrahedralSolver's loops call them).

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <random>
#include <tmfdem/discrete/element_kernel.h>
#include <tmfdem/discrete/joint_kernel.h>
#include <tmfdem/discrete/tetrahedral_update.h>
#include <vector>

using namespace tmfdem::discrete;

namespace
{
  /** The instruction sets with batches that this processor runs. */
  std::vector<VectorInstructions>
  batch_sets()
  {
    std::vector<VectorInstructions> sets;
    for (const auto &[name, set] : vector_instructions_registry())
      if (set != VectorInstructions::none && vector_instructions_supported(set))
        sets.push_back(set);
    return sets;
  }

  bool
  same_bits(const std::vector<double> &a, const std::vector<double> &b)
  {
    return a.size() == b.size() &&
           std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
  }

  /** @p n perturbed tetrahedra of edge 1 cm moving and straining at
   *  random, with random joint forces; tetrahedron 5 inverted. */
  DiscreteModel
  random_tetrahedra(const unsigned int n)
  {
    std::mt19937                           random(7);
    std::uniform_real_distribution<double> sym(-1., 1.);
    const double                           h = 0.01;
    DiscreteModel                          m;
    m.n_elements = n;
    m.n_nodes    = 4 * n;
    for (auto *v : {&m.x, &m.y, &m.z, &m.vx, &m.vy, &m.vz, &m.mass})
      v->resize(4 * n);
    m.inverse_basis.resize(9 * n);
    m.thermal_stretch.resize(n);
    m.stress.resize(6 * n);
    m.node_joint_force.resize(36 * n);
    const double corner[4][3] = {{0, 0, 0}, {h, 0, 0}, {0, h, 0}, {0, 0, h}};
    for (unsigned int e = 0; e < n; ++e)
      {
        double X[4][3];
        for (unsigned int k = 0; k < 4; ++k)
          for (unsigned int i = 0; i < 3; ++i)
            X[k][i] = corner[k][i] + 0.1 * h * sym(random);
        // the inverse of [X1 - X0, X2 - X0, X3 - X0] by cofactors
        double D[3][3];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            D[i][j] = X[j + 1][i] - X[0][i];
        const double det = D[0][0] * (D[1][1] * D[2][2] - D[1][2] * D[2][1]) -
                           D[0][1] * (D[1][0] * D[2][2] - D[1][2] * D[2][0]) +
                           D[0][2] * (D[1][0] * D[2][1] - D[1][1] * D[2][0]);
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int j = 0; j < 3; ++j)
            m.inverse_basis[9 * e + 3 * i + j] =
              (D[(j + 1) % 3][(i + 1) % 3] * D[(j + 2) % 3][(i + 2) % 3] -
               D[(j + 1) % 3][(i + 2) % 3] * D[(j + 2) % 3][(i + 1) % 3]) /
              det;
        m.thermal_stretch[e] = e % 3 == 0 ? 1. : 1. + 0.01 * sym(random);
        for (unsigned int k = 0; k < 4; ++k)
          {
            const unsigned int node = 4 * e + k;
            // strained 1 % at random, tetrahedron 5 turned inside out
            const double flip = e == 5 && k == 3 ? -1. : 1.;
            m.x[node]         = X[k][0] * (1. + 0.01 * sym(random));
            m.y[node]         = X[k][1] * (1. + 0.01 * sym(random));
            m.z[node]         = flip * X[k][2] * (1. + 0.01 * sym(random));
            m.vx[node]        = sym(random);
            m.vy[node]        = sym(random);
            m.vz[node]        = sym(random);
            m.mass[node]      = 1e-3 * (1. + 0.5 * sym(random));
            for (unsigned int i = 0; i < 9; ++i)
              m.node_joint_force[9 * node + i] = 1e3 * sym(random);
          }
      }
    return m;
  }

  /** The element loop of TetrahedralSolver::update_nodes() for free nodes,
   *  one tetrahedron at a time. */
  void
  update_one_at_a_time(DiscreteModel               &m,
                       const TetrahedronBatchInput &in,
                       double                      *works,
                       long long                   *guard)
  {
    for (std::size_t e = 0; e < m.n_elements; ++e)
      {
        const std::size_t   n0            = 4 * e;
        const double *const nodes[3]      = {&m.x[n0], &m.y[n0], &m.z[n0]};
        const double *const velocities[3] = {&m.vx[n0], &m.vy[n0], &m.vz[n0]};
        const double        s             = m.thermal_stretch[e];
        ElementResponse<3, double> r;
        element_response<3, double>(nodes,
                                    velocities,
                                    &m.inverse_basis[9 * e],
                                    s == 1. ? 1. : 1. / s,
                                    in.lame[e].mu,
                                    in.lame[e].lambda,
                                    in.anisotropy != nullptr ?
                                      &in.anisotropy[anisotropy_size<3> * e] :
                                      nullptr,
                                    in.viscosity[e],
                                    r);
        if (!(r.det > 0.) && guard[0] < 0)
          guard[0] = e;
        double *stress = &m.stress[6 * e];
        stress[0]      = r.stress[0][0] + r.viscous[0][0];
        stress[1]      = r.stress[1][1] + r.viscous[1][1];
        stress[2]      = r.stress[2][2] + r.viscous[2][2];
        stress[3]      = r.stress[0][1] + r.viscous[0][1];
        stress[4]      = r.stress[1][2] + r.viscous[1][2];
        stress[5]      = r.stress[0][2] + r.viscous[0][2];
        for (unsigned int k = 0; k < 4; ++k)
          {
            const std::size_t node = n0 + k;
            const double     *jf   = &m.node_joint_force[9 * node];
            const double      mass = m.mass[node];
            const double      b_m  = in.damp_b / mass;
            double           *v[3] = {&m.vx[node], &m.vy[node], &m.vz[node]};
            double           *x[3] = {&m.x[node], &m.y[node], &m.z[node]};
            for (unsigned int i = 0; i < 3; ++i)
              {
                const double f_joint = jf[i] + jf[3 + i] + jf[6 + i];
                const double f =
                  r.f_elastic[k][i] + r.f_viscous[k][i] + f_joint;
                const double v_old = *v[i];
                const double v_new =
                  damped_velocity<double>(in.damp_a, v_old, b_m, f);
                const double travel = half_step_travel(in.dt, v_old, v_new);
                const TetrahedronNodeWorks<double> w =
                  tetrahedron_node_works<double>(r.f_elastic[k][i],
                                                 r.f_viscous[k][i],
                                                 f_joint,
                                                 0.,
                                                 travel,
                                                 in.c_m,
                                                 mass,
                                                 in.dt);
                works[0] += w.elastic;
                works[1] += w.viscous;
                works[2] += w.joint;
                works[3] += w.reaction;
                works[4] += w.damping;
                *v[i] = v_new;
                *x[i] += in.dt * v_new;
                if (!(std::abs(v_new) < 1e300) && guard[1] < 0)
                  guard[1] = node;
              }
          }
      }
  }
} // namespace

// The element batches of every instruction set against one tetrahedron at a
// time, an inverted tetrahedron among them, with viscosity and mass damping,
// without and with the anisotropic correction of joint compliance
// compensation.
TEST(TetrahedralBatches, ElementsMatchOneAtATimeBitwise)
{
  const unsigned int         n = 16; // whole batches of 8, 4 and 2
  std::vector<LameConstants> lame(n);
  std::vector<double>        eta(n);
  for (unsigned int e = 0; e < n; ++e)
    {
      lame[e].mu     = 4e9 * (1. + 0.01 * e);
      lame[e].lambda = 4e9 * (1. - 0.01 * e);
      eta[e]         = e % 2 == 0 ? 0. : 1e3 * e;
    }
  TetrahedronBatchInput in;
  in.lame      = lame.data();
  in.viscosity = eta.data();
  in.dt        = 1e-7;
  in.c_m       = 50.;
  in.damp_a    = (1. - 0.5 * in.c_m * in.dt) / (1. + 0.5 * in.c_m * in.dt);
  in.damp_b    = in.dt / (1. + 0.5 * in.c_m * in.dt);
  std::vector<double> anisotropy(anisotropy_size<3> * n);
  for (std::size_t k = 0; k < anisotropy.size(); ++k)
    anisotropy[k] = 1e9 * std::sin(0.37 * k + 0.1);
  for (const bool anisotropic : {false, true})
    {
      SCOPED_TRACE(anisotropic ? "anisotropic" : "isotropic");
      in.anisotropy = anisotropic ? anisotropy.data() : nullptr;

      const DiscreteModel start = random_tetrahedra(n);
      DiscreteModel       expected(start);
      double              expected_works[5] = {0., 0., 0., 0., 0.};
      long long           expected_guard[2] = {-1, -1};
      update_one_at_a_time(expected, in, expected_works, expected_guard);
      EXPECT_EQ(expected_guard[0], 5);
      EXPECT_EQ(expected_guard[1], -1);

      const auto sets = batch_sets();
      EXPECT_FALSE(sets.empty());
      for (const VectorInstructions set : sets)
        {
          SCOPED_TRACE(vector_instructions_name(set));
          const TetrahedronBatchKernel kernel = tetrahedron_batch_kernel(set);
          ASSERT_NE(kernel, nullptr);
          DiscreteModel m(start);
          double        works[5] = {0., 0., 0., 0., 0.};
          long long     guard[2] = {-1, -1};
          for (std::size_t e = 0; e < n; e += vector_lanes(set))
            kernel(m, e, in, works, guard);
          EXPECT_TRUE(same_bits(m.x, expected.x));
          EXPECT_TRUE(same_bits(m.y, expected.y));
          EXPECT_TRUE(same_bits(m.z, expected.z));
          EXPECT_TRUE(same_bits(m.vx, expected.vx));
          EXPECT_TRUE(same_bits(m.vy, expected.vy));
          EXPECT_TRUE(same_bits(m.vz, expected.vz));
          EXPECT_TRUE(same_bits(m.stress, expected.stress));
          EXPECT_EQ(std::memcmp(works, expected_works, sizeof(works)), 0);
          EXPECT_EQ(guard[0], expected_guard[0]);
          EXPECT_EQ(guard[1], expected_guard[1]);
        }
    }
}

namespace
{
  /** @p n face joints between the faces 0 of tetrahedra 2 j and 2 j + 1
   *  (nodes 0, 1, 2 of each): elastic, softening (damaged before) and
   *  breaking ones. */
  DiscreteModel
  random_face_joints(const unsigned int n, const SofteningLaw law)
  {
    std::mt19937                           random(11);
    std::uniform_real_distribution<double> sym(-1., 1.);
    const double                           h = 0.01;
    DiscreteModel                          m;
    m.n_elements = 2 * n;
    m.n_nodes    = 8 * n;
    m.n_joints   = n;
    for (auto *v : {&m.x, &m.y, &m.z})
      v->resize(8 * n);
    m.node_joint_force.assign(72 * n, 0.);
    m.joint_nodes.resize(6 * n);
    m.joint_constants.resize(n);
    m.joint_damage.resize(3 * n);
    m.joint_status.assign(n, JointStatus::intact);
    m.joint_break_time.assign(n, -1.);
    for (unsigned int j = 0; j < n; ++j)
      {
        EXPECT_TRUE(make_joint_constants(3e6,
                                         8e6,
                                         30.,
                                         120.,
                                         600.,
                                         1e11,
                                         1e11,
                                         h * (1. + 0.1 * sym(random)),
                                         law,
                                         m.joint_constants[j]));
        // gaps: below the peak, softening, broken (lanes 1, 2, 3 of 4)
        const double gap = j % 4 == 0 ? 1e-7 :
                           j % 4 == 1 ? 1e-5 :
                           j % 4 == 2 ? 1e-4 :
                                        1e-1;
        for (unsigned int q = 0; q < 3; ++q)
          m.joint_damage[3 * j + q] = j % 3 == 1 ? 0.3 : 0.;
        double origin[3], e1[3], e2[3];
        for (unsigned int i = 0; i < 3; ++i)
          {
            origin[i] = 0.1 * sym(random);
            e1[i]     = h * sym(random);
            e2[i]     = h * sym(random);
          }
        for (unsigned int k = 0; k < 3; ++k)
          {
            const unsigned int a = 8 * j + k, b = 8 * j + 4 + k;
            m.joint_nodes[6 * j + k]     = a;
            m.joint_nodes[6 * j + 3 + k] = b;
            double *xa[3]                = {&m.x[a], &m.y[a], &m.z[a]};
            double *xb[3]                = {&m.x[b], &m.y[b], &m.z[b]};
            for (unsigned int i = 0; i < 3; ++i)
              {
                *xa[i] = origin[i] + (k == 1 ? e1[i] : k == 2 ? e2[i] : 0.);
                *xb[i] = *xa[i] + gap * sym(random);
              }
          }
      }
    return m;
  }

  /** The face-joint loop of TetrahedralSolver::compute_joint_forces() for
   *  intact joints, one at a time. */
  template <SofteningLaw law>
  void
  joints_one_at_a_time(DiscreteModel       &m,
                       const unsigned char *joint_face,
                       const double         time,
                       char                &broke)
  {
    for (std::size_t j = 0; j < m.n_joints; ++j)
      {
        const unsigned int *p = &m.joint_nodes[6 * j];
        double              x[3][6];
        for (unsigned int k = 0; k < 6; ++k)
          {
            x[0][k] = m.x[p[k]];
            x[1][k] = m.y[p[k]];
            x[2][k] = m.z[p[k]];
          }
        const double *const           nodes[3] = {x[0], x[1], x[2]};
        const FaceJointFrameT<double> g = face_joint_frame<double>(nodes);
        FaceJointResponse<double>     r;
        double                       *damage = &m.joint_damage[3 * j];
        face_joint_response<law>(g, m.joint_constants[j], damage, r);
        double f[2][3][3];
        if (damage[0] >= 1. && damage[1] >= 1. && damage[2] >= 1.)
          {
            mark_face_joint_broken(m, j, r.d_opening, r.d_slip, time);
            broke = 1;
            for (auto &side : f)
              for (auto &node : side)
                node[0] = node[1] = node[2] = 0.;
          }
        else
          for (unsigned int k = 0; k < 3; ++k)
            for (unsigned int i = 0; i < 3; ++i)
              {
                f[0][k][i] = r.a[k][i] + r.frame[k][i];
                f[1][k][i] = -r.a[k][i] + r.frame[k][i];
              }
        write_face_joint_forces(m, j, joint_face, f);
      }
  }

  template <SofteningLaw law>
  void
  check_face_joint_batches()
  {
    const unsigned int               n = 16;
    const std::vector<unsigned char> joint_face(2 * n, 0);
    const DiscreteModel              start = random_face_joints(n, law);
    DiscreteModel                    expected(start);
    char                             expected_broke = 0;
    joints_one_at_a_time<law>(expected, joint_face.data(), 0.5, expected_broke);
    // some joints broke, some soften, some stay below the peak
    EXPECT_EQ(expected_broke, 1);
    EXPECT_EQ(expected.joint_status[0], JointStatus::intact);
    EXPECT_NE(expected.joint_status[3], JointStatus::intact);
    EXPECT_GT(expected.joint_damage[3 * 2], 0.);
    EXPECT_LT(expected.joint_damage[3 * 2], 1.);
    for (const VectorInstructions set : batch_sets())
      {
        SCOPED_TRACE(vector_instructions_name(set));
        const FaceJointBatchKernel kernel = face_joint_batch_kernel(set, law);
        ASSERT_NE(kernel, nullptr);
        DiscreteModel m(start);
        char          broke = 0;
        for (std::size_t j = 0; j < n; j += vector_lanes(set))
          kernel(m, j, joint_face.data(), 0.5, broke);
        EXPECT_EQ(broke, expected_broke);
        EXPECT_TRUE(same_bits(m.node_joint_force, expected.node_joint_force));
        EXPECT_TRUE(same_bits(m.joint_damage, expected.joint_damage));
        EXPECT_TRUE(same_bits(m.joint_break_time, expected.joint_break_time));
        EXPECT_TRUE(m.joint_status == expected.joint_status);
      }
  }
} // namespace

// The face-joint batches of every instruction set against one joint at a
// time: below the peak, softening, damaged before, and breaking.
TEST(TetrahedralBatches, FaceJointsMatchOneAtATimeBitwise)
{
  check_face_joint_batches<SofteningLaw::munjiza>();
  check_face_joint_batches<SofteningLaw::linear>();
}
