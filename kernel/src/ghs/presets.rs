//! Material presets: complex IORs at the paper's RGB wavelengths (645, 526, 444 nm, H&P
//! §5.2.2) from named published sources, and example GHS parameter sets.
//!
//! | material | source |
//! |---|---|
//! | gold | D. I. Yakubovsky et al., "Optical constants and structural properties of thin gold films", Opt. Express 25, 25574 (2017), 117 nm e-beam film; tabulated n, k (refractiveindex.info), linearly interpolated between the 10 nm samples |
//! | fused silica | I. H. Malitson, "Interspecimen comparison of the refractive index of fused silica", JOSA 55, 1205 (1965), Sellmeier formula |
//! | N-BK7 | SCHOTT optical glass data sheet N-BK7, Sellmeier coefficients |
//! | silver | K. M. McPeak et al., "Plasmonic films can easily be better: rules and recipes", ACS Photonics 2, 326 (2015), thermally evaporated, template-stripped Ag; tabulated n, k (refractiveindex.info), linearly interpolated between the 10 nm samples |
//! | copper | McPeak et al. 2015 (as silver), template-stripped Cu; linearly interpolated between the 10 nm samples |
//! | aluminium | McPeak et al. 2015 (as silver), template-stripped Al; linearly interpolated between the 5 nm samples |
//! | nickel | P. B. Johnson and R. W. Christy, "Optical constants of transition metals: Ti, V, Cr, Mn, Fe, Co, Ni, and Pd", Phys. Rev. B 9, 5056 (1974), room temperature; tabulated n, k (refractiveindex.info), linearly interpolated between the tabulated photon energies (20–42 nm apart here) |
//!
//! The metal values (gold included) are reproduced by `reference/ghs/presets_nk.py` from the
//! refractiveindex.info YAML files bundled in the `optiland` 0.6.3 wheel; add further
//! materials the same way, only with values read from a cited table.

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

/// Silver (McPeak et al. 2015).
pub const SILVER: RgbIor = RgbIor {
    n: [0.051_280_2, 0.042_271_6, 0.041_033_8],
    k: [4.418_53, 3.396_76, 2.614_26],
};

/// Copper (McPeak et al. 2015).
pub const COPPER: RgbIor = RgbIor {
    n: [0.105_713, 0.972_701, 1.053_07],
    k: [3.721_25, 2.607_69, 2.382_62],
};

/// Aluminium (McPeak et al. 2015).
pub const ALUMINIUM: RgbIor = RgbIor {
    n: [1.218_51, 0.707_395, 0.474_503],
    k: [6.807_11, 5.598_75, 4.713_06],
};

/// Nickel (Johnson & Christy 1974).
pub const NICKEL: RgbIor = RgbIor {
    n: [1.99, 1.862_5, 1.723],
    k: [4.18, 3.453_93, 2.904_5],
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
