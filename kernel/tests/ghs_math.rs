//! The special functions the GHS model added to the math seam, against f64 `std`.

use scratchwave_kernel::math;

#[test]
fn expm1_and_ln1p_keep_relative_accuracy() {
    let mut max = [0.0f64; 2];
    for i in -400..=400 {
        for &sign in &[-1.0f64, 1.0] {
            let x = sign * 10f64.powf(i as f64 / 50.0); // 1e-8 .. 1e8
            let xf = x as f32;
            if xf.abs() < 80.0 {
                let want = (xf as f64).exp_m1();
                let e = ((math::expm1(xf) as f64 - want) / want).abs();
                max[0] = max[0].max(e);
            }
            if xf > -1.0 {
                let want = (xf as f64).ln_1p();
                let e = ((math::ln1p(xf) as f64 - want) / want).abs();
                max[1] = max[1].max(e);
            }
        }
    }
    println!("expm1 max rel {:.1e}, ln1p max rel {:.1e}", max[0], max[1]);
    assert!(max[0] < 1e-6 && max[1] < 1e-6, "{max:?}");
    assert_eq!(math::expm1(0.0), 0.0);
    assert_eq!(math::ln1p(0.0), 0.0);
    assert_eq!(math::expm1(-200.0), -1.0);
    assert!(math::expm1(200.0).is_infinite());
    assert_eq!(math::ln1p(-1.0), f32::NEG_INFINITY);
}

#[test]
fn incomplete_gamma_tails_are_complementary() {
    for &a in &[0.25f32, 0.5, 1.0, 2.5, 10.0] {
        for i in 0..200 {
            let x = 0.01 * (i as f32 + 0.5) * a.max(1.0);
            let (p, q) = (math::gamma_p(a, x), math::gamma_q(a, x));
            assert!((p + q - 1.0).abs() < 2e-6, "a {a} x {x}: {p} + {q}");
        }
        // a = 1: P(1, x) = 1 − e^{−x}
        if a == 1.0 {
            for &x in &[0.1f32, 1.0, 5.0] {
                assert!((math::gamma_p(1.0, x) - (1.0 - (-x).exp())).abs() < 1e-6);
            }
        }
    }
    assert_eq!(math::gamma_p_inv(2.0, 0.0), 0.0);
    assert_eq!(math::gamma_q_inv(2.0, 0.0), f32::MAX);
    assert!(
        math::gamma_q_inv(2.0, f32::NAN) == 0.0 || math::gamma_q_inv(2.0, f32::NAN) == f32::MAX
    );
}
