//! The exponentially scaled modified Bessel function `e^{−x} I₀(x)` (x ≥ 0), for the von
//! Mises–Fisher ring density of Werner 2017 §5, whose `I₀(κ sinθi sinθo)` overflows `f32`
//! for the concentrations a coherence window needs (κ ~ 10⁴).
//!
//! Polynomial approximations of Abramowitz & Stegun 9.8.1 (`|x| ≤ 3.75`, relative error
//! < 1.6e-7) and 9.8.2 (`x ≥ 3.75`, `√x e^{−x} I₀(x)`, relative error < 1.9e-7); checked
//! against `I₀(x) = (1/π)∫₀^π e^{x cos t} dt` by quadrature in `kernel/tests/bsdf_parts.rs`.

use super::{abs, exp, sqrt};

/// `e^{−|x|} I₀(x)`: finite for every finite `x`, 1 at 0, `≈ 1/√(2π|x|)` for large `|x|`.
#[inline]
pub fn bessel_i0e(x: f32) -> f32 {
    let ax = abs(x);
    if ax <= 3.75 {
        let t = (ax / 3.75) * (ax / 3.75);
        let p = 1.0
            + t * (3.515_622_9
                + t * (3.089_942_4
                    + t * (1.206_749_2 + t * (0.265_973_2 + t * (0.036_076_8 + t * 0.004_581_3)))));
        p * exp(-ax)
    } else {
        let t = 3.75 / ax;
        let p = 0.398_942_28
            + t * (0.013_285_92
                + t * (0.002_253_19
                    + t * (-0.001_575_65
                        + t * (0.009_162_81
                            + t * (-0.020_577_06
                                + t * (0.026_355_37 + t * (-0.016_476_33 + t * 0.003_923_77)))))));
        p / sqrt(ax)
    }
}
