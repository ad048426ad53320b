#!/usr/bin/python3
"""Opens the files of a quick run in the real outside readers (make check-viewers).

1. Runs `tidalcrust run WORKFLOW --out TMP` (workflows/quick.toml unless told otherwise).
2. Opens EVERY .xdmf sidecar with ParaView's default reader (Xdmf3ReaderS), Xdmf3ReaderT and
   the legacy XDMFReader (one python3 process per reader), with the process's stderr (file
   descriptor 2, where VTK, Xdmf and HDF5 print) sent to a file during each load, so that any
   warning is caught and named with its sidecar: any output fails.
   Checks the point and cell counts of the particles, springs and shell grids and the springs'
   `failed` flags against the checkpoint (read with h5py).
3. Loads checkpoints with MDAnalysis's H5MDReader with its defaults (convert_units=True) and
   checks the positions, velocities, time and step it reports (units: docs/checkpoint-layout.md).

Usage: tools/check_viewers.py [--exe build/tidalcrust] [--workflow workflows/quick.toml]
                              [--keep DIR]
Exit 0 when every check passes, 1 otherwise (each failure printed on one line).
"""
import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile

READERS = ("Xdmf3ReaderS", "Xdmf3ReaderT", "XDMFReader")
# nm -> Angstrom: MDAnalysis converts to its own base units (Angstrom, ps).
LENGTH_TO_ANGSTROM = 10.0


def load_one(reader_name, sidecar):
    """Loads `sidecar` with one ParaView reader and returns its grids.

    Grids are named by their cells, not by block names: the legacy reader and Xdmf3ReaderT name
    the blocks, Xdmf3ReaderS returns the three grids as unnamed pieces of one partitioned block.
    """
    from paraview import simple, servermanager
    from vtkmodules.vtkCommonDataModel import (VTK_LINE, VTK_POLY_LINE, VTK_POLY_VERTEX, VTK_TRIANGLE,
                                               VTK_VERTEX, vtkDataObjectTreeIterator)

    grid_of_cell = {VTK_VERTEX: "particles", VTK_POLY_VERTEX: "particles", VTK_LINE: "springs",
                    VTK_POLY_LINE: "springs", VTK_TRIANGLE: "shell"}
    if reader_name == "XDMFReader":
        reader = simple.XDMFReader(FileNames=[sidecar])
    else:
        reader = getattr(simple, reader_name)(FileName=[sidecar])
    reader.UpdatePipeline()
    data = servermanager.Fetch(reader)
    grids = {}
    it = vtkDataObjectTreeIterator()
    it.SetDataSet(data)
    it.VisitOnlyLeavesOn()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        block = it.GetCurrentDataObject()
        cells = block.GetNumberOfCells()
        name = grid_of_cell.get(block.GetCellType(0), f"cell type {block.GetCellType(0)}") if cells else "empty"
        failed = block.GetCellData().GetArray("failed")
        if name in grids:
            name += " (again)"
        grids[name] = {
            "points": block.GetNumberOfPoints(),
            "cells": cells,
            "failed": [int(failed.GetTuple1(i)) for i in range(failed.GetNumberOfTuples())] if failed else None,
        }
        it.GoToNextItem()
    simple.Delete(reader)
    return grids


def load_all(reader_name, sidecars):
    """In a child process: load every sidecar with one reader; print, as JSON, the grids of
    each and whatever was written to stderr while it loaded."""
    results = {}
    saved = os.dup(2)
    for sidecar in sidecars:
        with tempfile.TemporaryFile() as captured:
            sys.stderr.flush()
            os.dup2(captured.fileno(), 2)
            try:
                grids = load_one(reader_name, sidecar)
            except Exception as err:  # reported like any other reader complaint
                grids = {}
                print(f"{type(err).__name__}: {err}", file=sys.stderr)
            finally:
                sys.stderr.flush()
                os.dup2(saved, 2)
            captured.seek(0)
            results[sidecar] = {"grids": grids, "output": captured.read().decode(errors="replace")}
    print(json.dumps(results))


def checkpoint_truth(h5file):
    import h5py

    with h5py.File(h5file, "r") as f:
        return {
            "N": f["/particles/body/mass"].shape[0],
            "Ns": f["/connectivity/springs"].shape[0],
            "Nf": f["/connectivity/faces"].shape[0],
            "failed": [int(v) for v in f["/checkpoint/springs/failed"][()]],
        }


def check_sidecars(sidecars, problems):
    # Absolute paths: Xdmf3 readers resolve the .h5 name wrongly beside a bare file name.
    names = [str(s.resolve()) for s in sidecars]
    for reader in READERS:
        run = subprocess.run([sys.executable, __file__, "--load-all", reader, *names], capture_output=True, text=True)
        if run.returncode != 0:
            problems.append(f"{reader}: exit {run.returncode}: {run.stderr.strip().splitlines()[-3:]}")
            continue
        results = json.loads(run.stdout.strip().splitlines()[-1])
        for sidecar in names:
            check_loaded(pathlib.Path(sidecar), reader, results[sidecar], problems)


def check_loaded(sidecar, reader, result, problems):
    truth = checkpoint_truth(sidecar.with_suffix(".h5"))
    expected = {"particles": (truth["N"], truth["N"]), "springs": (truth["N"], truth["Ns"])}
    if truth["Nf"] > 0:
        expected["shell"] = (truth["N"], truth["Nf"])
    where = f"{sidecar} ({reader})"
    noise = result["output"].strip()
    if noise:
        problems.append(f"{where}: reader output: {noise.splitlines()[:3]}")
    grids = result["grids"]
    for name, (points, cells) in expected.items():
        got = grids.get(name)
        if got is None:
            problems.append(f"{where}: no grid '{name}' (grids: {sorted(grids)})")
        elif (got["points"], got["cells"]) != (points, cells):
            problems.append(f"{where}: grid '{name}' has {got['points']} points, {got['cells']} cells;"
                            f" expected {points}, {cells}")
    extra = sorted(set(grids) - set(expected))
    if extra:
        problems.append(f"{where}: unexpected grids {extra}")
    springs = grids.get("springs")
    if springs and springs["failed"] != truth["failed"]:
        problems.append(f"{where}: springs' failed flags differ from /checkpoint/springs/failed"
                        f" ({sum(springs['failed'] or [])} against {sum(truth['failed'])} failed)")


def check_mdanalysis(h5file, problems):
    import h5py
    import numpy as np
    import warnings

    warnings.filterwarnings("ignore", category=DeprecationWarning)  # MDAnalysis 2.4 imports xdrlib
    from MDAnalysis.coordinates.H5MD import H5MDReader

    with h5py.File(h5file, "r") as f:
        position = f["/particles/body/position/value"][0]
        velocity = f["/particles/body/velocity/value"][0]
        time = f["/particles/body/position/time"][0]
        step = f["/particles/body/position/step"][0]
    try:
        reader = H5MDReader(str(h5file))  # the defaults: convert_units=True
    except Exception as err:  # any refusal is the failure we report
        problems.append(f"{h5file} (MDAnalysis): {type(err).__name__}: {err}")
        return
    ts = reader.ts
    checks = {
        "n_frames": reader.n_frames == 1,
        "n_atoms": reader.n_atoms == position.shape[0],
        "positions": np.allclose(ts.positions, LENGTH_TO_ANGSTROM * position, rtol=1e-6, atol=1e-6),
        "velocities": np.allclose(ts.velocities, LENGTH_TO_ANGSTROM * velocity, rtol=1e-6, atol=1e-6),
        "time": abs(ts.time - time) <= 1e-12 * max(1.0, abs(time)),
        "step": int(ts.data.get("step", -1)) == int(step),
    }
    reader.close()
    for what, ok in checks.items():
        if not ok:
            problems.append(f"{h5file} (MDAnalysis): {what} differ from the checkpoint")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--exe", default="build/tidalcrust")
    parser.add_argument("--workflow", default="workflows/quick.toml")
    parser.add_argument("--keep", help="run into this folder and keep it")
    parser.add_argument("--load-all", nargs="+", metavar="READER SIDECAR", help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.load_all:
        load_all(args.load_all[0], args.load_all[1:])
        return 0

    with tempfile.TemporaryDirectory(prefix="tidalcrust_viewers_") as scratch:
        out = pathlib.Path(args.keep or scratch) / "run"
        subprocess.run([args.exe, "run", args.workflow, "--out", str(out), "--quiet"], check=True)
        sidecars = sorted(out.rglob("*.xdmf"))
        problems = []
        if not sidecars:
            problems.append(f"{out}: the run wrote no .xdmf sidecar")
        check_sidecars(sidecars, problems)
        checkpoints = sorted(out.rglob("*.h5"))
        for h5file in checkpoints:
            check_mdanalysis(h5file, problems)
        for p in problems:
            print(p)
        print(f"check-viewers: {len(sidecars)} sidecars x {len(READERS)} ParaView readers,"
              f" {len(checkpoints)} checkpoints in MDAnalysis: {len(problems)} problems")
        return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
