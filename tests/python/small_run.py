"""The small run the Python tests share: tests/python/small.toml run by the program under test
into a scratch folder (about 2 s of CPU), or the tiny moon in SI for the figures in SI.
TIDALCRUST_EXE names the program (CTest sets it)."""
import os
import subprocess
import tempfile
from pathlib import Path

HERE = Path(__file__).resolve().parent


def make_small_run(parent: str, workflow: Path = HERE / "small.toml") -> Path:
    """Runs `workflow` (small.toml; or MOON_WORKFLOW, the tiny moon in SI) into `parent`/run and
    returns its encounter folder (A)."""
    exe = os.environ.get("TIDALCRUST_EXE")
    if not exe:
        raise RuntimeError("TIDALCRUST_EXE is not set (the tidalcrust program to test)")
    out = Path(parent) / "run"
    done = subprocess.run([exe, "run", str(workflow), "--out", str(out), "--quiet"],
                          capture_output=True, text=True)
    if done.returncode != 0:
        raise RuntimeError(f"{exe} run {workflow.name} failed ({done.returncode}): {done.stderr}")
    return out / "A"


#: The tiny moon given in SI of the C++ tests (tests/support/tiny-moon.toml, about 3 s of CPU).
MOON_WORKFLOW = HERE.parent / "support" / "tiny-moon.toml"


def scratch() -> tempfile.TemporaryDirectory:
    return tempfile.TemporaryDirectory(prefix="tidalcrust-py-")
