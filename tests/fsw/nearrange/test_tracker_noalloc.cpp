// REQUIREMENT: the per-frame call allocates nothing after init (fsw/nearrange/README.md).
#include <gtest/gtest.h>

#include <cmath>

#include "../../support/alloc_counter.hpp"
#include "tracker_fixture.hpp"

namespace visnav {
namespace {

void runAndCount(NearRangeParams params, const PolygonModel& model, const std::vector<Pose>& truths,
                 const synthetic::RenderOptions& render = {}, bool near_twin_checks = false) {
  synthetic::Renderer renderer;
  ASSERT_TRUE(renderer.init(test::vgaCamera(), model, render).ok);
  std::vector<test::RenderedFrame> frames;
  for (std::size_t i = 0; i < truths.size(); ++i) frames.push_back(test::renderFrame(renderer, truths[i], i));
  NearRangeTracker tracker;
  ASSERT_TRUE(tracker.init(test::vgaCamera(), model, params).ok);
  if (near_twin_checks) {
    ASSERT_GE(tracker.nearTwinCount(), 1) << "the model has near twins to refit";
    tracker.setNearTwinChecks(true);
  }
  Pose pose = truths.front();
  NearRangeResult result;
  int not_lost = 0;
  constexpr int kFrames = 400;
  const std::uint64_t before = test::allocationCount();
  for (int i = 0; i < kFrames; ++i) {
    const auto k = static_cast<std::size_t>(i) % frames.size();
    tracker.track(frames[k].image(), pose, static_cast<std::uint64_t>(i), result);
    pose = result.status == TrackStatus::kLost ? truths[k] : result.pose;
    not_lost += result.status != TrackStatus::kLost ? 1 : 0;
  }
  const std::uint64_t after = test::allocationCount();
  EXPECT_EQ(after - before, 0U) << "allocations in " << kFrames
                                << " frames (malloc counted: " << test::countsMalloc() << ")";
  EXPECT_GT(not_lost, kFrames * 9 / 10);  // the frames really exercised the full pipeline
}

TEST(TrackerNoAlloc, PlateVertexResidual) {
  std::vector<Pose> truths;
  for (int i = 0; i < 20; ++i) truths.push_back(test::plateAt(10.0 + 0.1 * i, 0.01 * i, 0.1 * i, -0.1 * i));
  runAndCount(NearRangeParams{}, makeRectanglePlate(2.3, 1.8), truths);
}

TEST(TrackerNoAlloc, BoxPointToLineResidual) {
  NearRangeParams params;
  params.pose_residual = static_cast<int>(PoseResidualMode::kPointToLine);
  std::vector<Pose> truths;
  for (int i = 0; i < 20; ++i)
    truths.push_back(Pose::fromYpr({0.6 + 0.01 * i, 0.4, 2.8}, Vec3(0.0, 0.0, 8.0 + 0.05 * i)));
  // Sun shading: with one flat brightness the box's inner edges have no contrast at all.
  synthetic::RenderOptions render;
  render.shading.enabled = true;
  render.shading.sun_dir_c = Vec3(0.3, 0.5, 1.0);
  runAndCount(params, makeBox(0.8, 0.6, 0.5), truths, render);
}

TEST(TrackerNoAlloc, NearSquareOctagonWithNearTwinChecks) {
  // The near twins' refits (kFlagNearTwinRival) relabel through tables built at init.
  std::vector<Pose> truths;
  for (int i = 0; i < 20; ++i) truths.push_back(test::plateAt(14.0 + 0.1 * i, 0.01 * i, 6.0, -0.2 * i));
  runAndCount(NearRangeParams{}, makeOctagonPlate(2.658, 2.513, 0.437), truths, {}, true);
}

TEST(TrackerNoAlloc, CounterSeesAllocations) {
  // The proof above is only as good as the counter: show it counts.
  const std::uint64_t before = test::allocationCount();
  auto* p = new std::vector<int>(100);
  delete p;
  EXPECT_GE(test::allocationCount() - before, 2U);
}

}  // namespace
}  // namespace visnav
