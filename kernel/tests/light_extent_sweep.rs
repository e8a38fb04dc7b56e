//! Domain sweep of the area-light integral with the Gaussian across the band (issue #20):
//! `lights::light_integral` with the extent rule (`bands = 20`, the renderer's default) and
//! the Gauss–Hermite bands (3 and 5) against the mpmath reference
//! `reference/light_extent_sweep.py`, at the very f32 inputs it evaluated, over
//! `reference/light_sweep.py`'s domain (sphere and polygon lights from 1e-5 to 1.4 rad, near
//! and on the horizon, 1–3 rectangular scratches, exact Si).
//!
//! The reference integrates `φ(x)·L(x·sd)` over the whole line by tanh-sinh quadrature, cut
//! at the kinks of the lit chord `L`, which it finds by its own equations. It computes no
//! conditioning (a query's κ would take ~50 more such quadratures), so the errors below are
//! relative errors against `FLOOR` (1e-4) alone: for the extent rule that is its quadrature
//! (8-point Gauss–Legendre panels in `1 − cos t`) and its cut at 4.5 standard deviations;
//! for the other rules, how far their fixed bands are from the Gaussian model. Velinov's
//! single band (`bands = 1`) against the same exact value is printed too: the error of
//! Eq. 27's model, not of its arithmetic (that is `light_domain_sweep.rs`).
//!
//! The extent rule does not meet #20's `1e-4` over this domain yet: 275 of the 387 lit
//! queries do, and the test prints where the rest come from (near the horizon; bands
//! beyond the kernel's 4.5-σ window; neither: lights below 1e-3 rad), see
//! `docs/stability.md` *The Gaussian across the band*. Asserted, as a ratchet: every lit
//! query within the committed subset's measured worst
//! ([`RATCHET`], [`RATCHET_WINDOW`], [`RATCHET_HORIZON`]), at least [`RATCHET_WITHIN`]
//! within 1e-4, and a value of at most [`TINY`] wherever the exact value is (no band within
//! 8 standard deviations meets the light).
//!
//! The committed subset (`reference/golden/sweep/light_extent.csv`) runs by default; a larger
//! sample (`python3 reference/light_extent_sweep.py --count N --seed-offset K --out DIR`)
//! with `LIGHT_EXTENT_SWEEP_DIR=DIR`.

mod sweep_common;

use scratchwave_kernel::lights::light_integral;
use scratchwave_kernel::scratch::ScratchSlice;
use std::collections::BTreeMap;
use sweep_common::{
    FLOOR, Row, Stat, TINY, Table, check_size, light_group, light_query, rel, report,
};

/// The committed subset's size (the test refuses fewer).
const MIN_QUERIES: usize = 400;

/// Not bounds: the extent rule does not meet #20's `1e-4` here yet (`docs/stability.md`
/// *The Gaussian across the band*). These are the committed subset's measured worst
/// relative errors by [`Cause`] (other: 1.6e-2, since the cuts where a band is tangent to a
/// polygon edge; 2.4e-2 since the cuts at the band's specular point, 0.31 before them; near
/// the horizon: 1.0, the kernel's 0 for values below 1e-11 that lie beyond the window,
/// since the band circle keeps `cos φ`, 7.0e3 before), and its count of lit queries within
/// 1e-4 (275 since the tangent cuts and panels of half a lobe step; 266 since arc ends
/// beyond `|s| = 1/2` take `s` from `cos φ` and a plane's two crossings the difference of
/// their roots; 257 before that, 207 before the specular cuts), so that a change can only
/// improve them; a fix lowers them.
const RATCHET: f64 = 0.02;
const RATCHET_WINDOW: f64 = 0.35;
const RATCHET_HORIZON: f64 = 1.0;
const RATCHET_WITHIN: usize = 273;

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
/// band-parameter defect near the horizon (`light_domain_sweep.rs`), bands beyond the
/// kernel's 4.5-σ window carrying more than 1e-4 of the value and at least half the error
/// (column `tail`), or neither.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Debug)]
enum Cause {
    Horizon,
    Window,
    Other,
}

/// One rule's statistics per report group.
type Groups = BTreeMap<((usize, usize), &'static str), Stat>;

/// Error counts of one [`Cause`]: queries, within 1e-4, within 1e-3, within 1e-2, worst.
#[derive(Default)]
struct Tally {
    n: usize,
    within: [usize; 3],
    worst: f64,
    worst_row: String,
}

#[test]
fn extent_rule_is_within_its_bound_over_the_domain() {
    let table = Table::load(
        "LIGHT_EXTENT_SWEEP_DIR",
        "reference/golden/sweep",
        "light_extent",
    );
    check_size("LIGHT_EXTENT_SWEEP_DIR", &table, MIN_QUERIES);
    let mut names = BTreeMap::new();
    let mut stats: Vec<Groups> = RULES.iter().map(|_| BTreeMap::new()).collect();
    let mut causes: BTreeMap<Cause, Tally> = BTreeMap::new();
    let mut bad = Vec::new();
    let (mut lit, mut within) = (0usize, [0usize; RULES.len()]);
    for r in table.rows() {
        let g = light_group(&r, &mut names);
        let want = r.d("ref");
        if want > TINY {
            lit += 1;
        }
        for (i, (bands, rule)) in RULES.iter().enumerate() {
            let got = kernel_value(&r, *bands);
            let text = || format!("kernel {got:e} exact {want:e}: {}", r.text());
            if want <= TINY {
                // No band within 8 standard deviations meets the light.
                if *bands == 20 && !(f64::from(got).abs() <= TINY) {
                    bad.push(format!(
                        "{rule}: {got:e} where the exact value is {want:e}: {}",
                        r.text()
                    ));
                }
                continue;
            }
            let err = rel(got, want);
            let err = if err.is_nan() { f64::INFINITY } else { err };
            if err <= FLOOR {
                within[i] += 1;
            }
            stats[i].entry(g).or_default().add(err, 0.0, text);
            if *bands != 20 {
                continue;
            }
            let cause = if g.1.ends_with("near the horizon") {
                Cause::Horizon
            } else if r.d("tail").abs() > FLOOR && r.d("tail").abs() >= 0.5 * err {
                Cause::Window
            } else {
                Cause::Other
            };
            let t = causes.entry(cause).or_default();
            t.n += 1;
            for (k, limit) in [1.0e-4, 1.0e-3, 1.0e-2].into_iter().enumerate() {
                if err <= limit {
                    t.within[k] += 1;
                }
            }
            if !(err <= t.worst) {
                t.worst = err;
                t.worst_row = text();
            }
            let limit = match cause {
                Cause::Horizon => RATCHET_HORIZON,
                Cause::Window => RATCHET_WINDOW,
                Cause::Other => RATCHET,
            };
            if !(err <= limit) {
                bad.push(format!(
                    "{rule}: relative error {err:.3e} over {limit:e} ({cause:?}): {}",
                    text()
                ));
            }
        }
    }
    for (i, (bands, rule)) in RULES.iter().enumerate() {
        println!(
            "{rule} (bands = {bands}) against the Gaussian across the band, relative error ÷ 1e-4; \
             {} of {lit} lit queries within 1e-4:",
            within[i]
        );
        report(&stats[i], 34);
    }
    println!("extent rule by cause: queries, within 1e-4 / 1e-3 / 1e-2, worst relative error");
    for (cause, t) in &causes {
        println!(
            "  {cause:?}: {} queries, {} / {} / {}, worst {:.3e}\n    {}",
            t.n, t.within[0], t.within[1], t.within[2], t.worst, t.worst_row
        );
    }
    let all = within[0];
    if all < RATCHET_WITHIN {
        bad.push(format!(
            "{all} lit queries within 1e-4, fewer than the {RATCHET_WITHIN} measured"
        ));
    }
    assert!(bad.is_empty(), "extent rule:\n{}", bad.join("\n"));
}
