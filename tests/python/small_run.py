"""The small run the Python tests share: tests/python/small.toml run by the program under test
into a scratch folder (about 2 s of CPU). TIDALCRUST_EXE names the program (CTest sets it)."""
import os
import subprocess
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent


def make_small_run(parent: str) -> Path:
    """Runs small.toml into `parent`/run and returns its encounter folder (A)."""
    exe = os.environ.get("TIDALCRUST_EXE")
    if not exe:
        raise RuntimeError("TIDALCRUST_EXE is not set (the tidalcrust program to test)")
    out = Path(parent) / "run"
    done = subprocess.run([exe, "run", str(HERE / "small.toml"), "--out", str(out), "--quiet"],
                          capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{exe} run small.toml failed ({done.returncode}): {done.stderr}")
    return out / "A"


def scratch() -> tempfile.TemporaryDirectory:
    return tempfile.TemporaryDirectory(prefix="tidalcrust-py-")
