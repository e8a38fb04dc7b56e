"""Renders and table sweeps spread over a Dask cluster (``dask.distributed``).

A render is cut into rectangular tiles, each rendered by a task with
:func:`scratchwave.render` (``region=...``) and pasted into the image: the result equals the
single-process render bit for bit, since every pixel is computed the same way wherever it
runs. A table sweep is cut into chunks of queries (listed queries, or the outermost ``wi``
axis of a grid) and concatenated in order, equal to :func:`scratchwave.table`.

Workers need the ``scratchwave`` package and, for scenes that name files (meshes, scratch
files), the same files at the same absolute paths (a shared file system): the scene travels
as JSON text with its base directory made absolute. Point it at a real cluster with
``Client("tcp://scheduler:8786")`` (README, "Python").
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any, List, Optional, Tuple, Union

import numpy as np

import scratchwave as _sw


def tiles(width: int, height: int, tile: int) -> List[Tuple[int, int, int, int]]:
    """The ``(x0, y0, w, h)`` tiles, at most ``tile`` pixels on a side, that cover a
    ``width × height`` image, row by row."""
    if tile <= 0:
        raise ValueError(f"tile: must be > 0, got {tile}")
    return [
        (x, y, min(tile, width - x), min(tile, height - y))
        for y in range(0, height, tile)
        for x in range(0, width, tile)
    ]


def _render_tile(text: str, base_dir: str, backend: str, region: Tuple[int, int, int, int]):
    return region, _sw.render(text, backend=backend, region=region, base_dir=base_dir)


def render(
    scene: Union[dict, str, os.PathLike],
    client: Any,
    tile: int = 64,
    backend: str = "cpu",
    base_dir: Union[str, os.PathLike, None] = None,
) -> np.ndarray:
    """Renders ``scene`` (a dict, JSON text or a scene file path) with one Dask task per
    tile on ``client`` (a ``dask.distributed.Client``); returns the (height, width, 3)
    image, bit-identical to :func:`scratchwave.render`."""
    text, _name, base = _sw._scene_text(scene, base_dir)
    cam = json.loads(text)["camera"]
    width, height = int(cam["width_px"]), int(cam["height_px"])
    base = str(Path(base).resolve())
    futures = [
        client.submit(_render_tile, text, base, backend, r, pure=False)
        for r in tiles(width, height, tile)
    ]
    image = np.zeros((height, width, 3), dtype=np.float32)
    for (x, y, w, h), part in client.gather(futures):
        image[y : y + h, x : x + w] = part
    return image


def _chunks(spec: dict, chunk: int) -> List[dict]:
    q = spec.get("queries")
    if isinstance(q, list):
        return [dict(spec, queries=q[i : i + chunk]) for i in range(0, len(q), chunk)] or [spec]
    if isinstance(q, dict) and isinstance(q.get("grid"), dict) and isinstance(q["grid"].get("wi"), list):
        g = q["grid"]
        # `wi` is the outermost grid axis: chunks of it concatenate in query order.
        per = max(1, chunk // max(1, _grid_inner(g)))
        wis = g["wi"]
        return [dict(spec, queries={"grid": dict(g, wi=wis[i : i + per])}) for i in range(0, len(wis), per)] or [spec]
    return [spec]


def _grid_inner(g: dict) -> int:
    n = 1
    for k in ("wo", "lambda_nm", "x"):
        if isinstance(g.get(k), list):
            n *= max(1, len(g[k]))
    return n


def table(spec: Union[dict, str], client: Any, chunk: int = 1 << 16, backend: str = "cpu") -> np.ndarray:
    """The values of a table spec with one Dask task per chunk of about ``chunk`` queries;
    equal to :func:`scratchwave.table` bit for bit."""
    s = json.loads(spec) if isinstance(spec, str) else spec
    futures = [client.submit(_sw.table, part, backend, pure=False) for part in _chunks(s, chunk)]
    return np.concatenate(client.gather(futures)).astype(np.float32, copy=False)


__all__ = ["render", "table", "tiles"]
