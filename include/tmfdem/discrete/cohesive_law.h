/**
 * @file
 * The cohesive law of the zero-thickness joints (paper Sec. 2.2 with the
 * corrections of the theory manual, doc/theory.md "Joints").
 *
 * Before the peak the normal traction follows f_t (2 r - r^2), r = o / o_p,
 * and the shear traction f_s (2 r - r^2), r = |s| / s_p, where the initial
 * slopes are the penalties: o_p = 2 f_t / k_n, s_p = 2 f_s / k_t. In
 * compression (o < 0) the normal traction is the penalty k_n o and the shear
 * strength is Mohr-Coulomb, f_s = c + max(0, -sigma) tan(phi). After the
 * peak the damage D = sqrt(d_o^2 + d_s^2) (the ellipse of paper Eq. 3, in
 * the normalised softening displacements d_o = (o - o_p) / w_I,
 * d_s = (|s| - s_p) / w_II) scales both strengths by a softening function
 * z(D); D never decreases; the joint is broken at D = 1.
 *
 * The softening widths w_I, w_II are chosen so that the work to break a
 * joint in pure Mode I (II) equals G_I (G_II) exactly, pre-peak work
 * included: G = 2/3 f o_p + f w int_0^1 z(D) dD.
 */
#ifndef tmfdem_discrete_cohesive_law_h
#define tmfdem_discrete_cohesive_law_h

#include <cmath>
#include <string>
#include <tmfdem/discrete/vector_instructions.h>
#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    /** The softening functions z(D) offered by `Softening law`. */
    enum class SofteningLaw
    {
      munjiza, ///< Munjiza's curve, a = 0.63, b = 1.8, c = 6
      linear   ///< z = 1 - D
    };

    /** Names of the softening laws, for Patterns::Selection. */
    const std::vector<std::pair<std::string, SofteningLaw>> &
    softening_law_registry();

    /** z(D) for D in [0, 1]: 1 at the peak, 0 when broken. */
    template <SofteningLaw law>
    inline double
    softening(const double D)
    {
      if constexpr (law == SofteningLaw::linear)
        return 1. - D;
      else
        {
          constexpr double a = 0.63, b = 1.8, c = 6.0;
          const double     one_minus_D = 1. - D;
          const double     p2          = one_minus_D * one_minus_D;
          const double     p6          = p2 * p2 * p2;
          return (1. - (a + b - 1.) / (a + b) *
                         std::exp(D * (a + c * b) / ((a + b) * (1. - a - b)))) *
                 (a * one_minus_D + b * p6);
        }
    }

    /** z(D) for a law chosen at run time. */
    double
    softening_value(const SofteningLaw law, const double D);

    /** int_0^1 z(D) dD (0.5 for linear, about 0.3863 for Munjiza's). */
    double
    softening_integral(const SofteningLaw law);

    /** Constants of one joint, fixed at start-up. */
    struct JointConstants
    {
      double normal_stiffness;     ///< k_n [Pa/m]
      double tangential_stiffness; ///< k_t [Pa/m]
      double tensile_strength;     ///< f_t [Pa]
      double cohesion;             ///< c [Pa]
      double friction_tangent;     ///< tan(phi) [-]
      double softening_width_I;    ///< w_I [m]
      double softening_width_II;   ///< w_II [m]
      /** 1 / o_p with the opening at the peak traction o_p = 2 f_t / k_n
       *  [1/m] (derived, so that the step multiplies instead of divides). */
      double inverse_opening_peak;
      /** 1 / s_p with the slip at the peak shear traction without
       *  compression s_p = 2 c / k_t [1/m] (derived; under compression the
       *  peak grows, see cohesive_traction()). */
      double inverse_slip_peak_open;
    };

    /**
     * Tractions on a joint face pair [Pa], for one joint (Number = double)
     * or one per lane of a vector batch.
     */
    template <typename Number>
    struct JointTractionT
    {
      Number normal;    ///< tension positive (resists opening)
      Number shear;     ///< along the slip (resists slip)
      Number d_opening; ///< normalised softening opening d_o (past the peak)
      Number d_slip;    ///< normalised softening slip d_s (past the peak)
      /** r = o / o_p > 1 or r_s = |s| / s_p > 1: past a peak (a comparison
       *  result: bool, or a lane mask) */
      decltype(Number() > 1.) beyond_peak;
    };

    /** The tractions of one joint. */
    using JointTraction = JointTractionT<double>;

    /**
     * The cohesive tractions for opening @p o and slip @p s [m]; @p damage
     * is the history variable in [0, 1], updated in place. Written once
     * for one joint (Number = double, @p k a JointConstants) and for the
     * lanes of a vector batch (Number a lane vector, @p k a struct of lane
     * vectors with JointConstants' member names: joint_kernel.h); both
     * perform the same operations in the same order. With @p with_softening =
     * false only the rising branch is formed (z = 1, @p damage not
     * updated): for joints whose damage is 0, and the caller discards the
     * result where beyond_peak is set, as the explicit loop's batches do.
     */
    template <SofteningLaw law,
              bool         with_softening = true,
              typename Number,
              typename Constants>
    __attribute__((always_inline)) inline JointTractionT<Number>
    cohesive_traction(const Number     o,
                      const Number     s,
                      const Constants &k,
                      Number          &damage)
    {
      const Number           zero{};
      JointTractionT<Number> t;
      const Number           ft     = k.tensile_strength;
      const auto             closed = o < 0.;
      const Number compression      = closed ? k.normal_stiffness * o : zero;
      // opening and slip relative to their peaks, r = o / o_p and
      // r_s = |s| / s_p (o_p = 2 f_t / k_n, s_p = 2 f_s / k_t): products
      // with the stored reciprocals where f_s = c (no compression); under
      // compression Mohr-Coulomb f_s = c - sigma_n tan(phi) grows with it
      const Number fs =
        closed ? k.cohesion - compression * k.friction_tangent : k.cohesion;
      const Number abs_s = lane_abs(s);
      const Number r     = o * k.inverse_opening_peak;
      // the division only where the joint (some joint of the batch) is
      // closed
      Number r_s = abs_s * k.inverse_slip_peak_open;
      if (any_lane(closed))
        r_s = closed ? abs_s * k.tangential_stiffness / (2. * fs) : r_s;
      const auto past_opening = r > 1., past_slip = r_s > 1.;
      t.beyond_peak = past_opening | past_slip;
      // beyond a peak: the softening displacements and the damage (rare;
      // divisions here); z(D) where the joint is damaged
      t.d_opening = zero;
      t.d_slip    = zero;
      Number D    = damage;
      Number z    = zero + 1.;
      if constexpr (with_softening)
        {
          if (any_lane(t.beyond_peak | (D > 0.)))
            {
              t.d_opening = past_opening ? (o - 2. * ft / k.normal_stiffness) /
                                             k.softening_width_I :
                                           zero;
              t.d_slip    = past_slip ?
                              (abs_s - 2. * fs / k.tangential_stiffness) /
                             k.softening_width_II :
                              zero;
              const auto softens = (t.d_opening > 0.) | (t.d_slip > 0.);
              if (any_lane(softens))
                {
                  const Number D_now =
                    lane_sqrt(t.d_opening * t.d_opening + t.d_slip * t.d_slip);
                  Number D_new = D_now > D ? D_now : D;
                  D_new        = D_new < 1. ? D_new : zero + 1.;
                  D            = softens ? D_new : D;
                  damage       = D;
                }
              if (any_lane(D > 0.))
                z = D > 0. ?
                      lane_map([](const double d) { return softening<law>(d); },
                               D) :
                      z;
            }
        }

      t.normal =
        closed ? compression : (r <= 1. ? z * ft * r * (2. - r) : z * ft);
      const Number shear_magnitude =
        z * fs * (r_s < 1. ? r_s * (2. - r_s) : zero + 1.);
      t.shear = s < 0. ? -shear_magnitude : shear_magnitude;
      return t;
    }

    /** The compression of a joint closed over part of its length: the
     *  normal forces on its two node pairs and the energy it stores (one
     *  joint, or one per lane). */
    template <typename Number>
    struct ClosedPartT
    {
      /** int k_n o(u) N(u) L du over the closed part, N = 1 - u for the
       *  pair that starts the edge, u for the pair that ends it [N/m];
       *  negative (pushes the faces apart), like JointTraction::normal. */
      Number force_start, force_end;
      /** k_n / 2 int o^2 L du over the closed part [J/m]. */
      Number energy;
    };

    /** The closed part of one joint. */
    using ClosedPart = ClosedPartT<double>;

    /**
     * The compression of a joint whose opening is linear along its edge,
     * o(u) = (1 - u) @p o_start + u @p o_end [m], closed (o < 0) at one end
     * and open at the other (the signs of @p o_start and @p o_end differ),
     * of length @p length [m]: the penalty k_n o integrated exactly over
     * the closed part u in [0, w] (or [1 - w, 1]), w = o_c / (o_c - o_o),
     * o_c the closed end's opening, o_o the open end's:
     *
     *   closed end  k_n L o_c w (1/2 - w/6),   open end  k_n L o_c w^2 / 6,
     *   energy      k_n L o_c^2 w / 6.
     *
     * The two Gauss points of the cohesive law miss the closed part where
     * it is shorter than 0.21 of the edge (a hinge): the faces would
     * interpenetrate there unresisted, and the contact that takes over at
     * the break would find that overlap (doc/theory.md 5.4). Written once
     * for a joint and for the lanes of a batch, as cohesive_traction(); in
     * a lane whose joint is not closed at one end only the result is
     * meaningless (the caller selects).
     */
    template <typename Number, typename Constants>
    __attribute__((always_inline)) inline ClosedPartT<Number>
    joint_closed_part(const Number     o_start,
                      const Number     o_end,
                      const Number     length,
                      const Constants &k)
    {
      const auto          at_start = o_start < 0.;
      const Number        oc       = at_start ? o_start : o_end;
      const Number        oo       = at_start ? o_end : o_start;
      const Number        w        = oc / (oc - oo);
      const Number        scale    = k.normal_stiffness * length * oc;
      ClosedPartT<Number> c;
      const Number        closed = scale * w * (0.5 - w / 6.),
                   open          = scale * w * w / 6.;
      c.force_start              = at_start ? closed : open;
      c.force_end                = at_start ? open : closed;
      c.energy                   = scale * oc * w / 6.;
      return c;
    }

    /**
     * Joint constants from material strengths and the joint length
     * @p length [m]: penalties p_n, p_t [Pa] give k = p / length; the
     * softening widths make the work to break equal G_I, G_II.
     * Returns false (and leaves @p k unfinished) when G is below the
     * pre-peak work 4 f^2 / (3 k), i.e. the penalty is too soft.
     */
    bool
    make_joint_constants(const double       tensile_strength,
                         const double       cohesion,
                         const double       friction_angle_degrees,
                         const double       fracture_energy_I,
                         const double       fracture_energy_II,
                         const double       normal_penalty,
                         const double       tangential_penalty,
                         const double       length,
                         const SofteningLaw law,
                         JointConstants    &k);

    /**
     * Work per unit joint area stored elastically before the peak [J/m^2]
     * for an undamaged joint at opening @p o and slip @p s: the integral of
     * the pre-peak tractions (the recoverable part).
     */
    double
    stored_joint_energy(const double          o,
                        const double          s,
                        const JointConstants &k);
  } // namespace discrete
} // namespace tmfdem

#endif
