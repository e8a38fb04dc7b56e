//! The BSDF interface's parts against independent references: the scaled Bessel function
//! against quadrature, the truncated 1-D lobes against numerical integration, the shading
//! frame and wavelength sets, and multi-wavelength `eval` against the renderer's
//! single-wavelength `brdf`/`brdf_footprint` and the table's `evaluate` (one shared scratch
//! walk must change nothing, bit for bit).
// Per-wavelength arrays are walked in step by index.
#![allow(clippy::needless_range_loop)]

mod bsdf_common;

use bsdf_common::{Pcg, config};
use glam::{Vec2, Vec3};
use scratchwave_kernel::bsdf::lobe1d::{Lobe1, Lobe1Kind};
use scratchwave_kernel::bsdf::{self, BsdfMaterial, DepthChoice, ShadingFrame, Wavelengths};
use scratchwave_kernel::math::bessel_i0e;
use scratchwave_kernel::render::shading::{SceneModel, ShadeMaterial, brdf, brdf_footprint};
use scratchwave_kernel::scratch::DepthTerm;
use scratchwave_kernel::table::{self, TableParams, TableQuery};

/// `e^{−x} I₀(x) = (1/π) ∫₀^π e^{x (cos t − 1)} dt` by the trapezoid rule (spectrally
/// accurate for this periodic integrand), f64.
fn i0e_quadrature(x: f64) -> f64 {
    let n = 20_000;
    let h = std::f64::consts::PI / n as f64;
    let mut s = 0.0;
    for k in 0..=n {
        let t = k as f64 * h;
        let w = if k == 0 || k == n { 0.5 } else { 1.0 };
        s += w * (x * (t.cos() - 1.0)).exp();
    }
    s * h / std::f64::consts::PI
}

#[test]
fn bessel_i0e_matches_quadrature() {
    let mut worst: f64 = 0.0;
    for k in 0..=120 {
        let x = 1e-3 * 10f64.powf(k as f64 * 8.0 / 120.0); // 1e-3 … 1e5
        let r = i0e_quadrature(x);
        let v = bessel_i0e(x as f32) as f64;
        worst = worst.max((v - r).abs() / r);
    }
    println!("e^-x I0(x): worst relative error {worst:.2e}");
    assert!(worst < 1.0e-6, "worst relative error {worst}");
}

fn lobes(r: &mut Pcg) -> Lobe1 {
    let kind = if r.f() < 0.5 {
        Lobe1Kind::Logistic
    } else {
        Lobe1Kind::Cauchy
    };
    let count = 1 + (r.next_u32() % 3);
    let mut l = Lobe1::single(kind, 0.0, 1.0);
    l.count = count;
    for j in 0..3 {
        l.mu[j] = 2.0 * r.f() - 1.0;
        l.scale[j] = 10f32.powf(-3.0 + 2.5 * r.f());
        l.weight[j] = 0.1 + r.f();
    }
    l
}

/// `∫_a^b pdf` by composite 4-point Gauss–Legendre on 20 000 panels (f64 sums).
fn integrate(f: impl Fn(f32) -> f32, a: f32, b: f32) -> f64 {
    const X: [f64; 4] = [
        -0.861_136_311_594_052_6,
        -0.339_981_043_584_856_3,
        0.339_981_043_584_856_3,
        0.861_136_311_594_052_6,
    ];
    const W: [f64; 4] = [
        0.347_854_845_137_453_8,
        0.652_145_154_862_546_1,
        0.652_145_154_862_546_1,
        0.347_854_845_137_453_8,
    ];
    let n = 20_000;
    let h = (b as f64 - a as f64) / n as f64;
    let mut s = 0.0;
    for k in 0..n {
        let c = a as f64 + (k as f64 + 0.5) * h;
        for (x, w) in X.iter().zip(W) {
            s += w * 0.5 * h * f((c + 0.5 * h * x) as f32) as f64;
        }
    }
    s
}

#[test]
fn truncated_lobes_integrate_to_one_and_invert_their_cdf() {
    let mut r = Pcg::new(11);
    for case in 0..360 {
        let l = lobes(&mut r);
        // Intervals around the lobe, and far in either tail.
        let (m0, s0) = (l.mu[0], l.scale[0]);
        let (a, b) = match case % 6 {
            0 => (-1.5, 1.5),
            1 => (-1.0 + r.f(), 1.0 + r.f()),
            2 => (5.0, 6.0),
            3 => (-9.0, -7.5),
            // A few scales into either tail of the first component.
            4 => (m0 + 3.0 * s0, m0 + 6.0 * s0),
            _ => (m0 - 9.0 * s0, m0 - 5.0 * s0),
        };
        let mass = l.mass(a, b);
        if !(mass > 1e-30) {
            continue;
        }
        let total = integrate(|x| l.pdf(x, a, b), a, b);
        // The narrowest lobes (scale 1e-3) need the quadrature's 1.5e-4 panels.
        assert!(
            (total - 1.0).abs() < 2e-4,
            "case {case}: ∫pdf = {total} ({l:?}, [{a}, {b}])"
        );
        if l.count == 1 {
            for k in 0..16 {
                let u = (k as f32 + 0.5) / 16.0;
                let x = l.sample(u, a, b).unwrap();
                assert!((a..=b).contains(&x));
                let cdf = integrate(|y| l.pdf(y, a, b), a, x);
                assert!(
                    (cdf - u as f64).abs() < 2e-4,
                    "case {case}: CDF(sample({u})) = {cdf}"
                );
            }
        }
    }
}

#[test]
fn shading_frame_is_orthonormal_and_inverts() {
    let mut r = Pcg::new(3);
    for k in 0..1000 {
        let n = Vec3::new(2.0 * r.f() - 1.0, 2.0 * r.f() - 1.0, 2.0 * r.f() - 1.0);
        let t = if k % 10 == 0 {
            n * 3.0
        } else {
            Vec3::new(r.f(), r.f() - 0.5, r.f())
        };
        let f = ShadingFrame::from_normal_tangent(n, t);
        let (tt, bb, nn) = (Vec3::from(f.t), Vec3::from(f.b), Vec3::from(f.n));
        for (a, b, d) in [
            (tt, tt, 1.0),
            (bb, bb, 1.0),
            (nn, nn, 1.0),
            (tt, bb, 0.0),
            (tt, nn, 0.0),
            (bb, nn, 0.0),
        ] {
            assert!((a.dot(b) - d).abs() < 1e-5, "frame {k}: {f:?}");
        }
        assert!((nn - n.normalize()).length() < 1e-5);
        assert!(tt.cross(bb).dot(nn) > 0.999, "right-handed");
        let v = Vec3::new(r.f() - 0.5, r.f() - 0.5, r.f());
        assert!((f.to_world(f.to_local(v)) - v).length() < 1e-5);
        assert!((f.to_local(nn) - Vec3::Z).length() < 1e-5);
    }
}

#[test]
fn wavelength_sets() {
    let rgb = Wavelengths::rgb();
    assert_eq!(&rgb.nm[..rgb.len()], &[700.0, 520.0, 440.0]);
    for k in 0..100 {
        let u = k as f32 / 100.0;
        let w = Wavelengths::sample_visible(u);
        assert_eq!(w.len(), 4);
        for j in 0..4 {
            // One wavelength in each quarter of [360, 830].
            let lo = 360.0 + j as f32 * 117.5;
            assert!(
                w.nm[j] >= lo - 1e-3 && w.nm[j] <= lo + 117.5 + 1e-3,
                "{w:?}"
            );
            assert!((w.pdf[j] - 1.0 / 470.0).abs() < 1e-9);
        }
    }
}

#[test]
fn depth_phase_defaults_follow_each_paper() {
    use scratchwave_kernel::material::Material;
    let f = Material::constant(1.0);
    assert_eq!(BsdfMaterial::werner(10.0, f).depth_term(), DepthTerm::Exact);
    let g = scratchwave_kernel::ghs::presets::ROUGH_METAL;
    assert_eq!(
        BsdfMaterial::werner_blended(10.0, f, g).depth_term(),
        DepthTerm::Exact
    );
    assert_eq!(
        BsdfMaterial::velinov(10.0, f).depth_term(),
        DepthTerm::SmallAngle
    );
    // A zeroed record is Werner's model with the exact phase, not the table default.
    let z: BsdfMaterial = bytemuck::Zeroable::zeroed();
    assert_eq!(z.depth_term(), DepthTerm::Exact);
    assert_eq!(
        TableParams::default().depth_term,
        DepthTerm::SmallAngle as u32
    );
    let mut v = BsdfMaterial::velinov(10.0, f);
    v.depth = DepthChoice::Exact as u32;
    assert_eq!(v.depth_term(), DepthTerm::Exact);
}

/// The renderer's record for a configuration's material (same fields, explicit depth term).
fn shade_of(m: &BsdfMaterial) -> ShadeMaterial {
    ShadeMaterial {
        table: m.table_params(),
        material: m.material,
        ghs: m.ghs,
        model: m.model,
        base: m.base,
        tolerance: 0.0,
        light_method: 0,
    }
}

#[test]
fn eval_equals_the_renderer_and_the_table_bit_for_bit() {
    let mut r = Pcg::new(5);
    let mut compared = 0;
    let mut tabled = 0;
    for i in 0..100 {
        let c = config(i, 10.0);
        let set = c.set();
        let lk = bsdf::Lookup::new(&set);
        let sm = shade_of(&c.m);
        assert_eq!(
            BsdfMaterial::from_shade(&sm).table_params(),
            c.m.table_params()
        );
        // A table's record maps back to the same model and options.
        assert_eq!(
            BsdfMaterial::from_table(&c.m.table_params(), c.m.material).table_params(),
            c.m.table_params()
        );
        for _ in 0..20 {
            let wi = bsdf_common::dir(1.5 * r.f(), std::f32::consts::TAU * r.f());
            // Near the mirror direction half of the time, where the lobes are.
            let wi = if r.f() < 0.5 {
                Vec3::new(
                    -c.wo.x + 0.05 * (r.f() - 0.5),
                    -c.wo.y + 0.05 * (r.f() - 0.5),
                    0.0,
                )
            } else {
                wi
            };
            let wi = Vec3::new(
                wi.x,
                wi.y,
                (1.0 - wi.x * wi.x - wi.y * wi.y).max(1e-4).sqrt(),
            )
            .normalize();
            let f = bsdf::eval(&c.m, &c.sp, wi, c.wo, &c.wl, &lk);
            for j in 0..c.wl.len() {
                let lam = c.wl.nm[j];
                let reference = match c.sp.footprint() {
                    Some(e) => brdf_footprint(&sm, wi, c.wo, c.sp.x(), &e, lam, &set),
                    None => brdf(&sm, wi, c.wo, c.sp.x(), lam, &set),
                };
                assert_eq!(
                    f.v[j].to_bits(),
                    reference.to_bits(),
                    "{}: λ = {lam}",
                    c.name
                );
                // The table has no GHS base and no footprint: every other scratch material
                // is a table query (Werner, Werner §5 without a base, Velinov at a point).
                if c.m.scene_model() != SceneModel::Ghs
                    && !c.m.has_ghs_base()
                    && c.sp.footprint().is_none()
                {
                    let q = TableQuery {
                        wi: wi.to_array(),
                        lambda_nm: lam,
                        wo: c.wo.to_array(),
                        x: c.sp.x_um,
                        material: c.m.material,
                        ..Default::default()
                    };
                    let t = table::evaluate(&c.m.table_params(), &q, &set);
                    assert_eq!(f.v[j].to_bits(), t.to_bits(), "{}: table", c.name);
                    tabled += 1;
                }
                compared += 1;
            }
            for j in c.wl.len()..4 {
                assert_eq!(f.v[j], 0.0);
            }
        }
    }
    println!("{compared} values bit-identical, {tabled} of them also as table queries");
    assert!(tabled > 1000, "{tabled} table comparisons");
}

#[test]
fn world_and_local_interfaces_agree() {
    let mut r = Pcg::new(9);
    for i in 0..40 {
        let c = config(i, 10.0);
        let set = c.set();
        let lk = bsdf::Lookup::new(&set);
        let frame = ShadingFrame::from_normal_tangent(
            Vec3::new(r.f() - 0.5, r.f() - 0.5, 1.0),
            Vec3::new(1.0, r.f() - 0.5, 0.0),
        );
        let (us, u) = (r.f(), Vec2::new(r.f(), r.f()));
        let local = bsdf::sample(&c.m, &c.sp, c.wo, &c.wl, us, u, &lk);
        let world =
            bsdf::sample_world(&c.m, &frame, &c.sp, frame.to_world(c.wo), &c.wl, us, u, &lk);
        match (local, world) {
            (Some(l), Some(w)) => {
                assert!((frame.to_local(w.wi) - l.wi).length() < 1e-3, "{}", c.name);
                let fw =
                    bsdf::eval_world(&c.m, &frame, &c.sp, w.wi, frame.to_world(c.wo), &c.wl, &lk);
                let pw =
                    bsdf::pdf_world(&c.m, &frame, &c.sp, frame.to_world(c.wo), w.wi, &c.wl, &lk);
                assert!(
                    (pw - w.pdf).abs() <= 1e-3 * w.pdf,
                    "{}: pdf {pw} vs {}",
                    c.name,
                    w.pdf
                );
                for j in 0..c.wl.len() {
                    assert!(
                        (fw.v[j] - w.value.v[j]).abs() <= 1e-3 * w.value.v[j].abs() + 1e-6,
                        "{}",
                        c.name
                    );
                }
            }
            (None, None) => {}
            (l, w) => {
                // A draw on the horizon may be dropped on one side of the rounding only.
                println!(
                    "{}: local {:?} world {:?}",
                    c.name,
                    l.map(|s| s.wi),
                    w.map(|s| s.wi)
                );
            }
        }
    }
}
