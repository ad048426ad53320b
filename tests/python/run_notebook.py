"""examples/quick-start.ipynb executed with nbclient on a run this test makes (tests/python/
small.toml), as a user would on `make run`'s output; then what it wrote is checked: the GeoJSON
has the run's crack count and opens in GeoPandas with the CRS of the body it was given (Tethys)."""
import json
import os
import sys
import time
from pathlib import Path

import geopandas as gpd
import nbclient
import nbformat

sys.path.insert(0, str(Path(__file__).resolve().parent))
from small_run import make_small_run, scratch  # noqa: E402

NOTEBOOK = Path(__file__).resolve().parents[2] / "examples" / "quick-start.ipynb"


def main() -> int:
    with scratch() as tmp:
        encounter = make_small_run(tmp)
        os.environ.update(TIDALCRUST_RUN=str(encounter), TIDALCRUST_BODY="Tethys", TIDALCRUST_NOTEBOOK_OUT=tmp,
                          MPLBACKEND="module://matplotlib_inline.backend_inline")
        notebook = nbformat.read(NOTEBOOK, as_version=4)
        start = time.monotonic()
        nbclient.NotebookClient(notebook, timeout=300, kernel_name="python3",
                                resources={"metadata": {"path": str(NOTEBOOK.parent)}}).execute()
        print(f"notebook executed in {time.monotonic() - start:.1f} s")
        summary = json.loads((encounter / "analysis" / "summary.json").read_text())
        cracks = gpd.read_file(Path(tmp) / "cracks.geojson")
        failures = []
        if len(cracks) != summary["failures"]["clusters"]:
            failures.append(f"GeoJSON has {len(cracks)} cracks, summary.json {summary['failures']['clusters']}")
        if cracks.crs is None or cracks.crs.name != "Tethys (2015) - Sphere / Ocentric":
            failures.append(f"GeoJSON CRS is {cracks.crs and cracks.crs.name}, not Tethys (2015) - Sphere / Ocentric")
        if sum(cracks["springs"]) != summary["failures"]["count"]:
            failures.append(f"GeoJSON cracks hold {sum(cracks['springs'])} springs, summary.json "
                            f"{summary['failures']['count']}")
        images = sum(1 for cell in notebook.cells if cell.cell_type == "code" for out in cell.get("outputs", [])
                     if "image/png" in out.get("data", {}))
        if images != 4:  # two maps, the failures, the energy budget
            failures.append(f"the notebook drew {images} figures, not 4")
        text = "".join(out.get("text", "") for cell in notebook.cells if cell.cell_type == "code"
                       for out in cell.get("outputs", []))
        if f"{summary['failures']['count']} failed springs, {summary['failures']['clusters']} cracks" not in text:
            failures.append("the notebook did not print the run's failed springs and cracks")
        for f in failures:
            print("FAIL:", f)
        return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
