#!/usr/bin/python3
"""How much of a fracture set's crack length runs beside another crack (docs/failure-rule.md).

usage: /usr/bin/python3 tools/parallel_cracks.py [--distance D] [--short S] RUN/.../analysis/cracks.json [...]

A crack (a cluster of failed shell springs joined through the faces they share, as `analyze`
groups them) is a set of dual-lattice polylines in cracks.json. For each piece of polyline (two
consecutive points) the tool asks whether its midpoint lies within D (default 0.04 R, about one
lattice spacing at level 5 and two at level 6) of a point of another crack, and sums the length
of those pieces: the crack length that runs beside another crack, parallel to it or overlapping
its end, which a crack's stress shadow should keep free. It also counts the cracks shorter than
S (default 0.6 R) and their length. Distances are chords on the unit sphere (R); lengths are the
polylines' chords, whose sum is summary.json's total_crack_length. One line per file.
"""
import argparse
import json
import math

import numpy as np
from scipy.spatial import cKDTree


def unit_vectors(points_deg):
    """(n, 3) unit vectors of [longitude, latitude] pairs in degrees."""
    p = np.radians(np.asarray(points_deg, dtype=float).reshape(-1, 2))
    return np.column_stack((np.cos(p[:, 1]) * np.cos(p[:, 0]), np.cos(p[:, 1]) * np.sin(p[:, 0]), np.sin(p[:, 1])))


def beside_another(cracks, distance):
    """Per crack: (its length, its length within `distance` of another crack), in R."""
    points, owner = [], []
    for k, crack in enumerate(cracks):
        for line in crack["polylines"]:
            points.append(unit_vectors(line))
            owner.append(np.full(len(line), k))
    if not points:
        return []
    tree = cKDTree(np.vstack(points))
    owner = np.concatenate(owner)
    result = []
    for k, crack in enumerate(cracks):
        total = near = 0.0
        for line in crack["polylines"]:
            x = unit_vectors(line)
            if len(x) < 2:
                continue
            piece = np.linalg.norm(x[1:] - x[:-1], axis=1)
            total += piece.sum()
            for mid, length in zip(0.5 * (x[1:] + x[:-1]), piece):
                if any(owner[j] != k for j in tree.query_ball_point(mid, distance)):
                    near += length
        result.append((total, near))
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cracks", nargs="+", help="cracks.json files written by tidalcrust analyze")
    parser.add_argument("--distance", type=float, default=0.04, help="R (default 0.04)")
    parser.add_argument("--short", type=float, default=0.6, help="R (default 0.6)")
    args = parser.parse_args()
    if not (args.distance > 0 and args.short > 0):
        parser.error("--distance and --short must be positive lengths in R")
    for path in args.cracks:
        try:
            with open(path) as f:
                cracks = json.load(f)["cracks"]
        except (OSError, ValueError, KeyError) as e:
            raise SystemExit(f"{path}: not a cracks.json of tidalcrust analyze ({e})")
        lengths = beside_another(cracks, args.distance)
        total = sum(t for t, _ in lengths)
        near = sum(n for _, n in lengths)
        short = [t for t, _ in lengths if t < args.short]
        share = near / total if total > 0 else math.nan
        print(f"{path}: {len(cracks)} cracks, {total:.2f} R; within {args.distance:g} R of another crack "
              f"{near:.2f} R ({100 * share:.1f}%); shorter than {args.short:g} R: {len(short)} cracks, {sum(short):.2f} R")


if __name__ == "__main__":
    main()
