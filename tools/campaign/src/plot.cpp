// DIR/campaign.png: four panels (tracked fraction per family with the worst scene, recovery latency
// histogram, confidently wrong frames per family, tracked fraction per scene).
#include "visnav/eval/plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "visnav/campaign/report.hpp"

namespace visnav::campaign {
namespace {

using eval::Canvas;
using eval::Rgb;

constexpr Rgb kWhite{255, 255, 255};
constexpr Rgb kBlack{0, 0, 0};
constexpr Rgb kGrid{225, 225, 225};
constexpr Rgb kBar{70, 120, 200};
constexpr Rgb kWorst{210, 30, 30};
constexpr Rgb kGate{240, 150, 0};
constexpr Rgb kGood{0, 150, 60};
constexpr int kText = 2;
constexpr int kPanelW = 800;
constexpr int kPanelH = 500;

struct Area {
  int left, top, right, bottom;
  double y_lo, y_hi;
  double py(double y) const { return bottom - 1 - (y - y_lo) / (y_hi - y_lo) * (bottom - top - 1); }
};

std::string format(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof(buf), f, v);
  return buf;
}

void centredText(Canvas& c, int cx, int y, const std::string& s, Rgb colour) {
  c.text(cx - Canvas::textWidth(s, kText) / 2, y, s, colour, kText);
}

Area drawFrame(Canvas& c, int x0, int y0, const std::string& title, double y_lo, double y_hi,
               const std::string& ylabel) {
  const Area a{x0 + 90, y0 + 50, x0 + kPanelW - 30, y0 + kPanelH - 70, y_lo, y_hi};
  centredText(c, (a.left + a.right) / 2, y0 + 6, title, kBlack);
  c.text(x0 + 8, y0 + 26, ylabel, kBlack, kText);  // under the title, left of the plot
  int decimals = 0;
  for (double t : eval::niceTicks(y_lo, y_hi, 5, decimals)) {
    const double y = a.py(t);
    c.line(a.left, y, a.right - 1, y, kGrid);
    const std::string label = format(("%." + std::to_string(decimals) + "f").c_str(), t);
    c.text(a.left - 8 - Canvas::textWidth(label, kText), static_cast<int>(y) - 7, label, kBlack, kText);
  }
  c.rect(a.left, a.top, a.right, a.bottom, kBlack);
  return a;
}

std::vector<const GroupSummary*> families(const std::vector<GroupSummary>& groups) {
  std::vector<const GroupSummary*> out;
  for (std::size_t i = 1; i < groups.size(); ++i) out.push_back(&groups[i]);
  return out;
}

void trackedPanel(Canvas& c, int x0, int y0, const std::vector<GroupSummary>& groups, const Gates& gates) {
  const Area a = drawFrame(c, x0, y0, "tracked fraction of expected frames: mean (bar), worst scene (red)",
                           0.0, 1.0, "fraction");
  const auto fam = families(groups);
  if (fam.empty()) return;
  const double slot = static_cast<double>(a.right - a.left) / static_cast<double>(fam.size());
  for (std::size_t k = 0; k < fam.size(); ++k) {
    const GroupSummary& g = *fam[k];
    const int cx = a.left + static_cast<int>((static_cast<double>(k) + 0.5) * slot);
    const int half = static_cast<int>(0.3 * slot);
    if (g.tracked_fraction.count > 0)
      c.fillRect(cx - half, static_cast<int>(a.py(g.tracked_fraction.mean)), cx + half, a.bottom - 1, kBar);
    centredText(c, cx, a.bottom + 8, g.name, kBlack);
    centredText(c, cx, a.bottom + 28, std::to_string(g.scenes) + " sc", kBlack);
    if (g.worst_tracked != nullptr) {
      const double y = a.py(g.tracked_fraction_worst);
      c.line(cx - half - 6, y, cx + half + 6, y, kWorst, 3);
      const std::string label =
          format("%.2f", g.tracked_fraction_worst) + " " +
          (g.worst_tracked->scene.is_case ? g.worst_tracked->scene.name
                                          : "s" + std::to_string(g.worst_tracked->scene.seed));
      centredText(c, cx, static_cast<int>(y) + (y > a.top + 40 ? -22 : 8), label, kWorst);
    }
  }
  if (gates.tracked_fraction) {
    const double y = a.py(gates.min_tracked_fraction);
    c.line(a.left, y, a.right - 1, y, kGate, 2);
  }
}

void recoveryPanel(Canvas& c, int x0, int y0, const std::vector<SceneRun>& runs) {
  constexpr int kBins = 22;  // 0..19, 20+, never
  int counts[kBins] = {};
  for (const SceneRun& r : runs)
    for (const RecoveryEvent& e : r.result.events)
      ++counts[e.latency < 0 ? kBins - 1 : std::min(e.latency, 20)];
  const int peak = *std::max_element(counts, counts + kBins);
  const Area a = drawFrame(c, x0, y0, "recovery latency (loss, eclipse end, reappear, slew)", 0.0,
                           std::max(1.0, 1.1 * peak), "events");
  const double slot = static_cast<double>(a.right - a.left) / kBins;
  for (int b = 0; b < kBins; ++b) {
    const int l = a.left + static_cast<int>(b * slot) + 2;
    const int r = a.left + static_cast<int>((b + 1) * slot) - 2;
    if (counts[b] > 0)
      c.fillRect(l, static_cast<int>(a.py(counts[b])), r, a.bottom - 1, b == kBins - 1 ? kWorst : kBar);
    const int cx = (l + r) / 2;
    if (b % 5 == 0 && b < 20) centredText(c, cx, a.bottom + 8, std::to_string(b), kBlack);
    if (b == 20) centredText(c, cx, a.bottom + 8, "20+", kBlack);
    if (b == kBins - 1) centredText(c, cx - 10, a.bottom + 28, "never", kWorst);
  }
  centredText(c, (a.left + a.right) / 2, a.bottom + 48, "frames until tracked again", kBlack);
}

void wrongPanel(Canvas& c, int x0, int y0, const std::vector<GroupSummary>& groups) {
  const auto fam = families(groups);
  int peak = 1;
  for (const GroupSummary* g : fam) peak = std::max(peak, g->wrong);
  const Area a = drawFrame(c, x0, y0, "confidently wrong frames per family (scenes affected)", 0.0,
                           1.15 * peak, "frames");
  if (fam.empty()) return;
  const double slot = static_cast<double>(a.right - a.left) / static_cast<double>(fam.size());
  for (std::size_t k = 0; k < fam.size(); ++k) {
    const GroupSummary& g = *fam[k];
    const int cx = a.left + static_cast<int>((static_cast<double>(k) + 0.5) * slot);
    const int half = static_cast<int>(0.3 * slot);
    if (g.wrong > 0) c.fillRect(cx - half, static_cast<int>(a.py(g.wrong)), cx + half, a.bottom - 1, kWorst);
    const std::string label = std::to_string(g.wrong) + " (" + std::to_string(g.wrong_scenes) + "/" +
                              std::to_string(g.scenes) + ")";
    centredText(c, cx, static_cast<int>(a.py(g.wrong)) - 20, label, g.wrong > 0 ? kWorst : kGood);
    centredText(c, cx, a.bottom + 8, g.name, kBlack);
  }
}

void scenePanel(Canvas& c, int x0, int y0, const std::vector<SceneRun>& runs, const Gates& gates) {
  const Area a = drawFrame(c, x0, y0, "tracked fraction per scene (red: confidently wrong frames)", 0.0, 1.0,
                           "fraction");
  if (runs.empty()) return;
  const double slot = static_cast<double>(a.right - a.left) / static_cast<double>(runs.size());
  const double gate = gates.tracked_fraction ? gates.min_tracked_fraction : 0.99;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const SceneResult& r = runs[i].result;
    const double xi = a.left + static_cast<double>(i) * slot;
    const double x = xi + 0.5 * slot;
    if (i > 0 && runs[i].scene.family != runs[i - 1].scene.family)
      c.line(xi, a.top, xi, a.bottom - 1, kBlack);
    if (i == 0 || runs[i].scene.family != runs[i - 1].scene.family)
      c.text(static_cast<int>(xi) + 4, a.bottom + 8, toString(runs[i].scene.family), kBlack, kText);
    if (r.tracked_fraction < 0.0) continue;
    const Rgb colour = r.wrong > 0 ? kWorst : r.tracked_fraction >= gate ? kGood : kBar;
    c.dot(x, a.py(r.tracked_fraction), std::clamp(static_cast<int>(slot / 4), 2, 5), colour);
  }
}

}  // namespace

Canvas renderCampaignPlot(const std::vector<SceneRun>& runs, const std::vector<GroupSummary>& groups,
                          const Gates& gates) {
  Canvas c(2 * kPanelW, 2 * kPanelH, kWhite);
  trackedPanel(c, 0, 0, groups, gates);
  recoveryPanel(c, kPanelW, 0, runs);
  wrongPanel(c, 0, kPanelH, groups);
  scenePanel(c, kPanelW, kPanelH, runs, gates);
  c.resetClip();
  return c;
}

}  // namespace visnav::campaign
