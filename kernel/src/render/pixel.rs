//! Sub-pixel sample positions: deterministic, so images are bitwise reproducible across
//! runs and thread counts.
//!
//! One sample is the pixel centre (the point model at the centre ray, exactly). `N > 1`
//! samples form a rank-1 lattice, `((k + ½)/N, frac(k·g + ½))` with `g = (√5 − 1)/2`
//! (stratified in `x`, well spread in `y`), shifted modulo 1 by a Cranley–Patterson
//! rotation from a 32-bit hash of the pixel index, so neighbouring pixels do not alias.

/// A 32-bit integer hash (the "lowbias32" mixer of C. Wellons' hash-prospector).
#[inline]
pub fn hash32(mut x: u32) -> u32 {
    x ^= x >> 16;
    x = x.wrapping_mul(0x7feb_352d);
    x ^= x >> 15;
    x = x.wrapping_mul(0x846c_a68b);
    x ^= x >> 16;
    x
}

/// `[0, 1)` from the top 24 bits.
#[inline]
fn unit(h: u32) -> f32 {
    (h >> 8) as f32 * (1.0 / 16_777_216.0)
}

/// `x − floor(x)` for `x ≥ 0`, kept below 1.
#[inline]
fn frac(x: f32) -> f32 {
    let f = x - crate::math::floor(x);
    if f >= 1.0 { 0.0 } else { f }
}

/// Offset of sample `k` of `n` inside pixel `pixel_index` (each coordinate in `[0, 1)`).
#[inline]
pub fn sample_offset(pixel_index: u32, k: u32, n: u32) -> (f32, f32) {
    if n <= 1 {
        return (0.5, 0.5);
    }
    let h = hash32(pixel_index);
    let (rx, ry) = (unit(h), unit(hash32(h ^ 0x9e37_79b9)));
    let g = 0.618_034_f32;
    let x = (k as f32 + 0.5) / n as f32;
    let y = frac(k as f32 * g + 0.5);
    (frac(x + rx), frac(y + ry))
}
