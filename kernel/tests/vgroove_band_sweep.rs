//! Domain sweep of the V-groove band integral (issue #20): `lights::integrate::across_integral`
//! with `Profile::Triangle`, the panelled Gauss–Legendre rule the area lights run across the
//! band for V-shaped grooves, against the mpmath reference `reference/vgroove_band_sweep.py`
//! at the very f32 inputs it evaluated (W, D, `2γ/λ`, the chord's start and length).
//!
//! A result is accepted when `err ≤ max(1e-4, 8κ)` (`κ`: the largest relative change of the
//! exact value under a one-ulp change of one input), the rule of the other sweeps
//! (`docs/stability.md` *The V-groove across the band*). Groups: how the chord was drawn,
//! and how many of the integrand's lobes (`W·|len|`) it covers: beyond 16 lobes the rule's
//! old cap of 64 panels made its panels wider than a quarter lobe (38 of this subset over
//! the bound, up to 597×); the cap is now `MAX_PANELS`.
//!
//! The committed subset (`reference/golden/sweep/vgroove_band.csv`) runs by default; a larger
//! sample (`python3 reference/vgroove_band_sweep.py --count N --out DIR`) with
//! `VGROOVE_BAND_SWEEP_DIR=DIR`.

mod sweep_common;

use scratchwave_kernel::lights::SiMode;
use scratchwave_kernel::lights::integrate::{Across, across_integral};
use scratchwave_kernel::scratch::Profile;
use std::collections::BTreeMap;
use sweep_common::{Stat, Table, check_size, rel, report};

/// Lobes (`W·|len|`) up to which the old cap (64 panels) kept the panels a quarter lobe wide.
const OLD_CAP_LOBES: f64 = 16.0;

fn coverage(lobes: f64) -> (u8, &'static str) {
    if lobes <= 1.0 {
        (0, "≤ 1 lobe")
    } else if lobes <= OLD_CAP_LOBES {
        (1, "1–16 lobes")
    } else if lobes <= 64.0 {
        (2, "16–64 lobes")
    } else {
        (3, "> 64 lobes")
    }
}

#[test]
fn vgroove_band_integral_is_within_its_bound_over_the_domain() {
    let table = Table::load(
        "VGROOVE_BAND_SWEEP_DIR",
        "reference/golden/sweep",
        "vgroove_band",
    );
    check_size("VGROOVE_BAND_SWEEP_DIR", &table, 1500);
    let mut by_coverage: BTreeMap<(u8, &'static str), Stat> = BTreeMap::new();
    let mut by_kind: BTreeMap<(u8, &'static str), Stat> = BTreeMap::new();
    for r in table.rows() {
        let a = Across {
            profile: Profile::Triangle,
            width: r.f("w"),
            depth: r.f("d"),
            depth_half_turns_per_um: r.f("ht"),
            lambda: 0.55,
            si: SiMode::Exact,
        };
        let (q0, len) = (r.f("q0"), r.f("len"));
        let got = across_integral(&a, q0, len);
        let (want, kappa) = (r.d("ref"), r.d("kappa"));
        let err = rel(got, want);
        let lobes = f64::from(a.width) * f64::from(len).abs();
        let describe = || format!("{} (kernel {got:e}, lobes {lobes:.3})", r.text());
        by_coverage
            .entry(coverage(lobes))
            .or_default()
            .add(err, kappa, describe);
        let kind = match r.s("kind") {
            "anywhere" => (0, "two ends anywhere"),
            "feature" => (1, "around a peak or 0"),
            _ => (2, "log-uniform length"),
        };
        by_kind.entry(kind).or_default().add(err, kappa, describe);
    }
    println!("by the lobes the chord covers:");
    let bad = report(&by_coverage, 16);
    println!("by how the chord was drawn:");
    report(&by_kind, 20);
    assert!(bad.is_empty(), "over the bound:\n{}", bad.join("\n"));
}
