"""Fits the coefficients of kernel/src/lights/si_fast.rs (run: python3 kernel/gen/si_fast_consts.py).

si_fast(x), x >= 0:
  x <= X0:  x * P(x^2)                       (odd polynomial, least squares on [0, X0])
  x >  X0:  pi/2 - f(x) cos x - g(x) sin x,   x f = F(t), x^2 g = G(t), t = (X0/x)^2 in (0, 1]
Targets ~1e-5 absolute error with few terms (cheaper than the exact `math::si`).
"""
import numpy as np
import mpmath as mp

mp.mp.dps = 30
X0 = 4.0
NP, NF, NG = 7, 4, 4


def si(x):
    return float(mp.si(x))


def aux(x):
    x = mp.mpf(x)
    ci, s = mp.ci(x), mp.si(x)
    f = ci * mp.sin(x) - (s - mp.pi / 2) * mp.cos(x)
    g = -ci * mp.cos(x) - (s - mp.pi / 2) * mp.sin(x)
    return float(x * f), float(x * x * g)


xs = np.linspace(1e-3, X0, 800)
A = np.stack([xs ** (2 * k + 1) for k in range(NP)], axis=1)
p = np.linalg.lstsq(A, np.array([si(x) for x in xs]), rcond=None)[0]
ts = np.linspace(1e-4, 1.0, 800)
xx = X0 / np.sqrt(ts)
fg = np.array([aux(x) for x in xx])
F = np.polyfit(ts, fg[:, 0], NF - 1)[::-1]
G = np.polyfit(ts, fg[:, 1], NG - 1)[::-1]


def approx(x):
    if x <= X0:
        return sum(p[k] * x ** (2 * k + 1) for k in range(NP))
    t = (X0 / x) ** 2
    f = np.polyval(F[::-1], t) / x
    g = np.polyval(G[::-1], t) / x ** 2
    return np.pi / 2 - f * np.cos(x) - g * np.sin(x)


test = np.concatenate([np.linspace(0, 12, 3000), np.linspace(12, 400, 2000)])
err = max(abs(approx(x) - si(x)) for x in test)
print("// max abs error", err)
print("P:", [float(v) for v in p])
print("F:", [float(v) for v in F])
print("G:", [float(v) for v in G])
