"""Crack polylines as GIS products: GeoDataFrame, GeoJSON, shapefile (docs/python.md).

The cracks are defined once, by the C++ analysis (`tidalcrust analyze`: failed shell springs
joined through shared faces, drawn as dual-lattice bars; docs/crack-geometry.md), which writes
them to `analysis/cracks.json`. This module only reads that file; it never re-derives a crack.
"""
from __future__ import annotations

import json
import os
import warnings
from pathlib import Path

import numpy as np
import pyproj
from pyproj.database import query_crs_info
from shapely.geometry import MultiLineString

from .checkpoint import TidalcrustError

CRACKS_FORMAT = "tidalcrust-cracks"
CRACKS_VERSION = 1

#: The CRS of a body without a name: a sphere of radius 1 (R = 1, the model's unit), planetocentric
#: longitude and latitude in degrees.
UNIT_SPHERE_CRS = pyproj.CRS.from_proj4("+proj=longlat +R=1 +no_defs +type=crs")


class CracksError(TidalcrustError):
    """A missing, unreadable or foreign cracks.json; the message names the file."""


def cracks_file(path: str | os.PathLike) -> Path:
    """cracks.json for `path`: the file itself, an analysis folder, or an encounter folder (its
    `analysis/`). Raises CracksError naming the path when there is none."""
    path = Path(path)
    for candidate in (path, path / "cracks.json", path / "analysis" / "cracks.json"):
        if candidate.is_file():
            return candidate
    raise CracksError(f"{path}: no cracks.json (written by `tidalcrust analyze` since issue 27; "
                      f"rerun `tidalcrust run` or `analyze` to add it)")


def read_cracks(path: str | os.PathLike) -> dict:
    """cracks.json as written by `analyze` (docs/python.md lists its keys): crack_count, cracks
    (each: crack, springs, length and extent in R, polylines of [lon, lat] in degrees of the maps'
    orbital frame), frame, units, state_hash. Raises CracksError naming the file."""
    file = cracks_file(path)
    try:
        data = json.loads(file.read_text())
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as err:
        raise CracksError(f"{file}: not a readable JSON file ({err})") from None
    if not isinstance(data, dict) or data.get("format") != CRACKS_FORMAT:
        raise CracksError(f"{file}: not a tidalcrust cracks.json (no \"format\": \"{CRACKS_FORMAT}\")")
    if data.get("version") != CRACKS_VERSION:
        raise CracksError(f"{file}: cracks.json version {data.get('version')}; this package reads {CRACKS_VERSION}")
    if len(data.get("cracks", [])) != data.get("crack_count"):
        raise CracksError(f"{file}: crack_count {data.get('crack_count')} but {len(data.get('cracks', []))} cracks")
    return data


def body_crs(body: str | None = None) -> pyproj.CRS:
    """The planetocentric CRS of a named body: IAU_2015 "<body> (2015) - Sphere / Ocentric"
    (Tethys: IAU_2015:60300), from PROJ's database; without a body, UNIT_SPHERE_CRS (radius 1).

    The longitudes are those of the maps' orbital frame (subsatellite point at +90), not the
    body's IAU prime meridian: the CRS gives the body's sphere and the planetocentric convention,
    not its rotation (the simulation has none). Raises CracksError for a body PROJ does not know.
    """
    if body is None:
        return UNIT_SPHERE_CRS
    name = f"{body.strip().capitalize()} (2015) - Sphere / Ocentric"
    for info in query_crs_info(auth_name="IAU_2015"):
        if info.name == name:
            return pyproj.CRS.from_user_input(f"IAU_2015:{info.code}")
    raise CracksError(f"body '{body}': PROJ {pyproj.proj_version_str} has no IAU_2015 CRS named '{name}'")


def _split_at_antimeridian(line: list) -> list[list[tuple[float, float]]]:
    """A polyline of (lon, lat) cut where it crosses longitude +-180 (RFC 7946, 3.1.9); the
    crossing latitude is interpolated linearly in longitude (a bar spans about one lattice cell)."""
    pieces = [[tuple(line[0])]]
    for (lon0, lat0), (lon1, lat1) in zip(line[:-1], line[1:]):
        if abs(lon1 - lon0) > 180:
            edge = 180.0 if lon0 > 0 else -180.0
            lon1_unwrapped = lon1 + (360.0 if lon0 > 0 else -360.0)
            f = (edge - lon0) / (lon1_unwrapped - lon0)
            lat = lat0 + f * (lat1 - lat0)
            pieces[-1].append((edge, lat))
            pieces.append([(-edge, lat)])
        pieces[-1].append((lon1, lat1))
    return [p for p in pieces if len(p) >= 2]


def cracks_frame(path: str | os.PathLike, body: str | None = None) -> gpd.GeoDataFrame:
    """One row per crack of cracks.json (`path`: as cracks_file), longest first.

    Columns: crack (index in summary.json's clusters), springs (failed springs in it), length and
    extent (R; length: dual-lattice length, extent: largest great-circle distance between its face
    centroids), length_km and extent_km with a named body (its IAU sphere radius), geometry (a
    MultiLineString: one line per failed spring, its dual-lattice bar, cut at the antimeridian).
    CRS: body_crs(body). Raises CracksError.
    """
    data = read_cracks(path)
    crs = body_crs(body)
    rows = []
    for crack in data["cracks"]:
        lines = [piece for line in crack["polylines"] for piece in _split_at_antimeridian(line)]
        rows.append({"crack": int(crack["crack"]), "springs": len(crack["springs"]),
                     "length": float(crack["length"]), "extent": float(crack["extent"]),
                     "geometry": MultiLineString(lines)})
    import geopandas as gpd  # here, not at the top: the figure script does not need it (and it is slow to import)

    frame = gpd.GeoDataFrame(rows, columns=["crack", "springs", "length", "extent", "geometry"],
                             geometry="geometry", crs=crs)
    if body is not None:
        radius_km = crs.ellipsoid.semi_major_metre / 1000.0
        frame.insert(4, "length_km", frame["length"] * radius_km)
        frame.insert(5, "extent_km", frame["extent"] * radius_km)
    return frame


def _crs_member(crs: pyproj.CRS) -> dict:
    """The GeoJSON (2008) "crs" member GDAL and GeoPandas read back: an authority's URN, or for a
    CRS without one (the unit sphere) its PROJ string, which GDAL also accepts as a name."""
    authority = crs.to_authority()
    if authority:
        name = f"urn:ogc:def:crs:{authority[0]}::{authority[1]}"
    else:
        with warnings.catch_warnings():  # a longlat sphere loses nothing in a PROJ string
            warnings.simplefilter("ignore", UserWarning)
            name = crs.to_proj4()
    return {"type": "name", "properties": {"name": name}}


def write_geojson(path: str | os.PathLike, out: str | os.PathLike, body: str | None = None) -> Path:
    """The cracks of `path` as a GeoJSON FeatureCollection `out`: one Feature per crack with
    cracks_frame's columns as properties, and a "crs" member naming body_crs(body) (RFC 7946
    GeoJSON is WGS 84 only; GeoPandas/GDAL read this member back, so the file opens with the
    body's sphere). Returns `out`."""
    frame = cracks_frame(path, body)
    collection = json.loads(frame.to_json(drop_id=True))
    collection = {"type": "FeatureCollection", "crs": _crs_member(frame.crs), "features": collection["features"]}
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    out.write_text(json.dumps(collection) + "\n")
    return out


def write_shapefile(path: str | os.PathLike, out: str | os.PathLike, body: str | None = None) -> Path:
    """The cracks of `path` as an ESRI shapefile `out` (.shp with .shx, .dbf, .prj holding the
    CRS's WKT; the folder is created). Returns `out`."""
    out = Path(out)
    out.parent.mkdir(parents=True, exist_ok=True)
    cracks_frame(path, body).to_file(out, driver="ESRI Shapefile")
    return out


def vertices(path: str | os.PathLike) -> tuple[np.ndarray, np.ndarray]:
    """Every polyline of cracks.json as (lon, lat) arrays with NaN between lines (for plotting)."""
    lon, lat = [], []
    for crack in read_cracks(path)["cracks"]:
        for line in crack["polylines"]:
            for piece in _split_at_antimeridian(line):
                lon.extend(p[0] for p in piece)
                lat.extend(p[1] for p in piece)
                lon.append(np.nan)
                lat.append(np.nan)
    return np.array(lon), np.array(lat)
