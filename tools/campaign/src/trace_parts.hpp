// The campaign's --trace text for one frame (trace.cpp), apart from the run loop (runner.cpp) that fills it.
#pragma once

#include <string>

#include "visnav/campaign/runner.hpp"

namespace visnav::campaign::detail {

/// The far fix's line of sight against the model origin's [deg].
double farDirectionErrorDeg(const far::FarRangeResult& fr, const Pose& truth);
/// The target's angular radius (its bounding sphere) seen from the camera [deg].
double targetAngularRadiusDeg(const Scene& scene, const Pose& truth);

/// What one frame's trace reads: the frame's outcome, the pipeline after it, the truth-started tracker's
/// result (`oracle` null, or `f.oracle` < 0: not run on this frame).
struct FrameTraceInputs {
  const FrameOutcome& f;
  const nav::NavigationPipeline& pipeline;
  const nav::FilterUpdate& update;
  const NearRangeTracker* oracle;
  const NearRangeResult& oracle_result;
  const nav::PoseSigmas& oracle_sigma;
  const Pose& truth;
  const Scene& scene;
  const PinholeCamera& camera;
  const nav::NavigationParams& navigation;
};

/// traceLine's line and what follows it for this frame: the oracle's fit and edges, the tracker's edges,
/// the filter, and the acquisition, far range or close-range search that ran.
std::string traceFrame(const FrameTraceInputs& in);

}  // namespace visnav::campaign::detail
