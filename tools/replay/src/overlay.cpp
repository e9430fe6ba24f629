#include "visnav/replay_tool/overlay.hpp"

#include <cmath>
#include <cstdio>

#include "visnav/eval/canvas.hpp"

namespace visnav::replay_tool {

namespace {
constexpr eval::Rgb kBlue{60, 120, 255};
constexpr eval::Rgb kYellow{230, 200, 40};
constexpr eval::Rgb kGreen{40, 230, 60};
constexpr eval::Rgb kRed{255, 40, 40};
constexpr eval::Rgb kMagenta{240, 60, 240};
constexpr eval::Rgb kOrange{255, 150, 30};
}  // namespace

LoadError writeOverlayPng(const std::string& path, const MonoImage& image, const NearRangeTracker& tracker,
                          const NearRangeResult& result) {
  const int w = image.width();
  const int h = image.height();
  eval::Canvas canvas(w, h, eval::Rgb{});
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      double v = 0.0;
      if (image.depth == MonoImage::Depth::kU8)
        v = image.u8.at(x, y) / 255.0;
      else
        v = static_cast<double>(image.u16.at(x, y)) / image.max_code;
      const auto g = static_cast<std::uint8_t>(std::lround(255.0 * v));
      canvas.setPixel(x, y, eval::Rgb{g, g, g});
    }
  const PinholeCamera& camera = tracker.camera();
  const int half = tracker.params().scanline_half_length_px;
  for (const EdgeMeasurement& edge : tracker.lastEdges()) {
    canvas.line(edge.predicted_a_px.x(), edge.predicted_a_px.y(), edge.predicted_b_px.x(),
                edge.predicted_b_px.y(), kBlue);
    for (int i = 0; i < edge.point_count; ++i) {
      const ScanPoint& sp = tracker.lastScanPoints()[edge.first_point + i];
      const Vec2 a = sp.scan_centre_px - half * sp.scan_normal;
      const Vec2 b = sp.scan_centre_px + half * sp.scan_normal;
      canvas.line(a.x(), a.y(), b.x(), b.y(), kYellow);
    }
    if (edge.line_ok) {
      // The fitted line lives in ideal pixels: draw it through the distortion, in short pieces.
      const Vec2 n = edge.line.normal();
      const Vec2 dir(-n.y(), n.x());
      const Vec2 foot = edge.line.rho_px * n;
      const Vec2 a_ideal = camera.undistortPixel(edge.predicted_a_px);
      const double t0 = (a_ideal - foot).dot(dir);
      const double t1 = (camera.undistortPixel(edge.predicted_b_px) - foot).dot(dir);
      constexpr int kPieces = 16;
      for (int k = 0; k < kPieces; ++k) {
        const Vec2 p = camera.distortPixel(foot + (t0 + (t1 - t0) * k / kPieces) * dir);
        const Vec2 q = camera.distortPixel(foot + (t0 + (t1 - t0) * (k + 1) / kPieces) * dir);
        canvas.line(p.x(), p.y(), q.x(), q.y(), kOrange);
      }
    }
    for (int i = 0; i < edge.point_count; ++i) {
      const ScanPoint& sp = tracker.lastScanPoints()[edge.first_point + i];
      const eval::Rgb c = sp.method == EdgeMethod::kTexture ? kMagenta : (sp.inlier ? kGreen : kRed);
      canvas.dot(sp.edge_px.x(), sp.edge_px.y(), 1, c);
    }
  }
  char label[96];
  std::snprintf(label, sizeof(label), "%s q=%.2f rms=%.2fpx lines %d/%d", toString(result.status),
                result.quality, result.rms_px, result.lines_used, result.lines_total);
  canvas.text(4, 4, label, kYellow, 1);
  return canvas.writePng(path);
}

}  // namespace visnav::replay_tool
