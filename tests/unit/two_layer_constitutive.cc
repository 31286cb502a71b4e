// The two layers' thermoelastic laws held against each other: the
// continuum ThermoelasticMaterial (finite strain, Eq. 44 on F_e = F / s) and
// the discrete constant-strain triangle's law (solid.h: lame_constants,
// thermal_stretch, elastic_stress) give the same Cauchy stress for the same
// deformation gradient F and temperature change dT, in plane stress and
// plane strain; and their Lame constants and thermal stretch agree.

#include <deal.II/base/tensor.h>

#include <cmath>
#include <gtest/gtest.h>
#include <tmfdem/base/parameters.h>
#include <tmfdem/continuum/thermoelastic_material.h>
#include <tmfdem/discrete/solid.h>

using namespace dealii;
using namespace tmfdem;

namespace
{
  struct Case
  {
    double f00, f01, f10, f11; ///< F [-]
    double temperature;        ///< [C]
  };
} // namespace

TEST(TwoLayerConstitutive, SameStressForSameDeformationAndTemperature)
{
  MaterialProperties properties;
  properties.youngs_modulus        = 37e9;
  properties.poisson_ratio         = 0.27;
  properties.thermal_expansion     = 8e-6;
  properties.reference_temperature = 20.;
  const double angle               = 0.7; // a finite rotation [rad]
  const double c = std::cos(angle), s = std::sin(angle);
  const Case   cases[] = {
      {1., 0., 0., 1., 20.},              // reference state
      {1., 0., 0., 1., 520.},             // free heating, restrained
      {1.01, 0.003, -0.002, 0.995, -80.}, // small strain, cooling
      {1.2, 0.1, 0.05, 0.9, 300.},        // finite strain and heating
      {c * 1.05, -s * 0.98, s * 1.05, c * 0.98, 150.}, // rotated stretch
  };
  for (const auto idealisation :
       {MechanicsParameters::Idealisation::plane_stress,
        MechanicsParameters::Idealisation::plane_strain})
    {
      MechanicsParameters mechanics;
      mechanics.idealisation   = idealisation;
      mechanics.strain_measure = MechanicsParameters::StrainMeasure::finite;
      const ThermoelasticMaterial continuum(properties, mechanics);
      const auto                  discrete_idealisation =
        idealisation == MechanicsParameters::Idealisation::plane_strain ?
                           discrete::Idealisation::plane_strain :
                           discrete::Idealisation::plane_stress;
      const discrete::LameConstants lame =
        discrete::lame_constants(properties.youngs_modulus,
                                 properties.poisson_ratio,
                                 discrete_idealisation);
      EXPECT_NEAR(lame.mu, continuum.mu(), 1e-12 * continuum.mu());
      EXPECT_NEAR(lame.lambda, continuum.lambda(), 1e-12 * continuum.mu());
      for (const Case &k : cases)
        {
          const double dT = k.temperature - 20.;
          const double stretch =
            discrete::thermal_stretch(properties.thermal_expansion,
                                      properties.poisson_ratio,
                                      dT,
                                      discrete_idealisation);
          EXPECT_NEAR(stretch, continuum.thermal_stretch(k.temperature), 1e-15);

          Tensor<2, 2> grad_u;
          grad_u[0][0]             = k.f00 - 1.;
          grad_u[0][1]             = k.f01;
          grad_u[1][0]             = k.f10;
          grad_u[1][1]             = k.f11 - 1.;
          const Tensor<2, 2> sigma = continuum.cauchy(grad_u, k.temperature);

          const discrete::Matrix2 Fe = {k.f00 / stretch,
                                        k.f01 / stretch,
                                        k.f10 / stretch,
                                        k.f11 / stretch};
          const discrete::Stress2 s2 = discrete::elastic_stress(Fe, lame);
          const double            scale =
            std::max(1e6, std::abs(sigma[0][0]) + std::abs(sigma[1][1]));
          EXPECT_NEAR(s2.xx, sigma[0][0], 1e-12 * scale);
          EXPECT_NEAR(s2.yy, sigma[1][1], 1e-12 * scale);
          EXPECT_NEAR(s2.xy, sigma[0][1], 1e-12 * scale);
          EXPECT_NEAR(s2.xy, sigma[1][0], 1e-12 * scale);
        }
    }
}
