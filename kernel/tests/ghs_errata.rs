//! Numerical checks of the printed errata (the errata table in ARCHITECTURE.md plus those found here). Each
//! test states the printed form, the corrected form, and what distinguishes them.

use glam::{Vec2, Vec3};
use scratchwave_kernel::fresnel::fresnel;
use scratchwave_kernel::ghs::{Ghs, GhsParams, energy};
use scratchwave_kernel::sampling::ghs as gs;

/// Eq. 35: on a nearly flat surface (β → 0) the reflection lobe must carry GHS's specular
/// fraction `A(θi, θi)` (Eq. 16) times `F`. With the exponent `(4π σs cosθd/λ)²` it does;
/// the printed `(4π σs cosθd)²` (σs in µm) would differ by the factor `λ²` in the exponent.
#[test]
fn eq35_reflection_attenuation_needs_the_wavelength() {
    let (sigma, lambda, ti) = (0.05f32, 0.5f32, 0.5f32);
    let p = GhsParams::new(sigma, 0.01, 1.0, 2.0, 2.0, 1.5, 0.0);
    let g = Ghs::new(&p, lambda);
    let wi = Vec3::new(ti.sin(), 0.0, ti.cos());
    // ∫ ρ_refl cosθo dωo by importance sampling of the micro-facet lobe (256² strata)
    let n = 256;
    let mut s = 0.0f64;
    for a in 0..n {
        for b in 0..n {
            let u = Vec2::new((a as f32 + 0.5) / n as f32, (b as f32 + 0.5) / n as f32);
            if let Some(wo) = gs::sample_microfacet(&g.ndf, wi, u) {
                let pdf = gs::microfacet_pdf(&g.ndf, wi, wo);
                s += (g.reflection(wi, wo) * wo.z / pdf) as f64;
            }
        }
    }
    let albedo = (s / (n * n) as f64) as f32;
    let ghs_a =
        energy::specular_fraction(sigma / lambda, ti.cos(), ti.cos()) * fresnel(ti.cos(), 1.5, 0.0);
    let t = 4.0 * std::f32::consts::PI * sigma * ti.cos();
    let printed = (-(t * t)).exp() * fresnel(ti.cos(), 1.5, 0.0);
    println!("refl albedo {albedo:.5}, A·F {ghs_a:.5}, printed-form {printed:.5}");
    assert!((albedo / ghs_a - 1.0).abs() < 5e-3);
    assert!((printed / ghs_a - 1.0).abs() > 0.1);
}

/// Eq. 43: `S′` is the K-correlation density renormalised to the visible disk, so
/// `∫ S′ cosθo dωo = ∫_disk S′ d²o_p = 1` for every θi; the printed extra `σs²` (µm²) would
/// make it `σs²`. Midpoint rule on a 2000² grid over the projected disk.
#[test]
fn eq43_spread_has_unit_albedo_over_the_visible_disk() {
    for &(b, c, ti) in &[(2.0f32, 2.0f32, 0.3f32), (0.3, 1.3, 1.2), (20.0, 4.0, 1.45)] {
        let g = Ghs::new(&GhsParams::new(0.1, 0.2, 1.0, b, c, 1.5, 0.0), 1.0);
        let wi = Vec3::new(ti.sin(), 0.0, ti.cos());
        let srel = g.sigma_rel_sq(wi);
        let m = 2000;
        let h = 2.0 / m as f64;
        let mut s = 0.0f64;
        for i in 0..m {
            for j in 0..m {
                let x = -1.0 + (i as f64 + 0.5) * h;
                let y = -1.0 + (j as f64 + 0.5) * h;
                if x * x + y * y < 1.0 {
                    let r = ((x + wi.x as f64).powi(2) + y * y).sqrt() as f32;
                    s += (g.spread.density(r) / srel) as f64 * h * h;
                }
            }
        }
        println!("B={b} c={c} θi={ti}: ∫S′ = {s:.5}");
        assert!((s - 1.0).abs() < 5e-3, "{s}");
    }
}

/// Eq. 63: with `wi` pointing away from the surface, the arc of admissible `d_p` is centred
/// on `+i_p` (towards the disk centre). Centred on `φi + π` as printed, a radius in
/// `(1 − sinθi, 1 + sinθi)` puts most of the arc outside the disk.
#[test]
fn eq63_arc_is_centred_towards_the_disk_centre() {
    let g = Ghs::new(&GhsParams::new(0.3, 0.2, 1.0, 0.5, 1.5, 1.5, 0.0), 1.0);
    let wi = Vec3::new(1.3f32.sin(), 0.0, 1.3f32.cos());
    let (mut ok, mut flipped_ok) = (0, 0);
    for a in 0..200 {
        for b in 0..200 {
            let u = Vec2::new((a as f32 + 0.5) / 200.0, (b as f32 + 0.5) / 200.0);
            if gs::sample_diffraction(&g.spread, wi, u).is_some() {
                ok += 1;
            }
            // the printed centring: rotate the sampled offset by π about −i_p
            let s = wi.x;
            let m = g.spread.cdf(1.0 + s);
            let r = g.spread.radius_from_cdf(m * u.x);
            let pm = scratchwave_kernel::ghs::spread::phi_max(r, s);
            let alpha = std::f32::consts::PI + (2.0 * u.y - 1.0) * pm;
            let op = Vec2::new(-s + r * alpha.cos(), r * alpha.sin());
            if op.length_squared() < 1.0 {
                flipped_ok += 1;
            }
        }
    }
    println!("inside the disk: corrected {ok}/40000, printed {flipped_ok}/40000");
    assert!(ok > 39_900 && flipped_ok < 36_000);
}
