#!/usr/bin/env python3
"""Where a campaign run's confidently wrong frames come from (`visnav-campaign --frames --out DIR`).

Each wrong frame is traced back, within its scene, to what began the track it belongs to: the scene's
true start (`start`), a close-range reacquisition's find (`reacq`, the frame marked `reacquired`), or a
hand-over from another mode into near range (`acq:<mode>`). It is a `drift` when that track delivered a
valid, accurate frame before it, else `never-right`. Prints one line per origin with its frames, scenes
and the scenes with most frames.

    python3 tools/campaign/wrong_origins.py DIR
    python3 tools/campaign/wrong_origins.py --self-test
"""
import csv
import sys
from collections import Counter, defaultdict


def origins(rows):
    """rows: frames.csv rows in file order. Returns {origin: Counter(scene -> wrong frames)}."""
    found = defaultdict(Counter)
    scene, origin, right_since, prev_mode = None, "start", False, None
    for r in rows:
        if r["scene"] != scene:
            scene, origin, right_since, prev_mode = r["scene"], "start", False, None
        if r["reacquired"] == "1":
            origin, right_since = "reacq", False
        elif prev_mode is not None and r["mode"] == "near_range" and prev_mode != "near_range":
            origin, right_since = "acq:" + prev_mode, False
        prev_mode = r["mode"]
        if r["wrong"] == "1":
            found[origin + ("/drift" if right_since else "/never-right")][scene] += 1
        elif r["pose_valid"] == "1" and r["accurate"] == "1":
            right_since = True
    return found


def report(found):
    total = sum(sum(c.values()) for c in found.values())
    print(f"wrong frames: {total}")
    for key, scenes in sorted(found.items(), key=lambda kv: -sum(kv[1].values())):
        worst = " ".join(f"{s}:{n}" for s, n in scenes.most_common(6))
        print(f"  {key:28s} {sum(scenes.values()):5d} frames in {len(scenes):3d} scenes  {worst}")


def self_test():
    def row(scene, mode, valid, accurate, wrong, reacquired="0"):
        return {"scene": scene, "mode": mode, "pose_valid": valid, "accurate": accurate, "wrong": wrong,
                "reacquired": reacquired}
    rows = [
        row("a", "near_range", "1", "0", "1"),  # wrong from the true start
        row("a", "near_range", "1", "1", "0"),
        row("a", "near_range", "1", "0", "1"),  # after a right frame: drift
        row("b", "far_range", "0", "0", "0"),
        row("b", "near_range", "1", "0", "1"),  # handed over from far range, never right
        row("b", "near_range", "1", "0", "1", reacquired="1"),  # a find, never right
    ]
    got = {k: dict(v) for k, v in origins(rows).items()}
    want = {"start/never-right": {"a": 1}, "start/drift": {"a": 1}, "acq:far_range/never-right": {"b": 1},
            "reacq/never-right": {"b": 1}}
    if got != want:
        print(f"wrong_origins self-test failed: {got} != {want}")
        return 1
    print("wrong_origins self-test passed")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    if sys.argv[1] == "--self-test":
        sys.exit(self_test())
    with open(f"{sys.argv[1]}/frames.csv") as f:
        report(origins(csv.DictReader(f)))
