//! Domain sweep of the area-light integral with the Gaussian across the band (issue #20):
//! `lights::light_integral` with the extent rule (`bands = 20`, the renderer's default) and
//! the Gauss–Hermite bands (3 and 5) against the mpmath reference
//! `reference/light_extent_sweep.py`, at the very f32 inputs it evaluated, over
//! `reference/light_sweep.py`'s domain (sphere and polygon lights from 1e-5 to 1.4 rad, near
//! and on the horizon, 1–3 rectangular scratches, exact Si), and the same draws with V
//! grooves (`--vgroove`, `light_extent_vgroove.csv`: the chord `Σ_lit ∫ |M − P|² dξ₂` at the
//! one depth phase the kernel takes for every band), reported in their own groups.
//!
//! The reference integrates `φ(x)·L(x·sd)` over the whole line by tanh-sinh quadrature, cut
//! at the kinks of the lit chord `L`, which it finds by its own equations, and the same
//! integral over the kernel's window `|x| ≤ 4.5` alone (column `window`). The window is part
//! of the extent rule's model, as the 6σ window is of Werner's coherent sum: the rule's
//! arithmetic and quadrature are measured against `window`, and the share of the whole value
//! from beyond it (column `tail`) is reported apart as the model's error. The bound is #20's
//! `max(1e-4, 8κ)`, κ the window value's one-ulp conditioning, which takes ~60 further
//! quadratures a query: `reference/light_extent_kappa.py` computes it for the rows over
//! 1e-4 (`light_extent_kappa.csv`; the test prints the rows over 1e-4 that lack it, and
//! counts them against 1e-4 alone). For the fixed-band rules the error is against the whole
//! line, relative to 1e-4: how far their fixed bands are from the Gaussian model. Velinov's single band (`bands = 1`) against the same exact value is printed too:
//! the error of Eq. 27's model, not of its arithmetic (that is `light_domain_sweep.rs`).
//!
//! On the committed subset every lit query meets that bound (since a small polygon crosses
//! the bands in local form, `lights::polygon`); further samples are measured in
//! `docs/stability.md` *The Gaussian across the band*. Asserted: every lit query within the
//! bound ([`RATCHET`], [`RATCHET_HORIZON`]: 1, the bound itself, near the horizon or not),
//! at least [`RATCHET_WITHIN`] within it (all of them), and a value of at most [`TINY`]
//! wherever the window's exact value is (no band within 4.5 standard deviations meets the
//! light).
//!
//! The V grooves (200 queries, 194 lit) are all within the bound as well, worst 0.70
//! ([`RATCHET_VGROOVE`], [`RATCHET_VGROOVE_HORIZON`], [`RATCHET_VGROOVE_WITHIN`]).
//!
//! The committed subsets (`reference/golden/sweep/light_extent.csv`,
//! `light_extent_vgroove.csv`) run by default; a larger sample
//! (`python3 reference/light_extent_sweep.py [--vgroove] --count N --seed-offset K --out DIR`)
//! with `LIGHT_EXTENT_SWEEP_DIR=DIR` (`LIGHT_EXTENT_VGROOVE_SWEEP_DIR=DIR`); the count
//! ratchets apply to the committed subsets only. `LIGHT_EXTENT_SWEEP_DUMP=FILE` writes the extent rule's
//! rectangular lit queries (kind, angular radius, elevation, distance, error against the
//! window and bound) for the stability map (`docs/light_stability_map.py --extent`).

mod sweep_common;

use scratchwave_kernel::lights::light_integral;
use scratchwave_kernel::scratch::ScratchSlice;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use sweep_common::{
    FLOOR, Row, Stat, TINY, Table, bound, check_size, light_distance, light_group, light_query,
    rel, report,
};

/// One table of the sweep: its family (`DIR/family.csv`), the environment variable naming
/// a further sample's `DIR`, the committed subset's size (the test refuses fewer),
/// whether its scratches are V grooves, its largest error ÷ bound away from the horizon and
/// near it, and how many of the committed subset's lit queries must be within the bound.
struct Sweep {
    family: &'static str,
    env: &'static str,
    min: usize,
    vgroove: bool,
    ratchet: f64,
    ratchet_horizon: f64,
    within: usize,
}

/// The rectangular grooves (`light_extent_sweep.py`) and the same draws with V grooves
/// (`--vgroove`), whose chords the kernel integrates across by quadrature
/// (`lights::integrate::across_integral`).
const SWEEPS: [Sweep; 2] = [
    Sweep {
        family: "light_extent",
        env: "LIGHT_EXTENT_SWEEP_DIR",
        min: 400,
        vgroove: false,
        ratchet: RATCHET,
        ratchet_horizon: RATCHET_HORIZON,
        within: RATCHET_WITHIN,
    },
    Sweep {
        family: "light_extent_vgroove",
        env: "LIGHT_EXTENT_VGROOVE_SWEEP_DIR",
        min: MIN_VGROOVE_QUERIES,
        vgroove: true,
        ratchet: RATCHET_VGROOVE,
        ratchet_horizon: RATCHET_VGROOVE_HORIZON,
        within: RATCHET_VGROOVE_WITHIN,
    },
];

/// #20's bound, `err ≤ max(1e-4, 8κ)` against the window's exact value, by [`Cause`] (κ
/// where `light_extent_kappa.csv` has it, else 0), and the count of lit queries within it,
/// so that a change can only keep them. Since a small polygon crosses the bands in local
/// form (`lights::polygon`): all 383 lit queries within the bound (380 before, the other 3
/// polygons at the horizon up to 3.7×), worst 0.72 near the horizon and 0.64 away
/// from it; 370 within 1e-4 of the window's value (325 before). Since a sphere's bands are
/// placed by their exact offset from the band's centre line, its range ends and lit arcs come
/// from the same numbers as its crossings and its horizon crossings are formed without
/// cancellation: 380 within the bound (360 before), every query away from the horizon within it
/// (worst 24× before) and 3.7× near it (53× before); 325 within 1e-4 (300 before). Since the
/// window is measured apart, the cuts at bands tangent inside a sphere's cone, the panels'
/// Gaussian mass without `erf` differences, the panels following the chord ends' sweep and
/// panels of at most 2.5 sd and 4.5 e-folds: 360 within the bound (346 before them), worst 24×
/// away from the horizon (48× before) and 53× near it; 300 within 1e-4 of the window's value
/// (282 before; 275 on the whole line). History on the whole line before: other 1.6e-2 since
/// the cuts where a band is tangent to a polygon edge, 2.4e-2 since the cuts at the band's
/// specular point, 0.31 before them; near the horizon 1.0 (values below 1e-11 wholly beyond the
/// window), 7.0e3 before the band circle kept `cos φ`; within 1e-4: 275, 266, 257, 207.
const RATCHET: f64 = 1.0;
const RATCHET_HORIZON: f64 = 1.0;
const RATCHET_WITHIN: usize = 383;

/// The committed V-groove subset's size (`light_extent_vgroove.csv`).
const MIN_VGROOVE_QUERIES: usize = 200;
/// [`RATCHET`] and [`RATCHET_WITHIN`] for the V grooves (`light_extent_vgroove.csv`): all
/// 194 lit queries within the bound, 192 within 1e-4 of the window's value; the other two
/// (rows 5 and 137, 1.2e-4 and 3.0e-4) within 0.0089 and 0.072 of their bound with κ
/// (`light_extent_vgroove_kappa.csv`).
const RATCHET_VGROOVE: f64 = 1.0;
const RATCHET_VGROOVE_HORIZON: f64 = 1.0;
const RATCHET_VGROOVE_WITHIN: usize = 194;

/// The band rules compared: `LightParams::bands` and a name.
const RULES: [(u32, &str); 4] = [
    (20, "extent"),
    (5, "hermite5"),
    (3, "hermite3"),
    (1, "single band"),
];

/// The kernel's value of one row with `bands`.
fn kernel_value(r: &Row, bands: u32) -> f32 {
    let (mut params, q, s) = light_query(r);
    params.bands = bands;
    light_integral(&params, &q, &ScratchSlice { scratches: &s })
}

/// Where the extent rule's error comes from, as far as the reference tells: the known
/// band-parameter defect near the horizon (`light_domain_sweep.rs`) or not.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Cause {
    Horizon,
    Other,
}

/// One rule's statistics per report group.
type Groups = BTreeMap<((usize, usize), &'static str), Stat>;

/// Error counts of one [`Cause`]: queries, within 1e-4, within the bound, within 10× the
/// bound (by the error ÷ its bound), the worst of the bound.
#[derive(Default)]
struct Tally {
    n: usize,
    within: [usize; 3],
    worst: f64,
    worst_row: String,
}

impl Tally {
    /// Counts one query's relative error `err` and its ratio to the bound `ratio`, keeping
    /// `row`'s text if it is the worst yet.
    fn add(&mut self, err: f64, ratio: f64, row: impl FnOnce() -> String) {
        self.n += 1;
        for (k, over) in [err / FLOOR, ratio, ratio / 10.0].into_iter().enumerate() {
            if over <= 1.0 {
                self.within[k] += 1;
            }
        }
        if !(ratio <= self.worst) {
            self.worst = ratio;
            self.worst_row = row();
        }
    }
}

impl std::fmt::Display for Tally {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let [a, b, c] = self.within;
        write!(
            f,
            "{} queries, {a} / {b} / {c}, worst {:.3}\n    {}",
            self.n, self.worst, self.worst_row
        )
    }
}

#[test]
fn extent_rule_is_within_its_bound_over_the_domain() {
    let mut names = BTreeMap::new();
    let mut stats: Vec<Groups> = RULES.iter().map(|_| BTreeMap::new()).collect();
    let mut causes: BTreeMap<(bool, Cause), Tally> = BTreeMap::new();
    let mut bad = Vec::new();
    // Per table (rectangular, V groove): lit queries, and those within 1e-4 by rule.
    let (mut lit, mut within) = ([0usize; 2], [[0usize; RULES.len()]; 2]);
    // The extent rule against the whole line, its window's share included (within 1e-4),
    // the window's own share of the value (the model's error), and per table the rows over
    // 1e-4 whose κ has not been computed.
    let (mut within_whole, mut shares) = ([0usize; 2], [Vec::new(), Vec::new()]);
    let mut no_kappa: Vec<(&Sweep, Vec<usize>)> = Vec::new();
    // The extent rule's lit queries for the stability map (`LIGHT_EXTENT_SWEEP_DUMP`),
    // rectangular and V grooves (their kinds apart, `light_group`).
    let mut dump = String::from("kind,alpha,elev,distance,err,bound\n");
    for sweep in &SWEEPS {
        let table = Table::load(sweep.env, "reference/golden/sweep", sweep.family);
        check_size(sweep.env, &table, sweep.min);
        let kappas = kappas(sweep, &table);
        let mut missing = Vec::new();
        let v = usize::from(sweep.vgroove);
        for (index, r) in table.rows().enumerate() {
            let g = light_group(&r, &mut names);
            let (whole, window) = (r.d("ref"), r.d("window"));
            if whole > TINY {
                lit[v] += 1;
                shares[v].push((r.d("tail").abs(), index));
            }
            for (i, (bands, rule)) in RULES.iter().enumerate() {
                let got = kernel_value(&r, *bands);
                // The extent rule is measured against its own window, the others against
                // the whole line.
                let want = if *bands == 20 { window } else { whole };
                let text = || {
                    format!(
                        "{} row {index}: kernel {got:e} exact {want:e}: {}",
                        sweep.family,
                        r.text()
                    )
                };
                if *bands == 20 && whole > TINY && rel(got, whole) <= FLOOR {
                    within_whole[v] += 1;
                }
                if want <= TINY {
                    // No band within the window (the extent rule) or within 8 standard
                    // deviations (the others) meets the light.
                    if *bands == 20 && !(f64::from(got).abs() <= TINY) {
                        bad.push(format!(
                            "{rule}: {got:e} where the exact value is {want:e}: {} row \
                             {index}: {}",
                            sweep.family,
                            r.text()
                        ));
                    }
                    continue;
                }
                let err = rel(got, want);
                let err = if err.is_nan() { f64::INFINITY } else { err };
                if err <= FLOOR {
                    within[v][i] += 1;
                }
                if *bands != 20 {
                    stats[i].entry(g).or_default().add(err, 0.0, text);
                    continue;
                }
                let kappa = kappas.get(&index).copied();
                if err > FLOOR && kappa.is_none() {
                    missing.push(index);
                }
                let kappa = kappa.unwrap_or(0.0);
                stats[i].entry(g).or_default().add(err, kappa, text);
                let cause = if g.1.ends_with("near the horizon") {
                    Cause::Horizon
                } else {
                    Cause::Other
                };
                let ratio = err / bound(kappa);
                writeln!(
                    dump,
                    "{},{:e},{:e},{:e},{err:e},{:e}",
                    g.0.0,
                    r.d("alpha"),
                    r.d("elev"),
                    light_distance(&r),
                    bound(kappa)
                )
                .unwrap();
                causes
                    .entry((sweep.vgroove, cause))
                    .or_default()
                    .add(err, ratio, text);
                let limit = match cause {
                    Cause::Horizon => sweep.ratchet_horizon,
                    Cause::Other => sweep.ratchet,
                };
                if !(ratio <= limit) {
                    bad.push(format!(
                        "{rule}: relative error {err:.3e}, {ratio:.3} of max(1e-4, 8κ), κ \
                         {kappa:.3e}, over {limit:e} ({cause:?}): {}",
                        text()
                    ));
                }
            }
        }
        if !missing.is_empty() {
            no_kappa.push((sweep, missing));
        }
    }
    for (i, (bands, rule)) in RULES.iter().enumerate() {
        let against = if *bands == 20 {
            "the Gaussian within 4.5 standard deviations (its window), error ÷ max(1e-4, 8κ) \
             (κ where computed, else 0)"
        } else {
            "the Gaussian across the band, relative error ÷ 1e-4"
        };
        println!(
            "{rule} (bands = {bands}) against {against}; lit queries within 1e-4: rectangular \
             {} ({} lit on the whole line), V groove {} ({}):",
            within[0][i], lit[0], within[1][i], lit[1]
        );
        report(&stats[i], 40);
    }
    println!(
        "extent rule against its window by groove and cause: queries, within 1e-4 / \
         max(1e-4, 8κ) / 10× that, worst of the bound"
    );
    let mut within_bound = [0usize; 2];
    for ((vgroove, cause), t) in &causes {
        let groove = if *vgroove { "V groove" } else { "rectangular" };
        println!("  {groove}, {cause:?}: {t}");
        within_bound[usize::from(*vgroove)] += t.within[1];
    }
    for sweep in &SWEEPS {
        let v = usize::from(sweep.vgroove);
        let share = &shares[v];
        let [a, b, c] = [1.0e-4, 1.0e-3, 1.0e-2].map(|l| share.iter().filter(|s| s.0 <= l).count());
        let worst = share
            .iter()
            .copied()
            .fold((0.0, 0), |w, s| if s.0 > w.0 { s } else { w });
        println!(
            "{}: the window as a model, the share of the whole line's value from beyond 4.5 \
             standard deviations: {} lit queries, {a} / {b} / {c} within 1e-4 / 1e-3 / 1e-2, \
             worst {:.3e} (row {}); the extent rule against the whole line: {} within 1e-4",
            sweep.family, lit[v], worst.0, worst.1, within_whole[v]
        );
    }
    for (sweep, rows) in &no_kappa {
        let rows: Vec<String> = rows.iter().map(usize::to_string).collect();
        let flag = if sweep.vgroove { " --vgroove" } else { "" };
        println!(
            "{} rows of {} over 1e-4 have no κ: python3 reference/light_extent_kappa.py{flag} \
             --rows {} (with --dir DIR for {})",
            rows.len(),
            sweep.family,
            rows.join(","),
            sweep.env
        );
    }
    if let Ok(path) = std::env::var("LIGHT_EXTENT_SWEEP_DUMP") {
        std::fs::write(&path, dump).unwrap();
    }
    for sweep in &SWEEPS {
        let (n, ratchet) = (within_bound[usize::from(sweep.vgroove)], sweep.within);
        if std::env::var_os(sweep.env).is_none() && n < ratchet {
            bad.push(format!(
                "{}: {n} lit queries within max(1e-4, 8κ), fewer than the {ratchet} measured",
                sweep.family
            ));
        }
    }
    assert!(bad.is_empty(), "extent rule:\n{}", bad.join("\n"));
}

/// κ of the rows `reference/light_extent_kappa.py` has computed (`FAMILY_kappa.csv`
/// beside the table), by row index; a row whose recorded window value is not the table's
/// is stale and fails the test.
fn kappas(sweep: &Sweep, table: &Table) -> BTreeMap<usize, f64> {
    let family = format!("{}_kappa", sweep.family);
    let Some(k) = Table::load_optional(sweep.env, "reference/golden/sweep", &family) else {
        return BTreeMap::new();
    };
    let windows: Vec<String> = table.rows().map(|r| r.s("window").to_string()).collect();
    k.rows()
        .map(|r| {
            let index: usize = r.s("row").parse().expect("row index");
            assert_eq!(
                windows.get(index).map(String::as_str),
                Some(r.s("window")),
                "{family}.csv row {index} is not {}.csv's: rerun \
                 reference/light_extent_kappa.py",
                sweep.family
            );
            (index, r.d("kappa"))
        })
        .collect()
}
