#include <deal.II/base/utilities.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <tmfdem/base/exceptions.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <tmfdem/discrete/heterogeneity.h>
#include <tmfdem/discrete/joints.h>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      /** Gauss points of a joint, parameter u in [0, 1] along the edge. */
      constexpr double gauss_0 = 0.21132486540518713,
                       gauss_1 = 0.78867513459481287;

      /** Joint elements per chunk of the threaded loop. */
      constexpr unsigned int joint_chunk_size = 512;

      /**
       * Joints whose frames (a square root and a division each) are formed
       * ahead of their tractions: independent of each other, the long
       * latencies of a block overlap instead of stalling every joint.
       */
      constexpr unsigned int frame_block_size = 32;

      /**
       * The frame of joint @p j at the current state: the gaps d0, d1 of
       * its two node pairs (B - A) and the unit tangent and normal of the
       * mean edge (normal outward of element A).
       */
      struct JointFrame
      {
        double d0x, d0y, d1x, d1y;
        double L, tx, ty, nx, ny;
      };

      inline JointFrame
      joint_frame(const DiscreteModel &m, const unsigned int j)
      {
        JointFrame          g;
        const unsigned int *n = &m.joint_nodes[4 * j];
        g.d0x                 = m.x[n[2]] - m.x[n[0]];
        g.d0y                 = m.y[n[2]] - m.y[n[0]];
        g.d1x                 = m.x[n[3]] - m.x[n[1]];
        g.d1y                 = m.y[n[3]] - m.y[n[1]];
        const double ex = 0.5 * (m.x[n[1]] + m.x[n[3]] - m.x[n[0]] - m.x[n[2]]);
        const double ey = 0.5 * (m.y[n[1]] + m.y[n[3]] - m.y[n[0]] - m.y[n[2]]);
        g.L             = std::sqrt(ex * ex + ey * ey);
        const double inverse_L = 1. / g.L;
        g.tx                   = ex * inverse_L;
        g.ty                   = ey * inverse_L;
        g.nx                   = g.ty;
        g.ny                   = -g.tx;
        return g;
      }

      /** Is the comparison @p mask true in some lane? */
      template <typename Mask>
      inline bool
      any_lane(const Mask mask)
      {
        for (unsigned int l = 0; l < sizeof(Mask) / sizeof(long long); ++l)
          if (mask[l] != 0)
            return true;
        return false;
      }

      /** |v| lane by lane (the sign bit cleared, as std::abs). */
      template <typename Lanes, typename Mask>
      inline Lanes
      lanes_abs(const Lanes v)
      {
        return reinterpret_cast<Lanes>(reinterpret_cast<Mask>(v) &
                                       0x7fffffffffffffffLL);
      }

      /**
       * The forces of the joints j0 ... j0 + joint_lanes - 1 if all are
       * intact and undamaged and stay below their peaks at both Gauss points
       * (the cohesive law's rising branch, z = 1, no new damage: the common
       * case), written to DiscreteModel::node_joint_force; returns true. The
       * operations are those of joint_frame(), cohesive_traction() and
       * joint_closed_part() in the same order, one joint per lane (no FMA
       * contraction: this file is compiled with -ffp-contract=off), so the
       * forces are bitwise those of the joint-by-joint loop. Returns false,
       * having written nothing, where any joint of the batch needs that
       * loop (damaged, broken, softening). Compiled once per instruction
       * set (the wrappers below).
       */
      template <unsigned int joint_lanes>
      __attribute__((always_inline)) inline bool
      elastic_joint_batch(DiscreteModel &m, const std::size_t j0)
      {
        using JointLanes = typename LaneVector<joint_lanes>::type;
        using JointMask  = typename LaneVector<joint_lanes>::mask;
        for (unsigned int l = 0; l < joint_lanes; ++l)
          if (m.joint_status[j0 + l] != JointStatus::intact ||
              m.joint_damage[2 * (j0 + l)] != 0. ||
              m.joint_damage[2 * (j0 + l) + 1] != 0.)
            return false;
        // joint_frame()
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
        const JointLanes d0x = x[2] - x[0], d0y = y[2] - y[0];
        const JointLanes d1x = x[3] - x[1], d1y = y[3] - y[1];
        const JointLanes ex = 0.5 * (x[1] + x[3] - x[0] - x[2]);
        const JointLanes ey = 0.5 * (y[1] + y[3] - y[0] - y[2]);
        const JointLanes L2 = ex * ex + ey * ey;
        JointLanes       L;
        for (unsigned int l = 0; l < joint_lanes; ++l)
          L[l] = std::sqrt(L2[l]);
        const JointLanes inverse_L = 1. / L;
        const JointLanes tx = ex * inverse_L, ty = ey * inverse_L;
        const JointLanes nx = ty, ny = -tx;
        // the joints' constants
        JointLanes kn, kt, ft, coh, ftan, inv_op, inv_sp;
        for (unsigned int l = 0; l < joint_lanes; ++l)
          {
            const JointConstants &k = m.joint_constants[j0 + l];
            kn[l]                   = k.normal_stiffness;
            kt[l]                   = k.tangential_stiffness;
            ft[l]                   = k.tensile_strength;
            coh[l]                  = k.cohesion;
            ftan[l]                 = k.friction_tangent;
            inv_op[l]               = k.inverse_opening_peak;
            inv_sp[l]               = k.inverse_slip_peak_open;
          }
        const JointLanes zero          = {};
        const JointLanes o_start       = d0x * nx + d0y * ny;
        const JointLanes o_end         = d1x * nx + d1y * ny;
        const JointMask  partly_closed = (o_start < 0.) != (o_end < 0.);
        JointLanes       fa0x = zero, fa0y = zero, fa1x = zero, fa1y = zero;
        JointMask        beyond_peak = {};
        for (unsigned int q = 0; q < 2; ++q)
          {
            const double     u  = q == 0 ? gauss_0 : gauss_1;
            const JointLanes dx = (1. - u) * d0x + u * d1x;
            const JointLanes dy = (1. - u) * d0y + u * d1y;
            const JointLanes o  = dx * nx + dy * ny;
            const JointLanes s  = dx * tx + dy * ty;
            // cohesive_traction() with z = 1
            const JointMask  closed      = o < 0.;
            const JointLanes compression = closed ? kn * o : zero;
            const JointLanes fs    = closed ? coh - compression * ftan : coh;
            const JointLanes abs_s = lanes_abs<JointLanes, JointMask>(s);
            const JointLanes r     = o * inv_op;
            // the division only where some joint of the batch is closed
            JointLanes r_s = abs_s * inv_sp;
            if (any_lane(closed))
              r_s = closed ? abs_s * kt / (2. * fs) : r_s;
            beyond_peak |= (r > 1.) | (r_s > 1.);
            const JointLanes rising = ft * r * (2. - r);
            const JointLanes normal =
              closed ? compression : (r <= 1. ? rising : ft);
            const JointLanes shear_magnitude =
              fs * (r_s < 1. ? r_s * (2. - r_s) : 1. + zero);
            const JointLanes shear =
              s < 0. ? -shear_magnitude : shear_magnitude;
            const JointLanes w      = 0.5 * L;
            const JointLanes n_used = (partly_closed & closed) ? zero : normal;
            const JointLanes px     = w * (n_used * nx + shear * tx);
            const JointLanes py     = w * (n_used * ny + shear * ty);
            fa0x += (1. - u) * px;
            fa0y += (1. - u) * py;
            fa1x += u * px;
            fa1y += u * py;
          }
        for (unsigned int l = 0; l < joint_lanes; ++l)
          if (beyond_peak[l])
            return false;
        // joint_closed_part() where the joint is closed at one end only
        if (any_lane(partly_closed))
          {
            const JointMask  at_start = o_start < 0.;
            const JointLanes oc       = at_start ? o_start : o_end;
            const JointLanes oo       = at_start ? o_end : o_start;
            const JointLanes w        = oc / (oc - oo);
            const JointLanes scale    = kn * L * oc;
            const JointLanes closed   = scale * w * (0.5 - w / 6.);
            const JointLanes open     = scale * w * w / 6.;
            const JointLanes f_start  = at_start ? closed : open;
            const JointLanes f_end    = at_start ? open : closed;
            fa0x = partly_closed ? fa0x + f_start * nx : fa0x;
            fa0y = partly_closed ? fa0y + f_start * ny : fa0y;
            fa1x = partly_closed ? fa1x + f_end * nx : fa1x;
            fa1y = partly_closed ? fa1y + f_end * ny : fa1y;
          }
        // a0 and b1 start the joint's edge (slot 0), a1 and b0 end it
        // (slot 2): DiscreteModel::node_joint_force
        for (unsigned int l = 0; l < joint_lanes; ++l)
          {
            const unsigned int *n  = &m.joint_nodes[4 * (j0 + l)];
            double             *a0 = &m.node_joint_force[4 * n[0]];
            double             *a1 = &m.node_joint_force[4 * n[1]];
            double             *b0 = &m.node_joint_force[4 * n[2]];
            double             *b1 = &m.node_joint_force[4 * n[3]];
            a0[0]                  = fa0x[l];
            a0[1]                  = fa0y[l];
            a1[2]                  = fa1x[l];
            a1[3]                  = fa1y[l];
            b0[2]                  = -fa0x[l];
            b0[3]                  = -fa0y[l];
            b1[0]                  = -fa1x[l];
            b1[1]                  = -fa1y[l];
          }
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
            JointFrame frames[frame_block_size];
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
                      frames[b - block_begin] = joint_frame(m, jb);
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
                    const JointFrame     &g = frames[block];
                    const JointConstants &k = m.joint_constants[j];
                    double fa0x = 0, fa0y = 0, fa1x = 0, fa1y = 0;
                    double last_do = 0., last_ds = 0.;
                    // the openings at the two ends: a joint closed at one end
                    // and open at the other takes its compression exactly
                    // (below), not at the Gauss points
                    const double o_start       = g.d0x * g.nx + g.d0y * g.ny;
                    const double o_end         = g.d1x * g.nx + g.d1y * g.ny;
                    const bool   partly_closed = (o_start < 0.) != (o_end < 0.);
                    for (unsigned int q = 0; q < 2; ++q)
                      {
                        const double        u  = q == 0 ? gauss_0 : gauss_1;
                        const double        dx = (1. - u) * g.d0x + u * g.d1x;
                        const double        dy = (1. - u) * g.d0y + u * g.d1y;
                        const double        o  = dx * g.nx + dy * g.ny;
                        const double        s  = dx * g.tx + dy * g.ty;
                        const JointTraction tr =
                          cohesive_traction<law>(o,
                                                 s,
                                                 k,
                                                 m.joint_damage[2 * j + q]);
                        last_do = std::max(last_do, tr.d_opening);
                        last_ds = std::max(last_ds, tr.d_slip);
                        // traction on A (pulls A toward B), weight L/2
                        const double w = 0.5 * g.L;
                        const double normal =
                          partly_closed && o < 0. ? 0. : tr.normal;
                        const double px = w * (normal * g.nx + tr.shear * g.tx);
                        const double py = w * (normal * g.ny + tr.shear * g.ty);
                        fa0x += (1. - u) * px;
                        fa0y += (1. - u) * py;
                        fa1x += u * px;
                        fa1y += u * py;
                      }
                    if (partly_closed)
                      {
                        // k_n o(u) over the closed part, with the shape
                        // functions of the two ends (joint_closed_part())
                        const ClosedPart c =
                          joint_closed_part(o_start, o_end, g.L, k);
                        fa0x += c.force_start * g.nx;
                        fa0y += c.force_start * g.ny;
                        fa1x += c.force_end * g.nx;
                        fa1y += c.force_end * g.ny;
                      }
                    if (m.joint_damage[2 * j] >= 1. &&
                        m.joint_damage[2 * j + 1] >= 1.)
                      {
                        const double ratio =
                          last_do * last_do /
                          std::max(1e-300,
                                   last_do * last_do + last_ds * last_ds);
                        m.joint_status[j] = ratio > 0.9 ? JointStatus::mode_I :
                                            ratio < 0.1 ? JointStatus::mode_II :
                                                          JointStatus::mixed;
                        m.joint_break_time[j] = t;
                        fa0x = fa0y = fa1x = fa1y = 0.;
                        tally[c].broke            = true;
                      }
                    // a0 and b1 start the joint's edge (slot 0), a1 and b0 end
                    // it (slot 2): DiscreteModel::node_joint_force
                    const unsigned int *nodes = &m.joint_nodes[4 * j];
                    double             *a0 = &m.node_joint_force[4 * nodes[0]];
                    double             *a1 = &m.node_joint_force[4 * nodes[1]];
                    double             *b0 = &m.node_joint_force[4 * nodes[2]];
                    double             *b1 = &m.node_joint_force[4 * nodes[3]];
                    a0[0]                  = fa0x;
                    a0[1]                  = fa0y;
                    a1[2]                  = fa1x;
                    a1[3]                  = fa1y;
                    b0[2]                  = -fa0x;
                    b0[3]                  = -fa0y;
                    b1[0]                  = -fa1x;
                    b1[1]                  = -fa1y;
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

    void
    joint_utilisations(const DiscreteModel &model,
                       std::vector<double> &utilisation)
    {
      utilisation.assign(model.n_joints, -1.);
      for (unsigned int j = 0; j < model.n_joints; ++j)
        {
          if (model.joint_status[j] != JointStatus::intact ||
              model.joint_damage[2 * j] > 0. ||
              model.joint_damage[2 * j + 1] > 0.)
            continue;
          const JointFrame      g       = joint_frame(model, j);
          const JointConstants &k       = model.joint_constants[j];
          double                highest = 0.;
          for (const double u : {gauss_0, gauss_1})
            {
              const double dx = (1. - u) * g.d0x + u * g.d1x;
              const double dy = (1. - u) * g.d0y + u * g.d1y;
              const double o  = dx * g.nx + dy * g.ny;
              const double s  = dx * g.tx + dy * g.ty;
              const double fs =
                k.cohesion -
                (o < 0. ? k.normal_stiffness * o : 0.) * k.friction_tangent;
              highest =
                std::max({highest,
                          o * k.normal_stiffness / (2. * k.tensile_strength),
                          std::abs(s) * k.tangential_stiffness / (2. * fs)});
            }
          utilisation[j] = std::min(highest, 1.);
        }
    }

    void
    joint_damages(const DiscreteModel &model, std::vector<double> &damage)
    {
      damage.resize(model.n_joints);
      for (unsigned int j = 0; j < model.n_joints; ++j)
        damage[j] =
          model.joint_status[j] != JointStatus::intact ?
            1. :
            std::max(model.joint_damage[2 * j], model.joint_damage[2 * j + 1]);
    }

    unsigned int
    n_damaged_or_broken_joints(const DiscreteModel &model)
    {
      unsigned int n = 0;
      for (unsigned int j = 0; j < model.n_joints; ++j)
        n += model.joint_status[j] != JointStatus::intact ||
             model.joint_damage[2 * j] > 0. ||
             model.joint_damage[2 * j + 1] > 0.;
      return n;
    }
  } // namespace discrete
} // namespace tmfdem
