/**
 * @file
 * The stable step of the explicit scheme and the meaning of the damping
 * ratio, derived from the scheme itself (doc/theory.md, "Stable step"),
 * for triangles (2D) and tetrahedra (3D).
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
 * Every simplex owns its nodes, so M and C are block diagonal per
 * element; a joint couples two elements, and its energy
 * 1/2 int k |u_A - u_B|^2 ds is at most int k |u_A|^2 + int k |u_B|^2 ds,
 * so each element carries twice its joints' one-sided stiffness G: the
 * consistent matrix of the joint's facet with the linear shape functions,
 * in 2D on an edge of length L with tangent t and normal n
 *
 *   G = L / 6 [[2, 1], [1, 2]] (x) (k_n n n^T + k_t t t^T),
 *
 * in 3D on a triangular face of area A and unit normal n
 *
 *   G = A / 12 [[2, 1, 1], [1, 2, 1], [1, 1, 2]] (x)
 *       (k_n n n^T + k_t (I - n n^T))
 *
 * (what the two- and three-point Gauss rules of the joint forces integrate
 * exactly). Contact springs are bounded the same way (a diagonal stiffness
 * R per node). The per-element condition
 *
 *   4 M_e - 2 dt C_e - dt^2 (K_e + 2 sum_joints G_j + R_e) >= 0
 *
 * then implies the global one: critical_time_step() returns the largest
 * such dt of one element (a 6 x 6 test for a triangle, 12 x 12 for a
 * tetrahedron; bisection on Cholesky). It is exact for one free element and
 * for assemblies whose highest mode moves joined facets of equal nodal
 * masses against each other, and a lower bound everywhere (for masses
 * m_A >= m_B across a stiff joint, sqrt((1 + m_B / m_A) / 2) of the exact
 * step).
 *
 * The functions are templates on the dimension (2 or 3); the triangle's
 * names (ElementStepInput, Matrix6) are those of the 2D instantiation.
 */
#ifndef tmfdem_discrete_stable_step_h
#define tmfdem_discrete_stable_step_h

#include <array>
#include <cstddef>
#include <tmfdem/discrete/solid.h>

namespace tmfdem
{
  namespace discrete
  {
    /** Number of nodal dofs of a simplex in @p dim dimensions,
     *  dim (dim + 1): 6 for a triangle, 12 for a tetrahedron. */
    template <int dim>
    constexpr std::size_t simplex_dofs = dim *(dim + 1);

    /** Dense symmetric matrix of one simplex's nodal dofs, node by node:
     *  (x0, y0, x1, y1, x2, y2) in 2D, (x0, y0, z0, x1, ..., z3) in 3D. */
    template <int dim>
    using ElementMatrix =
      std::array<std::array<double, simplex_dofs<dim>>, simplex_dofs<dim>>;

    /** Dense symmetric 6 x 6 matrix of one triangle's nodal dofs
     *  (x0, y0, x1, y1, x2, y2). */
    using Matrix6 = ElementMatrix<2>;

    /** Dense symmetric 12 x 12 matrix of one tetrahedron's nodal dofs
     *  (x0, y0, z0, x1, y1, z1, x2, y2, z2, x3, y3, z3). */
    using Matrix12 = ElementMatrix<3>;

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

    /**
     * The linearised stiffness K_e [N/m] and the viscous matrix C_e for
     * eta = 1 Pa s [N s/m] of a linear (constant-strain) tetrahedron with
     * nodes (@p x, @p y, @p z) [m]: K_e = V B^T D B with D of the 3D Lame
     * constants (Voigt order xx, yy, zz, xy, yz, xz, engineering shear),
     * C_e = V B^T D_v B with D_v = diag(2, 2, 2, 1, 1, 1) (the viscous
     * stress 2 eta sym(grad v)), V the volume. Linearised about a
     * stress-free state at the given geometry.
     */
    void
    element_matrices(const std::array<double, 4> &x,
                     const std::array<double, 4> &y,
                     const std::array<double, 4> &z,
                     const LameConstants         &lame,
                     Matrix12                    &stiffness,
                     Matrix12                    &unit_viscosity);

    /** Everything critical_time_step() needs of one simplex: specialised
     *  for triangles (dim = 2) and tetrahedra (dim = 3). */
    template <int dim>
    struct ElementStepInputT;

    /** Everything critical_time_step() needs of one triangle (per unit
     *  thickness). */
    template <>
    struct ElementStepInputT<2>
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

    /** Everything critical_time_step() needs of one tetrahedron. */
    template <>
    struct ElementStepInputT<3>
    {
      std::array<double, 4> x = {{0., 0., 0., 0.}}; ///< node x [m]
      std::array<double, 4> y = {{0., 0., 0., 0.}}; ///< node y [m]
      std::array<double, 4> z = {{0., 0., 0., 0.}}; ///< node z [m]
      LameConstants         lame;                   ///< [Pa]
      double                viscosity = 0.;         ///< eta [Pa s]
      double                node_mass = 0.;         ///< [kg]
      /** Normal stiffness per unit area k_n [Pa/m] of the intact joint on
       *  face k, the face opposite node k (nodes k+1, k+2, k+3 mod 4); 0
       *  where there is none. */
      std::array<double, 4> face_joint_normal_stiffness = {{0., 0., 0., 0.}};
      /** Tangential stiffness k_t [Pa/m] of the joint on face k (isotropic
       *  in the face plane). */
      std::array<double, 4> face_joint_tangential_stiffness = {
        {0., 0., 0., 0.}};
      /** Bound of the contact stiffness on each node [N/m]. */
      double node_contact_stiffness = 0.;
    };

    /** The input of critical_time_step() for a triangle. */
    using ElementStepInput = ElementStepInputT<2>;

    /** The input of critical_time_step() for a tetrahedron. */
    using TetrahedronStepInput = ElementStepInputT<3>;

    /**
     * The largest dt [s] with 4 M_e - 2 dt C_e - dt^2 (K_e + 2 G + R) >= 0,
     * G the consistent joint matrix of every joined edge (2D) or face (3D)
     * (see the file comment), to a relative 1e-4, rounded down. Returns
     * +infinity for an element with neither stiffness nor damping, 0 for a
     * degenerate (zero or negative area or volume; a tetrahedron is
     * positive when (x1 - x0) . ((x2 - x0) x (x3 - x0)) > 0) or massless
     * element.
     */
    template <int dim>
    double
    critical_time_step(const ElementStepInputT<dim> &element);

    /**
     * True when the step @p dt [s] satisfies the condition of
     * critical_time_step() for @p element, i.e. dt does not exceed its
     * critical step (one Cholesky test instead of a bisection: what the
     * deformed-mesh guard asks of every element).
     */
    template <int dim>
    bool
    stable_at(const ElementStepInputT<dim> &element, const double dt);

    /**
     * Damping ratio [-] of the highest free mode of the triangle (no
     * joints) per unit viscosity [1/(Pa s)]: zeta_1 = phi^T C_1 phi / (2 m
     * omega) with K_e phi = m omega^2 phi, omega the largest frequency and
     * C_1 the viscous matrix for eta = 1 Pa s; @p node_mass [kg/m]. The
     * viscosity that damps the highest mode critically is 1 / zeta_1
     * (`Damping ratio = 1`).
     */
    double
    highest_mode_damping_per_viscosity(const std::array<double, 3> &x,
                                       const std::array<double, 3> &y,
                                       const LameConstants         &lame,
                                       const double                 node_mass);

    /**
     * The same for a tetrahedron with nodes (@p x, @p y, @p z) [m] and
     * @p node_mass [kg]: the damping ratio [-] of its highest free mode per
     * unit viscosity [1/(Pa s)], averaged over the modes of a repeated
     * highest frequency.
     */
    double
    highest_mode_damping_per_viscosity(const std::array<double, 4> &x,
                                       const std::array<double, 4> &y,
                                       const std::array<double, 4> &z,
                                       const LameConstants         &lame,
                                       const double                 node_mass);

    /**
     * Eigenvalues (ascending) and eigenvectors (columns of @p vectors) of a
     * symmetric N x N matrix (Matrix6 or Matrix12), by cyclic Jacobi
     * rotations; the eigenvalues in the units of @p matrix.
     */
    template <std::size_t N>
    void
    symmetric_eigen(const std::array<std::array<double, N>, N> &matrix,
                    std::array<double, N>                      &values,
                    std::array<std::array<double, N>, N>       &vectors);
  } // namespace discrete
} // namespace tmfdem

#endif
