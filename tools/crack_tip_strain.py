#!/usr/bin/python3
"""Strain at the tips of the griffith rule's flaws in an encounter checkpoint (docs/failure-rule.md).

usage: /usr/bin/python3 tools/crack_tip_strain.py ENCOUNTER.h5 [...]

For each flaw (a step that failed three or more shell springs at once) it takes the largest
strain of the unfailed shell springs ahead of the flaw's springs (midpoint within the record's
exclusion_distance r_ex and at least 45 degrees off the failed spring's axis, as the rule's
CrackMap decides "extends"), and the ambient strain: the 90th percentile of the unfailed shell
springs' strains 0.35-0.6 R from the flaw's centre. It prints, per file, the medians over the
flaws of tip / eps_S, ambient / eps_S and tip / ambient, and the rule's growth_strain_factor,
the tip / far-field ratio the rule assumes (LEFM). Lengths in R, strains dimensionless.
"""
import collections
import sys

import h5py
import numpy as np


def flaw_tips(path):
    f = h5py.File(path, "r")
    x = f["particles/body/position/value"][0]
    springs = f["connectivity/springs"][:]
    kind = f["checkpoint/springs/kind"][:]
    failed = f["checkpoint/springs/failed"][:]
    rest = f["checkpoint/springs/rest_length"][:]
    record = f["checkpoint/record"].attrs
    eps_s, r_ex = float(record["failure_strain"]), float(record["exclusion_distance"])
    events = f["checkpoint/failures"]
    if len(events["spring"]) == 0:
        return None
    shell = kind == kind[events["spring"][0]]
    length = np.linalg.norm(x[springs[:, 0]] - x[springs[:, 1]], axis=1)
    strain = (length - rest) / rest
    mid = 0.5 * (x[springs[:, 0]] + x[springs[:, 1]])
    axis = (x[springs[:, 1]] - x[springs[:, 0]]) / length[:, None]
    by_step = collections.defaultdict(list)
    for step, spring in zip(events["step"][:], events["spring"][:]):
        by_step[step].append(spring)
    intact = np.where(shell & (failed == 0))[0]
    rows = []
    for flaw in (np.array(s) for s in by_step.values() if len(s) >= 3):
        tip = 0.0
        for n in flaw:
            offset = mid[intact] - mid[n]
            distance = np.linalg.norm(offset, axis=1)
            along = offset @ axis[n]
            ahead = (distance < r_ex) & (2 * along * along <= distance * distance)
            if ahead.any():
                tip = max(tip, strain[intact][ahead].max())
        centre_distance = np.linalg.norm(mid[intact] - mid[flaw].mean(axis=0), axis=1)
        ring = strain[intact][(centre_distance > 0.35) & (centre_distance < 0.6)]
        if len(ring):
            rows.append((tip / eps_s, np.percentile(ring, 90) / eps_s))
    return np.array(rows), float(record["growth_strain_factor"])


def main(paths):
    if not paths:
        sys.exit(__doc__.strip().splitlines()[2])
    for path in paths:
        result = flaw_tips(path)
        if result is None or len(result[0]) == 0:
            print(f"{path}: no flaws")
            continue
        rows, factor = result
        print(f"{path}: {len(rows)} flaws; median tip/eps_S {np.median(rows[:, 0]):.2f}, "
              f"ambient/eps_S {np.median(rows[:, 1]):.2f}, tip/ambient {np.median(rows[:, 0] / rows[:, 1]):.2f} "
              f"(rule's growth_strain_factor {factor:.2f})")


if __name__ == "__main__":
    main(sys.argv[1:])
