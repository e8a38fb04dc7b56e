#!/usr/bin/env python3
"""Turns reference/ghs/golden/brdf.json (132 mpmath/scipy GHS values) into conformance case
files, one per material, in reference/ghs/golden/tables/ (read by `scratchwave run`).

Run: python3 reference/ghs/to_cases.py   (after reference/ghs/generate.py)
"""
import json
from pathlib import Path

HERE = Path(__file__).resolve().parent
COLOURS = ["Q/2", "Q", "F", "none"]
LAYERS = ["none", "plastic", "subsurface"]
FORMS = ["published", "energy-conserving"]


def cli_material(m):
    out = {k: m[k] for k in ("sigma_s_um", "beta", "p", "b_um", "c")}
    out["ior"] = [m["n"], m["k"]]
    out["diff_color"] = COLOURS[m["diff_color"]]
    layer = LAYERS[m["layer"]]
    if layer != "none":
        key = "rho_d" if layer == "plastic" else "albedo"
        out["layer"] = {"type": layer, key: m["layer_albedo"], "form": FORMS[m["layer_form"]]}
    return out


def main():
    cases = json.loads((HERE / "golden/brdf.json").read_text())
    groups = {}
    for c in cases:
        m = c["material"]
        key = json.dumps(cli_material(m), sort_keys=True)
        groups.setdefault((m["name"], key), []).append(c)
    out_dir = HERE / "golden/tables"
    out_dir.mkdir(parents=True, exist_ok=True)
    for old in out_dir.glob("*.json"):
        old.unlink()
    for i, ((name, key), cs) in enumerate(sorted(groups.items())):
        spec = {"model": "ghs", "material": json.loads(key),
                "queries": [{"wi": c["wi"], "wo": c["wo"], "lambda_nm": c["lambda_um"] * 1000.0} for c in cs]}
        case = {"description": f"GHS {name} ({len(cs)} directions/wavelengths), mpmath/scipy reference",
                "spec": spec, "expected": [c["rho"] for c in cs]}
        (out_dir / f"ghs_{i:02d}_{name}.json").write_text(json.dumps(case, indent=1) + "\n")
    print(f"wrote {len(groups)} case files to {out_dir}")


if __name__ == "__main__":
    main()
