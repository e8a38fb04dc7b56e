//! Material presets: complex IORs at the paper's RGB wavelengths (645, 526, 444 nm, H&P
//! §5.2.2) from named published sources, and example GHS parameter sets.
//!
//! | material | source |
//! |---|---|
//! | gold | D. I. Yakubovsky et al., "Optical constants and structural properties of thin gold films", Opt. Express 25, 25574 (2017), 117 nm e-beam film; tabulated n, k (refractiveindex.info), linearly interpolated between the 10 nm samples |
//! | fused silica | I. H. Malitson, "Interspecimen comparison of the refractive index of fused silica", JOSA 55, 1205 (1965), Sellmeier formula |
//! | N-BK7 | SCHOTT optical glass data sheet N-BK7, Sellmeier coefficients |
//!
//! Other metals (silver, copper, aluminium, nickel, chrome) are not included yet: add them
//! only with values read from a cited table.

use super::{GhsParams, Layer, layers::LayerForm};

/// The RGB wavelengths (µm) the presets are given at.
pub const RGB_LAMBDA_UM: [f32; 3] = [0.645, 0.526, 0.444];

/// A complex IOR at [`RGB_LAMBDA_UM`]: `(n, k)` per channel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RgbIor {
    /// `n` at 645, 526, 444 nm.
    pub n: [f32; 3],
    /// `k` at 645, 526, 444 nm.
    pub k: [f32; 3],
}

/// Gold (Yakubovsky et al. 2017).
pub const GOLD: RgbIor = RgbIor {
    n: [0.147_988, 0.487_844, 1.517_713],
    k: [3.651_548, 2.201_734, 1.925_413],
};

/// Fused silica (Malitson 1965).
pub const FUSED_SILICA: RgbIor = RgbIor {
    n: [1.456_67, 1.460_99, 1.466_03],
    k: [0.0; 3],
};

/// SCHOTT N-BK7.
pub const BK7: RgbIor = RgbIor {
    n: [1.514_68, 1.519_81, 1.525_88],
    k: [0.0; 3],
};

/// The single-wavelength parameters of `base` (its `n`, `k` ignored) with channel `ch` of `ior`
/// (0 red, 1 green, 2 blue; larger values select blue).
pub const fn channel(base: GhsParams, ior: &RgbIor, ch: usize) -> GhsParams {
    let ch = if ch < 3 { ch } else { 2 };
    let mut p = base;
    p.n = ior.n[ch];
    p.k = ior.k[ch];
    p
}

/// Polished metal: weak roughness (σs = 0.02 µm), sharp NDF, narrow diffraction lobe.
pub const POLISHED_METAL: GhsParams = GhsParams::new(0.02, 0.05, 0.8, 5.0, 2.5, 1.0, 0.0);

/// Brushed/rough metal: σs ≈ λ/2, diffraction dominates except at grazing angles.
pub const ROUGH_METAL: GhsParams = GhsParams::new(0.25, 0.2, 0.6, 2.0, 2.0, 1.0, 0.0);

/// Glossy plastic: dielectric varnish over a diffuse base (`ρd = 0.8`).
pub const GLOSSY_PLASTIC: GhsParams = GhsParams::new(0.05, 0.1, 1.0, 3.0, 3.0, 1.5, 0.0)
    .with_layer(Layer::Plastic, LayerForm::Published, 0.8);

/// Translucent stone: subsurface layer with albedo 0.9.
pub const TRANSLUCENT_STONE: GhsParams = GhsParams::new(0.1, 0.15, 1.0, 2.0, 2.5, 1.5, 0.0)
    .with_layer(Layer::Subsurface, LayerForm::Published, 0.9);
