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
