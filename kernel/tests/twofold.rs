//! `math::twofold`: the error-free transformations are exact and the two-fold operations
//! keep about 44 bits, against `f64` (which holds an `f32` sum or product exactly) and, for
//! the square root, quotient and length, against the `f64` results of the `f64` values.

use scratchwave_kernel::math::twofold::{Twofold, dot2, length, two_prod, two_sum};

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

#[test]
fn quotients_and_lengths_keep_44_bits() {
    let v: Vec<Vec<f32>> = (0..4).map(|k| sample(20_000, 20 + k)).collect();
    let (mut worst_div, mut worst_len) = (0.0f64, 0.0f64);
    let quads = v[0].iter().zip(&v[1]).zip(&v[2]).zip(&v[3]);
    for (((&a, &b), &c), &d) in quads {
        // Two-fold operands, each `hi` with a `lo` below half its ulp.
        let x = two_prod(a, b);
        let y = two_sum(c, d * 1e-3);
        let q = x / y;
        let want = wide(x) / wide(y);
        worst_div = worst_div.max((wide(q) - want).abs() / want.abs());
        // The length of a vector (a light's position, a view), its square from exact
        // products (2^±30 components: the squares stay within f32's range).
        let l = length(a, b, c);
        let exact = (f64::from(a).powi(2) + f64::from(b).powi(2) + f64::from(c).powi(2)).sqrt();
        worst_len = worst_len.max((wide(l) - exact).abs() / exact);
    }
    println!("div worst {worst_div:e}; length worst {worst_len:e}");
    assert!(worst_div < 2f64.powi(-44), "div: {worst_div:e}");
    assert!(worst_len < 2f64.powi(-44), "length: {worst_len:e}");
}
