#include "core/scenario/signal.h"

#include <gtest/gtest.h>

namespace terra::scenario {
namespace {

TEST(Signal, ShapesFollowTheirDefinitions) {
    Signal step;
    step.kind = Signal::Kind::kStep;
    step.value = 1.0, step.amplitude = 2.0, step.start_s = 5.0;
    EXPECT_EQ(step.at(4.999), 1.0);
    EXPECT_EQ(step.at(5.0), 3.0);

    Signal pulse = step;
    pulse.kind = Signal::Kind::kPulse;
    pulse.duration_s = 2.0;
    EXPECT_EQ(pulse.at(4.0), 1.0);
    EXPECT_EQ(pulse.at(6.0), 3.0);
    EXPECT_EQ(pulse.at(7.0), 1.0);  // [start, start + duration)

    Signal ramp = pulse;
    ramp.kind = Signal::Kind::kRamp;
    EXPECT_EQ(ramp.at(5.0), 1.0);
    EXPECT_DOUBLE_EQ(ramp.at(6.5), 1.0 + 2.0 * 0.75);
    EXPECT_EQ(ramp.at(100.0), 3.0);

    Signal table;
    table.kind = Signal::Kind::kTable;
    table.times_s = {0.0, 1.0, 3.0};
    table.values = {0.0, 2.0, -2.0};
    EXPECT_EQ(table.at(-1.0), 0.0);
    EXPECT_DOUBLE_EQ(table.at(0.5), 1.0);
    EXPECT_DOUBLE_EQ(table.at(2.0), 0.0);
    EXPECT_EQ(table.at(10.0), -2.0);

    EXPECT_EQ(Signal::constant(0.4).at(123.0), 0.4);
}

}  // namespace
}  // namespace terra::scenario
