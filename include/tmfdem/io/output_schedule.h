/**
 * @file
 * The output schedule of a time-dependent run: the listed output times,
 * the multiples of an interval and the end time, sorted, with times that
 * lie within one time tolerance of each other written once. One helper for
 * every model, so that all of them agree on which times they write and
 * when a step has reached one of them.
 */
#ifndef tmfdem_io_output_schedule_h
#define tmfdem_io_output_schedule_h

#include <vector>

namespace tmfdem
{
  struct OutputParameters;

  /**
   * The times [s] at which a run from @p start to @p end writes its
   * outputs, and the tolerance that decides when a time has been reached.
   *
   * The times are: those of @p listed strictly inside (start, end) by more
   * than the tolerance, start + k @p interval (k = 1, 2, ..., accumulated by
   * repeated addition) below end - tolerance when @p interval > 0, and
   * @p end itself, sorted; of two times closer than the tolerance only the
   * earlier one is kept. The start time is not in the list: models write
   * their initial state before the first step.
   */
  class OutputSchedule
  {
  public:
    /**
     * The one time tolerance of the continuum models [s]:
     * 10^-10 max(1 s, |end|). Two times closer than this are the same
     * time; a step that ends within it of an output time has reached it.
     */
    static double
    default_tolerance(const double end);

    /** Output/Output times and Output/Output interval from @p start to
     *  @p end [s], with default_tolerance(end). */
    OutputSchedule(const OutputParameters &output,
                   const double            start,
                   const double            end);

    /** @p listed times and multiples of @p interval (0: none) from
     *  @p start to @p end, all in s, with @p tolerance [s] (>= 0). */
    OutputSchedule(const std::vector<double> &listed,
                   const double               interval,
                   const double               start,
                   const double               end,
                   const double               tolerance);

    /** The output times [s], sorted, the end time last. */
    const std::vector<double> &
    times() const
    {
      return output_times;
    }

    /** The time tolerance [s]. */
    double
    tolerance() const
    {
      return time_tolerance;
    }

    /** True if @p time [s] is @p output_time [s] within the tolerance. */
    bool
    reached(const double time, const double output_time) const;

    /**
     * The step [s] to take from @p time towards @p target [s] with the
     * nominal step @p dt [s]: @p dt, or target - time where the step would
     * pass the target or stop short of it by less than 10^-3 dt (no sliver
     * of a step is left before an output time).
     */
    static double
    step_towards(const double time, const double target, const double dt);

  private:
    std::vector<double> output_times;
    double              time_tolerance;
  };
} // namespace tmfdem

#endif
