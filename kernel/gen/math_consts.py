"""Generates the constant tables of kernel/src/math/{faddeeva,si}.rs.

Run: python3 kernel/gen/math_consts.py  (prints Rust source fragments; numpy + mpmath).

* Faddeeva w(z): Weideman (1994), "Computation of the complex error function",
  SIAM J. Numer. Anal. 31(5): w(z) = 2 p(Z)/(L - iz)^2 + 1/(sqrt(pi) (L - iz)),
  Z = (L + iz)/(L - iz), p a polynomial of degree N-1 whose coefficients come from an FFT.
* Si(x) for |x| > X0: Si = pi/2 - f(x) cos x - g(x) sin x (auxiliary functions, A&S 5.2.8/9).
  x f(x) and x^2 g(x) are smooth in t = (X0/x)^2 in (0, 1]; fitted by Chebyshev least squares
  against mpmath at 40 digits.
"""
import numpy as np
import mpmath as mp

mp.mp.dps = 40


def weideman(n):
    m = 2 * n
    m2 = 2 * m
    k = np.arange(-m + 1, m)
    big_l = np.sqrt(n / np.sqrt(2.0))
    theta = k * np.pi / m
    t = big_l * np.tan(theta / 2)
    f = np.exp(-t ** 2) * (big_l ** 2 + t ** 2)
    f = np.concatenate([[0.0], f])
    a = np.real(np.fft.fft(np.fft.fftshift(f))) / m2
    a = a[1:n + 1][::-1]  # highest degree first (polyval order)
    return big_l, a


def si_aux(x):
    x = mp.mpf(x)
    si = mp.si(x)
    ci = mp.ci(x)
    # f = Ci sin x - (Si - pi/2) cos x ; g = -Ci cos x - (Si - pi/2) sin x
    f = ci * mp.sin(x) - (si - mp.pi / 2) * mp.cos(x)
    g = -ci * mp.cos(x) - (si - mp.pi / 2) * mp.sin(x)
    return f, g


def fit_si(x0, deg):
    ts = np.cos(np.pi * (np.arange(400) + 0.5) / 400) * 0.5 + 0.5  # Chebyshev nodes in (0,1)
    xs = x0 / np.sqrt(ts)
    xf, x2g = [], []
    for x in xs:
        f, g = si_aux(x)
        xf.append(float(f * x))
        x2g.append(float(g * x * x))
    pf = np.polynomial.chebyshev.Chebyshev.fit(ts, xf, deg, domain=[0, 1]).convert(kind=np.polynomial.Polynomial)
    pg = np.polynomial.chebyshev.Chebyshev.fit(ts, x2g, deg, domain=[0, 1]).convert(kind=np.polynomial.Polynomial)
    # check
    err = 0.0
    for x in np.linspace(x0, 200 * x0, 3000):
        t = (x0 / x) ** 2
        f = pf(t) / x
        g = pg(t) / x ** 2
        approx = np.pi / 2 - f * np.cos(x) - g * np.sin(x)
        exact = float(mp.si(x))
        err = max(err, abs(approx - exact) / abs(exact))
    return pf.coef, pg.coef, err


def main():
    big_l, a = weideman(32)
    print(f"// Weideman N = 32, L = {big_l!r}")
    print(f"const L: f32 = {float(big_l)!r};")
    print("const COEFFS: [f32; 32] = [")
    for c in a:
        print(f"    {float(c)!r},")
    print("];")
    for deg in (8, 10, 12):
        cf, cg, err = fit_si(6.0, deg)
        print(f"// Si aux fit X0=6 deg={deg}: max rel err (f64 eval) {err:.3e}")
    cf, cg, err = fit_si(6.0, 8)
    print("const SI_F: [f32; 9] = [", ", ".join(repr(float(c)) for c in cf), "];")
    print("const SI_G: [f32; 9] = [", ", ".join(repr(float(c)) for c in cg), "];")


if __name__ == "__main__":
    main()
