"""Renders and table sweeps on a Dask LocalCluster (worker processes) equal the
single-process results bit for bit."""

import json
from pathlib import Path

import numpy as np
import pytest

import scratchwave as sw

distributed = pytest.importorskip("dask.distributed")
from scratchwave import distributed as swd  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]


@pytest.fixture(scope="module")
def client():
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster:
        with distributed.Client(cluster) as c:
            yield c


def test_tiles_cover_the_image():
    t = swd.tiles(50, 20, 16)
    covered = np.zeros((20, 50), dtype=int)
    for x, y, w, h in t:
        covered[y:y + h, x:x + w] += 1
    assert (covered == 1).all() and len(t) == 4 * 2


@pytest.mark.parametrize("name", ["velinov_footprint.json", "ghs_polygon_shadow.json"])
def test_dask_render_equals_single_process(client, name):
    scene = ROOT / "conformance/scenes" / name
    whole = sw.render(scene)
    spread = swd.render(scene, client, tile=24)
    np.testing.assert_array_equal(spread.view(np.uint32), whole.view(np.uint32))


def test_dask_table_equals_single_process(client):
    spec = json.loads((ROOT / "reference/golden/tables/ensemble_werner_exact.json").read_text())["spec"]
    one = sw.table(spec)
    many = swd.table(spec, client, chunk=max(1, one.size // 5))
    np.testing.assert_array_equal(many.view(np.uint32), one.view(np.uint32))


def test_dask_grid_table_equals_single_process(client):
    wi = [[np.sin(t), 0.0, np.cos(t)] for t in np.linspace(0.0, 1.2, 7)]
    spec = {
        "model": "velinov",
        "sigma_um": 10,
        "scratches": [{"p0": [-100, 0], "p1": [100, 0], "width": 2, "depth": 0.3}],
        "queries": {"grid": {"wi": wi, "wo": [[0.1, 0.2, 0.97], [-0.3, 0.0, 0.95]],
                             "lambda_nm": [450, 600], "x": [[0, 0], [0, 1.5]]}},
    }
    one = sw.table(spec)
    assert one.size == 7 * 2 * 2 * 2
    many = swd.table(spec, client, chunk=16)
    assert len(swd._chunks(spec, 16)) == 4
    np.testing.assert_array_equal(many.view(np.uint32), one.view(np.uint32))
