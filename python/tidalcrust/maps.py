"""Figures of a Dataset (tidalcrust.open): the failures and the energy budget over time, each
returning its Figure for the caller to restyle (docs/python.md); the figures of `analyze`, drawn
from its files, are in tidalcrust.figures. Nothing here sets a backend: in a script without a display use
MPLBACKEND=Agg.
"""
from __future__ import annotations  # the annotations name xarray types without importing xarray (slow)

import json
import os
from pathlib import Path

import matplotlib.pyplot as plt
import numpy as np

from .checkpoint import TidalcrustError

#: The binding energy of a uniform sphere, 3/5 G M^2/R: the scale of the energy errors.
BINDING_ENERGY = 0.6


def read_summary(path: str | os.PathLike) -> dict:
    """summary.json of an encounter folder, analysis folder or the file itself. Raises
    TidalcrustError naming the path."""
    path = Path(path)
    for candidate in (path, path / "summary.json", path / "analysis" / "summary.json"):
        if candidate.is_file():
            try:
                return json.loads(candidate.read_text())
            except (OSError, UnicodeDecodeError, json.JSONDecodeError) as err:
                raise TidalcrustError(f"{candidate}: not a readable JSON file ({err})") from None
    raise TidalcrustError(f"{path}: no summary.json (written by `tidalcrust analyze`)")


def _pericenter_time(ds: xr.Dataset) -> float:
    return float(ds.attrs.get("record_pericenter_time", 0.0))


def failure_history(ds: xr.Dataset, ax=None):
    """Cumulative failed springs against time from pericenter (t_grav), from the failure log
    (ds.failure_time of tidalcrust.open). Returns the Figure."""
    if ax is None:
        fig, ax = plt.subplots(figsize=(6, 4))
    times = np.sort(ds["failure_time"].values[np.isfinite(ds["failure_time"].values)]) - _pericenter_time(ds)
    ax.step(times, np.arange(1, times.size + 1), where="post", color="black")
    ax.axvline(0.0, color="0.6", linewidth=0.8)
    ax.set_xlabel("time from pericenter [t_grav]")
    ax.set_ylabel("failed springs")
    return ax.figure


def conserved_energy(ds: xr.Dataset) -> xr.DataArray:
    """E = K + U_s + U_h + U_g + U_p + D + F - W_h per sample (G M^2/R; docs/energy-budget.md)."""
    return (ds.ts_kinetic_energy + ds.ts_spring_energy + ds.ts_hinge_energy + ds.ts_self_gravity_energy +
            ds.ts_perturber_energy + ds.ts_damping_dissipated + ds.ts_failure_released - ds.ts_hinge_residual_work)


def energy_budget(ds: xr.Dataset, axes=None):
    """The energy budget (docs/energy-budget.md): top, the relative error of the conserved total,
    (E - E_0)/(3/5 G M^2/R); bottom, each term's change since the first sample (G M^2/R), against
    time from pericenter. Returns the Figure."""
    if axes is None:
        fig, axes = plt.subplots(2, 1, figsize=(6, 6), sharex=True)
    t = ds.sample_time.values - _pericenter_time(ds)
    energy = conserved_energy(ds).values
    axes[0].plot(t, (energy - energy[0]) / BINDING_ENERGY, color="black")
    axes[0].set_ylabel("(E - E0) / (3/5 GM²/R)")
    for name in ("kinetic_energy", "spring_energy", "hinge_energy", "self_gravity_energy", "perturber_energy",
                 "damping_dissipated", "failure_released", "hinge_residual_work"):
        values = ds[f"ts_{name}"].values
        axes[1].plot(t, values - values[0], label=name.replace("_", " "))
    axes[1].set_xlabel("time from pericenter [t_grav]")
    axes[1].set_ylabel("change [GM²/R]")
    axes[1].legend(fontsize=7)
    return axes[0].figure
