#!/usr/bin/env python3
"""Print the Markdown summary tables used in reference/README.md from the golden data.

    python3 reference/report.py
"""

import json
import math
import os
from collections import defaultdict

HERE = os.path.dirname(os.path.abspath(__file__))
G = os.path.join(HERE, "golden")


def rel(a, e):
    return (a - e) / e if e else float("nan")


def footprint_table():
    cases = json.load(open(os.path.join(G, "footprint.json")))["cases"]
    by_ratio = defaultdict(list)
    for c in cases:
        by_ratio[round(c["A_P_over_A_C"], 6)].append(c)
    print("### Velinov footprint approximations vs exact quadrature (relative error)\n")
    print("Centred long scratch (ellipse centre on the line, aspect 1, 2, 4): the paper's setting.\n")
    print("| A_P/A_C | Eq. 15 | Eq. 16 (pi restored) | Eq. 16 printed | Eq. 18 (corrected) | Eq. 18 printed |")
    print("|---:|---:|---:|---:|---:|---:|")
    for r in sorted(by_ratio):
        cs = [c for c in by_ratio[r] if c["config"].startswith("long") and "centre 0 sigma" in c["config"]]
        if not cs:
            continue

        def span(key, ex):
            v = [rel(c[key], c[ex]) for c in cs]
            lo, hi = min(v), max(v)
            return "%+.3f" % lo if abs(hi - lo) < 5e-4 else "%+.3f .. %+.3f" % (lo, hi)
        print("| %.3g | %s | %s | %s | %s | %s |" % (
            r, span("eq15", "exact_eta_p"), span("eq16", "exact_eta_p"),
            span("eq16_printed", "exact_eta_p"), span("eq18", "exact_rho_p"),
            span("eq18_printed", "exact_rho_p")))
    print()
    print("All 200 cases (long scratches off-centre by 0.5-3 sigma, short scratches inside the "
          "ellipse, segment ends inside): median |relative error| and the worst case.\n")
    print("| A_P/A_C range | n | Eq. 15 median / max | Eq. 16 median / max | Eq. 18 median / max |")
    print("|---|---:|---:|---:|---:|")
    bins = [(0.0, 0.1), (0.1, 1.0), (1.0, 2.0), (2.0, 10.0), (10.0, 101.0)]
    for lo, hi in bins:
        cs = [c for c in cases if lo <= c["A_P_over_A_C"] < hi]

        def mm(key, ex):
            v = sorted(abs(rel(c[key], c[ex])) for c in cs)
            return "%.3g / %.3g" % (v[len(v) // 2], v[-1])
        print("| [%g, %g) | %d | %s | %s | %s |" % (lo, hi, len(cs), mm("eq15", "exact_eta_p"),
                                                   mm("eq16", "exact_eta_p"),
                                                   mm("eq18", "exact_rho_p")))
    print()


def eta_summary():
    d = json.load(open(os.path.join(G, "eta.json")))
    tags = defaultdict(int)
    tiny = 0
    under = 0
    for r in d:
        tags[r["tag"]] += 1
        if r["eta_ln_abs"] is not None and r["eta_ln_abs"] < math.log(1e-30):
            tiny += 1
        if r["eta_ln_abs"] is not None and r["eta"] == [0.0, 0.0]:
            under += 1
    lns = [r["eta_ln_abs"] for r in d if r["eta_ln_abs"] is not None]
    print("### eta.json\n")
    print("%d cases: %s. |eta| < 1e-30 in %d cases; %d underflow float64 "
          "(eta = [0, 0] but eta_ln_abs is exact); smallest |eta| = exp(%.1f)."
          % (len(d), ", ".join("%s %d" % kv for kv in sorted(tags.items())), tiny, under, min(lns)))
    print()


def tables_summary():
    print("### tables\n")
    print("| file | queries | scratches | log10 range | zeros in float64 |")
    print("|---|---:|---:|---|---:|")
    td = os.path.join(G, "tables")
    for f in sorted(os.listdir(td)):
        d = json.load(open(os.path.join(td, f)))
        lg = [x for x in d["expected_log10"] if x is not None]
        z = sum(1 for x in d["expected"] if x == 0)
        print("| %s | %d | %d | %.1f .. %.1f | %d |" % (
            f, len(d["expected"]), len(d["spec"]["scratches"]), min(lg), max(lg), z))
    print()


if __name__ == "__main__":
    eta_summary()
    tables_summary()
    footprint_table()
