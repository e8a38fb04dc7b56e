"""The same scratched plane under a sphere light, rendered by scratchwave and by Mitsuba 3.

scratchwave renders it with its own renderer (``scratchwave.render``: Velinov's closed-form
integral over the sphere light, many pixel samples, no footprint); Mitsuba renders it with
its ``direct`` integrator (MIS of one emitter and one BSDF sample per camera sample), the
plane's BSDF being scratchwave's, called through the plugin ``scratchwave.mitsuba``.
Mitsuba renders K times with different seeds; per pixel and channel the mean, its standard
error and ``z = (scratchwave − mean)/stderr`` are reported as a markdown table, and
``scratchwave | Mitsuba mean | z map`` is written as a PNG.

Run (3–6 minutes on 2 cores)::

    python python/examples/mitsuba_compare.py --out docs/images/mitsuba_compare.png

Needs ``mitsuba`` (3.9, scalar_rgb variant) besides the scratchwave package.
"""

from __future__ import annotations

import argparse
import struct
import sys
import time
import zlib
from pathlib import Path

import numpy as np


PATTERNS = {
    # Long straight scratches (one segment each, longer than the plane): no segment ends
    # in view, where the closed-form light integral's infinite-scratch profile along the
    # scratch holds (the like-for-like comparison).
    "straight": {
        "seed": 7,
        "count": 70,
        "region": {"min": [-2500, -2500], "max": [2500, 2500]},
        "shape": {"type": "straight", "length": 12000},
        "orientation": {"type": "random"},
        "width": {"uniform": [0.8, 6]},
        "depth": {"uniform": [0.1, 0.6]},
    },
    # Arcs, split into chords: segment ends everywhere (see docs/mitsuba.md).
    "arcs": {
        "seed": 7,
        "density_per_mm2": 12,
        "region": {"min": [-3000, -3000], "max": [3000, 3000]},
        "shape": {"type": "arc", "radius": {"log_uniform": [600, 3000]}, "sweep_deg": {"uniform": [40, 120]}},
        "orientation": {"type": "random"},
        "width": {"uniform": [0.8, 6]},
        "depth": {"uniform": [0.1, 0.6]},
        "chord_tol_um": 0.5,
    },
}


def scene(width: int = 64, height: int = 48, spp: int = 256, pattern: str = "straight") -> dict:
    """The comparison scene (``docs/render.md`` format).

    A 6 × 6 mm plane of Velinov incoherent scratches (a seeded pattern, ``PATTERNS``:
    widths 0.8–6 µm, rectangular grooves, an aluminium-like conductor, no base, so only
    the scratches reflect) seen by an orthographic camera from 37° off the normal, lit by
    a sphere light placed off the mirror direction, so that the scratches light up where
    their cone of diffraction crosses it and the colour varies along them (iridescence).
    ``footprint: none`` makes scratchwave average the point model over the pixel, as
    Mitsuba's box filter does; ``shadows: all_nodes`` skips nothing (nothing occludes).
    """
    if pattern not in PATTERNS:
        raise ValueError(f"pattern: expected one of {sorted(PATTERNS)}, got {pattern!r}")
    return {
        "description": f"scratchwave vs Mitsuba 3: Velinov {pattern} scratches under a sphere light",
        "unit_um": 1000,
        "camera": {"type": "orthographic", "eye": [0, -3, 4], "target": [0, 0, 0], "up": [0, 0, 1],
                   "view_height": 3, "width_px": width, "height_px": height},
        "materials": {
            "scratched": {
                "model": "velinov", "sigma_um": 10, "material": {"ior": [1.2, 7.0]},
                "scratches": [{"generate": PATTERNS[pattern]}],
            }
        },
        "objects": [{"shape": "rectangle", "center": [0, 0, 0], "tangent": [1, 0, 0], "normal": [0, 0, 1],
                     "size": [6, 6], "material": "scratched"}],
        "lights": [{"type": "sphere", "center": [1.6, 2.4, 4.0], "radius": 0.6, "radiance": 1.0}],
        "spectrum": {"mode": "rgb"},
        "render": {"spp": spp, "footprint": "none", "shadows": "all_nodes"},
    }


def render_scratchwave(sc: dict) -> tuple:
    """(image, seconds) from scratchwave's own renderer."""
    import scratchwave as sw

    t0 = time.perf_counter()
    img = sw.render(sc, backend="cpu")
    return np.asarray(img, dtype=np.float64), time.perf_counter() - t0


def render_mitsuba(sc: dict, spp: int, seeds) -> tuple:
    """(stack of K images, seconds) from Mitsuba's ``direct`` integrator with the plugin."""
    import mitsuba as mi

    mi.set_variant("scalar_rgb")
    import scratchwave.mitsuba as swmi

    swmi.register()
    ms = mi.load_dict(swmi.scene_dict(sc, spp=spp))
    t0 = time.perf_counter()
    imgs = [np.array(mi.render(ms, seed=int(s)), dtype=np.float64) for s in seeds]
    return np.stack(imgs), time.perf_counter() - t0


def recheck_mitsuba(sc: dict, pixels, spp: int, seeds) -> dict:
    """Mitsuba again at single pixels (1×1 film crops), ``len(seeds)`` renders × ``spp``:
    {(x, y): (mean RGB, stderr RGB)}. Where a lobe crosses the light in only a small part
    of the pixel, the per-sample values are heavy-tailed (most are 0) and a few hundred
    samples mostly miss the rare large ones; many more samples settle it."""
    import mitsuba as mi
    import scratchwave.mitsuba as swmi

    out = {}
    for (x, y) in pixels:
        md = swmi.scene_dict(sc, spp=spp)
        md["sensor"]["film"].update({"crop_offset_x": int(x), "crop_offset_y": int(y), "crop_width": 1, "crop_height": 1})
        ms = mi.load_dict(md)
        imgs = np.stack([np.array(mi.render(ms, seed=int(s)), dtype=np.float64)[0, 0] for s in seeds])
        out[(int(x), int(y))] = (imgs.mean(axis=0), imgs.std(axis=0, ddof=1) / np.sqrt(len(seeds)))
    return out


def pixel_quadrature(sc: dict, x: int, y: int, n_pos: int = 8, n_dir: int = 300) -> np.ndarray:
    """An independent value of pixel (x, y), RGB, with neither renderer: the point BRDF
    ``scratchwave.Material.eval`` times cos θi integrated over the sphere light's cone by
    the midpoint rule in (cos α, φ) with ``n_dir``² nodes, averaged over ``n_pos``² points
    of the pixel square. For the orthographic camera and the single rectangle at z = 0
    with tangent x of :func:`scene`."""
    import scratchwave as sw

    cam = sc["camera"]
    w, h = cam["width_px"], cam["height_px"]
    eye, tgt, up = (np.array(cam[k], dtype=np.float64) for k in ("eye", "target", "up"))
    f = (tgt - eye) / np.linalg.norm(tgt - eye)
    r = np.cross(f, up)
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    vh = cam["view_height"]
    obj = sc["objects"][0]
    if obj["center"] != [0, 0, 0] or obj["tangent"] != [1, 0, 0] or obj["normal"] != [0, 0, 1]:
        raise ValueError("objects[0]: pixel_quadrature needs the plane z = 0 with tangent x")
    mat = sw.Material(sc["materials"][obj["material"]])
    light = sc["lights"][0]
    c, rad = np.array(light["center"], dtype=np.float64), float(light["radius"])
    total = np.zeros(3)
    grid = (np.arange(n_dir) + 0.5) / n_dir
    for a in range(n_pos):
        for b in range(n_pos):
            s = ((x + (a + 0.5) / n_pos) / w - 0.5) * vh * w / h
            t = (0.5 - (y + (b + 0.5) / n_pos) / h) * vh
            o = eye + s * r + t * u
            p = o + f * (-o[2] / f[2])
            d = c - p
            dist = np.linalg.norm(d)
            axis = d / dist
            cmax = np.sqrt(1 - (rad / dist) ** 2)
            e1 = np.cross(axis, [0.0, 0.0, 1.0])
            e1 /= np.linalg.norm(e1)
            e2 = np.cross(axis, e1)
            ca, ph = np.meshgrid(1 - grid * (1 - cmax), grid * 2 * np.pi, indexing="ij")
            sa = np.sqrt(1 - ca**2)
            wi = (ca[..., None] * axis + sa[..., None] * (np.cos(ph)[..., None] * e1 + np.sin(ph)[..., None] * e2)).reshape(-1, 3)
            n = wi.shape[0]
            fv = mat.eval(np.repeat(-f[None], n, axis=0), wi, x_um=np.repeat((p[:2] * sc.get("unit_um", 1000))[None], n, axis=0))
            total += (fv * np.maximum(wi[:, 2:3], 0)).sum(axis=0) * (1 - cmax) * 2 * np.pi / n_dir**2
    return total * float(light["radiance"]) / n_pos**2


def statistics(ref: np.ndarray, stack: np.ndarray, floor_rel: float = 1e-4) -> dict:
    """Per-pixel and per-channel mean, standard error and z of ``ref`` against the K
    images of ``stack`` (K, H, W, 3).

    Values (pixel × channel) where both ``ref`` and the Mitsuba mean are below
    ``floor_rel`` × the peak (the 99.5 % quantile of ``ref``) are not given a z: there the
    images hold only the far tails of the scratch lobes (down to 1e-25, where the Monte
    Carlo estimate is often exactly 0 and z is meaningless); their largest absolute
    difference is reported instead."""
    k = stack.shape[0]
    mean = stack.mean(axis=0)
    se = stack.std(axis=0, ddof=1) / np.sqrt(k)
    peak = float(np.quantile(ref, 0.995))
    floor = floor_rel * peak
    small = (ref < floor) & (mean < floor)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(se > 0, (ref - mean) / se, np.where(ref == mean, 0.0, np.inf))
    z = np.where(small, np.nan, z)
    zv = z[~small]
    mean_sw, mean_mi = ref.mean(), mean.mean()
    # The standard error of the image mean, from the K per-render image means.
    se_img = stack.mean(axis=(1, 2, 3)).std(ddof=1) / np.sqrt(k)
    order = np.argsort(-np.abs(np.nan_to_num(z, nan=0.0)), axis=None)[:6]
    worst = [np.unravel_index(i, z.shape) for i in order]
    # Pixels with a lit scratch (luminance above the floor): relative differences.
    rel = np.abs(ref - mean) / np.maximum(mean, floor)
    return {
        "k": k, "mean": mean, "se": se, "z": z, "zv": zv, "small": int(small.sum()), "peak": peak,
        "floor_rel": floor_rel, "small_max_abs": float(np.max(np.abs(ref - mean)[small], initial=0.0)),
        "mean_sw": mean_sw, "mean_mi": mean_mi, "se_img": se_img,
        "rel_mean": (mean_sw - mean_mi) / mean_mi,
        "rel_mean_rgb": (ref.mean(axis=(0, 1)) - mean.mean(axis=(0, 1))) / mean.mean(axis=(0, 1)),
        "frac3": float(np.mean(np.abs(zv) <= 3)), "frac2": float(np.mean(np.abs(zv) <= 2)),
        "quantiles": {q: float(np.quantile(zv, q)) for q in (0.01, 0.05, 0.25, 0.5, 0.75, 0.95, 0.99)},
        "rel_median": float(np.median(rel[~small])),
        "worst": worst,
    }


def table(ref: np.ndarray, st: dict, spp_sw: int, spp_mi: int, t_sw: float, t_mi: float, pattern: str = "straight",
          recheck: dict = None, recheck_spp: int = 0) -> str:
    """The markdown report."""
    h, w, _ = ref.shape
    q = st["quantiles"]
    rows = [
        "| quantity | value |",
        "|---|---|",
        f"| image | {w}×{h} px, RGB (700/520/440 nm), {pattern} scratches |",
        f"| scratchwave | `scratchwave.render`, spp {spp_sw}, footprint none, closed-form sphere light; {t_sw:.1f} s |",
        f"| Mitsuba | `direct` integrator, box filter, {st['k']} renders × {spp_mi} spp (seeds 1..{st['k']}); {t_mi:.0f} s |",
        f"| image mean, scratchwave | {st['mean_sw']:.6g} |",
        f"| image mean, Mitsuba | {st['mean_mi']:.6g} ± {st['se_img']:.2g} (standard error over the {st['k']} renders) |",
        f"| relative difference of the means | {st['rel_mean']:+.3%} ({st['rel_mean']*st['mean_mi']/st['se_img']:+.2f} standard errors) |",
        "| per channel R, G, B | " + ", ".join(f"{v:+.3%}" for v in st["rel_mean_rgb"]) + " |",
        f"| values compared (pixel × channel) | {st['zv'].size}; {st['small']} where both are below {st['floor_rel']:g} × the peak ({st['peak']:.3g}) left out, largest difference there {st['small_max_abs']:.2g} |",
        f"| z quantiles 1 %, 5 %, 25 %, 50 %, 75 %, 95 %, 99 % | {q[0.01]:.2f}, {q[0.05]:.2f}, {q[0.25]:.2f}, {q[0.5]:.2f}, {q[0.75]:.2f}, {q[0.95]:.2f}, {q[0.99]:.2f} |",
        f"| fraction with \\|z\\| ≤ 2 / ≤ 3 | {st['frac2']:.3f} / {st['frac3']:.3f} |",
        f"| median relative difference per value | {st['rel_median']:.2%} |",
        "",
        "Worst values (pixel x, y from the top left; channel):",
        "",
        f"| pixel | channel | scratchwave | Mitsuba mean ± stderr | z | Mitsuba, {recheck_spp} spp × {st['k']} | z |",
        "|---|---|---|---|---|---|---|",
    ]
    for (y, x, c) in st["worst"]:
        again = ""
        if recheck and (x, y) in recheck:
            m2, s2 = recheck[(x, y)]
            again = f"{m2[c]:.5g} ± {s2[c]:.2g} | {(ref[y, x, c] - m2[c]) / s2[c]:+.2f}"
        rows.append(
            f"| ({x}, {y}) | {'RGB'[c]} | {ref[y, x, c]:.5g} | {st['mean'][y, x, c]:.5g} ± {st['se'][y, x, c]:.2g} | {st['z'][y, x, c]:+.2f} | {again or '— | —'} |"
        )
    return "\n".join(rows)


def _tonemap(img: np.ndarray, scale: float) -> np.ndarray:
    v = np.clip(img * scale, 0.0, 1.0)
    v = np.where(v <= 0.0031308, 12.92 * v, 1.055 * np.power(v, 1 / 2.4) - 0.055)
    return (v * 255 + 0.5).astype(np.uint8)


def _zmap(z: np.ndarray, dark: np.ndarray) -> np.ndarray:
    """Largest-|z| channel per pixel on a blue (−4) – white (0) – red (+4) scale."""
    idx = np.argmax(np.abs(np.nan_to_num(z, posinf=1e9, neginf=-1e9)), axis=2)
    zz = np.take_along_axis(z, idx[..., None], axis=2)[..., 0]
    t = np.clip(np.nan_to_num(zz, posinf=4, neginf=-4) / 4, -1, 1)
    rgb = np.ones(zz.shape + (3,))
    pos, neg = t > 0, t < 0
    rgb[pos, 1] -= t[pos]
    rgb[pos, 2] -= t[pos]
    rgb[neg, 0] += t[neg]
    rgb[neg, 1] += t[neg]
    rgb[dark.all(axis=2)] = 0.85
    return (rgb * 255 + 0.5).astype(np.uint8)


def write_png(path: Path, rgb: np.ndarray) -> None:
    """An 8-bit RGB PNG (zlib + struct, no imaging library)."""
    h, w, _ = rgb.shape
    raw = b"".join(b"\x00" + rgb[y].tobytes() for y in range(h))

    def chunk(kind: bytes, data: bytes) -> bytes:
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF)

    png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0))
    png += chunk(b"IDAT", zlib.compress(raw, 9)) + chunk(b"IEND", b"")
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_bytes(png)


def side_by_side(ref: np.ndarray, st: dict, zoom: int = 4) -> np.ndarray:
    """``scratchwave | Mitsuba mean | z map``, each ``zoom``× (nearest), 4 px gaps."""
    scale = 1.0 / max(np.quantile(ref, 0.995), 1e-12)
    dark = np.isnan(st["z"])
    panels = [_tonemap(ref, scale), _tonemap(st["mean"], scale), _zmap(st["z"], dark)]
    panels = [np.repeat(np.repeat(p, zoom, axis=0), zoom, axis=1) for p in panels]
    gap = np.full((panels[0].shape[0], 4, 3), 255, np.uint8)
    return np.concatenate([panels[0], gap, panels[1], gap, panels[2]], axis=1)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--width", type=int, default=64)
    ap.add_argument("--height", type=int, default=48)
    ap.add_argument("--spp-scratchwave", type=int, default=256)
    ap.add_argument("--spp-mitsuba", type=int, default=64)
    ap.add_argument("--renders", type=int, default=8, help="Mitsuba renders (K >= 2), seeds 1..K")
    ap.add_argument("--pattern", choices=sorted(PATTERNS), default="straight")
    ap.add_argument("--recheck-spp", type=int, default=4096,
                    help="re-render the worst pixels alone with this many spp per render (0: skip)")
    ap.add_argument("--quadrature", nargs="*", default=[], metavar="X,Y",
                    help="also print these pixels by an independent quadrature of Material.eval over the light")
    ap.add_argument("--out", type=Path, default=None, help="side-by-side PNG")
    ap.add_argument("--save", type=Path, default=None, help="also save both images (.npz: scratchwave, mitsuba stack)")
    a = ap.parse_args(argv)
    if a.renders < 2:
        ap.error("--renders: need at least 2 for a standard error")
    sc = scene(a.width, a.height, a.spp_scratchwave, a.pattern)
    ref, t_sw = render_scratchwave(sc)
    stack, t_mi = render_mitsuba(sc, a.spp_mitsuba, range(1, a.renders + 1))
    if a.save is not None:
        np.savez_compressed(a.save, scratchwave=ref, mitsuba=stack)
    st = statistics(ref, stack)
    recheck = {}
    if a.recheck_spp > 0:
        recheck = recheck_mitsuba(sc, sorted({(int(x), int(y)) for (y, x, _) in st["worst"]}), a.recheck_spp,
                                  range(1, a.renders + 1))
    print(table(ref, st, a.spp_scratchwave, a.spp_mitsuba, t_sw, t_mi, a.pattern, recheck, a.recheck_spp))
    if a.quadrature:
        print("\n| pixel | quadrature R, G, B | scratchwave R, G, B | Mitsuba mean R, G, B |\n|---|---|---|---|")
        for xy in a.quadrature:
            x, y = (int(v) for v in xy.split(","))
            q = pixel_quadrature(sc, x, y)
            fmt = lambda v: ", ".join(f"{e:.4g}" for e in v)  # noqa: E731
            print(f"| ({x}, {y}) | {fmt(q)} | {fmt(ref[y, x])} | {fmt(st['mean'][y, x])} |")
    if a.out is not None:
        write_png(a.out, side_by_side(ref, st))
        print(f"\nwrote {a.out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
