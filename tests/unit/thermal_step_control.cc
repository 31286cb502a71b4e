// Unit tests of the quasi-static thermal step control near failure
// (coupling/quasi_static_relaxation.h, theory manual 8, "Thermal steps near
// failure"): joint j may rise per thermal step by
// a_j = max(c, f (1 - U_j)), c = Maximum utilisation change, f =
// Utilisation margin fraction once a joint of the model is damaged (0
// before), so the next step is at most
// min_j a_j dt / dU_j over the joints undamaged at both ends whose
// utilisation rose. The expected steps are worked out by hand from that
// rule; the schedule (Time step x growth^n) is made long enough not to
// bind.

#include <gtest/gtest.h>
#include <tmfdem/base/parameters.h>
#include <tmfdem/coupling/quasi_static_relaxation.h>
#include <tmfdem/discrete/discrete_parameters.h>
#include <vector>

using tmfdem::Parameters;
using tmfdem::coupling::QuasiStaticRelaxation;

namespace
{
  /** Time step 1 ms growing by 10 per step (after 3 steps the schedule
   *  allows 1 s), no cap, no break control, c = 0.01 and margin fraction
   *  @p f, from t = 0 to 100 s. */
  Parameters
  control_parameters(const double f)
  {
    Parameters parameters;
    parameters.time.start_time = 0.;
    parameters.time.end_time   = 100.;
    parameters.time.time_step  = 1e-3;
    auto &dh                = parameters.get<tmfdem::DiscreteHeatParameters>();
    dh.thermal_step_growth  = 10.;
    dh.maximum_thermal_step = 0.;
    dh.maximum_utilisation_change     = 0.01;
    dh.utilisation_margin_fraction    = f;
    dh.maximum_broken_joints_per_step = 0;
    dh.minimum_thermal_step           = 1e-9;
    return parameters;
  }

  /** The step chosen at t = 1 s after a step of 1 ms from @p start to
   *  @p end. */
  double
  next_step(const Parameters          &parameters,
            const std::vector<double> &start,
            const std::vector<double> &end)
  {
    QuasiStaticRelaxation control(parameters);
    control.record_utilisation(start, end, 1e-3, false);
    return control.next_thermal_step(1., 3, {});
  }
} // namespace

TEST(ThermalStepControl, FarFromThePeakAJointUsesAFractionOfItsMargin)
{
  // joint 0: 0.50 -> 0.53, a = max(0.01, 0.1 x 0.47) = 0.047: 1.5667 ms;
  // joint 1: 0.20 -> 0.26, a = 0.074: 0.074 / 0.06 ms = 1.2333 ms;
  // joint 2 fell, joint 3 damaged at the end: neither counts
  const Parameters parameters = control_parameters(0.1);
  EXPECT_NEAR(next_step(parameters,
                        {0.5, 0.2, 0.7, 0.6},
                        {0.53, 0.26, 0.4, -1.}),
              0.074 / 0.06 * 1e-3,
              1e-15);
}

TEST(ThermalStepControl, NearThePeakTheChangeRules)
{
  // 0.93 -> 0.95: a = max(0.01, 0.005) = 0.01, 0.01 / 0.02 ms = 0.5 ms;
  // the highest U (0.95 > 0.9) also caps the step at 0.01 x 1 s = 10 ms
  const Parameters parameters = control_parameters(0.1);
  EXPECT_NEAR(next_step(parameters, {0.93, 0.2}, {0.95, 0.21}), 0.5e-3, 1e-15);
}

TEST(ThermalStepControl, WithoutTheMarginFractionEveryJointHasTheChange)
{
  // f = 0: joint 1 of the first test gives 0.01 / 0.06 ms
  const Parameters parameters = control_parameters(0.);
  EXPECT_NEAR(next_step(parameters, {0.5, 0.2}, {0.53, 0.26}),
              0.01 / 0.06 * 1e-3,
              1e-15);
}

TEST(ThermalStepControl, UpsAndDownsFarFromThePeakDoNotHoldTheStep)
{
  // joints at 0.2-0.7 moving by up to 0.03 per step (the 3D disc after its
  // cracks open, joint 4 broken): none uses up its allowance in a step of
  // 1 ms, so the step may grow, to 0.1 x 0.28 / 0.02 ms = 1.4 ms (joint
  // 2), where c alone would cut it to a third of 1 ms
  const std::vector<double> start = {0.2, 0.45, 0.7, 0.68, -1.};
  const std::vector<double> end   = {0.23, 0.43, 0.72, 0.69, -1.};
  EXPECT_NEAR(next_step(control_parameters(0.1), start, end), 1.4e-3, 1e-15);
  EXPECT_NEAR(next_step(control_parameters(0.), start, end),
              0.01 / 0.03 * 1e-3,
              1e-15);
}

TEST(ThermalStepControl, BeforeTheFirstDamageEveryJointHasTheChange)
{
  // the joints of the first test, none damaged: the load still rises
  // smoothly, and c alone keeps the steps to the onset short, 0.01 / 0.06
  // ms (joint 1), whatever f says
  EXPECT_NEAR(next_step(control_parameters(0.1),
                        {0.5, 0.2, 0.7, 0.6},
                        {0.53, 0.26, 0.4, 0.61}),
              0.01 / 0.06 * 1e-3,
              1e-15);
}
