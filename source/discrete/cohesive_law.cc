#include <cmath>
#include <tmfdem/discrete/cohesive_law.h>

namespace tmfdem
{
  namespace discrete
  {
    const std::vector<std::pair<std::string, SofteningLaw>> &
    softening_law_registry()
    {
      static const std::vector<std::pair<std::string, SofteningLaw>> laws =
        {{"Munjiza", SofteningLaw::munjiza}, {"linear", SofteningLaw::linear}};
      return laws;
    }

    double
    softening_value(const SofteningLaw law, const double D)
    {
      return law == SofteningLaw::linear ? softening<SofteningLaw::linear>(D) :
                                           softening<SofteningLaw::munjiza>(D);
    }

    namespace
    {
      /** The integral of z over [0, 1] by composite Simpson; z is smooth,
       *  2000 intervals give 1e-12. */
      double
      integrate_softening(const SofteningLaw law)
      {
        const unsigned int n = 2000;
        const double       h = 1. / n;
        double sum = softening_value(law, 0.) + softening_value(law, 1.);
        for (unsigned int i = 1; i < n; ++i)
          sum += (i % 2 ? 4. : 2.) * softening_value(law, i * h);
        return sum * h / 3.;
      }
    } // namespace

    double
    softening_integral(const SofteningLaw law)
    {
      // once per law, not per joint (2000 evaluations of z each: most of
      // the set-up of a large mesh)
      static const double munjiza = integrate_softening(SofteningLaw::munjiza);
      static const double linear  = integrate_softening(SofteningLaw::linear);
      return law == SofteningLaw::linear ? linear : munjiza;
    }

    bool
    make_joint_constants(const double       tensile_strength,
                         const double       cohesion,
                         const double       friction_angle_degrees,
                         const double       fracture_energy_I,
                         const double       fracture_energy_II,
                         const double       normal_penalty,
                         const double       tangential_penalty,
                         const double       length,
                         const SofteningLaw law,
                         JointConstants    &k)
    {
      k.normal_stiffness       = normal_penalty / length;
      k.tangential_stiffness   = tangential_penalty / length;
      k.tensile_strength       = tensile_strength;
      k.cohesion               = cohesion;
      k.friction_tangent       = std::tan(friction_angle_degrees * M_PI / 180.);
      k.inverse_opening_peak   = k.normal_stiffness / (2. * tensile_strength);
      k.inverse_slip_peak_open = k.tangential_stiffness / (2. * cohesion);
      const double integral    = softening_integral(law);
      const double pre_peak_I =
        4. / 3. * tensile_strength * tensile_strength / k.normal_stiffness;
      const double pre_peak_II =
        4. / 3. * cohesion * cohesion / k.tangential_stiffness;
      if (fracture_energy_I <= pre_peak_I || fracture_energy_II <= pre_peak_II)
        return false;
      k.softening_width_I =
        (fracture_energy_I - pre_peak_I) / (integral * tensile_strength);
      k.softening_width_II =
        (fracture_energy_II - pre_peak_II) / (integral * cohesion);
      return true;
    }

    double
    stored_joint_energy(const double o, const double s, const JointConstants &k)
    {
      double energy = 0.;
      if (o < 0.)
        energy += 0.5 * k.normal_stiffness * o * o;
      else
        {
          const double op = 2. * k.tensile_strength / k.normal_stiffness;
          const double r  = std::min(o / op, 1.);
          energy += k.tensile_strength * op * (r * r - r * r * r / 3.);
        }
      const double compression = o < 0. ? k.normal_stiffness * o : 0.;
      const double fs          = k.cohesion - compression * k.friction_tangent;
      const double sp          = 2. * fs / k.tangential_stiffness;
      const double r           = std::min(std::abs(s) / sp, 1.);
      energy += fs * sp * (r * r - r * r * r / 3.);
      return energy;
    }
  } // namespace discrete
} // namespace tmfdem
