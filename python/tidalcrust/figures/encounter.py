"""The figures of `tidalcrust analyze`, drawn with matplotlib and cartopy from the files it writes
(summary.json, cracks.json, figure_data.json in an analysis folder): one short function per
figure, each taking the folder (an encounter folder, its analysis folder or a file in it) and
optionally the Axes to draw into, and returning the Figure for the caller to restyle
(docs/python.md, "Figures"). Every number drawn is computed by the C++ program; these functions
only draw it.

    python3 -m tidalcrust.figures analysis FOLDER [--mosaic IMAGE]

draws every figure of an analysis folder as PNG and SVG (what `analyze` runs). Maps are in the
orbital frame: the orbital plane is the equator, the subsatellite point (the perturber's
direction at pericenter) is at longitude +90, latitude 0. Of a workflow with a [moon]
(figure_data.json's `map`, `time_axis`, `length_axis`; docs/moon.md, "Output in SI") the maps are
in planetocentric longitude (0 at the subsatellite point, east positive) with a km scale bar, the
time axes in hours (t_grav on a second axis) and the orbit has a km axis beside R.
"""
from __future__ import annotations

import json
import os
import textwrap
from pathlib import Path

import cartopy.crs as ccrs
import matplotlib
import matplotlib.pyplot as plt
import numpy as np
from matplotlib.collections import LineCollection, PolyCollection
from matplotlib.patches import Circle, FancyArrow, Polygon

from ..checkpoint import TidalcrustError
from ..cracks import _split_at_antimeridian, read_cracks

#: The unit sphere (R = 1) as cartopy's globe: the maps are in the model's units.
UNIT_GLOBE = ccrs.Globe(semimajor_axis=1.0, semiminor_axis=1.0, ellipse=None)
SUBSATELLITE_LON_LAT = (90.0, 0.0)
FIGURE_DATA_FORMAT = "tidalcrust-figure-data"
FIGURE_DATA_VERSION = 1
#: Colours shared by the figures (restyle by passing your own Axes and changing the artists).
CRACK_COLOR = "black"
EARLIER_CRACK_COLOR = "0.6"  # cracks of the encounters before this one (an encounter history)
SURFACE_COLOR = "#ede6d8"
SUBSATELLITE_COLOR = "#f2c200"
PERTURBER_COLOR = "#c0209a"
ARC_COLOR = "#1f6fd0"
TICK_COLOR = "#d02020"
TIME_LABEL = "t \u2212 t_peri [t_grav]"
VIEWS = ("overview", "mollweide", "equirectangular", "orthographic", "antipode")
#: The map frame of figure_data.json's `map` without a [moon] (and of files written before it).
ORBITAL_MAP = {"frame": "orbital", "longitude_shift_deg": 0.0, "subsatellite": list(SUBSATELLITE_LON_LAT),
               "scale_bar": None,
               "note": "top: Mollweide (equal-area), longitude and latitude in degrees in the body's frame; below: "
                       "orthographic; ring: subsatellite point"}


def _analysis_folder(path: str | os.PathLike) -> Path:
    path = Path(path)
    if path.is_file():
        path = path.parent
    if (path / "analysis").is_dir() and not (path / "summary.json").is_file():
        path = path / "analysis"
    return path


def _read_json(path: Path, what: str) -> dict:
    if not path.is_file():
        raise TidalcrustError(f"{path}: missing ({what})")
    try:
        return json.loads(path.read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as err:
        raise TidalcrustError(f"{path}: not a readable JSON file ({err})") from None


def read_figure_data(path: str | os.PathLike) -> dict:
    """analysis/figure_data.json (what the encounter figures draw, written by `analyze`) as a dict.
    Raises TidalcrustError naming the file."""
    file = _analysis_folder(path) / "figure_data.json"
    data = _read_json(file, "written by `tidalcrust analyze`")
    if data.get("format") != FIGURE_DATA_FORMAT or data.get("version") != FIGURE_DATA_VERSION:
        raise TidalcrustError(f"{file}: not {FIGURE_DATA_FORMAT} version {FIGURE_DATA_VERSION}")
    return data


def _summary(path) -> dict:
    return _read_json(_analysis_folder(path) / "summary.json", "written by `tidalcrust analyze`")


def _number(value, spec: str) -> str:
    """`value` formatted by `spec`, or "n/a" for an undefined one (null in the JSON files)."""
    return "n/a" if value is None or not np.isfinite(value) else format(value, spec)


def _title(fig, title) -> None:
    if title:
        # A line wider than the figure (about 11 characters per inch at this size) is wrapped, not clipped.
        width = max(40, int(11 * fig.get_figwidth()))
        title = "\n".join(textwrap.fill(line, width) for line in title.split("\n"))
        fig.suptitle(title, fontsize=10)
        # A moon's third title line (SI) and axes on top (t_grav, km): room above the subplots.
        lines = title.count("\n") + 1
        top_axis = any(child.get_gid() in ("t_grav_axis", "km_axis") for ax in fig.axes for child in ax.child_axes)
        if lines >= 3 or top_axis:
            needed = (0.19 * lines + (0.4 if top_axis else 0.0) + 0.12) / fig.get_figheight()
            if fig.subplotpars.top > 1 - needed:
                fig.subplots_adjust(top=1 - needed)


def map_frame(path) -> dict:
    """How the maps of an analysis folder show the surface (figure_data.json's `map`): `frame`
    ("orbital", or "planetocentric" for a [moon] workflow), `longitude_shift_deg` (added to the
    orbital-frame longitudes of cracks.json and summary.json), `subsatellite` ([lon, lat] on the
    map), `scale_bar` (length_km, length_R, label; None without a moon) and `note`. The orbital
    frame when there is no figure_data.json or it has no `map`."""
    file = _analysis_folder(path) / "figure_data.json"
    return read_figure_data(path).get("map", ORBITAL_MAP) if file.is_file() else ORBITAL_MAP


def _time_axis(data: dict) -> tuple[float, str]:
    """(hours or t_grav per t_grav, axis label) of figure_data.json's `time_axis`."""
    axis = data.get("time_axis") or {"per_t_grav": 1.0, "label": TIME_LABEL}
    return float(axis["per_t_grav"]), axis["label"]


def _time_in_axis_units(ax, data: dict, times, label: bool = True):
    """`times` (t_grav from pericenter) in the unit of the time axis; labels the axis (unless
    `label` is False), and of a moon adds the t_grav axis on top."""
    scale, text = _time_axis(data)
    if label:
        ax.set_xlabel(text)
    if scale != 1.0:
        top = ax.secondary_xaxis("top", functions=(lambda x: x / scale, lambda x: x * scale))
        top.set_xlabel(data["time_axis"]["model_label"], fontsize=7)
        top.tick_params(labelsize=6)
        top.set_gid("t_grav_axis")
    return np.asarray(times, dtype=float) * scale


# ---- maps ---------------------------------------------------------------------------------------

def projection(view: str, subsatellite=SUBSATELLITE_LON_LAT) -> ccrs.Projection:
    """The cartopy projection of a map view: "mollweide" (global, equal-area, no polar
    stretching), "equirectangular" (longitude and latitude as x and y), "orthographic" (the
    hemisphere centred on the subsatellite point `subsatellite`, (lon, lat) in degrees of the map's
    frame: cracks.json's `subsatellite`, (90, 0) for the paper's orbit, shifted as map_frame(path)
    says) or "antipode" (the other one)."""
    if view == "mollweide":
        return ccrs.Mollweide(globe=UNIT_GLOBE)
    if view == "equirectangular":
        return ccrs.PlateCarree(globe=UNIT_GLOBE)
    if view == "orthographic":
        return ccrs.Orthographic(*subsatellite, globe=UNIT_GLOBE)
    if view == "antipode":
        return ccrs.Orthographic(subsatellite[0] - 180.0, -subsatellite[1], globe=UNIT_GLOBE)
    raise ValueError(f"view '{view}': one of {', '.join(VIEWS)}")


def _densify(line, step_deg: float = 2.0, shift_deg: float = 0.0) -> np.ndarray:
    """A polyline of (lon, lat) in degrees, its longitudes shifted by shift_deg, with great-circle
    points at most step_deg apart; longitudes in [-180, 180]."""
    lon, lat = np.radians(np.asarray(line, dtype=float) + [shift_deg, 0.0]).T
    xyz = np.stack([np.cos(lat) * np.cos(lon), np.cos(lat) * np.sin(lon), np.sin(lat)], axis=1)
    out = [xyz[:1]]
    for a, b in zip(xyz[:-1], xyz[1:]):
        n = max(1, int(np.ceil(np.degrees(np.arccos(np.clip(a @ b, -1.0, 1.0))) / step_deg)))
        f = (np.arange(1, n + 1) / n)[:, None]
        p = a + (b - a) * f
        out.append(p / np.linalg.norm(p, axis=1, keepdims=True))
    out = np.concatenate(out)
    return np.column_stack([np.degrees(np.arctan2(out[:, 1], out[:, 0])), np.degrees(np.arcsin(np.clip(out[:, 2], -1, 1)))])


def _project_lines(lines, proj: ccrs.Projection, shift_deg: float = 0.0) -> tuple[list[np.ndarray], list[int]]:
    """The projected pieces of polylines of (lon, lat) in degrees (longitudes shifted by shift_deg
    into the map's frame), and the index of the line each piece is of: densified along great
    circles, cut at the antimeridian (the seam of the global projections, centred on longitude 0)
    and where a line leaves the visible hemisphere of an orthographic view. One projection call for
    all points."""
    parts, owners = [], []
    for i, line in enumerate(lines):
        for part in _split_at_antimeridian([tuple(p) for p in _densify(line, shift_deg=shift_deg)]):
            parts.append(np.asarray(part, dtype=float))
            owners.append(i)
    if not parts:
        return [], []
    lonlat = np.concatenate(parts)
    xy = proj.transform_points(ccrs.Geodetic(globe=UNIT_GLOBE), lonlat[:, 0], lonlat[:, 1])[:, :2]
    visible = np.all(np.isfinite(xy), axis=1)
    if isinstance(proj, ccrs.Orthographic):  # points behind the limb
        lon0, lat0 = np.radians(proj.proj4_params["lon_0"]), np.radians(proj.proj4_params["lat_0"])
        lon, lat = np.radians(lonlat[:, 0]), np.radians(lonlat[:, 1])
        visible &= np.sin(lat0) * np.sin(lat) + np.cos(lat0) * np.cos(lat) * np.cos(lon - lon0) >= 0
    pieces, piece_owners, start = [], [], 0
    for part, owner in zip(parts, owners):
        end = start + len(part)
        run = None
        for i in range(start, end + 1):
            if i < end and visible[i]:
                run = i if run is None else run
            elif run is not None:
                if i - run >= 2:
                    pieces.append(xy[run:i])
                    piece_owners.append(owner)
                run = None
        start = end
    return pieces, piece_owners


def crack_collection(cracks: dict, proj: ccrs.Projection, color=CRACK_COLOR, linewidth: float = 1.0,
                     longitude_shift: float = 0.0) -> LineCollection:
    """The failed springs' dual-lattice bars of cracks.json (read_cracks) as one LineCollection in
    `proj`'s coordinates (add it to a GeoAxes of that projection), their longitudes shifted by
    `longitude_shift` (map_frame's longitude_shift_deg: -90 for planetocentric maps). Its attribute
    `springs` names the failed spring of every segment (a bar cut at the seam or the limb gives
    several)."""
    lines, springs = [], []
    for crack in cracks["cracks"]:
        for spring, line in zip(crack["springs"], crack["polylines"]):
            lines.append(line)
            springs.append(spring)
    segments, owners = _project_lines(lines, proj, longitude_shift)
    collection = LineCollection(segments, colors=color, linewidths=linewidth, capstyle="round", joinstyle="round",
                                gid="cracks", zorder=3)
    collection.springs = [springs[k] for k in owners]
    return collection


def _scale_bar(ax, proj: ccrs.Projection, bar: dict) -> None:
    """A bar of bar["length_R"] at the map's scale along the equator at its central longitude (true
    there), drawn in the lower left corner with its label."""
    lon0, step = proj.proj4_params.get("lon_0", 0.0), 1e-3  # degrees
    ends = proj.transform_points(ccrs.Geodetic(globe=UNIT_GLOBE), np.array([lon0 - step, lon0 + step]),
                                 np.zeros(2))[:, :2]
    length = float(np.hypot(*(ends[1] - ends[0]))) / np.radians(2 * step) * bar["length_R"]
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    x, y = x0 + 0.03 * (x1 - x0), y0 + 0.04 * (y1 - y0)
    ax.plot([x, x + length], [y, y], color="black", linewidth=2.5, solid_capstyle="butt", gid="scale_bar", zorder=6,
            clip_on=False)  # in the corner, outside the map's outline
    ax.text(x + length / 2, y + 0.015 * (y1 - y0), bar["label"], fontsize=7, ha="center", va="bottom", zorder=6,
            gid="scale_bar_label")


def _crust_field(ax, cracks: dict, data_crs, frame: dict = ORBITAL_MAP) -> None:
    """A crust that varies (cracks.json's `crust`, docs/crust.md) under the cracks: the thickness factor
    at the shell nodes (brown thin, green thick) and the strength factor at the springs (red weak,
    blue strong), each shaded symmetrically about 1 where it is not 1; nothing for a uniform crust."""
    for kind, cmap, size in (("thickness", "BrBG", 7), ("strength", "RdBu", 2)):
        field = cracks.get("crust", {}).get(kind, {})
        shown = [k for k, f in enumerate(field.get("factor", [])) if f != 1]  # a weak line: only the line
        if shown:
            factor = [field["factor"][k] for k in shown]
            half = max(abs(f - 1) for f in factor)
            ax.scatter([_in_map_frame(field["lon"][k], frame) for k in shown], [field["lat"][k] for k in shown],
                       c=factor, s=size, cmap=cmap, vmin=1 - half, vmax=1 + half, linewidths=0, transform=data_crs,
                       gid=f"crust_{kind}", zorder=1)


def _in_map_frame(lon: float, frame: dict) -> float:
    """A longitude of cracks.json (the body frame) in the map's frame, (-180, 180]."""
    return (lon + frame["longitude_shift_deg"] + 180.0) % 360.0 - 180.0


def _subsatellite(cracks: dict, frame: dict = ORBITAL_MAP) -> tuple[float, float]:
    """The encounter's subsatellite point (lon, lat) of a cracks.json ((90, 0) in files before it),
    in the map's frame (its longitude shifted by frame["longitude_shift_deg"])."""
    lon, lat = cracks.get("subsatellite", SUBSATELLITE_LON_LAT)
    return _in_map_frame(lon, frame), lat


def _map_axes(ax, view: str, cracks: dict, mosaic=None, mosaic_extent=(-180, 180, -90, 90), linewidth: float = 1.0,
              frame: dict = ORBITAL_MAP):
    proj = projection(view, _subsatellite(cracks, frame))
    data_crs = ccrs.PlateCarree(globe=UNIT_GLOBE)
    ax.set_global()
    if mosaic is not None:
        image = plt.imread(mosaic) if isinstance(mosaic, (str, os.PathLike)) else np.asarray(mosaic)
        ax.imshow(image, origin="upper", extent=mosaic_extent, transform=data_crs, zorder=0,
                  cmap="gray" if image.ndim == 2 else None)
    else:
        ax.set_facecolor(SURFACE_COLOR)
    if view == "equirectangular":
        ax.gridlines(crs=data_crs, draw_labels=True, linewidth=0.4, color="0.55", xlocs=range(-180, 181, 30),
                     ylocs=range(-90, 91, 30))
    else:  # the graticule every 30 deg as plain lines (cartopy's Gridliner is slow to draw)
        meridians = [[(lon, lat) for lat in (-89.999, 0.0, 89.999)] for lon in range(-180, 180, 30)]
        parallels = [[(lon, lat) for lon in range(-180, 181, 10)] for lat in (-60, -30, 0, 30, 60)]
        ax.add_collection(LineCollection(_project_lines(meridians + parallels, proj)[0], colors="0.55",
                                         linewidths=0.4, gid="graticule", zorder=1))
    if view == "mollweide":  # longitudes along the equator, latitudes along the central meridian
        for lon in range(-150, 151, 60):
            ax.text(lon, -1, f"{lon}\u00b0", fontsize=6, color="0.35", ha="center", va="top", transform=data_crs)
        for lat in (-60, -30, 30, 60):
            ax.text(2, lat, f"{lat}\u00b0", fontsize=6, color="0.35", ha="left", va="bottom", transform=data_crs)
    _crust_field(ax, cracks, data_crs, frame)
    earlier = cracks.get("earlier", {}).get("polylines", [])
    if earlier:  # an encounter of a history: the cracks it began with, under its own
        ax.add_collection(LineCollection(_project_lines(earlier, proj, frame["longitude_shift_deg"])[0],
                                         colors=EARLIER_CRACK_COLOR, linewidths=linewidth, capstyle="round",
                                         gid="earlier_cracks", zorder=2))
    ax.add_collection(crack_collection(cracks, proj, linewidth=linewidth, longitude_shift=frame["longitude_shift_deg"]))
    if frame.get("scale_bar"):
        _scale_bar(ax, proj, frame["scale_bar"])
    ax.plot(*_subsatellite(cracks, frame), marker="o", markersize=11, markerfacecolor="none", markeredgewidth=2,
            markeredgecolor=SUBSATELLITE_COLOR, transform=data_crs, gid="subsatellite", zorder=4)
    return ax


def fracture_map(path: str | os.PathLike, view: str = "overview", ax=None, mosaic=None,
                 mosaic_extent=(-180, 180, -90, 90), linewidth: float = 1.0, title: str | None = None):
    """The cracks of an encounter (its folder, analysis folder or cracks.json) on a map.

    view "overview" (analyze's fracture_map.png): a global Mollweide map with the orthographic
    hemispheres centred on the subsatellite point and on its antipode below it; or one map,
    "mollweide", "equirectangular", "orthographic" or "antipode", into `ax` (a cartopy GeoAxes of
    projection(view)) or a new figure. mosaic: an image (file or array) in the orbital frame's
    longitude and latitude, drawn under the cracks over `mosaic_extent` (lon0, lon1, lat0, lat1,
    degrees; in the map's frame: planetocentric for a [moon] workflow). The ring marks the
    subsatellite point; of a [moon] workflow each map has a km scale bar (true along the equator
    at the map's centre). Returns the Figure. Raises CracksError (no cracks.json), ValueError
    (view)."""
    cracks = read_cracks(path)
    frame = map_frame(path)
    if title is None:
        summary_file = _analysis_folder(path) / "figure_data.json"
        title = (read_figure_data(path)["titles"]["fracture_map"] if summary_file.is_file()
                 else f"{cracks['crack_count']} cracks")
    if view == "overview":
        fig = plt.figure(figsize=(9, 8.2))
        top = fig.add_axes([0.04, 0.42, 0.92, 0.46], projection=projection("mollweide"))
        _map_axes(top, "mollweide", cracks, mosaic, mosaic_extent, linewidth, frame)
        for k, (v, label) in enumerate((("orthographic", "hemisphere centred on the subsatellite point"),
                                        ("antipode", "hemisphere centred on its antipode"))):
            sub = fig.add_axes([0.06 + 0.48 * k, 0.04, 0.4, 0.34],
                               projection=projection(v, _subsatellite(cracks, frame)))
            _map_axes(sub, v, cracks, mosaic, mosaic_extent, linewidth, frame)
            sub.set_title(label, fontsize=8)
        history = "; grey: cracks of the earlier encounters" if cracks.get("earlier", {}).get("polylines") else ""
        crust = cracks.get("crust", {})
        history += "; dots: thickness, brown thin" if crust.get("thickness", {}).get("factor") else ""
        history += "; dots: strength, red weak" if crust.get("strength", {}).get("factor") else ""
        fig.text(0.5, 0.01, frame["note"] + history, ha="center", fontsize=7, wrap=True, gid="note")
        _title(fig, title)
        return fig
    proj = projection(view, _subsatellite(cracks, frame))
    if ax is None:
        fig = plt.figure(figsize=(9, 5) if view in ("equirectangular", "mollweide") else (5.5, 5.5))
        ax = fig.add_subplot(1, 1, 1, projection=proj)
    _map_axes(ax, view, cracks, mosaic, mosaic_extent, linewidth, frame)
    ax.set_title(title, fontsize=9)
    return ax.figure


def crack_geometry(path: str | os.PathLike, axes=None, title: str | None = None):
    """The crack geometry (docs/crack-geometry.md): left, the cracks on a Mollweide map with the
    small circles fitted to the long cracks (the arc each covers thick, the rest of its circle
    dashed) and their poles as numbered dots; right, the rose of crack azimuths about the
    subsatellite point (0 up, counter-clockwise as seen from outside; equal-area petals; dashed:
    the uniform level) and the fitted arcs in words. axes: (GeoAxes of projection("mollweide"),
    polar Axes). Returns the Figure."""
    summary, data, cracks = _summary(path), read_figure_data(path), read_cracks(path)
    geometry = summary["crack_geometry"]
    frame = data.get("map", ORBITAL_MAP)
    shift = frame["longitude_shift_deg"]
    if axes is None:
        fig = plt.figure(figsize=(12, 6.2))
        map_ax = fig.add_axes([0.02, 0.2, 0.6, 0.66], projection=projection("mollweide"))
        rose_ax = fig.add_axes([0.68, 0.42, 0.28, 0.42], projection="polar")
    else:
        map_ax, rose_ax = axes
        fig = map_ax.figure
    _map_axes(map_ax, "mollweide", cracks, frame=frame)
    proj = projection("mollweide")
    circles = data["crack_geometry"]["circles"]
    covered = _project_lines([c["covered"] for c in circles], proj, shift)[0]
    rest = _project_lines([c["rest"] for c in circles], proj, shift)[0]
    map_ax.add_collection(LineCollection(rest, colors=ARC_COLOR, linewidths=0.8, linestyles=(0, (4, 3)), alpha=0.7,
                                         gid="circles", zorder=5))
    map_ax.add_collection(LineCollection(covered, colors=ARC_COLOR, linewidths=2.4, alpha=0.85, gid="arcs",
                                         zorder=5))
    data_crs = ccrs.PlateCarree(globe=UNIT_GLOBE)
    arcs = geometry["arcs"]
    if arcs:
        pole_lon = [(a["pole_longitude_deg"] + shift + 180.0) % 360.0 - 180.0 for a in arcs]
        map_ax.scatter(pole_lon, [a["pole_latitude_deg"] for a in arcs], s=30,
                       color=ARC_COLOR, edgecolors="white", transform=data_crs, gid="poles", zorder=6)
        for k, a in enumerate(arcs):
            map_ax.text(pole_lon[k], a["pole_latitude_deg"], f" {k + 1}", fontsize=7,
                        color=ARC_COLOR, transform=data_crs, zorder=6)

    rose = geometry["rose"]
    counts = np.asarray(rose["histogram"], dtype=float)
    width = np.radians(rose["bin_width_deg"])
    centres = np.radians(np.asarray(rose["bin_centres_deg"], dtype=float))
    peak = counts.max() if counts.size and counts.max() > 0 else 1.0
    radius = np.sqrt(counts / peak)  # equal-area petals
    rose_ax.set_theta_zero_location("N")
    rose_ax.set_theta_direction(1)  # counter-clockwise, as on the sphere seen from outside
    theta = np.concatenate([centres, centres + np.pi])  # axial: each bin at a and a + 180 deg
    rose_ax.bar(theta, np.concatenate([radius, radius]), width=width, color=ARC_COLOR, alpha=0.75,
                edgecolor="white", gid="rose")
    if rose["elements"]:
        uniform = np.sqrt(rose["elements"] / counts.size / peak)
        rose_ax.plot(np.linspace(0, 2 * np.pi, 181), np.full(181, uniform), "k--", linewidth=0.8, gid="uniform")
    rose_ax.set_yticklabels([])
    rose_ax.set_title("crack azimuth from the direction to the subsatellite point", fontsize=8)
    concentricity = geometry.get("concentricity")
    lines = [f"concentricity {_number(concentricity, '.2f')} (1: rings about the subsatellite point; 0.64: random)"]
    si_arcs = summary["si"]["crack_geometry"]["arcs"] if "si" in summary else [None] * len(arcs)
    for k, (a, si) in enumerate(zip(arcs, si_arcs)):
        pole_lon = a["pole_longitude_deg"] if si is None else si["pole_planetocentric_longitude_deg"]
        km = "" if si is None else (f" = {_number(si['radius_km'], '.0f')} km, arc "
                                    f"{_number(si['arc_length_km'], '.0f')} km long")
        lines.append(f"{k + 1}: pole ({_number(pole_lon, '.0f')}\u00b0, "
                     f"{_number(a['pole_latitude_deg'], '.0f')}\u00b0), "
                     f"{_number(a['pole_axis_from_subsatellite_deg'], '.0f')}\u00b0 from the subsatellite axis, radius "
                     f"{_number(a['radius_deg'], '.0f')}\u00b0{km}, arc {_number(a['arc_deg'], '.0f')}\u00b0, misfit "
                     f"{_number(a['rms_misfit_deg'], '.1f')}\u00b0")
    if axes is None:
        fig.text(0.66, 0.36, "\n".join(lines), fontsize=7, va="top")
    _title(fig, title if title is not None else data["titles"]["crack_geometry"])
    return fig


# ---- the body ---------------------------------------------------------------------------------

def _panel_axes(count: int, axes, size: float = 2.6):
    if axes is not None:
        return axes[0].figure, list(axes)
    fig, axes = plt.subplots(1, max(1, count), figsize=(size * max(1, count) + 0.4, size + 1.4), squeeze=False)
    return fig, list(axes[0])


def hemisphere(path: str | os.PathLike, axes=None, title: str | None = None):
    """Figure 6: one panel per snapshot, an orthographic view of the hemisphere facing the
    subsatellite point (viewer on +y in the orbital plane, +z up, +x to the left): Lambert-shaded
    shell triangles, the crack bars in view, the perturber as a translucent magenta disc of radius
    M2^(1/3) R (hidden behind the body, under the cracks in front of it). Returns the Figure."""
    data = read_figure_data(path)
    h = data["hemisphere"]
    faces = np.asarray(h["faces"], dtype=int)
    light = np.array([0.35, 0.85, 0.40]) / np.linalg.norm([0.35, 0.85, 0.40])
    ice = np.array([0.93, 0.91, 0.86])
    fig, axes = _panel_axes(len(h["panels"]), axes)
    for ax, panel in zip(axes, h["panels"]):
        p = np.asarray(panel["positions"], dtype=float)
        a, b, c = p[faces[:, 0]], p[faces[:, 1]], p[faces[:, 2]]
        normal = np.cross(b - a, c - a)
        normal /= np.linalg.norm(normal, axis=1, keepdims=True)
        visible = normal[:, 1] > 0
        order = np.flatnonzero(visible)[np.argsort((a + b + c)[visible, 1], kind="stable")]
        brightness = 0.2 + 0.8 * np.maximum(0.0, normal[order] @ light)
        screen = np.stack([-p[:, 0], p[:, 2]], axis=1)
        ax.set_facecolor("#0a0a12")
        ax.add_collection(PolyCollection(screen[faces[order]], facecolors=ice * brightness[:, None],
                                         edgecolors=ice * brightness[:, None], linewidths=0.3, gid="faces", zorder=2))
        bars = [bar for bar in panel["crack_bars"] if visible[bar["face"]]]
        ax.add_collection(LineCollection([[(-bar["from"][0], bar["from"][2]), (-bar["to"][0], bar["to"][2])]
                                          for bar in bars], colors=CRACK_COLOR, linewidths=1.1, capstyle="round",
                                         gid="cracks", zorder=4))
        if panel["perturber"] is not None:
            x, y, z = panel["perturber"]["position"]
            front = y >= 0
            r = panel["perturber"]["radius"]
            ax.add_patch(Circle((-x, z), r, facecolor=PERTURBER_COLOR, alpha=0.28, zorder=3 if front else 1,
                                gid="perturber"))
            ax.add_patch(Circle((-x, z), r, facecolor="none", edgecolor=PERTURBER_COLOR, alpha=0.75,
                                zorder=5 if front else 1))
        ax.set_xlim(-1.45, 1.45)
        ax.set_ylim(-1.45, 1.45)
        ax.set_aspect("equal")
        ax.set_xticks([])
        ax.set_yticks([])
        ax.set_title(panel["label"], fontsize=8)
        ax.text(0.04, 0.04, f"{panel['failed']} failed", color="white", fontsize=7, transform=ax.transAxes)
    fig.text(0.5, 0.02, "orthographic; viewer on +y in the orbital plane, facing the subsatellite point; +z up, "
             "+x left; magenta: perturber, radius M\u2082^(1/3) R", ha="center", fontsize=7)
    _title(fig, title if title is not None else data["titles"]["hemisphere"])
    return fig


def body_shape(path: str | os.PathLike, axes=None, title: str | None = None):
    """Figure 5: one panel per snapshot, the body seen from +z: its outline (convex hull, grey),
    the springs within the slice about the orbital plane (pink) and their particles, the
    perturber's direction as a magenta arrow at the rim; labelled with b/a and c/a. Returns the
    Figure."""
    data = read_figure_data(path)
    shape = data["body_shape"]
    fig, axes = _panel_axes(len(shape["panels"]), axes)
    for ax, panel in zip(axes, shape["panels"]):
        hull = np.asarray(panel["hull"], dtype=float)
        if len(hull) >= 3:
            ax.add_patch(Polygon(hull, closed=True, facecolor="0.55", alpha=0.15, edgecolor="0.55", linewidth=1.2,
                                 gid="outline"))
        ax.add_collection(LineCollection(panel["springs"], colors="#ed739e", linewidths=0.7, gid="springs"))
        particles = np.asarray(panel["particles"], dtype=float).reshape(-1, 2)
        ax.plot(particles[:, 0], particles[:, 1], ".", color="#1a1a2e", markersize=2.5, gid="particles")
        if panel["perturber_direction"] is not None:
            ux, uy = panel["perturber_direction"]
            ax.add_patch(FancyArrow(1.15 * ux, 1.15 * uy, 0.3 * ux, 0.3 * uy, width=0.03, color=PERTURBER_COLOR,
                                    length_includes_head=True, gid="perturber"))
        ax.set_xlim(-1.5, 1.5)
        ax.set_ylim(-1.5, 1.5)
        ax.set_aspect("equal")
        ax.set_xlabel("x [R]", fontsize=7)
        ax.tick_params(labelsize=6)
        ax.set_title(panel["label"], fontsize=8)
        ax.text(0.04, 0.04, f"b/a = {_number(panel['b_over_a'], '.3f')}, c/a = {_number(panel['c_over_a'], '.3f')}",
                fontsize=7,
                transform=ax.transAxes)
    axes[0].set_ylabel("y [R]", fontsize=7)
    fig.text(0.5, 0.01, f"seen from +z; springs and particles within {shape['slice_half_width']} R of the orbital "
             "plane; grey: outline of the whole body", ha="center", fontsize=7)
    _title(fig, title if title is not None else data["titles"]["body_shape"])
    return fig


def axis_ratios(path: str | os.PathLike, ax=None, title: str | None = None):
    """Principal axis ratios b/a (solid) and c/a (dashed) against t - t_peri, one marker per
    checkpoint (summary.json's principal_axis_ratios). Returns the Figure."""
    ratios = _summary(path)["principal_axis_ratios"]
    data = read_figure_data(path)
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4))
    t = _time_in_axis_units(ax, data, [r["time_from_pericenter"] for r in ratios])
    ax.plot(t, [r["b_over_a"] for r in ratios], "o-", color="black", label="b/a", gid="b_over_a")
    ax.plot(t, [r["c_over_a"] for r in ratios], "s--", color="black", label="c/a", gid="c_over_a")
    ax.axvline(0.0, color="0.45", linestyle="--", linewidth=0.8)
    ax.set_ylabel("axis ratio")
    ax.legend(fontsize=8)
    _title(ax.figure, title if title is not None else data["titles"]["axis_ratios"])
    return ax.figure


# ---- time series ------------------------------------------------------------------------------

def orbit(path: str | os.PathLike, ax=None, title: str | None = None):
    """Figure 7: the perturber's track relative to the body's centre of mass in the orbital plane
    (simulated, with the analytic two-body track thin grey dashed), the body as a black disc of
    radius R, red diamonds every tick_every t_grav, open circles of radius M2^(1/3) R at the
    snapshots, a red arrow for the direction of motion at the closest approach and the stored
    position (blue cross). Returns the Figure."""
    data = read_figure_data(path)
    o = data["orbit"]
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 7))
    ax.add_patch(Circle((0, 0), 1.0, color="black", gid="body"))
    track = np.asarray(o["track"], dtype=float)
    if o["simulated"]:
        analytic = np.asarray(o["analytic_track"], dtype=float)
        ax.plot(analytic[:, 0], analytic[:, 1], color="0.55", linewidth=0.8, linestyle=(0, (4, 3)),
                label="two-body track (analytic)", gid="analytic_track")
    ax.plot(track[:, 0], track[:, 1], color="black", linewidth=1.0, gid="track",
            label=f"simulated (max {_number(o['max_deviation'], '.3f')} R from analytic)" if o["simulated"]
            else "two-body track (analytic; q, V_q, M\u2082)")
    ticks = np.asarray(o["ticks"], dtype=float).reshape(-1, 2)
    ax.plot(ticks[:, 0], ticks[:, 1], "D", color=TICK_COLOR, markersize=4, linestyle="none", gid="ticks",
            label=f"every {o['tick_every']:g} t_grav from the stage start")
    for k, (x, y) in enumerate(o["snapshots"]):
        ax.add_patch(Circle((x, y), o["snapshot_radius"], fill=False, edgecolor="black", linewidth=0.9,
                            gid="snapshot", label="snapshots (radius M\u2082^(1/3) R)" if k == 0 else None))
    p, d = np.asarray(o["pericenter"]), np.asarray(o["direction"])
    start = p + 0.3 * p / max(np.linalg.norm(p), 1e-12) - 0.35 * d
    ax.add_patch(FancyArrow(*start, *(0.7 * d), width=0.02, head_width=0.09, color=TICK_COLOR,
                            length_includes_head=True, gid="direction"))
    if o["stored_position"] is not None:
        ax.plot(*o["stored_position"], "x", color="#004de6", markersize=8, markeredgewidth=1.4, linestyle="none",
                gid="stored", label=o["stored_label"])
    ax.set_aspect("equal")
    ax.autoscale_view()
    ax.set_xlabel("x [R]")
    ax.set_ylabel("y [R]")
    if data.get("length_axis"):  # of a moon: km beside R
        per_r, unit = data["length_axis"]["per_R"], data["length_axis"]["unit"]
        top = ax.secondary_xaxis("top", functions=(lambda x: x * per_r, lambda x: x / per_r))
        top.set_xlabel(f"x [{unit}]", fontsize=7)
        top.set_gid("km_axis")
        right = ax.secondary_yaxis("right", functions=(lambda y: y * per_r, lambda y: y / per_r))
        right.set_ylabel(f"y [{unit}]", fontsize=7)
        for secondary in (top, right):
            secondary.tick_params(labelsize=7)
    ax.legend(fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.13), ncol=2)
    ax.text(0.0, -0.36, "relative to the body's centre of mass (black disc, radius R); pericenter on +y",
            transform=ax.transAxes, fontsize=7)
    _title(ax.figure, title if title is not None else data["titles"]["orbit"])
    ax.figure.subplots_adjust(bottom=0.28)
    return ax.figure


def failures(path: str | os.PathLike, ax=None, title: str | None = None):
    """Failed shell springs against t - t_peri: the cumulative failure events as a step function
    (the sampled counts of a record without events). Returns the Figure."""
    data = read_figure_data(path)
    f = data["failures"]
    if ax is None:
        _, ax = plt.subplots(figsize=(6.4, 4))
    ax.plot(_time_in_axis_units(ax, data, f["time_from_pericenter"]), f["failed"], color="black", linewidth=1.4,
            gid="failures")
    ax.axvline(0.0, color="0.45", linestyle="--", linewidth=0.8, label="pericenter")
    ax.set_ylabel("failed shell springs")
    ax.set_ylim(0, 1.08 * max(1.0, max(f["failed"], default=0)))
    ax.figure.text(0.02, 0.015, f["note"], fontsize=7)
    _title(ax.figure, title if title is not None else data["titles"]["failures"])
    ax.figure.subplots_adjust(bottom=0.2)
    return ax.figure


def conservation(path: str | os.PathLike, axes=None, title: str | None = None):
    """Conservation diagnostics against t - t_peri: the energy budget's conserved total relative
    to the binding energy 3/5 G M^2/R (docs/energy-budget.md), |P - P0| and |L - L0| (body +
    perturber about the origin). axes: three Axes. Returns the Figure."""
    data = read_figure_data(path)
    c = data["conservation"]
    if axes is None:
        _, axes = plt.subplots(3, 1, figsize=(6.4, 7), sharex=True)
    t = _time_in_axis_units(axes[0], data, c["time_from_pericenter"], label=False)
    for ax, key, label in zip(axes, ("energy", "momentum", "angular_momentum"),
                              (c["energy_label"], "|P \u2212 P\u2080| [M \u221a(GM/R)]",
                               "|L \u2212 L\u2080| [M R \u221a(GM/R)]")):
        ax.plot(t, c[key], color="black", linewidth=1.2, gid=key)
        ax.axvline(0.0, color="0.45", linestyle="--", linewidth=0.8)
        ax.set_ylabel(label, fontsize=8)
    axes[-1].set_xlabel(_time_axis(data)[1])
    axes[-1].text(0.0, -0.45, c["note"], transform=axes[-1].transAxes, fontsize=7)
    _title(axes[0].figure, title if title is not None else data["titles"]["conservation"])
    return axes[0].figure


#: The function that draws each figure of analyze, by the name figure_data.json lists it under.
ANALYSIS_FIGURES = {"fracture_map": fracture_map, "hemisphere": hemisphere, "orbit": orbit, "failures": failures,
                    "conservation": conservation, "body_shape": body_shape, "axis_ratios": axis_ratios,
                    "crack_geometry": crack_geometry}


# ---- files ------------------------------------------------------------------------------------

def save(fig, stem: str | os.PathLike) -> list[Path]:
    """Writes `fig` as stem.png and stem.svg (deterministic: fixed SVG ids, no dates) and closes
    it. Returns the two paths."""
    stem = Path(stem)
    with matplotlib.rc_context({"svg.hashsalt": "tidalcrust", "svg.fonttype": "path"}):
        # Not with_suffix: a stem may hold dots (phase_M0.5_eps0.002).
        png, svg = stem.parent / f"{stem.name}.png", stem.parent / f"{stem.name}.svg"
        fig.savefig(png, dpi=110, metadata={"Software": None})
        fig.savefig(svg, metadata={"Date": None})
    plt.close(fig)
    return [png, svg]


def draw_analysis(folder: str | os.PathLike, mosaic=None) -> list[Path]:
    """Every figure of an analysis folder (the names figure_data.json lists), each as PNG and SVG
    into the folder; what `analyze` runs. Returns the files written."""
    folder = _analysis_folder(folder)
    data = read_figure_data(folder)
    written = []
    for name in data["figures"]:
        if name not in ANALYSIS_FIGURES:
            raise TidalcrustError(f"{folder / 'figure_data.json'}: unknown figure '{name}'")
        fig = ANALYSIS_FIGURES[name](folder, mosaic=mosaic) if name == "fracture_map" else ANALYSIS_FIGURES[name](folder)
        written += save(fig, folder / name)
    return written
