//! The ranges the readers accept for the physical parameters every model shares (σ, λ,
//! scratch width and depth, footprint semi-axes). Outside them a reader returns a
//! [`SpecError`] naming the field; inside them every value the kernel returns is finite.
//!
//! An accepted range is wider than the range the accuracy sweeps certify against mpmath
//! (`docs/stability.md`, README *Parameter ranges*): between the two the same formulas run,
//! uncertified. Each bound below says what breaks beyond it.

use crate::error::SpecError;

/// An accepted interval `[lo, hi]` (or `(lo, hi]`) of one parameter, with its unit and the
/// interval as printed in errors and docs.
#[derive(Clone, Copy, Debug)]
pub struct Range {
    /// Lower bound.
    pub lo: f64,
    /// Upper bound (inclusive).
    pub hi: f64,
    /// Whether `lo` itself is excluded.
    pub lo_open: bool,
    /// The interval as written in messages, e.g. `[1e-3, 1e6] µm`.
    pub text: &'static str,
}

/// Gaussian coherence (window) σ, µm. Below ~1e-19 µm Werner's `1/(πσ²λ²)` overflows f32,
/// above ~7e12 µm Velinov Eq. 15's `σ³` does (1.1e24 µm gave an infinite footprint average:
/// a `footprint_spec` fuzz find); a nanometre to a metre keeps every product in range.
pub const SIGMA_UM: Range = Range {
    lo: 1.0e-3,
    hi: 1.0e6,
    lo_open: false,
    text: "[1e-3, 1e6] µm",
};

/// Wavelength, nm: far UV to far infrared, the scene reader's single-wavelength range.
pub const LAMBDA_NM: Range = Range {
    lo: 100.0,
    hi: 1.0e4,
    lo_open: false,
    text: "[100, 1e4] nm",
};

/// Scratch width, µm (0 is a scratch that reflects nothing). Up to a metre, as σ.
pub const WIDTH_UM: Range = Range {
    lo: 0.0,
    hi: 1.0e6,
    lo_open: false,
    text: "[0, 1e6] µm",
};

/// Scratch depth, µm. Beyond a metre the depth phase `4πD/λ` exceeds 1e11 rad, where one
/// f32 ulp of it is already more than a turn.
pub const DEPTH_UM: Range = Range {
    lo: 0.0,
    hi: 1.0e6,
    lo_open: false,
    text: "[0, 1e6] µm",
};

/// A footprint ellipse's semi-axis, µm: a picometre to a kilometre, so that the ellipse's
/// area `π a1 a2`, its squared axes and the inverse squares `1/a²` of the accurate
/// average's quadratic form (and their product) stay within f32: `a1` = 2.8e-27 µm gave a
/// NaN average (a `footprint_spec` fuzz find), and below ~1e-10 µm for both axes the
/// product overflows.
pub const ELLIPSE_AXIS_UM: Range = Range {
    lo: 1.0e-6,
    hi: 1.0e9,
    lo_open: false,
    text: "[1e-6, 1e9] µm",
};

impl Range {
    /// Whether `x` lies in the range.
    pub fn contains(&self, x: f64) -> bool {
        (if self.lo_open {
            x > self.lo
        } else {
            x >= self.lo
        }) && x <= self.hi
    }

    /// Whether the f32 `x` is the f32 rounding of a value in the range, i.e. what
    /// [`Range::check`] may return: the bounds are rounded to f32, so `1e-6f32` (a little
    /// below 1e-6) is in `[1e-6, 1e9]`. NaN is not. For the f32 arrays of the C and Python
    /// interfaces.
    pub fn contains_f32(&self, x: f32) -> bool {
        let (lo, hi) = (self.lo as f32, self.hi as f32);
        (if self.lo_open { x > lo } else { x >= lo }) && x <= hi
    }

    /// `x` (finite, as [`crate::json::number`] returns it) as f32 if it lies in the range,
    /// else an error at `path`: `must be > 0` / `must be >= 0` for a value of the wrong
    /// sign (the ranges are all non-negative), the interval otherwise.
    pub fn check(&self, x: f64, path: &str) -> Result<f32, SpecError> {
        if self.contains(x) {
            return Ok(x as f32);
        }
        let zero_allowed = self.lo == 0.0 && !self.lo_open;
        let msg = if x < 0.0 && zero_allowed {
            format!("must be >= 0, got {x}")
        } else if x <= 0.0 && !zero_allowed {
            format!("must be > 0, got {x}")
        } else {
            format!("must be in {}, got {x}", self.text)
        };
        Err(SpecError::field(path, msg))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The printed interval says what the numbers say.
    #[test]
    fn text_matches_bounds() {
        for r in [SIGMA_UM, LAMBDA_NM, WIDTH_UM, DEPTH_UM, ELLIPSE_AXIS_UM] {
            let (interval, _unit) = r.text.rsplit_once(' ').unwrap();
            let open = interval.starts_with('(');
            let inner = &interval[1..interval.len() - 1];
            let (lo, hi) = inner.split_once(", ").unwrap();
            assert_eq!(open, r.lo_open, "{}", r.text);
            assert_eq!(lo.parse::<f64>().unwrap(), r.lo, "{}", r.text);
            assert_eq!(hi.parse::<f64>().unwrap(), r.hi, "{}", r.text);
            assert!(interval.ends_with(']'));
        }
    }

    /// f32 inputs meet the bounds as rounded to f32: exactly at them in, one ulp out not.
    #[test]
    fn f32_values_meet_rounded_bounds() {
        for r in [SIGMA_UM, LAMBDA_NM, WIDTH_UM, DEPTH_UM, ELLIPSE_AXIS_UM] {
            let (lo, hi) = (r.lo as f32, r.hi as f32);
            assert_eq!(r.contains_f32(lo), !r.lo_open, "{}", r.text);
            assert!(
                r.contains_f32(hi) && !r.contains_f32(hi.next_up()),
                "{}",
                r.text
            );
            assert!(!r.contains_f32(lo.next_down()) && !r.contains_f32(f32::NAN));
        }
        // 1e-6f32 is 9.99999997e-7, below the f64 bound
        assert!(!ELLIPSE_AXIS_UM.contains(f64::from(1e-6f32)));
        assert!(ELLIPSE_AXIS_UM.contains_f32(1e-6));
        assert!(!ELLIPSE_AXIS_UM.contains_f32(2.828427e-27));
    }

    #[test]
    fn errors_name_the_interval_or_the_sign() {
        let e = |r: Range, x| r.check(x, "f").unwrap_err().to_string();
        assert_eq!(
            e(SIGMA_UM, 2e6),
            "f: must be in [1e-3, 1e6] µm, got 2000000"
        );
        assert_eq!(e(SIGMA_UM, -1.0), "f: must be > 0, got -1");
        assert_eq!(
            e(SIGMA_UM, 1e-4),
            "f: must be in [1e-3, 1e6] µm, got 0.0001"
        );
        assert_eq!(e(WIDTH_UM, -1.0), "f: must be >= 0, got -1");
        assert_eq!(e(ELLIPSE_AXIS_UM, 0.0), "f: must be > 0, got 0");
        // the fuzz find whose accurate footprint average was NaN
        assert_eq!(
            e(ELLIPSE_AXIS_UM, 2.828427e-27),
            "f: must be in [1e-6, 1e9] µm, got 0.000000000000000000000000002828427"
        );
        assert_eq!(e(LAMBDA_NM, 50.0), "f: must be in [100, 1e4] nm, got 50");
        assert_eq!(SIGMA_UM.check(1e6, "f").unwrap(), 1e6);
        assert_eq!(WIDTH_UM.check(0.0, "f").unwrap(), 0.0);
    }
}
