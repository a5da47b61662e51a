"""The example script and the notebook run as they are, so that neither can rot."""

import pathlib
import subprocess
import sys

import nbclient
import nbformat

import topomill

from conftest import ROOT

EXAMPLES = ROOT / "examples" / "python"


def test_the_lambda_sweep_script(tmp_path):
    p = subprocess.run([sys.executable, EXAMPLES / "lambda_sweep.py", "--out", tmp_path,
                        "--spacing", "0.005"], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr
    rows = (tmp_path / "lambda_sweep.csv").read_text().splitlines()
    assert rows[0] == "lambda_deg,Sa_um,Sq_um,Sz_um,time_s" and len(rows) == 8
    assert (tmp_path / "lambda_sweep.png").stat().st_size > 10000


def test_the_notebook_executes(tmp_path, monkeypatch):
    monkeypatch.setenv("TOPOMILL_FIGURES", str(tmp_path))
    # The kernel runs in the notebook's directory: the package's place made absolute.
    monkeypatch.setenv("PYTHONPATH", str(pathlib.Path(topomill.__file__).resolve().parents[1]))
    monkeypatch.setenv("PYDEVD_DISABLE_FILE_VALIDATION", "1")  # ipykernel's debugger notice
    nb = nbformat.read(EXAMPLES / "analysis.ipynb", as_version=4)
    nbclient.NotebookClient(nb, timeout=600, kernel_name="python3",
                            resources={"metadata": {"path": str(EXAMPLES)}}).execute()
    for name in ("notebook_sweep.png", "notebook_surface.png", "notebook_compare.png"):
        assert (tmp_path / name).stat().st_size > 10000, name
    errors = [o for c in nb.cells if c.cell_type == "code" for o in c.outputs
              if o.output_type == "error"]
    assert not errors
