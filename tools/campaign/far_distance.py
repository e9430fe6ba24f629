#!/usr/bin/env python3
"""Far range's distance against the truth over a campaign run (`visnav-campaign --frames --out DIR`).

For every far fix outside an eclipse, by the target's true apparent radius (f x bounding radius / range),
prints the median and 90th percentile of |log(distance / range)| for eq. 16 (gamma / sqrt(n)), for the
extent (f x bounding radius / the cluster's extent) and for the distance far range delivered (the nearer
of the two where the extent is at least [farrange] extent_distance_min_px). Only fixes that either
estimate puts within a factor 2 of the range are counted: the others are clusters that are not the target,
on which no distance is right.

    python3 tools/campaign/far_distance.py DIR
"""
import csv
import math
import sys
from collections import defaultdict

BINS_PX = [2, 4, 8, 16, 32, 64, 128, math.inf]


def main(out_dir):
    scenes = {s["name"]: s for s in csv.DictReader(open(f"{out_dir}/scenes.csv"))}
    errors = defaultdict(lambda: ([], [], []))
    with open(f"{out_dir}/frames.csv") as frames:
        for r in csv.DictReader(frames):
            if r["far_valid"] != "1" or r["eclipsed"] == "1":
                continue
            s = scenes[r["scene"]]
            range_m = float(r["range_m"])
            radius_px = float(s["f_px"]) * float(s["bounding_radius_m"]) / range_m
            ratios = [float(r[c]) / range_m for c in ("far_eq16_distance_m", "far_extent_distance_m", "far_distance_m")]
            if not (0.5 < ratios[0] < 2.0 or 0.5 < ratios[1] < 2.0):
                continue
            upper = next(b for b in BINS_PX if radius_px < b)
            for k, ratio in enumerate(ratios):
                errors[upper][k].append(abs(math.log(ratio)))

    def stats(values):
        v = sorted(values)
        return f"{v[len(v) // 2]:.2f} {v[9 * len(v) // 10]:.2f}"

    print("true radius px   fixes   eq. 16 med p90   extent med p90   delivered med p90   (abs log error)")
    lower = 0
    for upper in BINS_PX:
        if upper in errors:
            e = errors[upper]
            print(f"{lower:>5}-{upper:<8} {len(e[0]):>7}   {stats(e[0]):>14}   {stats(e[1]):>14}   {stats(e[2]):>17}")
        lower = upper


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
