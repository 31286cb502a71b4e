/**
 * Unit checks of ThermoelasticMaterial: the consistent tangent against a
 * central finite difference of the first Piola-Kirchhoff stress, P = J sigma
 * F^-T, the small-strain limit of the finite-strain law, zero stress under
 * rigid rotation and free thermal expansion, and the restrained-sheet
 * stresses of both idealisations against their closed forms.
 */
#include <deal.II/base/symmetric_tensor.h>

#include <cmath>
#include <cstdio>
#include <tmfdem/continuum/thermoelastic_material.h>

using namespace tmfdem;

namespace
{
  int failures = 0;

  void
  expect(const bool condition, const char *what, const double value)
  {
    std::printf("%s: %s (%.3e)\n", condition ? "PASS" : "FAIL", what, value);
    failures += condition ? 0 : 1;
  }

  double
  max_abs(const Tensor<2, 2> &t)
  {
    double m = 0.;
    for (unsigned int i = 0; i < 2; ++i)
      for (unsigned int j = 0; j < 2; ++j)
        m = std::max(m, std::abs(t[i][j]));
    return m;
  }

  MaterialProperties
  table3_material()
  {
    MaterialProperties m;
    m.youngs_modulus        = 75.1e9;
    m.poisson_ratio         = 0.311;
    m.thermal_expansion     = 3e-6;
    m.reference_temperature = 20.;
    return m;
  }
} // namespace

int
main()
{
  const MaterialProperties properties = table3_material();
  const double E = properties.youngs_modulus, nu = properties.poisson_ratio,
               alpha = properties.thermal_expansion;
  Tensor<2, 2> grad_u;
  grad_u[0][0]   = 0.031;
  grad_u[0][1]   = -0.12;
  grad_u[1][0]   = 0.27;
  grad_u[1][1]   = -0.045;
  const double T = 20. + 8000.; // alpha dT = 0.024 (plane stress)

  for (const auto idealisation :
       {MechanicsParameters::Idealisation::plane_stress,
        MechanicsParameters::Idealisation::plane_strain})
    for (const auto measure : {MechanicsParameters::StrainMeasure::small,
                               MechanicsParameters::StrainMeasure::finite})
      {
        MechanicsParameters mechanics;
        mechanics.idealisation   = idealisation;
        mechanics.strain_measure = measure;
        const ThermoelasticMaterial material(properties, mechanics);
        const bool                  finite =
          measure == MechanicsParameters::StrainMeasure::finite;
        std::printf("--- %s, %s strain\n",
                    idealisation ==
                        MechanicsParameters::Idealisation::plane_stress ?
                      "plane stress" :
                      "plane strain",
                    finite ? "finite" : "small");

        // tangent against central differences
        const Tensor<4, 2> A     = material.tangent(grad_u, T);
        const double       h     = 1e-6;
        double             error = 0., scale = 0.;
        for (unsigned int k = 0; k < 2; ++k)
          for (unsigned int l = 0; l < 2; ++l)
            {
              Tensor<2, 2> plus = grad_u, minus = grad_u;
              plus[k][l] += h;
              minus[k][l] -= h;
              const Tensor<2, 2> difference = (material.first_piola(plus, T) -
                                               material.first_piola(minus, T)) /
                                              (2. * h);
              for (unsigned int i = 0; i < 2; ++i)
                for (unsigned int j = 0; j < 2; ++j)
                  {
                    error =
                      std::max(error,
                               std::abs(difference[i][j] - A[i][j][k][l]));
                    scale = std::max(scale, std::abs(A[i][j][k][l]));
                  }
            }
        expect(error < 1e-7 * scale,
               "tangent = finite difference of P",
               error / scale);

        // major symmetry (hyperelastic)
        double asymmetry = 0.;
        for (unsigned int i = 0; i < 2; ++i)
          for (unsigned int j = 0; j < 2; ++j)
            for (unsigned int k = 0; k < 2; ++k)
              for (unsigned int l = 0; l < 2; ++l)
                asymmetry =
                  std::max(asymmetry, std::abs(A[i][j][k][l] - A[k][l][i][j]));
        expect(asymmetry < 1e-12 * scale,
               "tangent has major symmetry",
               asymmetry / scale);

        // restrained sheet: grad u = 0
        const double       s   = material.in_plane_expansion() * (T - 20.);
        const double       lam = material.lambda(), mu = material.mu();
        const Tensor<2, 2> restrained = material.cauchy(Tensor<2, 2>(), T);
        const double       expected =
          finite ?
                  mu * (1. - (1. + s) * (1. + s)) +
              0.5 * lam * (1. / ((1. + s) * (1. + s)) - (1. + s) * (1. + s)) :
                  -2. * (lam + mu) * s;
        expect(std::abs(restrained[0][0] - expected) <
                   1e-12 * std::abs(expected) &&
                 std::abs(restrained[0][1]) < 1e-9,
               "restrained sheet stress = closed form",
               std::abs(restrained[0][0] - expected) / std::abs(expected));
        const double idealisation_formula =
          idealisation == MechanicsParameters::Idealisation::plane_stress ?
            -E * alpha * (T - 20.) / (1. - nu) :
            -E * alpha * (T - 20.) / (1. - 2. * nu);
        if (!finite)
          expect(std::abs(restrained[0][0] - idealisation_formula) <
                   1e-12 * std::abs(idealisation_formula),
                 "small strain: -E alpha dT/(1-nu) (plane stress) or /(1-2nu) "
                 "(plane strain)",
                 std::abs(restrained[0][0] / idealisation_formula - 1.));

        // free expansion: F = (1 + beta dT) I gives no stress
        Tensor<2, 2> free_expansion;
        free_expansion[0][0] = free_expansion[1][1] = s;
        expect(max_abs(material.cauchy(free_expansion, T)) < 1e-12 * E,
               "free thermal expansion is stress free",
               max_abs(material.cauchy(free_expansion, T)) / E);

        if (finite)
          {
            // P = J sigma F^-T
            const Tensor<2, 2> F = unit_symmetric_tensor<2>() + grad_u;
            const Tensor<2, 2> P_from_sigma = determinant(F) *
                                              material.cauchy(grad_u, T) *
                                              transpose(invert(F));
            const double difference =
              max_abs(P_from_sigma - material.first_piola(grad_u, T));
            expect(difference < 1e-12 * max_abs(P_from_sigma),
                   "P = J sigma F^-T",
                   difference / max_abs(P_from_sigma));
            // rigid rotation by 90 degrees at the reference temperature
            Tensor<2, 2> rotation; // R - I
            rotation[0][0] = -1.;
            rotation[0][1] = -1.;
            rotation[1][0] = 1.;
            rotation[1][1] = -1.;
            expect(max_abs(material.cauchy(rotation, 20.)) < 1e-12 * E,
                   "90 degree rotation is stress free",
                   max_abs(material.cauchy(rotation, 20.)) / E);
            // small-strain limit
            MechanicsParameters linear = mechanics;
            linear.strain_measure = MechanicsParameters::StrainMeasure::small;
            const ThermoelasticMaterial small(properties, linear);
            const Tensor<2, 2>          tiny   = 1e-7 * grad_u;
            const double                T_tiny = 20. + 0.01;
            const double limit = max_abs(material.cauchy(tiny, T_tiny) -
                                         small.cauchy(tiny, T_tiny));
            expect(limit < 1e-5 * max_abs(small.cauchy(tiny, T_tiny)),
                   "finite -> small strain for small gradients",
                   limit / max_abs(small.cauchy(tiny, T_tiny)));
          }
      }
  std::printf(failures == 0 ? "all checks passed\n" : "%d checks failed\n",
              failures);
  return failures == 0 ? 0 : 1;
}
