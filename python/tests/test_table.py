"""`scratchwave.table(spec)` returns exactly the values `scratchwave table SPEC --backend cpu`
prints, bit for bit, for every mpmath-golden table spec (all models)."""

import json
import subprocess
from pathlib import Path

import numpy as np
import pytest

import scratchwave as sw

ROOT = Path(__file__).resolve().parents[2]
SPECS = sorted((ROOT / "reference/golden/tables").glob("*.json"))


@pytest.mark.parametrize("path", SPECS, ids=[p.stem for p in SPECS])
def test_table_equals_cli_bitwise(path, cli, tmp_path):
    spec = json.loads(path.read_text())["spec"]
    f = tmp_path / "spec.json"
    f.write_text(json.dumps(spec))
    out = subprocess.run([str(cli), "table", str(f), "--backend", "cpu"], check=True,
                         capture_output=True, text=True).stdout
    cli_vals = np.array([np.float32(float(t)) for t in out.split()], dtype=np.float32)
    py = sw.table(spec)
    assert py.dtype == np.float32 and py.shape == cli_vals.shape
    np.testing.assert_array_equal(py.view(np.uint32), cli_vals.view(np.uint32))


def test_table_rejects_bad_specs():
    with pytest.raises(sw.InputError, match="model"):
        sw.table({"model": "nope"})
    with pytest.raises(ValueError, match="backend"):
        sw.table({"model": "werner"}, backend="gpu")


def test_velinov_takes_deepest_crossings():
    # Velinov's intensity form of `crossings: deepest` (issue #21): each groove's term loses
    # the overlap pieces where the other groove cuts deeper before it is squared. Two
    # rectangular grooves of unequal depth crossing at 90° 2 µm from the shading point: the
    # shallower one loses the whole overlap, which moves every direction here; with the
    # frozen window and no tie in depth, the grooves' order does not matter.
    cross = [{"p0": [-500, 0], "p1": [500, 0], "width": 3, "depth": 0.2},
             {"p0": [2, -500], "p1": [2, 500], "width": 3, "depth": 0.1}]
    wos = [[0.0, 0.0, 1.0], [0.05, 0.05, 0.9975], [0.1, -0.05, 0.99373]]
    queries = [{"wi": [0, 0, 1], "wo": wo, "lambda_nm": 550, "x": [0, 0]} for wo in wos]
    spec = {"model": "velinov", "sigma_um": 10, "scratches": cross, "queries": queries}
    deepest = {**spec, "options": {"crossings": "deepest"}}
    summed, cut = sw.table(spec), sw.table(deepest)
    assert np.all(np.isfinite(cut)) and np.all(cut > 0)
    assert np.min(np.abs(cut - summed) / summed) > 1e-3
    swapped = sw.table({**deepest, "scratches": cross[::-1]})
    np.testing.assert_allclose(swapped, cut, rtol=1e-5)
