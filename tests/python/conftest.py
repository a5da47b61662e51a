"""Shared by the package's tests: the source tree, the command line beside the package, and a
quick scene. ctest runs them from the source tree with PYTHONPATH at the build's package and
TOPOMILL_EXE at its program (tests/CMakeLists.txt)."""

import json
import os
import pathlib
import subprocess

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]
QUICK = ROOT / "configs" / "examples" / "quick.toml"


def topomill_exe():
    exe = os.environ.get("TOPOMILL_EXE")
    if not exe:
        pytest.fail("TOPOMILL_EXE is not set: run these tests through ctest")
    return exe


def cli(*args, check=True):
    """Runs the command line; returns (exit code, stdout, stderr)."""
    p = subprocess.run([topomill_exe(), *map(str, args)], capture_output=True, text=True,
                       cwd=ROOT, timeout=600)
    if check and p.returncode != 0:
        pytest.fail(f"topomill {' '.join(map(str, args))}: exit {p.returncode}\n{p.stderr}")
    return p.returncode, p.stdout, p.stderr


def cli_json(*args):
    return json.loads(cli(*args)[1])
