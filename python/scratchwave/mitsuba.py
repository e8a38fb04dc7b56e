"""scratchwave's BSDFs as a Mitsuba 3 plugin.

``register()`` registers the BSDF ``"scratchwave"`` for the current Mitsuba variant (call
``mitsuba.set_variant`` first; scalar variants only, ``scalar_rgb`` or
``scalar_spectral``). Mitsuba is imported by this module alone: the rest of the package
does not need it.

Properties (``mitsuba.load_dict``)::

    {"type": "scratchwave",
     "material": <the material as JSON text, docs/render.md "materials">,
     "center": [x, y, z], "tangent": [x, y, z], "normal": [x, y, z],  # the planar object
     "unit_um": 1000.0,             # micrometres per scene unit (default 1000)
     "base_dir": "."}               # directory of {"file": ...} scratch sources

The scratch-space position of a hit is computed from ``si.p`` exactly as scratchwave's
rectangle does (``docs/render.md``, objects): the point ``center + a·tangent +
b·(normal × tangent)`` is at ``(a, b)·unit_um`` µm, with the local frame ``x = tangent``,
``y = normal × tangent``, ``z = normal``. Mitsuba's ``rectangle`` shape with ``to_world``
columns ``(tangent·su/2, (normal × tangent)·sv/2, normal, center)`` has exactly this
shading frame (``si.sh_frame``: ``s`` = normalised ``dp_du``, ``t = n × s``); when a hit's
shading frame differs (another shape, a flipped normal), directions are rotated from it
into the object's frame through world space.

Convention mapping (``docs/bsdf.md``): Mitsuba's ``si.wi`` (towards the camera) is
scratchwave's ``wo``; Mitsuba's ``wo`` argument (towards the light) is scratchwave's
``wi``. Mitsuba's ``eval`` includes the cosine foreshortening ``cos θ`` of the light
direction, scratchwave's does not; ``sample``'s weight ``f·cosθ/pdf`` is the same in both.
``sample`` passes ``(sample1, sample2.x, sample2.y)`` as scratchwave's ``u``. Only radiance
transport is supported (the models are not reciprocal; the particle tracer's importance
transport would need ``wi`` drawn given the light side).

RGB variants evaluate at 700, 520 and 440 nm into R, G and B (scratchwave's ``"rgb"``
spectrum mode); spectral variants at the ray's wavelengths ``si.wavelengths``.

Example::

    import json
    import mitsuba as mi
    mi.set_variant("scalar_rgb")
    import scratchwave.mitsuba as swmi
    swmi.register()
    bsdf = mi.load_dict({"type": "scratchwave",
                         "material": json.dumps({"model": "velinov", "sigma_um": 10,
                             "scratches": [{"p0": [-1000, 0], "p1": [1000, 0],
                                            "width": 2, "depth": 0.3}]}),
                         "center": [0, 0, 0], "tangent": [1, 0, 0], "normal": [0, 0, 1]})
"""

from __future__ import annotations

import json
from typing import Any, Sequence

import numpy as np

from . import Material

__all__ = ["register", "rectangle_to_world", "scene_dict", "PLUGIN_NAME"]

PLUGIN_NAME = "scratchwave"

# Frames whose axes differ by less than this (per component) are taken as equal.
_FRAME_TOL = 1e-5


def _vec3(value: Any, name: str) -> np.ndarray:
    """A property as a float64 3-vector; accepts lists, Mitsuba vectors/points and
    whitespace- or comma-separated text. Errors name the property."""
    if isinstance(value, str):
        parts = value.replace(",", " ").split()
        try:
            arr = np.array([float(p) for p in parts], dtype=np.float64)
        except ValueError:
            raise ValueError(f"{name}: expected three numbers, got {value!r}") from None
    else:
        try:
            arr = np.array([float(value[0]), float(value[1]), float(value[2])], dtype=np.float64)
            if len(value) != 3:
                raise ValueError
        except (TypeError, IndexError, ValueError):
            raise ValueError(f"{name}: expected three numbers, got {value!r}") from None
    if arr.shape != (3,) or not np.all(np.isfinite(arr)):
        raise ValueError(f"{name}: expected three finite numbers, got {value!r}")
    return arr


def _object_frame(tangent: np.ndarray, normal: np.ndarray):
    """(x, y, z) of the object's shading frame, as scratchwave's rectangle builds it."""
    nt, nn = np.linalg.norm(tangent), np.linalg.norm(normal)
    if nt == 0.0:
        raise ValueError("tangent: must not be zero")
    if nn == 0.0:
        raise ValueError("normal: must not be zero")
    t, n = tangent / nt, normal / nn
    if abs(float(np.dot(t, n))) > 1e-4:
        raise ValueError(f"tangent: must be perpendicular to normal (|dot| <= 1e-4), got dot {float(np.dot(t, n)):.3g}")
    return t, np.cross(n, t), n


def rectangle_to_world(center: Sequence[float], tangent: Sequence[float], normal: Sequence[float], size: Sequence[float]) -> list:
    """The 4×4 ``to_world`` matrix (nested lists) of Mitsuba's ``rectangle`` shape (the
    square [-1, 1]² in xy, normal +z) that makes scratchwave's rectangle ``{"center",
    "tangent", "normal", "size": [su, sv]}``: columns ``tangent·su/2``, ``(normal ×
    tangent)·sv/2``, ``normal`` and ``center``. Its hits then have ``si.sh_frame`` equal to
    the scratchwave frame (checked by ``python/tests/test_mitsuba.py``)."""
    c = _vec3(center, "center")
    x, y, z = _object_frame(_vec3(tangent, "tangent"), _vec3(normal, "normal"))
    if len(size) != 2 or not all(float(s) > 0 for s in size):
        raise ValueError(f"size: expected two positive numbers, got {size!r}")
    m = np.eye(4)
    m[:3, 0] = x * float(size[0]) / 2
    m[:3, 1] = y * float(size[1]) / 2
    m[:3, 2] = z
    m[:3, 3] = c
    return m.tolist()


def _make_class(mi):
    """The BSDF class for the current variant (``mi.BSDF`` depends on it)."""
    variant = mi.variant()
    if variant is None or not variant.startswith("scalar_") or "polarized" in variant:
        raise RuntimeError(
            f"scratchwave.mitsuba: variant {variant!r} is not supported; use scalar_rgb or "
            "scalar_spectral (the plugin evaluates one query per call)"
        )
    spectral = "spectral" in variant
    flags = mi.BSDFFlags.GlossyReflection | mi.BSDFFlags.FrontSide

    class ScratchwaveBSDF(mi.BSDF):
        """scratchwave's material on a planar object, as a Mitsuba BSDF."""

        def __init__(self, props):
            mi.BSDF.__init__(self, props)
            if "material" not in props:
                raise ValueError("material: required (the material JSON text)")
            text = props["material"]
            if not isinstance(text, str):
                raise ValueError(f"material: expected JSON text, got {type(text).__name__}")
            base_dir = props["base_dir"] if "base_dir" in props else None
            self._spec = text
            self._material = Material(text, base_dir=base_dir)
            try:
                self._model = json.loads(text).get("model", "?")
            except (ValueError, AttributeError):
                self._model = "?"
            self._center = _vec3(props["center"] if "center" in props else [0, 0, 0], "center")
            tangent = _vec3(props["tangent"] if "tangent" in props else [1, 0, 0], "tangent")
            normal = _vec3(props["normal"] if "normal" in props else [0, 0, 1], "normal")
            self._x, self._y, self._z = _object_frame(tangent, normal)
            self._unit_um = float(props["unit_um"]) if "unit_um" in props else 1000.0
            if not (np.isfinite(self._unit_um) and self._unit_um > 0):
                raise ValueError(f"unit_um: must be positive, got {self._unit_um}")
            self.m_flags = flags
            self.m_components = [flags]

        # --- helpers -------------------------------------------------------------------

        def _query(self, si):
            """(same_frame, x_um, lambda_nm or None) of an interaction."""
            s, n = si.sh_frame.s, si.sh_frame.n
            same = (
                abs(s[0] - self._x[0]) < _FRAME_TOL and abs(s[1] - self._x[1]) < _FRAME_TOL
                and abs(s[2] - self._x[2]) < _FRAME_TOL and abs(n[0] - self._z[0]) < _FRAME_TOL
                and abs(n[1] - self._z[1]) < _FRAME_TOL and abs(n[2] - self._z[2]) < _FRAME_TOL
            )
            d = np.array([si.p[0], si.p[1], si.p[2]], dtype=np.float64) - self._center
            x_um = np.array([[np.dot(d, self._x) * self._unit_um, np.dot(d, self._y) * self._unit_um]])
            lam = None
            if spectral:
                lam = np.array([si.wavelengths[i] for i in range(len(si.wavelengths))], dtype=np.float32)
            return same, x_um, lam

        def _to_sw(self, si, v, same):
            """A direction in Mitsuba's local frame as a (1, 3) array in scratchwave's."""
            if same:
                return np.array([[v[0], v[1], v[2]]], dtype=np.float32)
            w = si.sh_frame.to_world(v)
            w = np.array([w[0], w[1], w[2]], dtype=np.float64)
            return np.array([[np.dot(w, self._x), np.dot(w, self._y), np.dot(w, self._z)]], dtype=np.float32)

        def _from_sw(self, si, v, same):
            """A scratchwave local direction (3,) as a Mitsuba local ``Vector3f``."""
            if same:
                return mi.Vector3f(float(v[0]), float(v[1]), float(v[2]))
            w = v[0] * self._x + v[1] * self._y + v[2] * self._z
            return si.sh_frame.to_local(mi.Vector3f(float(w[0]), float(w[1]), float(w[2])))

        @staticmethod
        def _spectrum(values):
            return mi.Spectrum(*[float(v) for v in values])

        def _enabled(self, ctx):
            if ctx.mode != mi.TransportMode.Radiance:
                raise RuntimeError("scratchwave BSDF: only radiance transport is supported (not the particle tracer)")
            return ctx.is_enabled(mi.BSDFFlags.GlossyReflection)

        # --- the BSDF interface ----------------------------------------------------------

        def eval(self, ctx, si, wo, active=True):
            """BRDF × cos θ of ``wo`` (towards the light), ``si.wi`` towards the camera."""
            if not self._enabled(ctx) or si.wi[2] <= 0 or wo[2] <= 0:
                return mi.Spectrum(0.0)
            same, x_um, lam = self._query(si)
            sw_wi = self._to_sw(si, wo, same)
            f = self._material.eval(self._to_sw(si, si.wi, same), sw_wi, x_um=x_um, lambda_nm=lam)[0]
            return self._spectrum(f * float(wo[2] if same else sw_wi[0, 2]))

        def pdf(self, ctx, si, wo, active=True):
            """Solid-angle pdf with which :meth:`sample` draws ``wo``."""
            if not self._enabled(ctx) or si.wi[2] <= 0 or wo[2] <= 0:
                return 0.0
            same, x_um, lam = self._query(si)
            p = self._material.pdf(self._to_sw(si, si.wi, same), self._to_sw(si, wo, same), x_um=x_um, lambda_nm=lam)
            return float(p[0])

        def eval_pdf(self, ctx, si, wo, active=True):
            """``(eval, pdf)`` in one call."""
            if not self._enabled(ctx) or si.wi[2] <= 0 or wo[2] <= 0:
                return mi.Spectrum(0.0), 0.0
            same, x_um, lam = self._query(si)
            sw_wo, sw_wi = self._to_sw(si, si.wi, same), self._to_sw(si, wo, same)
            f = self._material.eval(sw_wo, sw_wi, x_um=x_um, lambda_nm=lam)[0]
            p = self._material.pdf(sw_wo, sw_wi, x_um=x_um, lambda_nm=lam)
            return self._spectrum(f * float(wo[2] if same else sw_wi[0, 2])), float(p[0])

        def sample(self, ctx, si, sample1, sample2, active=True):
            """Draws the light direction given ``si.wi``: ``(BSDFSample3f, f·cosθ/pdf)``."""
            bs = mi.BSDFSample3f()
            if not self._enabled(ctx) or si.wi[2] <= 0:
                return bs, mi.Spectrum(0.0)
            same, x_um, lam = self._query(si)
            u = np.array([[sample1, sample2[0], sample2[1]]], dtype=np.float32)
            wi, weight, pdf = self._material.sample(self._to_sw(si, si.wi, same), u, x_um=x_um, lambda_nm=lam)
            if not pdf[0] > 0:
                return bs, mi.Spectrum(0.0)
            bs.wo = self._from_sw(si, wi[0], same)
            if bs.wo[2] <= 0:
                return mi.BSDFSample3f(), mi.Spectrum(0.0)
            bs.pdf = float(pdf[0])
            bs.eta = 1.0
            bs.sampled_type = int(mi.BSDFFlags.GlossyReflection)
            bs.sampled_component = 0
            return bs, self._spectrum(weight[0])

        def traverse(self, callback):
            pass

        def parameters_changed(self, keys):
            pass

        def to_string(self):
            c, x, z = self._center, self._x, self._z
            return (
                f"ScratchwaveBSDF[model={self._model!r}, scratches={self._material.scratch_count}, "
                f"center=[{c[0]:g}, {c[1]:g}, {c[2]:g}], tangent=[{x[0]:g}, {x[1]:g}, {x[2]:g}], "
                f"normal=[{z[0]:g}, {z[1]:g}, {z[2]:g}], unit_um={self._unit_um:g}]"
            )

    return ScratchwaveBSDF


def register(name: str = PLUGIN_NAME):
    """Registers the BSDF plugin ``name`` (default ``"scratchwave"``) for Mitsuba's current
    variant and returns its class. Call after ``mitsuba.set_variant``; call again after
    switching variants."""
    import mitsuba as mi

    cls = _make_class(mi)
    mi.register_bsdf(name, lambda props: cls(props))
    return cls


def _camera_to_world(mi, cam: dict):
    """Mitsuba sensor ``to_world`` and field of view for a scratchwave camera."""
    eye, target, up = (_vec3(cam[k], f"camera.{k}") for k in ("eye", "target", "up"))
    w, h = int(cam["width_px"]), int(cam["height_px"])
    look = mi.ScalarTransform4f().look_at(origin=eye.tolist(), target=target.tolist(), up=up.tolist())
    if cam.get("type") == "orthographic":
        # Mitsuba's orthographic camera sees [-1, 1] across the width in camera space.
        half_w = float(cam["view_height"]) * w / h / 2
        return {"type": "orthographic", "to_world": look @ mi.ScalarTransform4f().scale([half_w, half_w, 1.0])}
    if cam.get("type") == "perspective":
        return {"type": "perspective", "to_world": look, "fov": float(cam["fov_y_deg"]), "fov_axis": "y"}
    raise ValueError(f"camera.type: expected \"orthographic\" or \"perspective\", got {cam.get('type')!r}")


def scene_dict(scene: dict, spp: int = 16, integrator: Any = None, base_dir: Any = None) -> dict:
    """A Mitsuba ``load_dict`` scene for a scratchwave scene dict (``docs/render.md``).

    Supported: an ``orthographic`` or ``perspective`` camera (a box-filtered ``hdrfilm``,
    linear RGB, ``independent`` sampler with ``spp`` samples), ``rectangle`` objects whose
    material is any scratchwave material (this plugin), ``sphere`` lights (Mitsuba
    ``sphere`` shapes with an ``area`` emitter of the same radiance at every wavelength) and
    the ``"rgb"`` spectrum mode (the default). Anything else raises ``ValueError`` naming the
    field. ``integrator``: a Mitsuba integrator dict (default ``{"type": "direct"}``:
    one emitter and one BSDF sample per camera sample, combined by MIS). Register the
    plugin first (:func:`register`)."""
    import mitsuba as mi

    if not isinstance(spp, int) or spp < 1:
        raise ValueError(f"spp: expected a positive integer, got {spp!r}")
    spectrum = scene.get("spectrum", {"mode": "rgb"})
    if spectrum.get("mode") != "rgb":
        raise ValueError(f"spectrum.mode: only \"rgb\" is converted, got {spectrum.get('mode')!r}")
    cam = scene["camera"]
    sensor = _camera_to_world(mi, cam)
    sensor["film"] = {
        "type": "hdrfilm",
        "width": int(cam["width_px"]),
        "height": int(cam["height_px"]),
        "rfilter": {"type": "box"},
        "pixel_format": "rgb",
        "component_format": "float32",
    }
    sensor["sampler"] = {"type": "independent", "sample_count": spp}
    out = {"type": "scene", "integrator": integrator or {"type": "direct"}, "sensor": sensor}
    unit_um = float(scene.get("unit_um", 1000.0))
    materials = scene["materials"]
    for i, obj in enumerate(scene["objects"]):
        if obj.get("shape") != "rectangle":
            raise ValueError(f"objects[{i}].shape: only \"rectangle\" is converted, got {obj.get('shape')!r}")
        name = obj["material"]
        if name not in materials:
            raise ValueError(f"objects[{i}].material: no material {name!r}")
        bsdf = {
            "type": PLUGIN_NAME,
            "material": json.dumps(materials[name]),
            "center": list(map(float, obj["center"])),
            "tangent": list(map(float, obj["tangent"])),
            "normal": list(map(float, obj["normal"])),
            "unit_um": unit_um,
        }
        if base_dir is not None:
            bsdf["base_dir"] = str(base_dir)
        out[f"object_{i}"] = {
            "type": "rectangle",
            "to_world": mi.ScalarTransform4f(rectangle_to_world(obj["center"], obj["tangent"], obj["normal"], obj["size"])),
            "bsdf": bsdf,
        }
    for i, light in enumerate(scene["lights"]):
        if light.get("type") != "sphere":
            raise ValueError(f"lights[{i}].type: only \"sphere\" is converted, got {light.get('type')!r}")
        L = float(light["radiance"])
        out[f"light_{i}"] = {
            "type": "sphere",
            "center": list(map(float, light["center"])),
            "radius": float(light["radius"]),
            "emitter": {"type": "area", "radiance": {"type": "rgb", "value": [L, L, L]}},
        }
    return out
