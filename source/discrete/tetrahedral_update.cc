/**
 * @file
 * The vector batches of the 3D explicit step (TetrahedralSolver): the
 * element loop (element_response<3>(), the node update and the works) and
 * the face-joint loop (face_joint_frame(), face_joint_response()), one
 * tetrahedron or joint per lane of a GCC vector, compiled once per
 * instruction set (AVX-512, AVX2, SSE2) and chosen at run time
 * (tetrahedral_update.h). The kernels are those of the one-at-a-time loop
 * in tetrahedral_solver.cc, called on lanes; this file is compiled without
 * FMA contraction (CMakeLists.txt), so every lane's result is bitwise that
 * of that loop.
 */
#include <tmfdem/discrete/element_kernel.h>
#include <tmfdem/discrete/joint_kernel.h>
#include <tmfdem/discrete/tetrahedral_update.h>
#include <utility>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      template <typename Lanes, std::size_t... l>
      __attribute__((always_inline)) inline Lanes
      gather(const double      *p,
             const unsigned int stride,
             std::index_sequence<l...>)
      {
        // one initialiser: the loads are combined as a tree (insertion lane
        // by lane would chain them)
        return Lanes{p[stride * l]...};
      }

      /** The vector of p[0], p[stride], ... (one per lane). */
      template <typename Lanes>
      __attribute__((always_inline)) inline Lanes
      gather(const double *p, const unsigned int stride)
      {
        return gather<Lanes>(
          p,
          stride,
          std::make_index_sequence<sizeof(Lanes) / sizeof(double)>());
      }

      /** p[0], p[stride], ... = the lanes of @p v. */
      template <typename Lanes>
      __attribute__((always_inline)) inline void
      scatter(const Lanes v, double *p, const unsigned int stride)
      {
        for (unsigned int l = 0; l < sizeof(Lanes) / sizeof(double); ++l)
          p[stride * l] = v[l];
      }

      template <typename Lanes, std::size_t... l>
      __attribute__((always_inline)) inline Lanes
      gather_nodes(const double       *v,
                   const unsigned int *nodes,
                   const unsigned int  k,
                   std::index_sequence<l...>)
      {
        return Lanes{v[nodes[6 * l + k]]...};
      }

      /** The vector of v[nodes[k]], v[nodes[6 + k]], ... (node k of
       *  consecutive face joints, DiscreteModel::joint_nodes). */
      template <typename Lanes>
      __attribute__((always_inline)) inline Lanes
      gather_nodes(const double       *v,
                   const unsigned int *nodes,
                   const unsigned int  k)
      {
        return gather_nodes<Lanes>(
          v,
          nodes,
          k,
          std::make_index_sequence<sizeof(Lanes) / sizeof(double)>());
      }

      /**
       * The element batch (TetrahedronBatchKernel) on @p lanes lanes: the
       * operations of TetrahedralSolver::update_nodes() for a free node,
       * element by element in the lanes; the works and guards then in that
       * loop's order.
       */
      template <unsigned int lanes>
      __attribute__((always_inline)) inline void
      update_free_tetrahedra(DiscreteModel               &m,
                             const std::size_t            e0,
                             const TetrahedronBatchInput &in,
                             double                      *works,
                             long long                   *guard)
      {
        using Lanes                   = typename LaneVector<lanes>::type;
        const std::size_t n0          = 4 * e0;
        double *const     position[3] = {m.x.data(), m.y.data(), m.z.data()};
        double *const     velocity[3] = {m.vx.data(), m.vy.data(), m.vz.data()};
        // [component][node], lane l: element e0 + l
        Lanes X[3][4], V[3][4];
        for (unsigned int i = 0; i < 3; ++i)
          for (unsigned int k = 0; k < 4; ++k)
            {
              X[i][k] = gather<Lanes>(position[i] + n0 + k, 4);
              V[i][k] = gather<Lanes>(velocity[i] + n0 + k, 4);
            }
        Lanes ib[9];
        for (unsigned int i = 0; i < 9; ++i)
          ib[i] = gather<Lanes>(&m.inverse_basis[9 * e0 + i], 9);
        // 1 / s (1 / 1 is 1: the scalar loop's shortcut, bit for bit)
        const Lanes inv_s = 1. / gather<Lanes>(&m.thermal_stretch[e0], 1);
        Lanes       mu, lambda;
        for (unsigned int l = 0; l < lanes; ++l)
          {
            mu[l]     = in.lame[e0 + l].mu;
            lambda[l] = in.lame[e0 + l].lambda;
          }
        const Lanes        eta           = gather<Lanes>(&in.viscosity[e0], 1);
        const Lanes *const nodes[3]      = {X[0], X[1], X[2]};
        const Lanes *const velocities[3] = {V[0], V[1], V[2]};
        constexpr int      n_anisotropy  = anisotropy_size<3>;
        Lanes              anisotropy[n_anisotropy];
        if (in.anisotropy != nullptr)
          for (int i = 0; i < n_anisotropy; ++i)
            anisotropy[i] = gather<Lanes>(&in.anisotropy[n_anisotropy * e0 + i],
                                          n_anisotropy);
        ElementResponse<3, Lanes> r;
        element_response<3, Lanes>(nodes,
                                   velocities,
                                   ib,
                                   inv_s,
                                   mu,
                                   lambda,
                                   in.anisotropy != nullptr ? anisotropy :
                                                              nullptr,
                                   eta,
                                   r);
        // xx, yy, zz, xy, yz, xz
        double *stress = &m.stress[6 * e0];
        scatter(r.stress[0][0] + r.viscous[0][0], stress, 6);
        scatter(r.stress[1][1] + r.viscous[1][1], stress + 1, 6);
        scatter(r.stress[2][2] + r.viscous[2][2], stress + 2, 6);
        scatter(r.stress[0][1] + r.viscous[0][1], stress + 3, 6);
        scatter(r.stress[1][2] + r.viscous[1][2], stress + 4, 6);
        scatter(r.stress[0][2] + r.viscous[0][2], stress + 5, 6);
        const Lanes                 zero = {};
        TetrahedronNodeWorks<Lanes> t[4][3];
        Lanes                       abs_v[4][3];
        for (unsigned int k = 0; k < 4; ++k)
          {
            const std::size_t node = n0 + k;
            const double     *jf   = &m.node_joint_force[9 * node];
            const Lanes       mass = gather<Lanes>(&m.mass[node], 4);
            const Lanes       b_m  = in.damp_b / mass;
            for (unsigned int i = 0; i < 3; ++i)
              {
                const Lanes f_joint = gather<Lanes>(jf + i, 36) +
                                      gather<Lanes>(jf + 3 + i, 36) +
                                      gather<Lanes>(jf + 6 + i, 36);
                const Lanes f_gravity = mass * in.gravity[i];
                Lanes       f = r.f_elastic[k][i] + r.f_viscous[k][i] + f_joint;
                if (in.with_gravity)
                  f = f + f_gravity;
                const Lanes v_old = V[i][k];
                const Lanes v_new =
                  damped_velocity<Lanes>(in.damp_a, v_old, b_m, f);
                const Lanes travel = half_step_travel(in.dt, v_old, v_new);
                t[k][i] =
                  tetrahedron_node_works<Lanes>(r.f_elastic[k][i],
                                                r.f_viscous[k][i],
                                                f_joint,
                                                in.with_gravity ? f_gravity :
                                                                  zero,
                                                travel,
                                                in.c_m,
                                                mass,
                                                in.dt);
                scatter(v_new, velocity[i] + node, 4);
                scatter(X[i][k] + in.dt * v_new, position[i] + node, 4);
                abs_v[k][i] = lane_abs(v_new);
              }
          }
        // the sums in the scalar loop's order: element by element, node by
        // node, component by component
        for (unsigned int l = 0; l < lanes; ++l)
          {
            if (!(r.det[l] > 0.) && guard[0] < 0)
              guard[0] = e0 + l;
            for (unsigned int k = 0; k < 4; ++k)
              for (unsigned int i = 0; i < 3; ++i)
                {
                  works[0] += t[k][i].elastic[l];
                  works[1] += t[k][i].viscous[l];
                  works[2] += t[k][i].joint[l];
                  works[3] += t[k][i].reaction[l];
                  works[4] += t[k][i].damping[l];
                  if (!(abs_v[k][i][l] < 1e300) && guard[1] < 0)
                    guard[1] = n0 + 4 * l + k;
                }
          }
      }

      /**
       * The face-joint batch (FaceJointBatchKernel) on @p lanes lanes: the
       * operations of TetrahedralSolver::compute_joint_forces() for an
       * intact joint, joint by joint in the lanes.
       */
      template <unsigned int lanes, SofteningLaw law>
      __attribute__((always_inline)) inline void
      face_joint_batch(DiscreteModel       &m,
                       const std::size_t    j0,
                       const unsigned char *joint_face,
                       const double         time,
                       char                &broke)
      {
        using Lanes = typename LaneVector<lanes>::type;
        // the nodes of the batch after next, scattered over the model:
        // their coordinates and force slots fetched ahead (no effect on
        // the results)
        const std::size_t ahead = j0 + 2 * lanes;
        if (ahead + lanes <= m.n_joints)
          {
            const unsigned int *q = &m.joint_nodes[6 * ahead];
            for (unsigned int n = 0; n < 6 * lanes; ++n)
              {
                __builtin_prefetch(&m.x[q[n]]);
                __builtin_prefetch(&m.y[q[n]]);
                __builtin_prefetch(&m.z[q[n]]);
                __builtin_prefetch(&m.node_joint_force[9 * q[n]], 1);
              }
          }
        // x[component][node], nodes a0, a1, a2, b0, b1, b2
        Lanes               x[3][6];
        const unsigned int *p = &m.joint_nodes[6 * j0];
        for (unsigned int k = 0; k < 6; ++k)
          {
            x[0][k] = gather_nodes<Lanes>(m.x.data(), p, k);
            x[1][k] = gather_nodes<Lanes>(m.y.data(), p, k);
            x[2][k] = gather_nodes<Lanes>(m.z.data(), p, k);
          }
        const Lanes *const              nodes[3] = {x[0], x[1], x[2]};
        const FaceJointFrameT<Lanes>    g = face_joint_frame<Lanes>(nodes);
        const JointConstantLanes<Lanes> k(&m.joint_constants[j0]);
        Lanes                           damage[3];
        for (unsigned int q = 0; q < 3; ++q)
          damage[q] = gather<Lanes>(&m.joint_damage[3 * j0 + q], 3);
        FaceJointResponse<Lanes> r;
        face_joint_response<law>(g, k, damage, r);
        for (unsigned int q = 0; q < 3; ++q)
          scatter(damage[q], &m.joint_damage[3 * j0 + q], 3);
        const auto all_damaged =
          (damage[0] >= 1.) & (damage[1] >= 1.) & (damage[2] >= 1.);
        Lanes fa[3][3], fb[3][3];
        for (unsigned int n = 0; n < 3; ++n)
          for (unsigned int i = 0; i < 3; ++i)
            {
              fa[n][i] = r.a[n][i] + r.frame[n][i];
              fb[n][i] = -r.a[n][i] + r.frame[n][i];
            }
        for (unsigned int l = 0; l < lanes; ++l)
          {
            const std::size_t j = j0 + l;
            double            f[2][3][3]; // side, node, component
            if (all_damaged[l])
              {
                mark_face_joint_broken(m, j, r.d_opening[l], r.d_slip[l], time);
                broke = 1;
                for (auto &side : f)
                  for (auto &node : side)
                    node[0] = node[1] = node[2] = 0.;
              }
            else
              for (unsigned int n = 0; n < 3; ++n)
                for (unsigned int i = 0; i < 3; ++i)
                  {
                    f[0][n][i] = fa[n][i][l];
                    f[1][n][i] = fb[n][i][l];
                  }
            write_face_joint_forces(m, j, joint_face, f);
          }
      }

#if defined(__x86_64__)
      __attribute__((target("avx512f"))) void
      update_free_tetrahedra_avx512(DiscreteModel               &m,
                                    const std::size_t            e0,
                                    const TetrahedronBatchInput &in,
                                    double                      *works,
                                    long long                   *guard)
      {
        update_free_tetrahedra<8>(m, e0, in, works, guard);
      }

      __attribute__((target("avx2"))) void
      update_free_tetrahedra_avx2(DiscreteModel               &m,
                                  const std::size_t            e0,
                                  const TetrahedronBatchInput &in,
                                  double                      *works,
                                  long long                   *guard)
      {
        update_free_tetrahedra<4>(m, e0, in, works, guard);
      }

      template <SofteningLaw law>
      __attribute__((target("avx512f"))) void
      face_joint_batch_avx512(DiscreteModel       &m,
                              const std::size_t    j0,
                              const unsigned char *joint_face,
                              const double         time,
                              char                &broke)
      {
        face_joint_batch<8, law>(m, j0, joint_face, time, broke);
      }

      template <SofteningLaw law>
      __attribute__((target("avx2"))) void
      face_joint_batch_avx2(DiscreteModel       &m,
                            const std::size_t    j0,
                            const unsigned char *joint_face,
                            const double         time,
                            char                &broke)
      {
        face_joint_batch<4, law>(m, j0, joint_face, time, broke);
      }
#endif

      void
      update_free_tetrahedra_baseline(DiscreteModel               &m,
                                      const std::size_t            e0,
                                      const TetrahedronBatchInput &in,
                                      double                      *works,
                                      long long                   *guard)
      {
        update_free_tetrahedra<2>(m, e0, in, works, guard);
      }

      template <SofteningLaw law>
      void
      face_joint_batch_baseline(DiscreteModel       &m,
                                const std::size_t    j0,
                                const unsigned char *joint_face,
                                const double         time,
                                char                &broke)
      {
        face_joint_batch<2, law>(m, j0, joint_face, time, broke);
      }

      template <SofteningLaw law>
      FaceJointBatchKernel
      face_joint_batch_kernel_of(const VectorInstructions instructions)
      {
        switch (instructions)
          {
#if defined(__x86_64__)
            case VectorInstructions::avx512:
              return face_joint_batch_avx512<law>;
            case VectorInstructions::avx2:
              return face_joint_batch_avx2<law>;
#endif
            case VectorInstructions::none:
              return nullptr;
            default:
              return face_joint_batch_baseline<law>;
          }
      }
    } // namespace

    TetrahedronBatchKernel
    tetrahedron_batch_kernel(const VectorInstructions instructions)
    {
      switch (instructions)
        {
#if defined(__x86_64__)
          case VectorInstructions::avx512:
            return update_free_tetrahedra_avx512;
          case VectorInstructions::avx2:
            return update_free_tetrahedra_avx2;
#endif
          case VectorInstructions::none:
            return nullptr;
          default:
            return update_free_tetrahedra_baseline;
        }
    }

    FaceJointBatchKernel
    face_joint_batch_kernel(const VectorInstructions instructions,
                            const SofteningLaw       law)
    {
      return law == SofteningLaw::linear ?
               face_joint_batch_kernel_of<SofteningLaw::linear>(instructions) :
               face_joint_batch_kernel_of<SofteningLaw::munjiza>(instructions);
    }
  } // namespace discrete
} // namespace tmfdem
