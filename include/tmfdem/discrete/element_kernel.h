/**
 * @file
 * One element's stress and nodal forces in one explicit step, written once
 * for triangles (dim = 2) and tetrahedra (dim = 3), for the
 * element-by-element loop (Number = double) and for the vector batches
 * (Number = a GCC vector of doubles, one element per lane;
 * source/discrete/node_update.cc): the deformation gradient F from the
 * current nodes and the inverse initial basis (paper Eq. 39), its elastic
 * part F_e = F / s, the Cauchy stress of Eq. 44 on F_e
 * (constitutive::elastic_stress()) plus the anisotropic correction
 * of joint compliance compensation (anisotropic_stress()), the viscous
 * stress 2 eta sym(dF/dt F^-1) (Eqs. 45-46) and the nodal forces of both
 * (nodal_forces()); then each node's resultant, its damped velocity
 * update and the works of its forces over the step (NodeForces,
 * damped_velocity(), node_works()). Both number types perform the same
 * operations in the same order, so an element in a batch gets bitwise the
 * forces and nodes of the scalar loop (node_update.cc is compiled without
 * FMA contraction).
 */
#ifndef tmfdem_discrete_element_kernel_h
#define tmfdem_discrete_element_kernel_h

#include <tmfdem/discrete/solid.h>
#include <type_traits>

namespace tmfdem
{
  namespace discrete
  {
    /** What element_response() computes for one simplex (or one per
     *  lane): a triangle (dim = 2) or a tetrahedron (dim = 3). */
    template <int dim, typename Number>
    struct ElementResponse
    {
      Number det; ///< det F [-] (not > 0: an inverted element)
      /** Elastic and anisotropic Cauchy stress (symmetric) [Pa]. */
      Number stress[dim][dim];
      /** Viscous stress (symmetric) [Pa]; exactly +0 where eta = 0. */
      Number viscous[dim][dim];
      /** Nodal forces of the elastic stress, [node][component] [N/m in 2D,
       *  N in 3D]. */
      Number f_elastic[dim + 1][dim];
      /** Of the viscous stress; +0 where eta = 0. */
      Number f_viscous[dim + 1][dim];
    };

    /**
     * The inverse of @p F [-] as Eigen forms a fixed-size one: 1 / det F
     * (@p det), then the adjugate's entries times it, written to @p G.
     */
    template <int dim, typename Number>
    __attribute__((always_inline)) inline void
    inverse(const Number (&F)[dim][dim],
            const Number det,
            Number (&G)[dim][dim])
    {
      const Number invdet = 1. / det;
      if constexpr (dim == 2)
        {
          G[0][0] = F[1][1] * invdet;
          G[1][0] = -F[1][0] * invdet;
          G[0][1] = -F[0][1] * invdet;
          G[1][1] = F[0][0] * invdet;
        }
      else
        for (int i = 0; i < 3; ++i)
          for (int j = 0; j < 3; ++j)
            {
              // adj(F)_ij = cofactor C_ji
              const int r0 = (j + 1) % 3, r1 = (j + 2) % 3;
              const int c0 = (i + 1) % 3, c1 = (i + 2) % 3;
              G[i][j] =
                (F[r0][c0] * F[r1][c1] - F[r0][c1] * F[r1][c0]) * invdet;
            }
    }

    /**
     * The stress and nodal forces of a constant-strain simplex (triangle or
     * tetrahedron) with current nodes @p x (x[i][a]: component i of node a)
     * [m] and nodal velocities @p v (the same layout) [m/s], inverse initial
     * basis @p inverse_basis (row-major dim x dim) [1/m], inverse thermal
     * stretch @p inverse_stretch (1 / s) [-], Lame constants @p mu,
     * @p lambda [Pa], Mandel components of the anisotropic correction
     * @p anisotropy (anisotropy_size<dim>, or nullptr for none) [Pa] and
     * viscosity
     * @p eta [Pa s] (no viscous stress where eta is not > 0).
     */
    template <int dim, typename Number>
    __attribute__((always_inline)) inline void
    element_response(const Number *const (&x)[dim],
                     const Number *const (&v)[dim],
                     const Number                 *inverse_basis,
                     const Number                  inverse_stretch,
                     const Number                  mu,
                     const Number                  lambda,
                     const Number                 *anisotropy,
                     const Number                  eta,
                     ElementResponse<dim, Number> &r)
    {
      // F = [x_1 - x_0, ...] Fi^-1
      Number F[dim][dim];
      times_inverse_basis<dim>(x, inverse_basis, F);
      r.det = constitutive::determinant<dim>(F);
      // F_e = F / s; Eq. 44 and the anisotropic correction on it
      Number Fe[dim][dim];
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j)
          Fe[i][j] = F[i][j] * inverse_stretch;
      constitutive::elastic_stress<dim>(Fe, mu, lambda, r.stress);
      if (anisotropy != nullptr)
        {
          Number a[dim][dim];
          anisotropic_stress<dim>(Fe, anisotropy, a);
          for (int i = 0; i < dim; ++i)
            for (int j = i; j < dim; ++j)
              {
                r.stress[i][j] += a[i][j];
                r.stress[j][i] = r.stress[i][j];
              }
        }
      nodal_forces<dim>(r.stress, x, r.f_elastic);

      // viscous stress 2 eta sym(dF/dt F^-1) where eta > 0, else +0; a
      // single element skips the arithmetic where eta is not > 0
      const Number zero{};
      bool         any_viscous = true;
      if constexpr (std::is_same_v<Number, double>)
        any_viscous = eta > 0.;
      if (!any_viscous)
        {
          for (int i = 0; i < dim; ++i)
            for (int j = 0; j < dim; ++j)
              r.viscous[i][j] = zero;
          for (int a = 0; a <= dim; ++a)
            for (int i = 0; i < dim; ++i)
              r.f_viscous[a][i] = zero;
          return;
        }
      // L = dF/dt F^-1 from the nodal velocities
      Number D[dim][dim], G[dim][dim], L[dim][dim];
      times_inverse_basis<dim>(v, inverse_basis, D);
      inverse<dim>(F, r.det, G);
      for (int i = 0; i < dim; ++i)
        for (int j = 0; j < dim; ++j)
          {
            Number l = D[i][0] * G[0][j];
            for (int k = 1; k < dim; ++k)
              l = l + D[i][k] * G[k][j];
            L[i][j] = l;
          }
      const auto viscous = eta > 0.;
      for (int i = 0; i < dim; ++i)
        {
          r.viscous[i][i] = viscous ? Number(2. * eta * L[i][i]) : zero;
          for (int j = i + 1; j < dim; ++j)
            {
              r.viscous[i][j] =
                viscous ? Number(eta * (L[i][j] + L[j][i])) : zero;
              r.viscous[j][i] = r.viscous[i][j];
            }
        }
      Number fv[dim + 1][dim];
      nodal_forces<dim>(r.viscous, x, fv);
      for (int a = 0; a <= dim; ++a)
        for (int i = 0; i < dim; ++i)
          r.f_viscous[a][i] = viscous ? fv[a][i] : zero;
    }

    /**
     * The forces on one node (or one per lane) in an explicit step, by
     * origin [N/m]: component 0 along x, 1 along y.
     */
    template <typename Number>
    struct NodeForces
    {
      Number elastic[2], viscous[2], joint[2], contact[2], gravity[2];

      /** The resultant along component @p i, summed in this order. */
      __attribute__((always_inline)) Number
      total(const unsigned int i) const
      {
        return elastic[i] + viscous[i] + joint[i] + contact[i] + gravity[i];
      }
    };

    /**
     * The new velocity of a node [m/s] under mass-proportional damping c
     * integrated exactly: v_new = a v_old + b / m f with
     * a = (1 - c dt / 2) / (1 + c dt / 2), @p b_over_mass = dt / ((1 + c dt
     * / 2) m) [s/kg m], the resultant force @p force [N/m].
     */
    template <typename Number>
    __attribute__((always_inline)) inline Number
    damped_velocity(const double damping_a,
                    const Number velocity_old,
                    const Number b_over_mass,
                    const Number force)
    {
      return damping_a * velocity_old + b_over_mass * force;
    }

    /** The works of a node's forces over one step [J/m], by origin. */
    template <typename Number>
    struct NodeWorks
    {
      Number elastic, viscous, joint, contact, gravity;
    };

    /**
     * The works of the forces @p f over the step's displacement
     * (@p ax, @p ay) = dt (v_old + v_new) / 2 [m] (the trapezoidal rule of
     * the energy balance, doc/theory.md).
     */
    template <typename Number>
    __attribute__((always_inline)) inline NodeWorks<Number>
    node_works(const NodeForces<Number> &f, const Number ax, const Number ay)
    {
      NodeWorks<Number> w;
      w.elastic = f.elastic[0] * ax + f.elastic[1] * ay;
      w.viscous = f.viscous[0] * ax + f.viscous[1] * ay;
      w.joint   = f.joint[0] * ax + f.joint[1] * ay;
      w.contact = f.contact[0] * ax + f.contact[1] * ay;
      w.gravity = f.gravity[0] * ax + f.gravity[1] * ay;
      return w;
    }
  } // namespace discrete
} // namespace tmfdem

#endif
