//! `"model": "auto"`: per hit and light, the cheapest model whose difference from Werner's
//! coherent model stays within the material's tolerance τ.
//!
//! Werner's coherent BRDF is `|B − Σ S_k|²` (Werner Eq. 15), Velinov's incoherent one
//! `(1 − ρc)|B|² + Σ |S_k|²` (Velinov Eq. 7); with a base of their own (`werner_blended`,
//! `velinov` with that base) `|Σ S_k|²` against `Σ |S_k|²`. They differ by the cross terms
//! `S_j S_k*` of scratches that share the coherence window and, without a base, by the
//! scratches' interference with the window's own response `B` (and `ρc|B|²`), which lives
//! within `|ξ| ≲ 1/(πσ)` of the mirror direction. The incoherent model is cheaper where it
//! matters: under an area light one closed-form integral (Velinov Eqs. 19–41) replaces a
//! 32–36 node quadrature, and its mirror term is exact where the quadrature cannot resolve
//! Werner's narrow base lobe. The closed form has errors of its own against the incoherent
//! model integrated over the light: it takes the exact depth phase `γi + γo` at the light's
//! centre, and separates a segment's `|η|²` in `ξ₁` like an infinite scratch's. The rules
//! ([`choose`]), each measured by `benches/src/bin/auto_calibration.rs` (`docs/auto.md`):
//!
//! 1. **Nothing within reach** (no scratch within 6σ, [`Reach::count`] = 0): both models
//!    are `|B|²`; incoherent (whose mirror term under an area light is exact), except where
//!    the mirror direction lies within `λ_max ξ_m` of an area light's edge (rule 2's angle):
//!    Werner's base lobe then straddles the edge, the closed form's mirror is a delta.
//! 2. **Near the mirror direction** (without a base): when a light's directions come within
//!    `λ_max ξ_m` of the mirror direction, `B(ξ_m)/B(0) = τ/2` ([`mirror_angle`], Werner
//!    Eq. 16), coherent.
//! 3. **One scratch**: when the second strongest scratch's window amplitude
//!    `W_k exp(−d_k²/2σ²)` ([`Reach`]) is at most [`SINGLE_RATIO`]`·τ` of the strongest's:
//!    incoherent under point and directional lights; under an area light only when no
//!    segment end lies within 6σ ([`Reach::nearest_end`]) and the light's half-angle is at
//!    most `min(τ/2, `[`CLOSED_FORM_MAX_ANGLE`]`)` radians (the closed form's own error grows
//!    with the light: up to 1 % at 0.01 rad, 16 % at 0.03 rad, measured).
//! 4. Otherwise coherent. Several scratches in the window are not averaged enough by the
//!    lights measured (random scratches at Velinov's benchmark density under a light of
//!    radius 0.1 rad: median 5 %, 99th percentile 37 % between the two models), so no rule
//!    trades them.
//!
//! Everything here is a few comparisons and one walk over the scratches in reach without
//! evaluating any of them.

use super::area::SceneLight;
use super::shading::{self, BaseKind, SceneModel, ShadeMaterial};
use super::surface::SurfacePoint;
use crate::bsdf::Lookup;
use crate::footprint::Ellipse;
use crate::lights::{LightKind, LightRegion};
use crate::math;
use crate::scratch::response::CUTOFF_SIGMAS;
use crate::scratch::{EtaMode, NearCursor, ScratchSet};
use crate::table::Model;
use glam::{Vec2, Vec3};

gpu_enum! {
    /// The model an `auto` material uses for one hit and light.
    pub enum Choice {
        /// Werner's coherent sum (Werner Eq. 15; `werner_blended` with a base).
        Coherent = 0,
        /// Velinov's incoherent sum (Velinov Eq. 7), its closed form under area lights.
        Incoherent = 1,
    }
    fallback = Coherent;
}

/// The largest half-angle (radians) of an area light under which rule 3 takes the
/// closed form (`docs/auto.md`).
pub const CLOSED_FORM_MAX_ANGLE: f32 = 0.01;

/// Rule 3's "one scratch": the second strongest amplitude is at most `SINGLE_RATIO·τ` of
/// the strongest (a weaker scratch can sit at a peak of its response where the strongest
/// is near a zero: measured differences up to 7.4× the amplitude ratio, `docs/auto.md`).
pub const SINGLE_RATIO: f32 = 1.0 / 16.0;

/// The scratches within reach of a shading point: how many, and the two largest window
/// amplitudes `W_k exp(−d_k²/2σ²)` (µm; `d_k` the distance from the point, less the
/// footprint's larger semi-axis).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Reach {
    /// Scratches within `6σ` (plus the footprint's semi-axis).
    pub count: u32,
    /// The largest amplitude.
    pub strongest: f32,
    /// The second largest.
    pub second: f32,
    /// The distance from the point to the nearest segment end among them, less the
    /// footprint's semi-axis, in units of σ (∞ without scratches).
    pub nearest_end: f32,
}

/// One walk over the scratches within `6σ` of `x0` (grown by the footprint's larger
/// semi-axis `fp.a1`, 0 without one).
pub fn reach<S: ScratchSet>(set: &S, x0: Vec2, sigma: f32, fp: &Ellipse) -> Reach {
    let grow = math::max(math::max(fp.a1, fp.a2), 0.0);
    let mut out = Reach {
        nearest_end: f32::INFINITY,
        ..Reach::default()
    };
    let mut cursor = NearCursor::default();
    while let Some(s) = set.next_near(&mut cursor, x0, CUTOFF_SIGMAS * sigma + grow) {
        let d = math::max(s.distance_to(x0) - grow, 0.0) / sigma;
        let (a, b) = s.endpoints();
        let end = math::min(
            Vec2::from_array(a).distance(x0),
            Vec2::from_array(b).distance(x0),
        );
        out.nearest_end = math::min(out.nearest_end, math::max(end - grow, 0.0) / sigma);
        let a = s.width * math::exp(-0.5 * d * d);
        out.count += 1;
        if a > out.strongest {
            out.second = out.strongest;
            out.strongest = a;
        } else if a > out.second {
            out.second = a;
        }
    }
    out
}

/// The reach of a hit for the lights' choices: [`reach`] at the hit's scratch-space
/// position and footprint for an `auto` material, empty (unused) for any other. Computed
/// once per hit: it does not depend on the light.
pub fn hit_reach<S: ScratchSet>(
    m: &ShadeMaterial,
    lk: &Lookup<'_, S>,
    x_um: Vec2,
    fp: &Ellipse,
) -> Reach {
    if SceneModel::from_u32(m.model) == SceneModel::Auto {
        reach(&lk.scratches, x_um, m.table.sigma_um, fp)
    } else {
        Reach::default()
    }
}

/// The record of Werner's coherent model with the same scratches, reflectance, depth phase
/// and base: `werner` without a base, `werner_blended` with one.
pub fn coherent(m: &ShadeMaterial) -> ShadeMaterial {
    let mut c = *m;
    let blended = BaseKind::from_u32(m.base) != BaseKind::None;
    c.model = if blended {
        SceneModel::WernerBlended as u32
    } else {
        SceneModel::Werner as u32
    };
    c.table.model = if blended {
        Model::WernerBlended as u32
    } else {
        Model::Werner as u32
    };
    c.table.eta = EtaMode::Finite as u32;
    c.table.base_gaussian = 0;
    c.tolerance = 0.0;
    c
}

/// The record of Velinov's incoherent model with the same scratches, reflectance, depth
/// phase and base; without a base, Velinov's Gaussian base `(1 − ρc)|B|²` (Velinov Eq. 7),
/// the incoherent counterpart of Werner's `B`.
pub fn incoherent(m: &ShadeMaterial) -> ShadeMaterial {
    let mut c = *m;
    c.model = SceneModel::Velinov as u32;
    c.table.model = Model::Velinov as u32;
    c.table.eta = EtaMode::Finite as u32;
    c.table.base_gaussian = if BaseKind::from_u32(m.base) == BaseKind::None {
        1
    } else {
        0
    };
    c.tolerance = 0.0;
    c
}

/// The record `choice` stands for.
#[inline]
pub fn resolve(m: &ShadeMaterial, choice: Choice) -> ShadeMaterial {
    if choice == Choice::Incoherent {
        incoherent(m)
    } else {
        coherent(m)
    }
}

/// `λ ξ_m / λ`: the angle (radians, as `|Δ(wi)_xy|`) from the mirror direction within which
/// the window's response `B` (Werner Eq. 16) is above `τ/2` of its peak, per µm of
/// wavelength: `ξ_m = √(ln(2/τ)/2)/(πσ)`.
#[inline]
pub fn mirror_angle(sigma_um: f32, tolerance: f32, lambda_max_um: f32) -> f32 {
    let t = math::clamp(tolerance, 1.0e-6, 1.0);
    lambda_max_um * math::sqrt(0.5 * math::ln(2.0 / t)) / (math::PI * sigma_um)
}

/// The cone containing a light's region (shading frame): its axis and half-angle (a
/// sphere's cap, or a polygon's vertex mean and its largest angle to a vertex).
pub fn light_cone(region: &LightRegion) -> (Vec3, f32) {
    if LightKind::from_u32(region.kind) == LightKind::Polygon {
        (region.polygon.center, region.polygon.half_angle())
    } else {
        (region.sphere.axis, region.sphere.alpha)
    }
}

/// The model of an `auto` material `m` for one light at the hit `sp` seen from `wo`
/// (shading frame), given the scratches in `reach` and the frame's longest wavelength
/// `lambda_max_nm` (rules 1–4 of the module).
pub fn choose(
    m: &ShadeMaterial,
    sp: &SurfacePoint,
    wo: Vec3,
    light: &SceneLight,
    reach: &Reach,
    lambda_max_nm: f32,
) -> Choice {
    let tol = m.tolerance;
    let sigma = m.table.sigma_um;
    let lambda_um = lambda_max_nm * 1.0e-3;
    let no_base = BaseKind::from_u32(m.base) == BaseKind::None;
    let wm = Vec3::new(-wo.x, -wo.y, wo.z);
    let near_mirror_limit = mirror_angle(sigma, tol, lambda_um);
    let single = reach.second <= SINGLE_RATIO * tol * reach.strongest;
    if shading::is_delta(light) {
        let Some((dir, _, _)) = shading::delta_direction(light, sp.position) else {
            return Choice::Incoherent;
        };
        let wi = sp.to_local(dir);
        let near_mirror = Vec2::new(wi.x + wo.x, wi.y + wo.y).length() < near_mirror_limit;
        return if reach.count == 0 || (single && !(no_base && near_mirror)) {
            Choice::Incoherent
        } else {
            Choice::Coherent
        };
    }
    // Degenerate or wholly below the horizon: nothing is shaded; the coherent model.
    let Some(region) = LightRegion::new(&shading::local_light(sp, light)) else {
        return Choice::Coherent;
    };
    let (axis, half) = light_cone(&region);
    // How far the mirror direction lies outside the light's cone (negative inside).
    let gap = math::angle_between(axis, wm) - half;
    if no_base && math::abs(gap) < near_mirror_limit {
        // Werner's base lobe straddles the light's edge; the closed form's mirror is a delta.
        return Choice::Coherent;
    }
    if reach.count == 0 {
        return Choice::Incoherent;
    }
    if no_base && gap < near_mirror_limit {
        return Choice::Coherent;
    }
    let closed_form_fits =
        reach.nearest_end >= CUTOFF_SIGMAS && half <= math::min(0.5 * tol, CLOSED_FORM_MAX_ANGLE);
    if single && closed_form_fits {
        Choice::Incoherent
    } else {
        Choice::Coherent
    }
}
