// Guest side of tests/arm/insn_count_plugin.c: the arm64 program asks the qemu plugin for the number of
// guest instructions executed so far. insnClock() has the signature of the components' monotonic clock
// (NearRangeTracker::setClock, FarRangeEstimator::setClock), so their per-stage "timing" fields, in us,
// read as thousands of instructions: instructions = timing_us * 1000.
#pragma once

#include <cstdint>

namespace visnav::armcost {

/// Opens the reply pipe and checks that the plugin answers. False when not run under
/// `qemu-aarch64 -plugin libinsncount.so` (natively, or without the plugin).
bool initInsnCounter();

/// Guest instructions executed so far (-1 if the plugin did not answer). Each call costs a fixed number of
/// instructions itself (insnCounterOverhead()).
std::int64_t insnCount();

/// insnCount() with the clock signature; counts its calls (insnClockCalls()).
std::int64_t insnClock();
std::int64_t insnClockCalls();

/// Instructions between two back-to-back insnClock() calls: the cost one clock read adds to an interval.
std::int64_t insnCounterOverhead();

}  // namespace visnav::armcost
