/**
 * @file
 * The hot path of the discrete layer: one fused pass over the elements per
 * explicit step (paper Eq. 2). Per element: F and the elastic (Eq. 44 on
 * F_e = F / s) and viscous stresses, their nodal forces, the joint forces
 * (joints.cc) and contact forces (contact_system.cc) gathered per node,
 * gravity, bodies and boundary conditions (drivers.h); then the
 * central-difference update of velocities and positions, and per chunk the
 * sums of works, reactions and guards, added in chunk order so that the
 * result does not depend on the thread count.
 */
#include <algorithm>
#include <cmath>
#include <tmfdem/discrete/element_kernel.h>
#include <tmfdem/discrete/explicit_solver.h>
#include <tmfdem/discrete/vector_instructions.h>
#include <type_traits>

namespace tmfdem
{
  namespace discrete
  {
    namespace
    {
      /** The sums of one chunk of the node update, in element order. */
      struct ChunkSums
      {
        double w_elastic = 0., w_viscous = 0., w_joint = 0., w_contact = 0.,
               w_external = 0., max_speed = 0.;
        /** first non-finite node and first inverted element, or -1 */
        double bad_node = -1., inverted = -1.;
        /** with the diagnostics: the out-of-balance force and the internal
         *  force scale, squared, and the kinetic energy */
        double unbalanced = 0., internal = 0., kinetic = 0.;
      };

      /** What the vectorised update of a batch reads besides the model. */
      struct BatchInput
      {
        const LameConstants *lame;
        /** six constants per element, or nullptr (no anisotropic part) */
        const double *anisotropy;
        const double *viscosity;
        /** per element of the batch its contact forces (6), or nullptr */
        const double *contact_forces;
        double        dt, damp_a, damp_b, c_damp, gravity_x, gravity_y;
      };

      /** The vector of p[0], p[stride], ... (one per lane). */
      template <typename Lanes>
      inline Lanes
      gather(const double *p, const unsigned int stride)
      {
        Lanes v;
        for (unsigned int l = 0; l < sizeof(Lanes) / sizeof(double); ++l)
          v[l] = p[stride * l];
        return v;
      }

      /** p[0], p[stride], ... = the lanes of @p v. */
      template <typename Lanes>
      inline void
      scatter(const Lanes v, double *p, const unsigned int stride)
      {
        for (unsigned int l = 0; l < sizeof(Lanes) / sizeof(double); ++l)
          p[stride * l] = v[l];
      }

      /**
       * The node update of the elements e0 ... e0 + lanes - 1, all of whose
       * nodes are free (no condition, no fixed or driven body): the same
       * operations in the same order as the element-by-element loop of
       * ExplicitSolver::update_nodes() (no FMA contraction: the file is
       * compiled with -ffp-contract=off), one element per lane, so that
       * every node's result is bitwise that of the scalar loop; the sums
       * are then added lane by lane, node by node, in element order as
       * there. Compiled once per instruction set (the wrappers below).
       */
      template <unsigned int lanes, bool diagnostics>
      __attribute__((always_inline)) inline void
      update_free_batch(DiscreteModel    &m,
                        const std::size_t e0,
                        const BatchInput &in,
                        ChunkSums        &sums)
      {
        using Lanes          = typename LaneVector<lanes>::type;
        const std::size_t n0 = 3 * e0;
        Lanes             X[3], Y[3], VX[3], VY[3], mass[3];
        for (unsigned int k = 0; k < 3; ++k)
          {
            X[k]    = gather<Lanes>(&m.x[n0 + k], 3);
            Y[k]    = gather<Lanes>(&m.y[n0 + k], 3);
            VX[k]   = gather<Lanes>(&m.vx[n0 + k], 3);
            VY[k]   = gather<Lanes>(&m.vy[n0 + k], 3);
            mass[k] = gather<Lanes>(&m.mass[n0 + k], 3);
          }
        Lanes ib[4];
        for (unsigned int i = 0; i < 4; ++i)
          ib[i] = gather<Lanes>(&m.inverse_basis[4 * e0 + i], 4);
        // 1 / s (1 / 1 is 1: the scalar loop's shortcut, bit for bit)
        const Lanes inv_s = 1. / gather<Lanes>(&m.thermal_stretch[e0], 1);
        Lanes       mu, lambda;
        for (unsigned int l = 0; l < lanes; ++l)
          {
            mu[l]     = in.lame[e0 + l].mu;
            lambda[l] = in.lame[e0 + l].lambda;
          }
        Lanes anisotropy[6];
        if (in.anisotropy != nullptr)
          for (unsigned int i = 0; i < 6; ++i)
            anisotropy[i] = gather<Lanes>(&in.anisotropy[6 * e0 + i], 6);
        const Lanes               eta = gather<Lanes>(&in.viscosity[e0], 1);
        const Lanes *const        nodes[2]      = {X, Y};
        const Lanes *const        velocities[2] = {VX, VY};
        ElementResponse<2, Lanes> r;
        element_response<2, Lanes>(nodes,
                                   velocities,
                                   ib,
                                   inv_s,
                                   mu,
                                   lambda,
                                   in.anisotropy != nullptr ? anisotropy :
                                                              nullptr,
                                   eta,
                                   r);
        const Lanes det = r.det;
        scatter(r.stress[0][0] + r.viscous[0][0], &m.stress[3 * e0], 3);
        scatter(r.stress[1][1] + r.viscous[1][1], &m.stress[3 * e0 + 1], 3);
        scatter(r.stress[0][1] + r.viscous[0][1], &m.stress[3 * e0 + 2], 3);
        const Lanes zero = {};
        Lanes       t_elastic[3], t_viscous[3], t_damping[3], t_joint[3],
          t_contact[3], t_external[3], speed2[3];
        Lanes t_unbalanced[3], t_internal[3], t_kinetic[3];
        for (unsigned int k = 0; k < 3; ++k)
          {
            NodeForces<Lanes> f;
            f.elastic[0] = r.f_elastic[k][0];
            f.elastic[1] = r.f_elastic[k][1];
            f.viscous[0] = r.f_viscous[k][0];
            f.viscous[1] = r.f_viscous[k][1];
            for (unsigned int i = 0; i < 2; ++i)
              f.joint[i] =
                0. + gather<Lanes>(&m.node_joint_force[4 * (n0 + k) + i], 12) +
                gather<Lanes>(&m.node_joint_force[4 * (n0 + k) + 2 + i], 12);
            f.contact[0] = f.contact[1] = zero;
            if (in.contact_forces != nullptr)
              for (unsigned int i = 0; i < 2; ++i)
                f.contact[i] = gather<Lanes>(&in.contact_forces[2 * k + i], 6);
            f.gravity[0]    = mass[k] * in.gravity_x;
            f.gravity[1]    = mass[k] * in.gravity_y;
            const Lanes fx  = f.total(0);
            const Lanes fy  = f.total(1);
            const Lanes b_m = in.damp_b / mass[k];
            const Lanes vx  = damped_velocity<Lanes>(in.damp_a, VX[k], b_m, fx);
            const Lanes vy  = damped_velocity<Lanes>(in.damp_a, VY[k], b_m, fy);
            const Lanes ax  = 0.5 * in.dt * (VX[k] + vx);
            const Lanes ay  = 0.5 * in.dt * (VY[k] + vy);
            const NodeWorks<Lanes> w = node_works(f, ax, ay);
            t_elastic[k]             = w.elastic;
            t_viscous[k]             = w.viscous;
            t_damping[k] = in.c_damp * mass[k] / in.dt * (ax * ax + ay * ay);
            t_joint[k]   = w.joint;
            t_contact[k] = w.contact;
            if constexpr (diagnostics)
              {
                const Lanes ux = fx - f.viscous[0], uy = fy - f.viscous[1];
                t_unbalanced[k] = ux * ux + uy * uy;
                t_internal[k] =
                  f.elastic[0] * f.elastic[0] + f.elastic[1] * f.elastic[1];
              }
            t_external[k] = w.gravity;
            scatter(vx, &m.vx[n0 + k], 3);
            scatter(vy, &m.vy[n0 + k], 3);
            scatter(X[k] + in.dt * vx, &m.x[n0 + k], 3);
            scatter(Y[k] + in.dt * vy, &m.y[n0 + k], 3);
            speed2[k] = vx * vx + vy * vy;
            if constexpr (diagnostics)
              t_kinetic[k] = 0.5 * mass[k] * speed2[k];
          }
        // the sums in the scalar loop's order: element by element, node by
        // node
        for (unsigned int l = 0; l < lanes; ++l)
          {
            if (!(det[l] > 0.) && sums.inverted < 0.)
              sums.inverted = e0 + l;
            for (unsigned int k = 0; k < 3; ++k)
              {
                if constexpr (diagnostics)
                  sums.unbalanced += t_unbalanced[k][l];
                sums.w_elastic += t_elastic[k][l];
                if constexpr (diagnostics)
                  sums.internal += t_internal[k][l];
                sums.w_viscous += t_viscous[k][l];
                if (in.c_damp > 0.)
                  sums.w_viscous -= t_damping[k][l];
                sums.w_joint += t_joint[k][l];
                sums.w_contact += t_contact[k][l];
                sums.w_external += t_external[k][l];
                const double v2 = speed2[k][l];
                sums.max_speed  = std::max(sums.max_speed, v2);
                if constexpr (diagnostics)
                  sums.kinetic += t_kinetic[k][l];
                if (!(v2 < 1e300) && sums.bad_node < 0.)
                  sums.bad_node = n0 + 3 * l + k;
              }
          }
      }

      /** The batch update compiled for each instruction set (with and
       *  without the diagnostics). */
      using FreeBatchKernel = void (*)(DiscreteModel &,
                                       const std::size_t,
                                       const BatchInput &,
                                       ChunkSums &);

#if defined(__x86_64__)
      template <bool diagnostics>
      __attribute__((target("avx512f"))) void
      update_free_batch_avx512(DiscreteModel    &m,
                               const std::size_t e0,
                               const BatchInput &in,
                               ChunkSums        &sums)
      {
        update_free_batch<8, diagnostics>(m, e0, in, sums);
      }

      template <bool diagnostics>
      __attribute__((target("avx2"))) void
      update_free_batch_avx2(DiscreteModel    &m,
                             const std::size_t e0,
                             const BatchInput &in,
                             ChunkSums        &sums)
      {
        update_free_batch<4, diagnostics>(m, e0, in, sums);
      }
#endif

      template <bool diagnostics>
      void
      update_free_batch_baseline(DiscreteModel    &m,
                                 const std::size_t e0,
                                 const BatchInput &in,
                                 ChunkSums        &sums)
      {
        update_free_batch<2, diagnostics>(m, e0, in, sums);
      }

      /** The kernel of @p instructions, or nullptr (element by element). */
      template <bool diagnostics>
      FreeBatchKernel
      free_batch_kernel(const VectorInstructions instructions)
      {
        switch (instructions)
          {
#if defined(__x86_64__)
            case VectorInstructions::avx512:
              return update_free_batch_avx512<diagnostics>;
            case VectorInstructions::avx2:
              return update_free_batch_avx2<diagnostics>;
#endif
            case VectorInstructions::none:
              return nullptr;
            default:
              return update_free_batch_baseline<diagnostics>;
          }
      }
    } // namespace

    void
    ExplicitSolver::update_nodes()
    {
      DiscreteModel     &m            = model;
      const double       dt           = time_step;
      const Drivers     &d            = drivers;
      const unsigned int n_bodies     = d.body_motion.size();
      const unsigned int n_conditions = d.conditions.size();
      // per chunk: the sums, then the reactions of the bodies and conditions
      const unsigned int stride  = n_sums + 2 * n_bodies + 2 * n_conditions;
      const std::size_t n_chunks = (m.n_elements + chunk_size - 1) / chunk_size;
      // one slot after the chunks: joints broke on some rank (partition.h)
      chunk_sums.assign(n_chunks * stride + 1, 0.);
      // this rank's triangles: whole chunks from first_element on
      const std::size_t first_element = partition.begin();
      const std::size_t first_chunk   = first_element / chunk_size;
      const bool        have_contact  = contact.has_pairs();
      const bool        anisotropic   = !element_anisotropy.empty();
      // mass-proportional damping f_d = -c m v_avg, integrated exactly:
      // v_new = (a v_old + dt f / m) with a = (1 - c dt/2) / (1 + c dt/2)
      const double c_damp =
        parameters.get<DiscreteMechanicsParameters>().mass_damping;
      const double damp_a = (1. - 0.5 * c_damp * dt) / (1. + 0.5 * c_damp * dt);
      const double damp_b = dt / (1. + 0.5 * c_damp * dt);
      // the vector kernels of this run's instruction set (nullptr: none),
      // with and without the diagnostics below
      const FreeBatchKernel plain_batch_kernel =
        free_batch_kernel<false>(vector_instructions);
      const FreeBatchKernel diagnostics_batch_kernel =
        free_batch_kernel<true>(vector_instructions);
      // are the nodes [first, last) all free (no condition, no fixed or
      // driven body)?
      const auto nodes_free = [&d](const std::size_t first,
                                   const std::size_t last) {
        for (std::size_t n = first; n < last; ++n)
          if (d.node_condition_slot[n] >= 0 || !d.node_is_free(n))
            return false;
        return true;
      };
      // the out-of-balance force, the internal force scale and the kinetic
      // energy are read only with heat (quasi-static relaxation, the
      // summary's last_relative_unbalanced_force): formed only there
      // (a compile-time flag, so that the loop without them keeps no
      // accumulators for them)
      // gravity at the step's start (Gravity ramp time); exactly Gravity
      // without a ramp
      // under mass scaling (f m) the acceleration g / f keeps the physical
      // weight m g (x / 1 is x: without scaling, Gravity bit for bit)
      const double mass_scaling =
        parameters.get<DiscreteMechanicsParameters>().mass_scaling_factor;
      const double g_share = d.gravity_share(time) / mass_scaling;
      const double gravity_x =
        g_share == 1. ? d.gravity[0] : g_share * d.gravity[0];
      const double gravity_y =
        g_share == 1. ? d.gravity[1] : g_share * d.gravity[1];
      const auto chunk_update = [&](const auto        diagnostics_flag,
                                    const std::size_t local_begin,
                                    const std::size_t local_end,
                                    const std::size_t local_chunk) {
        constexpr bool    diagnostics = decltype(diagnostics_flag)::value;
        const std::size_t begin       = first_element + local_begin;
        const std::size_t end         = first_element + local_end;
        double *sums      = &chunk_sums[(first_chunk + local_chunk) * stride];
        double  w_elastic = 0., w_viscous = 0., w_joint = 0., w_contact = 0.,
               w_external = 0., max_speed = 0.;
        // batches of free elements: the same arithmetic, vectorised
        // (update_free_batch())
        const FreeBatchKernel batch_kernel =
          diagnostics ? diagnostics_batch_kernel : plain_batch_kernel;
        double     batched = 0.; // elements updated in batches
        BatchInput batch;
        batch.lame       = element_lame.data();
        batch.anisotropy = anisotropic ? element_anisotropy.data() : nullptr;
        batch.viscosity  = viscosity.data();
        batch.contact_forces     = nullptr;
        batch.dt                 = dt;
        batch.damp_a             = damp_a;
        batch.damp_b             = damp_b;
        batch.c_damp             = c_damp;
        batch.gravity_x          = gravity_x;
        batch.gravity_y          = gravity_y;
        const unsigned int lanes = vector_lanes(vector_instructions);
        double             batch_contact[6 * max_vector_lanes];
        // out-of-balance force (free components, no viscous part) and the
        // scale of the internal forces, both squared
        double unbalanced = 0., internal = 0., kinetic = 0.;
        // guards: first non-finite node and first inverted element
        double bad_node = -1., inverted = -1.;
        for (std::size_t e = begin; e < end; ++e)
          {
            if (batch_kernel != nullptr && e + lanes <= end &&
                nodes_free(3 * e, 3 * (e + lanes)))
              {
                if (have_contact)
                  {
                    std::fill(batch_contact, batch_contact + 6 * lanes, 0.);
                    for (unsigned int l = 0; l < lanes; ++l)
                      contact.add_forces(e + l, &batch_contact[6 * l]);
                    batch.contact_forces = batch_contact;
                  }
                // the running sums in and out of the batch (copied: the
                // one-at-a-time loop keeps them in registers)
                ChunkSums s;
                s.w_elastic  = w_elastic;
                s.w_viscous  = w_viscous;
                s.w_joint    = w_joint;
                s.w_contact  = w_contact;
                s.w_external = w_external;
                s.max_speed  = max_speed;
                s.bad_node   = bad_node;
                s.inverted   = inverted;
                s.unbalanced = unbalanced;
                s.internal   = internal;
                s.kinetic    = kinetic;
                batch_kernel(m, e, batch, s);
                w_elastic  = s.w_elastic;
                w_viscous  = s.w_viscous;
                w_joint    = s.w_joint;
                w_contact  = s.w_contact;
                w_external = s.w_external;
                max_speed  = s.max_speed;
                bad_node   = s.bad_node;
                inverted   = s.inverted;
                unbalanced = s.unbalanced;
                internal   = s.internal;
                kinetic    = s.kinetic;
                batched += lanes;
                e += lanes - 1;
                continue;
              }
            const unsigned int n0 = 3 * e;
            const double      *X = &m.x[n0], *Y = &m.y[n0];
            const double      *VX = &m.vx[n0], *VY = &m.vy[n0];
            // 1 / s: no division where there is no thermal stretch (the
            // mechanical models; F * 1 is F, bit for bit)
            const double               s             = m.thermal_stretch[e];
            const double               inv_s         = s == 1. ? 1. : 1. / s;
            const double *const        nodes[2]      = {X, Y};
            const double *const        velocities[2] = {VX, VY};
            ElementResponse<2, double> r;
            element_response<2, double>(nodes,
                                        velocities,
                                        &m.inverse_basis[4 * e],
                                        inv_s,
                                        element_lame[e].mu,
                                        element_lame[e].lambda,
                                        anisotropic ?
                                          &element_anisotropy[6 * e] :
                                          nullptr,
                                        viscosity[e],
                                        r);
            if (!(r.det > 0.) && inverted < 0.)
              inverted = e;
            m.stress[3 * e]     = r.stress[0][0] + r.viscous[0][0];
            m.stress[3 * e + 1] = r.stress[1][1] + r.viscous[1][1];
            m.stress[3 * e + 2] = r.stress[0][1] + r.viscous[0][1];
            double f_el[6], f_v[6];
            for (unsigned int k = 0; k < 3; ++k)
              for (unsigned int i = 0; i < 2; ++i)
                {
                  f_el[2 * k + i] = r.f_elastic[k][i];
                  f_v[2 * k + i]  = r.f_viscous[k][i];
                }

            // dt / ((1 + c dt / 2) m) per node: one division per element
            // where its three nodes have the same mass (the lumped mass of
            // setup_materials()), the same quotient otherwise
            const double *node_mass = &m.mass[n0];
            double        b_m[3];
            b_m[0] = damp_b / node_mass[0];
            b_m[1] =
              node_mass[1] == node_mass[0] ? b_m[0] : damp_b / node_mass[1];
            b_m[2] =
              node_mass[2] == node_mass[0] ? b_m[0] : damp_b / node_mass[2];

            double f_contact[6] = {0., 0., 0., 0., 0., 0.};
            if (have_contact)
              contact.add_forces(e, f_contact);
            for (unsigned int k = 0; k < 3; ++k)
              {
                const unsigned int node = n0 + k;
                // joints: node k starts edge k and ends edge k+2, in that
                // order (zero slots where an edge has no intact joint)
                const double      *jf   = &m.node_joint_force[4 * node];
                const double       mass = node_mass[k];
                NodeForces<double> f;
                for (unsigned int i = 0; i < 2; ++i)
                  {
                    f.elastic[i] = f_el[2 * k + i];
                    f.viscous[i] = f_v[2 * k + i];
                    f.joint[i]   = 0. + jf[i] + jf[2 + i];
                    f.contact[i] = f_contact[2 * k + i];
                  }
                f.gravity[0]               = mass * gravity_x;
                f.gravity[1]               = mass * gravity_y;
                const double        fx     = f.total(0);
                const double        fy     = f.total(1);
                const double        vx_old = m.vx[node], vy_old = m.vy[node];
                double              vx_new, vy_new;
                const unsigned char b    = d.node_body[node];
                const int           slot = d.node_condition_slot[node];
                if (slot >= 0)
                  {
                    // boundary conditions of boundary ids
                    const Drivers::NodeCondition &nc = d.node_conditions[slot];
                    const double tx = nc.force[0], ty = nc.force[1];
                    double       gx = fx + tx, gy = fy + ty;
                    vx_new = damped_velocity(damp_a, vx_old, b_m[k], gx);
                    vy_new = damped_velocity(damp_a, vy_old, b_m[k], gy);
                    if constexpr (diagnostics)
                      {
                        if (!nc.prescribed[0])
                          unbalanced += (gx - f_v[2 * k]) * (gx - f_v[2 * k]);
                        if (!nc.prescribed[1])
                          unbalanced +=
                            (gy - f_v[2 * k + 1]) * (gy - f_v[2 * k + 1]);
                      }
                    double rx = 0., ry = 0.;
                    if (nc.prescribed[0])
                      {
                        vx_new = nc.velocity[0];
                        rx     = mass * (vx_new - vx_old) / dt - gx;
                      }
                    if (nc.prescribed[1])
                      {
                        vy_new = nc.velocity[1];
                        ry     = mass * (vy_new - vy_old) / dt - gy;
                      }
                    w_external += 0.5 * dt *
                                  ((tx + rx) * (vx_old + vx_new) +
                                   (ty + ry) * (vy_old + vy_new));
                    double *r = sums + n_sums + 2 * n_bodies + 2 * nc.condition;
                    r[0] += rx;
                    r[1] += ry;
                  }
                else if (b == no_body ||
                         d.body_motion[b] == DiscreteBody::Motion::free)
                  {
                    vx_new = damped_velocity(damp_a, vx_old, b_m[k], fx);
                    vy_new = damped_velocity(damp_a, vy_old, b_m[k], fy);
                    if constexpr (diagnostics)
                      {
                        const double ux = fx - f_v[2 * k],
                                     uy = fy - f_v[2 * k + 1];
                        unbalanced += ux * ux + uy * uy;
                      }
                  }
                else
                  {
                    if (d.body_motion[b] == DiscreteBody::Motion::fixed)
                      vx_new = vy_new = 0.;
                    else
                      {
                        vx_new = d.body_velocity_now[b][0];
                        vy_new = d.body_velocity_now[b][1];
                      }
                    // reaction of the support or driver
                    const double rx = mass * (vx_new - vx_old) / dt - fx;
                    const double ry = mass * (vy_new - vy_old) / dt - fy;
                    w_external +=
                      0.5 * dt *
                      (rx * (vx_old + vx_new) + ry * (vy_old + vy_new));
                    sums[n_sums + 2 * b] += rx;
                    sums[n_sums + 2 * b + 1] += ry;
                  }
                const double            ax = 0.5 * dt * (vx_old + vx_new);
                const double            ay = 0.5 * dt * (vy_old + vy_new);
                const NodeWorks<double> w  = node_works(f, ax, ay);
                w_elastic += w.elastic;
                if constexpr (diagnostics)
                  internal += f_el[2 * k] * f_el[2 * k] +
                              f_el[2 * k + 1] * f_el[2 * k + 1];
                w_viscous += w.viscous;
                if (c_damp > 0. &&
                    (b == no_body ||
                     d.body_motion[b] == DiscreteBody::Motion::free))
                  {
                    // work of -c m v_avg on the components not prescribed
                    const bool px = d.prescribed(node, 0);
                    const bool py = d.prescribed(node, 1);
                    w_viscous -= c_damp * mass / dt *
                                 ((px ? 0. : ax * ax) + (py ? 0. : ay * ay));
                  }
                w_joint += w.joint;
                w_contact += w.contact;
                w_external += w.gravity;
                m.vx[node] = vx_new;
                m.vy[node] = vy_new;
                m.x[node] += dt * vx_new;
                m.y[node] += dt * vy_new;
                const double v2 = vx_new * vx_new + vy_new * vy_new;
                max_speed       = std::max(max_speed, v2);
                if constexpr (diagnostics)
                  kinetic += 0.5 * mass * v2;
                if (!(v2 < 1e300) && bad_node < 0.)
                  bad_node = node;
              }
          }
        // friction dissipated by the pairs whose first triangle is in
        // this chunk, in pair order
        sums[11] = have_contact ? contact.friction_of_elements(begin, end) : 0.;
        sums[8]  = unbalanced;
        sums[9]  = internal;
        sums[10] = kinetic;
        sums[0]  = w_elastic;
        sums[1]  = w_viscous;
        sums[2]  = w_joint;
        sums[3]  = w_contact;
        sums[4]  = w_external;
        sums[5]  = max_speed;
        sums[6]  = bad_node;
        sums[7]  = inverted;
        sums[12] = batched;
      };
      const bool diagnostics = with_heat;
      for_each_chunk(arena_for(n_threads),
                     partition.end() - first_element,
                     chunk_size,
                     [&](const std::size_t local_begin,
                         const std::size_t local_end,
                         const std::size_t local_chunk) {
                       if (diagnostics)
                         chunk_update(std::true_type(),
                                      local_begin,
                                      local_end,
                                      local_chunk);
                       else
                         chunk_update(std::false_type(),
                                      local_begin,
                                      local_end,
                                      local_chunk);
                     });
      // on several ranks: every chunk's sums from its one owner (exact), and
      // the joint-break flag; then each rank's ghosts
      joints_broke_anywhere = joints_broke;
      if (partition.distributed())
        {
          chunk_sums.back() = joints_broke ? 1. : 0.;
          partition.sum(chunk_sums);
          joints_broke_anywhere = chunk_sums.back() > 0.;
          if (joints_broke_anywhere)
            contact.request_search();
          partition.exchange_ghosts(m);
        }
      double max_speed = 0., unbalanced_sq = 0., internal_sq = 0., kinetic = 0.;
      drivers.clear_reactions();
      for (std::size_t c = 0; c < n_chunks; ++c)
        {
          const double *sums = &chunk_sums[c * stride];
          balance.elastic_work -= sums[0];
          balance.viscous_dissipation -= sums[1];
          balance.joint_work -= sums[2];
          balance.contact_work -= sums[3];
          balance.friction_dissipation += sums[11];
          balance.external_work += sums[4];
          max_speed = std::max(max_speed, sums[5]);
          unbalanced_sq += sums[8];
          internal_sq += sums[9];
          kinetic += sums[10];
          vectorised_element_steps += sums[12];
          // chunks in element order: the first flagged is the lowest index
          if (first_nonfinite_node < 0 && sums[6] >= 0.)
            first_nonfinite_node = static_cast<long long>(sums[6]);
          if (first_inverted_element < 0 && sums[7] >= 0.)
            first_inverted_element = static_cast<long long>(sums[7]);
          for (unsigned int b = 0; b < n_bodies; ++b)
            {
              drivers.body_reaction[b][0] += sums[n_sums + 2 * b];
              drivers.body_reaction[b][1] += sums[n_sums + 2 * b + 1];
            }
          for (unsigned int k = 0; k < drivers.conditions.size(); ++k)
            {
              drivers.condition_reaction[k][0] +=
                sums[n_sums + 2 * n_bodies + 2 * k];
              drivers.condition_reaction[k][1] +=
                sums[n_sums + 2 * n_bodies + 2 * k + 1];
            }
        }
      element_steps_done += m.n_elements;
      relative_unbalanced_force =
        std::sqrt(unbalanced_sq / std::max(internal_sq, 1e-300));
      step_kinetic = kinetic;
      contact.add_travel(std::sqrt(max_speed) * dt);
    }

  } // namespace discrete
} // namespace tmfdem
