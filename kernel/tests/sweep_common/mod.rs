//! What every domain sweep (issue #20) shares: the CSV tables the mpmath generators write
//! (`reference/scratch_sweep.py`, `reference/ghs/domain_sweep.py`, …), the acceptance rule
//! `err ≤ max(FLOOR, K·κ)` and the per-group report. Used by the kernel's sweep tests and,
//! through `#[path]`, by the conformance crate's cross-backend sweep.
#![allow(dead_code)]

pub mod sampling;

use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::ghs::GhsParams;
use scratchwave_kernel::lights::{Cone, Light, LightParams, LightQuery};
use scratchwave_kernel::material::Material;
use scratchwave_kernel::scratch::{Profile, Scratch};
use scratchwave_kernel::table::{Model, TableParams, TableQuery};
use std::collections::BTreeMap;

/// The multiple of `κ` (one-ulp conditioning) a result may be off by.
pub const K: f64 = 8.0;
/// The accuracy floor for well-conditioned queries.
pub const FLOOR: f64 = 1.0e-4;
/// Exact values below this are compared absolutely (f32 has no headroom there).
pub const TINY: f64 = 1.0e-30;

/// The bound of a query of conditioning `kappa`.
pub fn bound(kappa: f64) -> f64 {
    bound_with(K, kappa)
}

/// The bound with another multiple `k` of `κ` (a family that states and justifies its own).
pub fn bound_with(k: f64, kappa: f64) -> f64 {
    FLOOR.max(k * kappa)
}

/// One family's CSV: a header and rows of shortest decimals.
pub struct Table {
    pub head: Vec<String>,
    pub rows: Vec<Vec<String>>,
}

impl Table {
    /// `DIR/family.csv`, `DIR` from the environment variable `env` or else `default_dir`
    /// (relative to the repository root; every crate is one level below it).
    pub fn load(env: &str, default_dir: &str, family: &str) -> Table {
        match std::env::var(env) {
            Ok(dir) => Table::read(&format!("{dir}/{family}.csv")),
            Err(_) => Table::committed(default_dir, family),
        }
    }

    /// [`Table::load`]'s table, or `None` where its file does not exist.
    pub fn load_optional(env: &str, default_dir: &str, family: &str) -> Option<Table> {
        let path = match std::env::var(env) {
            Ok(dir) => format!("{dir}/{family}.csv"),
            Err(_) => format!(
                "{}/../{default_dir}/{family}.csv",
                env!("CARGO_MANIFEST_DIR")
            ),
        };
        std::path::Path::new(&path)
            .exists()
            .then(|| Table::read(&path))
    }

    /// `default_dir/family.csv` in the repository, whatever the environment says.
    pub fn committed(default_dir: &str, family: &str) -> Table {
        let root = concat!(env!("CARGO_MANIFEST_DIR"), "/..");
        Table::read(&format!("{root}/{default_dir}/{family}.csv"))
    }

    fn read(path: &str) -> Table {
        let text = std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{path}: {e}"));
        let mut lines = text.lines();
        let head = lines.next().unwrap().split(',').map(String::from).collect();
        let rows = lines
            .map(|l| l.split(',').map(String::from).collect())
            .collect();
        Table { head, rows }
    }

    /// The rows, each readable by column name.
    pub fn rows(&self) -> impl Iterator<Item = Row<'_>> {
        self.rows.iter().map(|r| Row { t: self, r })
    }
}

/// One query of a [`Table`].
pub struct Row<'a> {
    pub t: &'a Table,
    pub r: &'a [String],
}

impl Row<'_> {
    pub fn s(&self, col: &str) -> &str {
        let i = self.t.head.iter().position(|h| h == col);
        &self.r[i.unwrap_or_else(|| panic!("no column {col}"))]
    }
    /// An input: the stored shortest decimal reads back as the exact f32.
    pub fn f(&self, col: &str) -> f32 {
        self.s(col).parse().unwrap()
    }
    pub fn d(&self, col: &str) -> f64 {
        self.s(col).parse().unwrap()
    }
    /// [`Row::d`], or `default` where the table has no such column.
    pub fn d_or(&self, col: &str, default: f64) -> f64 {
        match self.t.head.iter().position(|h| h == col) {
            Some(i) => self.r[i].parse().unwrap(),
            None => default,
        }
    }
    pub fn u(&self, col: &str) -> u32 {
        self.s(col).parse().unwrap()
    }
    /// `name_x, name_y, name_z`.
    pub fn a3(&self, name: &str) -> [f32; 3] {
        [
            self.f(&format!("{name}_x")),
            self.f(&format!("{name}_y")),
            self.f(&format!("{name}_z")),
        ]
    }
    /// The row as written.
    pub fn text(&self) -> String {
        self.r.join(",")
    }
}

/// Refuses a committed subset of fewer than `min` queries; a sample given by the
/// environment variable `env` may have any size.
pub fn check_size(env: &str, table: &Table, min: usize) {
    if std::env::var_os(env).is_none() {
        assert!(table.rows.len() >= min, "{} queries", table.rows.len());
    }
}

/// Angle between two directions (f64, both normalised first), accurate when small.
pub fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let unit = |v: [f64; 3]| {
        let n = v.iter().map(|c| c * c).sum::<f64>().sqrt();
        v.map(|c| c / n)
    };
    let (a, b) = (unit(a), unit(b));
    let chord = (0..3).map(|i| (a[i] - b[i]).powi(2)).sum::<f64>().sqrt();
    2.0 * (chord / 2.0).min(1.0).asin()
}

/// Relative error of `got` against the exact `want`; below [`TINY`], 0 if `got` is as
/// small, else infinite.
pub fn rel(got: f32, want: f64) -> f64 {
    if want.abs() < TINY {
        return if (got as f64 - want).abs() <= TINY {
            0.0
        } else {
            f64::INFINITY
        };
    }
    ((got as f64 - want) / want).abs()
}

/// `|got − want|` in units of the f32 spacing at `want` rounded to f32 (0 when equal, also
/// for two zeros of either sign; ∞ where that spacing is not finite and they differ).
pub fn ulps(got: f32, want: f64) -> f64 {
    if f64::from(got) == want {
        return 0.0;
    }
    let w = (want as f32).abs();
    let spacing = f64::from(f32::from_bits(w.to_bits() + 1)) - f64::from(w);
    if spacing == 0.0 || !spacing.is_finite() {
        return f64::INFINITY;
    }
    (f64::from(got) - want).abs() / spacing
}

/// One report group's tally.
#[derive(Default)]
pub struct Stat {
    pub n: usize,
    pub over: usize,
    pub worst_err: f64,
    pub worst_ratio: f64,
    pub worst_row: String,
    /// The largest `err/κ` among the queries whose bound is `K·κ` (not the floor).
    pub worst_err_per_kappa: f64,
    pub n_kappa_bound: usize,
}

impl Stat {
    /// Adds one query; `row` (called only for the worst one so far) describes it. Returns
    /// `err / bound`.
    pub fn add(&mut self, err: f64, kappa: f64, row: impl FnOnce() -> String) -> f64 {
        self.add_with(K, err, kappa, row)
    }

    /// [`Stat::add`] under [`bound_with`]`(k, κ)`.
    pub fn add_with(&mut self, k: f64, err: f64, kappa: f64, row: impl FnOnce() -> String) -> f64 {
        let ratio = err / bound_with(k, kappa);
        self.n += 1;
        self.worst_err = self.worst_err.max(err);
        if k * kappa > FLOOR {
            self.n_kappa_bound += 1;
            self.worst_err_per_kappa = self.worst_err_per_kappa.max(err / kappa);
        }
        if !(ratio <= 1.0) {
            self.over += 1;
        }
        if !(ratio <= self.worst_ratio) {
            self.worst_ratio = ratio;
            self.worst_row = row();
        }
        ratio
    }
}

/// Prints the per-group table (groups keyed by `(order, name)`, `width` the name column)
/// and returns one line per group with queries over the bound.
pub fn report<O: Ord>(stats: &BTreeMap<(O, &'static str), Stat>, width: usize) -> Vec<String> {
    println!(
        "| {:<width$} | {:>6} | {:>13} | {:>12} | {:>6} | {:>16} |",
        "family", "n", "worst rel err", "worst err/bd", "over", "err/κ (n, κ-bd)"
    );
    let mut bad = Vec::new();
    for ((_, group), s) in stats {
        println!(
            "| {group:<width$} | {:>6} | {:>13.2e} | {:>12.3} | {:>6} | {:>16} |",
            s.n,
            s.worst_err,
            s.worst_ratio,
            s.over,
            format!("{:.2} ({})", s.worst_err_per_kappa, s.n_kappa_bound)
        );
        println!("  worst: {}", s.worst_row);
        if s.over > 0 {
            bad.push(format!("{group}: {} over, worst {}", s.over, s.worst_row));
        }
    }
    bad
}

/// One query of the scratch-model sweep (`reference/scratch_sweep.py`) as the kernel's
/// table records: what `table::evaluate` receives. `base` is the `werner_blended` base
/// (a `BaseKind` code; 0 for the other families, whose `base` column is
/// `TableParams::base_gaussian`): a base other than none is evaluated through `bsdf::eval`.
pub struct ScratchQuery {
    pub params: TableParams,
    pub scratches: Vec<Scratch>,
    pub query: TableQuery,
    pub base: u32,
    pub group: &'static str,
}

/// The families of `reference/golden/sweep/` (scratch models).
pub const SCRATCH_FAMILIES: [&str; 4] = ["velinov", "werner_rect", "werner_tri", "werner_blended"];

/// The row's `n` scratches, columns `s{i}_cx`, `_cy`, `_tx`, `_ty`, `_h`, `_w`, `_d`,
/// `_profile` (the scratch and light sweeps).
pub fn scratches_of(r: &Row) -> Vec<Scratch> {
    (0..r.u("n"))
        .map(|i| Scratch {
            center: [r.f(&format!("s{i}_cx")), r.f(&format!("s{i}_cy"))],
            tangent: [r.f(&format!("s{i}_tx")), r.f(&format!("s{i}_ty"))],
            half_len: r.f(&format!("s{i}_h")),
            width: r.f(&format!("s{i}_w")),
            depth: r.f(&format!("s{i}_d")),
            profile: r.u(&format!("s{i}_profile")),
        })
        .collect()
}

/// Decodes one scratch-sweep row of `family`.
pub fn scratch_query(family: &str, r: &Row) -> ScratchQuery {
    let scratches = scratches_of(r);
    let velinov = family == "velinov";
    let blended = family == "werner_blended";
    let params = TableParams {
        model: if velinov {
            Model::Velinov as u32
        } else if blended {
            Model::WernerBlended as u32
        } else {
            Model::Werner as u32
        },
        eta: r.u("eta"),
        depth_term: r.u("depth_term"),
        // werner_blended's `base` column is a BaseKind, not this flag
        base_gaussian: if blended { 0 } else { r.u("base") },
        sigma_um: r.f("sigma"),
        window: 0,
        crossings: 0,
        pad: [0; 1],
    };
    let query = TableQuery {
        wi: r.a3("wi"),
        lambda_nm: r.f("lambda_nm"),
        wo: r.a3("wo"),
        x: [r.f("x_x"), r.f("x_y")],
        material: Material::constant(1.0),
        ..Default::default()
    };
    let base = if blended { r.u("base") } else { 0 };
    let tri = scratches
        .iter()
        .any(|s| s.profile == Profile::Triangle as u32);
    let group = match (family, params.eta, params.base_gaussian) {
        ("werner_blended", _, _) => blended_group(base, r.d("rho_c")),
        ("velinov", 1, _) => "Velinov Eq. 7, η∞ (Eq. 8)",
        ("velinov", _, 1) => "Velinov Eqs. 6–7, finite η + (1−ρc)B²",
        ("velinov", _, _) => "Velinov Eq. 7, finite η (App. A)",
        _ if tri => "Werner Eq. 15, triangle",
        _ => "Werner Eq. 15, rectangle",
    };
    ScratchQuery {
        params,
        scratches,
        query,
        base,
        group,
    }
}

/// The report group of a `werner_blended` query: its base, and for the GHS base where ρc
/// (at the query's `x`) puts the weight `1 − ρc`.
fn blended_group(base: u32, rho_c: f64) -> &'static str {
    match base {
        0 => "Werner §5 |S|², no base (table)",
        1 => "Werner §5 |S|², smooth base (bsdf)",
        _ if rho_c < 0.01 => "Werner §5 + (1−ρc) GHS, ρc < 0.01",
        _ if rho_c < 0.99 => "Werner §5 + (1−ρc) GHS, 0.01 ≤ ρc < 0.99",
        _ => "Werner §5 + (1−ρc) GHS, ρc ≥ 0.99",
    }
}

/// A GHS material from the columns `{prefix}sigma_s`, `beta`, `p`, `b`, `c`, `n`, `k`,
/// `diff_color`, `layer`, `layer_form`, `albedo` (as `reference/ghs/domain_sweep.py` names
/// them).
pub fn ghs_params(r: &Row, prefix: &str) -> GhsParams {
    let f = |c: &str| r.f(&format!("{prefix}{c}"));
    let u = |c: &str| r.u(&format!("{prefix}{c}"));
    GhsParams {
        sigma_s_um: f("sigma_s"),
        beta: f("beta"),
        p: f("p"),
        b_um: f("b"),
        c: f("c"),
        n: f("n"),
        k: f("k"),
        diff_color: u("diff_color"),
        layer: u("layer"),
        layer_form: u("layer_form"),
        layer_albedo: f("albedo"),
        conductor: 0,
    }
}

/// The inputs of one footprint-sweep row (`reference/footprint_sweep.py`): the scratch
/// (depth and profile unused), the ellipse and σ.
pub fn footprint_inputs(r: &Row) -> (Scratch, Ellipse, f32) {
    let s = Scratch {
        center: [r.f("s_cx"), r.f("s_cy")],
        tangent: [r.f("s_tx"), r.f("s_ty")],
        half_len: r.f("s_h"),
        width: r.f("s_w"),
        depth: 0.0,
        profile: 0,
    };
    let e = Ellipse {
        center: [r.f("e_cx"), r.f("e_cy")],
        angle_rad: r.f("e_angle"),
        a1: r.f("e_a1"),
        a2: r.f("e_a2"),
        ..Ellipse::default()
    };
    (s, e, r.f("sigma"))
}

/// The multiple of `max(κ, κs)` a result may be off by: 8, the `K` of every other sweep,
/// so the light family's bound differs from the inputs' `8κ` only by the band parameter's
/// resolution `κs`. Where a band crosses a light near its edge, the chord hinges on the
/// angle `β` between the light's centre and the band circle, which the kernel formed from
/// the normalised centre, three dot products, the band's `c` and `ρ` and one `atan2`, each
/// rounded to about an ulp of an O(1) quantity, while `κ` moves one input by one ulp, which
/// moves `β` by as little as a tenth of that: measured worst `err/max(κ, κs)` 9.4 on the
/// committed subset (a band 1.6e-7 rad inside the edge of a 7.8e-5-rad sphere), so the
/// bound was 16 until that angle was formed in two-fold precision
/// (`SphereCap::axis_angle`, worst 3.3), a small polygon's height too
/// (`SphericalPolygon::centre_height`) and the SPIR-V host kept the driver from rewriting
/// the two-fold arithmetic (`backend-spirv/src/no_contraction.rs`): 0.39 of 16 over 10^5
/// further queries on the CPU and on lavapipe, so at most 0.78 of 8; the committed subset
/// 0.37 of 8. An exact 0's `reach` is taken at the same 8 ulps (`light_sweep.py`'s
/// `REACH_ULPS`).
pub const K_LIGHT: f64 = K;

/// The light sweep's tables: the committed subset (or `LIGHT_SWEEP_DIR`'s sample) first;
/// by default, the queries larger samples found over the bound (`light_found.csv`); and the
/// same domain with V grooves (`light_vgroove.csv`, `light_sweep.py --vgroove`, or
/// `LIGHT_VGROOVE_SWEEP_DIR`'s sample).
pub fn light_tables() -> Vec<Table> {
    let mut tables = vec![Table::load(
        "LIGHT_SWEEP_DIR",
        "reference/golden/sweep",
        "light",
    )];
    if std::env::var_os("LIGHT_SWEEP_DIR").is_none() {
        tables.push(Table::committed("reference/golden/sweep", "light_found"));
    }
    tables.push(Table::load(
        "LIGHT_VGROOVE_SWEEP_DIR",
        "reference/golden/sweep",
        "light_vgroove",
    ));
    tables
}

/// Whether a light-sweep row's scratches are V grooves (`light_sweep.py --vgroove`: all
/// of a query's scratches have the same profile).
pub fn light_is_vgroove(r: &Row) -> bool {
    r.u("s0_profile") == Profile::Triangle as u32
}

/// A light-sweep row's `reach` (0 in samples written before the column existed).
pub fn light_reach(r: &Row) -> f64 {
    r.d_or("reach", 0.0)
}

/// The error of `got` on a light-sweep query of exact value `want`, measured against its
/// bound `max(1e-4, K_LIGHT·max(κ, κs))`: [`rel`] (∞ for NaN), except where `want` is below
/// [`TINY`]. There a relative error says nothing, and the row's `reach` (the largest exact
/// value when one input moves by `K_LIGHT` f32 ulps either way, the bound's steps taken
/// literally rather than linearly; 0 where no such move lights anything) is what the
/// kernel may return: 0 up to it, ∞ beyond.
pub fn light_err(got: f32, want: f64, reach: f64) -> f64 {
    let err = if want.abs() < TINY && reach > TINY && f64::from(got).abs() <= reach {
        0.0
    } else {
        rel(got, want)
    };
    if err.is_nan() { f64::INFINITY } else { err }
}

/// One query of the light sweep (`reference/light_sweep.py`) as the kernel's records: the
/// single band (Velinov Eq. 27) with the exact Si, reflectance 1, and the row's scratches.
pub fn light_query(r: &Row) -> (LightParams, LightQuery, Vec<Scratch>) {
    let params = LightParams {
        sigma_um: r.f("sigma"),
        eta: r.u("eta"),
        depth_term: r.u("depth_term"),
        si_mode: 0,
        bands: 1,
        pad: [0; 3],
    };
    let light = if r.u("kind") == 0 {
        let cone = if r.u("cone") == 0 {
            Cone::Asin
        } else {
            Cone::Atan
        };
        Light::sphere(r.a3("l"), r.f("l_r"), cone)
    } else {
        let v: Vec<[f32; 3]> = (0..r.u("count")).map(|i| r.a3(&format!("v{i}"))).collect();
        Light::polygon(&v)
    };
    let q = LightQuery {
        wo: r.a3("wo"),
        lambda_nm: r.f("lambda_nm"),
        x: [r.f("x_x"), r.f("x_y")],
        material: Material::constant(1.0),
        light,
        ..Default::default()
    };
    (params, q, scratches_of(r))
}

/// Angular-radius bands (upper ends, rad) the light sweeps' reports group by.
const LIGHT_SIZES: [(f64, &str); 4] = [
    (1.0e-3, "α < 1e-3"),
    (0.1, "α 1e-3 – 0.1"),
    (3.0, "α ≥ 0.1"),
    (f64::INFINITY, "around the point"),
];

/// A light whose nearest point is within this of the horizon (rad) counts as near it.
const NEAR_HORIZON: f64 = 0.01;

/// The light's distance from the origin in the units the row is written in: the sphere's
/// centre, or the mean of the polygon's vertices (the stability maps' axis).
pub fn light_distance(r: &Row) -> f64 {
    let c = if r.u("kind") == 0 {
        [r.d("l_x"), r.d("l_y"), r.d("l_z")]
    } else {
        let n = r.u("count");
        let mut c = [0.0; 3];
        for i in 0..n {
            for (k, axis) in ["x", "y", "z"].iter().enumerate() {
                c[k] += r.d(&format!("v{i}_{axis}")) / f64::from(n);
            }
        }
        c
    };
    c.iter().map(|v| v * v).sum::<f64>().sqrt()
}

/// A light-sweep row's report group `((kind, size), name)`: the light's kind (sphere with
/// the `asin` or `atan` cone, polygon) and its angular radius, and apart from those the
/// lights that reach within [`NEAR_HORIZON`] of the horizon (names end in "near the
/// horizon"). `names` keeps one `'static` name per group.
pub fn light_group(
    r: &Row,
    names: &mut BTreeMap<(usize, usize), &'static str>,
) -> ((usize, usize), &'static str) {
    let (alpha, elev) = (r.d("alpha"), r.d("elev"));
    let (ki, kn) = match (r.u("kind"), r.u("cone"), light_is_vgroove(r)) {
        (0, 0, false) => (0, "sphere (asin)"),
        (0, _, false) => (1, "sphere (atan)"),
        (_, _, false) => (2, "polygon"),
        (0, 0, true) => (3, "V groove, sphere (asin)"),
        (0, _, true) => (4, "V groove, sphere (atan)"),
        (_, _, true) => (5, "V groove, polygon"),
    };
    let near = alpha < 3.0 && elev - alpha < NEAR_HORIZON;
    let si = if near {
        LIGHT_SIZES.len()
    } else {
        LIGHT_SIZES
            .iter()
            .position(|(hi, _)| alpha < *hi)
            .unwrap_or(LIGHT_SIZES.len() - 1)
    };
    let name = *names.entry((ki, si)).or_insert_with(|| {
        let band = if near {
            "near the horizon"
        } else {
            LIGHT_SIZES[si].1
        };
        Box::leak(format!("{kn}, {band}").into_boxed_str())
    });
    ((ki, si), name)
}
