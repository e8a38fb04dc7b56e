//! The area-light method of a scene material: which band rule and which sine integral the
//! incoherent model's closed form uses ([`super::integrate`]), so a scene can trade the
//! paper's cheapest form (Velinov 2018 Eq. 27 with its Eq. 29 Si) against the extent rule.

use super::band::SiMode;
use super::integrate::BandRule;

gpu_enum! {
    /// How a material's area lights are integrated under the incoherent model
    /// (`"light_integral"` of a scene material).
    pub enum LightMethod {
        /// Bands over the light's own ξ₁ range ([`BandRule::Extent`]), exact Si: the default.
        Extent = 0,
        /// Velinov Eq. 27: one band at ξ₁ = 0 ([`BandRule::Single`]), exact Si.
        Eq27 = 1,
        /// Velinov Eq. 27 with the paper's Si approximation, Eq. 29 ([`SiMode::Velinov`]).
        Eq27Eq29 = 2,
        /// 3-point Gauss–Hermite bands ([`BandRule::Hermite3`]), exact Si.
        Hermite3 = 3,
        /// 5-point Gauss–Hermite bands ([`BandRule::Hermite5`]), exact Si.
        Hermite5 = 5,
    }
    fallback = Extent;
}

impl LightMethod {
    /// The band rule across ξ₁.
    #[inline]
    pub fn band_rule(self) -> BandRule {
        match self {
            LightMethod::Extent => BandRule::Extent,
            LightMethod::Eq27 | LightMethod::Eq27Eq29 => BandRule::Single,
            LightMethod::Hermite3 => BandRule::Hermite3,
            LightMethod::Hermite5 => BandRule::Hermite5,
        }
    }

    /// The sine integral of the band integral.
    #[inline]
    pub fn si_mode(self) -> SiMode {
        if self == LightMethod::Eq27Eq29 {
            SiMode::Velinov
        } else {
            SiMode::Exact
        }
    }
}
