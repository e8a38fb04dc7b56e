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

use glam::{Vec2, Vec3};
use scratchwave_kernel::fresnel::fresnel;
use scratchwave_kernel::ghs::{self, Ghs, GhsParams, ndf::GenBeckmann, spread::KCorrelation};
use scratchwave_kernel::sampling::ghs as gs;
use std::collections::BTreeMap;
use std::fmt::Write as _;

/// The multiple of `κ` a kernel result may be off by.
const K: f64 = 8.0;
/// The accuracy floor for well-conditioned queries.
const FLOOR: f64 = 1.0e-4;
/// Exact values below this are compared absolutely (f32 has no headroom there).
const TINY: f64 = 1.0e-30;

struct Table {
    head: Vec<String>,
    rows: Vec<Vec<String>>,
}

struct Row<'a> {
    t: &'a Table,
    r: &'a [String],
}

impl Row<'_> {
    fn s(&self, col: &str) -> &str {
        let i = self.t.head.iter().position(|h| h == col);
        &self.r[i.unwrap_or_else(|| panic!("no column {col}"))]
    }
    /// An input: the stored shortest decimal reads back as the exact f32.
    fn f(&self, col: &str) -> f32 {
        self.s(col).parse().unwrap()
    }
    fn d(&self, col: &str) -> f64 {
        self.s(col).parse().unwrap()
    }
    fn u(&self, col: &str) -> u32 {
        self.s(col).parse().unwrap()
    }
    fn v3(&self, name: &str) -> Vec3 {
        Vec3::new(
            self.f(&format!("{name}_x")),
            self.f(&format!("{name}_y")),
            self.f(&format!("{name}_z")),
        )
    }
}

fn load(family: &str) -> Table {
    let dir = std::env::var("GHS_SWEEP_DIR").unwrap_or_else(|_| {
        format!(
            "{}/../reference/ghs/golden/sweep",
            env!("CARGO_MANIFEST_DIR")
        )
    });
    let path = format!("{dir}/{family}.csv");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    let mut lines = text.lines();
    let head = lines.next().unwrap().split(',').map(String::from).collect();
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    Table { head, rows }
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

fn rel(got: f32, want: f64) -> f64 {
    if want.abs() < TINY {
        // compared absolutely: an f32 result this small is only required to be as small
        return if (got as f64 - want).abs() <= TINY {
            0.0
        } else {
            f64::INFINITY
        };
    }
    ((got as f64 - want) / want).abs()
}

fn tan_of(v: Vec3) -> f64 {
    let (x, y, z) = (v.x as f64, v.y as f64, v.z as f64);
    (x * x + y * y).sqrt() / z
}

fn params(r: &Row) -> GhsParams {
    GhsParams {
        sigma_s_um: r.f("sigma_s"),
        beta: r.f("beta"),
        p: r.f("p"),
        b_um: r.f("b"),
        c: r.f("c"),
        n: r.f("n"),
        k: r.f("k"),
        diff_color: r.u("diff_color"),
        layer: r.u("layer"),
        layer_form: r.u("layer_form"),
        layer_albedo: r.f("albedo"),
        pad: 0,
    }
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
            let h = r.v3("h");
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
            scalar(g.g1(r.v3("w").z), "G1 (Eqs. 40-42)")
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
            ghs::color::diffraction_color(r.v3("wi"), r.v3("wo"), r.f("n"), r.f("k")),
            "Q (Eq. 27)",
        ),
        "sigma_rel" => {
            let g = Ghs::new(&material(0.1, 1.0, r.f("b"), r.f("c")), r.f("lambda"));
            scalar(g.sigma_rel_sq(r.v3("wi")), "σ_rel² (Eq. 25)")
        }
        "brdf" => {
            let p = params(r);
            let (wi, wo) = (r.v3("wi"), r.v3("wo"));
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
            let got = gs::sample_diffraction(&k, r.v3("wi"), Vec2::new(r.f("u0"), r.f("u1")));
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

#[derive(Default)]
struct Stat {
    n: usize,
    over: usize,
    worst_err: f64,
    worst_ratio: f64,
    worst_row: String,
    /// The largest `err/κ` among the queries whose bound is `K·κ` (not the floor).
    worst_err_per_kappa: f64,
    n_kappa_bound: usize,
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
        let t = load(family);
        assert!(!t.rows.is_empty(), "{family}: no queries");
        for raw in &t.rows {
            let r = Row { t: &t, r: raw };
            let Some(o) = eval(family, &r) else {
                continue;
            };
            total += 1;
            let bound = FLOOR.max(K * o.kappa);
            let ratio = o.err / bound;
            if let Some((beta, tan_h)) = o.map {
                writeln!(
                    dump,
                    "{family},{beta},{tan_h},{},{bound},{}",
                    o.err, o.kappa
                )
                .unwrap();
            }
            let s = stats.entry((fi, o.group)).or_default();
            s.n += 1;
            s.worst_err = s.worst_err.max(o.err);
            if K * o.kappa > FLOOR {
                s.n_kappa_bound += 1;
                s.worst_err_per_kappa = s.worst_err_per_kappa.max(o.err / o.kappa);
            }
            if !(ratio <= 1.0) {
                s.over += 1;
            }
            if !(ratio <= s.worst_ratio) {
                s.worst_ratio = ratio;
                s.worst_row = raw.join(",");
            }
        }
    }
    println!("{total} queries; bound = max({FLOOR:e}, {K}·κ)");
    println!(
        "| {:<34} | {:>6} | {:>13} | {:>12} | {:>6} | {:>16} |",
        "family", "n", "worst rel err", "worst err/bd", "over", "err/κ (n, κ-bd)"
    );
    let mut bad = Vec::new();
    for ((_, group), s) in &stats {
        println!(
            "| {group:<34} | {:>6} | {:>13.2e} | {:>12.3} | {:>6} | {:>16} |",
            s.n,
            s.worst_err,
            s.worst_ratio,
            s.over,
            format!("{:.2} ({})", s.worst_err_per_kappa, s.n_kappa_bound)
        );
        if s.over > 0 {
            bad.push(format!("{group}: {} over, worst {}", s.over, s.worst_row));
        }
    }
    if let Ok(path) = std::env::var("GHS_SWEEP_DUMP") {
        std::fs::write(&path, format!("family,beta,tan_h,err,bound,kappa\n{dump}")).unwrap();
    }
    assert!(total >= 10_000, "only {total} queries");
    assert!(bad.is_empty(), "{}", bad.join("\n"));
}
