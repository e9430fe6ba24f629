// The per-stage heartbeat behind the systemd watchdog: a cycle is healthy (WATCHDOG=1 due) only when every
// registered stage beat; misses are counted per stage, in total and in a row.
#include <gtest/gtest.h>

#include "visnav/app/heartbeat_monitor.hpp"

namespace visnav::app {
namespace {

constexpr CycleStage kAll[] = {CycleStage::kAcquire, CycleStage::kProcess, CycleStage::kPublish,
                               CycleStage::kHealth};

HeartbeatMonitor allRegistered() {
  HeartbeatMonitor monitor;
  monitor.reset();
  for (CycleStage stage : kAll) monitor.registerStage(stage);
  return monitor;
}

TEST(HeartbeatMonitor, EveryStageBeatStrokes) {
  HeartbeatMonitor monitor = allRegistered();
  for (int cycle = 0; cycle < 3; ++cycle) {
    for (CycleStage stage : kAll) monitor.beat(stage);
    EXPECT_TRUE(monitor.endCycle()) << cycle;
  }
  EXPECT_EQ(monitor.cycles(), 3U);
  EXPECT_EQ(monitor.healthyCycles(), 3U);
  for (CycleStage stage : kAll) {
    EXPECT_EQ(monitor.stage(stage).beats, 3U);
    EXPECT_EQ(monitor.stage(stage).missed, 0U);
  }
}

TEST(HeartbeatMonitor, OneMissingStageWithholdsTheStrokeAndIsCounted) {
  HeartbeatMonitor monitor = allRegistered();
  for (int cycle = 0; cycle < 4; ++cycle) {
    for (CycleStage stage : kAll)
      if (stage != CycleStage::kProcess) monitor.beat(stage);
    EXPECT_FALSE(monitor.endCycle()) << cycle;
    EXPECT_EQ(monitor.stage(CycleStage::kProcess).missed_run, static_cast<std::uint64_t>(cycle + 1));
  }
  EXPECT_EQ(monitor.stage(CycleStage::kProcess).missed, 4U);
  EXPECT_EQ(monitor.stage(CycleStage::kAcquire).missed, 0U);
  EXPECT_EQ(monitor.healthyCycles(), 0U);
  // The stage recovers: the run of misses ends and is reported once.
  for (CycleStage stage : kAll) monitor.beat(stage);
  EXPECT_TRUE(monitor.endCycle());
  EXPECT_EQ(monitor.stage(CycleStage::kProcess).ended_run, 4U);
  EXPECT_EQ(monitor.stage(CycleStage::kProcess).missed_run, 0U);
  for (CycleStage stage : kAll) monitor.beat(stage);
  EXPECT_TRUE(monitor.endCycle());
  EXPECT_EQ(monitor.stage(CycleStage::kProcess).ended_run, 0U);
}

TEST(HeartbeatMonitor, BeatsDoNotCarryOverToTheNextCycle) {
  HeartbeatMonitor monitor = allRegistered();
  for (CycleStage stage : kAll) {
    monitor.beat(stage);
    monitor.beat(stage);  // idempotent within a cycle
  }
  EXPECT_TRUE(monitor.endCycle());
  EXPECT_FALSE(monitor.endCycle());  // nobody beat since: a hung cycle is not healthy
  for (CycleStage stage : kAll) EXPECT_EQ(monitor.stage(stage).missed, 1U);
}

TEST(HeartbeatMonitor, OnlyRegisteredStagesCountAndNoneIsNeverHealthy) {
  HeartbeatMonitor monitor;
  monitor.reset();
  EXPECT_FALSE(monitor.endCycle());  // nothing registered: no evidence of health
  monitor.registerStage(CycleStage::kAcquire);
  monitor.beat(CycleStage::kAcquire);
  EXPECT_TRUE(monitor.endCycle());
  EXPECT_EQ(monitor.stage(CycleStage::kHealth).missed, 0U);  // not registered: never missed
  monitor.reset();
  EXPECT_FALSE(monitor.stage(CycleStage::kAcquire).registered);
  EXPECT_EQ(monitor.cycles(), 0U);
}

}  // namespace
}  // namespace visnav::app
