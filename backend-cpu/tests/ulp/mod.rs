//! Shared by the lane tests: directions over the upper hemisphere and the distance between
//! a lane result and a scalar result in units in the last place.

use scratchwave_host::rng::SplitMix64;

/// Below this both results count as equal when their absolute difference is below it too
/// (values this small carry no information about the lane arithmetic).
pub const TINY: f32 = 1.0e-30;

/// A direction uniform over the upper hemisphere (grazing included).
pub fn upper(r: &mut SplitMix64) -> [f32; 3] {
    let z = r.next_f32();
    let phi = r.next_f32() * std::f32::consts::TAU;
    let s = (1.0 - z * z).max(0.0).sqrt();
    [s * phi.cos(), s * phi.sin(), z]
}

/// ULP distance of two results of the same sign; `u32::MAX` for a sign change or a
/// non-finite value.
pub fn ulps(a: f32, b: f32) -> u32 {
    if a == b || (a.abs() < TINY && b.abs() < TINY) {
        return 0;
    }
    if a.is_sign_negative() != b.is_sign_negative() || !a.is_finite() || !b.is_finite() {
        return u32::MAX;
    }
    a.to_bits().abs_diff(b.to_bits())
}

/// The distances of paired results, with their order statistics.
pub struct UlpStats {
    /// Per pair, in input order.
    pub all: Vec<u32>,
    sorted: Vec<u32>,
}

impl UlpStats {
    /// The distances between `scalar[i]` and `lanes[i]`.
    pub fn of(scalar: &[f32], lanes: &[f32]) -> UlpStats {
        let all: Vec<u32> = scalar
            .iter()
            .zip(lanes)
            .map(|(s, l)| ulps(*s, *l))
            .collect();
        let mut sorted = all.clone();
        sorted.sort_unstable();
        UlpStats { all, sorted }
    }

    /// The largest distance and the first pair with it.
    pub fn worst(&self) -> (u32, usize) {
        self.all.iter().copied().zip(0..).max().unwrap_or((0, 0))
    }

    /// The distance at fraction `f` of the sorted distances.
    pub fn percentile(&self, f: f64) -> u32 {
        self.sorted[((self.sorted.len() - 1) as f64 * f) as usize]
    }

    /// Pairs with identical bits (or both tiny).
    pub fn identical(&self) -> usize {
        self.all.iter().filter(|&&u| u == 0).count()
    }
}
