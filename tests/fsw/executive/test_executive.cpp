// The cyclic executive on the simulated clock: schedule order and phases, releases, slips without catch-up
// bursts, task failures, throttled events, stop requests (also from a signal handler), statistics. Tasks are
// named by the TaskId addTask() hands out, never by their position in the table.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <csignal>
#include <vector>

#include "visnav/executive/executive.hpp"

namespace visnav::exec {
namespace {

constexpr std::int64_t kMs = 1000000;
constexpr std::int64_t kPeriod5Hz = 200 * kMs;

struct TaskCall {
  TaskId task;
  CycleInfo info;
  std::int64_t now_ns;
};

// Records every call; optionally fails or stops at chosen frames.
struct Recorder {
  SimulatedClock* clock = nullptr;
  std::vector<TaskCall>* log = nullptr;
  TaskId task;                   // set by addTask()
  std::uint64_t fail_every = 0;  // fail on minor frames that are multiples of this (0: never)
  std::int64_t advance_ns = 0;   // simulated work done by the task itself
};

Status record(void* context, const CycleInfo& info) {
  auto* r = static_cast<Recorder*>(context);
  r->log->push_back({r->task, info, r->clock->nowNs()});
  r->clock->advanceNs(r->advance_ns);
  if (r->fail_every != 0U && info.minor_frame % r->fail_every == 0U) return Status::kNotConverged;
  return Status::kOk;
}

struct CountingObserver final : ExecutiveObserver {
  std::vector<SlipEvent> slips;
  std::vector<TaskFailureEvent> failures;
  void onSlip(const SlipEvent& e) override { slips.push_back(e); }
  void onTaskFailure(const TaskFailureEvent& e) override { failures.push_back(e); }
};

class ExecutiveTest : public ::testing::Test {
 protected:
  void SetUp() override { log.reserve(10000); }
  void start(const ExecutiveParams& params = {}) { ASSERT_TRUE(executive.init(params, clock).ok); }
  Recorder& add(const char* name, int divisor = 1, int offset = 0) {
    Recorder& r = recorders[static_cast<std::size_t>(executive.taskCount())];
    r = Recorder{&clock, &log, TaskId{}, 0, 0};
    EXPECT_TRUE(executive.addTask(r.task, name, record, &r, divisor, offset).ok);
    EXPECT_TRUE(r.task.valid());
    return r;
  }
  std::vector<std::uint64_t> framesOf(TaskId task) const {
    std::vector<std::uint64_t> frames;
    for (const TaskCall& r : log)
      if (r.task == task) frames.push_back(r.info.minor_frame);
    return frames;
  }

  SimulatedClock clock{1000 * kMs};  // an arbitrary epoch: nothing may assume time starts at 0
  Executive executive;
  std::array<Recorder, kMaxTasks> recorders{};
  std::vector<TaskCall> log;
};

TEST_F(ExecutiveTest, RunsTasksInRegistrationOrderAtAbsoluteReleases) {
  start();
  const std::array<TaskId, 4> ids = {add("acquire").task, add("process").task, add("publish").task,
                                     add("health").task};
  for (std::size_t a = 0; a < ids.size(); ++a)
    for (std::size_t b = a + 1; b < ids.size(); ++b) EXPECT_NE(ids[a], ids[b]);
  EXPECT_FALSE(TaskId{}.valid());
  EXPECT_EQ(executive.run(5), StopReason::kCycleLimit);
  ASSERT_EQ(log.size(), 20U);
  for (std::size_t i = 0; i < log.size(); ++i) {
    const auto k = static_cast<std::int64_t>(i / 4);
    EXPECT_EQ(log[i].task, ids[i % 4]);
    EXPECT_EQ(log[i].info.minor_frame, static_cast<std::uint64_t>(k));
    EXPECT_EQ(log[i].info.release_ns, 1000 * kMs + k * kPeriod5Hz);
    EXPECT_EQ(log[i].info.deadline_ns, log[i].info.release_ns + kPeriod5Hz);
    EXPECT_EQ(log[i].now_ns, log[i].info.release_ns);  // zero task time, zero wake latency
  }
  EXPECT_EQ(executive.counters().cycles, 5U);
  EXPECT_EQ(executive.counters().slips, 0U);
  EXPECT_EQ(executive.taskStats(ids[2]).runs, 5U);
  EXPECT_STREQ(executive.taskStats(ids[3]).name, "health");
  EXPECT_STREQ(executive.taskStats(TaskId{}).name, "");  // an invalid id: an empty record, no out-of-bounds
  EXPECT_EQ(executive.taskStats(TaskId{}).runs, 0U);
}

TEST_F(ExecutiveTest, DivisorAndOffsetSelectMinorFrames) {
  ExecutiveParams params;
  params.minor_frames_per_major = 4;  // 20 Hz ticks in a 5 Hz major frame
  start(params);
  const TaskId every = add("every").task;
  const TaskId fourth = add("fourth_at_1", 4, 1).task;
  const TaskId second = add("second_at_0", 2, 0).task;
  executive.run(8);
  EXPECT_EQ(executive.minorPeriodNs(), 50 * kMs);
  EXPECT_EQ(framesOf(every), (std::vector<std::uint64_t>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(framesOf(fourth), (std::vector<std::uint64_t>{1, 5}));
  EXPECT_EQ(framesOf(second), (std::vector<std::uint64_t>{0, 2, 4, 6}));
}

TEST_F(ExecutiveTest, OverrunSkipsToNextFutureReleaseWithoutBurst) {
  ExecutiveParams params;
  params.event_throttle = 100;
  start(params);
  CountingObserver observer;
  executive.setObserver(&observer);
  const TaskId work = add("work").task;
  // Frame 3 takes 450 ms, the others 10 ms; a task taking exactly the period ends on its deadline: no slip.
  struct Model final : TaskDurationModel {
    std::int64_t durationNs(TaskId, std::uint64_t frame) override {
      return frame == 3U ? 450 * kMs : frame == 1U ? kPeriod5Hz : 10 * kMs;
    }
  } model;
  clock.setDurationModel(&model);
  executive.run(6);
  // Frame 3 released at +600 ms ends at +1050 ms: releases 4 (+800) and 5 (+1000) are in the past and
  // dropped; the next cycle is frame 6 at +1200 ms, then 7, 8 on time.
  EXPECT_EQ(framesOf(work), (std::vector<std::uint64_t>{0, 1, 2, 3, 6, 7}));
  for (std::size_t i = 1; i < log.size(); ++i) EXPECT_GE(log[i].now_ns - log[i - 1].now_ns, kPeriod5Hz);
  EXPECT_EQ(executive.counters().slips, 1U);
  EXPECT_EQ(executive.counters().releases_skipped, 2U);
  EXPECT_EQ(executive.counters().worst_overrun_ns, 250 * kMs);
  ASSERT_EQ(observer.slips.size(), 1U);
  EXPECT_EQ(observer.slips[0].minor_frame, 3U);
  EXPECT_EQ(observer.slips[0].overrun_ns, 250 * kMs);
  EXPECT_EQ(observer.slips[0].releases_skipped, 2U);
  EXPECT_EQ(executive.taskStats(work).exec.maxNs(), 450 * kMs);
}

TEST_F(ExecutiveTest, PersistentOverrunRunsEveryOtherReleaseAndThrottlesEvents) {
  ExecutiveParams params;
  params.event_throttle = 2;
  params.sim_task_time = static_cast<int>(SimulatedTaskTime::kFixed);
  params.sim_task_us = 250000.0;  // 250 ms of work in a 200 ms frame
  start(params);
  clock.applyParams(params);
  CountingObserver observer;
  executive.setObserver(&observer);
  const TaskId slow = add("slow").task;
  executive.run(5);
  EXPECT_EQ(framesOf(slow), (std::vector<std::uint64_t>{0, 2, 4, 6, 8}));
  EXPECT_EQ(executive.counters().slips, 5U);
  EXPECT_EQ(executive.counters().releases_skipped, 5U);
  EXPECT_EQ(observer.slips.size(), 2U);
  EXPECT_EQ(executive.counters().events_suppressed, 3U);
  EXPECT_EQ(executive.counters().worst_overrun_ns, 50 * kMs);
}

TEST_F(ExecutiveTest, FailingTaskIsCountedAndNeverStopsTheCycle) {
  ExecutiveParams params;
  params.event_throttle = 1;
  start(params);
  CountingObserver observer;
  executive.setObserver(&observer);
  const TaskId before = add("ok_before").task;
  Recorder& flaky = add("flaky");
  flaky.fail_every = 3;  // fails on frames 0, 3, 6, 9
  const TaskId after = add("ok_after").task;
  executive.run(10);
  EXPECT_EQ(executive.taskStats(before).runs, 10U);
  EXPECT_EQ(executive.taskStats(after).runs, 10U);  // the task after the failing one still runs every cycle
  EXPECT_EQ(executive.taskStats(flaky.task).failures, 4U);
  EXPECT_EQ(executive.taskStats(flaky.task).last_failure, Status::kNotConverged);
  EXPECT_EQ(executive.taskStats(before).failures, 0U);
  EXPECT_EQ(executive.counters().task_failures, 4U);
  ASSERT_EQ(observer.failures.size(), 1U);
  EXPECT_STREQ(observer.failures[0].name, "flaky");
  EXPECT_EQ(observer.failures[0].task, flaky.task);
  EXPECT_EQ(observer.failures[0].status, Status::kNotConverged);
  EXPECT_EQ(executive.counters().events_suppressed, 3U);
}

TEST_F(ExecutiveTest, StopRequestEndsTheLoopAfterTheCurrentCycle) {
  start();
  add("first");
  struct Stopper final : CycleTask {
    Executive* executive = nullptr;
    Status runCycle(const CycleInfo& info) override {
      if (info.minor_frame == 4U) executive->requestStop();
      return Status::kOk;
    }
  } stopper;
  stopper.executive = &executive;
  TaskId stopper_id;
  ASSERT_TRUE(executive.addTask(stopper_id, "stopper", stopper).ok);
  const TaskId last = add("last").task;
  EXPECT_EQ(executive.run(0), StopReason::kStopRequested);
  EXPECT_EQ(executive.counters().cycles, 5U);
  EXPECT_EQ(framesOf(last).back(), 4U);                     // the cycle that asked to stop was completed
  EXPECT_EQ(executive.run(3), StopReason::kStopRequested);  // the request stays until cleared
  executive.clearStop();
  EXPECT_EQ(executive.run(3), StopReason::kCycleLimit);
}

Executive* g_signal_target = nullptr;
extern "C" void stopFromSignal(int) { g_signal_target->requestStop(); }

TEST_F(ExecutiveTest, StopRequestFromSignalHandler) {
  start();
  struct Raiser final : CycleTask {
    Status runCycle(const CycleInfo& info) override {
      if (info.minor_frame == 2U) std::raise(SIGUSR1);
      return Status::kOk;
    }
  } raiser;
  TaskId raiser_id;
  ASSERT_TRUE(executive.addTask(raiser_id, "raiser", raiser).ok);
  g_signal_target = &executive;
  struct sigaction action {};
  action.sa_handler = stopFromSignal;
  struct sigaction previous {};
  ASSERT_EQ(sigaction(SIGUSR1, &action, &previous), 0);
  const StopReason reason = executive.run(100);
  sigaction(SIGUSR1, &previous, nullptr);
  EXPECT_EQ(reason, StopReason::kStopRequested);
  EXPECT_EQ(executive.counters().cycles, 3U);
}

TEST_F(ExecutiveTest, ReleaseJitterStatisticsMatchTheWakeLatencyModel) {
  start();
  add("t");
  clock.setWakeLatency(100000, 200000, 7);  // 100 us + U[0, 200 us)
  executive.run(1000);
  // Reproduce the clock's draws independently: the first release needs no sleep (jitter 0).
  Pcg32 rng(7);
  std::vector<std::int64_t> expected{0};
  for (int k = 1; k < 1000; ++k)
    expected.push_back(100000 + static_cast<std::int64_t>(rng.uniform() * 200000.0));
  const DurationStats& jitter = executive.releaseJitter();
  ASSERT_EQ(jitter.count(), 1000U);
  EXPECT_EQ(jitter.maxNs(), *std::max_element(expected.begin(), expected.end()));
  double sum = 0.0;
  for (const std::int64_t v : expected) sum += static_cast<double>(v);
  EXPECT_NEAR(jitter.meanNs(), sum / 1000.0, 1e-6);
  std::sort(expected.begin(), expected.end());
  EXPECT_GE(jitter.quantileNs(0.99), expected[989]);
  EXPECT_LE(static_cast<double>(jitter.quantileNs(0.99)), static_cast<double>(expected[989]) * 17.0 / 16.0);
  EXPECT_EQ(executive.counters().slips, 0U);  // wake latency alone stays inside the frame
}

TEST_F(ExecutiveTest, ExecutionTimeStatisticsFromDurationModel) {
  start();
  const TaskId t = add("t").task;
  struct Model final : TaskDurationModel {
    std::int64_t durationNs(TaskId, std::uint64_t frame) override {
      return static_cast<std::int64_t>(frame % 100U + 1U) * 1000;
    }
  } model;
  clock.setDurationModel(&model);
  executive.run(1000);
  const DurationStats& s = executive.taskStats(t).exec;
  EXPECT_EQ(s.minNs(), 1000);
  EXPECT_EQ(s.maxNs(), 100000);
  EXPECT_DOUBLE_EQ(s.meanNs(), 50500.0);
  EXPECT_GE(s.quantileNs(0.99), 99000);  // 1..100 us ten times each: rank 990 is 99 us
  EXPECT_LE(s.quantileNs(0.99), 99000 * 17 / 16);
  EXPECT_EQ(executive.cycleBusy().maxNs(), 100000);
  executive.resetStatistics();
  EXPECT_EQ(executive.taskStats(t).exec.count(), 0U);
  EXPECT_STREQ(executive.taskStats(t).name, "t");
}

TEST_F(ExecutiveTest, MeasuredTaskTimeAdvancesTheSimulatedClock) {
  ExecutiveParams params;
  params.sim_task_time = static_cast<int>(SimulatedTaskTime::kMeasured);
  start(params);
  clock.applyParams(params);
  struct Busy final : CycleTask {
    Status runCycle(const CycleInfo&) override {
      const std::int64_t until = monotonicNowNs() + 2 * kMs;
      while (monotonicNowNs() < until) {
      }
      return Status::kOk;
    }
  } busy;
  TaskId busy_id;
  ASSERT_TRUE(executive.addTask(busy_id, "busy", busy).ok);
  executive.run(3);
  EXPECT_GE(executive.taskStats(busy_id).exec.minNs(), 2 * kMs);
  EXPECT_LT(executive.taskStats(busy_id).exec.minNs(), kPeriod5Hz);
}

TEST_F(ExecutiveTest, InitRejectsBadParametersAndAFullTable) {
  ExecutiveParams bad;
  bad.major_frame_hz = 1000.0;
  bad.minor_frames_per_major = 64;
  EXPECT_FALSE(executive.init(bad, clock).ok);
  TaskId id;
  EXPECT_FALSE(executive.addTask(id, "early", record, nullptr).ok);  // before init
  EXPECT_FALSE(id.valid());
  start();
  EXPECT_FALSE(executive.addTask(id, "no_fn", nullptr, nullptr).ok);
  EXPECT_FALSE(executive.addTask(id, "bad_offset", record, nullptr, 2, 2).ok);
  EXPECT_FALSE(executive.addTask(id, "bad_divisor", record, nullptr, 0, 0).ok);
  for (int i = 0; i < kMaxTasks; ++i) add("t");
  const LoadError full = executive.addTask(id, "one_too_many", record, nullptr);
  EXPECT_FALSE(full.ok);
  EXPECT_FALSE(id.valid());
  EXPECT_NE(full.message.find("one_too_many"), std::string::npos);
  EXPECT_EQ(executive.taskCount(), kMaxTasks);
}

TEST(ExecutiveParamsTest, MinorPeriodFromRates) {
  ExecutiveParams p;
  EXPECT_EQ(p.minorPeriodNs(), 200000000LL);
  p.major_frame_hz = 3.0;
  p.minor_frames_per_major = 2;
  EXPECT_EQ(p.minorPeriodNs(), 166666667LL);
  EXPECT_EQ(p.crossCheck(), nullptr);
}

}  // namespace
}  // namespace visnav::exec
