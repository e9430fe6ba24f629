// REQUIREMENT (fsw/executive/README.md): the executive allocates nothing per cycle: 1000 cycles on the
// simulated clock with four tasks, failures, slips and throttled events.
#include <gtest/gtest.h>

#include <array>

#include "../../support/alloc_counter.hpp"
#include "visnav/executive/executive.hpp"

namespace visnav::exec {
namespace {

struct Work final : CycleTask {
  SimulatedClock* clock = nullptr;
  std::uint64_t fail_every = 0;
  std::uint64_t overrun_every = 0;
  Status runCycle(const CycleInfo& info) override {
    if (overrun_every != 0U && info.minor_frame % overrun_every == 0U) clock->advanceNs(300000000);
    if (fail_every != 0U && info.minor_frame % fail_every == 0U) return Status::kDegenerate;
    return Status::kOk;
  }
};

struct Sink final : ExecutiveObserver {
  std::uint64_t slips = 0;
  std::uint64_t failures = 0;
  void onSlip(const SlipEvent&) override { ++slips; }
  void onTaskFailure(const TaskFailureEvent&) override { ++failures; }
};

TEST(ExecutiveNoAlloc, ThousandSimulatedCyclesAllocateNothing) {
  SimulatedClock clock;
  clock.setWakeLatency(50000, 100000, 3);
  clock.setTaskTime(SimulatedTaskTime::kFixed);
  clock.setAllFixedTaskNs(1000000);
  Executive executive;
  ExecutiveParams params;
  params.event_throttle = 5;
  ASSERT_TRUE(executive.init(params, clock).ok);
  Work acquire;
  Work process;
  Work publish;
  Work health;
  process.clock = &clock;
  process.overrun_every = 97;
  publish.fail_every = 13;
  std::array<TaskId, 4> ids{};
  ASSERT_TRUE(executive.addTask(ids[0], "acquire", acquire).ok);
  ASSERT_TRUE(executive.addTask(ids[1], "process", process).ok);
  ASSERT_TRUE(executive.addTask(ids[2], "publish", publish).ok);
  ASSERT_TRUE(executive.addTask(ids[3], "health", health, 5, 4).ok);
  Sink sink;
  executive.setObserver(&sink);

  const std::uint64_t before = test::allocationCount();
  EXPECT_EQ(executive.run(1000), StopReason::kCycleLimit);
  const std::uint64_t after = test::allocationCount();
  EXPECT_EQ(after - before, 0U) << "allocations in 1000 cycles (malloc counted: " << test::countsMalloc()
                                << ")";

  // The run really exercised slips, failures and throttling.
  EXPECT_EQ(executive.counters().cycles, 1000U);
  EXPECT_GT(executive.counters().slips, 5U);
  EXPECT_GT(executive.counters().task_failures, 5U);
  EXPECT_EQ(sink.slips, 5U);
  EXPECT_GT(executive.counters().events_suppressed, 0U);
}

}  // namespace
}  // namespace visnav::exec
