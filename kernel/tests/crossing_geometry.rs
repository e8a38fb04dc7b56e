//! The crossing correction's geometry (issue #21, `scratch::crossing`): continuous in the
//! crossing angle through 90° (where the other groove's edges turn vertical in the cut-away
//! groove's frame and the slabs become slivers) and towards parallel grooves, zero for
//! grooves apart, and, with the exact window and unequal depths, independent of which
//! groove comes first. The values themselves are checked against the heightfield reference
//! in `testkit/tests/heightfield_reference.rs`.

use scratchwave_kernel::scratch::crossing::{
    Share, crossing_correction_lanes, crossing_overlap_weight_lanes,
};
use scratchwave_kernel::scratch::{Scratch, Window};

const SIGMA: f32 = 10.0;
const LAMBDA_UM: f32 = 0.55;
/// The walk's disk around x0 = 0 (6σ).
const NEAR: (glam::Vec2, f32) = (glam::Vec2::ZERO, 60.0);

fn groove(angle_deg: f32, depth: f32, profile: u32) -> Scratch {
    let a = angle_deg.to_radians();
    Scratch {
        center: [2.0, 0.0],
        tangent: [a.cos(), a.sin()],
        half_len: 500.0,
        width: 3.0,
        depth,
        profile,
    }
}

/// The correction at a few directions, for the pair at `angle` degrees.
fn corrections(angle: f32, profile: u32, window: Window, depths: (f32, f32)) -> Vec<(f32, f32)> {
    let a = groove(20.0, depths.0, profile);
    let b = groove(20.0 + angle, depths.1, profile);
    let (fa, fb) = (a.frame().unwrap(), b.frame().unwrap());
    [[0.0f32, 0.0, 1.0], [0.3, -0.2, 0.93], [-0.6, 0.1, 0.79]]
        .iter()
        .map(|wo| {
            let xi = [wo[0] / LAMBDA_UM, wo[1] / LAMBDA_UM];
            let depth = 2.0 * (1.0 + wo[2]) / LAMBDA_UM;
            let c = crossing_correction_lanes(
                a,
                fa,
                b,
                fb,
                [0.0f32, 0.0],
                xi,
                depth,
                SIGMA,
                window,
                NEAR,
                Share::Both,
            );
            (c.re, c.im)
        })
        .collect()
}

fn max_rel(x: &[(f32, f32)], y: &[(f32, f32)]) -> f32 {
    x.iter()
        .zip(y)
        .map(|(p, q)| {
            let d = ((p.0 - q.0).powi(2) + (p.1 - q.1).powi(2)).sqrt();
            d / (q.0.powi(2) + q.1.powi(2)).sqrt()
        })
        .fold(0.0, f32::max)
}

/// Through 90°: 89.99°, 90° and 90.01° agree to 1e-3 (the change of the overlap's area,
/// ~1e-7, is far below), both profiles, both windows. Before the slabs narrower than their
/// chord were integrated across, the frozen window at exactly 90° was 2× off (rectangles)
/// and 20× off (V grooves): the along-`u` first moment cancelled catastrophically.
#[test]
fn continuous_through_ninety_degrees() {
    for profile in [0, 1] {
        for window in [Window::Frozen, Window::Exact] {
            let at = corrections(90.0, profile, window, (0.2, 0.2));
            for near in [89.99, 90.01] {
                let e = max_rel(&corrections(near, profile, window, (0.2, 0.2)), &at);
                assert!(
                    e < 1e-3,
                    "profile {profile} {window:?} {near}°: {e:.2e} from 90°"
                );
            }
        }
    }
}

/// Towards parallel grooves the overlap grows as 1/sin α until the segments' ends bound it.
/// At the mirror direction the correction is the window's integral over the overlap times
/// `1 − T`, which changes by ~1 % per halving of α here (the heightfield reference gives
/// 121.37 − 55.43i, 122.53 − 55.96i and 123.11 − 56.22i µm² at 0.4°, 0.2° and 0.1°,
/// `reference/heightfield.py`'s `region_S` over its `overlap_pieces`); the correction
/// follows it through the switch from the parallelogram to the nearly-parallel construction
/// (between 0.4° and 0.2° for these 1 mm grooves), and is finite at exactly 0°.
#[test]
fn continuous_towards_parallel() {
    let reference = [
        (0.4f32, (121.365_93f32, -55.425_965f32)),
        (0.2, (122.528_415, -55.956_852)),
        (0.1, (123.109_69, -56.222_31)),
    ];
    for (angle, want) in reference {
        let c = corrections(angle, 0, Window::Exact, (0.2, 0.1))[0];
        let e = max_rel(&[c], &[want]);
        assert!(
            e < 1e-4,
            "{angle}°: {c:?} against the reference {want:?} ({e:.2e})"
        );
    }
    for profile in [0, 1] {
        let c = corrections(0.0, profile, Window::Exact, (0.2, 0.1));
        assert!(
            c.iter().all(|z| z.0.is_finite() && z.1.is_finite()),
            "0°: {c:?}"
        );
    }
}

/// Grooves that do not touch need no correction, and the overlap's window weight is 0.
#[test]
fn apart_grooves_have_no_correction() {
    let a = groove(20.0, 0.2, 0);
    let mut b = groove(110.0, 0.2, 1);
    b.center = [2.0, 20.0];
    b.half_len = 5.0;
    let (fa, fb) = (a.frame().unwrap(), b.frame().unwrap());
    for window in [Window::Frozen, Window::Exact] {
        let c = crossing_correction_lanes(
            a,
            fa,
            b,
            fb,
            [0.0f32, 0.0],
            [1.0, 0.5],
            7.0,
            SIGMA,
            window,
            NEAR,
            Share::Both,
        );
        assert_eq!((c.re, c.im), (0.0, 0.0));
        let w = crossing_overlap_weight_lanes(a, fa, b, fb, [0.0f32, 0.0], SIGMA, window, NEAR);
        assert_eq!(w, 0.0);
    }
}

/// With the exact window and unequal depths nothing depends on the pair's order.
#[test]
fn order_free_for_unequal_depths_and_the_exact_window() {
    for profile in [0, 1] {
        let a = groove(20.0, 0.2, profile);
        let b = groove(65.0, 0.1, profile);
        let (fa, fb) = (a.frame().unwrap(), b.frame().unwrap());
        let ab = crossing_correction_lanes(
            a,
            fa,
            b,
            fb,
            [0.0f32, 0.0],
            [0.8, -0.3],
            6.0,
            SIGMA,
            Window::Exact,
            NEAR,
            Share::Both,
        );
        let ba = crossing_correction_lanes(
            b,
            fb,
            a,
            fa,
            [0.0f32, 0.0],
            [0.8, -0.3],
            6.0,
            SIGMA,
            Window::Exact,
            NEAR,
            Share::Both,
        );
        let e = ((ab.re - ba.re).powi(2) + (ab.im - ba.im).powi(2)).sqrt() / ab.norm_sqr().sqrt();
        assert!(e < 1e-4, "profile {profile}: {ab:?} vs {ba:?}");
    }
}

/// The overlap's window weight of two perpendicular 3 µm grooves crossing at the window's
/// centre is the window over a 3 µm square: `(∫_{−1.5}^{1.5} e^{−x²/2σ²} dx)²`.
#[test]
fn overlap_weight_of_a_centred_square() {
    let mut a = groove(0.0, 0.2, 0);
    let mut b = groove(90.0, 0.1, 0);
    a.center = [0.0, 0.0];
    b.center = [0.0, 0.0];
    let (fa, fb) = (a.frame().unwrap(), b.frame().unwrap());
    let w = crossing_overlap_weight_lanes(a, fa, b, fb, [0.0f32, 0.0], SIGMA, Window::Exact, NEAR);
    // ∫_{−1.5}^{1.5} e^{−x²/200} dx by Simpson's rule in f64.
    let n = 2000;
    let h = 3.0 / n as f64;
    let f = |x: f64| (-x * x / 200.0).exp();
    let mut s = f(-1.5) + f(1.5);
    for i in 1..n {
        s += f(-1.5 + i as f64 * h) * if i % 2 == 1 { 4.0 } else { 2.0 };
    }
    let side = s * h / 3.0;
    let want = side * side;
    assert!(((w as f64) / want - 1.0).abs() < 1e-5, "{w} vs {want}");
}

/// The shares ([`Share::First`], [`Share::Second`]) split the pair's correction by the groove
/// cut away: they sum to the whole, the deeper of two rectangles loses nothing (it is never
/// the shallower one), and for V grooves of one depth each loses a part of the overlap.
#[test]
fn shares_split_the_correction_by_the_groove_cut_away() {
    let share = |a: Scratch, b: Scratch, window: Window, share: Share| {
        let (fa, fb) = (a.frame().unwrap(), b.frame().unwrap());
        crossing_correction_lanes(
            a,
            fa,
            b,
            fb,
            [0.0f32, 0.0],
            [0.5, -0.2],
            6.5,
            SIGMA,
            window,
            NEAR,
            share,
        )
    };
    for window in [Window::Frozen, Window::Exact] {
        for (profile, depths) in [(0, (0.2, 0.1)), (0, (0.1, 0.2)), (1, (0.2, 0.2))] {
            let a = groove(20.0, depths.0, profile);
            let b = groove(65.0, depths.1, profile);
            let whole = share(a, b, window, Share::Both);
            let first = share(a, b, window, Share::First);
            let second = share(a, b, window, Share::Second);
            let sum = first + second;
            let e = (sum - whole).norm_sqr().sqrt() / whole.norm_sqr().sqrt();
            assert!(
                e < 1e-6,
                "{window:?} profile {profile} {depths:?}: {first:?} + {second:?} vs {whole:?}"
            );
            if profile == 0 {
                let (deeper, shallower) = if depths.0 > depths.1 {
                    (first, second)
                } else {
                    (second, first)
                };
                assert_eq!((deeper.re, deeper.im), (0.0, 0.0), "{window:?} {depths:?}");
                assert_eq!(
                    (shallower.re, shallower.im),
                    (whole.re, whole.im),
                    "{window:?} {depths:?}"
                );
            } else {
                // Equal V grooves: each is the shallower one on part of the overlap.
                let (f, s) = (first.norm_sqr().sqrt(), second.norm_sqr().sqrt());
                let w = whole.norm_sqr().sqrt();
                assert!(f > 0.05 * w && s > 0.05 * w, "{window:?}: {f} {s} of {w}");
            }
        }
    }
}
