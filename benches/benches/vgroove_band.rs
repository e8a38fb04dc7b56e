//! Cost of the V-groove band integral (`lights::integrate::across_integral`,
//! `Profile::Triangle`) against the number of lobes `W·|len|` its chord covers: 4 panels a
//! lobe (`triangle_panels`), at most `MAX_PANELS` (the cap was 64 panels, i.e. 16 lobes, until its domain sweep
//! found chords over 16 lobes up to 35 % off; `docs/stability.md`).
//!
//! `cargo bench -p scratchwave-benches --bench vgroove_band`: ns per call, single thread,
//! for a 10 µm wide, 0.3 µm deep groove, 256 chords per length with seeded starts (the
//! fastest of 9 passes), and the same per panel.

use scratchwave_kernel::lights::SiMode;
use scratchwave_kernel::lights::integrate::{Across, across_integral, triangle_panels};
use scratchwave_kernel::scratch::Profile;
use std::time::Instant;

const WIDTH_UM: f32 = 10.0;

fn pass(a: &Across, starts: &[f32], len: f32) -> f64 {
    let t = Instant::now();
    let mut sink = 0.0f32;
    for &q0 in starts {
        sink += across_integral(a, std::hint::black_box(q0), len);
    }
    std::hint::black_box(sink);
    t.elapsed().as_nanos() as f64 / starts.len() as f64
}

fn main() {
    let a = Across {
        profile: Profile::Triangle,
        width: WIDTH_UM,
        depth: 0.3,
        depth_half_turns_per_um: 2.0 * 1.8 / 0.55,
        lambda: 0.55,
        si: SiMode::Exact,
    };
    // Starts spread over the band (|q| ≤ 2/λ), from a fixed linear congruential sequence.
    let mut state = 0x2545_f491u32;
    let starts: Vec<f32> = (0..256)
        .map(|_| {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 8) as f32 / (1u32 << 24) as f32 * 7.0 - 3.5
        })
        .collect();
    println!("| lobes `W·len` | panels | ns per call | ns per panel |");
    println!("|---|---|---|---|");
    for lobes in [0.25f32, 1.0, 4.0, 16.0, 64.0, 256.0, 512.0] {
        let len = lobes / WIDTH_UM;
        let panels = triangle_panels(WIDTH_UM, len);
        let ns = (0..9)
            .map(|_| pass(&a, &starts, len))
            .fold(f64::MAX, f64::min);
        println!(
            "| {lobes} | {panels} | {ns:.0} | {:.1} |",
            ns / f64::from(panels)
        );
    }
}
