#!/usr/bin/env python3
"""Regenerate every golden file under reference/golden/ (deterministic).

    python3 reference/generate.py            # everything, 2 worker processes
    python3 reference/generate.py --jobs 1   # single process
    python3 reference/generate.py --only eta,tables

Self-checks run alongside (checks.py) and are summarised in golden/checks.json;
the script fails if any check exceeds its tolerance.
"""

import argparse
import json
import math
import multiprocessing as mproc
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)

import mpmath as mp  # noqa: E402
import numpy as np  # noqa: E402

import refcore as rc  # noqa: E402

GOLDEN = os.path.join(HERE, "golden")


def f17(x):
    return "%.17g" % float(x)


def cplx(v):
    return [float(mp.re(v)), float(mp.im(v))]


def ln_arg(v):
    if v == 0:
        return None, None
    return float(mp.log(abs(v))), float(mp.arg(v))


# ---------------------------------------------------------------------------
# Special functions
# ---------------------------------------------------------------------------

def faddeeva_points():
    pts = []
    radii = np.logspace(-6, 4, 60)
    angs = np.linspace(0, math.pi, 25)  # includes 0, pi/2 (index 12), pi
    for r in radii:
        r = float(r)
        for i, a in enumerate(angs):
            if i == 0:
                z = (r, 0.0)
            elif i == 12:
                z = (0.0, r)
            elif i == 24:
                z = (-r, 0.0)
            else:
                z = (r * math.cos(a), r * math.sin(a))
            pts.append(z)
    pts.append((0.0, 0.0))
    for k in range(-600, 601):  # real axis, step 0.05
        pts.append((k / 20.0, 0.0))
    for y in np.logspace(-6, 4, 101):  # imaginary axis
        pts.append((0.0, float(y)))
    for y in (0.01, 0.1, 0.5, 1.0, 2.0, 5.0):  # lines just above the axis
        for k in range(-60, 61):
            pts.append((k / 2.0, y))
    # dedupe, keep order
    seen = set()
    out = []
    for p in pts:
        if p not in seen:
            seen.add(p)
            out.append(p)
    return out


def job_faddeeva():
    mp.mp.dps = 40
    lines = ["re,im,w_re,w_im"]
    for x, y in faddeeva_points():
        z = mp.mpc(x, y)
        w = mp.exp(-z ** 2) * mp.erfc(-1j * z)
        lines.append(",".join([f17(x), f17(y), f17(mp.re(w)), f17(mp.im(w))]))
    return {"faddeeva.csv": "\n".join(lines) + "\n"}


def job_si():
    mp.mp.dps = 40
    xs = [0.0]
    for v in np.logspace(-6, 4, 400):
        xs += [float(v), -float(v)]
    xs += [k / 20.0 for k in range(-1000, 1001)]
    seen = set()
    lines = ["x,si"]
    for x in xs:
        if x in seen:
            continue
        seen.add(x)
        lines.append(f17(x) + "," + f17(mp.si(mp.mpf(x))))
    return {"si.csv": "\n".join(lines) + "\n"}


FRESNEL_IORS = [(1.5, 0.0), (1.0, 0.0), (1.33, 0.0), (2.4, 0.0), (0.67, 0.0),
                (0.2, 3.0), (0.27, 3.41), (0.43, 2.45), (1.1, 6.9), (2.9, 3.0), (1.5, 0.5)]


def job_fresnel():
    mp.mp.dps = 40
    cs = [1e-4, 1e-3, 0.01, 0.02, 0.05] + [k / 20.0 for k in range(2, 20)] + [0.99, 0.999, 1.0]
    lines = ["cos_theta,n,k,F"]
    for n, k in FRESNEL_IORS:
        for c in cs:
            lines.append(",".join([f17(c), f17(n), f17(k), f17(rc.fresnel(c, n, k))]))
    return {"fresnel.csv": "\n".join(lines) + "\n"}


# ---------------------------------------------------------------------------
# eta.json
# ---------------------------------------------------------------------------

def _seg_case(sigma, x0, ang, L, along, across, xi1, xi2, tag):
    t = np.array([math.cos(ang), math.sin(ang)])
    b = np.array([-t[1], t[0]])
    c = np.asarray(x0, float) + along * t + across * b
    p0 = c - L / 2 * t
    p1 = c + L / 2 * t
    xi = xi1 * t + xi2 * b
    return {"sigma": float(sigma), "p0": [float(v) for v in p0], "p1": [float(v) for v in p1],
            "x0": [float(v) for v in x0], "xi": [float(v) for v in xi], "tag": tag}


def eta_cases():
    rng = np.random.default_rng(12)
    S = 10.0
    cases = []
    Ls = [0.01 * S, 0.1 * S, S, 3 * S, 10 * S, 10000.0]
    xi1s = [0.0, 0.003, 0.01, 0.03, 0.1, 0.3]
    x0 = [13.7, -4.2]
    # 1. through x0 at many angles
    for i in range(24):
        ang = i * math.pi / 12
        for j in range(3):
            L = Ls[(i + 2 * j) % 6]
            xi1 = xi1s[(i + j) % 6] * (1 if j != 1 else -1)
            cases.append(_seg_case(S, x0, ang, L, 0.0, 0.0, xi1, rng.uniform(-3, 3),
                                   "through_x0"))
    # 2. offsets along and across the tangent (up to 20 sigma)
    for along in (0.0, 2.0, 5.0, 10.0, 20.0):
        for across in (0.0, 1.0, 3.0, 10.0, 20.0):
            for L in (S, 10 * S, 10000.0):
                ang = rng.uniform(0, 2 * math.pi)
                xi1 = float(rng.choice(xi1s))
                cases.append(_seg_case(S, [rng.uniform(-50, 50), rng.uniform(-50, 50)], ang, L,
                                       along * S * (1 if rng.uniform() < 0.5 else -1),
                                       across * S * (1 if rng.uniform() < 0.5 else -1),
                                       xi1, rng.uniform(-3, 3), "offset"))
    # 3. far tail: large xi1
    for xi1 in (0.5, 1.0, 2.0, 5.0):
        for L in (0.01 * S, 0.1 * S, S, 5 * S, 10000.0):
            for along, across in ((0.0, 0.0), (3 * S, 1 * S)):
                cases.append(_seg_case(S, [0.0, 0.0], rng.uniform(0, 2 * math.pi), L,
                                       along, across, xi1, rng.uniform(-5, 5), "far_tail"))
    # 4. other sigma
    for sig in (1.0, 5.0, 30.0, 60.0):
        for _ in range(10):
            L = float(rng.choice([0.1, 1.0, 5.0, 20.0, 10000.0])) * sig
            cases.append(_seg_case(sig, [rng.uniform(-20, 20), rng.uniform(-20, 20)],
                                   rng.uniform(0, 2 * math.pi), L,
                                   rng.uniform(-3, 3) * sig, rng.uniform(-3, 3) * sig,
                                   rng.uniform(-0.3, 0.3) * 10 / sig, rng.uniform(-3, 3),
                                   "sigma_%g" % sig))
    # 5. random general
    for _ in range(60):
        L = float(math.exp(rng.uniform(math.log(0.1), math.log(10000.0))))
        cases.append(_seg_case(S, [rng.uniform(-100, 100), rng.uniform(-100, 100)],
                               rng.uniform(0, 2 * math.pi), L,
                               rng.uniform(-30, 30), rng.uniform(-30, 30),
                               rng.uniform(-0.4, 0.4), rng.uniform(-4, 4), "random"))
    # 6. degenerate and limit cases
    cases.append({"sigma": S, "p0": [3.0, 4.0], "p1": [3.0, 4.0], "x0": [0.0, 0.0],
                  "xi": [0.1, 0.2], "tag": "zero_length"})
    for xi1 in (0.0, 0.05, 0.2):
        cases.append(_seg_case(S, [1.0, 2.0], 0.7, 1.0e6, 0.0, 7.0, xi1, 1.3, "infinite_limit"))
    return cases


def job_eta(k, n):
    mp.mp.dps = 30
    out = []
    worst = {"cf": 0.0, "realaxis": 0.0, "err_est": 0.0, "n_realaxis": 0}
    for i, c in enumerate(eta_cases()):
        if i % n != k:
            continue
        args = (c["sigma"], c["p0"], c["p1"], c["x0"], c["xi"])
        v, info = rc.eta_quad(*args, dps=30, return_info=True, estimate=True)
        vi = rc.eta_inf(*args)
        seg = rc.Segment(c["p0"], c["p1"])
        s_t, s_b, xi1, xi2 = seg.frame(c["x0"], c["xi"])
        rec = dict(c)
        rec["eta"] = cplx(v)
        rec["eta_inf"] = cplx(vi)
        rec["eta_ln_abs"], rec["eta_arg"] = ln_arg(v)
        rec["eta_inf_ln_abs"], rec["eta_inf_arg"] = ln_arg(vi)
        rec.update({"L": float(seg.L), "s_t": float(s_t), "s_b": float(s_b),
                    "xi1": float(xi1), "xi2": float(xi2)})
        if v != 0:
            rel = info["err"] / abs(v)
            rec["rel_err_est"] = float(mp.mpf("%.3g" % float(rel))) if rel > 0 else 0.0
            worst["err_est"] = max(worst["err_est"], float(rel))
            cf = rc.closedform_eta(*args)
            worst["cf"] = max(worst["cf"], float(abs(cf - v) / abs(v)))
            if i % 3 == 0:
                ra = rc.eta_realaxis(*args, est=v, max_osc=300)
                if ra is not None:
                    worst["n_realaxis"] += 1
                    worst["realaxis"] = max(worst["realaxis"], float(abs(ra - v) / abs(v)))
        else:
            rec["rel_err_est"] = 0.0
        if c["tag"] == "infinite_limit":
            rec["rel_diff_to_eta_inf"] = float(abs(v - vi) / abs(vi))
        out.append((i, rec))
    return {"eta": out, "_checks": {"eta_part%d" % k: worst}}


# ---------------------------------------------------------------------------
# profile.json
# ---------------------------------------------------------------------------

def profile_cases():
    rng = np.random.default_rng(29)
    cases = []
    for i in range(300):
        prof = "rect" if i % 2 == 0 else "triangle"
        W = round(float(math.exp(rng.uniform(math.log(0.1), math.log(20.0)))), 4)
        D = 0.0 if rng.uniform() < 0.12 else round(float(rng.uniform(0, 5)), 4)
        gamma = 2.0 if rng.uniform() < 0.15 else round(float(rng.uniform(0.02, 2.0)), 6)
        lam = round(float(rng.uniform(0.38, 0.78)), 4)
        u = rng.uniform()
        if i < 6:
            W = 0.0
            xi2 = round(float(rng.uniform(-3, 3)), 6)
        elif u < 0.45:
            xi2 = round(float(rng.uniform(-6, 6)), 6)
        elif u < 0.65:
            xi2 = float(rng.choice([-7, -3, -2, -1, 1, 2, 3, 7])) / W  # mask sinc zero
        elif u < 0.88:
            q = 2 * D * gamma / (W * lam)  # triangle pole (both profiles tested there)
            xi2 = q if rng.uniform() < 0.5 else -q
        elif u < 0.94:
            xi2 = 0.0
        else:
            xi2 = round(float(rng.uniform(-0.05, 0.05)), 8)
        cases.append({"profile": prof, "W": W, "D": D, "gamma": gamma, "lambda": lam,
                      "xi2": float(xi2)})
    return cases


def job_profile(k, n):
    mp.mp.dps = 30
    out = []
    chk = {"rect_closed_form_max_abs_over_W": 0.0, "tri_corrected_max_abs_over_W": 0.0,
           "n_tri_compared": 0, "tri_sinc_form_incl_poles_max_abs_over_W": 0.0}
    wrong = ("tri_printed", "tri_printed_phi_plus", "tri_fixed_W_phi_minus")
    for w in wrong:
        chk[w + "_max_abs_over_W"] = 0.0
        chk[w + "_n_agree_1e-6"] = 0
    for i, c in enumerate(profile_cases()):
        if i % n != k:
            continue
        m, p = rc.profile_quad(c["profile"], c["W"], c["D"], c["gamma"], c["lambda"], c["xi2"])
        rec = dict(c)
        rec["mask"] = cplx(m)
        rec["scratch"] = cplx(p)
        out.append((i, rec))
        if c["W"] == 0:
            continue
        with mp.workdps(40):
            cm, cpr = rc.closedform_rect(c["W"], c["D"], c["gamma"], c["lambda"], c["xi2"])
            W = mp.mpf(c["W"])
            chk["rect_closed_form_max_abs_over_W"] = max(
                chk["rect_closed_form_max_abs_over_W"], float(abs(cm - m) / W))
            if c["profile"] == "rect":
                chk["rect_closed_form_max_abs_over_W"] = max(
                    chk["rect_closed_form_max_abs_over_W"], float(abs(cpr - p) / W))
            else:
                cs = rc.closedform_triangle_sinc(c["W"], c["D"], c["gamma"], c["lambda"], c["xi2"])
                chk["tri_sinc_form_incl_poles_max_abs_over_W"] = max(
                    chk["tri_sinc_form_incl_poles_max_abs_over_W"], float(abs(cs - p) / W))
                q = 2 * mp.mpf(c["D"]) * c["gamma"] / (W * c["lambda"])
                xi2 = mp.mpf(c["xi2"])
                if c["D"] > 0 and abs(abs(xi2) - q) > 1e-3 * q:  # away from removable poles
                    ct = rc.closedform_triangle_corrected(c["W"], c["D"], c["gamma"],
                                                          c["lambda"], c["xi2"])
                    chk["tri_corrected_max_abs_over_W"] = max(
                        chk["tri_corrected_max_abs_over_W"], float(abs(ct - p) / W))
                    for key, sg, fx in zip(wrong, (-1, 1, -1), (False, False, True)):
                        cp = rc.closedform_triangle_printed(c["W"], c["D"], c["gamma"],
                                                            c["lambda"], c["xi2"], sg, fx)
                        dev = float(abs(cp - p) / W)
                        chk[key + "_max_abs_over_W"] = max(chk[key + "_max_abs_over_W"], dev)
                        chk[key + "_n_agree_1e-6"] += int(dev < 1e-6)
                    chk["n_tri_compared"] += 1
    return {"profile": out, "_checks": {"profile_part%d" % k: chk}}


# ---------------------------------------------------------------------------
# footprint.json
# ---------------------------------------------------------------------------

def footprint_cases():
    rng = np.random.default_rng(2018)
    S = 10.0
    ratios = np.logspace(-2, 2, 25)
    configs = [
        # (aspect, centre across [sigma], centre along [sigma], segment kind, ellipse angle rel.)
        (1.0, 0.0, 0.0, "long", None),
        (2.0, 0.0, 0.0, "long", 0.0),
        (4.0, 0.0, 0.0, "long", math.pi / 2),
        (8.0, 0.5, 0.0, "long", None),
        (3.0, 1.5, 0.0, "long", None),
        (1.5, 3.0, 0.0, "long", None),
        (2.0, None, 0.0, "short_inside", None),
        (5.0, None, 0.0, "end_inside", None),
    ]
    cases = []
    for ci, (asp, across, along, kind, rel) in enumerate(configs):
        for r in ratios:
            A = float(r) * S * S  # a1 a2
            a1 = math.sqrt(A * asp)
            a2 = math.sqrt(A / asp)
            ang_s = rng.uniform(0, math.pi)
            t = np.array([math.cos(ang_s), math.sin(ang_s)])
            b = np.array([-t[1], t[0]])
            e_ang = ang_s + (rel if rel is not None else rng.uniform(0, math.pi))
            centre = np.array([rng.uniform(-20, 20), rng.uniform(-20, 20)])
            if kind == "long":
                L = 10000.0
                c = centre - across * S * b + rng.uniform(-50, 50) * t
            elif kind == "short_inside":
                # length 0.6 a2, centred 0.3 a2 off the centre: entirely inside
                L = 0.6 * a2
                c = centre - 0.3 * a2 * b
            else:  # one end inside (0.3 a2 off the centre), 40 sigma long
                L = 40 * S
                c = centre - 0.3 * a2 * b + (L / 2) * t
            p0 = c - L / 2 * t
            p1 = c + L / 2 * t
            cases.append({
                "sigma": S,
                "scratch": {"p0": [round(float(v), 9) for v in p0],
                            "p1": [round(float(v), 9) for v in p1],
                            "width": round(float(rng.uniform(0.5, 3.0)), 4),
                            "depth": round(float(rng.uniform(0.05, 1.0)), 4)},
                "ellipse": {"center": [round(float(v), 9) for v in centre],
                            "angle_rad": round(float(e_ang % (2 * math.pi)), 12),
                            "a1": float(a1), "a2": float(a2)},
                "config": ("%s, aspect %g, centre %g sigma off the line" % (kind, asp, across)
                           if across is not None else
                           "%s, aspect %g, line 0.3 a2 off the centre" % (kind, asp)),
            })
    return cases


def job_footprint():
    import footprint as fp
    out = []
    worst = 0.0
    for c in footprint_cases():
        s = c["scratch"]
        e = c["ellipse"]
        eta_p, rho_p, ch = fp.footprint_exact(c["sigma"], s["p0"], s["p1"], s["width"], e)
        ap = fp.paper_approximations(c["sigma"], s["p0"], s["p1"], s["width"], e)
        worst = max(worst, ch)
        rec = {"sigma": c["sigma"], "scratch": s, "ellipse": e, "config": c["config"],
               "A_P_over_A_C": e["a1"] * e["a2"] / c["sigma"] ** 2,
               "exact_eta_p": eta_p, "exact_rho_p": rho_p,
               "l_contained": ap["l_contained"], "eq15": ap["eq15"], "eq16": ap["eq16"],
               "eq18": ap["eq18"], "eq16_printed": ap["eq16_printed"],
               "eq18_printed": ap["eq18_printed"], "s_b": ap["s_b"],
               "refinement_rel_change": float("%.3g" % ch)}
        out.append(rec)
    if worst > 1e-10:
        raise AssertionError("footprint quadrature not converged: %g" % worst)
    return {"footprint.json": json.dumps({"cases": out}, indent=1) + "\n",
            "_checks": {"footprint_refinement_max_rel_change": worst}}


# ---------------------------------------------------------------------------
# tables
# ---------------------------------------------------------------------------

def job_tables(names):
    """Several tables in one job, so the eta/profile memo is shared between them."""
    import tables
    mp.mp.dps = 30
    rc.MEMO.clear()
    all_t = tables.all_tables()
    out = {"_checks": {}}
    rc.ETA_CHECK["max_rel"] = 0.0
    for name in names:
        desc, spec = all_t[name]
        exp_ = []
        logs = []
        for qq in spec["queries"]:
            v = rc.brdf(spec, qq)
            exp_.append(float(v))
            logs.append(float(mp.log10(v)) if v > 0 else None)
        chk = out["_checks"]
        if name == "offcenter_depth_sign":
            worst = 0.0
            for qq, v in zip(spec["queries"], exp_):
                vf = rc.brdf(spec, qq, flip_depth_sign=True)
                worst = max(worst, abs(float(vf) - v) / v)
            chk["offcenter_sign_flip_max_rel"] = worst
        case = {"description": desc, "spec": spec, "expected": exp_, "expected_log10": logs}
        out["tables/%s.json" % name] = json.dumps(case, indent=1) + "\n"
    rc.MEMO.clear()
    key = "tables_%s%s_eta_vs_closed_form_max_rel" % (names[0], "_group" if len(names) > 1 else "")
    out["_checks"][key] = rc.ETA_CHECK["max_rel"]
    return out


def job_sweeps():
    """golden/sweeps/: tables whose queries carry their conditioning (see tables.py)."""
    import tables
    mp.mp.dps = 30
    rc.MEMO.clear()
    out = {}
    for name, (desc, spec) in tables.sweep_tables().items():
        exp_, depth, amp = [], [], []
        for qq in spec["queries"]:
            v, parts = rc.brdf(spec, qq, return_parts=True)
            B, S = parts["B"], parts["S"]
            exp_.append(float(v))
            depth.append(float(abs(B - S) / abs(B)))
            amp.append(float((abs(B) + mp.fsum(abs(x) for x in parts["Sk"])) / abs(B - S)))
        case = {"description": desc, "spec": spec, "expected": exp_, "depth": depth,
                "amplification": amp}
        out["sweeps/%s.json" % name] = json.dumps(case, indent=1) + "\n"
    rc.MEMO.clear()
    return out


def table_groups():
    import tables
    names = list(tables.all_tables())
    groups = [[n for n in names if n.startswith(p)]
              for p in ("ensemble_", "ior_silver_", "short_segments_", "mirror_flat_")]
    grouped = {n for g in groups for n in g}
    return groups + [[n] for n in names if n not in grouped]


# ---------------------------------------------------------------------------

def run_job(job):
    t0 = time.time()
    kind = job[0]
    if kind == "faddeeva":
        r = job_faddeeva()
    elif kind == "si":
        r = job_si()
    elif kind == "fresnel":
        r = job_fresnel()
    elif kind == "eta":
        r = job_eta(job[1], job[2])
    elif kind == "profile":
        r = job_profile(job[1], job[2])
    elif kind == "footprint":
        r = job_footprint()
    elif kind == "tables":
        r = job_tables(job[1])
    elif kind == "sweeps":
        r = job_sweeps()
    elif kind == "checks":
        import checks
        r = {"_checks": checks.run_all()}
    else:
        raise ValueError(kind)
    return job, r, time.time() - t0


def job_label(job):
    if job[0] == "tables":
        return "tables " + (job[1][0] if len(job[1]) == 1 else job[1][0] + " (+%d)" % (len(job[1]) - 1))
    return " ".join(map(str, job))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--jobs", type=int, default=2)
    ap.add_argument("--only", default="")
    args = ap.parse_args()
    only = set(filter(None, args.only.split(",")))
    import tables
    jobs = []
    NE, NP = 4, 3
    jobs += [("eta", k, NE) for k in range(NE)]
    jobs += [("tables", tuple(grp)) for grp in table_groups()]
    jobs += [("profile", k, NP) for k in range(NP)]
    jobs += [("footprint",), ("checks",), ("faddeeva",), ("si",), ("fresnel",), ("sweeps",)]
    if only:
        jobs = [j for j in jobs if j[0] in only]
    os.makedirs(os.path.join(GOLDEN, "tables"), exist_ok=True)
    os.makedirs(os.path.join(GOLDEN, "sweeps"), exist_ok=True)
    t0 = time.time()
    results = {}
    if args.jobs > 1:
        with mproc.Pool(args.jobs) as pool:
            for job, r, dt in pool.imap_unordered(run_job, jobs):
                print("%-45s %7.1f s" % (job_label(job), dt), flush=True)
                results[job] = r
    else:
        for job in jobs:
            job, r, dt = run_job(job)
            print("%-45s %7.1f s" % (job_label(job), dt), flush=True)
            results[job] = r
    files = {}
    checks_all = {}
    eta_recs, prof_recs = [], []
    for job in jobs:
        r = results[job]
        for k, v in r.items():
            if k == "_checks":
                checks_all.update(v)
            elif k == "eta":
                eta_recs += v
            elif k == "profile":
                prof_recs += v
            else:
                files[k] = v
    if eta_recs:
        files["eta.json"] = json.dumps([r for _, r in sorted(eta_recs, key=lambda x: x[0])],
                                       indent=1) + "\n"
    if prof_recs:
        files["profile.json"] = json.dumps([r for _, r in sorted(prof_recs, key=lambda x: x[0])],
                                           indent=1) + "\n"
    for name, text in files.items():
        path = os.path.join(GOLDEN, name)
        with open(path, "w") as fh:
            fh.write(text)
    # merge check summaries into golden/checks.json
    cpath = os.path.join(GOLDEN, "checks.json")
    old = {}
    if only and os.path.exists(cpath):
        with open(cpath) as fh:
            old = json.load(fh)
    old.update(checks_all)
    with open(cpath, "w") as fh:
        json.dump(dict(sorted(old.items())), fh, indent=1)
        fh.write("\n")
    import checks
    bad = checks.tolerance_failures(old)
    print("total %.1f s" % (time.time() - t0))
    if bad:
        print("CHECK FAILURES:\n  " + "\n  ".join(bad))
        sys.exit(1)


if __name__ == "__main__":
    main()
