//! The gamma function family in `f32`: `ln Γ`, the regularized incomplete gamma functions
//! `P(a, x)` / `Q(a, x)` and their inverses (needed by the generalized Beckmann NDF's
//! normalisation and importance sampling; rust-gpu has none of them).
//!
//! Loops have fixed iteration caps (no recursion), so every function is GPU-safe.

const LN_SQRT_2PI: f32 = 0.918_938_533_204_672_7;
const FPMIN: f32 = 1.0e-30;

/// `ln Γ(x)` for `x > 0` (arguments `≤ 0` are treated as `1e-30`).
///
/// Stirling's series from `x ≥ 8` (terms to `1/(1260 x⁵)`, truncation < 3e-10), with the
/// recurrence `Γ(x) = Γ(x + n) / (x (x+1) … (x+n−1))` below. Absolute error ≈ f32 rounding
/// of the result (≤ 2e-6 for x ≤ 20).
pub fn lgamma(x: f32) -> f32 {
    let mut z = super::max(x, 1.0e-30);
    let mut prod = 1.0f32;
    let mut i = 0;
    while z < 8.0 && i < 8 {
        prod *= z;
        z += 1.0;
        i += 1;
    }
    let zi = 1.0 / z;
    let zi2 = zi * zi;
    let series = zi * (1.0 / 12.0 - zi2 * (1.0 / 360.0 - zi2 * (1.0 / 1260.0)));
    (z - 0.5) * super::ln(z) - z + LN_SQRT_2PI + series - super::ln(prod)
}

/// `Γ(x)` for `x > 0` via [`lgamma`] (overflows to `+∞` above x ≈ 35).
#[inline]
pub fn gamma(x: f32) -> f32 {
    super::exp(lgamma(x))
}

/// `x^a e^{−x} / Γ(a)`: the common prefactor, with the exponents combined before `exp`.
#[inline]
fn prefactor(a: f32, x: f32) -> f32 {
    super::exp(a * super::ln(x) - x - lgamma(a))
}

/// Series `Σ xⁿ / (a (a+1) … (a+n))`, converges fast for `x < a + 1`.
fn series_sum(a: f32, x: f32) -> f32 {
    let mut ap = a;
    let mut del = 1.0 / a;
    let mut sum = del;
    let mut i = 0;
    while i < 300 {
        ap += 1.0;
        del *= x / ap;
        sum += del;
        if del < sum * 1.0e-8 {
            break;
        }
        i += 1;
    }
    sum
}

/// Modified Lentz continued fraction for `Q(a, x) / prefactor`, converges for `x ≥ a + 1`.
fn continued_fraction(a: f32, x: f32) -> f32 {
    let mut b = x + 1.0 - a;
    let mut c = 1.0 / FPMIN;
    let mut d = 1.0 / b;
    let mut h = d;
    let mut i = 1;
    while i < 300 {
        let fi = i as f32;
        let an = -fi * (fi - a);
        b += 2.0;
        d = an * d + b;
        if super::abs(d) < FPMIN {
            d = FPMIN;
        }
        c = b + an / c;
        if super::abs(c) < FPMIN {
            c = FPMIN;
        }
        d = 1.0 / d;
        let del = d * c;
        h *= del;
        if super::abs(del - 1.0) < 1.0e-7 {
            break;
        }
        i += 1;
    }
    h
}

/// Regularized lower incomplete gamma `P(a, x) = γ(a, x)/Γ(a)`, `a > 0`, `x ≥ 0`.
pub fn gamma_p(a: f32, x: f32) -> f32 {
    if x <= 0.0 {
        return 0.0;
    }
    if x < a + 1.0 {
        super::min(prefactor(a, x) * series_sum(a, x), 1.0)
    } else {
        super::max(1.0 - prefactor(a, x) * continued_fraction(a, x), 0.0)
    }
}

/// Regularized upper incomplete gamma `Q(a, x) = 1 − P(a, x)`, computed directly in its tail.
pub fn gamma_q(a: f32, x: f32) -> f32 {
    if x <= 0.0 {
        return 1.0;
    }
    if x < a + 1.0 {
        super::max(1.0 - prefactor(a, x) * series_sum(a, x), 0.0)
    } else {
        super::min(prefactor(a, x) * continued_fraction(a, x), 1.0)
    }
}

/// `x` with `P(a, x) = p` (equivalently `Q(a, x) = 1 − p`); see [`gamma_inv`].
#[inline]
pub fn gamma_p_inv(a: f32, p: f32) -> f32 {
    gamma_inv(a, p, 1.0 - p)
}

/// `x` with `Q(a, x) = q`: the inverse of the normalised upper incomplete gamma function.
#[inline]
pub fn gamma_q_inv(a: f32, q: f32) -> f32 {
    gamma_inv(a, 1.0 - q, q)
}

/// Inverse of the regularized incomplete gamma function given both tails `p` and `q = 1 − p`
/// (the smaller one drives the Newton–Halley residual, so neither tail loses precision).
///
/// Initial guess and Halley iteration after Numerical Recipes 3rd ed. §6.2.1 (`invgammp`),
/// at most 16 steps. Returns 0 for `p ≤ 0` and `f32::MAX` for `q ≤ 0`.
pub fn gamma_inv(a: f32, p: f32, q: f32) -> f32 {
    if !(p > 0.0) {
        return 0.0;
    }
    if !(q > 0.0) {
        return f32::MAX;
    }
    let a1 = a - 1.0;
    let gln = lgamma(a);
    let mut x;
    if a > 1.0 {
        let pp = if p < 0.5 { p } else { q };
        let t = super::sqrt(-2.0 * super::ln(pp));
        let mut z = (2.30753 + t * 0.27061) / (1.0 + t * (0.99229 + t * 0.04481)) - t;
        if p < 0.5 {
            z = -z;
        }
        let w = 1.0 - 1.0 / (9.0 * a) - z / (3.0 * super::sqrt(a));
        x = super::max(1.0e-3, a * w * w * w);
    } else {
        let t = 1.0 - a * (0.253 + a * 0.12);
        if p < t {
            x = super::pow(p / t, 1.0 / a);
        } else {
            x = 1.0 - super::ln1p(-(p - t) / (1.0 - t));
            if q < 0.5 {
                // the same guess, from the tail that keeps its digits
                x = 1.0 - super::ln(q / (1.0 - t));
            }
        }
    }
    let mut j = 0;
    while j < 16 {
        if x <= 0.0 {
            return 0.0;
        }
        let err = if p < 0.5 {
            gamma_p(a, x) - p
        } else {
            q - gamma_q(a, x)
        };
        let t = super::exp(a1 * super::ln(x) - x - gln);
        if !(t > 0.0) {
            break;
        }
        let u = err / t;
        let step = u / (1.0 - 0.5 * super::min(1.0, u * (a1 / x - 1.0)));
        x -= step;
        if x <= 0.0 {
            x = 0.5 * (x + step);
        }
        if super::abs(step) < 1.0e-6 * x {
            break;
        }
        j += 1;
    }
    super::max(x, 0.0)
}
