// Where the untracked frames go: what a tracker started at the truth makes of them (--oracle) and the loss
// budget, each expected frame without a tracked pose counted by its first cause (lossCause, summary.cpp).
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "visnav/campaign/report.hpp"
#include "visnav/navigation/fdir_monitor.hpp"

namespace visnav::campaign {

std::string oracleTable(const std::vector<SceneRun>& runs) {
  struct Counts {
    std::string name;
    long untracked = 0;
    long verdict[3] = {0, 0, 0};  // FrameOutcome::oracle 0, 1, 2
    long supported_in_near_range = 0;
    long no_fit_by_evidence[nav::kEvidenceVerdictCount] = {};  // oracle 0, by its first failed test
  };
  std::vector<Counts> groups(1);
  groups[0].name = "all";
  for (const SceneRun& r : runs) {
    const std::string family = toString(r.scene.family);
    auto it = std::find_if(groups.begin(), groups.end(), [&](const Counts& c) { return c.name == family; });
    if (it == groups.end()) {
      groups.push_back(Counts{});
      groups.back().name = family;
      it = groups.end() - 1;
    }
    for (const FrameOutcome& f : r.result.frames) {
      if (!f.expected || f.tracked) continue;
      for (Counts* c : {&groups[0], &*it}) {
        ++c->untracked;
        if (f.oracle >= 0 && f.oracle <= 2) ++c->verdict[f.oracle];
        if (f.oracle == 2 && f.mode == nav::NavMode::kNearRange) ++c->supported_in_near_range;
        if (f.oracle == 0 && f.oracle_evidence >= 0 && f.oracle_evidence < nav::kEvidenceVerdictCount)
          ++c->no_fit_by_evidence[f.oracle_evidence];
      }
    }
  }
  std::ostringstream o;
  o << "image support (--oracle): expected frames without a valid pose, and what a near-range tracker\n"
    << "started at the truth made of each: a right, certain fit (lost by the search or the gates; of them\n"
    << "in near-range mode), a wrong or uncertain fit, no fit\n";
  char buf[200];
  for (const Counts& c : groups) {
    std::snprintf(
        buf, sizeof(buf),
        "%-8s untracked %6ld  right+certain %6ld (near range %6ld)  wrong/uncertain %6ld  no fit %6ld\n",
        c.name.c_str(), c.untracked, c.verdict[2], c.supported_in_near_range, c.verdict[1], c.verdict[0]);
    o << buf;
  }
  // Why no fit: the first image-evidence test the truth-started fit fails (nav::imageEvidenceVerdict).
  o << "no fit, by the first image-evidence test it fails (nav::EvidenceVerdict):\n";
  std::snprintf(buf, sizeof(buf), "%-8s", "group");
  o << buf;
  for (int v = 1; v < nav::kEvidenceVerdictCount; ++v) {
    std::snprintf(buf, sizeof(buf), " %12s", nav::toString(static_cast<nav::EvidenceVerdict>(v)));
    o << buf;
  }
  o << "\n";
  for (const Counts& c : groups) {
    std::snprintf(buf, sizeof(buf), "%-8s", c.name.c_str());
    o << buf;
    for (int v = 1; v < nav::kEvidenceVerdictCount; ++v) {
      std::snprintf(buf, sizeof(buf), " %12ld", c.no_fit_by_evidence[v]);
      o << buf;
    }
    o << "\n";
  }
  return o.str();
}

std::string lossTable(const std::vector<GroupSummary>& groups) {
  std::ostringstream o;
  o << "expected frames without a tracked pose, by cause (the first that applies, in this order):\n";
  char buf[64];
  std::snprintf(buf, sizeof(buf), "%-8s %8s", "group", "untrack");
  o << buf;
  for (int c = 0; c < kLossCauseCount; ++c) {
    std::snprintf(buf, sizeof(buf), " %14s", toString(static_cast<LossCause>(c)));
    o << buf;
  }
  o << "\n";
  for (const GroupSummary& g : groups) {
    int total = 0;
    for (const int n : g.untracked_by_cause) total += n;
    std::snprintf(buf, sizeof(buf), "%-8s %8d", g.name.c_str(), total);
    o << buf;
    for (const int n : g.untracked_by_cause) {
      std::snprintf(buf, sizeof(buf), " %14d", n);
      o << buf;
    }
    o << "\n";
  }
  return o.str();
}

}  // namespace visnav::campaign
