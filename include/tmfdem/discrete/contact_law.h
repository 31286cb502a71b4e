/**
 * @file
 * The contact law of the discrete layer (paper Sec. 2.3, Eqs. 5-6; theory
 * manual "Contact"): what one contactor edge inside one target triangle
 * exerts on both. A law is a policy class chosen at compile time (as the
 * softening law of the joints is): ContactSystem::compute_forces<Law>()
 * runs the pair loop, computes the potential integrals of each contactor
 * edge and calls the law; the law also gives the stiffness bound the
 * stable step needs (stable_step.h).
 *
 * To add a law: write a class with the four members of
 * PenaltyCoulombContact below (node_stiffness_bound(),
 * with_normal_penalty_scaled(), target_forces(), edge_forces()), add its name
 * to ContactLaw and dispatch on it in ContactSystem::compute_forces()
 * (source/discrete/contact_system.cc).
 */
#ifndef tmfdem_discrete_contact_law_h
#define tmfdem_discrete_contact_law_h

#include <algorithm>
#include <cmath>
#include <tmfdem/discrete/contact.h>

namespace tmfdem
{
  namespace discrete
  {
    /** The contact laws the discrete layer can use. */
    enum class ContactLaw
    {
      /** Munjiza's penalty potential with Coulomb friction and an elastic
       *  slip history per contactor edge. */
      penalty_coulomb
    };

    /**
     * Munjiza's penalty potential (normal force p_n L int phi_t N n along
     * the contactor edge, Eq. 5; on the target's nodes the exact gradient
     * of the potential energy, or Munjiza's reaction at the contact points)
     * with Coulomb friction on an elastic slip history: tangential spring p_t
     * over the clipped length, capped at mu times the normal force (Eq. 6).
     */
    struct PenaltyCoulombContact
    {
      double normal_penalty     = 0.; ///< p_n [Pa]
      double tangential_penalty = 0.; ///< p_t [Pa]
      double friction           = 0.; ///< Coulomb coefficient mu [-]
      /**
       * Memory slip L of the regularised friction law [m]: the strength
       * follows mu N, and the remembered slip rate the slip rate, over this
       * much slip (doc/theory.md 5.5, "Regularised friction"); 0: plain
       * Coulomb friction, the strength mu N at every instant.
       */
      double memory_slip = 0.;
      /** Rate effect a of the regularised law [-]: the strength times
       *  1 + a ln((v0 + |v|) / (v0 + remembered rate)). */
      double rate_effect = 0.;
      /** Reference slip rate v0 of the rate effect [m/s]. */
      double reference_slip_rate = 1e-6;
      /**
       * How the target's nodes get the normal force (`Contact force on the
       * target`). true: minus the gradient of p int_S phi_t dA with respect
       * to them (add_target_potential_forces(), once per contactor and
       * target), so that the normal force is conservative also when the
       * triangles deform; false: the reaction of each contactor edge's
       * force at its points, with the target's barycentric coordinates
       * there (Munjiza's and the Y code's rule, conservative for rigid
       * motions only).
       */
      bool potential_gradient_on_target = true;

      /**
       * Bound of the contact stiffness one node can feel [N/m per m]: a
       * node pressed into a target of altitude ~ its edge feels about
       * 3 p_n per unit penetration (both pair directions) and at most p_t
       * of stick stiffness.
       */
      double
      node_stiffness_bound() const
      {
        return 3. * normal_penalty + tangential_penalty;
      }

      /**
       * The same law with the normal penalty multiplied by @p factor (the
       * faces of a broken joint, ContactSystem::face_penalty_factor()).
       */
      PenaltyCoulombContact
      with_normal_penalty_scaled(const double factor) const
      {
        PenaltyCoulombContact scaled = *this;
        scaled.normal_penalty *= factor;
        return scaled;
      }

      /**
       * With potential_gradient_on_target: adds to @p ft the normal forces
       * on the target's nodes (@p tx, @p ty) of the contactor (@p cx,
       * @p cy) overlapping it [N/m]; to be called once per contactor and
       * target whenever they may overlap (an edge of the contactor entered
       * the target, or the target lies inside the contactor).
       */
      void
      target_forces(const double *cx,
                    const double *cy,
                    const double *tx,
                    const double *ty,
                    double       *ft) const
      {
        if (potential_gradient_on_target)
          add_target_potential_forces(cx, cy, tx, ty, normal_penalty, ft);
      }

      /**
       * The largest tangential force of one contactor edge [N/m] whose
       * Coulomb strength is @p coulomb (mu N) [N/m] and whose slip rate is
       * @p slip_rate [m/s] over the step @p dt [s]. Plain Coulomb
       * (memory_slip = 0): @p coulomb. Regularised: the strength S and the
       * remembered rate V of @p history relax towards mu N and |v| over the
       * memory slip L (Prakash and Clifton's law for the normal-stress
       * dependence; for the rate, the evolution of rate-and-state friction
       * with equal direct and evolution effects), dS = -(S - mu N) |v| dt /
       * L, integrated exactly over the step, and the limit is
       * S (1 + a ln((v0 + |v|) / (v0 + V))): mu N in steady sliding and at
       * rest, stronger while the slip accelerates. @p history: an
       * EdgeFriction (2D) or FaceFriction (3D), whose strength and
       * remembered_rate it updates.
       */
      template <typename FrictionHistory>
      double
      friction_limit(const double     coulomb,
                     const double     slip_rate,
                     const double     dt,
                     FrictionHistory &history) const
      {
        if (!(memory_slip > 0.))
          return coulomb;
        const double keep = std::exp(-slip_rate * dt / memory_slip);
        history.strength  = coulomb + (history.strength - coulomb) * keep;
        history.remembered_rate =
          slip_rate + (history.remembered_rate - slip_rate) * keep;
        const double factor =
          1. + rate_effect *
                 std::log((reference_slip_rate + slip_rate) /
                          (reference_slip_rate + history.remembered_rate));
        return history.strength * std::max(factor, 0.);
      }

      /**
       * Forces of the contactor edge from node @p a (local node @p ka of
       * the contactor) to node @p b (local @p kb) inside the target whose
       * first node is @p t0 (its nodes t0, t0+1, t0+2), with the potential
       * integrals @p I along the edge [N/m]: added to the contactor's six
       * nodal components @p fc and the target's @p ft. @p history is the
       * edge's friction history (elastic slip [m]; with the regularised
       * law its strength and remembered slip rate), updated over the step
       * @p dt [s]. Returns the energy dissipated by friction [J/m].
       */
      double
      edge_forces(const double                 *x,
                  const double                 *y,
                  const double                 *vx,
                  const double                 *vy,
                  const unsigned int            a,
                  const unsigned int            b,
                  const unsigned int            ka,
                  const unsigned int            kb,
                  const unsigned int            t0,
                  const EdgePotentialIntegrals &I,
                  const double                  dt,
                  EdgeFriction                 &history,
                  double                       *fc,
                  double                       *ft) const
      {
        const double ex = x[b] - x[a], ey = y[b] - y[a];
        const double L    = std::sqrt(ex * ex + ey * ey);
        const double tx_u = ex / L, ty_u = ey / L;
        const double nx = ty_u, ny = -tx_u; // outward of the contactor
        const double scale = normal_penalty * L;
        // normal: on the contactor -p L int phi_t N n, reaction on target
        const double fa = scale * I.phi_start, fb = scale * I.phi_end;
        fc[2 * ka] -= fa * nx;
        fc[2 * ka + 1] -= fa * ny;
        fc[2 * kb] -= fb * nx;
        fc[2 * kb + 1] -= fb * ny;
        if (!potential_gradient_on_target)
          for (unsigned int k = 0; k < 3; ++k)
            {
              ft[2 * k] += scale * I.phi_target[k] * nx;
              ft[2 * k + 1] += scale * I.phi_target[k] * ny;
            }
        // Coulomb friction with elastic slip history (and, regularised, a
        // strength and slip rate remembered over the memory slip)
        const double normal_force = fa + fb;
        const double mu           = friction;
        if (!(normal_force > 0.) || mu <= 0.)
          {
            history = EdgeFriction();
            return 0.;
          }
        const double total = I.total();
        const double u     = I.phi_end / total;
        const double lt[3] = {I.phi_target[0] / total,
                              I.phi_target[1] / total,
                              I.phi_target[2] / total};
        const double vcx   = (1. - u) * vx[a] + u * vx[b];
        const double vcy   = (1. - u) * vy[a] + u * vy[b];
        double       vtx = 0., vty = 0.;
        for (unsigned int k = 0; k < 3; ++k)
          {
            vtx += lt[k] * vx[t0 + k];
            vty += lt[k] * vy[t0 + k];
          }
        const double rate      = (vcx - vtx) * tx_u + (vcy - vty) * ty_u;
        const double trial     = history.slip + rate * dt;
        const double stiffness = tangential_penalty * I.clipped_length_fraction;
        double       tangential = -stiffness * trial;
        const double limit =
          friction_limit(mu * normal_force, std::abs(rate), dt, history);
        double new_slip   = trial;
        double dissipated = 0.;
        if (std::abs(tangential) > limit)
          {
            tangential = trial > 0. ? -limit : limit;
            new_slip   = -tangential / stiffness;
            dissipated = limit * (std::abs(trial) - std::abs(new_slip));
          }
        history.slip = new_slip;
        fc[2 * ka] += (1. - u) * tangential * tx_u;
        fc[2 * ka + 1] += (1. - u) * tangential * ty_u;
        fc[2 * kb] += u * tangential * tx_u;
        fc[2 * kb + 1] += u * tangential * ty_u;
        for (unsigned int k = 0; k < 3; ++k)
          {
            ft[2 * k] -= lt[k] * tangential * tx_u;
            ft[2 * k + 1] -= lt[k] * tangential * ty_u;
          }
        return dissipated;
      }
    };
  } // namespace discrete
} // namespace tmfdem

#endif
