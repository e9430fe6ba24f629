#!/usr/bin/env python3
"""Whether the 6-DOF poses' own attitude 1-sigma is honest, per family and target size in pixels.

Reads a campaign run with --frames (`visnav-campaign --frames --out DIR`): every near-range candidate,
delivered or withheld, with its attitude error against the truth (modulo the model's symmetries) and the
1-sigma it reported (square root of the trace of its attitude covariance, so an honest covariance gives
a mean normalised squared error (e/s)^2 of 1). Gross failures (error above --max-error-deg) are left out:
they are a wrong lock, not noise. Target size: the bounding sphere's diameter in pixels (scenes.csv).

For each group it prints the candidates, mean, median and 95th percentile of (e/s)^2, and the factor the
1-sigma would need to make the mean 1 (sqrt of the mean). Above 1: the covariance is too small, and the
validity limits ([navigation] max_valid_attitude_sigma_deg) let through more than they promise. With the
columns of stop 61 (cov_residual_factor, cov_vertex_factor, cov_bias_factor_per_px2), --line-end-bias-px B
first rescales each vertex fit's sigma as [nearrange] line_end_bias_px = B would (NearRangeResult::
systematic_gain), and with stop 62's cov_interior_factor_per_px2 and cov_narrow_factor_per_px2,
--interior-edge-bias-px B and --narrow-face-edge-bias-px B as [nearrange] interior_edge_bias_px and
narrow_face_edge_bias_px = B would; a term not given keeps its default, and the gain the run applied
(column systematic_gain) is divided out first.

    python3 tools/campaign/sigma_consistency.py DIR
    python3 tools/campaign/sigma_consistency.py DIR --line-end-bias-px 0.2
    python3 tools/campaign/sigma_consistency.py DIR --interior-edge-bias-px 0.5
    python3 tools/campaign/sigma_consistency.py DIR --by-edge-kind   # grouped by what the vertices stand on
    python3 tools/campaign/sigma_consistency.py --self-test
"""
import argparse
import collections
import csv
import math
import sys

SIZE_BUCKETS = [(0, 80), (80, 160), (160, 320), (320, math.inf)]


def bucket_name(px):
    for lo, hi in SIZE_BUCKETS:
        if lo <= px < hi:
            return f"{lo}-{'inf' if hi == math.inf else int(hi)} px"
    return "?"


# [nearrange] defaults of the systematic line-end terms (near_range_params.hpp).
DEFAULT_BIAS_PX = {'line_end_bias_px': 0.0, 'interior_edge_bias_px': 0.0, 'narrow_face_edge_bias_px': 0.0}
BIAS_KEYS = ('line_end_bias_px', 'interior_edge_bias_px', 'narrow_face_edge_bias_px')


def biases_asked(a):
    """The three bias values the options ask for, each its default where not given; None: none given."""
    if all(getattr(a, k) is None for k in BIAS_KEYS):
        return None
    return tuple(DEFAULT_BIAS_PX[k] if getattr(a, k) is None else getattr(a, k) for k in BIAS_KEYS)


def sigma_scale(r, biases):
    """What a candidate's delivered sigmas are multiplied by to be as `biases` would make them: the gain
    the run applied (column systematic_gain) divided out, the asked one applied."""
    if biases is None:
        return 1.0
    applied = float(r.get('systematic_gain') or 1.0)
    return math.sqrt(gain_for_bias(r, *biases) / applied) if applied > 0 else 1.0


def gain_for_bias(r, bias_px, interior_bias_px=0.0, narrow_bias_px=0.0):
    """NearRangeResult::systematic_gain for line_end_bias_px = bias_px, interior_edge_bias_px =
    interior_bias_px and narrow_face_edge_bias_px = narrow_bias_px, from the frame's covariance terms
    (cov_interior_factor_per_px2 and cov_narrow_factor_per_px2 since stop 62; a run without them has
    neither term)."""
    try:
        rf = float(r['cov_residual_factor'])
        vf = float(r['cov_vertex_factor'])
        bf = float(r['cov_bias_factor_per_px2'])
    except (KeyError, ValueError):
        return 1.0
    inf = optional_float(r, 'cov_interior_factor_per_px2')
    nf = optional_float(r, 'cov_narrow_factor_per_px2')
    base = max(rf, vf)
    if (bias_px <= 0 and interior_bias_px <= 0 and narrow_bias_px <= 0) or vf <= 0 or base <= 0:
        return 1.0
    return max(rf, vf + bias_px * bias_px * bf + interior_bias_px * interior_bias_px * inf
               + narrow_bias_px * narrow_bias_px * nf) / base


def optional_float(r, column):
    """A column later runs added: 0 when absent or empty."""
    try:
        return float(r.get(column) or 0.0)
    except ValueError:
        return 0.0


NARROW_FACE = 0x1000  # kFlagNarrowFace


def edge_kind(r):
    """What the fit's vertices stand on: 'interior' when some of their lines are of interior edges
    (cov_interior_factor_per_px2 > 0), else 'outline'; '+narrow' with kFlagNarrowFace."""
    kind = 'interior' if optional_float(r, 'cov_interior_factor_per_px2') > 0 else 'outline'
    return kind + ('+narrow' if int(r.get('near_flags') or 0) & NARROW_FACE else '')


def collect(frames, scenes, max_error_deg, biases=None, by_edge_kind=False):
    """frames, scenes: csv rows. Returns {(family, bucket): [(e/s)^2, ...]}, with family 'all' too; with
    by_edge_kind the bucket is edge_kind() instead of the target size."""
    size_m = {s['name']: (float(s['f_px']), 2.0 * float(s['bounding_radius_m'])) for s in scenes}
    groups = collections.defaultdict(list)
    for r in frames:
        if r['mode'] != 'near_range' or r['candidate'] != '1' or r['attitude_sigma_deg'] == '':
            continue
        error = float(r['candidate_attitude_error_deg'])
        sigma = float(r['attitude_sigma_deg']) * sigma_scale(r, biases)
        if error > max_error_deg or not sigma > 0 or r['scene'] not in size_m:
            continue
        f_px, diameter_m = size_m[r['scene']]
        bucket = edge_kind(r) if by_edge_kind else bucket_name(f_px * diameter_m / float(r['range_m']))
        z2 = (error / sigma) ** 2
        groups[(r['family'], bucket)].append(z2)
        groups[('all', bucket)].append(z2)
    return groups


def report(groups, out=sys.stdout):
    print(f"{'family':9s} {'size/kind':15s} {'poses':>7s} {'mean':>7s} {'median':>7s} {'p95':>7s} {'sigma x':>8s}",
          file=out)
    order = {name: i for i, name in enumerate(bucket_name(lo) for lo, _ in SIZE_BUCKETS)}
    for (family, bucket) in sorted(groups, key=lambda k: (k[0] == 'all', k[0], order.get(k[1], 9))):
        v = sorted(groups[(family, bucket)])
        mean = sum(v) / len(v)
        print(f"{family:9s} {bucket:15s} {len(v):7d} {mean:7.2f} {v[len(v) // 2]:7.2f} "
              f"{v[min(len(v) - 1, int(0.95 * len(v)))]:7.2f} {math.sqrt(mean):8.2f}", file=out)


def self_test():
    scenes = [{'name': 'box/1', 'f_px': '1000', 'bounding_radius_m': '1'}]

    def frame(error, sigma, mode='near_range', rf='0', vf='1', bf='100'):
        return {'scene': 'box/1', 'family': 'box', 'mode': mode, 'candidate': '1', 'range_m': '20',
                'candidate_attitude_error_deg': str(error), 'attitude_sigma_deg': str(sigma),
                'cov_residual_factor': rf, 'cov_vertex_factor': vf, 'cov_bias_factor_per_px2': bf}
    frames = [frame(2.0, 1.0), frame(0.0, 1.0), frame(30.0, 1.0), frame(1.0, 1.0, mode='acquisition')]
    g = collect(frames, scenes, 20.0)
    assert list(g.keys()) == [('box', '80-160 px'), ('all', '80-160 px')], g  # 100 px across at 20 m
    assert g[('box', '80-160 px')] == [4.0, 0.0], g  # the 30 deg lock and the acquisition left out
    # A 0.1 px bias with vertex factor 1 and 100 per px^2 doubles the variance: (e/s)^2 halves.
    g = collect(frames[:1], scenes, 20.0, (0.1, 0.0, 0.0))
    assert abs(g[('box', '80-160 px')][0] - 2.0) < 1e-12, g
    # A residual factor above the biased vertex factor leaves the sigma alone.
    assert gain_for_bias(frame(1, 1, rf='5'), 0.1) == 1.0
    assert gain_for_bias({'cov_vertex_factor': ''}, 0.1) == 1.0
    # An interior term of 50 per px^2 at 0.2 px adds 2 to the vertex factor 1: the variance triples.
    f = dict(frame(1, 1), cov_interior_factor_per_px2='50')
    assert abs(gain_for_bias(f, 0.0, 0.2) - 3.0) < 1e-12
    assert abs(gain_for_bias(f, 0.1, 0.2) - 4.0) < 1e-12
    assert gain_for_bias(frame(1, 1), 0.0, 0.2) == 1.0  # no interior column: no interior term
    f['cov_narrow_factor_per_px2'] = '25'  # 1 px on it adds 25: with the interior term's 2, gain 28
    assert abs(gain_for_bias(f, 0.0, 0.2, 1.0) - 28.0) < 1e-12
    # A run that applied a gain of 2 (a default term) replayed with every term off: sigma / sqrt(2).
    applied = dict(frame(1, 1), systematic_gain='2')
    assert abs(sigma_scale(applied, (0.0, 0.0, 0.0)) - math.sqrt(0.5)) < 1e-12
    assert sigma_scale(applied, None) == 1.0  # nothing asked: the delivered sigma
    # By edge kind: a vertex fit with interior lines, and one with a narrow face flagged.
    kinds = dict(frame(1.0, 1.0), cov_interior_factor_per_px2='5', near_flags=str(NARROW_FACE))
    g = collect([frame(2.0, 1.0), kinds], scenes, 20.0, by_edge_kind=True)
    assert g[('box', 'outline')] == [4.0] and g[('box', 'interior+narrow')] == [1.0], g
    print("sigma_consistency.py: self-test passed")
    return 0


def main(argv):
    p = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    p.add_argument('dir', nargs='?')
    p.add_argument('--max-error-deg', type=float, default=20.0)
    p.add_argument('--line-end-bias-px', type=float, default=None)
    p.add_argument('--interior-edge-bias-px', type=float, default=None)
    p.add_argument('--narrow-face-edge-bias-px', type=float, default=None)
    p.add_argument('--by-edge-kind', action='store_true')
    p.add_argument('--self-test', action='store_true')
    a = p.parse_args(argv)
    if a.self_test:
        return self_test()
    if not a.dir:
        p.error('DIR is required')
    with open(a.dir + '/frames.csv', newline='') as f:
        frames = list(csv.DictReader(f))
    with open(a.dir + '/scenes.csv', newline='') as f:
        scenes = list(csv.DictReader(f))
    groups = collect(frames, scenes, a.max_error_deg, biases_asked(a), a.by_edge_kind)
    if not groups:
        print("no near-range candidates", file=sys.stderr)
        return 1
    report(groups)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
