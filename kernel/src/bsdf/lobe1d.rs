//! One-dimensional lobes with a CDF and its inverse, truncated to an interval: the Gaussian
//! (the base response's `exp(−4π²σ²|ξ|²)`, Werner Eq. 16), the logistic (Gaussian-like
//! lobes with heavier, exponential tails: along a scratch, where a finite segment's ends
//! widen the window's Gaussian) and the Cauchy (for the scratch profile's `sinc²`), and
//! mixtures of up to three components of one kind.
//!
//! Why these two: `sinc²(πx) (1 + π²x²) = sin²(πx) (1 + 1/(πx)²) ≤ 2`, so a Cauchy of scale
//! `1/π` bounds the rectangular groove's `|M − P|² ∝ W² sinc²(πWξ₂)` (Werner Eq. 14/26) to
//! within a factor 2 everywhere, tails included; and both CDFs invert in closed form, so
//! truncating a lobe to the chord of the unit disk that keeps the sampled direction above
//! the horizon costs nothing and the pdf integrates to exactly 1 (Werner §5 drops
//! evanescent samples instead). The logistic's tails (`e^{−|x|/s}`) are heavier than the
//! Gaussian it stands for, so the ratio target/proposal stays bounded as well.
//!
//! Tail accuracy: masses and inverse CDFs are evaluated on the side of the centre where the
//! CDF is small (`F(z)` for `z ≤ 0`, `1 − F(z) = F(−z)` otherwise), so an interval far in
//! either tail keeps its relative accuracy; near the centre, where the CDF is near ½, the
//! inverse CDF takes `p − ½` formed from the masses between the centre and each end, so a
//! sample near the centre keeps its relative accuracy too. A Gaussian density far out is
//! formed relative to the interval's nearest tail ([`Lobe1::pdf`]).

use crate::math;

gpu_enum! {
    /// The component family of a [`Lobe1`].
    pub enum Lobe1Kind {
        /// Logistic: `F(z) = 1/(1 + e^{−z})`, `z = (x − μ)/s`.
        Logistic = 0,
        /// Cauchy: `F(z) = ½ + atan(z)/π`.
        Cauchy = 1,
        /// Gaussian: `F(z) = ½ erfc(−z/√2)` on the small side, inverted by Acklam's
        /// rational approximation and one Halley step.
        Gaussian = 2,
    }
    fallback = Logistic;
}

/// Most components of a [`Lobe1`].
pub const LOBE1_MAX: usize = 3;

/// A mixture of up to [`LOBE1_MAX`] components of one kind (weights need not be
/// normalised; they are renormalised over the truncation interval).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lobe1 {
    /// Component family.
    pub kind: Lobe1Kind,
    /// Number of components (1 to 3).
    pub count: u32,
    /// Centres μ.
    pub mu: [f32; LOBE1_MAX],
    /// Scales s (> 0).
    pub scale: [f32; LOBE1_MAX],
    /// Relative weights (≥ 0).
    pub weight: [f32; LOBE1_MAX],
}

impl Lobe1 {
    /// One component.
    pub fn single(kind: Lobe1Kind, mu: f32, scale: f32) -> Lobe1 {
        Lobe1 {
            kind,
            count: 1,
            mu: [mu, 0.0, 0.0],
            scale: [scale, 1.0, 1.0],
            weight: [1.0, 0.0, 0.0],
        }
    }

    #[inline]
    fn n(&self) -> usize {
        if self.count as usize > LOBE1_MAX {
            LOBE1_MAX
        } else {
            self.count as usize
        }
    }

    /// Untruncated density of component `j` at `x`, times `e^{shift}` for the Gaussian
    /// ([`Lobe1::density_std`]).
    #[inline]
    fn density_one(&self, j: usize, x: f32, shift: f32) -> f32 {
        if j >= LOBE1_MAX {
            return 0.0;
        }
        let s = self.scale[j];
        self.density_std((x - self.mu[j]) / s, shift) / s
    }

    /// Density `F'(z)` of the standardised component; the Gaussian's times `e^{shift}`, as
    /// `e^{shift − z²/2}/√(2π)` (a density that `e^{−z²/2}` alone would underflow; the
    /// logistic's and the Cauchy's tails stay within f32's range, and they take
    /// `shift = 0`, which they ignore).
    #[inline]
    fn density_std(&self, z: f32, shift: f32) -> f32 {
        match self.kind {
            Lobe1Kind::Logistic => {
                let e = math::exp(-math::abs(z));
                e / ((1.0 + e) * (1.0 + e))
            }
            Lobe1Kind::Cauchy => 1.0 / (math::PI * (1.0 + z * z)),
            Lobe1Kind::Gaussian => math::exp(shift - 0.5 * z * z) * FRAC_1_SQRT_TAU,
        }
    }

    /// `F(zb) − F(za)` of the standardised component, with `d = zb − za` formed from the
    /// interval's own ends (`(b − a)/s`: its width keeps its digits however far out it
    /// lies).
    ///
    /// Forms without the difference of two nearly equal CDF values where it would cancel:
    /// the logistic's exact `F(za) F(−zb) (e^d − 1)` for `d < 1`; the Cauchy's
    /// `atan(d/(1 + za zb))/π` wherever `za zb > −1`; for a [`narrow`] Gaussian interval
    /// the Gaussian interval integral of Werner App. A ([`math::gauss_interval_centered`]).
    /// Otherwise the CDFs on their small sides, whose difference then cancels by at most a
    /// factor of about 2.5 (the logistic's and the Gaussian's tails fall by `e^{−1}` or more
    /// across the interval; a Cauchy interval with `za zb ≤ −1` straddles the centre with
    /// one end at `|z| ≥ 1`, so its mass exceeds ¼).
    ///
    /// The Gaussian's mass comes times `e^{shift}` (`shift ≥ 0`, and 0 unless the interval
    /// lies on one side of the centre: [`Lobe1::pdf`]'s scaling); the logistic and the
    /// Cauchy take `shift = 0`.
    #[inline]
    fn std_mass(&self, za: f32, zb: f32, d: f32, shift: f32) -> f32 {
        let m = match self.kind {
            Lobe1Kind::Logistic => {
                if d < 1.0 {
                    self.cdf_low(za) * self.cdf_low(-zb) * math::expm1(d)
                } else {
                    self.std_mass_wide(za, zb, 0.0)
                }
            }
            Lobe1Kind::Cauchy => {
                if za * zb > -1.0 {
                    math::atan(d / (1.0 + za * zb)) * (1.0 / math::PI)
                } else {
                    self.std_mass_wide(za, zb, 0.0)
                }
            }
            Lobe1Kind::Gaussian => {
                let use_near = narrow(self.kind, za, zb, d);
                let half = 0.5 * d;
                let near = if use_near || UNIFORM_CONTROL {
                    math::gauss_interval_centered(za + half, half, 1.0) * FRAC_1_SQRT_TAU
                } else {
                    0.0
                };
                if use_near {
                    if shift > 0.0 {
                        near * math::exp(shift)
                    } else {
                        near
                    }
                } else {
                    self.std_mass_wide(za, zb, shift)
                }
            }
        };
        math::max(m, 0.0)
    }

    /// `F(zb) − F(za)` from the CDFs on their small sides; on one side of the centre times
    /// `e^{shift}` ([`Lobe1::cdf_scaled`]; `shift` is 0 for an interval around the centre).
    #[inline]
    fn std_mass_wide(&self, za: f32, zb: f32, shift: f32) -> f32 {
        if zb <= 0.0 {
            self.cdf_scaled(zb, shift) - self.cdf_scaled(za, shift)
        } else if za >= 0.0 {
            self.cdf_scaled(-za, shift) - self.cdf_scaled(-zb, shift)
        } else {
            1.0 - self.cdf_low(za) - self.cdf_low(-zb)
        }
    }

    /// `F(z)` for the standardised component, accurate where small (`z ≤ 0`).
    #[inline]
    fn cdf_low(&self, z: f32) -> f32 {
        self.cdf_scaled(z, 0.0)
    }

    /// [`Lobe1::cdf_low`], for `z ≤ 0` the Gaussian's times `e^{shift}` ([`gauss_tail`]);
    /// `shift` is 0 for `z > 0` and for the logistic and the Cauchy.
    #[inline]
    fn cdf_scaled(&self, z: f32, shift: f32) -> f32 {
        match self.kind {
            Lobe1Kind::Logistic => 1.0 / (1.0 + math::exp(-z)),
            // ½ + atan(z)/π = atan(−1/z)/π for z < 0 (no cancellation).
            Lobe1Kind::Cauchy => {
                if z < -1.0 {
                    math::atan(-1.0 / z) * (1.0 / math::PI)
                } else {
                    0.5 + math::atan(z) * (1.0 / math::PI)
                }
            }
            Lobe1Kind::Gaussian => {
                let t = gauss_tail(math::abs(z), shift);
                if z <= 0.0 { t } else { 1.0 - t }
            }
        }
    }

    /// `½ − F(−|z|)`, the standardised component's mass between its centre and `z`, to
    /// its own digits where it is small; `f_small` is [`Lobe1::cdf_low`]`(−|z|)`, whose
    /// difference from ½ serves where it cannot cancel (`F(−|z|) ≤ 0.27`). Near the centre
    /// (`|z| < 1`) the closed forms without ½: the logistic's
    /// `−½ (e^{−|z|} − 1)/(e^{−|z|} + 1)` (with `expm1`), the Cauchy's `atan(|z|)/π`, the
    /// Gaussian's `½ erf(|z|/√2)` (for `|z|/√2 < ½`, where [`math::erf`] is its Taylor
    /// series; beyond, `F(−|z|) ≤ 0.24`).
    #[inline]
    fn centre_mass(&self, z: f32, f_small: f32) -> f32 {
        let az = math::abs(z);
        match self.kind {
            Lobe1Kind::Logistic => {
                if az < 1.0 {
                    let e = math::expm1(-az);
                    -0.5 * e / (2.0 + e)
                } else {
                    0.5 - f_small
                }
            }
            Lobe1Kind::Cauchy => {
                if az < 1.0 {
                    math::atan(az) * (1.0 / math::PI)
                } else {
                    0.5 - f_small
                }
            }
            Lobe1Kind::Gaussian => {
                let x = az * core::f32::consts::FRAC_1_SQRT_2;
                if x < 0.5 {
                    0.5 * math::erf(x)
                } else {
                    0.5 - f_small
                }
            }
        }
    }

    /// Inverse of [`Lobe1::cdf_low`] for `p ∈ (0, ½]`, given also `q = p − ½` to its own
    /// digits (for `p` near ½ the caller forms it without passing through ½: `p` there
    /// holds `p − ½` only to ½'s ulp, 6e-8, which the inverse carries into `z` as an
    /// absolute error, large against a `z` near 0). The inverses in `q`: the logistic's
    /// `z = ln((½ + q)/(½ − q)) = ln1p(2q/(½ − q))` for `|q| <` [`CENTRE_BAND`], the
    /// Cauchy's `tan(πq)` for `p ≥ ¼`, the Gaussian's ([`gauss_inv_low`]).
    #[inline]
    fn inv_low(&self, p: f32, q: f32) -> f32 {
        match self.kind {
            Lobe1Kind::Logistic => {
                if q > -CENTRE_BAND {
                    math::ln1p(2.0 * q / (0.5 - q))
                } else {
                    math::ln(p / (1.0 - p))
                }
            }
            Lobe1Kind::Cauchy => {
                if p < 0.25 {
                    -1.0 / math::tan(math::PI * p)
                } else {
                    math::tan(math::PI * q)
                }
            }
            Lobe1Kind::Gaussian => gauss_inv_low(p, q),
        }
    }

    /// Mass of component `j` on `[a, b]`, the Gaussian's times `e^{shift}`
    /// ([`Lobe1::std_mass`]).
    #[inline]
    fn mass_one(&self, j: usize, a: f32, b: f32, shift: f32) -> f32 {
        if j >= LOBE1_MAX || !(b > a) {
            return 0.0;
        }
        let s = self.scale[j];
        let za = (a - self.mu[j]) / s;
        let zb = (b - self.mu[j]) / s;
        self.std_mass(za, zb, (b - a) / s, shift)
    }

    /// The exponent by which [`Lobe1::pdf`] scales a Gaussian mixture's densities and
    /// masses: `c²/2 = min_j c_j²/2` over the weighted components, `c_j` the standardised
    /// distance from the centre to the interval (0 when it holds the centre). Each
    /// component's terms are then at most `e^{(c² − c_j²)/2}`-scaled tails, the largest of
    /// order 1: an interval 12 and more scales out keeps its density where `e^{−z²/2}`
    /// underflows (`e^{−c²/2}` cancels in the ratio). 0 where `c² ≤` [`PDF_SHIFT_FROM`],
    /// and for the logistic and the Cauchy.
    #[inline]
    fn pdf_shift(&self, a: f32, b: f32) -> f32 {
        if self.kind != Lobe1Kind::Gaussian {
            return 0.0;
        }
        let n = self.n();
        let mut c2 = f32::INFINITY;
        let mut j = 0;
        while j < LOBE1_MAX && j < n {
            if self.weight[j] > 0.0 {
                let c = math::max(math::max(a - self.mu[j], self.mu[j] - b), 0.0) / self.scale[j];
                c2 = math::min(c2, c * c);
            }
            j += 1;
        }
        if c2 > PDF_SHIFT_FROM && c2.is_finite() {
            0.5 * c2
        } else {
            0.0
        }
    }

    /// Total weighted mass on `[a, b]`: `Σ w_j m_j(a, b)`.
    pub fn mass(&self, a: f32, b: f32) -> f32 {
        let n = self.n();
        let mut total = 0.0;
        let mut j = 0;
        while j < LOBE1_MAX && j < n {
            total += self.weight[j] * self.mass_one(j, a, b, 0.0);
            j += 1;
        }
        total
    }

    /// Density at `x` of the mixture truncated to `[a, b]` (0 outside):
    /// `Σ w_j f_j(x) / Σ w_j m_j(a, b)`; a Gaussian's numerator and mass each come times
    /// `e^{c²/2}` for an interval more than 8 scales from every centre (`c` the nearest
    /// centre's distance to it, in its scales), which cancels: the density deep in such an
    /// interval keeps its digits where `e^{−z²/2}` alone would underflow (`pdf_shift`).
    #[allow(clippy::manual_range_contains)] // `RangeInclusive::contains` is rejected by spirv-val
    pub fn pdf(&self, x: f32, a: f32, b: f32) -> f32 {
        if !(x >= a && x <= b) {
            return 0.0;
        }
        let shift = self.pdf_shift(a, b);
        let n = self.n();
        let mut total = 0.0;
        let mut j = 0;
        while j < LOBE1_MAX && j < n {
            total += self.weight[j] * self.mass_one(j, a, b, shift);
            j += 1;
        }
        // No density where the lobe carries no f32 mass (`e^{−shift} Σ w m` = [`Lobe1::mass`]
        // underflows), as [`Lobe1::sample`] then draws nothing.
        if !(total > 0.0) || (shift > 0.0 && !(total * math::exp(-shift) > 0.0)) {
            return 0.0;
        }
        let mut d = 0.0;
        j = 0;
        while j < LOBE1_MAX && j < n {
            d += self.weight[j] * self.density_one(j, x, shift);
            j += 1;
        }
        d / total
    }

    /// The same mixture moved by `dx` (every centre plus `dx`).
    pub fn shifted(&self, dx: f32) -> Lobe1 {
        let mut l = *self;
        let mut j = 0;
        while j < LOBE1_MAX {
            l.mu[j] += dx;
            j += 1;
        }
        l
    }

    /// The component drawn by `u` on `[a, b]` (probability `w_j m_j / Σ w m`), `u`
    /// rescaled within it, and its unweighted mass `m_j`; `None` when the interval carries
    /// no mass. Each component's mass is formed once.
    #[inline]
    fn pick(&self, u: f32, a: f32, b: f32) -> Option<(usize, f32, f32)> {
        let n = self.n();
        let mut m = [0.0; LOBE1_MAX];
        let mut total = 0.0;
        let mut j = 0;
        while j < LOBE1_MAX && j < n {
            m[j] = self.mass_one(j, a, b, 0.0);
            total += self.weight[j] * m[j];
            j += 1;
        }
        if !(total > 0.0) || !total.is_finite() {
            return None;
        }
        let target = u * total;
        let mut acc = 0.0;
        let mut pick = 0;
        let mut pick_mass = 0.0;
        let mut below = 0.0;
        j = 0;
        while j < LOBE1_MAX && j < n {
            let wm = self.weight[j] * m[j];
            if wm > 0.0 {
                pick = j;
                pick_mass = wm;
                below = acc;
                if target < acc + wm {
                    break;
                }
            }
            acc += wm;
            j += 1;
        }
        if !(pick_mass > 0.0) || pick >= LOBE1_MAX {
            return None;
        }
        let v = math::clamp((target - below) / pick_mass, 0.0, 1.0);
        Some((pick, v, m[pick]))
    }

    /// Draws `x` from the mixture truncated to `[a, b]`: the component `j` with probability
    /// `w_j m_j / Σ w m` (from `u`, rescaled), then its truncated inverse CDF. `None` when
    /// the interval carries no mass.
    pub fn sample(&self, u: f32, a: f32, b: f32) -> Option<f32> {
        let (j, v, m) = self.pick(u, a, b)?;
        Some(math::clamp(self.sample_one(j, v, m, a, b), a, b))
    }

    /// [`Lobe1::sample`] with the sample's distances from both ends, `(x, x − a, b − x)`,
    /// each keeping its digits where it is small: `x` itself resolves an offset only to
    /// its own ulp, so the nearer end's offset is refined by Newton's method on the
    /// component's mass between that end and the sample (`v m` from `a`, `(1 − v) m` from
    /// `b`), as for a narrow interval, where it may have lost digits (`end_offset`). The
    /// disk lobes need them at the rim, where `wi.z` is the square root of their product.
    pub fn sample_ends(&self, u: f32, a: f32, b: f32) -> Option<(f32, f32, f32)> {
        let (j, v, m) = self.pick(u, a, b)?;
        let x = math::clamp(self.sample_one(j, v, m, a, b), a, b);
        let (mu, s) = (self.mu[j], self.scale[j]);
        let za = (a - mu) / s;
        let zb = (b - mu) / s;
        let d = (b - a) / s;
        let far = math::abs(x - mu);
        // Only the nearer end's distance can have lost digits: the other is at least half
        // the interval.
        let (off_a, off_b) = (x - a, b - x);
        let near_a = off_a <= off_b;
        let (z0, dir, off0, target) = if near_a {
            (za, 1.0, off_a, v * m)
        } else {
            (zb, -1.0, off_b, (1.0 - v) * m)
        };
        let near = self.end_offset(z0, dir, off0, far, s, target, d);
        Some(if near_a {
            (x, near, off_b)
        } else {
            (x, off_a, near)
        })
    }

    /// The offset from the standardised end `z0` inwards (`dir` +1 from the lower end, −1
    /// from the upper) holding the component mass `target`, from the plain offset `off0`
    /// of a sample `far` (`|s z|`) from its component's centre: refined by three Newton
    /// steps on `t = off/s` within a scale of the end (the density varies by less than a
    /// factor e there for the logistic and the Cauchy, and the Gaussian's mass is the
    /// narrow interval integral) and, for the logistic and the Cauchy, where the end is
    /// nearer the sample than a quarter of `far` (the sample `μ + s z` then carried the
    /// rounding of the larger `s z` into the offset, and the mass between end and sample
    /// is a tail's, which their [`Lobe1::std_mass`] keeps to its digits at any width);
    /// otherwise `off0`.
    #[inline]
    #[allow(clippy::too_many_arguments)]
    fn end_offset(
        &self,
        z0: f32,
        dir: f32,
        off0: f32,
        far: f32,
        s: f32,
        target: f32,
        d: f32,
    ) -> f32 {
        let t0 = off0 / s;
        let refine = t0 < 1.0 || (self.kind != Lobe1Kind::Gaussian && off0 < 0.25 * far);
        if !(refine || UNIFORM_CONTROL) {
            return off0;
        }
        let t = self.newton_offset(z0, dir, math::clamp(t0, 0.0, d), target, d);
        if refine { s * t } else { off0 }
    }

    /// Three Newton steps from `t` on the standardised offset `t ∈ [0, d]` from the end
    /// `z0` inwards (`dir` +1 from the lower end, −1 from the upper) at which the
    /// component's mass between the end and `z0 + dir t` is `target`; a non-finite step
    /// leaves `t` as it is.
    #[inline]
    fn newton_offset(&self, z0: f32, dir: f32, t: f32, target: f32, d: f32) -> f32 {
        let mut t = t;
        let mut k = 0;
        while k < 3 {
            let z1 = z0 + dir * t;
            let (lo, hi) = if dir > 0.0 { (z0, z1) } else { (z1, z0) };
            let step = (self.std_mass(lo, hi, t, 0.0) - target) / self.density_std(z1, 0.0);
            if step.is_finite() {
                t = math::clamp(t - step, 0.0, d);
            }
            k += 1;
        }
        t
    }

    /// Truncated inverse CDF of component `j` at `v ∈ [0, 1]`; `m` is the component's
    /// unweighted mass on `[a, b]`.
    #[inline]
    fn sample_one(&self, j: usize, v: f32, m: f32, a: f32, b: f32) -> f32 {
        if j >= LOBE1_MAX {
            return a;
        }
        let (mu, s) = (self.mu[j], self.scale[j]);
        let za = (a - mu) / s;
        let zb = (b - mu) / s;
        let d = (b - a) / s;
        // A narrow interval: Newton's method on the offset `t` from `a` (in units of s) for
        // `F(za + t) − F(za) = v m`, from the linear guess `t = v d`. The inversion below
        // would lose the digits of `m` to the difference of two nearly equal CDF values and
        // those of `x − a` to the rounding of `μ + s z`. Three steps: the density varies by
        // less than a factor e across the interval. On SPIR-V it runs for every interval
        // and the result is selected at the end ([`UNIFORM_CONTROL`]). Not for an interval
        // around the centre (`za < 0 < zb`): the inversion below forms `p − ½` from the
        // masses between the centre and each end, without cancellation, while a sample
        // near the centre as `a + s t` kept only the digits of `t`'s Newton residual, on
        // masses of the interval's size.
        let is_narrow = narrow(self.kind, za, zb, d) && !(za < 0.0 && zb > 0.0);
        let x_narrow = if is_narrow || UNIFORM_CONTROL {
            a + s * self.newton_offset(za, 1.0, v * d, v * m, d)
        } else {
            a
        };
        // An interval wholly right of the centre is read mirrored, in the left tail, where
        // the CDF is small and keeps its relative accuracy; the mirror swaps `v` and
        // `1 − v`, each kept exact where it is small (`vl` from the lower end, `vh` from
        // the upper).
        let flip = za >= 0.0;
        let w = 1.0 - v;
        let (lo, hi, vl, vh) = if flip {
            (-zb, -za, w, v)
        } else {
            (za, zb, v, w)
        };
        let f_lo = self.cdf_low(lo);
        // F(−|hi|): the CDF at the upper end on its small side.
        let f_hi_small = self.cdf_low(-math::abs(hi));
        // The interval's mass and 1 − F(hi), each without cancellation.
        let (width, tail_hi) = if hi > 0.0 {
            (1.0 - f_hi_small - f_lo, f_hi_small)
        } else {
            (f_hi_small - f_lo, 1.0 - f_hi_small)
        };
        let width = math::max(width, 0.0);
        let p = f_lo + vl * width;
        // `q = p − ½` without passing through ½ where the sample is near the centre
        // (`|p − ½| <` [`CENTRE_BAND`]): `q = vl (F(hi) − ½) − vh (½ − F(lo))` (as
        // `vl + vh = 1`), each end's centre mass by [`Lobe1::centre_mass`].
        let central = math::abs(p - 0.5) < CENTRE_BAND;
        let q = if central {
            let s_lo = self.centre_mass(lo, f_lo);
            let s_hi = math::sign(hi) * self.centre_mass(hi, f_hi_small);
            vl * s_hi - vh * s_lo
        } else {
            p - 0.5
        };
        let z = if q <= 0.0 {
            self.inv_low(p, q)
        } else {
            // 1 − p on its own small side.
            let pm = math::max(vh * width + tail_hi, 0.0);
            -self.inv_low(pm, if central { -q } else { pm - 0.5 })
        };
        let z = if flip { -z } else { z };
        if is_narrow { x_narrow } else { mu + s * z }
    }
}

/// Whether a branch holding a loop (the Gaussian interval integral, the Newton steps) is
/// evaluated for every input and its result selected: on SPIR-V, where such a branch taken
/// differently by neighbouring invocations returned wrong values on lavapipe (Mesa 22.3;
/// not needed on Mesa 25, ARCHITECTURE.md *Divergence*); on the CPU only where its result
/// is used.
const UNIFORM_CONTROL: bool = cfg!(target_arch = "spirv");

/// Whether the standardised interval `[za, zb]` of width `d` is narrow: every lobe's
/// log-density varies by less than 1 across it. The logistic's and the Cauchy's log-density
/// slopes are at most 1 (`d < 1`); the Gaussian's is `|z|` (`d (1 + |za| + |zb|) < 1`).
#[inline]
fn narrow(kind: Lobe1Kind, za: f32, zb: f32, d: f32) -> bool {
    match kind {
        Lobe1Kind::Gaussian => d * (1.0 + math::abs(za) + math::abs(zb)) < 1.0,
        Lobe1Kind::Logistic | Lobe1Kind::Cauchy => d < 1.0,
    }
}

/// The inverse CDF forms `q = p − ½` from the ends' centre masses where `|p − ½|` is below
/// this (there `p`'s rounding to ½'s ulp, 6e-8, is 1e-6 or more of `q`, and the sample's
/// relative error grows as `q` shrinks; above it the plain `p − ½` costs less than 1e-6),
/// and the logistic's inverse CDF is `ln1p(2q/(½ − q))` (an argument below ¼ in magnitude,
/// where [`math::ln1p`] is its series).
const CENTRE_BAND: f32 = 1.0 / 16.0;

/// [`Lobe1::pdf`] scales a Gaussian's terms only for an interval more than `√64 = 8`
/// scales from every centre. Nearer, its density `e^{−z²/2}` reaches f32's subnormals
/// (`e^{−87}`) only where it is below `e^{−55}` of its value at the interval's nearest end,
/// with less than that share of the interval's mass beyond (far below the 2⁻²⁴ an f32 `u`
/// resolves), and the interval costs no `exp(shift)`.
const PDF_SHIFT_FROM: f32 = 64.0;

/// 1/√(2π).
const FRAC_1_SQRT_TAU: f32 = 0.398_942_280_401_432_7;

/// `e^{shift} (1 − Φ(x)) = e^{shift} ½ erfc(x/√2)` for `x ≥ 0`: the Chebyshev-fitted `erfc`
/// of Numerical Recipes (`erfcc`, fractional error below 1.2e-7 everywhere), one `exp` and
/// no cancellation in the tail; `shift` is added to the exponent (`−x²/2 + …`), so that a
/// tail beyond f32's range is kept relative to `e^{−shift}` ([`Lobe1::pdf_shift`]).
#[inline]
fn gauss_tail(x: f32, shift: f32) -> f32 {
    let z = math::abs(x) * core::f32::consts::FRAC_1_SQRT_2;
    let t = 1.0 / (1.0 + 0.5 * z);
    let poly = -z * z - 1.265_512_2
        + t * (1.000_023_7
            + t * (0.374_091_96
                + t * (0.096_784_18
                    + t * (-0.186_288_06
                        + t * (0.278_868_07
                            + t * (-1.135_203_98
                                + t * (1.488_515_87 + t * (-0.822_152_23 + t * 0.170_872_77))))))));
    0.5 * t * math::exp(poly + shift)
}

/// `Φ⁻¹(p)` for `p ∈ (0, ½]`, given also `q = p − ½` to its own digits: P. J. Acklam's
/// rational approximation (relative error 1.15e-9; its central region, `p ≥ 0.02425`, in
/// `q`) refined by one Halley step on the residual `e = Φ(x) − p`, formed as
/// `½ erf(x/√2) − q` near the centre (`|x|/√2 < ½`: [`math::erf`]'s Taylor series; `q` then
/// keeps the digits that `p` near ½ has lost) and as [`gauss_tail`]`(−x) − p` elsewhere.
#[inline]
fn gauss_inv_low(p: f32, q: f32) -> f32 {
    if !(p > 0.0) {
        return -14.0;
    }
    let x = if p < 0.024_25 {
        let q = math::sqrt(-2.0 * math::ln(p));
        (((((-7.784_894e-3 * q - 3.223_964_6e-1) * q - 2.400_758_3) * q - 2.549_732_5) * q
            + 4.374_664_1)
            * q
            + 2.938_163_9)
            / ((((7.784_695_7e-3 * q + 3.224_671_3e-1) * q + 2.445_134_1) * q + 3.754_408_7) * q
                + 1.0)
    } else {
        let r = q * q;
        (((((-3.969_683e1 * r + 2.209_461e2) * r - 2.759_285_1e2) * r + 1.383_577_5e2) * r
            - 3.066_479_8e1)
            * r
            + 2.506_628_3)
            * q
            / (((((-5.447_61e1 * r + 1.615_858_4e2) * r - 1.556_989_8e2) * r + 6.680_131_2e1) * r
                - 1.328_068_2e1)
                * r
                + 1.0)
    };
    // Halley: u = e √(2π) e^{x²/2}.
    let x = math::min(x, 0.0);
    let h = x * core::f32::consts::FRAC_1_SQRT_2;
    let e = if h > -0.5 {
        0.5 * math::erf(h) - q
    } else {
        gauss_tail(-x, 0.0) - p
    };
    let u = e * math::exp(0.5 * x * x) / FRAC_1_SQRT_TAU;
    let step = u / (1.0 + 0.5 * x * u);
    if step.is_finite() { x - step } else { x }
}
