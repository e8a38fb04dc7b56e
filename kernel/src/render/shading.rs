//! Per-hit shading: the BRDF of a scene material and the radiance each light kind sends
//! towards the viewer. Directions are in the shading frame (`z` = normal), `wo` towards the
//! viewer, `wi` towards the light.
//!
//! * The BRDF is the material interface's [`bsdf::eval()`] (one scratch walk for up to four
//!   wavelengths); the `table` command's [`crate::table::evaluate`] is its point values at
//!   one wavelength. GHS is [`ghs::brdf`].
//! * `werner_blended` and `velinov` with a GHS base add `(1 − ρc)·f_base` (Werner 2017 §5;
//!   Velinov 2018 Eq. 7's `(1 − ρc)` weight), ρc from [`scratch_area_density`].
//! * Point light: `f·max(cos θi, 0)·I/d²`; directional: `f·max(cos θi, 0)·E`.
//! * Area lights for `velinov`: Velinov's closed form ([`light_integrals_in`], Eqs. 19–41)
//!   times the radiance and the visible fraction of the light; a smooth base (or Velinov's
//!   Gaussian base, whose lobe integrates to a mirror) adds `(1 − ρc)·F·L` when the mirror
//!   direction of `wo` lies in the light. Every other model and a GHS base use the
//!   quadrature of [`super::area`].

use super::area::{AreaNode, SceneLight, SceneLightKind};
use super::footprint::footprint_density;
use super::surface::SurfacePoint;
use crate::bsdf::{self, BsdfMaterial, Lookup, ShadingPoint, Spectrum, Wavelengths};
use crate::footprint::Ellipse;
use crate::ghs::{self, GhsParams};
use crate::lights::{
    Cone, Light, LightMethod, LightParams, LightRegion, MAX_LAMBDAS, light_integrals_in,
    light_may_reach,
};
use crate::material::Material;
use crate::math;
use crate::scratch::{Crossings, ScratchSet, Window, scratch_area_density};
use crate::table::TableParams;
use crate::units::direction;
use bytemuck::{Pod, Zeroable};
use glam::{Vec2, Vec3};

gpu_enum! {
    /// The model of a [`ShadeMaterial`].
    pub enum SceneModel {
        /// Werner 2017 Eq. 15 (coherent base + scratches).
        Werner = 0,
        /// Werner 2017 §5: coherent scratches + `(1 − ρc)` base.
        WernerBlended = 1,
        /// Velinov 2018 Eq. 7 (incoherent) + `(1 − ρc)` base.
        Velinov = 2,
        /// Holzschuch & Pacanowski's two-scale BRDF alone.
        Ghs = 3,
        /// Werner's coherent model where the scratches interfere, Velinov's incoherent sum
        /// (and its closed form under area lights) elsewhere, chosen per hit and light
        /// within [`ShadeMaterial::tolerance`] ([`super::model_choice`]).
        Auto = 4,
    }
    fallback = Werner;
}

gpu_enum! {
    /// The base added with weight `(1 − ρc)` to `werner_blended` and `velinov`.
    pub enum BaseKind {
        /// No base.
        None = 0,
        /// A smooth mirror of the material's reflectance (a delta: only area lights whose
        /// solid angle contains the mirror direction are reflected).
        Smooth = 1,
        /// A GHS surface ([`ShadeMaterial::ghs`]).
        Ghs = 2,
    }
    fallback = None;
}

/// One scene material. GPU-visible: 128 bytes.
#[repr(C)]
#[derive(Clone, Copy, Debug, Default, PartialEq, Pod, Zeroable)]
pub struct ShadeMaterial {
    /// Model options exactly as a table spec gives them (`model` is the table model for
    /// the scratch models).
    pub table: TableParams,
    /// The scratch models' reflectance.
    pub material: Material,
    /// GHS parameters: the material of model `ghs`, or the base of [`BaseKind::Ghs`].
    pub ghs: GhsParams,
    /// A [`SceneModel`] as `u32`.
    pub model: u32,
    /// A [`BaseKind`] as `u32`.
    pub base: u32,
    /// [`SceneModel::Auto`]: the relative error the model choice may add (0 otherwise).
    pub tolerance: f32,
    /// A [`LightMethod`] as `u32`: how the incoherent model integrates area lights
    /// (`velinov`, and `auto` where it chooses the incoherent model).
    pub light_method: u32,
}

const _: () = assert!(core::mem::size_of::<ShadeMaterial>() == 128);

/// `1 − ρc` at `x` (≥ 0), the base weight.
#[inline]
pub fn base_weight<S: ScratchSet>(m: &ShadeMaterial, x: Vec2, set: &S) -> f32 {
    math::max(
        1.0 - scratch_area_density(
            set,
            x,
            m.table.sigma_um,
            Window::from_u32(m.table.window),
            Crossings::from_u32(m.table.crossings),
        ),
        0.0,
    )
}

/// The material's BRDF (1/sr, no cosine) for shading-frame `wi`, `wo` at scratch-space
/// `x` (µm) and λ (nm), the base included: [`brdf_spectrum`] at one wavelength.
pub fn brdf<S: ScratchSet>(
    m: &ShadeMaterial,
    wi: Vec3,
    wo: Vec3,
    x: Vec2,
    lambda_nm: f32,
    set: &S,
) -> f32 {
    brdf_footprint(m, wi, wo, x, &Ellipse::default(), lambda_nm, set)
}

/// [`brdf`], or with a footprint (`fp.a1 > 0`) Velinov's model averaged over it (Velinov
/// §4; a GHS base is weighted by `1 − ρc` at the footprint centre). The coherent models and
/// GHS are point-sampled at the centre.
pub fn brdf_footprint<S: ScratchSet>(
    m: &ShadeMaterial,
    wi: Vec3,
    wo: Vec3,
    x: Vec2,
    fp: &Ellipse,
    lambda_nm: f32,
    set: &S,
) -> f32 {
    brdf_spectrum(
        m,
        wi,
        wo,
        &shading_point(x, fp),
        &Wavelengths::single(lambda_nm),
        &Lookup::new(set),
    )
    .v[0]
}

/// The material interface's view of a scratch-space position and an optional footprint
/// (`fp.a1 = 0`: none).
#[inline]
pub fn shading_point(x: Vec2, fp: &Ellipse) -> ShadingPoint {
    if fp.a1 > 0.0 {
        ShadingPoint::with_footprint(x.to_array(), *fp)
    } else {
        ShadingPoint::at(x.to_array())
    }
}

/// The scene material's BRDF at every wavelength of `wl` in one scratch walk: the material
/// interface's [`bsdf::eval()`] of [`BsdfMaterial::from_shade`].
pub fn brdf_spectrum<S: ScratchSet>(
    m: &ShadeMaterial,
    wi: Vec3,
    wo: Vec3,
    sp: &ShadingPoint,
    wl: &Wavelengths,
    lk: &Lookup<'_, S>,
) -> Spectrum {
    bsdf::eval(&BsdfMaterial::from_shade(m), sp, wi, wo, wl, lk)
}

/// Where a point or directional light is seen from `p`: the unit direction towards it
/// (world frame), the shadow ray's extent (infinite for a directional light) and the
/// irradiance scale (`I/d²` or `E`); `None` for a point light at `p` or any other kind.
pub fn delta_direction(light: &SceneLight, p: Vec3) -> Option<(Vec3, f32, f32)> {
    let p0 = Vec3::new(light.p0[0], light.p0[1], light.p0[2]);
    match SceneLightKind::from_u32(light.kind) {
        SceneLightKind::Directional => {
            Some((p0.normalize_or_zero(), f32::INFINITY, light.emission))
        }
        SceneLightKind::Point => {
            let d = p0 - p;
            let d2 = d.length_squared();
            if !(d2 > 0.0) {
                return None;
            }
            let dist = math::sqrt(d2);
            Some((d / dist, dist, light.emission / d2))
        }
        _ => None,
    }
}

/// Whether `light` is a point or directional light.
#[inline]
pub fn is_delta(light: &SceneLight) -> bool {
    matches!(
        SceneLightKind::from_u32(light.kind),
        SceneLightKind::Point | SceneLightKind::Directional
    )
}

/// Radiance towards `wo` from a point light (`light.kind` Point) or a directional light,
/// unoccluded, at every wavelength of `wl` (one scratch walk): `f·max(cos θi, 0)·I/d²` or
/// `f·max(cos θi, 0)·E`; `fp` is the pixel footprint ([`brdf_footprint`]; `a1 = 0` for the
/// point model).
pub fn delta_light_spectrum<S: ScratchSet>(
    m: &ShadeMaterial,
    sp: &SurfacePoint,
    wo: Vec3,
    light: &SceneLight,
    wl: &Wavelengths,
    lk: &Lookup<'_, S>,
    fp: &Ellipse,
) -> Spectrum {
    let Some((wi_world, _, scale)) = delta_direction(light, sp.position) else {
        return Spectrum::ZERO;
    };
    let wi = sp.to_local(wi_world);
    if !(wi.z > 0.0) {
        return Spectrum::ZERO;
    }
    let mut f = brdf_spectrum(m, wi, wo, &shading_point(sp.x_um, fp), wl, lk);
    let mut j = 0;
    while j < MAX_LAMBDAS {
        f.v[j] = f.v[j] * wi.z * scale;
        j += 1;
    }
    f
}

/// One quadrature node's radiance towards `wo` at every wavelength of `wl` (one scratch
/// walk): `f·max(cos θi, 0)·L·dω` (the shadow ray is the caller's).
pub fn area_node_radiance_spectrum<S: ScratchSet>(
    m: &ShadeMaterial,
    sp: &SurfacePoint,
    wo: Vec3,
    node: &AreaNode,
    radiance: f32,
    wl: &Wavelengths,
    lk: &Lookup<'_, S>,
) -> Spectrum {
    let wi = sp.to_local(node.dir);
    if !(wi.z > 0.0) {
        return Spectrum::ZERO;
    }
    let mut f = brdf_spectrum(m, wi, wo, &ShadingPoint::at(sp.x_um.to_array()), wl, lk);
    let mut j = 0;
    while j < MAX_LAMBDAS {
        f.v[j] = f.v[j] * wi.z * radiance * node.weight;
        j += 1;
    }
    f
}

/// Whether `m` integrates area lights in closed form ([`velinov_area_light`]) rather than
/// by quadrature ([`area_node_radiance_spectrum`]).
#[inline]
pub fn closed_form_area(m: &ShadeMaterial) -> bool {
    SceneModel::from_u32(m.model) == SceneModel::Velinov
}

/// Whether `m` needs the per-node quadrature under an area light: every model but
/// `velinov`, and `velinov` with a GHS base ([`base_node_radiance`]); otherwise only the
/// light's visible fraction is needed.
#[inline]
pub fn needs_area_nodes(m: &ShadeMaterial) -> bool {
    !closed_form_area(m) || BaseKind::from_u32(m.base) == BaseKind::Ghs
}

/// The kernel light record of a sphere or triangle light relative to the shading point, in
/// the shading frame.
pub fn local_light(sp: &SurfacePoint, light: &SceneLight) -> Light {
    let rel = |p: [f32; 4]| {
        sp.to_local(Vec3::new(p[0], p[1], p[2]) - sp.position)
            .to_array()
    };
    if SceneLightKind::from_u32(light.kind) == SceneLightKind::Sphere {
        Light::sphere(rel(light.p0), light.p0[3], Cone::Asin)
    } else {
        let mut l = Light::sphere([0.0; 3], 0.0, Cone::Asin);
        l.kind = crate::lights::LightKind::Polygon as u32;
        l.count = 3;
        let (a, b, c) = (rel(light.p0), rel(light.p1), rel(light.p2));
        l.vertices[0] = [a[0], a[1], a[2], 0.0];
        l.vertices[1] = [b[0], b[1], b[2], 0.0];
        l.vertices[2] = [c[0], c[1], c[2], 0.0];
        l
    }
}

/// Velinov's model under a sphere or triangle light, unoccluded, at the first `count` of
/// `lambdas_nm` (one scratch walk): the closed-form scratch integral ([`light_integrals_in`],
/// Velinov Eqs. 19–41, band rule and Si from [`ShadeMaterial::light_method`]) times the
/// radiance, plus the mirror part of a smooth or Gaussian base (the same at every
/// wavelength). With a footprint
/// (`fp.a1 > 0`, centred on the shading point) each scratch's spatial factor is averaged
/// over it (Velinov §4) and the mirror base is weighted by `1 − ρ_P`
/// ([`footprint_density`], Velinov Eq. 18); `fp.a1 = 0` is the point model. A GHS base is
/// added by the caller through [`base_node_radiance`].
pub fn velinov_area_light<S: ScratchSet>(
    m: &ShadeMaterial,
    sp: &SurfacePoint,
    wo: Vec3,
    light: &SceneLight,
    lambdas_nm: &[f32; MAX_LAMBDAS],
    count: usize,
    lk: &Lookup<'_, S>,
    fp: &Ellipse,
) -> [f32; MAX_LAMBDAS] {
    let set = &lk.scratches;
    let kl = local_light(sp, light);
    let Some(region) = LightRegion::new(&kl) else {
        return [0.0; MAX_LAMBDAS];
    };
    let mut l = light_integrals_in(
        &velinov_light_params(m),
        &region,
        wo.to_array(),
        sp.x_um.to_array(),
        &m.material,
        lambdas_nm,
        count,
        fp,
        set,
    );
    let mirror = mirror_weight_in_region(m, sp, wo, &region, fp, set);
    let mut k = 0;
    while k < count && k < MAX_LAMBDAS {
        if mirror > 0.0 {
            l[k] += mirror * mirror_reflectance(m, wo, lambdas_nm[k]);
        }
        l[k] *= light.emission;
        k += 1;
    }
    l
}

/// The closed form's options for the material `m` ([`ShadeMaterial::light_method`]).
#[inline]
fn velinov_light_params(m: &ShadeMaterial) -> LightParams {
    let method = LightMethod::from_u32(m.light_method);
    LightParams {
        sigma_um: m.table.sigma_um,
        eta: m.table.eta,
        depth_term: m.table.depth_term,
        si_mode: method.si_mode() as u32,
        bands: method.band_rule() as u32,
        pad: [0; 3],
    }
}

/// Whether `light` sends nothing towards `wo` at this hit whatever its visibility, so that
/// a renderer needs no shadow ray for it: `m` is `velinov` without a GHS base (the closed
/// form times the visible fraction, no per-node part), the light is a sphere or triangle,
/// no scratch within reach has a band that may meet it up to `lambda_max_nm`
/// ([`light_may_reach`]), and the mirror direction of `wo` misses it (or there is no mirror
/// base). Then [`velinov_area_light`] is exactly 0 at every wavelength up to
/// `lambda_max_nm`. `false` whenever that is not certain (every other model, `auto`).
#[allow(clippy::too_many_arguments)]
pub fn area_light_is_dark<S: ScratchSet>(
    m: &ShadeMaterial,
    sp: &SurfacePoint,
    wo: Vec3,
    light: &SceneLight,
    lk: &Lookup<'_, S>,
    fp: &Ellipse,
    lambda_max_nm: f32,
) -> bool {
    if needs_area_nodes(m) || is_delta(light) {
        return false;
    }
    let Some(region) = LightRegion::new(&local_light(sp, light)) else {
        return true;
    };
    !mirror_in_region(m, wo, &region)
        && !light_may_reach(
            &velinov_light_params(m),
            &region,
            wo.to_array(),
            sp.x_um.to_array(),
            lambda_max_nm,
            fp,
            &lk.scratches,
        )
}

/// `F(wm, wo)` at `lambda_nm`, `wm` the mirror direction of `wo`: the reflectance of a
/// smooth (or Gaussian) base's mirror image.
#[inline]
pub fn mirror_reflectance(m: &ShadeMaterial, wo: Vec3, lambda_nm: f32) -> f32 {
    m.material
        .reflectance(Vec3::new(-wo.x, -wo.y, wo.z), wo, lambda_nm)
}

/// The weight of the mirror part of a smooth base (or of Velinov's Gaussian base, a mirror
/// at light scale) inside a light's `region`, per unit radiance and reflectance: `1 − ρ`
/// when the mirror direction `wm` of `wo` lies in the light, else 0 (Werner §5, Velinov
/// Eq. 7; the caller multiplies by [`mirror_reflectance`] per wavelength). `ρ` is the
/// scratch density at the point, or averaged over the footprint `fp` when it has one
/// (Velinov Eq. 18).
fn mirror_weight_in_region<S: ScratchSet>(
    m: &ShadeMaterial,
    sp: &SurfacePoint,
    wo: Vec3,
    region: &LightRegion,
    fp: &Ellipse,
    set: &S,
) -> f32 {
    if !mirror_in_region(m, wo, region) {
        return 0.0;
    }
    if fp.a1 > 0.0 && fp.a2 > 0.0 {
        math::max(1.0 - footprint_density(m.table.sigma_um, fp, set), 0.0)
    } else {
        base_weight(m, sp.x_um, set)
    }
}

/// Whether `m` has a mirror base (smooth, or Velinov's Gaussian base) and the mirror
/// direction of `wo` lies in `region`.
#[inline]
fn mirror_in_region(m: &ShadeMaterial, wo: Vec3, region: &LightRegion) -> bool {
    let mirror_base = BaseKind::from_u32(m.base) == BaseKind::Smooth || m.table.base_gaussian == 1;
    let wm = Vec3::new(-wo.x, -wo.y, wo.z);
    mirror_base && wm.z > 0.0 && region.contains(wm)
}

/// The weight of the mirror part of a smooth base under a sphere or triangle light for the
/// models the renderer integrates by quadrature (`werner_blended`): `1 − ρc` when the mirror
/// direction lies in the light, else 0; the radiance is this times
/// [`mirror_reflectance`] and the light's radiance, unoccluded (a delta base cannot be
/// integrated over nodes; [`velinov_area_light`] adds it for `velinov`).
pub fn area_mirror_weight<S: ScratchSet>(
    m: &ShadeMaterial,
    sp: &SurfacePoint,
    wo: Vec3,
    light: &SceneLight,
    lk: &Lookup<'_, S>,
    fp: &Ellipse,
) -> f32 {
    if BaseKind::from_u32(m.base) != BaseKind::Smooth {
        return 0.0;
    }
    match LightRegion::new(&local_light(sp, light)) {
        Some(region) => mirror_weight_in_region(m, sp, wo, &region, fp, &lk.scratches),
        None => 0.0,
    }
}

/// A GHS base's share of one quadrature node for Velinov's model under an area light:
/// `(1 − ρc)·f_ghs·cos θi·L·dω` (0 without a GHS base).
pub fn base_node_radiance<S: ScratchSet>(
    m: &ShadeMaterial,
    sp: &SurfacePoint,
    wo: Vec3,
    node: &AreaNode,
    radiance: f32,
    lambda_nm: f32,
    lk: &Lookup<'_, S>,
) -> f32 {
    if BaseKind::from_u32(m.base) != BaseKind::Ghs {
        return 0.0;
    }
    let wi = sp.to_local(node.dir);
    if !(wi.z > 0.0) {
        return 0.0;
    }
    let g = ghs::brdf(
        &m.ghs,
        lk.g1,
        direction(wi.to_array()),
        direction(wo.to_array()),
        lambda_nm,
    );
    base_weight(m, sp.x_um, &lk.scratches) * g * wi.z * radiance * node.weight
}

/// The shadow ray from `p` (offset along the geometric normal `ng` to the side of `dir`)
/// towards a point at distance `dist` along unit `dir`, stopping short of it by the same
/// relative margin.
pub fn shadow_ray(p: Vec3, ng: Vec3, dir: Vec3, dist: f32) -> crate::ray::Ray {
    let scale = math::max(
        math::max(math::abs(p.x), math::abs(p.y)),
        math::max(math::abs(p.z), dist),
    );
    let eps = SHADOW_EPSILON * math::max(scale, 1.0);
    let n = ng.normalize_or_zero();
    let side = if n.dot(dir) >= 0.0 { 1.0 } else { -1.0 };
    let o = p + n * (side * eps);
    crate::ray::Ray::new(o.to_array(), dir.to_array()).with_interval(0.0, dist - 2.0 * eps)
}

/// Relative offset of shadow-ray origins from the surface (and of their end from the light).
pub const SHADOW_EPSILON: f32 = 1.0e-4;
