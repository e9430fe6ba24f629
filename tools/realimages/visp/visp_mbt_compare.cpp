// visp_mbt_compare: ViSP's moving-edge model-based tracker (vpMbEdgeTracker, libvisp-dev) over the frames of
// a visnav sequence directory (drivers/replay/README.md), started from a given pose, writing one CSV row per
// frame with the columns visnav-eval's replay reader and visnav-edge-score find by name. The reference a
// user would try first (issue 10, "Real images"). NOT part of the main build: the main build never depends
// on ViSP; scripts/realimages.sh builds this with its own small CMake project (tools/realimages/visp).
//
//   visp_mbt_compare --sequence DIR --xml CONFIG.xml --model MODEL.cao --init tx,ty,tz,tux,tuy,tuz --out CSV
//   visp_mbt_compare --convert tx,ty,tz,tux,tuy,tuz
//
// --init is ViSP's cMo as a vpPoseVector (translation [m], theta-u [rad]). cMo maps object (model) points
// into the camera frame (x right, y down, z forward): the same transform as visnav's T_c_m
// (fsw/geometry/CONVENTIONS.md), so no axis change is needed. --convert prints that pose as visnav-replay's
// --initial-pose (x,y,z [m], yaw,pitch,roll [deg], DIN 9300: R = Rz(yaw) Ry(pitch) Rx(roll)).
// The camera comes from the XML (<camera> u0 v0 px py), as ViSP's own examples load it.
// A frame on which track() throws is written as status "lost" (no pose) and tracking goes on from the last
// pose, which is what ViSP's examples do not do (they stop); here the run continues so both trackers see
// every frame.
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpPoseVector.h>
#include <visp3/core/vpQuaternionVector.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/mbt/vpMbEdgeTracker.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

bool parseSix(const std::string& text, double v[6]) {
  std::stringstream ss(text);
  std::string item;
  int n = 0;
  while (std::getline(ss, item, ',')) {
    if (n >= 6) return false;
    char* end = nullptr;
    v[n] = std::strtod(item.c_str(), &end);
    if (end == item.c_str() || *end != '\0' || !std::isfinite(v[n])) return false;
    ++n;
  }
  return n == 6;
}

vpHomogeneousMatrix fromPoseVector(const double v[6]) {
  return vpHomogeneousMatrix(v[0], v[1], v[2], v[3], v[4], v[5]);
}

/// DIN 9300 yaw, pitch, roll [deg] of R = Rz(yaw) Ry(pitch) Rx(roll) (visnav's yprFromRotation).
void yawPitchRollDeg(const vpRotationMatrix& R, double& yaw, double& pitch, double& roll) {
  const double kDeg = 180.0 / M_PI;
  const double s = std::max(-1.0, std::min(1.0, -R[2][0]));
  pitch = std::asin(s) * kDeg;
  if (std::abs(s) > 1.0 - 1e-12) {  // gimbal lock: roll 0, yaw absorbs it (as visnav does)
    roll = 0.0;
    yaw = std::atan2(-R[0][1], R[1][1]) * kDeg;
  } else {
    yaw = std::atan2(R[1][0], R[0][0]) * kDeg;
    roll = std::atan2(R[2][1], R[2][2]) * kDeg;
  }
}

struct FrameRow {
  long long frame = 0;
  long long timestamp_ns = 0;
  std::string file;
};

bool readFrames(const std::string& dir, std::vector<FrameRow>& rows) {
  std::ifstream in(dir + "/frames.csv");
  if (!in) return false;
  std::string line;
  if (!std::getline(in, line) || line != "frame,timestamp_ns,file") return false;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string a, b, c;
    if (!std::getline(ss, a, ',') || !std::getline(ss, b, ',') || !std::getline(ss, c)) return false;
    rows.push_back({std::stoll(a), std::stoll(b), dir + "/" + c});
  }
  return !rows.empty();
}

void writePose(std::FILE* out, const vpHomogeneousMatrix& cMo) {
  vpRotationMatrix R;
  cMo.extract(R);
  vpQuaternionVector q(R);
  double w = q.w(), x = q.x(), y = q.y(), z = q.z();
  if (w < 0) w = -w, x = -x, y = -y, z = -z;  // visnav stores w >= 0
  double yaw, pitch, roll;
  yawPitchRollDeg(R, yaw, pitch, roll);
  std::fprintf(out, "%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", cMo[0][3], cMo[1][3],
               cMo[2][3], w, x, y, z, yaw, pitch, roll);
}

const char* const kUsage =
    "usage: visp_mbt_compare --sequence DIR --xml CONFIG.xml --model MODEL.cao --init tx,ty,tz,tux,tuy,tuz "
    "--out CSV\n"
    "       visp_mbt_compare --convert tx,ty,tz,tux,tuy,tuz\n";

}  // namespace

int main(int argc, char** argv) {
  std::string sequence, xml, model, init, out_path, convert;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) {
      std::fputs(kUsage, stderr);
      return 2;
    }
    const std::string value = argv[++i];
    if (arg == "--sequence")
      sequence = value;
    else if (arg == "--xml")
      xml = value;
    else if (arg == "--model")
      model = value;
    else if (arg == "--init")
      init = value;
    else if (arg == "--out")
      out_path = value;
    else if (arg == "--convert")
      convert = value;
    else {
      std::fprintf(stderr, "visp_mbt_compare: unknown argument '%s'\n%s", arg.c_str(), kUsage);
      return 2;
    }
  }
  double v[6];
  if (!convert.empty()) {
    if (!parseSix(convert, v)) {
      std::fprintf(stderr, "visp_mbt_compare: --convert wants six numbers\n");
      return 2;
    }
    const vpHomogeneousMatrix cMo = fromPoseVector(v);
    vpRotationMatrix R;
    cMo.extract(R);
    double yaw, pitch, roll;
    yawPitchRollDeg(R, yaw, pitch, roll);
    std::printf("%.10g,%.10g,%.10g,%.10g,%.10g,%.10g\n", cMo[0][3], cMo[1][3], cMo[2][3], yaw, pitch, roll);
    return 0;
  }
  if (sequence.empty() || xml.empty() || model.empty() || out_path.empty() || !parseSix(init, v)) {
    std::fputs(kUsage, stderr);
    return 2;
  }
  std::vector<FrameRow> frames;
  if (!readFrames(sequence, frames)) {
    std::fprintf(stderr, "visp_mbt_compare: %s/frames.csv: missing or malformed\n", sequence.c_str());
    return 3;
  }
  std::FILE* out = std::fopen(out_path.c_str(), "w");
  if (out == nullptr) {
    std::fprintf(stderr, "visp_mbt_compare: cannot write %s\n", out_path.c_str());
    return 3;
  }
  std::fprintf(
      out, "frame,timestamp_ns,status,mode,x_m,y_m,z_m,qw,qx,qy,qz,yaw_deg,pitch_deg,roll_deg,t_total_us\n");
  int tracked = 0;
  std::vector<double> times_us;
  try {
    vpMbEdgeTracker tracker;
    tracker.loadConfigFile(xml, false);
    tracker.loadModel(model);
    vpImage<unsigned char> image;
    vpImageIo::read(image, frames[0].file);
    tracker.initFromPose(image, fromPoseVector(v));
    for (std::size_t k = 0; k < frames.size(); ++k) {
      if (k > 0) vpImageIo::read(image, frames[k].file);
      bool ok = true;
      const auto t0 = std::chrono::steady_clock::now();
      try {
        if (k > 0) tracker.track(image);  // frame 0 is the initial pose, as in ViSP's examples
      } catch (const vpException& e) {
        ok = false;
        std::fprintf(stderr, "visp_mbt_compare: frame %lld: %s\n", frames[k].frame, e.getMessage());
      }
      const double us =
          std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
      if (k > 0) times_us.push_back(us);
      std::fprintf(out, "%lld,%lld,%s,near_range,", frames[k].frame, frames[k].timestamp_ns,
                   ok ? "tracking" : "lost");
      if (ok) {
        writePose(out, tracker.getPose());
        ++tracked;
      } else {
        std::fputs(",,,,,,,,,", out);
      }
      std::fprintf(out, ",%.1f\n", k > 0 ? us : 0.0);
    }
  } catch (const vpException& e) {
    std::fprintf(stderr, "visp_mbt_compare: %s\n", e.getMessage());
    std::fclose(out);
    return 3;
  }
  std::fclose(out);
  std::sort(times_us.begin(), times_us.end());
  const double median = times_us.empty() ? 0.0 : times_us[times_us.size() / 2];
  std::printf("visp_mbt_compare: %zu frames, %d with a pose, track() median %.0f us\n", frames.size(),
              tracked, median);
  return 0;
}
