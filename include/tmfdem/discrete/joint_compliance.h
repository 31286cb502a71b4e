/**
 * @file
 * Compensation of an element's stiffness for the compliance of its joints
 * (doc/theory.md, "Joint compliance compensation").
 *
 * Before anything breaks, the cohesive joints of the discrete layer are
 * springs in series with the triangles (normal stiffness k_n = p_n / L,
 * tangential k_t = p_t / L per unit length, L the joint length). Under a
 * uniform stress sigma a joint of normal n and tangent t opens by
 * [u] = L (sigma_nn / p_n n + sigma_nt / p_t t), and the average strain of
 * the jointed body gains, per element e that owns half of each of its joints,
 *
 *   eps_J = sum_k w_k (sigma_nn / p_n n n + sigma_nt / p_t sym(t n)),
 *   w_k = L_k^2 / (2 A_e).
 *
 * The isotropic part of this compliance is, with W = sum_k w_k,
 *   areal (bulk):  tr eps_J = W sigma_m / p_n  for sigma = sigma_m I,
 *   shear:         eps_J,xy = W (1 / p_n + 1 / p_t) / 4 tau  for sigma_xy =
 * tau, against the continuum's tr eps = sigma_m / K and eps_xy = tau / (2 mu);
 * the first is exact for any element shape, the second is the average
 * over shear directions (exact for every direction when the joint
 * directions are spread evenly, as in an equilateral triangle). The compensated
 * element takes the 2D bulk modulus K_e = lambda_e + mu_e and shear modulus
 * mu_e of
 *
 *   1 / K_e = 1 / K - W / p_n,   1 / mu_e = 1 / mu - W (1 / p_n + 1 / p_t) / 2,
 *
 * (K = lambda + mu, mu of the idealisation's Lame constants), so that the
 * element and its share of the joints in series have the continuum's
 * stiffness. The joint law itself (penalties, peak traction, fracture
 * energy) is not changed.
 *
 * The isotropic part is exact only where the joint directions are spread
 * evenly. A triangle on a free edge has no joint along that edge: its
 * joints add more compliance along the edge than the average, and it is
 * too soft there (an equilateral one by 0.58 / p_n with p_t = p_n). The
 * anisotropic compensation removes the joints' compliance tensor itself
 * and leaves the element an anisotropic correction Delta C of Eq. 44
 * (solid.h, anisotropic_stress()).
 */
#ifndef tmfdem_discrete_joint_compliance_h
#define tmfdem_discrete_joint_compliance_h

#include <array>
#include <tmfdem/discrete/solid.h>

namespace tmfdem
{
  namespace discrete
  {
    /** The result of compensate_joint_compliance(). */
    struct CompensatedElement
    {
      /** Lame constants of the compensated element [Pa]. */
      LameConstants lame;
      /** W = sum over the joined edges of L^2 / (2 A) [-]. */
      double weight = 0.;
      /** Largest share of the target compliance (bulk or shear) that the
       *  joints take, before any cap [-]; compensation needs it below 1. */
      double share = 0.;
      /** True when the share exceeded the cap and was limited to it. */
      bool capped = false;
      /**
       * Anisotropic compensation only: Delta C = C_e - C(lame) [Pa], the
       * element's stiffness (the inverse of the material's compliance minus
       * its joints' compliance tensor) less the isotropic part in `lame`,
       * stored as anisotropy_index<dim>() lays it out (solid.h): in 2D the
       * first six, (11, 22, 33, 12, 13, 23) of the Mandel (xx, yy,
       * sqrt 2 xy), in 3D all 21 of (xx, yy, zz, sqrt 2 xy, sqrt 2 xz,
       * sqrt 2 yz); all zero where the joints' compliance is isotropic.
       */
      std::array<double, anisotropy_size<3>> anisotropy = {};
      /** Anisotropic compensation only: f >= 1 with C_e <= f C(lame) in
       *  every direction, so that `lame` times f bounds the stiffness
       *  (stable step) [-]. */
      double stiffness_bound_factor = 1.;
    };

    /**
     * Lame constants [Pa] of a triangle with nodes (@p x, @p y) [m] such that
     * the triangle in series with half of each of its joints has the
     * stiffness of @p lame (see the file comment). @p normal_penalty and
     * @p tangential_penalty [Pa] are p_n and p_t of the joint on edge k
     * (nodes k, k+1), 0 where the edge has no joint. The joints' share of the
     * target compliance (W K / p_n in bulk, W mu (1/p_n + 1/p_t) / 2 in
     * shear) is limited to @p max_share (0 < max_share < 1, the element is
     * then at most 1 / (1 - max_share) times stiffer); a larger share is
     * reported in @p capped. An element without joints keeps @p lame.
     *
     * With @p anisotropic, also the tensor: the joints' compliance
     * S_J = sum_k w_k (m_n m_n^T / p_n + m_t m_t^T / p_t) (Mandel vectors of
     * n n and sym(t n)) is removed from the material's compliance S in
     * full, C_e = (S - S_J)^-1, limited to @p max_share of S in its
     * stiffest direction (largest eigenvalue of S^-1/2 S_J S^-1/2), and
     * C_e - C(lame) is returned in `anisotropy`.
     */
    CompensatedElement
    compensate_joint_compliance(const std::array<double, 3> &x,
                                const std::array<double, 3> &y,
                                const LameConstants         &lame,
                                const std::array<double, 3> &normal_penalty,
                                const std::array<double, 3> &tangential_penalty,
                                const double                 max_share,
                                const bool anisotropic = false);

    /**
     * The isotropic compensation of a tetrahedron with nodes (@p x, @p y,
     * @p z) [m] and, on face k (the face opposite node k), a joint of
     * penalties @p normal_penalty [k], @p tangential_penalty [k] [Pa] (0: no
     * joint) with k = p / h, h the face's mean edge. Under a uniform stress
     * a face joint of area a opens by [u] = h / p (sigma_nn n + ...), so the
     * element that owns half of each of its joints gains the compliance of
     * weight w_k = a_k h_k / (2 V). Its isotropic part, with W = sum w_k:
     * bulk tr eps_J = W sigma_m / p_n (exact for any shape), shear
     * eps_J,xy = W (2 / p_n + 3 / p_t) / 15 tau (the average over all
     * directions of n n n n / p_n and the tangential compliance
     * (sym(n (x) I (x) n) - n n n n) / p_t); so
     *
     *   1 / K_e = 1 / K - W / p_n,  1 / mu_e = 1 / mu - 2 W (2 / p_n + 3 / p_t)
     * / 15,
     *
     * K = lambda + 2 mu / 3 the 3D bulk modulus, the joints' share capped at
     * @p max_share as in 2D.
     *
     * With @p anisotropic, also the tensor, as for triangles: S_J =
     * sum_k w_k (m_n m_n^T / p_n + (m_t1 m_t1^T + m_t2 m_t2^T) / p_t) (Mandel
     * vectors of n n, sym(t1 n), sym(t2 n), t1 and t2 orthonormal in the
     * face) removed from the material's compliance, C_e = (S - S_J)^-1,
     * limited to @p max_share of S in its stiffest direction; C_e - C(lame)
     * in `anisotropy` (21 components) and the bound factor of C_e.
     */
    CompensatedElement
    compensate_joint_compliance(const std::array<double, 4> &x,
                                const std::array<double, 4> &y,
                                const std::array<double, 4> &z,
                                const LameConstants         &lame,
                                const std::array<double, 4> &normal_penalty,
                                const std::array<double, 4> &tangential_penalty,
                                const double                 max_share,
                                const bool anisotropic = false);
  } // namespace discrete
} // namespace tmfdem

#endif
