//! The tile loop: primary rays per 8×8 tile (rayon over tiles), closest hits through any
//! [`RayQueries`], shadow rays through the same structure, shading by kernel functions
//! only ([`scratchwave_kernel::render`]).

use crate::prepare::Prepared;
use crate::scene::Footprint;
use crate::scene::Scene;
use rayon::prelude::*;
use scratchwave_host::{Coherence, RayQueries};
use scratchwave_kernel::footprint::Ellipse;
use scratchwave_kernel::glam::Vec3;
use scratchwave_kernel::ray::Hit;
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
    let mut shading_evals = 0u64;
    let mut shadow_rays = 0u64;
    let mut out = Vec::with_capacity(pixels.len());
    for (p, _) in pixels.iter().enumerate() {
        let mut acc = [0.0f32; 3];
        for k in 0..spp as usize {
            let idx = p * spp as usize + k;
            if let Some(hit) = hits[idx] {
                shade_hit(
                    prep,
                    queries,
                    &diffs[idx],
                    footprint_scale,
                    &hit,
                    spec.mode,
                    n_lambda,
                    spec.samples,
                    spec.lambda_nm,
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

/// Shades one hit into the spectral accumulator `acc`.
#[allow(clippy::too_many_arguments)]
fn shade_hit<Q: RayQueries + ?Sized>(
    prep: &Prepared,
    queries: &Q,
    rd: &RayDifferential,
    footprint_scale: f32,
    hit: &Hit,
    mode: SpectrumMode,
    n_lambda: u32,
    samples: u32,
    single_nm: f32,
    acc: &mut [f32; 3],
    shading_evals: &mut u64,
    shadow_rays: &mut u64,
) {
    let Some(&object) = prep.prim_object.get(hit.prim_id as usize) else {
        return;
    };
    let surface = &prep.surfaces[object as usize];
    let mi = surface.material as usize;
    let m: &ShadeMaterial = &prep.materials[mi];
    let set = prep.lookups[mi].set();
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
        return;
    }
    let ng = Vec3::from_array(hit.ng);
    let fp = if footprint_scale > 0.0 {
        footprint_ellipse(rd, hit.t, &sp, footprint_scale)
    } else {
        Ellipse::default()
    };
    let lambda = |k: u32| spectrum::wavelength_nm(mode, k, samples, single_nm);
    for light in &prep.lights {
        let kind = SceneLightKind::from_u32(light.kind);
        if matches!(kind, SceneLightKind::Point | SceneLightKind::Directional) {
            let p0 = Vec3::new(light.p0[0], light.p0[1], light.p0[2]);
            let (dir, dist) = if kind == SceneLightKind::Directional {
                (p0.normalize_or_zero(), f32::INFINITY)
            } else {
                let d = p0 - sp.position;
                let l = d.length();
                (d / l, l)
            };
            if !(sp.to_local(dir).z > 0.0) {
                continue;
            }
            *shadow_rays += 1;
            if queries.occluded(&shading::shadow_ray(sp.position, ng, dir, dist)) {
                continue;
            }
            for k in 0..n_lambda {
                let l = shading::delta_light(m, &sp, wo, light, lambda(k), &set, &fp);
                *shading_evals += 1;
                spectrum::accumulate(mode, k, lambda(k), l, acc);
            }
        } else {
            area_light(
                m,
                &sp,
                wo,
                ng,
                light,
                queries,
                mode,
                n_lambda,
                &lambda,
                &set,
                acc,
                shading_evals,
                shadow_rays,
            );
        }
    }
}

/// A sphere or triangle light: shadow rays to its quadrature nodes, then the closed form
/// (velinov) scaled by the visible fraction, or the quadrature over the visible nodes.
#[allow(clippy::too_many_arguments)]
fn area_light<Q: RayQueries + ?Sized, S: scratchwave_kernel::scratch::ScratchSet>(
    m: &ShadeMaterial,
    sp: &SurfacePoint,
    wo: Vec3,
    ng: Vec3,
    light: &SceneLight,
    queries: &Q,
    mode: SpectrumMode,
    n_lambda: u32,
    lambda: &dyn Fn(u32) -> f32,
    set: &S,
    acc: &mut [f32; 3],
    shading_evals: &mut u64,
    shadow_rays: &mut u64,
) {
    let mut visible = [None; area::MAX_NODES as usize];
    let (mut w_vis, mut w_all) = (0.0f32, 0.0f32);
    for i in 0..area::node_count(light) {
        let Some(node) = area::area_node(light, sp.position, i) else {
            continue;
        };
        if !(sp.to_local(node.dir).z > 0.0) {
            continue;
        }
        w_all += node.weight;
        *shadow_rays += 1;
        if !queries.occluded(&shading::shadow_ray(sp.position, ng, node.dir, node.dist)) {
            w_vis += node.weight;
            visible[i as usize] = Some(node);
        }
    }
    if !(w_vis > 0.0) {
        return;
    }
    let closed = shading::closed_form_area(m);
    for k in 0..n_lambda {
        let lam = lambda(k);
        let mut l = 0.0;
        if closed {
            l += shading::velinov_area_light(m, sp, wo, light, lam, set) * (w_vis / w_all);
            *shading_evals += 1;
        }
        for node in visible.iter().flatten() {
            l += if closed {
                shading::base_node_radiance(m, sp, wo, node, light.emission, lam, set)
            } else {
                shading::area_node_radiance(m, sp, wo, node, light.emission, lam, set)
            };
            *shading_evals += 1;
        }
        spectrum::accumulate(mode, k, lam, l, acc);
    }
}
