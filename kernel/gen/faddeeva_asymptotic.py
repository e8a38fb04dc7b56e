"""The Faddeeva function's asymptotic branch (kernel/src/math/faddeeva.rs): its threshold
|z|^2 >= 19.7 and its order 10, and the reference points the kernel is tested on there.

w(z) ~ (i/(sqrt(pi) z)) sum_{n>=0} (2n-1)!! / (2 z^2)^n  (Abramowitz & Stegun 7.1.23 with
w(z) = exp(-z^2) erfc(-iz)), evaluated as the kernel does (1/z first, nested from the last
term) in float32 arithmetic, against mpmath's exp(-z^2) erfc(-iz) at 40 digits.

Run: python3 kernel/gen/faddeeva_asymptotic.py
  prints the worst relative error of each order on and above the threshold circle (where
  the series converges slowest: on and near the real axis) and writes
  kernel/tests/data/faddeeva_far.csv, dense points from the threshold out to |z| = 1e6
  (kernel/tests/golden.rs, `faddeeva_far_matches_mpmath`).
"""
import os

import mpmath as mp
import numpy as np

mp.mp.dps = 40
FAR = np.float32(19.7)
HERE = os.path.dirname(os.path.abspath(__file__))


def w_exact(z):
    z = mp.mpc(z.real, z.imag)
    return complex(mp.exp(-z ** 2) * mp.erfc(-1j * z))


def w_series(z, order):
    """The kernel's evaluation in float32: r = 1/z, u = r^2/2, t = 1 + (2n-1) u t."""
    z = np.complex64(z)
    r = np.complex64(1) / z
    u = np.complex64(r * r * np.float32(0.5))
    t = np.complex64(1)
    for n in range(order, 0, -1):
        t = np.complex64(1) + np.complex64(u * t) * np.float32(2 * n - 1)
    return complex(np.complex64(np.complex64(1j) * r * t) * np.float32(1 / np.sqrt(np.pi)))


def points():
    """On and above the threshold circle: radii from sqrt(19.7) to 1.5 times it (dense), then
    out to 1e6; angles over the closed upper half plane, the real axis included."""
    r0 = float(np.sqrt(FAR))
    pts = []
    for r in list(np.linspace(r0, 1.5 * r0, 60)) + list(np.geomspace(1.5 * r0, 1e6, 25)):
        for a in np.linspace(0.0, np.pi, 37):
            z = complex(np.complex64(complex(r * np.cos(a), max(r * np.sin(a), 0.0))))
            if z.real ** 2 + z.imag ** 2 >= FAR:
                pts.append(z)
    return pts


def main():
    pts = points()
    exact = [w_exact(z) for z in pts]
    for order in (8, 9, 10, 11, 12):
        worst = max(abs(w_series(z, order) - e) / abs(e) for z, e in zip(pts, exact))
        print(f"order {order}: worst relative {worst:.3e} over {len(pts)} points")
    path = os.path.join(HERE, "..", "tests", "data", "faddeeva_far.csv")
    with open(path, "w") as f:
        f.write("re,im,w_re,w_im\n")
        for z, e in zip(pts, exact):
            f.write(f"{z.real!r},{z.imag!r},{e.real!r},{e.imag!r}\n")
    print(f"wrote {os.path.normpath(path)}")


if __name__ == "__main__":
    main()
