//! Physical invariants of the Werner/Velinov models, each checked against an independent
//! f64 computation written here (never against the kernel's own output).

use scratchwave_kernel::material::{FresnelAngle, Material};
use scratchwave_kernel::scratch::{
    Crossings, Profile, Scratch, ScratchSlice, Window, scratch_area_density,
};
use scratchwave_kernel::table::{Model, TableParams, TableQuery, evaluate};
use std::f64::consts::PI;

fn params(model: Model, exact_depth: bool) -> TableParams {
    TableParams {
        model: model as u32,
        depth_term: exact_depth as u32,
        sigma_um: 10.0,
        ..Default::default()
    }
}

fn query(wi: [f64; 3], wo: [f64; 3], lambda_nm: f32, f: f32) -> TableQuery {
    let n = |v: [f64; 3]| {
        let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        [(v[0] / l) as f32, (v[1] / l) as f32, (v[2] / l) as f32]
    };
    TableQuery {
        wi: n(wi),
        wo: n(wo),
        lambda_nm,
        material: Material::constant(f),
        ..Default::default()
    }
}

/// `wo` with direction cosines `(α, β)` (projected-disk coordinates).
fn dir(a: f64, b: f64) -> [f64; 3] {
    [a, b, (1.0 - a * a - b * b).max(0.0).sqrt()]
}

fn rect(p0: [f32; 2], p1: [f32; 2], w: f32, d: f32) -> Scratch {
    let f = |p: [f32; 2]| [f64::from(p[0]), f64::from(p[1])];
    Scratch::from_endpoints(f(p0), f(p1), w, d, Profile::Rect)
}

/// Directional albedo `∫ f cosθo dωo = ∫ f dα dβ` of a flat mirror equals F.
#[test]
fn flat_mirror_albedo_is_f() {
    let set = ScratchSlice { scratches: &[] };
    for (theta_i, lambda) in [(0.0f64, 500.0f32), (0.6, 380.0), (1.2, 780.0)] {
        let wi = [-theta_i.sin(), 0.0, theta_i.cos()];
        let (a0, b0) = (theta_i.sin(), 0.0); // mirror direction cosines
        // The lobe is a Gaussian of standard deviation λ/(2√2 πσ) ≈ 0.0088 in (α, β) at most.
        let (h, n) = (0.08f64, 400);
        let step = 2.0 * h / n as f64;
        let mut sum = 0.0;
        for i in 0..n {
            for j in 0..n {
                let a = a0 - h + (i as f64 + 0.5) * step;
                let b = b0 - h + (j as f64 + 0.5) * step;
                if a * a + b * b < 1.0 {
                    let q = query(wi, dir(a, b), lambda, 0.7);
                    sum +=
                        f64::from(evaluate(&params(Model::Werner, true), &q, &set)) * step * step;
                }
            }
        }
        assert!(
            (sum - 0.7).abs() < 2e-4,
            "θi={theta_i} λ={lambda}: albedo {sum}, expected 0.7"
        );
    }
}

/// One long rectangular scratch through x0, seen along its bitangent: `|S|² ∝ sinc²(πWξ₂)`
/// with constant depth term (small-angle) and constant η.
#[test]
fn single_scratch_is_a_sinc_squared_lobe() {
    let (w, d, lambda) = (3.0f32, 0.2f32, 0.5f64);
    let s = [rect([-5000.0, 0.0], [5000.0, 0.0], w, d)];
    let set = ScratchSlice { scratches: &s };
    let p = params(Model::WernerBlended, false);
    let wi = [0.0, 0.0, 1.0];
    let f0 = f64::from(evaluate(&p, &query(wi, dir(0.0, 0.0), 500.0, 1.0), &set));
    // Independent value at ξ = 0: F/(πσ²λ²) |W (1 − e^{i4πD/λ}) √(2π)σ|².
    let sigma = 10.0f64;
    let depth = (2.0 - 2.0 * (4.0 * PI * f64::from(d) / lambda).cos()) * f64::from(w * w);
    let expect0 = depth * 2.0 * PI * sigma * sigma / (PI * sigma * sigma * lambda * lambda);
    assert!((f0 / expect0 - 1.0).abs() < 1e-5, "peak {f0} vs {expect0}");
    for k in 1..200 {
        let beta = k as f64 * 0.004; // direction cosine along the bitangent (= +y)
        let xi2 = beta / lambda;
        let x = PI * f64::from(w) * xi2;
        let sinc2 = (x.sin() / x).powi(2);
        let f = f64::from(evaluate(&p, &query(wi, dir(0.0, beta), 500.0, 1.0), &set));
        let rel = (f - f0 * sinc2).abs() / f0;
        assert!(
            rel < 2e-6,
            "β={beta}: {f} vs {} (rel to peak {rel})",
            f0 * sinc2
        );
    }
}

/// Parallel scratches of width W spaced W apart cover the window: ρc = 1 (the printed
/// Velinov Eq. 17 would give 2).
#[test]
fn fully_scratched_window_has_unit_area_density() {
    let w = 0.5f32;
    let s: Vec<Scratch> = (-200..=200)
        .map(|k| {
            let y = k as f32 * w;
            rect([-1000.0, y], [1000.0, y], w, 0.1)
        })
        .collect();
    let rho = scratch_area_density(
        &ScratchSlice { scratches: &s },
        glam::Vec2::new(0.3, 0.1),
        10.0,
        Window::Frozen,
        Crossings::Summed,
    );
    assert!((rho - 1.0).abs() < 1e-4, "ρc = {rho}");
}

/// Two crossed layers of abutting strips scratch every point of the window twice: ρc is 2
/// with Werner's summed crossings and 1 with the deeper cut counted once (issue #21), for
/// both windows. (Strips of one layer touch along their edges only: zero overlap.)
#[test]
fn deepest_crossings_count_a_doubly_scratched_window_once() {
    let w = 2.0f32;
    let mut s: Vec<Scratch> = Vec::new();
    for k in -60..=60 {
        let c = k as f32 * w;
        s.push(rect([-1000.0, c], [1000.0, c], w, 0.1));
        s.push(rect([c, -1000.0], [c, 1000.0], w, 0.2));
    }
    let set = ScratchSlice { scratches: &s };
    let x = glam::Vec2::new(0.3, 0.1);
    for window in [Window::Frozen, Window::Exact] {
        let summed = scratch_area_density(&set, x, 10.0, window, Crossings::Summed);
        let deepest = scratch_area_density(&set, x, 10.0, window, Crossings::Deepest);
        assert!(
            (summed - 2.0).abs() < 2e-4,
            "{window:?} summed ρc = {summed}"
        );
        assert!(
            (deepest - 1.0).abs() < 2e-4,
            "{window:?} deepest ρc = {deepest}"
        );
    }
}

/// Werner's BRDF depends on wi, wo only through ξ ∝ wi + wo, γ = wi.z + wo.z and F(θd):
/// swapping them changes nothing.
#[test]
fn models_are_reciprocal() {
    let s = [
        rect([-30.0, -4.0], [25.0, 9.0], 1.5, 0.3),
        Scratch {
            profile: Profile::Triangle as u32,
            ..rect([3.0, -20.0], [-2.0, 30.0], 2.5, 0.8)
        },
    ];
    let set = ScratchSlice { scratches: &s };
    let mut p = params(Model::Werner, true);
    for (i, (wi, wo)) in [
        ([0.3, 0.1, 0.9], [-0.2, 0.05, 0.8]),
        ([0.0, 0.6, 0.5], [0.01, -0.5, 0.7]),
    ]
    .into_iter()
    .enumerate()
    {
        for model in [Model::Werner, Model::WernerBlended, Model::Velinov] {
            p.model = model as u32;
            let mut a = query(wi, wo, 550.0, 1.0);
            a.material = Material::ior(0.2, 3.0, FresnelAngle::ThetaD);
            let mut b = a;
            b.wi = a.wo;
            b.wo = a.wi;
            let (fa, fb) = (evaluate(&p, &a, &set), evaluate(&p, &b, &set));
            assert!(
                (fa - fb).abs() <= 2e-6 * fa.abs().max(1e-30),
                "case {i} {model:?}: {fa} vs {fb}"
            );
        }
    }
}

/// A groove of zero depth is no groove: mask and profile cancel for both profiles (to f32
/// resolution of the lobe's peak; the triangle's `M − P` is a difference of O(W) terms).
#[test]
fn zero_depth_scratch_changes_nothing() {
    for profile in [Profile::Rect, Profile::Triangle] {
        let s = [Scratch {
            profile: profile as u32,
            ..rect([-50.0, 1.0], [40.0, -3.0], 2.0, 0.0)
        }];
        let set = ScratchSlice { scratches: &s };
        let empty = ScratchSlice { scratches: &[] };
        let p = params(Model::Werner, true);
        let peak = evaluate(
            &p,
            &query([0.1, 0.0, 1.0], [-0.1, 0.0, 1.0], 600.0, 1.0),
            &empty,
        );
        for k in 0..50 {
            let q = query(
                [0.1, 0.0, 1.0],
                dir(-0.1 + 0.002 * k as f64, 0.001 * k as f64),
                600.0,
                1.0,
            );
            let (a, b) = (evaluate(&p, &q, &set), evaluate(&p, &q, &empty));
            assert!(
                (a - b).abs() <= 1e-6 * peak,
                "{profile:?} k={k}: {a} vs {b} (peak {peak})"
            );
        }
    }
}
