//! `math::portable::sin_cos_within_half_pi` (the footprint quadrature's node angles) against
//! f64 `sin`/`cos` over its whole range `|θ| ≤ π/2`: every f32 near 0, ±π/4 (where it
//! switches to the complement) and ±π/2 (where `cos θ` → 0 must keep its relative
//! accuracy), and a uniform sweep between.

mod sweep_common;

use scratchwave_kernel::math::portable::sin_cos_within_half_pi;
use sweep_common::ulps;

/// f32 values: 20 000 consecutive ones on each side of each anchor, and a uniform sweep.
fn inputs() -> Vec<f32> {
    let mut v = Vec::new();
    let half_pi = core::f32::consts::FRAC_PI_2;
    for anchor in [0.0f32, core::f32::consts::FRAC_PI_4, half_pi] {
        let mut x = anchor;
        let mut y = anchor;
        for _ in 0..20_000 {
            v.extend([x, -x, y, -y]);
            x = f32::from_bits(x.to_bits() + 1);
            y = f32::from_bits(y.to_bits().saturating_sub(1));
        }
    }
    let n = 1 << 20;
    for i in 0..=n {
        v.push(-half_pi + 2.0 * half_pi * (i as f32 / n as f32));
    }
    v.into_iter()
        .filter(|x| x.abs() <= half_pi && x.is_finite())
        .collect()
}

#[test]
fn within_two_ulp_of_f64_everywhere_in_range() {
    let (mut worst_s, mut worst_c) = ((0.0f64, 0.0f32), (0.0f64, 0.0f32));
    for x in inputs() {
        let (s, c) = sin_cos_within_half_pi(x);
        let t = f64::from(x);
        let (es, ec) = (ulps(s, t.sin()), ulps(c, t.cos()));
        if es > worst_s.0 {
            worst_s = (es, x);
        }
        if ec > worst_c.0 {
            worst_c = (ec, x);
        }
    }
    println!(
        "sin worst {:.2} ulp at {:e}, cos worst {:.2} ulp at {:e}",
        worst_s.0, worst_s.1, worst_c.0, worst_c.1
    );
    assert!(worst_s.0 <= 2.0, "sin: {worst_s:?}");
    assert!(worst_c.0 <= 2.0, "cos: {worst_c:?}");
}
