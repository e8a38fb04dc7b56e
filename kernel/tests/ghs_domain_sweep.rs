//! Domain sweep of the GHS model and Fresnel (issue #20) against the mpmath reference
//! `reference/ghs/domain_sweep.py`, at the very f32 inputs the reference evaluated.
//!
//! Every query stores its f32 inputs, the exact value of the formula at those inputs and its
//! conditioning `κ`: the largest relative change of the exact value when one input moves by
//! one f32 ulp. A kernel result is accepted when
//!
//! `err ≤ max(1e-4, K·κ)`, `K = 8`:
//!
//! `κ` is what an exact evaluation would already lose to rounding one input; a kernel that
//! rounds each of the few quantities an ill-conditioned result depends on (a sum, a square, a
//! quotient: at most a handful of roundings, each worth ≤ one input ulp) stays within a small
//! multiple of it (measured on the full sweep where `K·κ` binds: `err/κ` ≤ 5.7, the diffraction
//! warp; ≤ 1.6 elsewhere). `1e-4` is the kernel's accuracy target for well-conditioned queries
//! (the G1 table and the σ_rel² quadrature are good to 1.5e-5 and 5.4e-6).
//!
//! The committed subset (`reference/ghs/golden/sweep/`, 13 300 queries) runs by default; the
//! full sweep (`python3 reference/ghs/domain_sweep.py --full --out DIR`, 108 800 queries)
//! with `GHS_SWEEP_DIR=DIR`. `GHS_SWEEP_DUMP=FILE` writes every D and full-BRDF query's
//! (β, tanθh, err, bound, κ) for the stability map (`docs/ghs_stability_map.py`).

mod sweep_common;

use glam::{Vec2, Vec3};
use scratchwave_kernel::fresnel::fresnel;
use scratchwave_kernel::ghs::{self, Ghs, GhsParams, ndf::GenBeckmann, spread::KCorrelation};
use scratchwave_kernel::sampling::ghs as gs;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use sweep_common::{FLOOR, K, Row, Stat, Table, bound, ghs_params, rel, report};

/// `name_x, name_y, name_z` as a vector.
fn v3(r: &Row, name: &str) -> Vec3 {
    Vec3::from_array(r.a3(name))
}

/// One kernel evaluation against its reference: relative error (or absolute error for tiny
/// exact values) and κ.
struct Outcome {
    err: f64,
    kappa: f64,
    /// β and tanθh for the stability map (D and the full BRDF only).
    map: Option<(f64, f64)>,
    /// Sub-family label for the report.
    group: &'static str,
}

fn tan_of(v: Vec3) -> f64 {
    let (x, y, z) = (v.x as f64, v.y as f64, v.z as f64);
    (x * x + y * y).sqrt() / z
}

/// A material that only fixes what the single-term families need.
fn material(beta: f32, p: f32, b: f32, c: f32) -> GhsParams {
    GhsParams::new(0.1, beta, p, b, c, 1.5, 0.0)
}

fn eval(family: &str, r: &Row) -> Option<Outcome> {
    let kappa = r.d("kappa");
    let scalar = |got: f32, group| {
        Some(Outcome {
            err: rel(got, r.d("ref")),
            kappa,
            map: None,
            group,
        })
    };
    match family {
        "ndf" => {
            let h = v3(r, "h");
            let (beta, p) = (r.f("beta"), r.f("p"));
            let got = GenBeckmann::new(beta, p).d(h);
            Some(Outcome {
                err: rel(got, r.d("ref")),
                kappa,
                map: Some((beta as f64, tan_of(h))),
                group: "D (Eq. 38)",
            })
        }
        "g1" => {
            let g = Ghs::new(&material(r.f("beta"), r.f("p"), 1.0, 2.0), 0.5);
            scalar(g.g1(v3(r, "w").z), "G1 (Eqs. 40-42)")
        }
        "fresnel" => {
            let (n, k) = (r.f("n"), r.f("k"));
            let group = match (n >= 1.0, k > 0.0) {
                (_, true) if k >= 0.5 => "F conductor",
                (_, true) => "F weak absorber",
                (true, false) => "F dielectric n > 1",
                (false, false) => "F dielectric n < 1",
            };
            scalar(fresnel(r.f("cos"), n, k), group)
        }
        "color" => scalar(
            ghs::color::diffraction_color(v3(r, "wi"), v3(r, "wo"), r.f("n"), r.f("k")),
            "Q (Eq. 27)",
        ),
        "sigma_rel" => {
            let g = Ghs::new(&material(0.1, 1.0, r.f("b"), r.f("c")), r.f("lambda"));
            scalar(g.sigma_rel_sq(v3(r, "wi")), "σ_rel² (Eq. 25)")
        }
        "brdf" => {
            let p = ghs_params(r, "");
            let (wi, wo) = (v3(r, "wi"), v3(r, "wo"));
            let got = ghs::evaluate(&p, wi, wo, r.f("lambda"));
            let group = match (p.layer, p.layer_form, p.k > 0.0) {
                (0, _, true) => "ρ conductor / absorber",
                (0, _, false) => "ρ dielectric",
                (1, 0, _) => "ρ plastic (published)",
                (1, _, _) => "ρ plastic (energy-conserving)",
                (_, 0, _) => "ρ subsurface (published)",
                _ => "ρ subsurface (energy-conserving)",
            };
            Some(Outcome {
                err: rel(got, r.d("ref")),
                kappa,
                map: Some((p.beta as f64, tan_of(wi + wo))),
                group,
            })
        }
        "halfvec" => {
            let ndf = GenBeckmann::new(r.f("beta"), r.f("p"));
            let h = gs::sample_half_vector(&ndf, Vec2::new(r.f("u0"), r.f("u1")));
            let (x, y) = (r.d("ref_x"), r.d("ref_y"));
            let (gx, gy) = (h.x as f64 / h.z as f64, h.y as f64 / h.z as f64);
            let err = ((gx - x).powi(2) + (gy - y).powi(2)).sqrt() / (x * x + y * y).sqrt();
            Some(Outcome {
                err,
                kappa,
                map: None,
                group: "half-vector warp (Eq. 59)",
            })
        }
        "diffsample" => {
            let k = KCorrelation {
                b: r.f("B"),
                c: r.f("c"),
            };
            let (x, y) = (r.d("ref_x"), r.d("ref_y"));
            let got = gs::sample_diffraction(&k, v3(r, "wi"), Vec2::new(r.f("u0"), r.f("u1")));
            let err = match got {
                Some(w) => ((w.x as f64 - x).powi(2) + (w.y as f64 - y).powi(2)).sqrt() / r.d("r"),
                // rejected as outside the disk: only allowed within rounding of the rim
                None if x * x + y * y > 1.0 - 1.0e-6 => return None,
                None => f64::INFINITY,
            };
            Some(Outcome {
                err,
                kappa,
                map: None,
                group: "diffraction warp (Eqs. 60-63)",
            })
        }
        _ => unreachable!(),
    }
}

#[test]
fn every_query_within_its_conditioning_bound() {
    let families = [
        "ndf",
        "g1",
        "fresnel",
        "color",
        "sigma_rel",
        "brdf",
        "halfvec",
        "diffsample",
    ];
    let mut stats: BTreeMap<(usize, &'static str), Stat> = BTreeMap::new();
    let mut dump = String::new();
    let mut total = 0;
    for (fi, family) in families.iter().enumerate() {
        let t = Table::load("GHS_SWEEP_DIR", "reference/ghs/golden/sweep", family);
        assert!(!t.rows.is_empty(), "{family}: no queries");
        for r in t.rows() {
            let Some(o) = eval(family, &r) else {
                continue;
            };
            total += 1;
            if let Some((beta, tan_h)) = o.map {
                writeln!(
                    dump,
                    "{family},{beta},{tan_h},{},{},{}",
                    o.err,
                    bound(o.kappa),
                    o.kappa
                )
                .unwrap();
            }
            stats
                .entry((fi, o.group))
                .or_default()
                .add(o.err, o.kappa, || r.text());
        }
    }
    println!("{total} queries; bound = max({FLOOR:e}, {K}·κ)");
    let bad = report(&stats, 34);
    if let Ok(path) = std::env::var("GHS_SWEEP_DUMP") {
        std::fs::write(&path, format!("family,beta,tan_h,err,bound,kappa\n{dump}")).unwrap();
    }
    assert!(total >= 10_000, "only {total} queries");
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
