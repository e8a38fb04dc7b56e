//! `math::twofold`: the error-free transformations are exact and the two-fold operations
//! keep about 44 bits, against `f64` (which holds an `f32` sum or product exactly) and, for
//! the square root, against the `f64` root of the `f64` value.

use scratchwave_kernel::math::twofold::{Twofold, dot2, two_prod, two_sum};

/// Seeded values spread over 2^-30 – 2^30 in magnitude, both signs.
fn sample(n: usize, seed: u64) -> Vec<f32> {
    let mut state = seed;
    (0..n)
        .map(|_| {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            let u = (state >> 11) as f64 / (1u64 << 53) as f64;
            let e = ((state >> 3) % 61) as i32 - 30;
            let sign = if state & 1 == 0 { 1.0 } else { -1.0 };
            (sign * (1.0 + u) * 2f64.powi(e)) as f32
        })
        .collect()
}

fn wide(x: Twofold) -> f64 {
    f64::from(x.hi) + f64::from(x.lo)
}

#[test]
fn sums_and_products_are_exact() {
    let (a, b) = (sample(20_000, 1), sample(20_000, 2));
    for (&x, &y) in a.iter().zip(&b) {
        let s = two_sum(x, y);
        assert_eq!(
            wide(s),
            f64::from(x) + f64::from(y),
            "two_sum({x:e}, {y:e})"
        );
        assert_eq!(s.hi, x + y);
        let p = two_prod(x, y);
        assert_eq!(
            wide(p),
            f64::from(x) * f64::from(y),
            "two_prod({x:e}, {y:e})"
        );
        assert_eq!(p.hi, x * y);
    }
}

#[test]
fn dot_products_and_roots_keep_44_bits() {
    let v: Vec<Vec<f32>> = (0..4).map(|k| sample(20_000, 10 + k)).collect();
    let mut worst_dot = 0.0f64;
    let mut worst_root = 0.0f64;
    let quads = v[0].iter().zip(&v[1]).zip(&v[2]).zip(&v[3]);
    for (((&a0, &b0), &a1), &b1) in quads {
        let d = dot2(a0, b0, a1, b1);
        // Each product is exact in f64; their sum is rounded once, 2^-53 of the larger.
        let (p, q) = (f64::from(a0) * f64::from(b0), f64::from(a1) * f64::from(b1));
        let scale = p.abs().max(q.abs());
        let err = (wide(d) - (p + q)).abs() / scale;
        worst_dot = worst_dot.max(err);
        // A root of a two-fold value near 1 (the factors of an angle's sine).
        let x = Twofold {
            hi: 0.5 + 0.25 * a0.abs().fract(),
            lo: 1e-9 * b0.signum(),
        }
        .normalized();
        let r = x.sqrt();
        let exact = wide(x).sqrt();
        worst_root = worst_root.max((wide(r) - exact).abs() / exact);
        let prod = d * r;
        let want = wide(d) * wide(r);
        if want != 0.0 {
            let e = (wide(prod) - want).abs() / want.abs();
            assert!(e < 2f64.powi(-44), "mul: {e:e}");
        }
    }
    println!("dot2 worst {worst_dot:e} of the larger product; sqrt worst {worst_root:e}");
    assert!(worst_dot < 2f64.powi(-44), "dot2: {worst_dot:e}");
    assert!(worst_root < 2f64.powi(-44), "sqrt: {worst_root:e}");
}
