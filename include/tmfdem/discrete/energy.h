/**
 * @file
 * Energy bookkeeping of the discrete layer: the balance of works and
 * stored energies (EnergyBalance, reported in history.csv and
 * summary.json) and the measurement of the stored terms at a state.
 */
#ifndef tmfdem_discrete_energy_h
#define tmfdem_discrete_energy_h

#include <tmfdem/discrete/discrete_model.h>
#include <tmfdem/discrete/solid.h>
#include <vector>

namespace tmfdem
{
  namespace discrete
  {
    /**
     * Energy terms of the discrete layer [J/m] (per unit thickness). Works
     * are integrated with the trapezoidal rule consistent with the central
     * difference scheme, so that kinetic energy + strain energy + joint,
     * contact and viscous work = external work + initial energy holds to the
     * time-integration error, which is reported as the balance error.
     */
    struct EnergyBalance
    {
      double kinetic              = 0.;
      double strain               = 0.;
      double initial_kinetic      = 0.;
      double initial_strain       = 0.;
      double joint_work           = 0.; ///< done on the joints
      double joint_stored         = 0.; ///< recoverable part, intact joints
      double contact_work         = 0.; ///< done on contacts (incl. friction)
      double friction_dissipation = 0.;
      double viscous_dissipation  = 0.;
      double external_work        = 0.; ///< gravity and driven/fixed bodies
      /** Strain energy put in by changes of the thermal stretch at fixed
       *  geometry (thermo-mechanical runs) [J/m]. */
      double thermal_work = 0.;
      double elastic_work = 0.; ///< done on the solid's elastic stress
      /** Strain and joint energy put in by the extrapolated starts of
       *  quasi-static relaxations (Discrete heat/Relaxation predictor)
       *  [J/m]. */
      double relaxation_work = 0.;

      /** Energy in minus energy accounted for [J/m]. */
      double
      balance_error() const
      {
        return (initial_kinetic + initial_strain + external_work +
                thermal_work + relaxation_work) -
               (kinetic + strain + joint_work + contact_work +
                viscous_dissipation);
      }
      /** The largest term, the scale of the relative balance error. */
      double
      scale() const;
    };

    /** Deformation gradient F of element @p e at the current node
     *  positions of @p model [-]. */
    inline Matrix2
    deformation_gradient(const DiscreteModel &model, const unsigned int e)
    {
      const unsigned int n0 = 3 * e;
      const double      *ib = &model.inverse_basis[4 * e];
      return element_basis(model.x[n0],
                           model.y[n0],
                           model.x[n0 + 1],
                           model.y[n0 + 1],
                           model.x[n0 + 2],
                           model.y[n0 + 2]) *
             matrix2(ib[0], ib[1], ib[2], ib[3]);
    }

    /** Strain energy of element @p e of @p model [J/m] at deformation
     *  gradient @p F and thermal stretch @p s (Eq. 44 on F_e = F / s, per
     *  reference area s^2 A) with Lame constants @p lame. */
    inline double
    element_strain_energy(const DiscreteModel &model,
                          const unsigned int   e,
                          const Matrix2       &F,
                          const double         s,
                          const LameConstants &lame,
                          const double        *anisotropy = nullptr)
    {
      const Matrix2 Fe  = F / s;
      double        psi = strain_energy_density(Fe, lame);
      if (anisotropy != nullptr)
        psi += anisotropic_energy_density(Fe, anisotropy);
      return model.reference_area[e] * s * s * psi;
    }

    /**
     * Sets the stored terms of @p balance at the current state of
     * @p model: kinetic energy 1/2 m |v|^2, strain energy of the elements
     * (Eq. 44 on F_e = F / s with their Lame constants @p element_lame, plus
     * the anisotropic correction of @p element_anisotropy, 6 per element,
     * where it is not empty) and
     * the energy stored in undamaged intact joints [J/m].
     */
    void
    measure_stored_energy(const DiscreteModel              &model,
                          const std::vector<LameConstants> &element_lame,
                          const std::vector<double>        &element_anisotropy,
                          EnergyBalance                    &balance);
  } // namespace discrete
} // namespace tmfdem

#endif
