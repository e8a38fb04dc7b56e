#!/usr/bin/env python3
"""Smoke test of the sweep generators: each one, run for its first queries, must write the
first lines of its committed subset byte for byte.

The kernel's sweep tests read the committed CSVs and never run the scripts that wrote them,
so a script can break (a changed helper's signature, a renamed column) without any test
noticing, and the subset could then no longer be regenerated or extended. This runs every
generator in `reference/*_sweep.py` and `reference/ghs/domain_sweep.py` with `--count 2`
into a temporary directory (seconds each), and `light_sweep.py --found` whole (~20 s), and
compares what it wrote with the committed files: the subsets are the first queries of the
same seeded draws (`docs/stability.md`), so the lines must be identical. The conditioning
script `light_extent_kappa.py` is run for one committed row of `light_extent_kappa.csv`
(KAPPA_ROW, a few seconds) on a copy of `light_extent.csv`, and must write that row again.

Needs mpmath, numpy and scipy (`reference/requirements.txt`; the test command installs them
into its virtual environment). Usage: python3 reference/smoke.py [NAME ...] (a subset of the
generator names below; all by default). Exit status 1 on any difference.
"""
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
SWEEP = HERE / "golden" / "sweep"
GHS_SWEEP = HERE / "ghs" / "golden" / "sweep"
GHS_FAMILIES = ("ndf", "g1", "fresnel", "color", "sigma_rel", "brdf", "halfvec", "diffsample")

# name: (script and arguments, committed directory, files it writes, whole file or a prefix)
GENERATORS = {
    "scratch": (["scratch_sweep.py", "--count", "2"], SWEEP,
                ["velinov", "werner_rect", "werner_tri", "werner_blended"], False),
    "footprint": (["footprint_sweep.py", "--count", "2"], SWEEP, ["footprint"], False),
    "light": (["light_sweep.py", "--count", "2"], SWEEP, ["light"], False),
    "light_found": (["light_sweep.py", "--found"], SWEEP, ["light_found"], True),
    "light_vgroove": (["light_sweep.py", "--vgroove", "--count", "2"], SWEEP, ["light_vgroove"], False),
    "light_extent": (["light_extent_sweep.py", "--count", "2"], SWEEP, ["light_extent"], False),
    "light_extent_vgroove": (["light_extent_sweep.py", "--vgroove", "--count", "2"], SWEEP,
                             ["light_extent_vgroove"], False),
    "vgroove_band": (["vgroove_band_sweep.py", "--count", "2"], SWEEP, ["vgroove_band"], False),
    "lobe1": (["lobe1_sweep.py", "--count", "2"], SWEEP, ["lobe1"], False),
    "disk_lobe": (["disk_lobe_sweep.py", "--count", "2"], SWEEP, ["disk_lobe"], False),
    "vmf_ring": (["vmf_ring_sweep.py", "--count", "2"], SWEEP, ["vmf_ring"], False),
    "ghs": (["ghs/domain_sweep.py", "--count", "2", "--jobs", "1"], GHS_SWEEP,
            list(GHS_FAMILIES), False),
}
# The row of `light_extent_kappa.csv` the smoke recomputes: a sphere light and one scratch,
# the fewest neighbours.
KAPPA_ROW = 48
NAMES = list(GENERATORS) + ["light_extent_kappa"]


def first_difference(got, want):
    """A description of where the lines `got` differ from `want` (None if they do not)."""
    for i, (g, w) in enumerate(zip(got, want)):
        if g != w:
            gf, wf = g.split(","), w.split(",")
            head = want[0].split(",")
            for j, (a, b) in enumerate(zip(gf, wf)):
                if a != b:
                    col = head[j] if j < len(head) else f"field {j}"
                    return f"line {i + 1}, column {col}: wrote {a!r}, committed {b!r}"
            return f"line {i + 1}: wrote {len(gf)} fields, committed {len(wf)}"
    if len(got) != len(want):
        return f"wrote {len(got)} lines, committed {len(want)}"
    return None


def run(name):
    """Runs one generator; returns the list of its failures (empty when it matches)."""
    args, committed, families, whole = GENERATORS[name]
    with tempfile.TemporaryDirectory() as out:
        t0 = time.time()
        proc = subprocess.run([sys.executable, str(HERE / args[0])] + args[1:] + ["--out", out],
                              cwd=HERE, capture_output=True, text=True)
        took = time.time() - t0
        if proc.returncode != 0:
            print(f"{name}: exit status {proc.returncode}", flush=True)
            tail = "\n    ".join(proc.stderr.strip().splitlines()[-6:])
            return [f"{name}: exit status {proc.returncode}\n    {tail}"]
        failures = []
        for fam in families:
            path = Path(out) / f"{fam}.csv"
            if not path.exists():
                failures.append(f"{name}: wrote no {fam}.csv")
                continue
            got = path.read_text().splitlines()
            want = (committed / f"{fam}.csv").read_text().splitlines()
            if not whole:
                want = want[:len(got)]
            diff = first_difference(got, want)
            if diff:
                failures.append(f"{name}: {fam}.csv {diff}")
        print(f"{name}: {len(families)} file(s), {took:.1f} s, "
              f"{'ok' if not failures else 'DIFFERENT'}", flush=True)
        return failures


def run_kappa():
    """`light_extent_kappa.py --rows KAPPA_ROW` on a copy of the committed table: the row it
    writes must be the committed one (its failures, empty when it matches)."""
    name = "light_extent_kappa"
    with tempfile.TemporaryDirectory() as out:
        (Path(out) / "light_extent.csv").write_text((SWEEP / "light_extent.csv").read_text())
        t0 = time.time()
        proc = subprocess.run([sys.executable, str(HERE / "light_extent_kappa.py"),
                               "--rows", str(KAPPA_ROW), "--dir", out],
                              cwd=HERE, capture_output=True, text=True)
        took = time.time() - t0
        if proc.returncode != 0:
            tail = "\n    ".join(proc.stderr.strip().splitlines()[-6:])
            print(f"{name}: exit status {proc.returncode}", flush=True)
            return [f"{name}: exit status {proc.returncode}\n    {tail}"]
        got = (Path(out) / "light_extent_kappa.csv").read_text().splitlines()
        lines = (SWEEP / "light_extent_kappa.csv").read_text().splitlines()
        want = lines[:1] + [line for line in lines[1:] if line.split(",")[0] == str(KAPPA_ROW)]
        diff = first_difference(got, want)
        print(f"{name}: row {KAPPA_ROW}, {took:.1f} s, {'ok' if not diff else 'DIFFERENT'}",
              flush=True)
        return [f"{name}: light_extent_kappa.csv {diff}"] if diff else []


def main():
    names = sys.argv[1:] or NAMES
    unknown = [n for n in names if n not in NAMES]
    if unknown:
        sys.exit(f"unknown generator(s) {unknown}; known: {', '.join(NAMES)}")
    failures = [f for n in names for f in (run_kappa() if n == "light_extent_kappa" else run(n))]
    for f in failures:
        print(f, file=sys.stderr)
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
