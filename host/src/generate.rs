//! The one seeded generator of random straight scratches: conformance recipes, benchmark
//! workloads and test fixtures are configurations of [`ScratchRecipe`].
//!
//! Per scratch it draws, in this order: the centre (x, then y), the direction, the half
//! length (only for [`HalfLength::Uniform`]), the width and the depth. Lengths that scale
//! with the coherence window are given in multiples of [`ScratchRecipe::unit`] (usually σ),
//! widths and depths in µm. The order and the arithmetic are part of the recipe: the
//! committed conformance cases name a seed, so changing either changes their inputs.

use crate::rng::SplitMix64;
use scratchwave_kernel::scratch::{Profile, Scratch};

/// `lo + span · u` with `u` uniform in `[0, 1)` (span given rather than the upper end, so
/// that no rounding of `hi − lo` enters the values).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Uniform {
    /// Lower end.
    pub lo: f32,
    /// Width of the range.
    pub span: f32,
}

impl Uniform {
    /// The range `[lo, lo + span)`.
    pub const fn new(lo: f32, span: f32) -> Uniform {
        Uniform { lo, span }
    }

    fn draw(&self, rng: &mut SplitMix64) -> f32 {
        self.lo + self.span * rng.next_f32()
    }
}

/// How half lengths are chosen (in multiples of [`ScratchRecipe::unit`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum HalfLength {
    /// Scratch `i` gets `values[i % values.len()]` (no random draw).
    Cycle(&'static [f32]),
    /// Drawn uniformly.
    Uniform(Uniform),
}

/// Which groove profiles the scratches get.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProfileMix {
    /// Rectangular for even indices, triangular for odd ones.
    Alternate,
    /// Every scratch the same.
    Only(Profile),
}

/// A recipe for `count` straight scratches with uniform random directions.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScratchRecipe {
    /// How many scratches.
    pub count: usize,
    /// Length unit of `side` and the half lengths (µm), e.g. the coherence σ.
    pub unit: f32,
    /// Centre of the region (µm).
    pub center: [f32; 2],
    /// Centres are uniform in the square of side `side · unit` about `center`.
    pub side: f32,
    /// `Some((period, side))`: scratch `i` with `i % period == period − 1` is placed in the
    /// larger square of side `side · unit` instead (far scratches that a lookup must skip).
    pub outliers: Option<(usize, f32)>,
    /// Half lengths.
    pub half_length: HalfLength,
    /// Groove widths (µm).
    pub width: Uniform,
    /// Groove depths (µm).
    pub depth: Uniform,
    /// Groove profiles.
    pub profile: ProfileMix,
}

impl ScratchRecipe {
    /// The scratches, in index order, drawn from `rng` (which a caller may go on drawing
    /// from, as the conformance recipes do for their queries).
    pub fn generate(&self, rng: &mut SplitMix64) -> Vec<Scratch> {
        (0..self.count).map(|i| self.scratch(i, rng)).collect()
    }

    fn scratch(&self, i: usize, rng: &mut SplitMix64) -> Scratch {
        let side = match self.outliers {
            Some((period, far)) if period > 0 && i % period == period - 1 => far,
            _ => self.side,
        };
        let cx = (rng.next_f32() - 0.5) * side * self.unit;
        let cy = (rng.next_f32() - 0.5) * side * self.unit;
        let angle = core::f32::consts::TAU * rng.next_f32();
        let half_len = self.unit
            * match self.half_length {
                HalfLength::Cycle(values) if !values.is_empty() => values[i % values.len()],
                HalfLength::Cycle(_) => 0.0,
                HalfLength::Uniform(u) => u.draw(rng),
            };
        let width = self.width.draw(rng);
        let depth = self.depth.draw(rng);
        let profile = match self.profile {
            ProfileMix::Alternate if i % 2 == 1 => Profile::Triangle,
            ProfileMix::Alternate => Profile::Rect,
            ProfileMix::Only(p) => p,
        };
        Scratch {
            center: [self.center[0] + cx, self.center[1] + cy],
            tangent: [angle.cos(), angle.sin()],
            half_len,
            width,
            depth,
            profile: profile as u32,
        }
    }
}
