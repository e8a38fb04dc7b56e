"""What the sampling sweeps (`lobe1_sweep.py`, `vmf_ring_sweep.py`, `disk_lobe_sweep.py`)
share: their command line, the CSV they write, float32 rounding and neighbours, and
direction helpers in mpmath."""
import argparse
import math
import sys
from pathlib import Path

import mpmath as mp
import numpy as np


def f32(x):
    """`x` rounded to float32 (as a Python float)."""
    return float(np.float32(x))


def nudges(x, ulps=1):
    """The float32 values `ulps` float32 steps above and below float32 `x`."""
    out = []
    for toward in (np.float32(np.inf), np.float32(-np.inf)):
        y = np.float32(x)
        for _ in range(ulps):
            y = np.nextafter(y, toward)
        out.append(float(y))
    return out


def parse_args(default_count, jobs=False):
    """`--count N --seed-offset K --out DIR` (DIR default `reference/golden/sweep/`), and
    `--jobs N` where the sweep evaluates in parallel (`parallel.ordered_map`)."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--count", type=int, default=default_count)
    ap.add_argument("--seed-offset", type=int, default=0)
    ap.add_argument("--out", default=str(Path(__file__).resolve().parent / "golden" / "sweep"))
    if jobs:
        ap.add_argument("--jobs", type=int, default=1, help="worker processes (default 1: this one)")
    return ap.parse_args()


def progress(done, count, every=100):
    if done % every == 0:
        print(f"{done}/{count}", file=sys.stderr)


def write_csv(out_dir, family, head, rows):
    """`out_dir/family.csv`: the header and one line per row (lists of strings)."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    path = out / f"{family}.csv"
    path.write_text("\n".join([",".join(head)] + [",".join(r) for r in rows]) + "\n")
    print(f"wrote {path} ({len(rows)} queries)", file=sys.stderr)


def draw_wo(rng):
    """An outgoing direction (float32): cos(theta) 0.005 - 1 log-uniform (20 % with
    1 - cos(theta) 1e-9 - 0.1), any azimuth."""
    if rng.random() < 0.2:
        ct = 1 - 10 ** rng.uniform(-9, -1)
    else:
        ct = 10 ** rng.uniform(math.log10(0.005), 0)
    st, ph = math.sqrt(max(0.0, 1 - ct * ct)), rng.uniform(0, 2 * math.pi)
    return [f32(st * math.cos(ph)), f32(st * math.sin(ph)), f32(ct)]


def unit(v):
    """`v` normalised exactly (mpmath)."""
    v = [mp.mpf(c) for c in v]
    n = mp.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def angle(p, q):
    """Angle between two directions (normalised first), accurate when small:
    2 asin(|p - q| / 2)."""
    chord = mp.sqrt(sum((x - y) ** 2 for x, y in zip(unit(p), unit(q))))
    return 2 * mp.asin(min(mp.mpf(1), chord / 2))


def gauss_legendre_mp(n):
    """Nodes and weights of the n-point Gauss-Legendre rule on [-1, 1] as mpmath numbers,
    Newton on the Legendre recurrence at 40 digits."""
    xs, ws = [], []
    with mp.workdps(40):
        for k in range(1, n + 1):
            x = mp.cos(mp.pi * (k - mp.mpf(1) / 4) / (n + mp.mpf(1) / 2))
            for _ in range(100):
                p0, p1 = mp.mpf(1), x
                for j in range(2, n + 1):
                    p0, p1 = p1, ((2 * j - 1) * x * p1 - (j - 1) * p0) / j
                dp = n * (x * p1 - p0) / (x * x - 1)
                dx = p1 / dp
                x -= dx
                if abs(dx) < mp.mpf(10) ** -35:
                    break
            xs.append(x)
            ws.append(2 / ((1 - x * x) * dp * dp))
    return xs, ws
