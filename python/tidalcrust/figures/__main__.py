"""`python3 -m tidalcrust.figures KIND FOLDER`: the figures of tidalcrust's data files as PNG and
SVG into FOLDER (docs/python.md, "Figures"). KIND: analysis (an analysis folder: what `analyze`
runs), report, compare or validate (a folder with figure_data.json: what `report`, `compare
--resolution --out` and `validate` run). Bad input: one line on stderr naming the file and the
problem, exit 2."""
import argparse
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")

from ..checkpoint import TidalcrustError  # noqa: E402
from . import draw_analysis, draw_folder  # noqa: E402


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(prog="python3 -m tidalcrust.figures",
                                     description="Draw the figures of tidalcrust's data files (PNG and SVG).")
    sub = parser.add_subparsers(dest="kind", required=True)
    analysis = sub.add_parser("analysis", help="the figures of an analysis folder (what `analyze` draws)")
    analysis.add_argument("folder")
    analysis.add_argument("--mosaic", help="an image in the orbital frame's longitude (-180..180) and latitude "
                          "(90..-90, top row first) drawn under the maps")
    for kind, what in (("report", "report/"), ("compare", "compare --resolution --out DIR"),
                       ("validate", "validate/")):
        sub.add_parser(kind, help=f"the figures of {what} (its figure_data.json)").add_argument("folder")
    args = parser.parse_args(argv)
    try:
        if args.kind == "analysis":
            draw_analysis(args.folder, mosaic=args.mosaic)
        else:
            draw_folder(args.folder)
    except (TidalcrustError, OSError) as err:
        print(f"tidalcrust.figures {args.kind}: {err}", file=sys.stderr)
        return 2
    except (KeyError, TypeError, ValueError, IndexError) as err:
        print(f"tidalcrust.figures {args.kind}: {Path(args.folder) / 'figure_data.json'}: unexpected content "
              f"({type(err).__name__}: {err})", file=sys.stderr)
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
