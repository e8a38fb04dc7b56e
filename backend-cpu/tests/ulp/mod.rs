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

/// The distances of paired scalar and lane results, with their order statistics.
pub struct UlpStats<'a> {
    scalar: &'a [f32],
    lanes: &'a [f32],
    all: Vec<u32>,
    sorted: Vec<u32>,
}

impl<'a> UlpStats<'a> {
    /// The distances between `scalar[i]` and `lanes[i]`.
    pub fn of(scalar: &'a [f32], lanes: &'a [f32]) -> UlpStats<'a> {
        let all: Vec<u32> = scalar
            .iter()
            .zip(lanes)
            .map(|(s, l)| ulps(*s, *l))
            .collect();
        let mut sorted = all.clone();
        sorted.sort_unstable();
        UlpStats {
            scalar,
            lanes,
            all,
            sorted,
        }
    }

    /// The largest distance and the first pair with it.
    pub fn worst(&self) -> (u32, usize) {
        self.all.iter().copied().zip(0..).max().unwrap_or((0, 0))
    }

    /// The distance at fraction `f` of the sorted distances.
    pub fn percentile(&self, f: f64) -> u32 {
        self.sorted[((self.sorted.len() - 1) as f64 * f) as usize]
    }

    /// One line: identical bits, median, 99th and 99.9th percentile, worst (and where).
    pub fn summary(&self) -> String {
        let (worst, at) = self.worst();
        let identical = self.all.iter().filter(|&&u| u == 0).count();
        format!(
            "identical {identical}/{}, median {}, 99% {}, 99.9% {}, worst {worst} ULP (query {at})",
            self.all.len(),
            self.percentile(0.5),
            self.percentile(0.99),
            self.percentile(0.999)
        )
    }

    /// Asserts the 99th percentile and the worst distance against their bounds; returns the
    /// worst.
    pub fn assert_within(&self, name: &str, p99: u32, max: u32) -> u32 {
        let (worst, at) = self.worst();
        let pct = self.percentile(0.99);
        assert!(pct <= p99, "{name}: 99th percentile {pct} ULP");
        assert!(
            worst <= max,
            "{name}: query {at}: lanes {} vs scalar {} ({worst} ULP)",
            self.lanes[at],
            self.scalar[at]
        );
        worst
    }
}
