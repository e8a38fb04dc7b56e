"""The Mitsuba 3 plugin (scratchwave.mitsuba) against scratchwave.Material and the renderer.

Skipped when mitsuba is not importable. Run: ``pip install mitsuba==3.9.1`` into the test
environment, then ``python -m pytest python/tests/test_mitsuba.py``.
"""

import importlib.util
import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

mi = pytest.importorskip("mitsuba")

import scratchwave as sw  # noqa: E402

mi.set_variant("scalar_rgb")
import scratchwave.mitsuba as swmi  # noqa: E402

swmi.register()

MATERIAL = {
    "model": "velinov",
    "sigma_um": 10,
    "material": {"ior": [1.2, 7.0]},
    "scratches": [
        {"p0": [-1500, -20], "p1": [1500, 30], "width": 3, "depth": 0.4},
        {"p0": [-40, -1500], "p1": [60, 1500], "width": 5, "depth": 0.3, "profile": "triangle"},
        {"p0": [-1200, 900], "p1": [1300, -800], "width": 2, "depth": 0.5},
    ],
}
# A tilted, rotated rectangle (scene units mm).
CENTER = [0.3, -0.2, 0.1]
NORMAL = list(np.array([0.2, -0.1, 1.0]) / np.linalg.norm([0.2, -0.1, 1.0]))
_t = np.cross([0.0, 0.0, 1.0], NORMAL) + np.array([0.9, 0.5, 0.0])
_t -= np.dot(_t, NORMAL) * np.array(NORMAL)
TANGENT = list(_t / np.linalg.norm(_t))
UNIT_UM = 1000.0


def _load_plane(tangent_prop=TANGENT):
    """A scene holding the rectangle; the plugin told ``tangent_prop`` as its tangent."""
    return mi.load_dict({
        "type": "scene",
        "plane": {
            "type": "rectangle",
            "to_world": mi.ScalarTransform4f(swmi.rectangle_to_world(CENTER, TANGENT, NORMAL, [4, 4])),
            "bsdf": {"type": "scratchwave", "material": json.dumps(MATERIAL), "center": CENTER,
                     "tangent": list(tangent_prop), "normal": NORMAL, "unit_um": UNIT_UM},
        },
    })


def _hits(scene, n=6, seed=3):
    """Surface interactions of rays from above at points near the scratches."""
    rng = np.random.default_rng(seed)
    c, nrm, t = np.array(CENTER), np.array(NORMAL), np.array(TANGENT)
    b = np.cross(nrm, t)
    out = []
    for _ in range(n):
        # Within ~30 µm of a scratch, so the BRDF is not negligible.
        a, bb = rng.uniform(-1.0, 1.0), rng.uniform(-0.03, 0.03)
        target = c + a * t + bb * b
        origin = target + 2.0 * nrm + 0.3 * t
        d = (target - origin) / np.linalg.norm(target - origin)
        si = scene.ray_intersect(mi.Ray3f(mi.Point3f(*origin), mi.Vector3f(*d)))
        assert si.is_valid()
        out.append(si)
    return out


def _x_um(si):
    d = np.array([si.p[0], si.p[1], si.p[2]], dtype=np.float64) - np.array(CENTER)
    t = np.array(TANGENT)
    b = np.cross(np.array(NORMAL), t)
    return np.array([[np.dot(d, t) * UNIT_UM, np.dot(d, b) * UNIT_UM]])


def _directions(rng, n):
    """Unit directions in the upper hemisphere, some near the scratch cones."""
    v = rng.normal(size=(n, 3))
    v[:, 2] = np.abs(v[:, 2]) + 0.2
    return v / np.linalg.norm(v, axis=1, keepdims=True)


def _arr(v):
    return np.array([v[0], v[1], v[2]], dtype=np.float64)


def test_frames_agree():
    """Mitsuba's shading frame of the rectangle is scratchwave's: s = tangent, t = n × s."""
    scene = _load_plane()
    for si in _hits(scene):
        assert np.allclose(_arr(si.sh_frame.n), NORMAL, atol=1e-6)
        assert np.allclose(_arr(si.sh_frame.s), TANGENT, atol=1e-6)
        assert np.allclose(_arr(si.sh_frame.t), np.cross(NORMAL, TANGENT), atol=1e-6)
        # The hit lies on the plane, inside the rectangle.
        x = _x_um(si)[0]
        assert abs(np.dot(_arr(si.p) - CENTER, NORMAL)) < 1e-6 and np.all(np.abs(x) <= 2000.0)


def test_eval_pdf_sample_equal_material():
    """eval = Material.eval·cosθ (Mitsuba's wo = scratchwave's wi), pdf and sample equal,
    bit for bit in the rectangle's own frame."""
    scene = _load_plane()
    bsdf = scene.shapes()[0].bsdf()
    m = sw.Material(MATERIAL)
    ctx = mi.BSDFContext()
    rng = np.random.default_rng(5)
    nonzero = 0
    for si in _hits(scene):
        x = _x_um(si)
        # Random pairs (mostly off the narrow scratch lobes), then light directions drawn
        # by the material itself (on its lobes).
        wos = _directions(rng, 8)
        drawn, _, p_drawn = m.sample(wos[4:], rng.random((4, 3)), x_um=np.repeat(x, 4, axis=0))
        lights = np.concatenate([_directions(rng, 4), np.where(p_drawn[:, None] > 0, drawn, _directions(rng, 4))])
        for wo_sw, wi_sw in zip(wos, lights):
            si.wi = mi.Vector3f(*wo_sw)
            wo_mi = mi.Vector3f(*wi_sw)
            f_ref = m.eval(np.array([_arr(si.wi)]), np.array([_arr(wo_mi)]), x_um=x)[0]
            p_ref = m.pdf(np.array([_arr(si.wi)]), np.array([_arr(wo_mi)]), x_um=x)[0]
            f = _arr(bsdf.eval(ctx, si, wo_mi))
            p = bsdf.pdf(ctx, si, wo_mi)
            f2, p2 = bsdf.eval_pdf(ctx, si, wo_mi)
            expect = (f_ref * np.float32(wo_mi[2])).astype(np.float64)
            np.testing.assert_array_equal(f, expect)
            np.testing.assert_array_equal(_arr(f2), f)
            assert p == pytest.approx(float(p_ref), rel=1e-7, abs=0) and p2 == p
            nonzero += bool(np.any(f > 0))
            # Below the horizon on either side: zero.
            below = mi.Vector3f(wi_sw[0], wi_sw[1], -wi_sw[2])
            assert np.all(_arr(bsdf.eval(ctx, si, below)) == 0) and bsdf.pdf(ctx, si, below) == 0
        # Sampling: the plugin's (sample1, sample2) are scratchwave's u.
        si.wi = mi.Vector3f(*wos[0])
        for u in rng.random((8, 3)):
            bs, w = bsdf.sample(ctx, si, float(u[0]), mi.Point2f(float(u[1]), float(u[2])))
            wi_ref, w_ref, p_ref = m.sample(np.array([_arr(si.wi)]), u[None, :].astype(np.float32), x_um=x)
            if p_ref[0] > 0:
                np.testing.assert_array_equal(_arr(bs.wo), wi_ref[0].astype(np.float64))
                np.testing.assert_array_equal(_arr(w), w_ref[0].astype(np.float64))
                assert bs.pdf == float(p_ref[0])
                assert bs.sampled_type == int(mi.BSDFFlags.GlossyReflection)
                # Mitsuba's identity: weight = eval/pdf at the sampled direction.
                np.testing.assert_allclose(_arr(bsdf.eval(ctx, si, bs.wo)) / bsdf.pdf(ctx, si, bs.wo), _arr(w), rtol=2e-3)
            else:
                assert bs.pdf == 0 and np.all(_arr(w) == 0)
    assert nonzero >= 12, "too few queries reach a scratch lobe to test anything"


def test_rotated_frame_goes_through_world_space():
    """A plugin told another tangent than the shape's dp_du rotates directions into its
    own frame; values equal Material at the rotated directions (to float32 rounding)."""
    ang = math.radians(30)
    t, n = np.array(TANGENT), np.array(NORMAL)
    t2 = math.cos(ang) * t + math.sin(ang) * np.cross(n, t)
    scene = _load_plane(tangent_prop=t2)
    bsdf = scene.shapes()[0].bsdf()
    m = sw.Material(MATERIAL)
    ctx = mi.BSDFContext()
    b2 = np.cross(n, t2)
    rng = np.random.default_rng(9)
    compared = 0
    for si in _hits(scene, n=4):
        d = _arr(si.p) - np.array(CENTER)
        x = np.array([[np.dot(d, t2) * UNIT_UM, np.dot(d, b2) * UNIT_UM]])

        def to2(v):
            w = _arr(si.sh_frame.to_world(v))
            return np.array([[np.dot(w, t2), np.dot(w, b2), np.dot(w, n)]])

        for wo_sw, wi_sw in zip(_directions(rng, 6), _directions(rng, 6)):
            si.wi = mi.Vector3f(*wo_sw)
            wo_mi = mi.Vector3f(*wi_sw)
            a, bb = to2(si.wi), to2(wo_mi)
            expect = m.eval(a, bb, x_um=x)[0] * bb[0, 2]
            np.testing.assert_allclose(_arr(bsdf.eval(ctx, si, wo_mi)), expect, rtol=2e-3, atol=1e-6 * max(expect.max(), 1e-30))
            compared += 1
        bs, w = bsdf.sample(ctx, si, 0.3, mi.Point2f(0.6, 0.2))
        if bs.pdf > 0:
            assert abs(np.linalg.norm(_arr(bs.wo)) - 1) < 1e-5 and bs.wo[2] > 0
    assert compared == 24


def test_bad_properties_are_named():
    with pytest.raises(Exception, match="material"):
        mi.load_dict({"type": "scratchwave", "center": [0, 0, 0]})
    with pytest.raises(Exception, match="tangent"):
        mi.load_dict({"type": "scratchwave", "material": json.dumps(MATERIAL), "tangent": [0, 0, 1], "normal": [0, 0, 1]})
    with pytest.raises(Exception, match="unit_um"):
        mi.load_dict({"type": "scratchwave", "material": json.dumps(MATERIAL), "unit_um": -1.0})
    s = str(mi.load_dict({"type": "scratchwave", "material": json.dumps(MATERIAL)}))
    assert "velinov" in s and "scratches=3" in s


def _example():
    path = Path(__file__).resolve().parents[1] / "examples" / "mitsuba_compare.py"
    spec = importlib.util.spec_from_file_location("mitsuba_compare", path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules["mitsuba_compare"] = mod
    spec.loader.exec_module(mod)
    return mod


def test_tiny_render_mean_matches_scratchwave():
    """16×12 px of the comparison scene: Mitsuba's image mean (direct integrator, MIS over
    the plugin's sample/pdf and the sphere light; 4 renders × 64 spp) is within TOL of
    scratchwave's (closed-form light integral, 64 spp)."""
    ex = _example()
    sc = ex.scene(16, 12, spp=64)
    ref, _ = ex.render_scratchwave(sc)
    stack, _ = ex.render_mitsuba(sc, spp=64, seeds=[1, 2, 3, 4])
    mean = stack.mean()
    se = stack.mean(axis=(1, 2, 3)).std(ddof=1) / math.sqrt(stack.shape[0])
    assert ref.mean() > 0 and mean > 0
    rel = abs(ref.mean() - mean) / mean
    assert rel < TOL, f"image mean: scratchwave {ref.mean():.6g}, Mitsuba {mean:.6g} ± {se:.2g} ({rel:.2%})"
    _same_layout(ref, stack.mean(axis=0))


def _same_layout(ref, mean):
    """Row and column profiles agree (a mirrored or shifted camera would not)."""
    for axis in ((1, 2), (0, 2)):
        a, b = ref.sum(axis=axis), mean.sum(axis=axis)
        assert np.argmax(a) == np.argmax(b), (a, b)
        assert np.corrcoef(a, b)[0, 1] > 0.95, (a, b)


def test_tiny_render_perspective_camera():
    """scene_dict's perspective sensor (fov_axis y) frames the image as scratchwave's
    perspective camera: image mean within TOL, same row and column profiles."""
    ex = _example()
    sc = ex.scene(16, 12, spp=64)
    sc["camera"] = {"type": "perspective", "eye": [0, -3, 4], "target": [0.5, 0, 0], "up": [0, 0, 1],
                    "fov_y_deg": 40, "width_px": 16, "height_px": 12}
    ref, _ = ex.render_scratchwave(sc)
    stack, _ = ex.render_mitsuba(sc, spp=64, seeds=[1, 2, 3, 4])
    rel = abs(ref.mean() - stack.mean()) / stack.mean()
    assert rel < TOL, f"image mean: scratchwave {ref.mean():.6g}, Mitsuba {stack.mean():.6g} ({rel:.2%})"
    _same_layout(ref, stack.mean(axis=0))


# Relative tolerance of the tiny render's image mean. Measured: over five groups of four
# seeds the relative difference had a standard deviation of 3.2 % (max 6.1 %; seeds 1-4:
# +2.2 %), so 10 % is about 3 standard deviations; Mitsuba is deterministic for fixed
# seeds. Measured with deliberately broken plugins: swapping the scratch-space axes moves
# the mean by +46 % (caught here); dropping the cosine from eval (-1.3 %) or swapping wo
# and wi in eval (+2.2 %) is not caught by this mean (MIS leans on the BSDF samples, and
# this Velinov material is nearly reciprocal) but by test_eval_pdf_sample_equal_material.
TOL = 0.10


_SPECTRAL = r"""
import json, sys
import numpy as np
import mitsuba as mi
mi.set_variant("scalar_spectral")
import scratchwave as sw
import scratchwave.mitsuba as swmi
swmi.register()
M = {"model": "velinov", "sigma_um": 10,
     "scratches": [{"p0": [-1000, 0], "p1": [1000, 0], "width": 3, "depth": 0.4}]}
scene = mi.load_dict({"type": "scene", "p": {"type": "rectangle",
                      "bsdf": {"type": "scratchwave", "material": json.dumps(M)}}})
si = scene.ray_intersect(mi.Ray3f(mi.Point3f(0.1, 0.000005, 1), mi.Vector3f(0, 0, -1)))
si.wavelengths = mi.Spectrum(450, 500, 600, 700)
si.wi = mi.Vector3f(0.3, 0.1, 0.9487)
wo = mi.Vector3f(-0.3, 0.3, 0.9055)
f = np.array(scene.shapes()[0].bsdf().eval(mi.BSDFContext(), si, wo), dtype=np.float32)
x = np.array([[si.p[0] * 1000.0, si.p[1] * 1000.0]])
ref = sw.Material(M).eval([[si.wi[0], si.wi[1], si.wi[2]]], [[wo[0], wo[1], wo[2]]], x_um=x,
                          lambda_nm=[450, 500, 600, 700])[0] * np.float32(wo[2])
assert f.shape == (4,) and np.all(f > 0), f
np.testing.assert_array_equal(f, ref)
print("ok")
"""


def test_spectral_variant_uses_ray_wavelengths():
    """In scalar_spectral the plugin evaluates at si.wavelengths (own process: the variant
    is global)."""
    import subprocess

    r = subprocess.run([sys.executable, "-c", _SPECTRAL], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and r.stdout.strip() == "ok", r.stderr[-2000:]
