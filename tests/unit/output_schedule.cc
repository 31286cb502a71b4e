// Unit tests of the output schedule (io/output_schedule.h): which times a
// run writes, that times within the tolerance are written once, and that a
// step towards an output time lands on it without leaving a sliver. The
// expected lists follow from the definitions (listed times strictly inside
// (start, end), start + k interval below end, the end; sorted, merged
// within the tolerance); they are written out by hand.

#include <gtest/gtest.h>
#include <tmfdem/base/parameters.h>
#include <tmfdem/io/output_schedule.h>
#include <vector>

using tmfdem::OutputSchedule;

TEST(OutputSchedule, ListedIntervalAndEnd)
{
  // 0.5 and 1.5 listed, every 1 s, from 0 to 3: 0.5 1 1.5 2 3
  const OutputSchedule      schedule({1.5, 0.5}, 1., 0., 3., 1e-10);
  const std::vector<double> expected = {0.5, 1., 1.5, 2., 3.};
  EXPECT_EQ(schedule.times(), expected);
}

TEST(OutputSchedule, OutsideTheRunAndTheStartAreDropped)
{
  // the start (written before the first step), times before it and after
  // the end are not in the list; the end is, once
  const OutputSchedule      schedule({-1., 2., 2.5, 7., 10., 12.},
                                0.,
                                2.,
                                10.,
                                1e-9);
  const std::vector<double> expected = {2.5, 7., 10.};
  EXPECT_EQ(schedule.times(), expected);
}

TEST(OutputSchedule, TimesWithinTheToleranceAreWrittenOnce)
{
  // 1 + 1e-12 is the output time 1 (the interval's); the earlier is kept
  const OutputSchedule schedule({1. + 1e-12, 1.25}, 0.5, 0., 1.5, 1e-10);
  ASSERT_EQ(schedule.times().size(), 4u);
  EXPECT_EQ(schedule.times()[0], 0.5);
  EXPECT_EQ(schedule.times()[1], 1.);
  EXPECT_EQ(schedule.times()[2], 1.25);
  EXPECT_EQ(schedule.times()[3], 1.5);
  EXPECT_TRUE(schedule.reached(1. + 5e-11, 1.));
  EXPECT_FALSE(schedule.reached(1. + 2e-10, 1.));
}

TEST(OutputSchedule, DefaultToleranceFromOutputParameters)
{
  EXPECT_EQ(OutputSchedule::default_tolerance(0.5), 1e-10);
  EXPECT_DOUBLE_EQ(OutputSchedule::default_tolerance(-1e4), 1e-6);
  tmfdem::OutputParameters output;
  output.times    = {250.};
  output.interval = 400.;
  const OutputSchedule      schedule(output, 0., 1000.);
  const std::vector<double> expected = {250., 400., 800., 1000.};
  EXPECT_EQ(schedule.times(), expected);
  EXPECT_DOUBLE_EQ(schedule.tolerance(), 1e-7);
}

TEST(OutputSchedule, ZeroToleranceKeepsEveryTime)
{
  // tolerance 0 (the discrete layer's explicit loop): nothing is merged
  const OutputSchedule      schedule({1., 1.}, 0., 0., 2., 0.);
  const std::vector<double> expected = {1., 1., 2.};
  EXPECT_EQ(schedule.times(), expected);
}

TEST(OutputSchedule, StepTowardsLandsWithoutASliver)
{
  // a full step that stays short of the target by more than 1e-3 dt
  EXPECT_EQ(OutputSchedule::step_towards(0., 1., 0.25), 0.25);
  // one that would pass it is shortened to land on it
  EXPECT_EQ(OutputSchedule::step_towards(0.875, 1., 0.25), 0.125);
  // one that would stop within 1e-3 dt of it takes the sliver along
  EXPECT_EQ(OutputSchedule::step_towards(0.5, 1.00001, 0.5), 1.00001 - 0.5);
}
