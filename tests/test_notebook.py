"""examples/analysis.ipynb runs top to bottom against tiny datasets made here with the library."""

import functools
import os
from pathlib import Path

import nbformat
import pytest
import yaml
from nbclient import NotebookClient

from contactlib import studies

from contactlib.pipeline import sweep

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def tiny_results(tmp_path_factory):
    """The three studies of tests/data/tiny_config.yaml, run serially (no Dask), as the workflow writes them."""
    out = tmp_path_factory.mktemp("results")
    config = yaml.safe_load((ROOT / "tests" / "data" / "tiny_config.yaml").read_text())
    for name, study in config["studies"].items():
        block = study["quick"]
        solver = {k: v for k, v in config["solver"].items() if k != "warm_start"}
        constants = {**config["material"], **solver, **study["constants"], **block["constants"]}
        ds = sweep.run_grid(functools.partial(studies.STUDIES[name]["point"], **constants), block["grid"],
                            labels=studies.STUDY_VARIABLES, progress=False,
                            attrs={"title": study["title"], "config": {"study": {"grid": block["grid"]}}})
        sweep.write_netcdf(ds, out / f"{name}.nc", sweep_dims=block["grid"])
    return out


def test_analysis_notebook_executes(tiny_results, monkeypatch):
    monkeypatch.setenv("CONTACTLIB_RESULTS", str(tiny_results))
    nb = nbformat.read(ROOT / "examples" / "analysis.ipynb", as_version=4)
    NotebookClient(nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(ROOT / "examples")}},
                   ).execute()
    outputs = [o for cell in nb.cells if cell.cell_type == "code" for o in cell.outputs]
    assert not [o for o in outputs if o.output_type == "error"]
    images = [o for o in outputs if "image/png" in o.get("data", {})]
    assert len(images) >= 3  # area-load curves, Hertz ratio, pressure maps
    assert os.environ["CONTACTLIB_RESULTS"] == str(tiny_results)
