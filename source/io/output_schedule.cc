#include <algorithm>
#include <cmath>
#include <tmfdem/base/parameters.h>
#include <tmfdem/io/output_schedule.h>

namespace tmfdem
{
  double
  OutputSchedule::default_tolerance(const double end)
  {
    return 1e-10 * std::max(1., std::abs(end));
  }

  OutputSchedule::OutputSchedule(const OutputParameters &output,
                                 const double            start,
                                 const double            end)
    : OutputSchedule(output.times,
                     output.interval,
                     start,
                     end,
                     default_tolerance(end))
  {}

  OutputSchedule::OutputSchedule(const std::vector<double> &listed,
                                 const double               interval,
                                 const double               start,
                                 const double               end,
                                 const double               tolerance)
    : time_tolerance(tolerance)
  {
    for (const double t : listed)
      if (t > start + tolerance && t < end - tolerance)
        output_times.push_back(t);
    if (interval > 0)
      for (double t = start + interval; t < end - tolerance; t += interval)
        output_times.push_back(t);
    output_times.push_back(end);
    std::sort(output_times.begin(), output_times.end());
    output_times.erase(std::unique(output_times.begin(),
                                   output_times.end(),
                                   [&](const double a, const double b) {
                                     return std::abs(a - b) < tolerance;
                                   }),
                       output_times.end());
  }

  bool
  OutputSchedule::reached(const double time, const double output_time) const
  {
    return std::abs(time - output_time) < time_tolerance;
  }

  double
  OutputSchedule::step_towards(const double time,
                               const double target,
                               const double dt)
  {
    return time + dt > target - 1e-3 * dt ? target - time : dt;
  }
} // namespace tmfdem
