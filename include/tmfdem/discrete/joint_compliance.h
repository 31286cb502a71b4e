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
     */
    CompensatedElement
    compensate_joint_compliance(const std::array<double, 3> &x,
                                const std::array<double, 3> &y,
                                const LameConstants         &lame,
                                const std::array<double, 3> &normal_penalty,
                                const std::array<double, 3> &tangential_penalty,
                                const double                 max_share);
  } // namespace discrete
} // namespace tmfdem

#endif
