#!/usr/bin/env python3
"""The fracture maps of a spinning body side by side (issue 26, docs/results/spin.md).

Draws, with the Python package's own map (tidalcrust.figures.encounter.fracture_map, view
"mollweide"), the cracks of member 0 of T5 on welded-L3 without spin and spinning at 0.3 and 0.6
of breakup, prograde and retrograde, each in the body frame that analyze wrote them in (spin pole
north, ring: the subsatellite point at pericenter), into one PNG:

    PYTHONPATH=python /usr/bin/python3 tools/spin_maps.py --runs DIR --out docs/figures/spin-T5-maps.png

DIR holds the run folders of docs/results/spin.md (crust-L3-uniform, spin-L3-0.3, spin-L3-0.6).
Exit 2 naming the missing analysis folder.
"""

import argparse
import json
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from tidalcrust.figures.encounter import fracture_map, projection  # noqa: E402

PANELS = [("crust-L3-uniform", "T5_m0", "no spin"),
          ("spin-L3-0.3", "T5-prograde_m0", "0.3 of breakup, prograde"),
          ("spin-L3-0.3", "T5-retrograde_m0", "0.3 of breakup, retrograde"),
          ("spin-L3-0.6", "T5-prograde_m0", "0.6 of breakup, prograde"),
          ("spin-L3-0.6", "T5-retrograde_m0", "0.6 of breakup, retrograde")]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--runs", required=True, type=Path)
    parser.add_argument("--out", required=True, type=Path)
    args = parser.parse_args(argv)
    fig = plt.figure(figsize=(12, 9.6))
    # no spin on top in the middle, then the 2 x 2 of spin rate (rows) and direction (columns)
    places = [(0.27, 0.64), (0.02, 0.33), (0.51, 0.33), (0.02, 0.02), (0.51, 0.02)]
    for (folder, member, label), (x, y) in zip(PANELS, places):
        analysis = args.runs / folder / member / "analysis"
        summary_file = analysis / "summary.json"
        if not summary_file.is_file():
            print(f"spin_maps: {summary_file}: no analysis (run the commands of docs/results/spin.md)", file=sys.stderr)
            return 2
        summary = json.loads(summary_file.read_text())
        f = summary["failures"]
        sub = summary["encounter"]["orbit"]["subsatellite_longitude_deg"]
        ax = fig.add_axes([x, y, 0.46, 0.27], projection=projection("mollweide"))
        title = (f"{label}: {f['count']} failed, {100 * f['hemisphere_fraction']:.0f}% on the subsatellite "
                 f"hemisphere\nsubsatellite point at longitude {sub:.1f} deg (body frame)")
        fracture_map(analysis, view="mollweide", ax=ax, title=title)
    fig.suptitle("T5 on welded-L3 (member 0 of each ensemble): cracks in the body frame, spin pole north; "
                 "ring: subsatellite point at pericenter", fontsize=10, y=0.995)
    args.out.parent.mkdir(parents=True, exist_ok=True)
    fig.savefig(args.out, dpi=90)
    print(args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main())
