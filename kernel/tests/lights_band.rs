//! The band integral across the scratch (Velinov Eq. 27) and the three sine integrals,
//! against mpmath quadrature committed in `tests/data/band_integral.json`
//! (`kernel/gen/band_reference.py`).

use scratchwave_kernel::lights::{SiMode, band_antiderivative, band_integral, si_fast};
use serde_json::Value;

fn data() -> Value {
    serde_json::from_str(include_str!("data/band_integral.json")).expect("valid JSON")
}

fn rows() -> Vec<(f32, f32, f64)> {
    data()["antiderivative"]
        .as_array()
        .expect("array")
        .iter()
        .map(|r| {
            (
                r["width"].as_f64().expect("w") as f32,
                r["q"].as_f64().expect("q") as f32,
                r["value"].as_f64().expect("v"),
            )
        })
        .collect()
}

/// Worst error of `A(q)` per mode, in units of `W` (A's scale: A(∞) = W/2).
fn worst(mode: SiMode) -> f64 {
    rows()
        .iter()
        .map(|&(w, q, v)| (band_antiderivative(w, q, mode) as f64 - v).abs() / w as f64)
        .fold(0.0, f64::max)
}

#[test]
fn exact_si_antiderivative_matches_quadrature() {
    for (w, q, v) in rows() {
        let a = band_antiderivative(w, q, SiMode::Exact) as f64;
        let tol = 2e-6 * v.abs() + 1e-7 * w as f64;
        assert!((a - v).abs() <= tol, "W={w} q={q}: {a} vs {v}");
    }
}

#[test]
fn approximate_si_errors_are_bounded() {
    let (fast, velinov) = (worst(SiMode::Fast), worst(SiMode::Velinov));
    println!("max |A − A_ref|/W: fast {fast:.2e}, Eq. 29 {velinov:.2e}");
    // |ΔSi| ≤ 6e-5 ⇒ |ΔA| ≤ W·6e-5/π.
    assert!(fast <= 2.0e-5, "{fast}");
    assert!(velinov <= 2.0e-2, "{velinov}");
    assert!(fast < velinov / 100.0);
}

#[test]
fn si_fast_matches_mpmath() {
    for r in data()["si"].as_array().expect("array") {
        let x = r["x"].as_f64().expect("x") as f32;
        let v = r["si"].as_f64().expect("si");
        let e = (si_fast(x) as f64 - v).abs();
        assert!(e <= 6.0e-5, "Si({x}): {} vs {v}", si_fast(x));
        assert_eq!(si_fast(-x), -si_fast(x));
    }
}

#[test]
fn whole_line_integrates_to_width() {
    // ∫ W² sinc²(πWξ) dξ = W over ℝ (the sinc² lobe's area).
    for w in [0.1f32, 1.0, 7.0] {
        let v = band_integral(w, -1.0e5, 1.0e5, SiMode::Exact);
        assert!((v - w).abs() <= 1e-3 * w, "W={w}: {v}");
    }
}

#[test]
fn limits_are_exact() {
    assert_eq!(band_antiderivative(1.0, 0.0, SiMode::Exact), 0.0);
    assert_eq!(band_antiderivative(0.0, 3.0, SiMode::Exact), 0.0);
    // Small W q: A(q) ≈ W² q.
    let a = band_antiderivative(0.5, 1.0e-4, SiMode::Exact);
    assert!((a - 0.25e-4).abs() < 1e-10, "{a}");
    assert!(band_integral(1.0, 0.3, -0.2, SiMode::Exact) < 0.0);
}
