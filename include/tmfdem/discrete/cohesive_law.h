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

    /** Tractions on a joint face pair [Pa]. */
    struct JointTraction
    {
      double normal;    ///< tension positive (resists opening)
      double shear;     ///< along the slip (resists slip)
      double d_opening; ///< normalised softening opening d_o >= 0
      double d_slip;    ///< normalised softening slip d_s >= 0
    };

    /**
     * The cohesive tractions for opening @p o and slip @p s [m]; @p damage
     * is the history variable in [0, 1], updated in place.
     */
    template <SofteningLaw law>
    inline JointTraction
    cohesive_traction(const double          o,
                      const double          s,
                      const JointConstants &k,
                      double               &damage)
    {
      JointTraction t{0., 0., 0., 0.};
      const double  ft          = k.tensile_strength;
      const double  compression = o < 0. ? k.normal_stiffness * o : 0.;
      // opening and slip relative to their peaks, r = o / o_p and
      // r_s = |s| / s_p (o_p = 2 f_t / k_n, s_p = 2 f_s / k_t): products
      // with the stored reciprocals where f_s = c (no compression); under
      // compression Mohr-Coulomb f_s = c - sigma_n tan(phi) grows with it
      const double fs =
        o < 0. ? k.cohesion - compression * k.friction_tangent : k.cohesion;
      const double abs_s = std::abs(s);
      const double r     = o * k.inverse_opening_peak;
      const double r_s   = o < 0. ? abs_s * k.tangential_stiffness / (2. * fs) :
                                    abs_s * k.inverse_slip_peak_open;
      // beyond a peak: the softening displacements (rare; divisions here)
      if (r > 1.)
        t.d_opening = (o - 2. * ft / k.normal_stiffness) / k.softening_width_I;
      if (r_s > 1.)
        t.d_slip =
          (abs_s - 2. * fs / k.tangential_stiffness) / k.softening_width_II;
      double D = damage;
      if (t.d_opening > 0. || t.d_slip > 0.)
        {
          const double D_now =
            std::sqrt(t.d_opening * t.d_opening + t.d_slip * t.d_slip);
          D      = D_now > D ? D_now : D;
          D      = D < 1. ? D : 1.;
          damage = D;
        }
      const double z = D > 0. ? softening<law>(D) : 1.;

      if (o < 0.)
        t.normal = compression;
      else if (r <= 1.)
        t.normal = z * ft * r * (2. - r);
      else
        t.normal = z * ft;

      const double shear_magnitude =
        z * fs * (r_s < 1. ? r_s * (2. - r_s) : 1.);
      t.shear = s < 0. ? -shear_magnitude : shear_magnitude;
      return t;
    }

    /** The compression of a joint closed over part of its length: the
     *  normal forces on its two node pairs and the energy it stores. */
    struct ClosedPart
    {
      /** int k_n o(u) N(u) L du over the closed part, N = 1 - u for the
       *  pair that starts the edge, u for the pair that ends it [N/m];
       *  negative (pushes the faces apart), like JointTraction::normal. */
      double force_start = 0., force_end = 0.;
      /** k_n / 2 int o^2 L du over the closed part [J/m]. */
      double energy = 0.;
    };

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
     * the break would find that overlap (doc/theory.md 5.4).
     */
    inline ClosedPart
    joint_closed_part(const double          o_start,
                      const double          o_end,
                      const double          length,
                      const JointConstants &k)
    {
      const bool   at_start = o_start < 0.;
      const double oc       = at_start ? o_start : o_end,
                   oo       = at_start ? o_end : o_start;
      const double w        = oc / (oc - oo);
      const double scale    = k.normal_stiffness * length * oc;
      ClosedPart   c;
      const double closed = scale * w * (0.5 - w / 6.),
                   open   = scale * w * w / 6.;
      c.force_start       = at_start ? closed : open;
      c.force_end         = at_start ? open : closed;
      c.energy            = scale * oc * w / 6.;
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
