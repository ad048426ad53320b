"""tidalcrust in Python: checkpoints as xarray Datasets, cracks as GIS products, fracture maps.

    import tidalcrust
    ds = tidalcrust.open("checkpoints/quick-balanced/strong")   # an encounter folder or one .h5
    cracks = tidalcrust.cracks_frame("checkpoints/quick-balanced/strong", body="Tethys")
    tidalcrust.write_geojson("checkpoints/quick-balanced/strong", "cracks.geojson")
    fig = tidalcrust.fracture_map("checkpoints/quick-balanced/strong")

Units: the model's, G = M = R = 1 (docs/python.md). Errors: TidalcrustError (a ValueError)
naming the file.
"""
from .checkpoint import UNITS_NOTE, CheckpointError, TidalcrustError, checkpoint_files, open  # noqa: A004
from .cracks import (UNIT_SPHERE_CRS, CracksError, body_crs, cracks_file, cracks_frame, read_cracks,
                     write_geojson, write_shapefile)
from .figures import fracture_map, read_figure_data
from .maps import energy_budget, failure_history, read_summary

__version__ = "0.1.0"
__all__ = ["open", "checkpoint_files", "read_cracks", "cracks_file", "cracks_frame", "body_crs", "write_geojson",
           "write_shapefile", "fracture_map", "read_figure_data", "failure_history", "energy_budget", "read_summary", "UNITS_NOTE",
           "UNIT_SPHERE_CRS", "TidalcrustError", "CheckpointError", "CracksError"]
