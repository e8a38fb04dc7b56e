"""Coefficients of the kernel's arctangent polynomial (`kernel/src/math/atan.rs`).

atan(u) = u + u·z·P(z), z = u², on |u| ≤ tan(π/8) (the kernel reduces every argument to
that range). P (degree 3) is a weighted least-squares fit of (atan(u) − u)/(u z) on 200
Chebyshev nodes in z, the weight z making the fit's error an error relative to atan(u).
Prints the f32 coefficients and the worst relative error of the f32 evaluation (Horner,
as in the kernel) against mpmath on 200 001 points.

Run: python3 reference/math/atan_fit.py   (numpy, mpmath)
"""
import mpmath as mp
import numpy as np

mp.mp.dps = 30
T = float(mp.tan(mp.pi / 8))
ZMAX = T * T
DEG = 3
N = 200


def g(z):
    if z == 0:
        return mp.mpf(-1) / 3
    u = mp.sqrt(z)
    return (mp.atan(u) - u) / (u * z)


zs = [ZMAX * (1 - np.cos(np.pi * (k + 0.5) / N)) / 2 for k in range(N)]
A = np.array([[z**j for j in range(DEG + 1)] for z in zs])
b = np.array([float(g(mp.mpf(z))) for z in zs])
w = np.array(zs)
c, *_ = np.linalg.lstsq(A * w[:, None], b * w, rcond=None)
c32 = [np.float32(x) for x in c]

worst = 0.0
for u in np.linspace(-T, T, 200001).astype(np.float32):
    if u == 0:
        continue
    z = np.float32(u * u)
    p = np.float32(0)
    for cc in reversed(c32):
        p = np.float32(p * z + cc)
    r = np.float32(u + np.float32(np.float32(u * z) * p))
    ex = mp.atan(mp.mpf(float(u)))
    worst = max(worst, abs(float((mp.mpf(float(r)) - ex) / ex)))

print("P coefficients (z^0 .. z^3):", ", ".join(repr(float(x)) for x in c32))
print("max relative error of the f32 evaluation: %.3g (%.2f ulp)" % (worst, worst / 2**-23))
