//! χ² tests (1M samples, pooled low bins, Šidák-corrected), eval/pdf consistency and warp
//! inversion for every GHS sampling routine.

mod ghs_common;

use ghs_common::{Pcg, chi2, sidak};
use glam::{Vec2, Vec3};
use scratchwave_kernel::ghs::{self, Ghs, GhsParams, Layer, layers::LayerForm, presets};
use scratchwave_kernel::sampling::{ghs as gs, warp};

const N: usize = 1_000_000;
/// Number of χ² tests in this file (for the Šidák correction).
const M: usize = 12;

fn dir(theta: f32, phi: f32) -> Vec3 {
    Vec3::new(
        theta.sin() * phi.cos(),
        theta.sin() * phi.sin(),
        theta.cos(),
    )
}

fn check(name: &str, p: f64) {
    assert!(
        p > sidak(M),
        "{name}: χ² rejects (p = {p:.2e} < {:.2e})",
        sidak(M)
    );
}

#[test]
fn chi2_cosine_hemisphere() {
    let p = chi2(
        "cosine",
        N,
        |r| Some(warp::cosine_hemisphere(Vec2::new(r.f(), r.f()))),
        &|w| warp::cosine_hemisphere_pdf(w) as f64,
    );
    check("cosine", p);
}

#[test]
fn chi2_microfacet_lobe() {
    for &(beta, pk, ti) in &[(0.3f32, 1.0f32, 0.5f32), (0.2, 0.4, 1.1), (0.5, 3.0, 0.2)] {
        let g = Ghs::new(&GhsParams::new(0.0, beta, pk, 1.0, 2.0, 1.5, 0.0), 0.5);
        let wi = dir(ti, 0.3);
        let name = format!("microfacet β={beta} p={pk} θi={ti}");
        let p = chi2(
            &name,
            N,
            |r| gs::sample_microfacet(&g.ndf, wi, Vec2::new(r.f(), r.f())),
            &|w| gs::microfacet_pdf(&g.ndf, wi, w) as f64,
        );
        check(&name, p);
    }
}

#[test]
fn chi2_diffraction_lobe() {
    for &(b, c, ti) in &[(2.0f32, 2.0f32, 0.4f32), (0.5, 1.2, 1.2), (4.0, 4.0, 0.0)] {
        let g = Ghs::new(&GhsParams::new(0.3, 0.2, 1.0, b, c, 1.5, 0.0), 1.0);
        let wi = dir(ti, 2.0);
        let name = format!("diffraction B={b} c={c} θi={ti}");
        let p = chi2(
            &name,
            N,
            |r| gs::sample_diffraction(&g.spread, wi, Vec2::new(r.f(), r.f())),
            &|w| gs::diffraction_pdf(&g.spread, wi, w) as f64,
        );
        check(&name, p);
    }
}

fn mixtures() -> [(&'static str, GhsParams, f32); 5] {
    [
        (
            "rough gold",
            presets::channel(presets::ROUGH_METAL, &presets::GOLD, 1),
            0.526,
        ),
        (
            "mixed split",
            GhsParams::new(0.06, 0.25, 0.7, 1.5, 2.0, 0.5, 2.2),
            0.526,
        ),
        ("plastic", presets::GLOSSY_PLASTIC, 0.645),
        ("subsurface", presets::TRANSLUCENT_STONE, 0.444),
        (
            "plastic energy-conserving",
            GhsParams::new(0.1, 0.3, 1.0, 1.0, 3.0, 1.5, 0.0).with_layer(
                Layer::Plastic,
                LayerForm::EnergyConserving,
                0.5,
            ),
            0.5,
        ),
    ]
}

#[test]
fn chi2_full_mixture() {
    for (name, params, lambda) in mixtures() {
        let wi = dir(0.6, 1.0);
        let g = Ghs::new(&params, lambda);
        let p = chi2(
            name,
            N,
            |r| gs::sample_prepared(&g, wi, r.f(), Vec2::new(r.f(), r.f())).map(|s| s.wo),
            &|w| gs::pdf_prepared(&g, wi, w) as f64,
        );
        check(name, p);
    }
}

#[test]
fn sample_reports_eval_and_pdf() {
    let mut rng = Pcg::new(7);
    for (name, params, lambda) in mixtures() {
        for _ in 0..20_000 {
            let wi = dir(rng.f() * 1.5, rng.f() * std::f32::consts::TAU);
            let (ul, u) = (rng.f(), Vec2::new(rng.f(), rng.f()));
            if let Some(s) = gs::sample(&params, wi, ul, u, lambda) {
                let pdf = gs::pdf(&params, wi, s.wo, lambda);
                let val = ghs::evaluate(&params, wi, s.wo, lambda);
                assert!(
                    (s.pdf - pdf).abs() <= 1e-5 * pdf,
                    "{name}: pdf {} vs {pdf}",
                    s.pdf
                );
                assert!((s.value - val).abs() <= 1e-5 * val.abs() + 1e-30, "{name}");
                assert!((s.weight - val * s.wo.z / pdf).abs() <= 1e-4 * s.weight.abs() + 1e-30);
                assert!(s.wo.z > 0.0 && (s.wo.length() - 1.0).abs() < 1e-4);
            }
        }
    }
}

#[test]
fn warps_invert() {
    let mut rng = Pcg::new(11);
    let g = Ghs::new(&GhsParams::new(0.2, 0.3, 0.8, 2.0, 2.5, 1.5, 0.0), 0.5);
    let mut max = [0.0f32; 3];
    for _ in 0..100_000 {
        let u = Vec2::new(rng.f(), rng.f() * 0.998 + 0.001);
        // cosine
        let w = warp::cosine_hemisphere(u);
        let e = (warp::cosine_hemisphere_inverse(w) - u).abs().max_element();
        max[0] = max[0].max(e);
        // half vector
        let h = gs::sample_half_vector(&g.ndf, u);
        let e = (gs::half_vector_inverse(&g.ndf, h) - u).abs().max_element();
        max[1] = max[1].max(e);
        // diffraction
        let wi = dir(rng.f() * 1.5, rng.f() * std::f32::consts::TAU);
        if let Some(wo) = gs::sample_diffraction(&g.spread, wi, u) {
            let e = (gs::diffraction_inverse(&g.spread, wi, wo) - u)
                .abs()
                .max_element();
            max[2] = max[2].max(e);
        }
    }
    println!(
        "inversion max |Δu|: cosine {:.1e}, half vector {:.1e}, diffraction {:.1e}",
        max[0], max[1], max[2]
    );
    assert!(max[0] < 1e-4 && max[1] < 2e-3 && max[2] < 2e-3, "{max:?}");
}
