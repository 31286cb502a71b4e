/**
 * @file
 * The stable step of the explicit scheme and the meaning of the damping
 * ratio, derived from the scheme itself (doc/theory.md, "Stable step").
 *
 * The discrete layer advances velocities at half steps (symplectic Euler /
 * central differences) with the viscous force evaluated at the old
 * velocity:
 *
 *   M (v_{n+1/2} - v_{n-1/2}) = -dt (K x_n + C v_{n-1/2}),
 *   x_{n+1} = x_n + dt v_{n+1/2}.
 *
 * For symmetric positive semi-definite K and C the discrete energy
 *   H = v^T (M - dt C / 2 - dt^2 K / 4) v + 1/4 xbar^T K xbar
 * (v = v_{n+1/2}, xbar = x_{n+1} + x_n) never grows, so the scheme is stable
 * whenever 4 M - 2 dt C - dt^2 K is positive definite; for one mode of
 * damping ratio zeta this is exactly the critical step
 * omega dt = 2 (sqrt(1 + zeta^2) - zeta).
 *
 * Every triangle owns its nodes, so M and C are block diagonal per
 * element; a joint couples two elements, and its energy
 * 1/2 int k |u_A - u_B|^2 ds is at most int k |u_A|^2 + int k |u_B|^2 ds,
 * so each element carries twice its joints' one-sided stiffness. Contact
 * springs are bounded the same way (a diagonal stiffness per node). The
 * per-element condition
 *
 *   4 M_e - 2 dt C_e - dt^2 (K_e + 2 sum_joints G_j + R_e) >= 0
 *
 * then implies the global one: critical_time_step() returns the largest
 * such dt of one element (a 6 x 6 test, bisection on Cholesky). It is exact
 * for one free element and for assemblies whose highest mode moves joined
 * faces against each other, and a lower bound everywhere.
 */
#ifndef tmfdem_discrete_stable_step_h
#define tmfdem_discrete_stable_step_h

#include <array>
#include <tmfdem/discrete/solid.h>

namespace tmfdem
{
  namespace discrete
  {
    /** Dense symmetric 6 x 6 matrix of one triangle's nodal dofs
     *  (x0, y0, x1, y1, x2, y2). */
    using Matrix6 = std::array<std::array<double, 6>, 6>;

    /**
     * The linearised stiffness K_e [N/m per m of thickness] and the
     * viscous matrix C_e for eta = 1 Pa s [N s/m per m] of a constant-strain
     * triangle with nodes (@p x, @p y) [m]: K_e = A B^T D B with D of the
     * Lame constants, C_e = A B^T D_v B with D_v = diag(2, 2, 1) (the
     * viscous stress 2 eta sym(grad v)). Linearised about a stress-free
     * state at the given geometry.
     */
    void
    element_matrices(const std::array<double, 3> &x,
                     const std::array<double, 3> &y,
                     const LameConstants         &lame,
                     Matrix6                     &stiffness,
                     Matrix6                     &unit_viscosity);

    /** Everything critical_time_step() needs of one element. */
    struct ElementStepInput
    {
      std::array<double, 3> x = {{0., 0., 0.}}; ///< node x [m]
      std::array<double, 3> y = {{0., 0., 0.}}; ///< node y [m]
      LameConstants         lame;               ///< [Pa]
      double                viscosity = 0.;     ///< eta [Pa s]
      double                node_mass = 0.;     ///< [kg/m]
      /** Normal stiffness per unit area k_n [Pa/m] of the intact joint on
       *  edge k (nodes k, k+1); 0 where there is none. */
      std::array<double, 3> edge_joint_normal_stiffness = {{0., 0., 0.}};
      /** Tangential stiffness k_t [Pa/m] of the joint on edge k. */
      std::array<double, 3> edge_joint_tangential_stiffness = {{0., 0., 0.}};
      /** Bound of the contact stiffness on each node [N/m per m]. */
      double node_contact_stiffness = 0.;
    };

    /**
     * The largest dt [s] with 4 M_e - 2 dt C_e - dt^2 (K_e + 2 G + R) >= 0,
     * G = L/6 [[2, 1], [1, 2]] (x) (k_n n n^T + k_t t t^T) per joined edge
     * (see the file comment), to a relative 1e-4, rounded down. Returns
     * +infinity for an element with neither stiffness nor damping, 0 for a
     * degenerate (zero or negative area) element.
     */
    double
    critical_time_step(const ElementStepInput &element);

    /**
     * True when the step @p dt [s] satisfies the condition of
     * critical_time_step() for @p element, i.e. dt does not exceed its
     * critical step (one Cholesky test instead of a bisection: what the
     * deformed-mesh guard asks of every element).
     */
    bool
    stable_at(const ElementStepInput &element, const double dt);

    /**
     * Damping ratio [-] of the highest free mode of the element (no
     * joints) per unit viscosity [1/(Pa s)]: zeta_1 = phi^T C_1 phi / (2 m
     * omega) with K_e phi = m omega^2 phi, omega the largest frequency and
     * C_1 the viscous matrix for eta = 1 Pa s. The viscosity that damps the
     * highest mode critically is 1 / zeta_1 (`Damping ratio = 1`).
     */
    double
    highest_mode_damping_per_viscosity(const std::array<double, 3> &x,
                                       const std::array<double, 3> &y,
                                       const LameConstants         &lame,
                                       const double                 node_mass);

    /**
     * Eigenvalues (ascending) and eigenvectors (columns of @p vectors) of a
     * symmetric 6 x 6 matrix, by cyclic Jacobi rotations.
     */
    void
    symmetric_eigen(const Matrix6         &matrix,
                    std::array<double, 6> &values,
                    Matrix6               &vectors);
  } // namespace discrete
} // namespace tmfdem

#endif
