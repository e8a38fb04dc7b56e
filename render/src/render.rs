//! The tile loop: primary rays per 8×8 tile (rayon over tiles), closest hits through any
//! [`RayQueries`], shadow rays through the same structure, shading by kernel functions
//! only ([`scratchwave_kernel::render`]).

use crate::prepare::Prepared;
use crate::scene::Scene;
use crate::scene::{Footprint, Shadows};
use rayon::prelude::*;
use scratchwave_host::{Coherence, RayQueries};
use scratchwave_kernel::bsdf::Wavelengths;
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::glam::Vec3;
use scratchwave_kernel::lights::MAX_LAMBDAS;
use scratchwave_kernel::ray::{Hit, Ray};
use scratchwave_kernel::render::area::{self, SceneLight, SceneLightKind};
use scratchwave_kernel::render::camera::Camera;
use scratchwave_kernel::render::camera::RayDifferential;
use scratchwave_kernel::render::footprint::footprint_ellipse;
use scratchwave_kernel::render::pixel::sample_offset;
use scratchwave_kernel::render::shading::{self, ShadeMaterial};
use scratchwave_kernel::render::spectrum::{self, SpectrumMode};
use scratchwave_kernel::render::surface::{
    SurfaceKind, SurfacePoint, hit_position, mesh_point, surface_point,
};
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::Instant;

/// Tile edge (pixels).
pub const TILE: u32 = 8;

/// A linear RGB image, rows from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    /// Width (pixels).
    pub width: u32,
    /// Height (pixels).
    pub height: u32,
    /// `width·height` linear RGB values, row-major from the top-left pixel.
    pub rgb: Vec<[f32; 3]>,
}

/// Counts and time of one render.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RenderStats {
    /// Primary rays traced.
    pub primary_rays: u64,
    /// Shadow rays traced.
    pub shadow_rays: u64,
    /// Kernel shading evaluations (BRDF × light, per node and wavelength; one per closed-form
    /// area-light integral).
    pub shading_evaluations: u64,
    /// Wall time of the tile loop (s).
    pub seconds: f64,
}

impl RenderStats {
    /// Million rays (primary + shadow) per second.
    pub fn mrays_per_s(&self) -> f64 {
        (self.primary_rays + self.shadow_rays) as f64 / self.seconds.max(1e-9) / 1e6
    }
}

struct Counters {
    shadow: AtomicU64,
    shading: AtomicU64,
}

/// Renders `scene` (prepared as `prep`) with `queries` for primary and shadow rays.
/// `progress(done_tiles, total_tiles)` is called from worker threads as tiles finish.
pub fn render<Q: RayQueries + ?Sized>(
    scene: &Scene,
    prep: &Prepared,
    queries: &Q,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> (Image, RenderStats) {
    let cam = scene.camera;
    let (w, h) = (cam.width_px, cam.height_px);
    let tiles_x = w.div_ceil(TILE);
    let tiles_y = h.div_ceil(TILE);
    let total = (tiles_x * tiles_y) as usize;
    let counters = Counters {
        shadow: AtomicU64::new(0),
        shading: AtomicU64::new(0),
    };
    let done = AtomicU64::new(0);
    let start = Instant::now();
    let tiles: Vec<(u32, Vec<[f32; 3]>)> = (0..total as u32)
        .into_par_iter()
        .map(|tile| {
            let out = render_tile(
                scene,
                prep,
                queries,
                &cam,
                tile % tiles_x,
                tile / tiles_x,
                &counters,
            );
            let d = done.fetch_add(1, Ordering::Relaxed) as usize + 1;
            progress(d, total);
            (tile, out)
        })
        .collect();
    let seconds = start.elapsed().as_secs_f64();
    let mut rgb = vec![[0.0f32; 3]; (w as usize) * (h as usize)];
    for (tile, px) in tiles {
        let (tx, ty) = (tile % tiles_x, tile / tiles_x);
        let mut k = 0;
        for j in ty * TILE..((ty + 1) * TILE).min(h) {
            for i in tx * TILE..((tx + 1) * TILE).min(w) {
                rgb[(j * w + i) as usize] = px[k];
                k += 1;
            }
        }
    }
    let spp = u64::from(scene.settings.spp.max(1));
    let stats = RenderStats {
        primary_rays: u64::from(w) * u64::from(h) * spp,
        shadow_rays: counters.shadow.into_inner(),
        shading_evaluations: counters.shading.into_inner(),
        seconds,
    };
    (
        Image {
            width: w,
            height: h,
            rgb,
        },
        stats,
    )
}

fn render_tile<Q: RayQueries + ?Sized>(
    scene: &Scene,
    prep: &Prepared,
    queries: &Q,
    cam: &Camera,
    tx: u32,
    ty: u32,
    counters: &Counters,
) -> Vec<[f32; 3]> {
    let (w, h) = (cam.width_px, cam.height_px);
    let spp = scene.settings.spp.max(1);
    let mut pixels = Vec::new();
    for j in ty * TILE..((ty + 1) * TILE).min(h) {
        for i in tx * TILE..((tx + 1) * TILE).min(w) {
            pixels.push((i, j));
        }
    }
    let mut rays = Vec::with_capacity(pixels.len() * spp as usize);
    let mut diffs = Vec::with_capacity(pixels.len() * spp as usize);
    for &(i, j) in &pixels {
        for k in 0..spp {
            let (ox, oy) = sample_offset(j * w + i, k, spp);
            let rd = cam.ray(i as f32 + ox, j as f32 + oy);
            rays.push(rd.ray);
            diffs.push(rd);
        }
    }
    let footprint_scale = if scene.settings.footprint == Footprint::Ellipse {
        1.0 / (spp as f32).sqrt()
    } else {
        0.0
    };
    let mut hits = vec![None; rays.len()];
    queries.closest_hits(&rays, &mut hits, Coherence::Coherent);
    let spec = scene.spectrum;
    let n_lambda = spectrum::wavelength_count(spec.mode, spec.samples);
    let y_norm = if spec.mode == SpectrumMode::Spectral {
        spectrum::y_normalisation(spec.samples)
    } else {
        1.0
    };
    let shadows = scene.settings.shadows;
    // Phase 1: the shading point of every hit and the first shadow rays of every light
    // (delta lights: their one ray; area lights: their probes), in (sample, light) order.
    let mut points: Vec<Option<HitPoint>> = Vec::with_capacity(rays.len());
    let mut first: Vec<Ray> = Vec::new();
    let mut slots: Vec<(u32, u32)> = Vec::new();
    for (idx, hit) in hits.iter().enumerate() {
        let point = hit
            .as_ref()
            .and_then(|h| hit_point(prep, &diffs[idx], footprint_scale, h));
        if let Some(hp) = &point {
            for light in &prep.lights {
                let start = first.len() as u32;
                first_rays(hp, light, shadows, &mut first);
                slots.push((start, first.len() as u32 - start));
            }
        }
        points.push(point);
    }
    // Phase 2: all of them at once (Embree traces neighbouring pixels' rays towards one
    // light as packets).
    let mut blocked = vec![false; first.len()];
    queries.occluded_many(&first, &mut blocked, Coherence::Coherent);
    let mut shadow_rays = first.len() as u64;
    // Phase 3: shading, in the same order.
    let mut shading_evals = 0u64;
    let mut out = Vec::with_capacity(pixels.len());
    let mut slot = 0usize;
    let lambda = |k: u32| spectrum::wavelength_nm(spec.mode, k, spec.samples, spec.lambda_nm);
    let ctx = Ctx {
        prep,
        shadows,
        mode: spec.mode,
        n_lambda,
        lambda: &lambda,
    };
    for (p, _) in pixels.iter().enumerate() {
        let mut acc = [0.0f32; 3];
        for k in 0..spp as usize {
            let idx = p * spp as usize + k;
            let Some(hp) = &points[idx] else {
                continue;
            };
            for light in &prep.lights {
                let (start, count) = slots[slot];
                slot += 1;
                let first_blocked = &blocked[start as usize..(start + count) as usize];
                shade_light(
                    &ctx,
                    queries,
                    hp,
                    light,
                    first_blocked,
                    &mut acc,
                    &mut shading_evals,
                    &mut shadow_rays,
                );
            }
        }
        let rgb = spectrum::finish(spec.mode, acc, y_norm);
        let inv = 1.0 / spp as f32;
        out.push([rgb[0] * inv, rgb[1] * inv, rgb[2] * inv]);
    }
    counters.shading.fetch_add(shading_evals, Ordering::Relaxed);
    counters.shadow.fetch_add(shadow_rays, Ordering::Relaxed);
    out
}

/// What shading one light at one hit needs besides the light.
struct Ctx<'a> {
    prep: &'a Prepared,
    shadows: Shadows,
    mode: SpectrumMode,
    n_lambda: u32,
    lambda: &'a dyn Fn(u32) -> f32,
}

/// A hit seen from the camera, ready to shade.
struct HitPoint {
    sp: SurfacePoint,
    wo: Vec3,
    ng: Vec3,
    fp: Ellipse,
    material: usize,
}

/// The shading point of a primary hit; `None` for a back-facing or unknown primitive.
fn hit_point(
    prep: &Prepared,
    rd: &RayDifferential,
    footprint_scale: f32,
    hit: &Hit,
) -> Option<HitPoint> {
    let &object = prep.prim_object.get(hit.prim_id as usize)?;
    let surface = &prep.surfaces[object as usize];
    let ray = &rd.ray;
    let p = hit_position(ray.origin, ray.dir, hit.t);
    let sp: SurfacePoint = if SurfaceKind::from_u32(surface.kind) == SurfaceKind::Mesh {
        let prim = hit.prim_id as usize;
        mesh_point(
            &prep.triangles[prim],
            &prep.uvs[prim],
            hit.u,
            hit.v,
            p,
            surface.scale_um,
        )
    } else {
        surface_point(surface, p)
    };
    let wo = sp.to_local(-Vec3::from_array(ray.dir).normalize_or_zero());
    if !(wo.z > 0.0) {
        return None;
    }
    let fp = if footprint_scale > 0.0 {
        footprint_ellipse(rd, hit.t, &sp, footprint_scale)
    } else {
        Ellipse::default()
    };
    Some(HitPoint {
        sp,
        wo,
        ng: Vec3::from_array(hit.ng),
        fp,
        material: surface.material as usize,
    })
}

/// Wavelengths `k0..` of the render's spectrum, at most [`MAX_LAMBDAS`] of them.
fn wavelength_group(ctx: &Ctx, k0: u32) -> Wavelengths {
    let count = (ctx.n_lambda - k0).min(MAX_LAMBDAS as u32);
    let mut wl = Wavelengths {
        count,
        ..Wavelengths::default()
    };
    for j in 0..count as usize {
        wl.nm[j] = (ctx.lambda)(k0 + j as u32);
        wl.pdf[j] = 1.0;
    }
    wl
}

/// Unit direction towards a point or directional light and the shadow ray's extent.
fn delta_direction(light: &SceneLight, sp: &SurfacePoint) -> (Vec3, f32) {
    let p0 = Vec3::new(light.p0[0], light.p0[1], light.p0[2]);
    if SceneLightKind::from_u32(light.kind) == SceneLightKind::Directional {
        (p0.normalize_or_zero(), f32::INFINITY)
    } else {
        let d = p0 - sp.position;
        let l = d.length();
        (d / l, l)
    }
}

/// Whether `light` is a point or directional light.
fn is_delta(light: &SceneLight) -> bool {
    matches!(
        SceneLightKind::from_u32(light.kind),
        SceneLightKind::Point | SceneLightKind::Directional
    )
}

/// Appends the shadow rays `light` needs first at `hp`: a delta light's one ray (if above
/// the horizon); an area light's probes above the horizon (adaptive shadows only).
fn first_rays(hp: &HitPoint, light: &SceneLight, shadows: Shadows, out: &mut Vec<Ray>) {
    let sp = &hp.sp;
    if is_delta(light) {
        let (dir, dist) = delta_direction(light, sp);
        if sp.to_local(dir).z > 0.0 {
            out.push(shading::shadow_ray(sp.position, hp.ng, dir, dist));
        }
    } else if shadows == Shadows::Adaptive && !area::below_horizon(light, sp.position, sp.z) {
        for node in area::probe_nodes(light, sp.position).iter().flatten() {
            if sp.to_local(node.dir).z > 0.0 {
                out.push(shading::shadow_ray(sp.position, hp.ng, node.dir, node.dist));
            }
        }
    }
}

/// Shades one light at one hit into the spectral accumulator `acc`, given the answers to
/// its first shadow rays ([`first_rays`]).
#[allow(clippy::too_many_arguments)]
fn shade_light<Q: RayQueries + ?Sized>(
    ctx: &Ctx,
    queries: &Q,
    hp: &HitPoint,
    light: &SceneLight,
    first_blocked: &[bool],
    acc: &mut [f32; 3],
    shading_evals: &mut u64,
    shadow_rays: &mut u64,
) {
    let m: &ShadeMaterial = &ctx.prep.materials[hp.material];
    let set = ctx.prep.scratch_set(hp.material);
    if is_delta(light) {
        // No ray (below the horizon) or a blocked one: nothing arrives.
        if first_blocked != [false] {
            return;
        }
        // Wavelengths in groups of MAX_LAMBDAS: one scratch walk per group.
        let mut k0 = 0;
        while k0 < ctx.n_lambda {
            let wl = wavelength_group(ctx, k0);
            let l = shading::delta_light_spectrum(m, &hp.sp, hp.wo, light, &wl, &set, &hp.fp);
            for j in 0..wl.count {
                *shading_evals += 1;
                spectrum::accumulate(ctx.mode, k0 + j, wl.nm[j as usize], l.v[j as usize], acc);
            }
            k0 += wl.count;
        }
        return;
    }
    let consensus = if ctx.shadows == Shadows::Adaptive {
        if area::below_horizon(light, hp.sp.position, hp.sp.z) {
            return;
        }
        let lit = first_blocked.iter().filter(|&&b| !b).count();
        if !first_blocked.is_empty() && (lit == 0 || lit == first_blocked.len()) {
            Some(lit > 0)
        } else {
            None
        }
    } else {
        None
    };
    area_light(
        m,
        hp,
        light,
        queries,
        consensus,
        ctx,
        &set,
        acc,
        shading_evals,
        shadow_rays,
    );
}

/// A sphere or triangle light: the visible fraction from `consensus` (its probes agreed:
/// wholly visible or hidden) or, without one, from a shadow ray to every quadrature node;
/// then the closed form (velinov) scaled by the visible fraction, or the quadrature over the
/// visible nodes.
#[allow(clippy::too_many_arguments)]
fn area_light<Q: RayQueries + ?Sized, S: scratchwave_kernel::scratch::ScratchSet>(
    m: &ShadeMaterial,
    hp: &HitPoint,
    light: &SceneLight,
    queries: &Q,
    consensus: Option<bool>,
    ctx: &Ctx,
    set: &S,
    acc: &mut [f32; 3],
    shading_evals: &mut u64,
    shadow_rays: &mut u64,
) {
    let (sp, wo, fp) = (&hp.sp, hp.wo, &hp.fp);
    let occluded = |node: &area::AreaNode, rays: &mut u64| {
        *rays += 1;
        queries.occluded(&shading::shadow_ray(
            sp.position,
            hp.ng,
            node.dir,
            node.dist,
        ))
    };
    let nodes = shading::needs_area_nodes(m);
    if consensus == Some(false) {
        return;
    }
    let mut visible = [None; area::MAX_NODES as usize];
    let (mut w_vis, mut w_all) = (1.0f32, 1.0f32);
    if consensus.is_none() || nodes {
        (w_vis, w_all) = (0.0, 0.0);
        for i in 0..area::node_count(light) {
            let Some(node) = area::area_node(light, sp.position, i) else {
                continue;
            };
            if !(sp.to_local(node.dir).z > 0.0) {
                continue;
            }
            w_all += node.weight;
            let lit = match consensus {
                Some(lit) => lit,
                None => !occluded(&node, shadow_rays),
            };
            if lit {
                w_vis += node.weight;
                visible[i as usize] = Some(node);
            }
        }
    }
    if !(w_vis > 0.0) {
        return;
    }
    let closed = shading::closed_form_area(m);
    let scale = w_vis / w_all;
    // Wavelengths in groups of MAX_LAMBDAS: one scratch walk per group (and per node).
    let mut k0 = 0;
    while k0 < ctx.n_lambda {
        let wl = wavelength_group(ctx, k0);
        let count = wl.count as usize;
        let closed_l = if closed {
            *shading_evals += count as u64;
            shading::velinov_area_light(m, sp, wo, light, &wl.nm, count, set, fp)
        } else {
            [0.0; MAX_LAMBDAS]
        };
        // Per node, every wavelength of the group (quadrature models: one walk per node).
        let mut node_l = [[0.0f32; MAX_LAMBDAS]; area::MAX_NODES as usize];
        if nodes && !closed {
            for (slot, node) in visible.iter().enumerate() {
                if let Some(node) = node {
                    node_l[slot] = shading::area_node_radiance_spectrum(
                        m,
                        sp,
                        wo,
                        node,
                        light.emission,
                        &wl,
                        set,
                    )
                    .v;
                }
            }
        }
        for j in 0..count {
            let lam = wl.nm[j];
            let mut l = closed_l[j] * scale;
            if nodes {
                for (slot, node) in visible.iter().enumerate() {
                    let Some(node) = node else {
                        continue;
                    };
                    l += if closed {
                        shading::base_node_radiance(m, sp, wo, node, light.emission, lam, set)
                    } else {
                        node_l[slot][j]
                    };
                    *shading_evals += 1;
                }
            }
            spectrum::accumulate(ctx.mode, k0 + j as u32, lam, l, acc);
        }
        k0 += wl.count;
    }
}
