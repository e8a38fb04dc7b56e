"""scratchwave: wave-optical scratched and rough surfaces from Python.

The BSDFs of Werner et al. 2017 (coherent scratches), Velinov et al. 2018 (incoherent
scratches, pixel footprints) and Holzschuch & Pacanowski (GHS), evaluated by the same
compiled kernel as the Rust library, the C ABI and the ``scratchwave`` CLI, so results are
bit-identical across the three. Batch calls take NumPy arrays and release the GIL.

Conventions (``docs/bsdf.md``): directions in the local shading frame (``z`` the normal,
``x`` the tangent = the first axis of scratch space), both pointing away from the surface,
``wo`` towards the viewer and ``wi`` towards the light; BRDF values in 1/sr without the
cosine; positions in µm of scratch space; wavelengths in nm (default 700, 520, 440).

Example::

    import numpy as np
    import scratchwave as sw

    m = sw.Material({"model": "velinov", "sigma_um": 10,
                     "scratches": [{"p0": [-100, 0], "p1": [100, 0],
                                    "width": 2, "depth": 0.3}]})
    wo = np.array([[0.0, 0.3, 0.954]])
    wi = np.array([[0.0, -0.3, 0.954]])
    f = m.eval(wo, wi)            # shape (1, 3): 700, 520, 440 nm
    wi2, weight, pdf = m.sample(wo, np.random.default_rng(1).random((1, 3)))
"""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native
from ._native import InputError

__version__ = _native.__version__

__all__ = [
    "InputError",
    "Material",
    "ScratchSet",
    "eval",
    "pdf",
    "sample",
    "render",
    "table",
    "__version__",
]

JsonLike = Union[str, dict, list]


def _json_text(spec: JsonLike, what: str) -> str:
    if isinstance(spec, str):
        return spec
    if isinstance(spec, (dict, list)):
        return json.dumps(spec)
    raise TypeError(f"{what}: expected a dict, a list or JSON text, got {type(spec).__name__}")


def _rows(a: Any, name: str, width: int, n: Optional[int]) -> np.ndarray:
    """`a` as a C-contiguous float32 (n, width) array, flattened; errors name `name`."""
    arr = np.asarray(a, dtype=np.float32)
    if arr.ndim == 1 and arr.shape[0] == width and (n is None or n == 1):
        arr = arr.reshape(1, width)
    if arr.ndim != 2 or arr.shape[1] != width or (n is not None and arr.shape[0] != n):
        want = f"({'n' if n is None else n}, {width})"
        raise ValueError(f"{name}: expected shape {want}, got {arr.shape}")
    return np.ascontiguousarray(arr).reshape(-1)


def _lambdas(lambda_nm: Any, n: int) -> Tuple[Optional[np.ndarray], int]:
    if lambda_nm is None:
        return None, 0
    arr = np.asarray(lambda_nm, dtype=np.float32)
    if arr.ndim == 0:
        arr = arr.reshape(1)
    if arr.ndim == 1:
        return np.ascontiguousarray(arr), int(arr.shape[0])
    if arr.ndim == 2 and arr.shape[0] == n:
        return np.ascontiguousarray(arr).reshape(-1), int(arr.shape[1])
    raise ValueError(f"lambda_nm: expected shape (k,) or ({n}, k), got {arr.shape}")


class ScratchSet:
    """Scratch segments in scratch space (µm).

    ``ScratchSet(sources)`` takes a list of scratch sources exactly as a scene material's
    ``"scratches"`` (``docs/scratches.md``): inline ``{"p0", "p1", "width", "depth",
    "profile"}`` scratches, ``{"file": ...}`` (JSON or CSV, relative to ``base_dir``) and
    ``{"generate": {...}}`` patterns. ``ScratchSet.from_rows`` takes an array.
    """

    def __init__(self, sources: JsonLike = (), base_dir: Union[str, os.PathLike, None] = None):
        if isinstance(sources, tuple):
            sources = list(sources)
        self._native = _native.NativeScratchSet.from_json(
            _json_text(sources, "sources"), None if base_dir is None else str(base_dir)
        )

    @classmethod
    def from_rows(cls, rows: Any, triangle: Optional[Sequence[bool]] = None) -> "ScratchSet":
        """Rows ``[x0, y0, x1, y1, width, depth]`` (µm, shape (n, 6)); ``triangle[i]`` true
        for a triangular profile (default: all rectangular)."""
        arr = np.asarray(rows, dtype=np.float64)
        if arr.ndim != 2 or arr.shape[1] != 6:
            raise ValueError(f"rows: expected shape (n, 6), got {arr.shape}")
        tri = [False] * arr.shape[0] if triangle is None else [bool(t) for t in triangle]
        self = cls.__new__(cls)
        self._native = _native.NativeScratchSet.from_rows(np.ascontiguousarray(arr).reshape(-1), tri)
        return self

    def __len__(self) -> int:
        return len(self._native)


class Material:
    """A material as a scene file writes it (``docs/render.md``, "materials")::

        {"model": "werner" | "werner_blended" | "velinov" | "ghs", "sigma_um": ...,
         "material": ..., "options": ..., "scratches": [...], "base": ...}

    ``scratches`` (a :class:`ScratchSet`) replaces the ``"scratches"`` field, which the spec
    must then leave out. A rejected spec raises :class:`InputError` naming the field.
    """

    def __init__(
        self,
        spec: JsonLike,
        scratches: Optional[ScratchSet] = None,
        base_dir: Union[str, os.PathLike, None] = None,
    ):
        self._native = _native.NativeBsdf.from_json(
            _json_text(spec, "spec"),
            None if base_dir is None else str(base_dir),
            None if scratches is None else scratches._native,
        )

    @property
    def scratch_count(self) -> int:
        """Number of scratch segments."""
        return self._native.scratch_count()

    def _common(self, wo: Any, x_um: Any, footprint: Any, lambda_nm: Any):
        wo_f = _rows(wo, "wo", 3, None)
        n = wo_f.shape[0] // 3
        x = None if x_um is None else _rows(x_um, "x_um", 2, n)
        fp = None if footprint is None else _rows(footprint, "footprint", 3, n)
        lam, k = _lambdas(lambda_nm, n)
        return wo_f, n, x, fp, lam, k

    def eval(self, wo: Any, wi: Any, x_um: Any = None, footprint: Any = None, lambda_nm: Any = None) -> np.ndarray:
        """BRDF (1/sr, without the cosine), shape (n, k) for n queries and k wavelengths.

        ``wo``, ``wi``: (n, 3) local directions; ``x_um``: (n, 2) scratch-space positions
        (default the origin); ``footprint``: (n, 3) pixel footprints ``(a1, a2, angle)``
        (µm, µm, radians; the Velinov model averages over it; semi-axes in [1e-6, 1e9] µm,
        else ``ValueError``); ``lambda_nm``: (k,) shared
        or (n, k) per query, k ≤ 4 (default 700, 520, 440 nm).
        """
        wo_f, n, x, fp, lam, k = self._common(wo, x_um, footprint, lambda_nm)
        wi_f = _rows(wi, "wi", 3, n)
        out = self._native.eval(wo_f, wi_f, x, fp, lam, k)
        return out.reshape(n, -1) if n else out.reshape(0, k or 3)

    def pdf(self, wo: Any, wi: Any, x_um: Any = None, footprint: Any = None, lambda_nm: Any = None) -> np.ndarray:
        """Solid-angle pdf with which :meth:`sample` draws ``wi`` given ``wo``, shape (n,)."""
        wo_f, n, x, fp, lam, k = self._common(wo, x_um, footprint, lambda_nm)
        wi_f = _rows(wi, "wi", 3, n)
        return self._native.pdf(wo_f, wi_f, x, fp, lam, k)

    def sample(self, wo: Any, u: Any, x_um: Any = None, footprint: Any = None, lambda_nm: Any = None):
        """Draws ``wi`` given ``wo`` from ``u`` (n, 3) uniform numbers. Returns ``(wi, weight,
        pdf)``: (n, 3) directions, (n, k) weights ``f·cosθi/pdf`` and (n,) pdfs; all zero
        where nothing can be drawn."""
        wo_f, n, x, fp, lam, k = self._common(wo, x_um, footprint, lambda_nm)
        u_f = _rows(u, "u", 3, n)
        wi, w, p = self._native.sample(wo_f, u_f, x, fp, lam, k)
        return wi.reshape(n, 3), w.reshape(n, -1) if n else w.reshape(0, k or 3), p


def eval(material: Material, wo: Any, wi: Any, **kw: Any) -> np.ndarray:
    """:meth:`Material.eval`."""
    return material.eval(wo, wi, **kw)


def pdf(material: Material, wo: Any, wi: Any, **kw: Any) -> np.ndarray:
    """:meth:`Material.pdf`."""
    return material.pdf(wo, wi, **kw)


def sample(material: Material, wo: Any, u: Any, **kw: Any):
    """:meth:`Material.sample`."""
    return material.sample(wo, u, **kw)


def _scene_text(scene: Union[JsonLike, os.PathLike], base_dir) -> Tuple[str, str, str]:
    """(JSON text, name for messages, base directory) of a scene dict, text or file."""
    if isinstance(scene, (str, os.PathLike)) and not (isinstance(scene, str) and scene.lstrip().startswith("{")):
        path = Path(scene)
        text = path.read_text()
        return text, str(path), str(Path(base_dir) if base_dir else path.resolve().parent)
    return _json_text(scene, "scene"), "scene", str(Path(base_dir) if base_dir else Path.cwd())


def render(
    scene: Union[JsonLike, os.PathLike],
    backend: str = "cpu",
    region: Optional[Tuple[int, int, int, int]] = None,
    base_dir: Union[str, os.PathLike, None] = None,
    return_stats: bool = False,
):
    """Renders a scene (a dict, JSON text or a path to a scene file; ``docs/render.md``) and
    returns the linear RGB image, shape (height, width, 3), float32, rows from the top.

    ``backend``: ``"cpu"`` (the portable BVH) or ``"embree"``. ``region``: ``(x0, y0,
    width, height)`` renders only those pixels, bit-identical to that part of the whole
    image (:mod:`scratchwave.distributed` spreads tiles over a Dask cluster). Files named by
    the scene are relative to ``base_dir`` (default: the scene file's directory, or the
    working directory for a dict). ``return_stats``: also return a dict of ray and shading
    counts and times.
    """
    text, name, base = _scene_text(scene, base_dir)
    flat, w, h, stats = _native.render(text, name, base, backend, None if region is None else tuple(int(v) for v in region))
    img = flat.reshape(h, w, 3)
    return (img, stats) if return_stats else img


def table(spec: JsonLike, backend: str = "cpu") -> np.ndarray:
    """The values of a table spec (README, "Table spec"), exactly as ``scratchwave table
    SPEC --backend cpu`` prints them (bit for bit), as a float32 array in query order.
    ``backend``: ``"cpu"`` or ``"simd"``."""
    return _native.table(_json_text(spec, "spec"), backend)
