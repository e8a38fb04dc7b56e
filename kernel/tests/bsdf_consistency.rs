//! Consistency of the BSDF interface: `sample`'s value, pdf and weight against `eval` and
//! `pdf` at the sampled direction (1e-5 relative), reciprocity where the model is
//! reciprocal, and the directional albedo of Werner's coherent model (energy: at most F up
//! to the model's stated error, see `docs/bsdf.md`).
// Per-wavelength arrays are walked in step by index.
#![allow(clippy::needless_range_loop)]

mod bsdf_common;

use bsdf_common::{Pcg, config, draw};
use glam::Vec3;
use scratchwave_kernel::bsdf::{
    self, BsdfMaterial, DepthChoice, ShadingPoint, Strategy, Wavelengths,
};
use scratchwave_kernel::material::{FresnelAngle, Material};
use scratchwave_kernel::render::shading::SceneModel;
use scratchwave_kernel::scratch::{Profile, Scratch, ScratchSlice};

fn rel(a: f32, b: f32) -> f32 {
    (a - b).abs() / a.abs().max(b.abs()).max(1e-30)
}

#[test]
fn sample_agrees_with_eval_and_pdf() {
    let mut r = Pcg::new(21);
    let mut checked = 0;
    for strategy in [Strategy::DiskProduct, Strategy::Werner2017] {
        for i in 0..100 {
            let c = config(i, 10.0);
            let set = c.set();
            let lk = bsdf::Lookup::new(&set);
            for _ in 0..50 {
                let (us, u) = draw(&mut r);
                let Some(s) = bsdf::sample_with(strategy, &c.m, &c.sp, c.wo, &c.wl, us, u, &lk)
                else {
                    continue;
                };
                assert!(s.wi.z > 0.0 && (s.wi.length() - 1.0).abs() < 1e-5);
                assert!((s.wavelength as usize) < c.wl.len());
                let p = bsdf::pdf_with(strategy, &c.m, &c.sp, c.wo, s.wi, &c.wl, &lk);
                assert!(
                    rel(p, s.pdf) <= 1e-5,
                    "{}: pdf {p} vs sample's {}",
                    c.name,
                    s.pdf
                );
                let f = bsdf::eval(&c.m, &c.sp, s.wi, c.wo, &c.wl, &lk);
                for j in 0..4 {
                    // eval = (value/pdf · cos) · pdf / cos.
                    let back = s.weight.v[j] * s.pdf / s.wi.z;
                    assert!(
                        rel(back, f.v[j]) <= 1e-5 || (f.v[j] == 0.0 && back == 0.0),
                        "{}: λ{j}: {back} vs {}",
                        c.name,
                        f.v[j]
                    );
                    assert_eq!(s.value.v[j], f.v[j]);
                }
                checked += 1;
            }
        }
    }
    println!("{checked} samples consistent");
    assert!(checked > 8000);
}

#[test]
fn reciprocal_models_are_reciprocal() {
    // Werner, Velinov (point and footprint) and Werner-blended without a GHS base are
    // symmetric in (wi, wo): ξ and γi + γo are, and so is F at θd. GHS is not.
    let mut r = Pcg::new(8);
    let mut worst: f32 = 0.0;
    let mut n = 0;
    for i in 0..100 {
        let mut c = config(i, 10.0);
        match c.m.scene_model() {
            SceneModel::Ghs => continue,
            SceneModel::WernerBlended => c.m.base = 0,
            _ => {}
        }
        // Both depth phases are symmetric.
        c.m.depth = if i % 2 == 0 {
            DepthChoice::Exact
        } else {
            DepthChoice::SmallAngle
        } as u32;
        let set = c.set();
        let lk = bsdf::Lookup::new(&set);
        for _ in 0..20 {
            let (us, u) = draw(&mut r);
            let Some(s) = bsdf::sample(&c.m, &c.sp, c.wo, &c.wl, us, u, &lk) else {
                continue;
            };
            let a = bsdf::eval(&c.m, &c.sp, s.wi, c.wo, &c.wl, &lk);
            let b = bsdf::eval(&c.m, &c.sp, c.wo, s.wi, &c.wl, &lk);
            let peak = a.v.iter().fold(0.0f32, |m, v| m.max(*v));
            for j in 0..4 {
                // Relative to the largest value of the call: F(θd) rounds differently
                // for the two orders, and a value near a zero of the pattern magnifies it.
                let d = (a.v[j] - b.v[j]).abs() / peak.max(1e-30);
                worst = worst.max(d);
            }
            n += 1;
        }
    }
    println!("reciprocity: {n} pairs, worst difference {worst:.2e} of the call's peak");
    assert!(n > 1000);
    assert!(worst <= 1e-4, "worst {worst}");
}

/// Directional albedo `∫ f cosθi dωi` by the disk-product sampler: mean and standard error.
fn albedo(
    m: &BsdfMaterial,
    wo: Vec3,
    lambda: f32,
    lk: &bsdf::Lookup<ScratchSlice>,
    n: usize,
    seed: u64,
) -> (f64, f64) {
    let mut r = Pcg::new(seed);
    let wl = Wavelengths::single(lambda);
    let sp = ShadingPoint::at([0.0, 0.0]);
    let (mut s1, mut s2) = (0.0f64, 0.0f64);
    for _ in 0..n {
        let (us, u) = draw(&mut r);
        let w = bsdf::sample(m, &sp, wo, &wl, us, u, lk).map_or(0.0, |s| s.weight.v[0] as f64);
        s1 += w;
        s2 += w * w;
    }
    let mean = s1 / n as f64;
    (
        mean,
        ((s2 / n as f64 - mean * mean).max(0.0) / n as f64).sqrt(),
    )
}

#[test]
fn werner_albedo_is_at_most_f() {
    // Werner's coherent model conserves energy by Parseval for non-overlapping scratches,
    // up to (a) the evanescent part of the angular spectrum (a loss) and (b) the coherence
    // window taken constant across each groove (Werner Eq. 11), an error of order (W/σ)².
    let f = 0.8;
    let m = BsdfMaterial::werner(10.0, Material::constant(f));
    let mut worst: f64 = 0.0;
    let mut r = Pcg::new(4);
    for k in 0..40 {
        let count = [0, 1, 3][k % 3];
        // Parallel scratches 12 µm apart never overlap.
        let phi = std::f32::consts::PI * r.f();
        let (t, b) = (
            [phi.cos() as f64, phi.sin() as f64],
            [-phi.sin() as f64, phi.cos() as f64],
        );
        let scratches: Vec<Scratch> = (0..count)
            .map(|j| {
                let o = 12.0 * (j as f64 - 1.0) + 3.0 * r.f() as f64;
                let h = 50.0 + 100.0 * r.f() as f64;
                let prof = if r.f() < 0.5 {
                    Profile::Rect
                } else {
                    Profile::Triangle
                };
                Scratch::from_endpoints(
                    [o * b[0] - h * t[0], o * b[1] - h * t[1]],
                    [o * b[0] + h * t[0], o * b[1] + h * t[1]],
                    0.5 + 2.5 * r.f(),
                    0.05 + 0.5 * r.f(),
                    prof,
                )
            })
            .collect();
        let set = ScratchSlice {
            scratches: &scratches,
        };
        let theta = [5.0f32, 40.0, 70.0, 85.0][k % 4].to_radians();
        let wo = bsdf_common::dir(theta, 6.0 * r.f());
        let lambda = 420.0 + 280.0 * r.f();
        let (a, se) = albedo(&m, wo, lambda, &bsdf::Lookup::new(set), 20_000, k as u64);
        let ratio = a / f as f64;
        println!(
            "albedo/F = {ratio:.4} ± {:.4} ({count} scratches, θo = {:.0}°)",
            se / f as f64,
            theta.to_degrees()
        );
        worst = worst.max(ratio - 3.0 * se / f as f64);
    }
    println!("largest albedo/F − 3 s.e. = {worst:.4}");
    assert!(
        worst <= 1.01,
        "albedo exceeds F by more than the 1 % model error: {worst}"
    );
}

#[test]
fn fresnel_theta_d_material_is_accepted_everywhere() {
    // A smoke test over extreme inputs: nothing panics, nothing is NaN.
    let m = BsdfMaterial::velinov(10.0, Material::ior(0.2, 3.0, FresnelAngle::ThetaD));
    let s = [Scratch::from_endpoints(
        [-50.0, 0.0],
        [50.0, 0.0],
        1.0,
        0.2,
        Profile::Rect,
    )];
    let set = ScratchSlice { scratches: &s };
    let lk = bsdf::Lookup::new(&set);
    let mut r = Pcg::new(1);
    for _ in 0..2000 {
        let wo = Vec3::new(r.f() * 2.0 - 1.0, r.f() * 2.0 - 1.0, r.f() * 1e-3);
        let wl = Wavelengths::single(300.0 + 600.0 * r.f());
        let (us, u) = draw(&mut r);
        if let Some(smp) = bsdf::sample(&m, &ShadingPoint::at([0.0, 0.0]), wo, &wl, us, u, &lk) {
            assert!(smp.pdf.is_finite() && smp.pdf > 0.0);
            assert!(smp.weight.v.iter().all(|v| v.is_finite() && *v >= 0.0));
        }
    }
}
