/**
 * @file
 * One triangle's stress and nodal forces in one explicit step, written once
 * for the element-by-element loop (Number = double) and for the vector
 * batches (Number = a GCC vector of doubles, one triangle per lane;
 * source/discrete/node_update.cc): the deformation gradient F from the
 * current nodes and the inverse initial basis (paper Eq. 39), its elastic
 * part F_e = F / s, the Cauchy stress of Eq. 44 on F_e
 * (constitutive::elastic_stress()) plus the anisotropic correction of joint
 * compliance compensation (anisotropic_stress()), the viscous stress
 * 2 eta sym(dF/dt F^-1) (Eqs. 45-46) and the nodal forces of both
 * (nodal_forces()); then each node's resultant, its damped velocity
 * update and the works of its forces over the step (NodeForces,
 * damped_velocity(), node_works()). Both instantiations perform the same
 * operations in the same order, so a triangle in a batch gets bitwise the
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
    /** What element_response() computes for one triangle (or one per
     *  lane). */
    template <typename Number>
    struct ElementResponse
    {
      Number det;            ///< det F [-] (not > 0: an inverted triangle)
      Number sxx, syy, sxy;  ///< elastic and anisotropic Cauchy stress [Pa]
      Number vxx, vyy, vxy;  ///< viscous stress [Pa]; exactly +0 where eta = 0
      Number fex[3], fey[3]; ///< nodal forces of the elastic stress [N/m]
      Number fvx[3], fvy[3]; ///< of the viscous stress [N/m]; +0 where eta = 0
    };

    /**
     * [u1 - u0, u2 - u0; v1 - v0, v2 - v0] times the inverse initial basis
     * @p ib (row-major 2x2) [1/m], written row-major to @p G: the
     * deformation gradient from the nodes' positions (@p u, @p v = x, y)
     * and its rate from their velocities, in the order of Eigen's 2x2
     * product.
     */
    template <typename Number>
    __attribute__((always_inline)) inline void
    times_inverse_basis(const Number *u,
                        const Number *v,
                        const Number *ib,
                        Number       *G)
    {
      const Number b00 = u[1] - u[0], b01 = u[2] - u[0];
      const Number b10 = v[1] - v[0], b11 = v[2] - v[0];
      G[0] = b00 * ib[0] + b01 * ib[2];
      G[1] = b00 * ib[1] + b01 * ib[3];
      G[2] = b10 * ib[0] + b11 * ib[2];
      G[3] = b10 * ib[1] + b11 * ib[3];
    }

    /**
     * The stress and nodal forces of a constant-strain triangle with
     * current nodes @p x, @p y [m] and nodal velocities @p vx, @p vy [m/s]
     * (three each), inverse initial basis @p inverse_basis (row-major 2x2)
     * [1/m], inverse thermal stretch @p inverse_stretch (1 / s) [-], Lame
     * constants @p mu, @p lambda [Pa], Mandel components of the anisotropic
     * correction @p anisotropy (six, or nullptr for none) [Pa] and
     * viscosity @p eta [Pa s] (no viscous stress where eta is not > 0).
     */
    template <typename Number>
    __attribute__((always_inline)) inline void
    element_response(const Number            *x,
                     const Number            *y,
                     const Number            *vx,
                     const Number            *vy,
                     const Number            *inverse_basis,
                     const Number             inverse_stretch,
                     const Number             mu,
                     const Number             lambda,
                     const Number            *anisotropy,
                     const Number             eta,
                     ElementResponse<Number> &r)
    {
      // F = [x1 - x0, x2 - x0; y1 - y0, y2 - y0] Fi^-1
      Number F[4];
      times_inverse_basis(x, y, inverse_basis, F);
      const Number F00 = F[0], F01 = F[1], F10 = F[2], F11 = F[3];
      r.det = F00 * F11 - F10 * F01;
      // F_e = F / s; Eq. 44 and the anisotropic correction on it
      const Number f00 = F00 * inverse_stretch, f01 = F01 * inverse_stretch;
      const Number f10 = F10 * inverse_stretch, f11 = F11 * inverse_stretch;
      constitutive::elastic_stress(f00,
                                   f01,
                                   f10,
                                   f11,
                                   mu,
                                   lambda,
                                   r.sxx,
                                   r.syy,
                                   r.sxy);
      if (anisotropy != nullptr)
        {
          Number axx, ayy, axy;
          anisotropic_stress(f00, f01, f10, f11, anisotropy, axx, ayy, axy);
          r.sxx += axx;
          r.syy += ayy;
          r.sxy += axy;
        }
      nodal_forces(r.sxx, r.syy, r.sxy, x, y, r.fex, r.fey);

      // viscous stress 2 eta sym(dF/dt F^-1) where eta > 0, else +0; a
      // single triangle skips the arithmetic where eta is not > 0
      const Number zero{};
      bool         any_viscous = true;
      if constexpr (std::is_same_v<Number, double>)
        any_viscous = eta > 0.;
      if (!any_viscous)
        {
          r.vxx = r.vyy = r.vxy = zero;
          for (unsigned int k = 0; k < 3; ++k)
            r.fvx[k] = r.fvy[k] = zero;
          return;
        }
      // dF/dt from the nodal velocities
      Number D[4];
      times_inverse_basis(vx, vy, inverse_basis, D);
      const Number D00 = D[0], D01 = D[1], D10 = D[2], D11 = D[3];
      // F^-1 as Eigen forms it: 1 / det, then the cofactors times it
      const Number invdet = 1. / r.det;
      const Number G00 = F11 * invdet, G10 = -F10 * invdet;
      const Number G01 = -F01 * invdet, G11 = F00 * invdet;
      const Number L00 = D00 * G00 + D01 * G10, L01 = D00 * G01 + D01 * G11;
      const Number L10 = D10 * G00 + D11 * G10, L11 = D10 * G01 + D11 * G11;
      const auto   viscous = eta > 0.;
      r.vxx                = viscous ? Number(2. * eta * L00) : zero;
      r.vyy                = viscous ? Number(2. * eta * L11) : zero;
      r.vxy                = viscous ? Number(eta * (L01 + L10)) : zero;
      Number fvx[3], fvy[3];
      nodal_forces(r.vxx, r.vyy, r.vxy, x, y, fvx, fvy);
      for (unsigned int k = 0; k < 3; ++k)
        {
          r.fvx[k] = viscous ? fvx[k] : zero;
          r.fvy[k] = viscous ? fvy[k] : zero;
        }
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
