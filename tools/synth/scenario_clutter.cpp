// Scenario keys of the per-frame clutter (tools/synth/README.md): [render.bar1] .. [render.bar8] and
// [render.glint1] .. [render.glint8].
#include <cstdio>
#include <string>

#include "scenario.hpp"

namespace visnav::synth {
namespace {

constexpr int kMaxObjects = 8;
constexpr double kGlintMinPeak = 0.5;  // fainter spots model stars, not glints

void readWindow(replay::TomlReader& r, const std::string& key, std::int64_t& first, std::int64_t& last,
                Vec2& start, Vec2& end) {
  r.getInt(key + ".first_frame", first, true);
  r.getInt(key + ".last_frame", last, true);
  if (r.good() && last < first) r.fail(key + ".last_frame", "must be >= first_frame");
  r.getVector(key + ".start_px", start.data(), 2, true);
  end = start;
  r.getVector(key + ".end_px", end.data(), 2);
}

}  // namespace

void readDynamicClutter(replay::TomlReader& r, synthetic::RenderOptions& o) {
  for (int k = 1; k <= kMaxObjects; ++k) {
    const std::string key = "render.bar" + std::to_string(k);
    if (!r.has(key)) continue;
    synthetic::MovingBar b;
    readWindow(r, key, b.first_frame, b.last_frame, b.start_px, b.end_px);
    r.getDouble(key + ".length_px", b.length_px, true);
    r.getDouble(key + ".width_px", b.width_px, true);
    r.checkRange(key + ".length_px", b.length_px, 0.1, 1e5);
    r.checkRange(key + ".width_px", b.width_px, 0.1, 1e5);
    r.getDouble(key + ".angle_deg", b.angle_deg);
    r.getDouble(key + ".brightness_start", b.brightness_start, true);
    b.brightness_end = b.brightness_start;
    r.getDouble(key + ".brightness_end", b.brightness_end);
    r.checkRange(key + ".brightness_start", b.brightness_start, 0.0, 1.0);
    r.checkRange(key + ".brightness_end", b.brightness_end, 0.0, 1.0);
    o.bars.push_back(b);
  }
  for (int k = 1; k <= kMaxObjects; ++k) {
    const std::string key = "render.glint" + std::to_string(k);
    if (!r.has(key)) continue;
    synthetic::Glint g;
    readWindow(r, key, g.first_frame, g.last_frame, g.start_px, g.end_px);
    r.getDouble(key + ".sigma_px", g.sigma_px, true);
    r.checkRange(key + ".sigma_px", g.sigma_px, 0.05, 1e4);
    r.getDouble(key + ".peak", g.peak, true);
    r.checkRange(key + ".peak", g.peak, -1.0, 2.0);
    o.glints.push_back(g);
  }
}

namespace {

bool centreInView(const Vec2& start, const Vec2& end, double fraction, double margin, int w, int h) {
  const Vec2 c = start + fraction * (end - start);
  return c.x() >= -margin && c.y() >= -margin && c.x() <= w + margin && c.y() <= h + margin;
}

}  // namespace

LoadError writeClutterCsv(const std::string& directory, const synthetic::RenderOptions& o,
                          const std::vector<int>& frames, int width_px, int height_px) {
  if (o.bars.empty() && o.glints.empty()) return LoadError::success();
  const std::string path = directory + "/clutter.csv";
  std::FILE* f = std::fopen(path.c_str(), "w");
  if (f == nullptr) return LoadError::failure(path + ": cannot write");
  std::fputs("frame,bars_in_view,glints_in_view\n", f);
  for (const int frame : frames) {
    int bars = 0;
    int glints = 0;
    double t = 0.0;
    for (const synthetic::MovingBar& b : o.bars) {
      if (synthetic::clutterAt(b.first_frame, b.last_frame, frame, t) &&
          centreInView(b.start_px, b.end_px, t, 0.5 * b.length_px, width_px, height_px))
        ++bars;
    }
    for (const synthetic::Glint& g : o.glints) {
      if (g.peak >= kGlintMinPeak && synthetic::clutterAt(g.first_frame, g.last_frame, frame, t) &&
          centreInView(g.start_px, g.end_px, t, 3.0 * g.sigma_px, width_px, height_px))
        ++glints;
    }
    std::fprintf(f, "%d,%d,%d\n", frame, bars, glints);
  }
  return std::fclose(f) == 0 ? LoadError::success() : LoadError::failure(path + ": write failed");
}

}  // namespace visnav::synth
