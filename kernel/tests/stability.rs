//! Stability: 10^6 adversarial inputs through the table models and the footprint averages,
//! asserting finite, non-negative output below an a-priori bound.
//!
//! Adversarial means: grazing and below-horizon directions, ξ₂ exactly on sinc zeros,
//! triangle profiles on their (removable) poles β = ±κ, zero-length and 10 mm segments,
//! scratches 20σ away, W = 0 or D = 0, λ at 380 and 780 nm, tiny and huge σ.
//! Bound: |B| ≤ 2πσ², |M − P| ≤ 2W and |η| ≤ √(2π)σ, so
//! `f ≤ F/(πσ²λ²) (2πσ² + Σ 2W√(2π)σ)²` for every model.

use scratchwave_kernel::footprint::{
    Ellipse, eta_p_accurate, eta_p_eq15, eta_p_eq16, rho_p_accurate,
};
use scratchwave_kernel::material::{FresnelAngle, Material};
use scratchwave_kernel::scratch::{Profile, Scratch, ScratchSlice};
use scratchwave_kernel::table::{Model, TableParams, TableQuery, evaluate};
use std::f32::consts::PI;

/// SplitMix64: a small deterministic generator (the test must be replayable).
struct Rng(u64);
impl Rng {
    fn u(&mut self) -> f32 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 40) as f32 / (1u64 << 24) as f32
    }
    fn pick<T: Copy>(&mut self, xs: &[T]) -> T {
        xs[((self.u() * xs.len() as f32) as usize).min(xs.len() - 1)]
    }
}

fn direction(r: &mut Rng) -> [f32; 3] {
    let (u1, u2) = (r.u(), r.u());
    let z = r.pick(&[0.0, 1e-7, 1e-3, 0.02, -0.1, u1, u2, 1.0]);
    let phi = 2.0 * PI * r.u();
    let s = (1.0 - z * z).max(0.0).sqrt();
    [s * phi.cos(), s * phi.sin(), z]
}

fn scratch(r: &mut Rng, sigma: f32) -> Scratch {
    let far = r.pick(&[0.0, 0.5, 3.0, 20.0]) * sigma;
    let len = r.pick(&[0.0, 1e-3, 0.1 * sigma, 5.0 * sigma, 10_000.0]);
    let a = 2.0 * PI * r.u();
    let c = [far * (r.u() - 0.5), far * (r.u() - 0.5)];
    Scratch {
        center: c,
        tangent: [a.cos(), a.sin()],
        half_len: 0.5 * len,
        width: r.pick(&[0.0, 0.05, 1.0, 3.0, 25.0]),
        depth: r.pick(&[0.0, 1e-4, 0.2, 1.3, 5.0]),
        profile: r.pick(&[Profile::Rect as u32, Profile::Triangle as u32]),
    }
}

#[test]
fn table_models_are_finite_and_bounded() {
    let mut r = Rng(0x5eed);
    let mut count = 0usize;
    while count < 1_000_000 {
        let sigma = r.pick(&[10.0, 10.0, 0.5, 200.0]);
        let n = r.pick(&[0usize, 1, 1, 3, 6]);
        let scratches: Vec<Scratch> = (0..n).map(|_| scratch(&mut r, sigma)).collect();
        let set = ScratchSlice {
            scratches: &scratches,
        };
        let params = TableParams {
            model: r.pick(&[0u32, 1, 2]),
            eta: r.pick(&[0u32, 1]),
            depth_term: r.pick(&[0u32, 1]),
            base_gaussian: r.pick(&[0u32, 1]),
            sigma_um: sigma,
            ..Default::default()
        };
        for _ in 0..50 {
            let u = r.u();
            let lambda_nm = r.pick(&[380.0, 780.0, 380.0 + 400.0 * u]);
            let lam = lambda_nm * 1e-3;
            let mut wi = direction(&mut r);
            let mut wo = direction(&mut r);
            // Put ξ₂ exactly on a sinc zero / triangle pole of the first scratch.
            let nudge = r.u() < 0.3;
            if let (Some(s), true) = (scratches.first(), nudge)
                && let Some(f) = s.frame()
            {
                let k = r.pick(&[1.0f32, 2.0, -3.0]);
                let target = if s.width > 0.0 {
                    k * lam / s.width
                } else {
                    0.0
                };
                let gamma = wi[2].max(0.0) + wo[2].max(0.0);
                let pole = 2.0 * gamma * s.depth / s.width.max(1e-6) * r.pick(&[1.0f32, -1.0]);
                let shift = if r.u() < 0.5 { target } else { pole * lam };
                let cur = (wi[0] + wo[0]) * f.bitangent.x + (wi[1] + wo[1]) * f.bitangent.y;
                let d = shift - cur;
                wo[0] += d * f.bitangent.x;
                wo[1] += d * f.bitangent.y;
                let l = (wo[0] * wo[0] + wo[1] * wo[1]).min(1.0);
                wo[2] = (1.0 - l).max(0.0).sqrt();
            }
            if r.u() < 0.05 {
                std::mem::swap(&mut wi, &mut wo);
            }
            let material = if r.u() < 0.5 {
                Material::constant(r.u())
            } else {
                Material::ior(
                    r.pick(&[0.05, 1.0, 1.5, 2.5]),
                    r.pick(&[0.0, 3.0, 10.0]),
                    FresnelAngle::ThetaD,
                )
            };
            let q = TableQuery {
                wi,
                wo,
                lambda_nm,
                x: [r.u() * 4.0 - 2.0, 0.0],
                material,
                ..Default::default()
            };
            let v = evaluate(&params, &q, &set);
            let sum_w: f32 = scratches.iter().map(|s| s.width).sum();
            let amp = 2.0 * PI * sigma * sigma + 2.0 * sum_w * (2.0 * PI).sqrt() * sigma;
            let bound = amp * amp / (PI * sigma * sigma * lam * lam) * 1.0001;
            assert!(
                v.is_finite() && v >= 0.0 && v <= bound,
                "{params:?} {q:?} {scratches:?} → {v} (bound {bound})"
            );
            let _ = Model::from_u32(params.model);
            count += 1;
        }
    }
}

#[test]
fn footprint_averages_are_finite_and_bounded() {
    let mut r = Rng(0xf00d);
    for _ in 0..50_000 {
        let sigma = r.pick(&[10.0, 1.0, 100.0]);
        let s = scratch(&mut r, sigma);
        let e = Ellipse {
            center: [sigma * (r.u() * 10.0 - 5.0), sigma * (r.u() * 10.0 - 5.0)],
            angle_rad: 7.0 * r.u() - 3.5,
            a1: r.pick(&[1e-3, 0.3, 10.0, 1000.0]) * sigma * (0.1 + r.u()),
            a2: r.pick(&[1e-3, 0.3, 10.0, 1000.0]) * sigma * (0.1 + r.u()),
            ..Default::default()
        };
        // |η_s|² ≤ 2πσ², so the true average (the accurate method) is bounded by it. Eq. 16 is a
        // convex blend of Eq. 15 and 2πσ², and Eq. 15 itself overshoots for small footprints
        // (the failure the README charts), so Eq. 16 is only bounded by max(Eq. 15, 2πσ²).
        let max_eta = 2.0 * PI * sigma * sigma * 1.001;
        let acc = eta_p_accurate(&s, &e, sigma);
        assert!(
            acc.is_finite() && (0.0..=max_eta).contains(&acc),
            "{s:?} {e:?} accurate → {acc}"
        );
        let v15 = eta_p_eq15(&s, &e, sigma);
        assert!(v15.is_finite() && v15 >= 0.0, "{s:?} {e:?} eq15 → {v15}");
        let v16 = eta_p_eq16(&s, &e, sigma);
        assert!(
            v16.is_finite() && v16 >= 0.0 && v16 <= max_eta.max(v15 * 1.001),
            "{s:?} {e:?} eq16 → {v16}"
        );
        let rho = rho_p_accurate(&s, &e, sigma);
        assert!(
            rho.is_finite()
                && rho >= 0.0
                && rho <= 1.001 * s.width / (2.0 * PI).sqrt() / sigma + 1e-6,
            "{s:?} {e:?} ρ → {rho}"
        );
    }
}
