"""Python batch eval vs the Rust core on the same 10^6 queries, in one run.

    scripts/python.sh install && ~/.cache/scratchwave/venv/bin/python python/bench/eval_throughput.py [N] [REPEATS]

Times `Material.eval` and the Rust example `eval_throughput` (the same batch call without
Python), alternately, best of REPEATS each, on identical queries, checks that the values are bit-identical,
and prints both times and their ratio (Rust time / Python time: 1.0 means the binding adds
nothing). The README's "Python" table quotes this output.
"""

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

import scratchwave as sw

ROOT = Path(__file__).resolve().parents[2]
MATERIAL = {
    "model": "velinov",
    "sigma_um": 10,
    "material": {"F": 0.9},
    "scratches": [{"generate": {"seed": 5, "density_per_mm2": 60,
                                "region": {"min": [-500, -500], "max": [500, 500]},
                                "shape": {"type": "straight", "length": {"uniform": [50, 400]}},
                                "orientation": {"type": "random"},
                                "width": {"uniform": [0.5, 4]}, "depth": {"uniform": [0.05, 0.5]}}}],
}


def main() -> None:
    n = int(sys.argv[1]) if len(sys.argv) > 1 else 1_000_000
    repeats = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    rng = np.random.default_rng(12)
    t_o, p_o = rng.uniform(0, 1.3, n), rng.uniform(0, 2 * np.pi, n)
    t_i, p_i = rng.uniform(0, 1.3, n), rng.uniform(0, 2 * np.pi, n)
    wo = np.stack([np.sin(t_o) * np.cos(p_o), np.sin(t_o) * np.sin(p_o), np.cos(t_o)], 1).astype(np.float32)
    wi = np.stack([np.sin(t_i) * np.cos(p_i), np.sin(t_i) * np.sin(p_i), np.cos(t_i)], 1).astype(np.float32)
    x = rng.uniform(-400, 400, (n, 2)).astype(np.float32)
    m = sw.Material(MATERIAL)
    py_best = rust_best = float("inf")
    with tempfile.TemporaryDirectory() as d:
        mat, qf, of = Path(d, "m.json"), Path(d, "q.f32"), Path(d, "o.f32")
        mat.write_text(json.dumps(MATERIAL))
        np.concatenate([wo, wi, x], 1).astype("<f4").tofile(qf)
        cmd = ["cargo", "run", "--release", "--quiet", "-p", "scratchwave-capi", "--example",
               "eval_throughput", "--", str(mat), str(qf), str(of), "1"]
        subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True)  # build once
        # Alternate the two so that a busy machine slows both alike.
        for _ in range(repeats):
            t = time.perf_counter()
            f = m.eval(wo, wi, x_um=x)
            py_best = min(py_best, time.perf_counter() - t)
            out = subprocess.run(cmd, cwd=ROOT, check=True, capture_output=True, text=True).stdout
            rust_best = min(rust_best, float(out.strip()) * 1e-9 * n)
        rust_f = np.fromfile(of, dtype="<f4").reshape(n, 3)
    py_ns, rust_ns = py_best * 1e9 / n, rust_best * 1e9 / n
    same = np.array_equal(rust_f.view(np.uint32), f.view(np.uint32))
    print(f"queries {n}, scratches {m.scratch_count}, threads {os.cpu_count()}")
    print(f"rust   {rust_ns:8.1f} ns/query")
    print(f"python {py_ns:8.1f} ns/query")
    print(f"ratio (rust/python) {rust_ns / py_ns:.3f}; values bit-identical: {same}")
    if not same:
        sys.exit(1)


if __name__ == "__main__":
    main()
