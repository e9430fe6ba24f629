// The daemon's cycle in-process: a replay camera on the simulated clock (deterministic), real DDS on loopback
// read back by a GroundLink in the same process. Checks the wiring against the pipeline driven directly, the
// command path, slips and task timings in Health, the bounded camera wait on the real clock and the log. The
// systemd watchdog: test_daemon_watchdog.cpp.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <array>
#include <chrono>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <thread>
#include <vector>

#include "daemon_test_support.hpp"
#include "visnav/app/daemon.hpp"
#include "visnav/executive/clock.hpp"
#include "visnav/replay/replay_camera.hpp"
#include "visnav/telemetry/ground_link.hpp"

namespace visnav::app {
namespace {

using test::kFrames;
using test::LogFile;
using test::partitionFor;
using test::replayConfig;

template <typename Sample, typename Take>
std::vector<Sample> drain(telemetry::GroundLink& link, Take take, std::size_t expected) {
  std::vector<Sample> out;
  std::array<Sample, telemetry::kMaxTakeBatch> batch{};
  std::array<dds_sample_info_t, telemetry::kMaxTakeBatch> infos{};
  for (int attempt = 0; attempt < 300 && out.size() < expected; ++attempt) {  // bounded: 3 s
    link.waitForData(10'000'000);
    const int n = (link.*take)(batch.data(), infos.data(), telemetry::kMaxTakeBatch);
    for (int i = 0; i < n; ++i)
      if (infos[static_cast<std::size_t>(i)].valid_data) out.push_back(batch[static_cast<std::size_t>(i)]);
  }
  return out;
}

TEST(Daemon, PublishesWhatThePipelineComputesForEveryFrame) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  ASSERT_FALSE(sequence.empty());
  test::TempDir dir("daemon");
  const std::string partition = partitionFor("daemon-wiring");
  const VisnavConfig config = test::configFromText(dir, replayConfig(sequence, partition, true));
  telemetry::GroundLink ground;
  ASSERT_TRUE(ground.init(config.telemetry, 256).ok);
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.simulated_clock = true;
  options.wait_subscribers = 1;
  options.apply_realtime = false;
  ASSERT_EQ(daemon.init(config, options), kExitOk) << log.text();
  // The writers keep the last [telemetry] history_depth samples (8): a reader that falls further behind loses
  // the oldest, by design (the newest pose matters in flight). On a loaded machine the in-process reader does
  // fall behind a replay that runs as fast as it can (seen in CI: 77 of 80 poses), so the frames are cycled
  // one at a time, each cycle's samples acknowledged before the next; run() then takes the end-of-stream
  // cycle. Discovery is two-sided too: init() waited for the writers to match the readers; a reader that has
  // not matched the writer yet drops what it sends.
  for (int i = 0; i < 1000 && !ground.allReadersMatched(); ++i)  // bounded: 10 s
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ASSERT_TRUE(ground.allReadersMatched());
  for (int cycle = 0; cycle < kFrames; ++cycle) {
    ASSERT_EQ(daemon.executive().run(1), exec::StopReason::kCycleLimit) << cycle;
    ASSERT_TRUE(daemon.telemetryWriter().waitForAcks(10'000'000'000LL)) << cycle;
  }
  ASSERT_EQ(daemon.run(), kExitOk);

  // Reference: the same pipeline driven directly over the same frames at their recorded times.
  replay::ReplayCamera camera({sequence, camera::Pacing::kAsFastAsPossible, false, 2});
  ASSERT_TRUE(camera.open().ok);
  nav::NavigationPipeline reference;
  ASSERT_TRUE(
      reference.init(PinholeCamera(camera.sequence().camera), camera.sequence().model, config.pipeline).ok);
  std::vector<nav::NavSolution> expected;
  std::vector<nav::NavMode> mode_after;
  Frame frame;
  while (camera.acquire(0, frame) == camera::AcquireResult::kFrame) {
    nav::NavSolution solution;
    reference.process(&frame, frame.exposure_time_ns, solution);
    expected.push_back(solution);
    mode_after.push_back(reference.mode());
    camera.release(frame);
  }
  ASSERT_EQ(expected.size(), static_cast<std::size_t>(kFrames));

  const auto poses = drain<visnav_PoseEstimate>(ground, &telemetry::GroundLink::takePose, kFrames);
  const auto healths = drain<visnav_Health>(ground, &telemetry::GroundLink::takeHealth, kFrames);
  ASSERT_EQ(poses.size(), static_cast<std::size_t>(kFrames));
  ASSERT_EQ(healths.size(), static_cast<std::size_t>(kFrames));
  for (std::size_t i = 0; i < poses.size(); ++i) {
    const nav::NavSolution& e = expected[i];
    EXPECT_EQ(poses[i].sample_number, i + 1);
    EXPECT_EQ(poses[i].frame_number, e.frame_number);
    EXPECT_EQ(poses[i].exposure_time_ns, e.exposure_time_ns);
    EXPECT_EQ(poses[i].mode, static_cast<std::uint8_t>(e.mode)) << i;
    EXPECT_EQ(poses[i].pose_valid, e.pose_valid) << i;
    EXPECT_EQ(poses[i].position_m[2], e.pose.t_c_m.z()) << i;  // bit-identical: same code, same inputs
    EXPECT_EQ(healths[i].sample_number, i + 1);
    EXPECT_EQ(healths[i].frames_processed, i + 1);
    EXPECT_EQ(healths[i].mode, static_cast<std::uint8_t>(mode_after[i])) << i;
  }
  EXPECT_EQ(healths.back().mode_transitions, reference.modes().transitionCount());
  EXPECT_TRUE(daemon.counters().end_of_stream);
  EXPECT_EQ(daemon.executive().counters().cycles,
            static_cast<std::uint64_t>(kFrames + 1));  // + end of stream
  // run() wrote the queue and joined the publisher thread: every sample queued, none dropped, all written.
  const telemetry::WriterCounters w = daemon.telemetryWriter().counters();
  EXPECT_EQ(w.samples_queued, 3U * kFrames);
  EXPECT_EQ(w.samples_dropped, 0U);
  EXPECT_EQ(w.samples_written, 3U * kFrames);

  const std::string text = log.text();
  EXPECT_NE(text.find("event=subscribers_matched readers=1"), std::string::npos) << text;
  EXPECT_NE(text.find("event=start config="), std::string::npos) << text;
  const std::string frames = std::to_string(kFrames);
  EXPECT_NE(text.find("event=end_of_stream driver=replay frames=" + frames + " action=stop"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("event=stop reason=end_of_stream cycles=" + std::to_string(kFrames + 1) +
                      " frames=" + frames + " cycles_without_frame=0"),
            std::string::npos)
      << text;
  // The delivered frames' sequence span: every frame of the replay, no gap (last - first + 1 = frames).
  EXPECT_NE(text.find(" camera_dropped=0 camera_timeouts=0 camera_errors=0 first_sequence=" +
                      std::to_string(expected.front().frame_number) +
                      " last_sequence=" + std::to_string(expected.back().frame_number) + " "),
            std::string::npos)
      << text;
  EXPECT_EQ(expected.back().frame_number - expected.front().frame_number + 1,
            static_cast<std::uint64_t>(kFrames));
  const std::string samples = std::to_string(3 * kFrames);
  EXPECT_NE(text.find(" samples_queued=" + samples + " samples_dropped=0 samples_written=" + samples +
                      " write_failures=0 "),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("event=stop_timing clock=simulated"), std::string::npos) << text;
  // One log line per mode transition, with its reason.
  std::size_t lines = 0;
  for (std::size_t at = text.find("event=mode_transition"); at != std::string::npos;
       at = text.find("event=mode_transition", at + 1))
    ++lines;
  EXPECT_EQ(lines, reference.modes().transitionCount());
  EXPECT_GE(lines, 1U);  // far range -> near range (the acquisition beside far range)
  EXPECT_EQ(daemon.pipeline().mode(), nav::NavMode::kNearRange);
}

TEST(Daemon, CommandsAreValidatedAndAcknowledgedInHealth) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  test::TempDir dir("daemon");
  const VisnavConfig config = test::configFromText(
      dir, replayConfig(sequence, partitionFor("daemon-commands"), true, "[daemon]\nplayback_loop = true\n"));
  telemetry::GroundLink ground;
  ASSERT_TRUE(ground.init(config.telemetry, 256).ok);
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.simulated_clock = true;
  options.wait_subscribers = 1;
  ASSERT_EQ(daemon.init(config, options), kExitOk) << log.text();
  ASSERT_TRUE(telemetry::waitForReaders(ground.commandWriter(), 1, 10'000'000'000LL));
  ASSERT_EQ(daemon.executive().run(3), exec::StopReason::kCycleLimit);

  auto commandRoundTrip = [&](std::uint32_t id, std::uint8_t kind) {
    EXPECT_EQ(ground.sendCommand(id, kind), DDS_RETCODE_OK);
    for (int i = 0; i < 200 && daemon.lastHealth().last_command.command_id != id; ++i) {  // bounded: 2 s
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      daemon.executive().run(1);
    }
    return daemon.lastHealth().last_command;
  };
  nav::CommandAck ack = commandRoundTrip(77, 2);  // standby
  EXPECT_EQ(ack.command_id, 77U);
  EXPECT_TRUE(ack.accepted);
  EXPECT_EQ(daemon.pipeline().mode(), nav::NavMode::kStandby);
  ack = commandRoundTrip(78, 9);  // no such kind
  EXPECT_EQ(ack.command_id, 78U);
  EXPECT_FALSE(ack.accepted);
  EXPECT_NE(std::string(ack.reason.data()).find('9'), std::string::npos) << ack.reason.data();
  EXPECT_EQ(daemon.pipeline().mode(), nav::NavMode::kStandby);
  ack = commandRoundTrip(79, 3);  // resume
  EXPECT_TRUE(ack.accepted) << ack.reason.data();
  EXPECT_NE(daemon.pipeline().mode(), nav::NavMode::kStandby);
  EXPECT_EQ(daemon.counters().commands, 3U);
  EXPECT_EQ(daemon.counters().commands_accepted, 2U);

  const std::string text = log.text();
  EXPECT_NE(text.find("event=command id=77 kind=standby raw_kind=2 accepted=yes"), std::string::npos) << text;
  EXPECT_NE(text.find("event=command id=78 kind=unknown raw_kind=9 accepted=no"), std::string::npos) << text;
  EXPECT_NE(text.find("to=standby reason="), std::string::npos) << text;
}

TEST(Daemon, SlipsAndTaskTimingsReachHealth) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  test::TempDir dir("daemon");
  // Each task "takes" 60 ms on the simulated clock: 240 ms per 200 ms cycle, a slip every cycle.
  const VisnavConfig config = test::configFromText(
      dir, replayConfig(sequence, partitionFor("daemon-slips"), false,
                        "[executive]\nsim_task_time = \"fixed\"\nsim_task_us = 60000.0\n"));
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.simulated_clock = true;
  ASSERT_EQ(daemon.init(config, options), kExitOk) << log.text();
  ASSERT_EQ(daemon.executive().run(6), exec::StopReason::kCycleLimit);
  const nav::HealthRecord& health = daemon.lastHealth();
  EXPECT_EQ(daemon.executive().counters().slips, 6U);
  EXPECT_EQ(health.cycle_slips, 5U);  // the sixth slip is known only after its health task ran
  EXPECT_EQ(health.fault_counts[static_cast<std::size_t>(bitIndex(kFaultCycleSlip))], 5U);
  EXPECT_NE(health.fault_bits & nav::kFaultCycleSlip, 0U);
  for (int task = 0; task < nav::kTaskCount; ++task) {
    const nav::TaskTimingSummary& t = health.task_timing[static_cast<std::size_t>(task)];
    EXPECT_DOUBLE_EQ(t.min_us, 60000.0) << task;
    EXPECT_DOUBLE_EQ(t.max_us, 60000.0) << task;
  }
  EXPECT_NE(log.text().find("event=cycle_slip minor_frame=0 overrun_ms=40.000 releases_skipped=1"),
            std::string::npos)
      << log.text();
}

// Real clock, 5 Hz, a replay recorded at 0.625 Hz and paced at that rate: 7 of 8 cycles have no frame. The
// wait is bounded by acquire_timeout_ms, so the cycle never slips, and the missing frames are counted.
TEST(Daemon, ACameraSlowerThanTheCycleNeverBlocksIt) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  test::TempDir dir("daemon");
  const VisnavConfig slow =
      test::configFromText(dir, "[camera]\ndriver = \"replay\"\ndevice = \"" + sequence +
                                    "\"\nacquire_timeout_ms = 50.0\n[telemetry]\nenabled = false\n");
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.max_cycles = 10;
  options.apply_realtime = false;
  ASSERT_EQ(daemon.init(slow, options), kExitOk) << log.text();
  ASSERT_EQ(daemon.run(), kExitOk);
  EXPECT_EQ(daemon.counters().frames, 2U);  // t = 0 and t = 1.6 s
  EXPECT_EQ(daemon.counters().cycles_without_frame, 8U);
  EXPECT_EQ(daemon.camera().counters().timeouts, 8U);
  EXPECT_EQ(daemon.executive().counters().slips, 0U);
  const exec::DurationStats& acquire = daemon.executive().taskStats(daemon.taskId(CycleStage::kAcquire)).exec;
  EXPECT_LT(acquire.maxNs(), 80'000'000);  // 50 ms bound plus scheduling
  EXPECT_GE(acquire.maxNs(), 50'000'000);
  EXPECT_EQ(daemon.lastHealth().frames_dropped, 8U);
  EXPECT_NE(log.text().find("event=fault_onset fault=no_frame frame="), std::string::npos) << log.text();
}

/// systemd's end of $NOTIFY_SOCKET: a datagram socket bound at a path of the test.

TEST(Daemon, AStopRequestEndsTheLoopWithinOneCycle) {
  const std::string sequence = test::renderedApproachCi(kFrames);
  test::TempDir dir("daemon");
  const VisnavConfig config = test::configFromText(
      dir, replayConfig(sequence, partitionFor("daemon-stop"), false, "[daemon]\nplayback_loop = true\n"));
  LogFile log;
  Daemon daemon(log.log);
  DaemonOptions options;
  options.apply_realtime = false;
  ASSERT_EQ(daemon.init(config, options), kExitOk) << log.text();
  std::int64_t requested_ns = 0;
  std::thread stopper([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(700));
    requested_ns = exec::monotonicNowNs();
    daemon.requestStop();
  });
  EXPECT_EQ(daemon.run(), kExitOk);
  const std::int64_t stopped_ns = exec::monotonicNowNs();
  stopper.join();
  EXPECT_LT(stopped_ns - requested_ns,
            200'000'000 + 50'000'000);  // at most one period (no signal to wake it)
  EXPECT_NE(log.text().find("event=stop reason=stop_request"), std::string::npos) << log.text();
}

TEST(Daemon, InitFailuresGiveTheirExitCodes) {
  test::TempDir dir("daemon");
  LogFile log;
  {
    Daemon daemon(log.log);
    const VisnavConfig missing = test::configFromText(
        dir, "[camera]\ndriver = \"replay\"\ndevice = \"no-such-sequence\"\n[telemetry]\nenabled = false\n");
    EXPECT_EQ(daemon.init(missing, {}), kExitInit);
  }
  {
    Daemon daemon(log.log);
    const VisnavConfig bad_model = test::configFromText(
        dir, "[camera]\ndriver = \"synthetic\"\ndevice = \"" + std::string(VISNAV_SOURCE_DIR) +
                 "/config/scenarios/approach_ci.toml\"\n[files]\nmodel = \"nothing.toml\"\n");
    EXPECT_EQ(daemon.init(bad_model, {}), kExitConfig);
  }
  const std::string text = log.text();
  EXPECT_NE(text.find("level=error event=init_failed stage=camera message=\"camera replay '" + dir.path() +
                      "/no-such-sequence'"),
            std::string::npos)
      << text;
  EXPECT_NE(text.find("level=error event=config_invalid message=\"" + dir.path() + "/nothing.toml"),
            std::string::npos)
      << text;
}

}  // namespace
}  // namespace visnav::app
