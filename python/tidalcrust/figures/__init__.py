"""The figures of tidalcrust, drawn with matplotlib and cartopy from the files the program writes
(docs/python.md, "Figures"): one function per figure, each taking the folder (or one figure's
data) and optionally the Axes to draw into, and returning the Figure for the caller to restyle.
`python3 -m tidalcrust.figures KIND FOLDER` draws them as PNG and SVG files (what analyze,
report, compare --resolution and validate run)."""
from .encounter import (ANALYSIS_FIGURES, UNIT_GLOBE, VIEWS, axis_ratios, body_shape, conservation, crack_collection,
                        crack_geometry, draw_analysis, failures, fracture_map, hemisphere, map_frame, orbit,
                        projection, read_figure_data, save)
from .plots import (KINDS, draw_folder, figure_spec, fracture_map_row, phase_diagram, read_figure_specs, signal_plot,
                    tidal_strain_plot)

__all__ = ["fracture_map", "crack_geometry", "hemisphere", "orbit", "failures", "conservation", "body_shape",
           "axis_ratios", "phase_diagram", "fracture_map_row", "signal_plot", "tidal_strain_plot", "draw_analysis",
           "draw_folder", "read_figure_data", "read_figure_specs", "figure_spec", "projection", "map_frame",
           "crack_collection",
           "save", "ANALYSIS_FIGURES", "KINDS", "UNIT_GLOBE", "VIEWS"]
