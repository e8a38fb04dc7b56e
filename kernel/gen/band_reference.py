"""Writes kernel/tests/data/band_integral.json: W^2 * integral_0^q sinc^2(pi W t) dt by mpmath
quadrature (independent of the closed form with Si), and Si(x) at a few points.

Run: python3 kernel/gen/band_reference.py
"""
import json
import mpmath as mp

mp.mp.dps = 30
rows = []
for w in [0.05, 0.2, 1.0, 3.0, 10.0]:
    for q in [-7.3, -1.0, -0.31, -1e-3, 0.0, 1e-4, 0.05, 0.4, 1.7, 4.0, 25.0]:
        f = lambda t: (w * mp.sinc(mp.pi * w * t)) ** 2
        # split at the sinc zeros so the quadrature is exact to many digits
        n = int(abs(q) * w) + 1
        pts = [q * k / n for k in range(n + 1)]
        v = mp.quad(f, pts) if q != 0 else mp.mpf(0)
        rows.append({"width": w, "q": q, "value": float(v)})
si = [{"x": x, "si": float(mp.si(x))} for x in [0.0, 0.01, 0.5, 1.0, 2.0, 3.9, 4.0, 4.1, 6.0, 10.0, 33.0, 150.0, 1e4]]
json.dump({"antiderivative": rows, "si": si}, open("kernel/tests/data/band_integral.json", "w"), indent=1)
print(len(rows), "rows")
