#!/usr/bin/python3
"""Where on the body a fracture set's crack length lies and how it runs: by the angle from the
subsatellite point (docs/results/crust-coupling.md, the nonlocal rules' resolution studies).

usage: /usr/bin/python3 tools/rose_by_angle.py RUN/.../analysis/cracks.json [...]

Each piece of a crack's dual-lattice polylines in cracks.json (two consecutive points) is put in
the band of angle from the subsatellite point (cracks.json's `subsatellite`) that holds its
midpoint, BANDS_DEG, and counted with its chord length (R) as radial when its direction lies
within 22.5 deg of the great circle through the subsatellite point, concentric when within 22.5
deg of the perpendicular: the sectors rose_0 and rose_90 of docs/crack-geometry.md, here weighted by
length piece by piece instead of per failed spring. One line per file and band: the band's crack
length and its radial and concentric shares.
"""
import argparse
import json

import numpy as np

from parallel_cracks import unit_vectors

BANDS_DEG = (0, 20, 30, 40, 50, 60, 90)


def bands(cracks, subsatellite_deg):
    """(len(BANDS_DEG) - 1, 3) array: per band of angle from the subsatellite point, the crack
    length, its radial part and its concentric part (R). Pieces beyond the last band (farther than
    90 deg) and at the subsatellite point itself (no direction to it) are left out."""
    s = unit_vectors(subsatellite_deg)[0]
    out = np.zeros((len(BANDS_DEG) - 1, 3))
    for crack in cracks:
        for line in crack["polylines"]:
            x = unit_vectors(line)
            if len(x) < 2:
                continue
            piece = x[1:] - x[:-1]
            length = np.linalg.norm(piece, axis=1)
            mid = 0.5 * (x[1:] + x[:-1])
            mid /= np.linalg.norm(mid, axis=1)[:, None]
            angle = np.degrees(np.arccos(np.clip(mid @ s, -1, 1)))
            toward = s[None, :] - (mid @ s)[:, None] * mid  # tangent toward the subsatellite point
            norm = np.linalg.norm(toward, axis=1)
            ok = (norm > 1e-12) & (length > 0)
            cos = np.abs(np.sum(piece * toward, axis=1))[ok] / (length[ok] * norm[ok])
            azimuth = np.degrees(np.arccos(np.clip(cos, 0, 1)))  # 0 radial .. 90 concentric
            band = np.digitize(angle[ok], BANDS_DEG) - 1
            for b, a, l in zip(band, azimuth, length[ok]):
                if 0 <= b < len(BANDS_DEG) - 1:
                    out[b] += (l, l if a < 22.5 else 0, l if a >= 67.5 else 0)
    return out


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cracks_json", nargs="+")
    args = parser.parse_args()
    for path in args.cracks_json:
        with open(path) as f:
            data = json.load(f)
        for (lo, hi), (total, radial, concentric) in zip(zip(BANDS_DEG, BANDS_DEG[1:]),
                                                         bands(data["cracks"], data["subsatellite"])):
            shares = (radial / total, concentric / total) if total > 0 else (float("nan"),) * 2
            print(f"{path}: {lo}-{hi} deg: length {total:.3f} R, radial {shares[0]:.3f}, concentric {shares[1]:.3f}")


if __name__ == "__main__":
    main()
