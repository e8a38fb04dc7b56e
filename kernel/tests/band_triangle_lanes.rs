//! The V-groove band integral (`across_integral`, `Profile::Triangle`) evaluates the 4
//! Gauss–Legendre nodes of each panel in one `Lanes<4>` on the CPU and one node at a time
//! on SPIR-V. The node formula (`mask_minus_profile`) uses only the kernel's own
//! polynomials, so the lanes must give the bits of the plain scalar rule written out here:
//! the same panels, nodes in the order `−x₀, x₀, −x₁, x₁`, each `|M − P|²` from the public
//! scalar `mask_minus_profile`.

use scratchwave_kernel::lights::SiMode;
use scratchwave_kernel::lights::integrate::{Across, MAX_PANELS, PANEL_BLOCK, across_integral};
use scratchwave_kernel::math::quadrature::{GL4_W, GL4_X};
use scratchwave_kernel::scratch::Profile;
use scratchwave_kernel::scratch::profile::mask_minus_profile;

/// The scalar rule: panels no wider than a quarter of the sinc lobe spacing (at most
/// `MAX_PANELS`), 4-point Gauss–Legendre on each, summed in blocks of `PANEL_BLOCK` panels.
fn scalar_rule(a: &Across, q0: f32, len: f32) -> f32 {
    let want = len.abs() * a.width * 4.0 + 1.0;
    let panels = if want < MAX_PANELS as f32 {
        want as u32
    } else {
        MAX_PANELS
    }
    .max(1);
    let h = len / panels as f32;
    let mut total = 0.0f32;
    for start in (0..panels).step_by(PANEL_BLOCK as usize) {
        total += block_sum(a, q0, h, start..panels.min(start + PANEL_BLOCK));
    }
    0.5 * h * total
}

fn block_sum(a: &Across, q0: f32, h: f32, panels: std::ops::Range<u32>) -> f32 {
    let mut acc = 0.0f32;
    for p in panels {
        let mid = q0 + (p as f32 + 0.5) * h;
        for i in 0..4 {
            let j = i / 2;
            let x = if i % 2 == 0 { -GL4_X[j] } else { GL4_X[j] };
            let q = mid + 0.5 * h * x;
            let mp = mask_minus_profile(
                Profile::Triangle,
                a.width,
                a.depth,
                a.depth_half_turns_per_um,
                q,
            );
            acc += GL4_W[j] * mp.norm_sqr();
        }
    }
    acc
}

#[test]
fn lanes_give_the_scalar_rules_bits() {
    let widths = [0.05f32, 0.8, 2.5, 6.0, 25.0];
    let depths = [0.003f32, 0.1, 0.5, 2.0];
    // 2γ/λ for γ ∈ {0.2, 1, 2} and λ ∈ {0.38, 0.55, 0.78} µm.
    let mut half_turns = Vec::new();
    for gamma in [0.2f32, 1.0, 2.0] {
        for lambda in [0.38f32, 0.55, 0.78] {
            half_turns.push(2.0 * gamma / lambda);
        }
    }
    let starts = [-40.0f32, -1.3, -0.02, 0.0, 1e-4, 0.7, 12.0];
    let lengths = [1e-6f32, 3e-4, 0.02, 0.4, -0.4, 5.0, 80.0, -300.0];
    let (mut total, mut nonzero) = (0usize, 0usize);
    for &width in &widths {
        for &depth in &depths {
            for &ht in &half_turns {
                let a = Across {
                    profile: Profile::Triangle,
                    width,
                    depth,
                    depth_half_turns_per_um: ht,
                    lambda: 0.55,
                    si: SiMode::Exact,
                };
                for &q0 in &starts {
                    for &len in &lengths {
                        let got = across_integral(&a, q0, len);
                        let want = scalar_rule(&a, q0, len);
                        assert_eq!(
                            got.to_bits(),
                            want.to_bits(),
                            "W {width} D {depth} 2γ/λ {ht} q0 {q0} len {len}: {got} vs {want}"
                        );
                        total += 1;
                        nonzero += usize::from(got != 0.0);
                    }
                }
            }
        }
    }
    println!("{total} V-groove band integrals bit-identical ({nonzero} nonzero)");
    assert!(nonzero > total / 2);
}
