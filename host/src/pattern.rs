//! Seeded scratch patterns for scenes: straight scratches, circular arcs and smooth random
//! walks over a rectangle, with width/depth/length distributions and orientation modes
//! (random, brushed, circular polish), split into straight segments.
//!
//! Per scratch `i` a [`ScratchPattern`] draws, in this order, all in f64:
//!
//! 1. the anchor: `x`, then `y`, uniform in the region (scratches may reach beyond it);
//! 2. the heading θ at the anchor ([`Orientation`]): `Random` one draw, `Brushed` two
//!    (Box–Muller), `Circular` none;
//! 3. the shape ([`Shape`]): `Straight` its length; `Arc` its radius, its sweep and the side
//!    it bends to; `Walk` its length, then one Gaussian turn per step after the first;
//! 4. the width, then the depth.
//!
//! A [`Distribution::Constant`] consumes no draw. The order is part of the pattern: a scene
//! names a seed, so changing it changes the scene.
//!
//! The anchor is the midpoint of a straight scratch or an arc and the start of a walk.
//! Curves become polylines whose consecutive segments share their end points exactly (the
//! same f64 point goes to both [`Scratch::from_endpoints`] calls).

use crate::rng::SplitMix64;
use scratchwave_kernel::scratch::{Profile, Scratch};
use std::f64::consts::{FRAC_1_SQRT_2, PI, TAU};

/// Default bound on the segments one pattern (or one scene's scratch sources together) may
/// produce: 2²⁵ ≈ 3.4·10⁷ segments, 1 GiB of 32-byte records.
pub const MAX_SEGMENTS: usize = 1 << 25;

/// A random quantity (µm for lengths, radians for angles).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Distribution {
    /// Always `x`; consumes no random draw.
    Constant(f64),
    /// Uniform in `[lo, hi)` (one draw).
    Uniform {
        /// Lower end.
        lo: f64,
        /// Upper end.
        hi: f64,
    },
    /// Log-uniform in `[lo, hi)`, `lo > 0` (one draw).
    LogUniform {
        /// Lower end (> 0).
        lo: f64,
        /// Upper end.
        hi: f64,
    },
}

impl Distribution {
    /// One value from `rng`.
    pub fn sample(&self, rng: &mut SplitMix64) -> f64 {
        match *self {
            Distribution::Constant(x) => x,
            Distribution::Uniform { lo, hi } => rng.range_f64(lo, hi),
            Distribution::LogUniform { lo, hi } => rng.log_range_f64(lo, hi),
        }
    }

    /// The largest value it can take.
    pub fn max(&self) -> f64 {
        match *self {
            Distribution::Constant(x) => x,
            Distribution::Uniform { hi, .. } | Distribution::LogUniform { hi, .. } => hi,
        }
    }

    /// Checks that the values are finite, `lo ≤ hi`, and every value is `> 0` (or `≥ 0` when
    /// `allow_zero`) and at most `max`; `LogUniform` needs `lo > 0` in any case.
    pub fn check(
        &self,
        field: &'static str,
        allow_zero: bool,
        max: f64,
    ) -> Result<(), PatternError> {
        let (lo, hi) = match *self {
            Distribution::Constant(x) => (x, x),
            Distribution::Uniform { lo, hi } => (lo, hi),
            Distribution::LogUniform { lo, hi } => {
                if !(lo > 0.0) {
                    return Err(PatternError::invalid(
                        field,
                        format!("log_uniform needs lo > 0, got {lo}"),
                    ));
                }
                (lo, hi)
            }
        };
        if !(lo.is_finite() && hi.is_finite()) {
            return Err(PatternError::invalid(field, "must be finite"));
        }
        if lo > hi {
            return Err(PatternError::invalid(
                field,
                format!("needs lo <= hi, got [{lo}, {hi}]"),
            ));
        }
        let ok = if allow_zero { lo >= 0.0 } else { lo > 0.0 };
        if !ok {
            let what = if allow_zero { ">= 0" } else { "> 0" };
            return Err(PatternError::invalid(
                field,
                format!("must be {what}, got {lo}"),
            ));
        }
        if hi > max {
            return Err(PatternError::invalid(
                field,
                format!("must be <= {max}, got {hi}"),
            ));
        }
        Ok(())
    }
}

/// How many scratches.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Count {
    /// Exactly this many.
    Exact(u64),
    /// `round(density · area)`, the density per mm² and the area of the region (not a
    /// Poisson draw: the count is the expectation, rounded).
    PerMm2(f64),
}

/// The shape of each scratch.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Shape {
    /// A straight segment of the given length (µm), centred on the anchor.
    Straight {
        /// Length (µm, > 0).
        length: Distribution,
    },
    /// A circular arc centred (by arc length) on the anchor, tangent to the heading there,
    /// bending left or right with equal probability; split into the fewest equal chords
    /// whose sagitta is at most [`ScratchPattern::chord_tol_um`] (at most a half turn each).
    Arc {
        /// Radius (µm, > 0).
        radius: Distribution,
        /// Swept angle (radians, in (0, 2π]).
        sweep_rad: Distribution,
    },
    /// A smooth random walk from the anchor: `n = ⌈length/step_um⌉` straight steps of
    /// `length/n` each; the first follows the heading, and before each later step the heading
    /// turns by a Gaussian angle of standard deviation `turn_sd_rad` (a discretised
    /// Brownian heading, so the direction changes gradually). One segment per step: the
    /// polyline is the walk, so the chord tolerance does not apply.
    Walk {
        /// Total length (µm, > 0).
        length: Distribution,
        /// Step length (µm, > 0).
        step_um: f64,
        /// Standard deviation of the turn per step (radians, ≥ 0).
        turn_sd_rad: f64,
    },
}

/// The heading at each scratch's anchor.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Orientation {
    /// Uniform in `[0, 2π)`.
    Random,
    /// Brushed: `angle_rad + spread_rad · z` with `z` standard Gaussian (Box–Muller), so
    /// `spread_rad` is the standard deviation of the heading about the brushing direction.
    Brushed {
        /// Brushing direction (radians from +x).
        angle_rad: f64,
        /// Standard deviation of the heading (radians, ≥ 0).
        spread_rad: f64,
    },
    /// Circular polish about `center_um`: the heading is perpendicular to the radius from
    /// the centre to the anchor (counter-clockwise; +x at the centre itself).
    Circular {
        /// Centre of the polish (µm).
        center_um: [f64; 2],
    },
}

/// Which groove profile each scratch gets (all segments of one curve share it).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ProfileChoice {
    /// Every scratch the same.
    Only(Profile),
    /// Rectangular for even scratch indices, triangular for odd ones.
    Alternate,
}

/// A seeded scratch pattern over an axis-aligned rectangle (µm).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScratchPattern {
    /// Lower corner of the region of anchors (µm).
    pub min: [f64; 2],
    /// Upper corner (µm), `≥ min`.
    pub max: [f64; 2],
    /// How many scratches.
    pub count: Count,
    /// Their shape.
    pub shape: Shape,
    /// Their heading at the anchor.
    pub orientation: Orientation,
    /// Groove widths (µm, ≥ 0). Velinov's benchmark: uniform 0.8–6 µm.
    pub width: Distribution,
    /// Groove depths (µm, ≥ 0).
    pub depth: Distribution,
    /// Groove profiles.
    pub profile: ProfileChoice,
    /// Largest distance allowed between an arc and its chords (µm, > 0).
    pub chord_tol_um: f64,
    /// Most segments [`ScratchPattern::generate`] may produce (e.g. [`MAX_SEGMENTS`]).
    pub max_segments: usize,
}

/// Why a pattern cannot be generated.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum PatternError {
    /// A parameter is out of range; `field` names it (`shape.radius`, `width`, …).
    #[error("{field}: {msg}")]
    Invalid {
        /// The parameter.
        field: &'static str,
        /// What is wrong.
        msg: String,
    },
    /// The pattern could produce more segments than allowed.
    #[error(
        "the pattern could produce up to {estimate:.4e} segments, more than the limit of {limit}"
    )]
    TooManySegments {
        /// Worst-case number of segments.
        estimate: f64,
        /// The limit.
        limit: usize,
    },
}

impl PatternError {
    fn invalid(field: &'static str, msg: impl Into<String>) -> PatternError {
        PatternError::Invalid {
            field,
            msg: msg.into(),
        }
    }
}

/// One generated scratch before splitting: its polyline (µm, f64) and groove.
#[derive(Clone, Copy, Debug)]
pub struct Stroke<'a> {
    /// Index of the scratch in the pattern.
    pub index: u64,
    /// The polyline's points (at least two); segment `k` runs from `points[k]` to
    /// `points[k + 1]`.
    pub points: &'a [[f64; 2]],
    /// Groove width (µm).
    pub width: f32,
    /// Groove depth (µm).
    pub depth: f32,
    /// Groove profile.
    pub profile: Profile,
}

/// Largest coordinate or length accepted (µm): 10 m, well inside f32.
const MAX_UM: f64 = 1.0e7;

/// Largest angle accepted (radians): a full turn, with room for the rounding of a
/// conversion from 360°.
const MAX_ANGLE: f64 = TAU * (1.0 + 1e-12);

/// The largest angle a chord of a circle of radius `r` may subtend with sagitta ≤ `tol`:
/// `r (1 − cos(δ/2)) = 2 r sin²(δ/4) ≤ tol`, capped at a half turn.
fn max_chord_angle(r: f64, tol: f64) -> f64 {
    4.0 * (tol / (2.0 * r)).sqrt().min(FRAC_1_SQRT_2).asin()
}

/// Number of chords for an arc of radius `r` sweeping `sweep` radians.
fn arc_chords(r: f64, sweep: f64, tol: f64) -> f64 {
    (sweep / max_chord_angle(r, tol)).ceil().max(1.0)
}

/// Standard Gaussian from two draws (Box–Muller; `1 − u` keeps the logarithm finite).
fn gaussian(rng: &mut SplitMix64) -> f64 {
    let u1 = rng.next_f64();
    let u2 = rng.next_f64();
    (-2.0 * (1.0 - u1).ln()).sqrt() * (TAU * u2).cos()
}

impl ScratchPattern {
    /// Checks every parameter (the spec reader checks them first with JSON paths; this is
    /// the API's own guard).
    pub fn validate(&self) -> Result<(), PatternError> {
        for a in 0..2 {
            let (lo, hi) = (self.min[a], self.max[a]);
            if !(lo.is_finite() && hi.is_finite() && lo.abs() <= MAX_UM && hi.abs() <= MAX_UM) {
                return Err(PatternError::invalid(
                    "region",
                    format!("corners must be finite and within ±{MAX_UM} µm"),
                ));
            }
            if lo > hi {
                return Err(PatternError::invalid("region", "needs min <= max"));
            }
        }
        if let Count::PerMm2(d) = self.count
            && !(d.is_finite() && d >= 0.0)
        {
            return Err(PatternError::invalid(
                "density_per_mm2",
                format!("must be finite and >= 0, got {d}"),
            ));
        }
        match self.shape {
            Shape::Straight { length } => length.check("shape.length", false, MAX_UM)?,
            Shape::Arc { radius, sweep_rad } => {
                radius.check("shape.radius", false, MAX_UM)?;
                sweep_rad.check("shape.sweep", false, MAX_ANGLE)?;
            }
            Shape::Walk {
                length,
                step_um,
                turn_sd_rad,
            } => {
                length.check("shape.length", false, MAX_UM)?;
                Distribution::Constant(step_um).check("shape.step_um", false, MAX_UM)?;
                Distribution::Constant(turn_sd_rad).check("shape.turn_sd", true, MAX_ANGLE)?;
            }
        }
        match self.orientation {
            Orientation::Random => {}
            Orientation::Brushed {
                angle_rad,
                spread_rad,
            } => {
                if !angle_rad.is_finite() {
                    return Err(PatternError::invalid("orientation.angle", "must be finite"));
                }
                Distribution::Constant(spread_rad).check("orientation.spread", true, MAX_ANGLE)?;
            }
            Orientation::Circular { center_um } => {
                if !center_um.iter().all(|c| c.is_finite() && c.abs() <= MAX_UM) {
                    return Err(PatternError::invalid(
                        "orientation.center",
                        format!("must be finite and within ±{MAX_UM} µm"),
                    ));
                }
            }
        }
        self.width.check("width", true, MAX_UM)?;
        self.depth.check("depth", true, MAX_UM)?;
        if !(self.chord_tol_um > 0.0 && self.chord_tol_um.is_finite()) {
            return Err(PatternError::invalid(
                "chord_tol_um",
                format!("must be finite and > 0, got {}", self.chord_tol_um),
            ));
        }
        Ok(())
    }

    /// The number of scratches (after [`ScratchPattern::validate`]), as f64 so that absurd
    /// densities do not overflow.
    fn scratch_count(&self) -> f64 {
        match self.count {
            Count::Exact(n) => n as f64,
            Count::PerMm2(d) => {
                let area_mm2 = (self.max[0] - self.min[0]) * (self.max[1] - self.min[1]) * 1e-6;
                (d * area_mm2).round()
            }
        }
    }

    /// The most segments one scratch can become.
    fn max_segments_per_scratch(&self) -> f64 {
        match self.shape {
            Shape::Straight { .. } => 1.0,
            // The chord count grows with the radius and the sweep.
            Shape::Arc { radius, sweep_rad } => {
                arc_chords(radius.max(), sweep_rad.max(), self.chord_tol_um)
            }
            Shape::Walk {
                length, step_um, ..
            } => (length.max() / step_um).ceil().max(1.0),
        }
    }

    /// Validates, then returns the number of scratches and the worst-case number of
    /// segments, or [`PatternError::TooManySegments`] when that exceeds the limit.
    pub fn estimate(&self) -> Result<(u64, f64), PatternError> {
        self.validate()?;
        let n = self.scratch_count();
        let estimate = n * self.max_segments_per_scratch();
        if !(estimate <= self.max_segments as f64) {
            return Err(PatternError::TooManySegments {
                estimate,
                limit: self.max_segments,
            });
        }
        Ok((n as u64, estimate))
    }

    /// Calls `f` with each scratch's polyline, in index order, drawing from `rng` (see the
    /// module doc for the draw order). Checks the parameters and the segment limit first.
    pub fn for_each_stroke(
        &self,
        rng: &mut SplitMix64,
        mut f: impl FnMut(&Stroke<'_>),
    ) -> Result<(), PatternError> {
        let (count, _) = self.estimate()?;
        let mut points: Vec<[f64; 2]> = Vec::new();
        for index in 0..count {
            let x = rng.range_f64(self.min[0], self.max[0]);
            let y = rng.range_f64(self.min[1], self.max[1]);
            let heading = match self.orientation {
                Orientation::Random => TAU * rng.next_f64(),
                Orientation::Brushed {
                    angle_rad,
                    spread_rad,
                } => angle_rad + spread_rad * gaussian(rng),
                Orientation::Circular { center_um } => {
                    (y - center_um[1]).atan2(x - center_um[0]) + 0.5 * PI
                }
            };
            points.clear();
            self.trace([x, y], heading, rng, &mut points);
            let width = self.width.sample(rng) as f32;
            let depth = self.depth.sample(rng) as f32;
            let profile = match self.profile {
                ProfileChoice::Only(p) => p,
                ProfileChoice::Alternate if index % 2 == 1 => Profile::Triangle,
                ProfileChoice::Alternate => Profile::Rect,
            };
            f(&Stroke {
                index,
                points: &points,
                width,
                depth,
                profile,
            });
        }
        Ok(())
    }

    /// Appends the polyline of one scratch anchored at `a` with heading `theta`.
    fn trace(&self, a: [f64; 2], theta: f64, rng: &mut SplitMix64, out: &mut Vec<[f64; 2]>) {
        let (s, c) = theta.sin_cos();
        match self.shape {
            Shape::Straight { length } => {
                let h = 0.5 * length.sample(rng);
                out.push([a[0] - h * c, a[1] - h * s]);
                out.push([a[0] + h * c, a[1] + h * s]);
            }
            Shape::Arc { radius, sweep_rad } => {
                let r = radius.sample(rng);
                let sweep = sweep_rad.sample(rng);
                let side = if rng.next_f64() < 0.5 { 1.0 } else { -1.0 };
                // Tangent t = (c, s), normal towards the centre n = side · (−s, c):
                // p(φ) = a + r [t sin φ + n (1 − cos φ)], with 1 − cos φ = 2 sin²(φ/2).
                let n = [-side * s, side * c];
                let chords = arc_chords(r, sweep, self.chord_tol_um) as u64;
                for k in 0..=chords {
                    let phi = sweep * (k as f64 / chords as f64 - 0.5);
                    let (sp, h) = (phi.sin(), 2.0 * (0.5 * phi).sin().powi(2));
                    out.push([
                        a[0] + r * (c * sp + n[0] * h),
                        a[1] + r * (s * sp + n[1] * h),
                    ]);
                }
            }
            Shape::Walk {
                length,
                step_um,
                turn_sd_rad,
            } => {
                let len = length.sample(rng);
                let steps = (len / step_um).ceil().max(1.0) as u64;
                let h = len / steps as f64;
                let (mut p, mut heading) = (a, theta);
                out.push(p);
                for k in 0..steps {
                    if k > 0 {
                        heading += turn_sd_rad * gaussian(rng);
                    }
                    let (s, c) = heading.sin_cos();
                    p = [p[0] + h * c, p[1] + h * s];
                    out.push(p);
                }
            }
        }
    }

    /// The scratches' segments, in scratch order and along each curve, drawn from `rng`.
    /// Consecutive segments of one curve share their end points exactly (in f64, before the
    /// records' f32 rounding).
    pub fn generate(&self, rng: &mut SplitMix64) -> Result<Vec<Scratch>, PatternError> {
        let (count, _) = self.estimate()?;
        let mut out = Vec::with_capacity(count as usize);
        self.for_each_stroke(rng, |st| {
            out.extend(
                st.points
                    .windows(2)
                    .map(|w| Scratch::from_endpoints(w[0], w[1], st.width, st.depth, st.profile)),
            );
        })?;
        Ok(out)
    }
}
