// Stage interfaces: the records and codes that cross from one stage library to the next, kept in core so the
// dependencies stay one-way (README.md, "The house"; scripts/check-deps.sh enforces it). Far range produces a
// FarRangeSolution that acquisition and navigation consume; every stage raises FaultBits that navigation,
// the daemon and telemetry report; the daemon's executive runs the CycleStages. Each enum has its names
// table right beside it, checked against its count at compile time: logs, tools and tests print these names
// and no other table of them exists. Header-only; fixed-size members (no heap).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>

#include "visnav/core/types.hpp"

namespace visnav {

namespace detail {
/// True when no entry of a names table is missing (a short initializer list leaves nullptr at the end).
template <std::size_t N>
constexpr bool allNamed(const std::array<const char*, N>& names) {
  for (const char* name : names)
    if (name == nullptr || name[0] == '\0') return false;
  return true;
}
}  // namespace detail

/// Far range's answer for one frame: the cue acquisition starts from, and part of every NavSolution.
struct FarRangeSolution {
  bool valid = false;
  Vec3 direction_c = Vec3::UnitZ();  ///< unit line of sight in the camera frame (CONVENTIONS.md)
  double azimuth_rad = 0.0;          ///< atan2(x, z)
  double elevation_rad = 0.0;        ///< atan2(-y, hypot(x, z)): up in the image is positive
  double distance_m = 0.0;           ///< eq. 16, gamma / sqrt(n), or from the target's extent if nearer
  int cluster_pixels = 0;            ///< n of eq. 16
  double circularity = 0.0;          ///< eq. 15
  int cluster_count = 0;
  double quality = 0.0;  ///< [0, 1]
  /// Found by its outline (far range's kFlagExtended): edge structure already shown, so acquisition's
  /// no-target test takes outline_cue_min_edge_snr instead of min_edge_snr.
  bool outline = false;
};

/// FDIR fault bits (HealthRecord::fault_bits, NavSolution::fault_bits; idl/visnav.idl FAULT_BIT_COUNT).
enum FaultBit : std::uint32_t {
  kFaultInlierRatio = 1U << 0,        ///< edge-point inlier ratio of a line below threshold
  kFaultTooFewLines = 1U << 1,        ///< usable lines below threshold
  kFaultResidual = 1U << 2,           ///< LM residual above threshold
  kFaultNotConverged = 1U << 3,       ///< LM did not converge
  kFaultInnovation = 1U << 4,         ///< NIS against the Kalman prediction above the gate
  kFaultImplausible = 1U << 5,        ///< range or image-bounds check failed
  kFaultFrameAge = 1U << 6,           ///< frame older than allowed when processed
  kFaultNoFrame = 1U << 7,            ///< camera delivered no frame this cycle
  kFaultFarRangeNoTarget = 1U << 8,   ///< far range found no acceptable cluster
  kFaultAcquisitionFailed = 1U << 9,  ///< acquisition gave up on a candidate
  kFaultCycleSlip = 1U << 10,         ///< the executive missed a deadline
  kFaultBadFrame = 1U << 11,          ///< the camera delivered a frame the pipeline cannot use (wrong size)
};
constexpr int kFaultBitCount = 12;

/// Name of each fault bit for logs and tools, indexed by bit index (bitIndex()).
constexpr std::array<const char*, kFaultBitCount> kFaultNames = {
    "inlier_ratio",        "too_few_lines",      "residual",   "not_converged",
    "innovation",          "implausible",        "frame_age",  "no_frame",
    "far_range_no_target", "acquisition_failed", "cycle_slip", "bad_frame"};

/// Index of a fault bit in fault_bits (and in HealthRecord::fault_counts, kFaultNames).
constexpr int bitIndex(FaultBit bit) {
  int index = 0;
  for (std::uint32_t b = bit; b > 1U; b >>= 1U) ++index;
  return index;
}
static_assert(bitIndex(kFaultBadFrame) == kFaultBitCount - 1, "kFaultBitCount: one past the last fault bit");
static_assert(detail::allNamed(kFaultNames), "one name per fault bit");

/// Name of a fault bit index (0 .. kFaultBitCount-1): "inlier_ratio", ...; "unknown" outside.
constexpr const char* faultName(int bit) {
  // cppcheck-suppress CastIntegerToAddressAtReturn
  return bit >= 0 && bit < kFaultBitCount ? kFaultNames[static_cast<std::size_t>(bit)] : "unknown";
}

/// The stages of one flight cycle, in the order visnavd registers them with the executive; also the index of
/// HealthRecord::task_timing (idl/visnav.idl TASK_COUNT).
enum class CycleStage : int { kAcquire = 0, kProcess = 1, kPublish = 2, kHealth = 3 };
constexpr int kCycleStageCount = 4;

/// Name of each stage (executive task names, log fields), indexed by stageIndex().
constexpr std::array<const char*, kCycleStageCount> kCycleStageNames = {"acquire", "process", "publish",
                                                                        "health"};
static_assert(detail::allNamed(kCycleStageNames), "one name per cycle stage");
static_assert(static_cast<int>(CycleStage::kHealth) == kCycleStageCount - 1,
              "kCycleStageCount: one past the last");

constexpr int stageIndex(CycleStage stage) { return static_cast<int>(stage); }
constexpr const char* stageName(CycleStage stage) {
  // cppcheck 2.10 reads the array element as an integer (false positive, as in faultName above).
  // cppcheck-suppress CastIntegerToAddressAtReturn
  return kCycleStageNames[static_cast<std::size_t>(stageIndex(stage))];
}

}  // namespace visnav
