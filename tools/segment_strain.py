#!/usr/bin/python3
"""How close a crust came to the critical_distance rule's threshold (docs/failure-rule.md).

usage: /usr/bin/python3 tools/segment_strain.py LENGTH CHECKPOINT.h5 [...]

For each checkpoint (an encounter's snapshots, say) it prints the largest strain of an unfailed
shell spring and the largest mean strain over the segments the critical_distance rule would look
at: for each of the 400 most strained unfailed shell springs, the unfailed shell springs across
the great-circle segment of length LENGTH (R) centred on its midpoint, perpendicular to its axis,
about the body's centre of mass (the geometry of GreatCircleSegment in
src/physics/shell_failure.cpp). Both also over the checkpoint's eps_S. Strains dimensionless.
"""
import sys

import h5py
import numpy as np

SHELL = 1  # SpringKind::shell


def largest_strains(path, length, candidates=400):
    with h5py.File(path, "r") as f:
        x = f["particles/body/position/value"][0]
        mass = f["particles/body/mass"][:]
        springs = f["connectivity/springs"][:]
        kind = f["checkpoint/springs/kind"][:]
        rest = f["checkpoint/springs/rest_length"][:]
        failed = f["checkpoint/springs/failed"][:]
        eps_s = float(f["checkpoint/record"].attrs["failure_strain"])
    shell = np.nonzero((kind == SHELL) & (failed == 0))[0]
    a, b = x[springs[shell, 0]], x[springs[shell, 1]]
    strain = (np.linalg.norm(a - b, axis=1) - rest[shell]) / rest[shell]
    center = (mass[:, None] * x).sum(0) / mass.sum()
    p, q = a - center, b - center
    largest_mean = 0.0
    for k in np.argsort(-strain)[:candidates]:
        m = 0.5 * (p[k] + q[k])
        rho = np.linalg.norm(m)
        up = m / rho
        axis = q[k] - p[k]
        normal = axis - axis.dot(up) * up
        normal /= np.linalg.norm(normal)
        along = np.cross(normal, up)
        sp, sq = p @ normal, q @ normal
        crossing = sp * sq < 0
        t = np.where(crossing, sp / np.where(crossing, sp - sq, 1.0), 0.0)
        r = p + (q - p) * t[:, None]
        sideways = rho * (r @ along)
        across = crossing & (r @ up > 0) & (4 * sideways**2 <= length**2 * (r * r).sum(1))
        largest_mean = max(largest_mean, strain[across].mean())
    return strain.max(), largest_mean, eps_s


def main(argv):
    if len(argv) < 3:
        sys.exit(__doc__.strip().splitlines()[2])
    length = float(argv[1])
    for path in argv[2:]:
        spring, segment, eps_s = largest_strains(path, length)
        print(f"{path}: largest spring strain {spring:.3e} ({spring / eps_s:.2f} eps_S), largest mean over a "
              f"{length:g} R segment {segment:.3e} ({segment / eps_s:.2f} eps_S)")


if __name__ == "__main__":
    main(sys.argv)
