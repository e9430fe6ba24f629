#include "visnav/far_eval/far_evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <unordered_map>

#include "visnav/eval/metrics.hpp"
#include "visnav/executive/clock.hpp"
#include "visnav/farrange/far_range_estimator.hpp"

namespace visnav::far_eval {

LoadError runSequence(const replay::Sequence& sequence, const far::FarRangeParams& params,
                      bool reset_each_frame, std::vector<FrameRecord>& out) {
  out.clear();
  const PinholeCamera camera(sequence.camera);
  far::FarRangeEstimator estimator;
  LoadError e = estimator.init(camera, params);
  if (!e.ok) return e;
  estimator.setClock(&exec::monotonicNowNs);
  std::unordered_map<std::int64_t, const replay::TruthRow*> truth;
  for (const replay::TruthRow& row : sequence.truth) truth[row.frame] = &row;
  const int w = camera.width();
  const int h = camera.height();
  const std::size_t bytes = static_cast<std::size_t>(w) * static_cast<std::size_t>(h) * 2U;
  std::vector<std::uint16_t> buffer(bytes / 2U);
  const double radius_m = sequence.model.boundingRadius();
  for (const replay::FrameEntry& entry : sequence.frames) {
    const auto it = truth.find(entry.frame);
    if (it == truth.end()) continue;
    int fw = 0;
    int fh = 0;
    int maxval = 0;
    e = replay::readPgm(entry.file, reinterpret_cast<std::uint8_t*>(buffer.data()), bytes, fw, fh, maxval,
                        sequence.max_code);
    if (!e.ok) return e;
    if (fw != w || fh != h) return LoadError::failure(entry.file + ": image size differs from the camera");
    const MonoImage image =
        maxval <= 255
            ? MonoImage::from8(ImageView8(reinterpret_cast<const std::uint8_t*>(buffer.data()), w, h))
            : MonoImage::from16(ImageView16(buffer.data(), w, h), static_cast<std::uint16_t>(maxval));
    if (reset_each_frame) estimator.reset();
    far::FarRangeResult result;
    estimator.estimate(image, result);
    const Vec3& t = it->second->pose.t_c_m;
    FrameRecord r;
    r.frame = entry.frame;
    r.truth_range_m = t.norm();
    r.target_radius_deg = std::atan2(radius_m, r.truth_range_m) * kDegPerRad;
    r.valid = result.valid;
    r.cluster_pixels = result.cluster_pixels;
    r.raw_pixels = result.raw_pixels;
    r.boundary_pixels = result.boundary_pixels;
    r.cluster_count = result.cluster_count;
    r.flags = result.flags;
    r.step_us = result.timing.total_us;
    eval::FarRangeError error;  // the definitions visnav-eval uses (tools/eval metrics.hpp)
    if (result.valid && eval::farRangeError(result.direction_c, result.distance_m, t, error)) {
      r.direction_error_deg = error.direction_deg;
      r.distance_m = result.distance_m;
      r.distance_error_pct = error.distance_pct;
      r.right_target = r.direction_error_deg <= r.target_radius_deg + 0.1;
    }
    out.push_back(r);
  }
  return readClutter(sequence.directory, out);
}

LoadError readClutter(const std::string& directory, std::vector<FrameRecord>& records) {
  const std::string path = directory + "/clutter.csv";
  std::ifstream in(path);
  if (!in) return LoadError::success();
  std::unordered_map<std::int64_t, std::pair<int, int>> rows;
  std::string line;
  std::getline(in, line);  // header
  for (int number = 2; std::getline(in, line); ++number) {
    long long frame = 0;
    int bars = 0;
    int glints = 0;
    if (std::sscanf(line.c_str(), "%lld,%d,%d", &frame, &bars, &glints) != 3)
      return LoadError::failure(path + ":" + std::to_string(number) + ": expected frame,bars,glints");
    rows[frame] = {bars, glints};
  }
  for (FrameRecord& r : records) {
    const auto it = rows.find(r.frame);
    if (it == rows.end()) continue;
    r.bars_in_view = it->second.first;
    r.glints_in_view = it->second.second;
  }
  return LoadError::success();
}

far::GammaEstimate calibrateFromRecords(const std::vector<FrameRecord>& records, double min_range_m,
                                        double max_range_m) {
  std::vector<far::GammaSample> samples;
  for (const FrameRecord& r : records) {
    if (!r.right_target || r.truth_range_m < min_range_m || r.truth_range_m > max_range_m) continue;
    samples.push_back({r.truth_range_m, static_cast<double>(r.cluster_pixels)});
  }
  return far::calibrateGamma(samples);
}

Summary summarise(const std::vector<FrameRecord>& records, double min_range_m, double max_range_m) {
  Summary s;
  std::vector<double> direction;
  std::vector<double> distance;
  std::vector<double> step;
  for (const FrameRecord& r : records) {
    if (r.truth_range_m < min_range_m || r.truth_range_m >= max_range_m) continue;
    ++s.frames;
    s.valid += r.valid ? 1 : 0;
    s.right += r.right_target ? 1 : 0;
    if (r.bars_in_view > 0) {
      ++s.clutter_frames;
      s.clutter_right += r.right_target ? 1 : 0;
    }
    if (r.glints_in_view > 0) {
      ++s.glint_frames;
      s.glint_right += r.right_target ? 1 : 0;
    }
    step.push_back(r.step_us);
    if (!r.right_target) continue;
    direction.push_back(r.direction_error_deg);
    distance.push_back(r.distance_error_pct);
  }
  const eval::ErrorStats d = eval::absStats(direction);
  const eval::ErrorStats p = eval::absStats(distance);
  const eval::ErrorStats t = eval::absStats(step);
  s.direction_median_deg = d.median;
  s.direction_p95_deg = d.p95;
  s.distance_median_pct = p.median;
  s.distance_p95_pct = p.p95;
  s.step_median_us = t.median;
  s.step_p95_us = t.p95;
  return s;
}

LoadError writeRecordsCsv(const std::string& path, const char* method,
                          const std::vector<FrameRecord>& records, bool append) {
  std::ofstream out(path, append ? std::ios::app : std::ios::trunc);
  if (!out) return LoadError::failure(path + ": cannot write");
  if (!append) {
    out << "method,frame,truth_range_m,valid,right_target,direction_error_deg,distance_m,distance_error_pct,"
           "cluster_pixels,raw_pixels,boundary_pixels,cluster_count,flags,bars_in_view,glints_in_view,step_"
           "us\n";
  }
  for (const FrameRecord& r : records) {
    out << method << ',' << r.frame << ',' << r.truth_range_m << ',' << (r.valid ? 1 : 0) << ','
        << (r.right_target ? 1 : 0) << ',' << r.direction_error_deg << ',' << r.distance_m << ','
        << r.distance_error_pct << ',' << r.cluster_pixels << ',' << r.raw_pixels << ',' << r.boundary_pixels
        << ',' << r.cluster_count << ',' << r.flags << ',' << r.bars_in_view << ',' << r.glints_in_view << ','
        << r.step_us << '\n';
  }
  return out ? LoadError::success() : LoadError::failure(path + ": write failed");
}

}  // namespace visnav::far_eval
