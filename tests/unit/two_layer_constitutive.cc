// The one constitutive core (base/constitutive.h) as both layers use it:
// the continuum ThermoelasticMaterial (finite strain, deal.II tensors,
// Eq. 44 on F_e = F / s) and the discrete constant-strain triangle's law
// (solid.h on Matrix2, F_e formed as the explicit hot path forms it) give
// the same Cauchy stress for the same deformation gradient F and
// temperature change dT, in plane stress and plane strain, with the same
// Lame constants and thermal stretch; and both layers' stress meets closed
// forms: the restrained sheet (F = I) at finite and at small alpha dT, and
// zero stress under free expansion with a finite rotation.

#include <deal.II/base/tensor.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <tmfdem/base/constitutive.h>
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

  constexpr double reference_temperature = 20.; ///< [C]

  MaterialProperties
  rock()
  {
    MaterialProperties properties;
    properties.youngs_modulus        = 37e9;
    properties.poisson_ratio         = 0.27;
    properties.thermal_expansion     = 8e-6;
    properties.reference_temperature = reference_temperature;
    return properties;
  }

  constexpr constitutive::Idealisation idealisations[] = {
    constitutive::Idealisation::plane_stress,
    constitutive::Idealisation::plane_strain};

  MechanicsParameters
  finite_strain(const constitutive::Idealisation idealisation)
  {
    MechanicsParameters mechanics;
    mechanics.idealisation   = idealisation;
    mechanics.strain_measure = MechanicsParameters::StrainMeasure::finite;
    return mechanics;
  }

  /** Both layers' Cauchy stress for one F and temperature [Pa]. */
  struct TwoStresses
  {
    Tensor<2, 2>      continuum;
    discrete::Stress2 discrete;
  };

  TwoStresses
  both_layers(const MaterialProperties        &properties,
              const constitutive::Idealisation idealisation,
              const Case                      &k)
  {
    const ThermoelasticMaterial<2> continuum(properties,
                                             finite_strain(idealisation));
    Tensor<2, 2>                   grad_u;
    grad_u[0][0] = k.f00 - 1.;
    grad_u[0][1] = k.f01;
    grad_u[1][0] = k.f10;
    grad_u[1][1] = k.f11 - 1.;

    // the discrete layer as source/discrete/node_update.cc does it:
    // F_e = F (1 / s), Eq. 44 on F_e with the element's Lame constants
    const discrete::LameConstants lame =
      discrete::lame_constants(properties.youngs_modulus,
                               properties.poisson_ratio,
                               idealisation);
    const double s =
      discrete::thermal_stretch(properties.thermal_expansion,
                                properties.poisson_ratio,
                                k.temperature - reference_temperature,
                                idealisation);
    const double            inv_s = 1. / s;
    const discrete::Matrix2 Fe =
      discrete::matrix2(k.f00, k.f01, k.f10, k.f11) * inv_s;
    return {continuum.cauchy(grad_u, k.temperature),
            discrete::elastic_stress(Fe, lame)};
  }

  /**
   * Every component of both layers' stress within @p tol of @p xx, @p yy,
   * @p xy [Pa]; returns the largest deviation [Pa].
   */
  double
  expect_both(const TwoStresses &t,
              const double       xx,
              const double       yy,
              const double       xy,
              const double       tol)
  {
    EXPECT_NEAR(t.continuum[0][0], xx, tol);
    EXPECT_NEAR(t.continuum[1][1], yy, tol);
    EXPECT_NEAR(t.continuum[0][1], xy, tol);
    EXPECT_NEAR(t.continuum[1][0], xy, tol);
    EXPECT_NEAR(t.discrete.xx, xx, tol);
    EXPECT_NEAR(t.discrete.yy, yy, tol);
    EXPECT_NEAR(t.discrete.xy, xy, tol);
    return std::max({std::abs(t.continuum[0][0] - xx),
                     std::abs(t.continuum[1][1] - yy),
                     std::abs(t.continuum[0][1] - xy),
                     std::abs(t.continuum[1][0] - xy),
                     std::abs(t.discrete.xx - xx),
                     std::abs(t.discrete.yy - yy),
                     std::abs(t.discrete.xy - xy)});
  }
} // namespace

TEST(TwoLayerConstitutive, SameStressForSameDeformationAndTemperature)
{
  const MaterialProperties properties = rock();
  const double             angle      = 0.7; // a finite rotation [rad]
  const double             c = std::cos(angle), s = std::sin(angle);
  const Case               cases[] = {
                  {1., 0., 0., 1., 20.},  // reference state
                  {1., 0., 0., 1., 520.}, // free heating, restrained
                  {1.01, 0.003, -0.002, 0.995, -80.}, // small strain, cooling
                  {1.2, 0.1, 0.05, 0.9, 300.},        // finite strain, heating
                  {c * 1.05, -s * 0.98, s * 1.05, c * 0.98, 150.}, // rotated stretch
  };
  double worst = 0.; // relative to the stress scale
  for (const auto idealisation : idealisations)
    {
      const ThermoelasticMaterial<2> continuum(properties,
                                               finite_strain(idealisation));
      const discrete::LameConstants  lame =
        discrete::lame_constants(properties.youngs_modulus,
                                 properties.poisson_ratio,
                                 idealisation);
      EXPECT_NEAR(lame.mu, continuum.mu(), 1e-12 * continuum.mu());
      EXPECT_NEAR(lame.lambda, continuum.lambda(), 1e-12 * continuum.mu());
      for (const Case &k : cases)
        {
          EXPECT_NEAR(discrete::thermal_stretch(properties.thermal_expansion,
                                                properties.poisson_ratio,
                                                k.temperature -
                                                  reference_temperature,
                                                idealisation),
                      continuum.thermal_stretch(k.temperature),
                      1e-15);
          const TwoStresses t = both_layers(properties, idealisation, k);
          const double      scale =
            std::max(1e6,
                     std::abs(t.continuum[0][0]) + std::abs(t.continuum[1][1]));
          worst = std::max(worst,
                           expect_both(t,
                                       t.continuum[0][0],
                                       t.continuum[1][1],
                                       t.continuum[0][1],
                                       1e-12 * scale) /
                             scale);
        }
    }
  std::printf("largest difference between the layers: %.3e of the stress "
              "scale (bound 1e-12)\n",
              worst);
}

// F = I, heated: F_e = I / s, J = 1 / s^2, B = I / s^2, so Eq. 44 gives
// sigma_xx = sigma_yy = mu (1 - s^2) + lambda / 2 (1 / s^2 - s^2), with
// s = 1 + beta dT (beta = alpha in plane stress, (1 + nu) alpha in plane
// strain); at small beta dT this is the restrained sheet's
// -E alpha dT / (1 - nu) (plane stress) or -E alpha dT / (1 - 2 nu) (plane
// strain), with relative error (lambda - mu) beta dT / (2 (mu + lambda)),
// below beta dT.
TEST(TwoLayerConstitutive, RestrainedSheetClosedForms)
{
  const MaterialProperties p  = rock();
  const double             E  = p.youngs_modulus;
  const double             nu = p.poisson_ratio;
  for (const auto idealisation : idealisations)
    {
      const bool strain =
        idealisation == constitutive::Idealisation::plane_strain;
      const double mu     = E / (2. * (1. + nu));
      const double lambda = strain ? E * nu / ((1. + nu) * (1. - 2. * nu)) :
                                     E * nu / (1. - nu * nu);
      const double beta =
        strain ? (1. + nu) * p.thermal_expansion : p.thermal_expansion;
      // finite: alpha dT = 0.04 (5000 K of this rock: a stretch test of the
      // law, not a physical state)
      {
        const double dT = 5000.;
        const double s  = 1. + beta * dT;
        const double sigma =
          mu * (1. - s * s) + 0.5 * lambda * (1. / (s * s) - s * s);
        const TwoStresses t =
          both_layers(p, idealisation, {1., 0., 0., 1., 20. + dT});
        std::printf("%s, beta dT = %.3g: Eq. 44 closed form to %.3e "
                    "relative (bound 1e-12)\n",
                    strain ? "plane strain" : "plane stress",
                    beta * dT,
                    expect_both(t, sigma, sigma, 0., 1e-12 * std::abs(sigma)) /
                      std::abs(sigma));
      }
      // small: dT = 1 K, beta dT ~ 1e-5
      {
        const double      dT    = 1.;
        const double      sigma = strain ?
                                    -E * p.thermal_expansion * dT / (1. - 2. * nu) :
                                    -E * p.thermal_expansion * dT / (1. - nu);
        const TwoStresses t =
          both_layers(p, idealisation, {1., 0., 0., 1., 20. + dT});
        std::printf(
          "%s, beta dT = %.3g: restrained sheet to %.3e relative "
          "(bound beta dT)\n",
          strain ? "plane strain" : "plane stress",
          beta * dT,
          expect_both(t, sigma, sigma, 0., beta * dT * std::abs(sigma)) /
            std::abs(sigma));
      }
    }
}

// F = s R: the free thermal expansion s = 1 + beta dT with a 1 rad
// rotation R is stress-free in both layers (Eq. 44 on F_e = R: J = 1,
// B = I), to round-off of E.
TEST(TwoLayerConstitutive, FreeExpansionWithRotationIsStressFree)
{
  const MaterialProperties p = rock();
  const double             c = std::cos(1.), s = std::sin(1.);
  for (const auto idealisation : idealisations)
    {
      const double dT      = 300.;
      const double stretch = constitutive::thermal_stretch(p.thermal_expansion,
                                                           p.poisson_ratio,
                                                           dT,
                                                           idealisation);
      const TwoStresses t  = both_layers(p,
                                        idealisation,
                                        {stretch * c,
                                          -stretch * s,
                                          stretch * s,
                                          stretch * c,
                                          reference_temperature + dT});
      std::printf("free expansion, rotated: largest stress %.3e E (bound "
                  "1e-14 E)\n",
                  expect_both(t, 0., 0., 0., 1e-14 * p.youngs_modulus) /
                    p.youngs_modulus);
    }
}
