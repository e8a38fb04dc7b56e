//! Adversarial inputs: zero NaN/Inf and no negative values from `evaluate`, `pdf` and
//! `sample` over 10⁶ random parameter sets and directions drawn from extreme ranges
//! (grazing angles, c → 1⁺, tiny and huge b/λ, σs → 0, p → small, huge β, metals with
//! huge k), plus named limits.

mod ghs_common;

use ghs_common::Pcg;
use glam::{Vec2, Vec3};
use scratchwave_kernel::ghs::{self, GhsParams};
use scratchwave_kernel::sampling::ghs as gs;

fn log_uniform(r: &mut Pcg, lo: f32, hi: f32) -> f32 {
    (lo.ln() + r.f() * (hi.ln() - lo.ln())).exp()
}

fn pick(r: &mut Pcg, choices: &[f32]) -> f32 {
    choices[(r.next_u32() as usize) % choices.len()]
}

/// A direction with z drawn to stress grazing and normal incidence.
fn adversarial_dir(r: &mut Pcg) -> Vec3 {
    let z = match r.next_u32() % 6 {
        0 => pick(r, &[0.0, 1e-30, 1e-12, 1e-7, 1e-4, 1.0, 1.0 - 1e-7]),
        1 => log_uniform(r, 1e-9, 1.0),
        _ => r.f(),
    };
    let s = (1.0 - z * z).max(0.0).sqrt();
    let phi = r.f() * std::f32::consts::TAU;
    Vec3::new(s * phi.cos(), s * phi.sin(), z)
}

fn adversarial_params(r: &mut Pcg) -> (GhsParams, f32) {
    let p = GhsParams {
        sigma_s_um: if r.f() < 0.2 {
            0.0
        } else {
            log_uniform(r, 1e-9, 1e3)
        },
        beta: log_uniform(r, 1e-6, 1e4),
        p: log_uniform(r, 1e-3, 20.0),
        b_um: log_uniform(r, 1e-9, 1e9),
        c: 1.0
            + if r.f() < 0.2 {
                pick(r, &[0.0, 1e-12, 1e-6, 1e-4])
            } else {
                log_uniform(r, 1e-5, 1e5)
            },
        n: log_uniform(r, 1e-3, 1e3),
        k: if r.f() < 0.3 {
            0.0
        } else {
            log_uniform(r, 1e-4, 1e3)
        },
        diff_color: r.next_u32() % 5,
        layer: r.next_u32() % 4,
        layer_form: r.next_u32() % 3,
        layer_albedo: pick(r, &[0.0, 1.0, 0.5, 1e-7, 1.0 - 1e-7]),
        conductor: 0,
    };
    (p, log_uniform(r, 0.2, 20.0))
}

#[test]
fn no_nan_or_inf_over_a_million_adversarial_inputs() {
    let mut r = Pcg::new(0xbad);
    let mut bad = 0usize;
    let n = 1_000_000;
    for i in 0..n {
        let (p, lambda) = adversarial_params(&mut r);
        let wi = adversarial_dir(&mut r);
        // half the queries near the mirror direction, where the lobes peak
        let wo = if i % 2 == 0 {
            let m = Vec3::new(-wi.x, -wi.y, wi.z);
            (m + adversarial_dir(&mut r) * log_uniform(&mut r, 1e-7, 1.0)).normalize_or(m)
        } else {
            adversarial_dir(&mut r)
        };
        let v = ghs::evaluate(&p, wi, wo, lambda);
        // the parts before `eval`'s final mask: must be finite on their own
        if i % 2 == 1 && wi.z > 0.0 && wo.z > 0.0 {
            let g = ghs::Ghs::new(&p, lambda);
            let srel = g.sigma_rel_sq(wi);
            let parts = [
                g.reflection(wi, wo),
                g.diffraction(wi, wo, srel),
                g.layer_lobe(wi, wo),
            ];
            if !parts.iter().all(|x| x.is_finite() && *x >= 0.0) {
                bad += 1;
                if bad < 10 {
                    println!("parts {parts:?}: {p:?} λ={lambda} wi={wi} wo={wo}");
                }
            }
        }
        if !(v.is_finite() && v >= 0.0) {
            bad += 1;
            if bad < 10 {
                println!("evaluate {p:?} λ={lambda} wi={wi} wo={wo} → {v}");
            }
        }
        if i % 4 == 0 {
            let pdf = gs::pdf(&p, wi, wo, lambda);
            if !(pdf.is_finite() && pdf >= 0.0) {
                bad += 1;
                println!("pdf {p:?} λ={lambda} wi={wi} wo={wo} → {pdf}");
            }
            let u = Vec2::new(r.f(), r.f());
            if let Some(s) = gs::sample(&p, wi, r.f(), u, lambda) {
                let ok = s.pdf.is_finite()
                    && s.pdf > 0.0
                    && s.value.is_finite()
                    && s.weight.is_finite()
                    && s.weight >= 0.0
                    && s.wo.is_finite()
                    && s.wo.z > 0.0;
                if !ok {
                    bad += 1;
                    println!("sample {p:?} λ={lambda} wi={wi} → {s:?}");
                }
            }
        }
    }
    assert_eq!(bad, 0, "{bad} non-finite or negative results");
}

#[test]
fn limits_are_continuous() {
    let wi = Vec3::new(0.5f32.sin(), 0.0, 0.5f32.cos());
    let wo = Vec3::new(-0.3f32.sin(), 0.1, 0.3f32.cos()).normalize();
    let base = GhsParams::new(0.2, 0.3, 1.0, 2.0, 2.0, 0.5, 2.0);
    let at = |f: &dyn Fn(&mut GhsParams)| {
        let mut p = base;
        f(&mut p);
        ghs::evaluate(&p, wi, wo, 0.5)
    };
    // c → 1⁺: the diffraction lobe flattens smoothly (σ_rel² and S′ both ∝ c − 1)
    let (a, b) = (at(&|p| p.c = 1.0 + 1e-4), at(&|p| p.c = 1.0 + 2e-4));
    assert!(a > 0.0 && (a / b - 1.0).abs() < 1e-2, "c→1⁺: {a} {b}");
    // σs → 0: diffraction vanishes like σs², the result tends to Cook–Torrance
    let ct = at(&|p| p.sigma_s_um = 0.0);
    let tiny = at(&|p| p.sigma_s_um = 1e-6);
    assert!((tiny / ct - 1.0).abs() < 1e-5, "σs→0: {tiny} vs {ct}");
    // huge b/λ: the lobe is a spike at the mirror direction, off-specular value → 0
    let huge = at(&|p| p.b_um = 1e6);
    assert!(huge.is_finite() && huge <= at(&|p| p.b_um = 1e3));
    // tiny b/λ: the lobe is flat, σ_rel² → 1 − ... finite
    let flat = at(&|p| p.b_um = 1e-7);
    assert!(flat.is_finite() && flat > 0.0);
    // grazing incidence: finite, nonnegative
    let g = ghs::evaluate(&base, Vec3::new(1.0, 0.0, 1e-7).normalize(), wo, 0.5);
    assert!(g.is_finite() && g >= 0.0);
}
