//! The accurate footprint averages evaluate the 8 Gauss–Legendre nodes of each panel either
//! in one `Lanes<8>` (the CPU's default) or one node at a time (what SPIR-V runs): one
//! formula, so the two differ only where the lanes' arithmetic differs from the scalar
//! seam's, that is in `exp` (the kernel's own polynomial in lanes, libm's scalar; both the
//! kernel's with `--features portable-math`, where the results are bit for bit equal).
//!
//! Inputs: every query of the committed footprint sweep (`reference/golden/sweep/`, 800
//! footprints from 1e-3σ to 1e4σ, needles, edge-only and far-off cases).

mod sweep_common;

use scratchwave_kernel::footprint::{Nodes, eta_p_accurate_by, rho_p_accurate_by};
use sweep_common::{Table, footprint_inputs, ulps};

#[test]
fn lanes_and_one_node_at_a_time_agree() {
    let t = Table::load("FOOTPRINT_SWEEP_DIR", "reference/golden/sweep", "footprint");
    assert!(t.rows.len() >= 800, "only {} queries", t.rows.len());
    let (mut worst, mut same, mut total) = (0.0f64, 0usize, 0usize);
    let mut worst_row = String::new();
    for r in t.rows() {
        let (s, e, sigma) = footprint_inputs(&r);
        for (name, f) in [
            ("eta", eta_p_accurate_by as fn(_, _, _, _) -> f32),
            ("rho", rho_p_accurate_by),
        ] {
            let lanes = f(&s, &e, sigma, Nodes::Lanes);
            let one = f(&s, &e, sigma, Nodes::OneAtATime);
            assert!(
                lanes.is_finite() && one.is_finite(),
                "{name}: {lanes} / {one} at {}",
                r.text()
            );
            let d = ulps(lanes, f64::from(one));
            total += 1;
            if d == 0.0 {
                same += 1;
            }
            if d > worst {
                worst = d;
                worst_row = format!("{name}: lanes {lanes:e}, one {one:e} at {}", r.text());
            }
        }
    }
    println!(
        "{total} averages: {same} bit-identical ({:.1} %), worst {worst:.1} ulp{}",
        100.0 * same as f64 / total as f64,
        if worst > 0.0 {
            format!(" ({worst_row})")
        } else {
            String::new()
        }
    );
    if cfg!(feature = "portable-math") {
        assert_eq!(worst, 0.0, "{worst_row}");
    } else {
        // Each node's exp differs by an ulp or two between the seams; a sum of positive
        // terms keeps that.
        assert!(worst <= 16.0, "{worst} ulp: {worst_row}");
    }
}
