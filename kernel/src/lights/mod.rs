//! Area lights: the incoherent scratch response integrated over the solid angle of a
//! spherical or polygonal light in closed form (Velinov 2018 §3.4, Eqs. 19–41).
//!
//! | file | what |
//! |---|---|
//! | `band` | the across-scratch band integral `A(q1) − A(q0)` (Eq. 27), [`SiMode`] |
//! | `si_fast` | a cheap Si (|err| ≤ 6e-5) beside Eq. 29 and the exact one |
//! | `band_circle` | the band ξ₁ = 0 as a circle of directions; crossings with planes |
//! | `horizon` | clipping at the horizon |
//! | `sphere` | sphere cone (`asin` true, `atan` Eq. 31), its crossings (Eqs. 30–35) |
//! | `polygon` | spherical polygons, their crossings (Eqs. 36–41) |
//! | `integrate` | `Pod` records and [`light_integral`] |
//! | `method` | [`LightMethod`]: a scene material's band rule and Si |
//! | `limits` | capacities of the fixed-size lists |

pub mod band;
pub mod band_circle;
pub mod horizon;
pub mod integrate;
pub mod limits;
pub mod method;
pub mod polygon;
pub mod si_fast;
pub mod sphere;

pub use band::{SiMode, band_antiderivative, band_integral, band_integral_len};
pub use integrate::{
    BandRule, Light, LightKind, LightParams, LightQuery, LightRegion, MAX_LAMBDAS, light_integral,
    light_integral_footprint, light_integrals, light_integrals_in, light_may_reach,
};
pub use limits::{MAX_BREAKPOINTS, MAX_VERTICES};
pub use method::LightMethod;
pub use polygon::SphericalPolygon;
pub use si_fast::si_fast;
pub use sphere::{Cone, SphereCap};
