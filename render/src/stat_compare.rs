//! Per-pixel statistical comparison of an image with a Monte Carlo reference (mean and
//! standard error per pixel), in the manner of Mitsuba 3's BSDF χ²/z tests: per channel
//! `z = (image − mean)/stderr`, its distribution, the fraction of pixels whose every channel
//! lies within 3 standard errors, and, where a pixel lies beyond them (the image's own
//! error exceeds the noise), its relative error `|image − mean| / max(|mean|, floor)`.
//!
//! A standard error of zero (every sample equal, e.g. a background pixel) is raised to
//! [`SE_ROUNDING`] of `max(|mean|, floor)`, the rounding of an `f32` mean, so a pixel that
//! both compute identically has `z = 0` and any real difference is counted.

use crate::RenderError;
use crate::output;
use crate::reference::quantile_sorted;
use crate::render::Image;
use std::path::Path;

/// The smallest standard error, relative to `max(|mean|, floor)`.
pub const SE_ROUNDING: f64 = 1.0e-6;

/// The quantiles of `z` reported per channel.
pub const Z_QUANTILES: [f64; 7] = [0.001, 0.01, 0.25, 0.5, 0.75, 0.99, 0.999];

/// The result of [`compare`].
#[derive(Clone, Debug, PartialEq)]
pub struct Comparison {
    /// Pixels compared.
    pub pixels: usize,
    /// Per channel (R, G, B) the quantiles [`Z_QUANTILES`] of `z`.
    pub z_quantiles: [[f64; Z_QUANTILES.len()]; 3],
    /// Fraction of pixels whose every channel has `|z| ≤ 3`.
    pub within_3se: f64,
    /// Pixels with some `|z| > 3`.
    pub beyond: usize,
    /// Relative error of those pixels (largest channel): median, 99th percentile, worst;
    /// zeros when there are none.
    pub beyond_rel_err: [f64; 3],
    /// The pixel `(i, j)` of the worst relative error among them.
    pub worst_pixel: Option<(u32, u32)>,
    /// `z` per pixel and channel.
    pub z: Image,
    /// Relative error per pixel and channel.
    pub rel_err: Image,
    /// The floor of the relative error (radiance).
    pub floor: f64,
}

/// Compares `image` with a reference `mean` ± `stderr` (all the same size; checked by the
/// caller); `floor` is the reference's floor of relative errors.
pub fn compare(image: &Image, mean: &Image, stderr: &Image, floor: f64) -> Comparison {
    let n = image.rgb.len().min(mean.rgb.len()).min(stderr.rgb.len());
    let mut z = vec![[0.0f32; 3]; n];
    let mut rel = vec![[0.0f32; 3]; n];
    let mut zs: [Vec<f64>; 3] = [Vec::new(), Vec::new(), Vec::new()];
    let mut within = 0usize;
    let mut beyond: Vec<(f64, usize)> = Vec::new();
    for k in 0..n {
        let mut max_abs_z: f64 = 0.0;
        let mut max_rel: f64 = 0.0;
        for c in 0..3 {
            let a = f64::from(image.rgb[k][c]);
            let m = f64::from(mean.rgb[k][c]);
            let scale = m.abs().max(floor);
            let se = f64::from(stderr.rgb[k][c]).max(SE_ROUNDING * scale);
            let zc = if se > 0.0 { (a - m) / se } else { 0.0 };
            let rc = if scale > 0.0 {
                (a - m).abs() / scale
            } else {
                0.0
            };
            z[k][c] = zc as f32;
            rel[k][c] = rc as f32;
            zs[c].push(zc);
            max_abs_z = max_abs_z.max(zc.abs());
            max_rel = max_rel.max(rc);
        }
        if max_abs_z <= 3.0 {
            within += 1;
        } else {
            beyond.push((max_rel, k));
        }
    }
    let mut z_quantiles = [[0.0; Z_QUANTILES.len()]; 3];
    for c in 0..3 {
        zs[c].sort_by(f64::total_cmp);
        for (q, out) in Z_QUANTILES.iter().zip(z_quantiles[c].iter_mut()) {
            *out = quantile_sorted(&zs[c], *q);
        }
    }
    beyond.sort_by(|a, b| a.0.total_cmp(&b.0));
    let errs: Vec<f64> = beyond.iter().map(|b| b.0).collect();
    let w = image.width.max(1);
    let worst_pixel = beyond.last().map(|b| (b.1 as u32 % w, b.1 as u32 / w));
    Comparison {
        pixels: n,
        z_quantiles,
        within_3se: if n > 0 { within as f64 / n as f64 } else { 1.0 },
        beyond: beyond.len(),
        beyond_rel_err: [
            quantile_sorted(&errs, 0.5),
            quantile_sorted(&errs, 0.99),
            errs.last().copied().unwrap_or(0.0),
        ],
        worst_pixel,
        z: Image {
            width: image.width,
            height: image.height,
            rgb: z,
            model_choice: Vec::new(),
        },
        rel_err: Image {
            width: image.width,
            height: image.height,
            rgb: rel,
            model_choice: Vec::new(),
        },
        floor,
    }
}

/// Pixels of the heat map per image pixel along each axis.
pub const HEAT_MAP_SCALE: u32 = 4;

/// The heat map's colour of a pixel: grey (darker for smaller `|z|`) within 3 standard
/// errors; beyond them red where the image is brighter than the reference, blue where it
/// is darker, brighter for larger relative errors (1e-4 faint … 1e-1 and above full).
pub fn heat_colour(z: [f32; 3], rel: [f32; 3]) -> [u8; 3] {
    let (mut zc, mut rc) = (0.0f32, 0.0f32);
    for c in 0..3 {
        if z[c].abs() > zc.abs() {
            zc = z[c];
        }
        rc = rc.max(rel[c]);
    }
    if zc.abs() <= 3.0 {
        let g = (40.0 + 60.0 * zc.abs() / 3.0) as u8;
        return [g, g, g];
    }
    let s = ((rc.max(1e-9).log10() + 4.0) / 3.0).clamp(0.2, 1.0);
    let hot = (80.0 + 175.0 * s) as u8;
    let cool = (40.0 * (1.0 - s)) as u8;
    if zc > 0.0 {
        [hot, cool, cool]
    } else {
        [cool, cool, hot]
    }
}

/// Writes the heat map of `cmp` as a PNG, each pixel [`HEAT_MAP_SCALE`]² wide
/// ([`heat_colour`]).
pub fn write_heat_map(path: &Path, cmp: &Comparison) -> Result<(), RenderError> {
    output::write_rgb8_png(path, cmp.z.width, cmp.z.height, HEAT_MAP_SCALE, |k| {
        heat_colour(cmp.z.rgb[k], cmp.rel_err.rgb[k])
    })
}
