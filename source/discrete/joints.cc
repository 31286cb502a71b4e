#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/heterogeneity.h>
#include <tmfdem/discrete/joint_kernel.h>
#include <tmfdem/discrete/joints.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      /** Joint elements per chunk of the threaded loop. */
      constexpr unsigned int joint_chunk_size = 512;

      /**
       * Joints whose frames (a square root and a division each) are formed
       * ahead of their tractions: independent of each other, the long
       * latencies of a block overlap instead of stalling every joint.
       */
      constexpr unsigned int frame_block_size = 32;

      /** The frame of joint @p j at the current state (joint_frame()). */
      inline JointFrameT<double>
      joint_frame_of(const DiscreteModel &m, const unsigned int j)
      {
        const unsigned int *n = &m.joint_nodes[4 * j];
        double              x[4], y[4];
        for (unsigned int a = 0; a < 4; ++a)
          {
            x[a] = m.x[n[a]];
            y[a] = m.y[n[a]];
          }
        return joint_frame(x, y);
      }

      /**
       * Writes the forces of joint @p j to DiscreteModel::node_joint_force
       * (JointResponse: the tractions' forces on a0, a1 and the frame
       * force): a0 and b1 start the joint's edge (slot 0), a1 and b0 end it
       * (slot 2).
       */
      inline void
      write_joint_forces(DiscreteModel    &m,
                         const std::size_t j,
                         const double      a0x,
                         const double      a0y,
                         const double      a1x,
                         const double      a1y,
                         const double      frame_x,
                         const double      frame_y)
      {
        const unsigned int *n  = &m.joint_nodes[4 * j];
        double             *a0 = &m.node_joint_force[4 * n[0]];
        double             *a1 = &m.node_joint_force[4 * n[1]];
        double             *b0 = &m.node_joint_force[4 * n[2]];
        double             *b1 = &m.node_joint_force[4 * n[3]];
        a0[0]                  = a0x + frame_x;
        a0[1]                  = a0y + frame_y;
        a1[2]                  = a1x - frame_x;
        a1[3]                  = a1y - frame_y;
        b0[2]                  = frame_x - a0x;
        b0[3]                  = frame_y - a0y;
        b1[0]                  = -a1x - frame_x;
        b1[1]                  = -a1y - frame_y;
      }

      /**
       * The forces of the joints j0 ... j0 + joint_lanes - 1 if all are
       * intact and undamaged and stay below their peaks at both Gauss points
       * (the cohesive law's rising branch, no new damage: the common case),
       * written to DiscreteModel::node_joint_force; returns true. One joint
       * per lane through joint_response(), the kernel of the joint-by-joint
       * loop, so the forces are bitwise those of that loop. Returns false,
       * having written nothing, where any joint of the batch needs that
       * loop (damaged, broken, softening). Where some joint of the batch is
       * closed at one end only, every lane forms the closed part and the others
       * discard it. Compiled once per instruction set (the wrappers
       * below); the softening law does not matter below the peak.
       */
      template <unsigned int joint_lanes>
      __attribute__((always_inline)) inline bool
      elastic_joint_batch(DiscreteModel &m, const std::size_t j0)
      {
        using JointLanes = typename LaneVector<joint_lanes>::type;
        for (unsigned int l = 0; l < joint_lanes; ++l)
          if (m.joint_status[j0 + l] != JointStatus::intact ||
              m.joint_damage[2 * (j0 + l)] != 0. ||
              m.joint_damage[2 * (j0 + l) + 1] != 0.)
            return false;
        JointLanes x[4], y[4];
        for (unsigned int l = 0; l < joint_lanes; ++l)
          {
            const unsigned int *n = &m.joint_nodes[4 * (j0 + l)];
            for (unsigned int a = 0; a < 4; ++a)
              {
                x[a][l] = m.x[n[a]];
                y[a][l] = m.y[n[a]];
              }
          }
        const JointFrameT<JointLanes>        g = joint_frame(x, y);
        const JointConstantLanes<JointLanes> k(&m.joint_constants[j0]);
        JointLanes                           damage[2] = {};
        JointResponse<JointLanes>            f;
        joint_response<SofteningLaw::linear, false>(g, k, damage, f);
        if (any_lane(f.beyond_peak))
          return false;
        for (unsigned int l = 0; l < joint_lanes; ++l)
          write_joint_forces(m,
                             j0 + l,
                             f.a0x[l],
                             f.a0y[l],
                             f.a1x[l],
                             f.a1y[l],
                             f.frame_x[l],
                             f.frame_y[l]);
        return true;
      }

      /** The joint batch compiled for each instruction set. */
      using JointBatchKernel = bool (*)(DiscreteModel &, const std::size_t);

#if defined(__x86_64__)
      __attribute__((target("avx512f"))) bool
      elastic_joint_batch_avx512(DiscreteModel &m, const std::size_t j0)
      {
        return elastic_joint_batch<8>(m, j0);
      }

      __attribute__((target("avx2"))) bool
      elastic_joint_batch_avx2(DiscreteModel &m, const std::size_t j0)
      {
        return elastic_joint_batch<4>(m, j0);
      }
#endif

      bool
      elastic_joint_batch_baseline(DiscreteModel &m, const std::size_t j0)
      {
        return elastic_joint_batch<2>(m, j0);
      }

      /** The kernel of @p instructions, or nullptr (joint by joint). */
      JointBatchKernel
      joint_batch_kernel(const VectorInstructions instructions)
      {
        switch (instructions)
          {
#if defined(__x86_64__)
            case VectorInstructions::avx512:
              return elastic_joint_batch_avx512;
            case VectorInstructions::avx2:
              return elastic_joint_batch_avx2;
#endif
            case VectorInstructions::none:
              return nullptr;
            default:
              return elastic_joint_batch_baseline;
          }
      }

      template <SofteningLaw law>
      bool
      compute_joint_forces_with(DiscreteModel                &m,
                                const double                  t,
                                tbb::task_arena              &arena,
                                std::vector<JointChunkTally> &tally,
                                const JointSubset            &subset,
                                const VectorInstructions      instructions)
      {
        const JointBatchKernel batch_kernel = joint_batch_kernel(instructions);
        const unsigned int     joint_lanes  = vector_lanes(instructions);
        // the joints of the subset: a range, then a list (partition.h)
        const std::size_t n_range = subset.end - subset.begin;
        const std::size_t n       = n_range + subset.others.size();
        tally.assign((n + joint_chunk_size - 1) / joint_chunk_size,
                     JointChunkTally());
        for_each_chunk(
          arena,
          n,
          joint_chunk_size,
          [&](const std::size_t begin,
              const std::size_t end,
              const std::size_t c) {
            JointFrameT<double> frames[frame_block_size];
            for (std::size_t block_begin = begin; block_begin < end;
                 block_begin += frame_block_size)
              {
                const std::size_t block_end =
                  std::min<std::size_t>(end, block_begin + frame_block_size);
                // batches of elastic joints, vectorised; the rest below
                std::uint32_t vectorised = 0;
                for (std::size_t b = block_begin;
                     batch_kernel != nullptr &&
                     b + joint_lanes <=
                       std::min<std::size_t>(block_end, n_range);
                     b += joint_lanes)
                  if (batch_kernel(m, subset.begin + b))
                    {
                      vectorised |= ((1u << joint_lanes) - 1)
                                    << (b - block_begin);
                      tally[c].intact += joint_lanes;
                      tally[c].vectorised += joint_lanes;
                    }
                // the frames of the block's other intact joints
                for (std::size_t b = block_begin; b < block_end; ++b)
                  {
                    const std::size_t jb = b < n_range ?
                                             subset.begin + b :
                                             subset.others[b - n_range];
                    if (!(vectorised >> (b - block_begin) & 1u) &&
                        m.joint_status[jb] == JointStatus::intact)
                      frames[b - block_begin] = joint_frame_of(m, jb);
                  }
                for (std::size_t i = block_begin; i < block_end; ++i)
                  {
                    const std::size_t block = i - block_begin;
                    if (vectorised >> block & 1u)
                      continue;
                    const std::size_t j = i < n_range ?
                                            subset.begin + i :
                                            subset.others[i - n_range];
                    if (m.joint_status[j] != JointStatus::intact)
                      continue;
                    ++tally[c].intact;
                    JointResponse<double> f;
                    joint_response<law>(frames[block],
                                        m.joint_constants[j],
                                        &m.joint_damage[2 * j],
                                        f);
                    if (m.joint_damage[2 * j] >= 1. &&
                        m.joint_damage[2 * j + 1] >= 1.)
                      {
                        const double d_o = f.d_opening, d_s = f.d_slip;
                        const double ratio =
                          d_o * d_o / std::max(1e-300, d_o * d_o + d_s * d_s);
                        m.joint_status[j] = ratio > 0.9 ? JointStatus::mode_I :
                                            ratio < 0.1 ? JointStatus::mode_II :
                                                          JointStatus::mixed;
                        m.joint_break_time[j] = t;
                        f.a0x = f.a0y = f.a1x = f.a1y = 0.;
                        f.frame_x = f.frame_y = 0.;
                        tally[c].broke        = true;
                      }
                    write_joint_forces(m,
                                       j,
                                       f.a0x,
                                       f.a0y,
                                       f.a1x,
                                       f.a1y,
                                       f.frame_x,
                                       f.frame_y);
                  }
              }
          });
        for (const JointChunkTally &t : tally)
          if (t.broke)
            return true;
        return false;
      }
    } // namespace

    void
    setup_joint_constants(const Parameters  &parameters,
                          const SofteningLaw softening_law,
                          DiscreteModel     &model)
    {
      const auto &dm = parameters.get<DiscreteMechanicsParameters>();
      const std::vector<double> strength_factor =
        random_strength_factors(dm, model);
      for (unsigned int j = 0; j < model.n_joints; ++j)
        {
          const unsigned int        ea = model.joint_elements[2 * j];
          const unsigned int        eb = model.joint_elements[2 * j + 1];
          const MaterialProperties &ma =
            parameters.materials[model.material[ea]];
          const MaterialProperties &mb =
            parameters.materials[model.material[eb]];
          // interfaces between materials take the weaker of both
          double       ft  = std::min(ma.tensile_strength, mb.tensile_strength);
          double       coh = std::min(ma.cohesion, mb.cohesion);
          const double phi = std::min(ma.friction_angle, mb.friction_angle);
          const double GI =
            std::min(ma.fracture_energy_I, mb.fracture_energy_I);
          const double GII =
            std::min(ma.fracture_energy_II, mb.fracture_energy_II);
          const double E = std::max(ma.youngs_modulus, mb.youngs_modulus);
          ft *= strength_factor[j];
          coh *= strength_factor[j];
          const bool ok =
            make_joint_constants(ft,
                                 coh,
                                 phi,
                                 GI,
                                 GII,
                                 dm.joint_normal_penalty_factor * E,
                                 dm.joint_tangential_penalty_factor * E,
                                 model.joint_length[j],
                                 softening_law,
                                 model.joint_constants[j]);
          if (!ok)
            {
              const double h = model.joint_length[j];
              const double stored_I =
                4. / 3. * ft * ft * h / (dm.joint_normal_penalty_factor * E);
              const double stored_II = 4. / 3. * coh * coh * h /
                                       (dm.joint_tangential_penalty_factor * E);
              const bool mode_I = GI <= stored_I;
              throw InputError(
                "joint " + std::to_string(j) + " between materials " +
                std::to_string(model.material[ea]) + " and " +
                std::to_string(model.material[eb]) + " (length " +
                Utilities::to_string(h) + " m): Mode " + (mode_I ? "I" : "II") +
                " fracture energy " + Utilities::to_string(mode_I ? GI : GII) +
                " J/m^2 is below the work stored before the peak, 4 f^2 h / "
                "(3 p) = " +
                Utilities::to_string(mode_I ? stored_I : stored_II) +
                " J/m^2; allowed are larger fracture energies or larger "
                "joint penalty factors (Discrete mechanics).");
            }
        }
    }

    bool
    compute_joint_forces(const SofteningLaw            law,
                         DiscreteModel                &model,
                         const double                  time,
                         tbb::task_arena              &arena,
                         std::vector<JointChunkTally> &tally,
                         const JointSubset            &subset,
                         const VectorInstructions      instructions)
    {
      switch (law)
        {
          case SofteningLaw::linear:
            return compute_joint_forces_with<SofteningLaw::linear>(
              model,
              time,
              arena,
              tally,
              subset,
              instructions);
          case SofteningLaw::munjiza:
            return compute_joint_forces_with<SofteningLaw::munjiza>(
              model,
              time,
              arena,
              tally,
              subset,
              instructions);
        }
      return false;
    }

    namespace
    {
      /** True if joint @p j is intact and undamaged at every Gauss point. */
      bool
      undamaged(const DiscreteModel &model, const unsigned int j)
      {
        if (model.joint_status[j] != JointStatus::intact)
          return false;
        const unsigned int n = model.gauss_points_per_joint();
        for (unsigned int q = 0; q < n; ++q)
          if (model.joint_damage[n * j + q] > 0.)
            return false;
        return true;
      }

      /** A Gauss point's utilisation of the peak strength: the larger of
       *  its opening @p o [m] and slip magnitude @p s [m] over the opening
       *  and slip of the peak (Eq. 34: 2 f_t / k_n, 2 f_s / k_t with the
       *  shear strength f_s raised by the friction of a compressed joint)
       *  [-]. */
      double
      point_utilisation(const JointConstants &k, const double o, const double s)
      {
        const double fs = k.cohesion - (o < 0. ? k.normal_stiffness * o : 0.) *
                                         k.friction_tangent;
        return std::max(o * k.normal_stiffness / (2. * k.tensile_strength),
                        std::abs(s) * k.tangential_stiffness / (2. * fs));
      }
    } // namespace

    void
    joint_utilisations(const DiscreteModel &model,
                       std::vector<double> &utilisation)
    {
      utilisation.assign(model.n_joints, -1.);
      for (unsigned int j = 0; j < model.n_joints; ++j)
        {
          if (!undamaged(model, j))
            continue;
          const JointConstants &k       = model.joint_constants[j];
          double                highest = 0.;
          if (model.dim == 2)
            {
              const JointFrameT<double> g = joint_frame_of(model, j);
              for (const double u : joint_gauss_points)
                {
                  const double dx = (1. - u) * g.d0x + u * g.d1x;
                  const double dy = (1. - u) * g.d0y + u * g.d1y;
                  highest         = std::max(highest,
                                     point_utilisation(k,
                                                       dx * g.nx + dy * g.ny,
                                                       dx * g.tx + dy * g.ty));
                }
            }
          else
            {
              const unsigned int *p = &model.joint_nodes[6 * j];
              double              x[3][6];
              for (unsigned int a = 0; a < 6; ++a)
                {
                  x[0][a] = model.x[p[a]];
                  x[1][a] = model.y[p[a]];
                  x[2][a] = model.z[p[a]];
                }
              const double *const           nodes[3] = {x[0], x[1], x[2]};
              const FaceJointFrameT<double> g = face_joint_frame<double>(nodes);
              for (const auto &lambda : face_joint_gauss_points)
                {
                  double d[3];
                  for (int i = 0; i < 3; ++i)
                    d[i] = lambda[0] * g.d[0][i] + lambda[1] * g.d[1][i] +
                           lambda[2] * g.d[2][i];
                  const double o =
                    d[0] * g.n[0] + d[1] * g.n[1] + d[2] * g.n[2];
                  double s2 = 0.;
                  for (int i = 0; i < 3; ++i)
                    s2 += (d[i] - o * g.n[i]) * (d[i] - o * g.n[i]);
                  highest =
                    std::max(highest, point_utilisation(k, o, std::sqrt(s2)));
                }
            }
          utilisation[j] = std::min(highest, 1.);
        }
    }

    void
    joint_damages(const DiscreteModel &model, std::vector<double> &damage)
    {
      const unsigned int n = model.gauss_points_per_joint();
      damage.resize(model.n_joints);
      for (unsigned int j = 0; j < model.n_joints; ++j)
        {
          double d = 1.;
          if (model.joint_status[j] == JointStatus::intact)
            {
              d = model.joint_damage[n * j];
              for (unsigned int q = 1; q < n; ++q)
                d = std::max(d, model.joint_damage[n * j + q]);
            }
          damage[j] = d;
        }
    }

    unsigned int
    n_damaged_or_broken_joints(const DiscreteModel &model)
    {
      unsigned int n = 0;
      for (unsigned int j = 0; j < model.n_joints; ++j)
        n += !undamaged(model, j);
      return n;
    }
  } // namespace discrete
} // namespace tmfdem
