"""The figures of `report` (phase diagrams), `compare --resolution` (fracture maps side by side)
and `validate` (signal plots), drawn from the figure_data.json those commands write into their
folder: {"figures": {stem: {"kind": ..., ...}}}. One function per kind, each taking one figure's
object (figure_spec) and optionally an Axes; draw_folder draws them all (docs/python.md)."""
from __future__ import annotations

import os
from pathlib import Path

import matplotlib.pyplot as plt
from matplotlib.collections import LineCollection
from matplotlib.colors import Normalize

from ..checkpoint import TidalcrustError
from .encounter import (FIGURE_DATA_FORMAT, FIGURE_DATA_VERSION, TICK_COLOR, _map_axes, _read_json,
                        projection, save)

BOUNDARY_COLOR = "#d62728"
EQ5_COLOR = "#ff7f0e"


def read_figure_specs(folder: str | os.PathLike) -> dict:
    """FOLDER/figure_data.json of report/, compare --resolution --out or validate/ as a dict of
    figure objects by file stem. Raises TidalcrustError naming the file."""
    file = Path(folder) / "figure_data.json"
    data = _read_json(file, "written by tidalcrust report, compare --resolution or validate")
    if data.get("format") != FIGURE_DATA_FORMAT or data.get("version") != FIGURE_DATA_VERSION \
            or not isinstance(data.get("figures"), dict):
        raise TidalcrustError(f"{file}: not {FIGURE_DATA_FORMAT} version {FIGURE_DATA_VERSION} with figures by name")
    return data["figures"]


def figure_spec(folder: str | os.PathLike, name: str) -> dict:
    """The object of figure `name` (its file stem) in FOLDER/figure_data.json."""
    specs = read_figure_specs(folder)
    if name not in specs:
        raise TidalcrustError(f"{Path(folder) / 'figure_data.json'}: no figure '{name}' (has {', '.join(specs)})")
    return specs[name]


def _spec(spec_or_folder, name):
    return spec_or_folder if isinstance(spec_or_folder, dict) else figure_spec(spec_or_folder, name)


def phase_diagram(spec, name: str | None = None, ax=None):
    """A sweep's phase diagram (`report`): encounters over pericenter q and speed V_q, filled
    circles coloured by the failed fraction (or the share of cracked members) where the crust
    cracked, open circles where it did not, grey crosses for encounters not finished; the eq. 5
    strain = eps_S line and the crack/no-crack boundary dashed. spec: a figure object, or a
    report folder and the figure's stem. Returns the Figure."""
    s = _spec(spec, name)
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 5.4))
    norm = Normalize(0.0, s["colour_top"])
    cmap = plt.get_cmap("viridis")
    points = s["points"]
    done = [p for p in points if p["finished"]]
    cracked = [p for p in done if p["cracked"]]
    intact = [p for p in done if not p["cracked"]]
    waiting = [p for p in points if not p["finished"]]
    ax.add_collection(LineCollection(s["boundary"], colors=BOUNDARY_COLOR, linewidths=2.2, linestyles=(0, (6, 3)),
                                     label=s["boundary_label"], gid="boundary"))
    ax.plot(s["eq5"]["q"], s["eq5"]["v_q"], color=EQ5_COLOR, linewidth=2.4, label=s["eq5"]["label"], gid="eq5")
    mappable = ax.scatter([p["q"] for p in cracked], [p["v_q"] for p in cracked],
                          c=[p["value"] if p["value"] is not None else 0.0 for p in cracked], cmap=cmap, norm=norm,
                          s=70, edgecolors="black", linewidths=0.7, zorder=3, gid="cracked",
                          label=None if s["crack_probability"] else "cracked")
    ax.scatter([p["q"] for p in intact], [p["v_q"] for p in intact], facecolors="white", edgecolors=cmap(0.0), s=70,
               linewidths=1.8, zorder=3, gid="intact", label="no crack")
    ax.scatter([p["q"] for p in waiting], [p["v_q"] for p in waiting], marker="x", color="0.6", s=40, zorder=3,
               gid="unfinished", label="not finished" if waiting else None)
    ax.figure.colorbar(mappable, ax=ax, label=s["colour_label"])
    ax.set_xlim(*s["x_range"])
    ax.set_ylim(*s["y_range"])
    ax.set_xlabel(s["x_label"])
    ax.set_ylabel(s["y_label"])
    ax.set_title(s["title"], fontsize=9)
    ax.legend(fontsize=7, loc="upper right")
    return ax.figure


def fracture_map_row(spec, name: str | None = None, axes=None, view: str = "mollweide"):
    """Fracture maps side by side (`compare --resolution`: one panel per shell level, coarsest
    first), each a `view` map (encounter.projection) of that level's cracks with its title.
    axes: GeoAxes of projection(view), one per panel. Returns the Figure."""
    s = _spec(spec, name)
    panels = s["panels"]
    if axes is None:
        fig = plt.figure(figsize=(4.6 * len(panels), 3.6))
        axes = [fig.add_subplot(1, len(panels), k + 1, projection=projection(view)) for k in range(len(panels))]
    for ax, panel in zip(axes, panels):
        _map_axes(ax, view, panel["cracks"], linewidth=0.8)
        ax.set_title(panel["title"], fontsize=8)
    fig = axes[0].figure
    fig.suptitle(s["title"], fontsize=9)
    fig.text(0.5, 0.02, f"{view}; equator = orbital plane; ring: subsatellite point (90\u00b0)", ha="center", fontsize=7)
    return fig


def signal_plot(spec, name: str | None = None, ax=None):
    """A measured signal against time (`validate`) with the times theory predicts (dashed grey)
    and those measured (solid red) as vertical lines. Returns the Figure."""
    s = _spec(spec, name)
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 4.2))
    ax.plot(s["time"], s["signal"], color="black", linewidth=1.2, gid="signal")
    theory = measured = 0
    for mark in s["marks"]:
        style = dict(color=TICK_COLOR, linewidth=0.9) if mark["measured"] else dict(color="0.45", linewidth=0.9,
                                                                                     linestyle=(0, (4, 3)))
        ax.axvline(mark["time"], gid="measured" if mark["measured"] else "theory", **style)
        if mark["label"]:
            k = measured if mark["measured"] else theory
            ax.annotate(mark["label"], (mark["time"], 0.04 + 0.07 * k if mark["measured"] else 0.96 - 0.07 * k),
                        xycoords=("data", "axes fraction"), xytext=(3, 0), textcoords="offset points", fontsize=7,
                        va="bottom" if mark["measured"] else "top")
            measured, theory = (measured + 1, theory) if mark["measured"] else (measured, theory + 1)
    ax.set_xlim(s["time"][0], s["time"][-1])
    ax.set_xlabel(s["x_label"])
    ax.set_ylabel(s["y_label"])
    ax.set_title(s["title"], fontsize=9)
    return ax.figure


def tidal_strain_plot(spec, name: str | None = None, ax=None):
    """Measured against continuum crust strain by angle from the tidal axis (`validate --measure
    tide`): the bands' meridional (red) and azimuthal (blue) strains as points, the continuum
    (Takeuchi and Saito 1972) as lines. Returns the Figure."""
    s = _spec(spec, name)
    if ax is None:
        _, ax = plt.subplots(figsize=(7, 4.2))
    theory, bands = s["theory"], s["bands"]
    ax.axhline(0.0, color="0.6", linewidth=0.6)
    gamma = [b["gamma_deg"] for b in bands]
    for key, color, label in (("meridional", "#d90000", "meridional eps_psipsi"),
                              ("azimuthal", "#0040cc", "azimuthal eps_lamlam")):
        ax.plot(theory["gamma_deg"], theory[key], color=color, linewidth=1.2, label=f"{label} (continuum)",
                gid=f"theory_{key}")
        ax.plot(gamma, [b[key] for b in bands], "o", color=color, markersize=5, label=f"{label} (crust springs)",
                gid=f"measured_{key}")
    ax.set_xlim(0, 90)
    ax.set_xlabel(s["x_label"])
    ax.set_ylabel(s["y_label"])
    ax.set_title(s["title"], fontsize=9)
    ax.legend(fontsize=7)
    return ax.figure


#: The function that draws each kind of figure object.
KINDS = {"phase_diagram": phase_diagram, "fracture_map_row": fracture_map_row, "signal": signal_plot,
         "tidal_strain": tidal_strain_plot}


def draw_folder(folder: str | os.PathLike) -> list[Path]:
    """Every figure of FOLDER/figure_data.json as FOLDER/<stem>.png and .svg. Returns the files."""
    folder = Path(folder)
    written = []
    for name, spec in read_figure_specs(folder).items():
        kind = spec.get("kind") if isinstance(spec, dict) else None
        if kind not in KINDS:
            raise TidalcrustError(f"{folder / 'figure_data.json'}: figure '{name}' of unknown kind '{kind}'")
        written += save(KINDS[kind](spec), folder / name)
    return written


__all__ = ["phase_diagram", "fracture_map_row", "signal_plot", "tidal_strain_plot", "draw_folder", "read_figure_specs",
           "figure_spec", "KINDS"]
