#!/usr/bin/env python3
"""Strain percentiles of the crust springs in tidalcrust checkpoints (a diagnostic, README
"Resolution convergence"): for each FILE.h5, strain = |x_i - x_j| / L0 - 1 of every shell spring
(kind 1), read with h5dump (hdf5-tools); prints the shell spring count, the maximum, the 99th and
90th percentiles, the median and the fraction above the checkpoint's failure strain EPS (default
0.003). Failed springs are included (they stretch freely): compare snapshots before the first
failure, or read the 90th percentile. Usage: tools/shell_strain_percentiles.py [--eps EPS] FILE.h5...
"""
import re
import subprocess
import sys


def dataset(path, name):
    out = subprocess.run(["h5dump", "-A", "0", "-d", name, "-y", "-w", "0", "-m", "%.17g", path],
                         capture_output=True, text=True, check=True).stdout
    body = out[out.index("DATA {") + 6: out.rindex("}")]
    return [float(x) for x in re.findall(r"[-+0-9.eE]+(?=[,\s])", body.replace("\n", " ") + " ")]


def main(argv):
    eps = 0.003
    if len(argv) > 2 and argv[1] == "--eps":
        eps, argv = float(argv[2]), argv[:1] + argv[3:]
    if len(argv) < 2:
        sys.exit(__doc__)
    for path in argv[1:]:
        pos = dataset(path, "/particles/body/position/value")
        ends = dataset(path, "/connectivity/springs")
        kind = dataset(path, "/checkpoint/springs/kind")
        rest = dataset(path, "/checkpoint/springs/rest_length")
        strain = []
        for s, k in enumerate(kind):
            if int(k) != 1:
                continue
            i, j = int(ends[2 * s]), int(ends[2 * s + 1])
            d = sum((pos[3 * i + a] - pos[3 * j + a]) ** 2 for a in range(3)) ** 0.5
            strain.append(d / rest[s] - 1)
        strain.sort()
        m = len(strain)
        if m == 0:
            print(f"{path}: no shell springs")
            continue
        above = sum(1 for x in strain if x > eps) / m
        print(f"{path}: {m} shell springs, max {strain[-1]:.3g}, p99 {strain[int(0.99 * m)]:.3g}, "
              f"p90 {strain[int(0.9 * m)]:.3g}, median {strain[m // 2]:.3g}, above {eps:g}: {100 * above:.2f}%")


if __name__ == "__main__":
    main(sys.argv)
