#!/usr/bin/env python3
"""Writes reference/golden/heightfield.json (issue #21): Werner's BRDF from the heightfield
integral (reference/heightfield.py) in four variants, window frozen|exact x crossings
summed|deepest, for single grooves and crossing pairs, at f32 inputs as the kernel's
TableQuery / Scratch take them.

Cases (sigma = 10 um, lambda = 550 nm, depth_term exact, material ior (0.2, 3.0) theta_d):
  single    W/sigma in {0.05, 0.1, 0.3, 0.6, 1.0} x {rect, triangle} x centre line offset
            from the window centre {0, 1, 2} sigma x theta_i in {0, 30, 60, 80} deg;
            D = 0.2 um, length 1 mm (>> sigma)                                  (120 cases)
  finite    the same with length 2 sigma (comparable to sigma), W/sigma in {0.3, 1.0},
            offset {0, 1} sigma, theta_i in {0, 60} deg                          (16 cases)
  crossing  two 1 mm grooves W = 3 um crossing at 90, 45, 10 deg, 2 um from the window
            centre, depths (0.2, 0.2) or (0.2, 0.1) um, rect or triangle,
            theta_i in {0, 30} deg                                               (24 cases)
  wide      two 1 mm grooves W = 50 um (the widest the domain sweeps certify) crossing at
            45 deg, at lambda = 360 nm (the shortest) and theta_i = 60 deg: rect with
            depths (0.2, 0.1) um and triangle with (2, 1) um, so that the phase along and
            across the overlap's slabs reaches ~1 000 - 2 000 rad (the kernel's panel cap,
            `MAX_PANELS` in kernel/src/scratch/crossing.rs; at 90 deg each slab is square
            and its phase is taken in closed form across it); the "m", "d" and "e"
            directions only, every second one (the 2-D quadrature of a 50 um overlap is
            what costs here)                                                      (2 cases)
Directions per case: the mirror (set "m"), each groove's diffraction line xi.t = 0 and the
parallel line xi.t = 1/(2 pi sigma) ("d", "e"), a 5 x 5 grid of xi around the mirror
(+-0.06/um, "g") and wo_xy on a 5 x 5 grid over [-0.8, 0.8]^2 ("h"); wo_z >= 0.01.

Usage:
  python3 reference/heightfield_golden.py           # all cases (~4 min CPU for all but the 2 wide
                                                    # ones, ~12 min each; 25 min wall on 2 shared cores)
  python3 reference/heightfield_golden.py --limit N # the first N cases only (a dry run)
"""
import argparse
import json
import math
import os
import sys
import time

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import heightfield as hf  # noqa: E402

OUT = os.path.join(HERE, "golden", "heightfield.json")
SIGMA = 10.0
LAMBDA_NM = 550.0
WIDE_LAMBDA_NM = 360.0
MATERIAL = {"ior": [0.2, 3.0], "fresnel_angle": "theta_d"}
DEG = math.pi / 180


def f32(x):
    """float32 rounding, returned as the float64 whose repr is the shortest f32 string."""
    v = np.float32(x)
    s = str(v)  # numpy: the shortest string that round-trips the f32
    y = float(s)
    assert np.float32(y) == v, (x, s)  # parsing as f64, then `as f32`, gives v back
    return y


def unit32(v):
    v = np.asarray(v, dtype=np.float64)
    v = v / np.linalg.norm(v)
    return [f32(a) for a in v]


def scratch(center, angle, half_len, W, D, profile):
    """The kernel's Scratch record (f32) and its end points."""
    t = np.array([math.cos(angle), math.sin(angle)])
    c = np.array(center, dtype=np.float64)
    rec = {"center": [f32(c[0]), f32(c[1])], "tangent": [f32(t[0]), f32(t[1])],
           "half_len": f32(half_len), "width": f32(W), "depth": f32(D), "profile": profile}
    cc, tt, h = np.array(rec["center"]), np.array(rec["tangent"]), rec["half_len"]
    rec["p0"] = [float(a) for a in cc - h * tt]
    rec["p1"] = [float(a) for a in cc + h * tt]
    return rec


def wi_of(theta_deg):
    th = theta_deg * DEG
    return unit32([math.sin(th), 0.0, math.cos(th)])


def directions(wi, scratches, lambda_nm=LAMBDA_NM):
    """(wo list, set letters)."""
    lam = lambda_nm / 1000.0
    wi = np.array(wi)
    targets = [(np.zeros(2), "m")]
    p = [0.0, 0.005, 0.015, 0.03, 0.06, 0.1, 0.15, 0.2, 0.3, 0.4, 0.55, 0.7, 0.9, 1.1, 1.4, 1.7]
    ps = sorted({s * v for v in p for s in (1, -1)})
    for s in scratches:
        t = np.array(s["tangent"], dtype=np.float64)
        t /= np.linalg.norm(t)
        b = np.array([-t[1], t[0]])
        for off, tag in ((0.0, "d"), (1.0 / (2 * math.pi * SIGMA), "e")):
            for u in ps:
                targets.append((u / lam * b + off * t, tag))
    for gx in np.linspace(-0.06, 0.06, 5):
        for gy in np.linspace(-0.06, 0.06, 5):
            targets.append((np.array([gx, gy]), "g"))
    wos, tags, seen = [], [], set()
    for xi, tag in targets:
        wxy = lam * xi - wi[:2]
        r2 = float(wxy @ wxy)
        if r2 > 1 - 0.01 ** 2:
            continue
        wo = unit32([wxy[0], wxy[1], math.sqrt(1 - r2)])
        if tuple(wo) in seen:
            continue
        seen.add(tuple(wo))
        wos.append(wo)
        tags.append(tag)
    for gx in np.linspace(-0.8, 0.8, 5):
        for gy in np.linspace(-0.8, 0.8, 5):
            r2 = gx * gx + gy * gy
            if r2 > 1 - 0.01 ** 2:
                continue
            wo = unit32([gx, gy, math.sqrt(1 - r2)])
            if tuple(wo) not in seen:
                seen.add(tuple(wo))
                wos.append(wo)
                tags.append("h")
    return wos, "".join(tags)


def all_cases():
    cases = []
    x = [0.0, 0.0]
    ang = 60 * DEG  # groove direction, 60 deg from the plane of incidence (x)
    t = np.array([math.cos(ang), math.sin(ang)])
    b = np.array([-t[1], t[0]])
    for kind, ws, offs, ths, half in (
            ("single", (0.05, 0.1, 0.3, 0.6, 1.0), (0, 1, 2), (0, 30, 60, 80), 500.0),
            ("finite", (0.3, 1.0), (0, 1), (0, 60), SIGMA)):
        for wr in ws:
            for prof in ("rect", "triangle"):
                for off in offs:
                    for th in ths:
                        c = np.array(x) + off * SIGMA * b
                        s = scratch(c, ang, half, wr * SIGMA, 0.2, prof)
                        cases.append({
                            "name": f"{kind}_{prof}_W{wr}_off{off}_th{th}",
                            "kind": "single", "length": "long" if kind == "single" else "finite",
                            "W_over_sigma": wr, "offset_sigma": off, "theta_i_deg": th,
                            "profile": prof, "x": x, "wi": wi_of(th), "scratches": [s]})
    for angle in (90, 45, 10):
        for depths in ((0.2, 0.2), (0.2, 0.1)):
            for prof in ("rect", "triangle"):
                for th in (0, 30):
                    a0 = 20 * DEG
                    cross = np.array([2.0, 0.0])  # crossing point, 2 um from the window centre
                    s = [scratch(cross, a0, 500.0, 3.0, depths[0], prof),
                         scratch(cross, a0 + angle * DEG, 500.0, 3.0, depths[1], prof)]
                    eq = "equal" if depths[0] == depths[1] else "unequal"
                    cases.append({
                        "name": f"crossing{angle}_{eq}_{prof}_th{th}", "kind": "crossing",
                        "length": "long", "angle_deg": angle, "depths": list(depths),
                        "W_over_sigma": 0.3, "offset_sigma": 0.2, "theta_i_deg": th,
                        "profile": prof, "x": x, "wi": wi_of(th), "scratches": s})
    for c in cases:
        c["lambda_nm"] = LAMBDA_NM
        c["wo"], c["sets"] = directions(c["wi"], c["scratches"])
    for prof, depths in (("rect", (0.2, 0.1)), ("triangle", (2.0, 1.0))):
        cross = np.array([2.0, 0.0])
        a0, th = 20 * DEG, 60
        s = [scratch(cross, a0, 500.0, 50.0, depths[0], prof),
             scratch(cross, a0 + 45 * DEG, 500.0, 50.0, depths[1], prof)]
        wo, sets = directions(wi_of(th), s, WIDE_LAMBDA_NM)
        keep = [i for i, tag in enumerate(sets) if tag in "mde"][::2]
        cases.append({
            "name": f"wide_crossing45_{prof}_th{th}", "kind": "crossing", "length": "long",
            "angle_deg": 45, "depths": list(depths), "W_over_sigma": 5.0,
            "offset_sigma": 0.2, "theta_i_deg": th, "profile": prof, "x": x,
            "wi": wi_of(th), "scratches": s, "lambda_nm": WIDE_LAMBDA_NM,
            "wo": [wo[i] for i in keep], "sets": "".join(sets[i] for i in keep)})
    return cases


def query_of(case):
    return hf.Query(case["wi"], case["wo"], case["lambda_nm"], case["x"], SIGMA, MATERIAL)


def r12(v):
    return [float(f"{a:.12g}") for a in v]


def stats(ref, test, frac=1e-3):
    """median and worst |test/ref - 1| over directions with ref >= frac * max(ref)."""
    sel = ref >= frac * ref.max()
    e = np.abs(test[sel] / ref[sel] - 1)
    return float(np.median(e)), float(e.max()), int(sel.sum())


def summary(path):
    """Crossing cases: which approximation costs what. Relative error against exact/deepest
    (median, worst over directions >= 1e-3 of the case's exact/deepest peak) of
    frozen/summed (Werner = the kernel), exact/summed (window exact, crossings summed) and
    frozen/deepest (window frozen, crossing cut once)."""
    with open(path) as fh:
        d = json.load(fh)
    print("| case | frozen/summed (Werner) | exact/summed | frozen/deepest |")
    print("|---|---:|---:|---:|")
    for c in d["cases"]:
        if c["kind"] != "crossing":
            continue
        ref = np.array(c["exact_deepest"])
        row = []
        for k in ("frozen_summed", "exact_summed", "frozen_deepest"):
            med, worst, n = stats(ref, np.array(c[k]))
            row.append(f"{med:.3f} / {worst:.2f}")
        print(f"| {c['name']} | " + " | ".join(row) + " |")
    # at the mirror direction (set "m", the first direction)
    print("\nmirror direction: frozen/summed / exact/deepest - 1")
    for c in d["cases"]:
        if c["kind"] == "crossing":
            assert c["sets"][0] == "m"
            print(f"  {c['name']}: {c['frozen_summed'][0] / c['exact_deepest'][0] - 1:+.3f}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--limit", type=int, default=None)
    ap.add_argument("--out", default=OUT)
    ap.add_argument("--summary", action="store_true",
                    help="print the crossing cases' error decomposition from --out and exit")
    a = ap.parse_args()
    if a.summary:
        summary(a.out)
        return
    cases = all_cases()[:a.limit]
    t0 = time.time()
    out_cases = []
    conv_worst = (0.0, 0.0)
    for i, case in enumerate(cases):
        q = query_of(case)
        vals, conv = {}, {}
        variants = hf.VARIANTS if case["kind"] == "crossing" else hf.VARIANTS[::2]
        for window, cross in variants:
            lo = hf.brdf_models(case["scratches"], q, window, cross, n=hf.ORDER)
            hi = hf.brdf_models(case["scratches"], q, window, cross, n=2 * hf.ORDER)
            # Velinov's incoherent sum for the crossing cases (a single groove's is
            # Werner's |S|^2, nothing new).
            models = (("", 0), ("velinov_", 1)) if case["kind"] == "crossing" else (("", 0),)
            for prefix, m in models:
                key = f"{prefix}{window}_{cross}"
                peak = hi[m].max()
                big = hi[m] >= 1e-6 * peak
                rel = float(np.max(np.abs(lo[m][big] / hi[m][big] - 1)))
                ab = float(np.max(np.abs(lo[m] - hi[m])) / peak)
                conv[key] = [rel, ab]
                conv_worst = (max(conv_worst[0], rel), max(conv_worst[1], ab))
                vals[key] = hi[m]
        fs = vals["frozen_summed"]
        ed = vals.get("exact_deepest", vals["exact_summed"])
        med, worst, n = stats(ed, fs)
        print(f"[{i + 1}/{len(cases)} {time.time() - t0:.0f}s] {case['name']}: "
              f"{len(q.kd)} dirs, conv rel {max(c[0] for c in conv.values()):.1e}; "
              f"frozen/summed vs exact/deepest median {med:.2e} worst {worst:.2e} ({n})",
              flush=True)
        oc = {k: v for k, v in case.items()}
        oc["conv"] = {k: [float(f"{v[0]:.3g}"), float(f"{v[1]:.3g}")] for k, v in conv.items()}
        for k, v in vals.items():
            oc[k] = r12(v)
        out_cases.append(oc)
    doc = {
        "description": "Werner et al. 2017 coherent BRDF (1/sr, no cosine) from the windowed "
                       "scalar integral over the heightfield, reference/heightfield.py (issue "
                       "#21). Variants: window frozen at each groove's centre line (Werner "
                       "Eqs. 9-13, the kernel's model) or exact; crossings summed (Werner Eq. "
                       "9) or deepest (cut once). Single grooves store frozen_summed and "
                       "exact_summed (deepest = summed without a crossing). Crossing cases "
                       "also store velinov_<window>_<crossings>: Velinov Eq. 7's incoherent "
                       "sum of the grooves' parts, F/(pi sigma^2 lambda^2) sum_k |S'_k|^2 "
                       "(no base), each groove's part less, with deepest, the overlap "
                       "pieces where it is the shallower groove.",
        "generator": "reference/heightfield_golden.py",
        "sigma_um": SIGMA,
        "params": {"model": "werner", "depth_term": "exact"},
        "material": MATERIAL,
        "quadrature": {"order": 2 * hf.ORDER, "convergence_order": hf.ORDER,
                       "panel_phase_rad": hf.PHI_PANEL, "window_truncation_sigmas":
                       hf.SIGMA_TRUNC,
                       "conv": "per variant [max rel diff over values >= 1e-6 of the case's "
                               "peak, max abs diff / peak] between ORDER and 2 ORDER"},
        "cases": out_cases,
    }
    with open(a.out, "w") as fh:
        json.dump(doc, fh, separators=(",", ":"))
        fh.write("\n")
    print(f"wrote {a.out}: {len(out_cases)} cases, {os.path.getsize(a.out) / 1e6:.2f} MB, "
          f"{time.time() - t0:.0f}s; convergence worst rel {conv_worst[0]:.2e}, "
          f"abs/peak {conv_worst[1]:.2e}")


if __name__ == "__main__":
    main()
