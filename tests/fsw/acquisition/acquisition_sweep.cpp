// acquisition_sweep: success rate of acquisition over a grid of attitudes and distances on rendered frames,
// with the far-range cue off by --distance-error (alternating sign) and --direction-error-deg. The figures in
// fsw/acquisition/README.md come from this program (release build):
//   build/h-acq-rel/bin/acquisition_sweep --target plate
//   build/h-acq-rel/bin/acquisition_sweep --target box
// A case counts as acquired when acquisition succeeds with the attitude within --max-attitude-error-deg
// (modulo the target's symmetries) and the position within --max-position-error-rel of the range; a success
// outside that is a false acquisition.
#include <time.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <string>

#include "acquisition_fixture.hpp"

namespace {

using namespace visnav;

std::int64_t nowNs() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<std::int64_t>(ts.tv_sec) * 1000000000LL + ts.tv_nsec;
}

struct Options {
  test::Target target = test::Target::kPlate;
  std::vector<double> distances = {5.0, 10.0, 15.0, 20.0, 25.0};
  double distance_error = 0.2;
  double direction_error_deg = 1.0;
  double max_attitude_error_deg = 5.0;
  double max_position_error_rel = 0.03;
  int box_attitudes = 40;
  bool verbose = false;
};

struct Tally {
  int runs = 0, acquired = 0, false_acquired = 0, failed = 0, frames = 0;
};

Mat3 randomRotation(Pcg32& rng) {
  // Uniform on SO(3): a normalised 4-D Gaussian quaternion (Box-Muller pairs).
  double q[4];
  for (int i = 0; i < 4; i += 2) {
    const double r = std::sqrt(-2.0 * std::log(1.0 - rng.uniform()));
    const double a = 2.0 * kPi * rng.uniform();
    q[i] = r * std::cos(a);
    q[i + 1] = r * std::sin(a);
  }
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

/// Most head-on visible surface: its obliquity [deg] (0 = facing the camera).
double bestObliquityDeg(const PolygonModel& model, const Pose& pose) {
  double best = 180.0;
  for (const ModelSurface& s : model.surfaces()) {
    const Vec3 n = pose.R_c_m * s.normal_m;
    const Vec3 los = pose.transform(s.centroid_m).normalized();
    best = std::min(best, std::acos(std::clamp(-n.dot(los), -1.0, 1.0)) * kDegPerRad);
  }
  return best;
}

bool parse(int argc, char** argv, Options& o) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool has_value = i + 1 < argc;
    if (a == "--target" && has_value) {
      const std::string t = argv[++i];
      if (t != "plate" && t != "box") return false;
      o.target = t == "plate" ? test::Target::kPlate : test::Target::kBox;
    } else if (a == "--distances" && has_value) {
      o.distances.clear();
      for (char* p = argv[++i]; *p != '\0';) {
        char* end = nullptr;
        o.distances.push_back(std::strtod(p, &end));
        if (end == p) return false;
        p = *end == ',' ? end + 1 : end;
      }
    } else if (a == "--distance-error" && has_value) {
      o.distance_error = std::atof(argv[++i]);
    } else if (a == "--direction-error-deg" && has_value) {
      o.direction_error_deg = std::atof(argv[++i]);
    } else if (a == "--box-attitudes" && has_value) {
      o.box_attitudes = std::atoi(argv[++i]);
    } else if (a == "-v") {
      o.verbose = true;
    } else {
      return false;
    }
  }
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  Options o;
  if (!parse(argc, argv, o)) {
    std::fputs(
        "usage: acquisition_sweep [--target plate|box] [--distances 5,10,..] [--distance-error 0.2]\n"
        "                         [--direction-error-deg 1] [--box-attitudes 40] [-v]\n",
        stderr);
    return 2;
  }
  const test::Scene scene = test::makeScene(o.target);
  synthetic::Renderer renderer;
  acq::Acquisition acquisition;
  if (!renderer.init(test::vgaCamera(), scene.model, scene.render).ok ||
      !acquisition.init(test::vgaCamera(), scene.model, acq::AcquisitionParams{}, NearRangeParams{}).ok) {
    std::fputs("acquisition_sweep: init failed\n", stderr);
    return 1;
  }
  // Attitudes: the plate over obliquity x tilt axis x spin; the box uniformly at random (fixed seed).
  std::vector<Mat3> attitudes;
  if (o.target == test::Target::kPlate) {
    for (double tilt : {0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0})
      for (double axis : {0.0, 60.0, 120.0})
        for (double spin : {0.0, 50.0, 100.0, 150.0})
          attitudes.push_back(test::tiltedAttitude(tilt, axis, spin));
  } else {
    Pcg32 rng(2024);
    for (int i = 0; i < o.box_attitudes; ++i) attitudes.push_back(randomRotation(rng));
  }
  std::map<int, Tally> by_obliquity;  // 10-deg bins of the most head-on surface
  std::map<double, Tally> by_distance;
  double step_sum_us = 0.0, step_max_us = 0.0;
  int step_count = 0, case_index = 0;
  for (double d : o.distances) {
    for (const Mat3& r : attitudes) {
      Pose truth;
      truth.R_c_m = r;
      truth.t_c_m = Vec3(0.03 * d * std::sin(case_index * 0.7), 0.03 * d * std::cos(case_index * 1.3), d);
      const double obliquity = bestObliquityDeg(scene.model, truth);
      const auto frames =
          test::renderStatic(renderer, truth, 3, 1000U * static_cast<std::uint64_t>(case_index));
      const double dist_err = (case_index % 2 == 0 ? 1.0 : -1.0) * o.distance_error;
      const FarRangeSolution cue =
          test::perturbedCue(truth, o.direction_error_deg, 137.0 * case_index, dist_err);
      const test::AcquisitionRun run = test::runAcquisition(acquisition, scene, frames, cue, 60, &nowNs);
      step_sum_us += run.step_sum_us;
      step_max_us = std::max(step_max_us, run.step_max_us);
      step_count += run.steps;
      const double att_err = run.attitude_error_deg;
      const double pos_err = run.position_error_m / truth.t_c_m.norm();
      const bool ok =
          run.succeeded() && att_err <= o.max_attitude_error_deg && pos_err <= o.max_position_error_rel;
      for (Tally* t : {&by_obliquity[static_cast<int>(obliquity / 10.0)], &by_distance[d]}) {
        ++t->runs;
        t->acquired += ok ? 1 : 0;
        t->false_acquired += run.succeeded() && !ok ? 1 : 0;
        t->failed += run.succeeded() ? 0 : 1;
        t->frames += run.steps;
      }
      if (o.verbose)
        std::printf("d %5.1f obl %5.1f  %-10s %-13s frames %2d  att %7.2f deg  pos %6.3f %%  verified %d\n",
                    d, obliquity, acq::toString(run.last.state), acq::toString(run.last.failure), run.steps,
                    att_err, 100.0 * pos_err, run.last.candidates_verified);
      ++case_index;
    }
  }
  std::printf(
      "target %s, cue: distance error +-%.0f %%, direction error %.1f deg; acquired = attitude within %.0f "
      "deg "
      "(modulo symmetry), position within %.0f %% of range\n\n",
      o.target == test::Target::kPlate ? "plate 2.3 x 1.8 m" : "shaded box 1.6 x 1.2 x 1.0 m",
      100.0 * o.distance_error, o.direction_error_deg, o.max_attitude_error_deg,
      100.0 * o.max_position_error_rel);
  std::printf(
      "| most head-on surface | runs | acquired | false | failed | mean frames "
      "|\n|---|---|---|---|---|---|\n");
  for (const auto& [bin, t] : by_obliquity)
    std::printf("| %d-%d deg | %d | %d (%.0f %%) | %d | %d | %.1f |\n", bin * 10, bin * 10 + 10, t.runs,
                t.acquired, 100.0 * t.acquired / t.runs, t.false_acquired, t.failed,
                static_cast<double>(t.frames) / t.runs);
  std::printf("\n| distance | runs | acquired | false | failed | mean frames |\n|---|---|---|---|---|---|\n");
  for (const auto& [d, t] : by_distance)
    std::printf("| %.0f m | %d | %d (%.0f %%) | %d | %d | %.1f |\n", d, t.runs, t.acquired,
                100.0 * t.acquired / t.runs, t.false_acquired, t.failed,
                static_cast<double>(t.frames) / t.runs);
  std::printf("\nstep time: mean %.0f us, max %.0f us over %d steps (wall clock, this machine)\n",
              step_sum_us / step_count, step_max_us, step_count);
  return 0;
}
