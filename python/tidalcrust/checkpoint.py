"""Checkpoints of tidalcrust as xarray Datasets (docs/python.md, docs/checkpoint-layout.md).

Every quantity is in the model's units, G = M = R = 1: lengths in R (the body's radius), masses
in M (its mass), times in t_grav = sqrt(R^3/(G M)), velocities in sqrt(G M/R), energies in
G M^2/R. The H5MD unit strings of the files say what R, t_grav and M are (docs/checkpoint-layout.md,
"Units in the file"): of a workflow with a [moon] the moon's own ("531000.0 m", ...), else the
stand-ins "nm", "ps", "14983000 kg"; the numbers are read unchanged, never scaled.
"""
from __future__ import annotations

import os
import re
from pathlib import Path

import h5py
import numpy as np

UNITS_NOTE = ("model units G = M = R = 1: lengths in R (the body's radius), masses in M, times in "
              "t_grav = sqrt(R^3/(G M)), velocities in sqrt(G M/R), energies in G M^2/R; the file's H5MD "
              "unit strings say what R, t_grav and M are (a [moon]'s own, else nm, ps, 14983000 kg) and are "
              "not converted")

READABLE_FORMATS = (4, 5, 6, 7, 8, 9)

# Units of the timeseries columns (docs/checkpoint-layout.md).
_TIMESERIES_UNITS = {
    "time": "t_grav", "failed": "1", "kinetic_energy": "G M^2/R", "internal_kinetic_energy": "G M^2/R",
    "spring_energy": "G M^2/R", "hinge_energy": "G M^2/R", "self_gravity_energy": "G M^2/R",
    "perturber_energy": "G M^2/R", "damping_dissipated": "G M^2/R", "failure_released": "G M^2/R",
    "hinge_residual_work": "G M^2/R", "momentum": "M sqrt(G M/R)", "angular_momentum": "M R sqrt(G M/R)",
    "perturber_offset": "R",
}


class TidalcrustError(ValueError):
    """Bad input to the package (a file or folder it cannot read); the message names it."""


class CheckpointError(TidalcrustError):
    """A file or folder that is not a readable tidalcrust checkpoint; the message names it."""


def _text(value) -> str:
    if isinstance(value, bytes):
        return value.decode("utf-8", "replace")
    if isinstance(value, np.ndarray) and value.shape == ():
        return _text(value[()])
    return str(value)


def _snapshot_step(path: Path) -> int | None:
    match = re.fullmatch(r".*\.snap-(\d+)\.h5", path.name)
    return int(match.group(1)) if match else None


def checkpoint_files(path: str | os.PathLike) -> list[Path]:
    """The checkpoint files `open` reads for `path`, in ascending step.

    A file: itself. A folder: its `encounter.h5` and the snapshots `encounter.snap-<step>.h5`
    beside it (open() keeps those before encounter.h5's step) (for another folder, its single `*.h5` without `.mid.`/`.diagnostic.`).
    Raises CheckpointError naming the path if it does not exist or holds no checkpoint.
    """
    path = Path(path)
    if not path.exists():
        raise CheckpointError(f"{path}: no such checkpoint file or encounter folder")
    if path.is_file():
        return [path]
    if not path.is_dir():
        raise CheckpointError(f"{path}: not a regular file or folder")
    final = path / "encounter.h5"
    if not final.is_file():
        candidates = [p for p in sorted(path.glob("*.h5"))
                      if _snapshot_step(p) is None and ".mid." not in p.name and ".diagnostic" not in p.name]
        if len(candidates) != 1:
            raise CheckpointError(f"{path}: no encounter.h5 (an encounter folder holds encounter.h5 and its "
                                  f"snapshots; found {len(candidates)} other checkpoint files)")
        final = candidates[0]
    snapshots = sorted((p for p in path.glob(final.stem + ".snap-*.h5") if _snapshot_step(p) is not None),
                       key=_snapshot_step)
    return snapshots + [final]


def _drop_late_snapshots(parts: list[dict]) -> list[dict]:
    """The snapshots before the last file's step (the one at the end step is the final state
    again), as `analyze` uses them."""
    return [p for p in parts[:-1] if p["step"] < parts[-1]["step"]] + parts[-1:]


def _open_h5(path: Path) -> h5py.File:
    try:
        handle = h5py.File(path, "r", locking=False)
    except OSError as err:
        raise CheckpointError(f"{path}: not an HDF5 file or unreadable ({err})") from None
    if "checkpoint" not in handle or "format_version" not in handle["checkpoint"].attrs:
        handle.close()
        raise CheckpointError(f"{path}: not a tidalcrust checkpoint (no /checkpoint@format_version)")
    version = int(handle["checkpoint"].attrs["format_version"])
    if version not in READABLE_FORMATS:
        handle.close()
        raise CheckpointError(f"{path}: checkpoint format {version}; this package reads formats "
                              f"{', '.join(map(str, READABLE_FORMATS))} "
                              f"(`tidalcrust inspect` reads older ones)")
    return handle


def _required(handle: h5py.File, path: Path, name: str) -> np.ndarray:
    if name not in handle:
        raise CheckpointError(f"{path}: dataset {name} is missing (damaged or not written by tidalcrust)")
    return handle[name][()]


def _read_one(path: Path) -> dict:
    with _open_h5(path) as h:
        c = h["checkpoint"]
        one = {
            "path": path,
            "stage": _text(c.attrs.get("stage", "")),
            "complete": bool(c.attrs.get("complete", 0)),
            "time": float(c.attrs["time"]),
            "step": int(c.attrs["step"]),
            "state_hash": _text(c.attrs.get("state_hash", "")),
            "format_version": int(c.attrs["format_version"]),
            "position": _required(h, path, "particles/body/position/value")[0],
            "velocity": _required(h, path, "particles/body/velocity/value")[0],
            "mass": _required(h, path, "particles/body/mass"),
            "species": _required(h, path, "particles/body/species"),
            "springs": _required(h, path, "connectivity/springs"),
            "faces": h["connectivity/faces"][()] if "connectivity/faces" in h else np.zeros((0, 3), np.int32),
            "rest_length": _required(h, path, "checkpoint/springs/rest_length"),
            "stiffness": _required(h, path, "checkpoint/springs/stiffness"),
            "kind": _required(h, path, "checkpoint/springs/kind"),
            "failed": _required(h, path, "checkpoint/springs/failed"),
            "failures": {k: h["checkpoint/failures"][k][()] for k in h["checkpoint/failures"]}
            if "checkpoint/failures" in h else {},
            "timeseries": {k: h["checkpoint/timeseries"][k][()] for k in h["checkpoint/timeseries"]}
            if "checkpoint/timeseries" in h else {},
            "record": {k: (_text(v) if isinstance(v, (bytes, str)) else v.item() if np.ndim(v) == 0 else v)
                       for k, v in h["checkpoint/record"].attrs.items()} if "checkpoint/record" in h else {},
            "config": _text(h["parameters/config"][()]) if "parameters/config" in h else "",
            "species_labels": [_text(x) for x in h["particles/body/species"].attrs.get("labels", [])],
            "kind_labels": [_text(x) for x in h["checkpoint/springs/kind"].attrs.get("labels", [])],
        }
    n = one["mass"].shape[0]
    if one["position"].shape != (n, 3) or one["springs"].ndim != 2 or one["springs"].shape[1] != 2:
        raise CheckpointError(f"{path}: positions {one['position'].shape} or springs {one['springs'].shape} "
                              f"do not fit {n} particles")
    return one


def open(path: str | os.PathLike) -> xr.Dataset:  # noqa: A001 (tidalcrust.open, like xarray.open_dataset)
    """A checkpoint file, or an encounter folder (its snapshots and encounter.h5), as a Dataset.

    Dimensions: `time` (one entry per file, ascending step), `particle` (N), `xyz` (3),
    `spring` (Ns), `end` (2), `face` (Nf), `vertex` (3), `failure` (failure events of the last
    file), `sample` (timeseries samples of the last file).

    Variables (units in each variable's `units` attribute, all in G = M = R = 1):
      position, velocity [time, particle, xyz] (R, sqrt(GM/R)); mass [particle] (M);
      species [particle] (0 interior, 1 shell); spring_particles [spring, end];
      spring_kind [spring] (0 interior, 1 shell, 2 cross); stiffness [spring] (last file);
      rest_length, strain [time, spring] ((L - L0)/L0, 1); failed [time, spring] (bool);
      failed_at [spring] (t_grav: when the spring failed; NaN for one that never failed);
      faces [face, vertex]; the failure log failure_{time, step, spring, strain, released_energy}
      [failure] and failure_position [failure, xyz]; the time series sample_time [sample] and
      ts_<column> [sample] or [sample, xyz] (ts_failed: failed springs so far).
    Coordinates: time (t_grav), step [time], file [time] (the file's name).
    Attributes: units (the note above), stage, state_hash, format_version, source, config (the
    resolved TOML), record_<field> (the stage record, e.g. record_pericenter_time).

    Raises CheckpointError (a ValueError) naming the file or folder for a missing path, a file
    that is not HDF5 or not a tidalcrust checkpoint, a format this package does not read, or
    snapshots of another body.
    """
    files = checkpoint_files(path)
    parts = _drop_late_snapshots([_read_one(f) for f in files])
    last = parts[-1]
    for p in parts[:-1]:
        if p["mass"].shape != last["mass"].shape or not np.array_equal(p["springs"], last["springs"]):
            raise CheckpointError(f"{p['path']}: another body than {last['path']} (particles or springs differ)")

    positions = np.stack([p["position"] for p in parts])
    springs = last["springs"].astype(np.int64)
    rest = np.stack([p["rest_length"] for p in parts])
    lengths = np.linalg.norm(positions[:, springs[:, 0], :] - positions[:, springs[:, 1], :], axis=-1)
    failures = last["failures"]
    failure_time = np.full(springs.shape[0], np.nan)
    if failures.get("spring") is not None and len(failures["spring"]):
        failure_time[failures["spring"].astype(np.int64)] = failures["time"]

    data = {
        "position": (("time", "particle", "xyz"), positions, {"units": "R", "long_name": "position"}),
        "velocity": (("time", "particle", "xyz"), np.stack([p["velocity"] for p in parts]),
                     {"units": "sqrt(G M/R)", "long_name": "velocity"}),
        "mass": (("particle",), last["mass"], {"units": "M"}),
        "species": (("particle",), last["species"], {"units": "1", "labels": last["species_labels"] or
                                                      ["interior", "shell"]}),
        "spring_particles": (("spring", "end"), springs, {"long_name": "particle indices of each spring"}),
        "spring_kind": (("spring",), last["kind"], {"labels": last["kind_labels"] or ["interior", "shell", "cross"]}),
        "stiffness": (("spring",), last["stiffness"], {"units": "G M^2/R^3", "note": "of the last file"}),
        "rest_length": (("time", "spring"), rest, {"units": "R"}),
        "strain": (("time", "spring"), (lengths - rest) / rest, {"units": "1", "long_name": "(L - L0)/L0"}),
        "failed": (("time", "spring"), np.stack([p["failed"] for p in parts]).astype(bool), {}),
        "failed_at": (("spring",), failure_time,
                         {"units": "t_grav", "long_name": "time the spring failed (NaN: never)"}),
        "faces": (("face", "vertex"), last["faces"].astype(np.int64), {"long_name": "shell triangles"}),
    }
    failure_units = {"time": "t_grav", "step": "1", "spring": "1", "strain": "1", "released_energy": "G M^2/R",
                     "position": "R"}
    for key, values in failures.items():
        dims = ("failure", "xyz") if values.ndim == 2 else ("failure",)
        data[f"failure_{key}"] = (dims, values, {"units": failure_units.get(key, "")})
    timeseries = last["timeseries"]
    for key, values in timeseries.items():
        if key == "time":
            continue
        dims = ("sample", "xyz") if values.ndim == 2 else ("sample",)
        data[f"ts_{key}"] = (dims, values, {"units": _TIMESERIES_UNITS.get(key, "")})
    coords = {
        "time": ("time", np.array([p["time"] for p in parts]), {"units": "t_grav"}),
        "step": ("time", np.array([p["step"] for p in parts], dtype=np.int64)),
        "file": ("time", [p["path"].name for p in parts]),
        "xyz": ("xyz", ["x", "y", "z"]),
    }
    if "time" in timeseries:
        coords["sample_time"] = ("sample", timeseries["time"], {"units": "t_grav"})
    attrs = {
        "units": UNITS_NOTE,
        "stage": last["stage"],
        "complete": int(last["complete"]),
        "state_hash": last["state_hash"],
        "format_version": last["format_version"],
        "source": str(Path(path)),
        "config": last["config"],
    }
    for key, value in last["record"].items():
        attrs[f"record_{key}"] = value
    import xarray as xr  # here, not at the top: the figure script does not need it (and it is slow to import)

    return xr.Dataset(data, coords=coords, attrs=attrs)
