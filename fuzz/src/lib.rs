//! Shared checks of the scratchwave fuzz targets: the a-priori bounds the kernel's outputs
//! must respect, and a byte reader that turns fuzz input into raw records and into records
//! projected onto the physical domain.
//!
//! # The bounds
//!
//! * **Table models** (`werner`, `werner_blended`, `velinov`), from the kernel's own
//!   derivation in `kernel/tests/stability.rs`: `|B| ≤ 2πσ²`, `|M − P| ≤ 2W` and
//!   `|η| ≤ √(2π)σ`, so every model's value is at most
//!   `F/(πσ²λ²) (2πσ² + Σ_k 2W_k √(2π) σ)²` (F ≤ 1 the reflectance, λ in µm).
//! * **Light integrals** (incoherent model): the integrand is at most
//!   `F/(πσ²λ²) Σ_k |S_k|² ≤ F/(πσ²λ²) Σ_k 8πW_k²σ²` and `∫ cosθ dω ≤ π` over any light, so
//!   the integral is at most `8π F Σ_k W_k² / λ²`. That physical bound holds for the extent
//!   rule, which integrates only the ξ₁ the light covers. The fixed band rules (Velinov
//!   Eq. 27's single band, Gauss–Hermite) weight chords by the *whole* Gaussian across ξ₁
//!   (`∫|η|² dξ₁ ≤ √π σ W²`) and a chord is at most `4·2/λ` (`|M − P|² ≤ 4W²` over a ξ₂ span
//!   ≤ 2/λ), so they are bounded by `8 F Σ_k W_k² / (√π σ λ)` instead — larger than the
//!   physical bound by `λ/(π^{3/2} σ)` when the Gaussian is wider than the visible disk
//!   (σ < λ/π^{3/2}), where Eq. 27 over-counts by design (see `lights::BandRule`).
//! * **Footprint averages** (as in `kernel/tests/stability.rs`): the accurate
//!   `(1/A_P)∫|η_s|² ≤ 2πσ²`; Eq. 16 ≤ `max(Eq. 15, 2πσ²)`; the accurate ρ_P ≤
//!   `W/(√(2π)σ)`.
//!
//! All bounds are evaluated in f64 and allowed a relative slack of [`SLACK`] for the kernel's
//! f32 rounding.

use scratchwave_kernel::lights::BandRule;
use scratchwave_kernel::material::{Material, MaterialKind};
use scratchwave_kernel::scratch::Scratch;
use std::f64::consts::PI;

/// Relative slack on every bound (f32 rounding of the kernel's sums).
pub const SLACK: f64 = 1.0e-3;

/// `F` for a bound: the constant reflectance, or 1 for a Fresnel material.
pub fn reflectance_bound(m: &Material) -> f64 {
    if MaterialKind::from_u32(m.kind) == MaterialKind::Constant {
        f64::from(m.f)
    } else {
        1.0
    }
}

/// The table-model bound `F/(πσ²λ²) (2πσ² + Σ 2W√(2π)σ)²` (σ in µm, λ in nm).
pub fn table_bound(f: f64, sigma_um: f32, lambda_nm: f32, scratches: &[Scratch]) -> f64 {
    let s = f64::from(sigma_um);
    let lam = f64::from(lambda_nm) * 1.0e-3;
    let sum_w: f64 = scratches.iter().map(|k| f64::from(k.width)).sum();
    let amp = 2.0 * PI * s * s + 2.0 * sum_w * (2.0 * PI).sqrt() * s;
    f * amp * amp / (PI * s * s * lam * lam) * (1.0 + SLACK)
}

/// The light-integral bound (λ in nm, σ in µm) for the band rule `bands`
/// ([`LightParams::bands`](scratchwave_kernel::lights::LightParams)): `8π F Σ W² / λ²` for
/// the extent rule, the larger of that and `8 F Σ W² / (√π σ λ)` for the fixed rules.
pub fn light_bound(
    f: f64,
    lambda_nm: f32,
    sigma_um: f32,
    bands: u32,
    scratches: &[Scratch],
) -> f64 {
    let lam = f64::from(lambda_nm) * 1.0e-3;
    let sum_w2: f64 = scratches
        .iter()
        .map(|k| f64::from(k.width) * f64::from(k.width))
        .sum();
    let physical = 8.0 * PI * f * sum_w2 / (lam * lam);
    let bound = if BandRule::from_u32(bands) == BandRule::Extent {
        physical
    } else {
        physical.max(8.0 * f * sum_w2 / (PI.sqrt() * f64::from(sigma_um) * lam))
    };
    bound * (1.0 + SLACK)
}

/// Asserts `v` is finite, non-negative and at most `bound`.
#[track_caller]
pub fn check(v: f32, bound: f64, what: &dyn Fn() -> String) {
    assert!(
        v.is_finite() && v >= 0.0 && f64::from(v) <= bound,
        "{}: {v} (bound {bound})",
        what()
    );
}

/// Reads fuzz bytes as little-endian words; past the end it reads zeros.
pub struct Bytes<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Bytes<'a> {
    /// A reader over `data`.
    pub fn new(data: &'a [u8]) -> Bytes<'a> {
        Bytes { data, pos: 0 }
    }

    /// The next `N` bytes (zero-padded).
    pub fn take<const N: usize>(&mut self) -> [u8; N] {
        let mut out = [0u8; N];
        for b in &mut out {
            *b = self.data.get(self.pos).copied().unwrap_or(0);
            self.pos += 1;
        }
        out
    }

    /// A raw `Pod` record of `size_of::<T>()` bytes (any bit pattern: NaN, ±Inf, denormals).
    pub fn record<T: bytemuck::Pod>(&mut self) -> T {
        let n = std::mem::size_of::<T>();
        let mut buf = vec![0u8; n];
        for b in &mut buf {
            *b = self.data.get(self.pos).copied().unwrap_or(0);
            self.pos += 1;
        }
        bytemuck::pod_read_unaligned(&buf)
    }

    /// The next byte.
    pub fn byte(&mut self) -> u8 {
        self.take::<1>()[0]
    }
}

/// `t ∈ [0, 1]` from the bits of a word.
pub fn unit_of(bits: u32) -> f64 {
    f64::from(bits) / f64::from(u32::MAX)
}

/// A value in `[lo, hi]` (`0 < lo`), log-uniform in the word's bits; 0 when the low byte is
/// 0 and `zero` is allowed.
pub fn log_range(bits: u32, lo: f64, hi: f64, zero: bool) -> f32 {
    if zero && bits & 0xff == 0 {
        return 0.0;
    }
    (lo * (hi / lo).powf(unit_of(bits))) as f32
}

/// A value in `[lo, hi]`, uniform in the word's bits.
pub fn lin_range(bits: u32, lo: f64, hi: f64) -> f32 {
    (lo + (hi - lo) * unit_of(bits)) as f32
}

/// The bits of an f32.
pub fn bits(x: f32) -> u32 {
    x.to_bits()
}

/// A unit direction from a raw one: the raw vector normalised in f64 when it is finite and
/// non-zero, else `None`.
pub fn unit_direction(v: [f32; 3]) -> Option<[f32; 3]> {
    let l2: f64 = v.iter().map(|&c| f64::from(c) * f64::from(c)).sum();
    if !(l2.is_finite() && l2 > 1.0e-30) {
        return None;
    }
    let s = 1.0 / l2.sqrt();
    Some(v.map(|c| (f64::from(c) * s) as f32))
}

/// A raw scratch projected onto the physical domain: centre within ±10⁵ µm, a unit tangent,
/// half length 0 or in [10⁻⁴, 10⁶] µm, width 0 or in [10⁻³, 100] µm, depth 0 or in
/// [10⁻⁴, 10] µm; the profile word as given (unknown values fall back in the kernel).
pub fn physical_scratch(s: &Scratch) -> Scratch {
    let a = unit_of(bits(s.tangent[0])) * 2.0 * PI;
    Scratch {
        center: [
            lin_range(bits(s.center[0]), -1.0e5, 1.0e5),
            lin_range(bits(s.center[1]), -1.0e5, 1.0e5),
        ],
        tangent: [a.cos() as f32, a.sin() as f32],
        half_len: log_range(bits(s.half_len), 1.0e-4, 1.0e6, true),
        width: log_range(bits(s.width), 1.0e-3, 100.0, true),
        depth: log_range(bits(s.depth), 1.0e-4, 10.0, true),
        profile: s.profile,
    }
}

/// A raw material projected: a constant `F ∈ [0, 1]`, or an IOR with `n ∈ [0.05, 10]`,
/// `k ∈ [0, 20]`; the kind and angle words as given (unknown values fall back).
pub fn physical_material(m: &Material) -> Material {
    Material {
        f: unit_of(bits(m.f)) as f32,
        n: log_range(bits(m.n), 0.05, 10.0, false),
        k: lin_range(bits(m.k), 0.0, 20.0),
        ..*m
    }
}

/// Asserts a scratch segment as the readers promise it: finite, a unit tangent (or a zero
/// one on a zero-length segment), sizes ≥ 0.
#[track_caller]
pub fn check_segment(s: &Scratch) {
    let t2 = s.tangent[0] * s.tangent[0] + s.tangent[1] * s.tangent[1];
    assert!(
        s.center.iter().all(|c| c.is_finite())
            && s.half_len.is_finite()
            && s.half_len >= 0.0
            && s.width.is_finite()
            && s.width >= 0.0
            && s.depth.is_finite()
            && s.depth >= 0.0
            && ((t2 - 1.0).abs() < 1.0e-5 || (s.half_len == 0.0 && t2 <= 1.0 + 1.0e-5)),
        "{s:?}"
    );
}

/// A per-process temporary directory for the files a fuzz input carries (scratch files,
/// OBJ meshes), created once.
pub fn work_dir() -> &'static std::path::Path {
    static DIR: std::sync::OnceLock<std::path::PathBuf> = std::sync::OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("scratchwave-fuzz-{}", std::process::id()));
        std::fs::create_dir_all(&d).expect("temp dir");
        d
    })
}
