//! The tile loop: primary rays per 8×8 tile (rayon over tiles), closest hits through any
//! [`RayQueries`], shadow rays through the same structure, shading by kernel functions
//! only ([`scratchwave_kernel::render`]).

use crate::prepare::Prepared;
use crate::scene::Footprint;
use crate::scene::Scene;
use rayon::prelude::*;
use scratchwave_host::{Coherence, RayQueries};
use scratchwave_kernel::bsdf::Lookup;
use scratchwave_kernel::ray::Ray;
use scratchwave_kernel::render::camera::Camera;
use scratchwave_kernel::render::model_choice::hit_reach;
use scratchwave_kernel::render::pixel::sample_offset;
use scratchwave_kernel::render::radiance::{
    FirstRays, FrameParams, HitPoint, Occlusion, ShadeCounts, first_rays, hit_point, pixel_rgb,
    shade_light,
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
    /// Per pixel (same order), the hit–light pairs of `"model": "auto"` materials shaded
    /// with the coherent and with the incoherent model
    /// (`scratchwave_kernel::render::model_choice`); empty when no such pair was shaded.
    pub model_choice: Vec<[u32; 2]>,
}

impl Image {
    /// An image of linear RGB values without a model-choice map.
    pub fn from_rgb(width: u32, height: u32, rgb: Vec<[f32; 3]>) -> Image {
        Image {
            width,
            height,
            rgb,
            model_choice: Vec::new(),
        }
    }
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
    /// Hit–light pairs of `auto` materials shaded with the coherent model.
    pub auto_coherent: u64,
    /// Hit–light pairs of `auto` materials shaded with the incoherent model.
    pub auto_incoherent: u64,
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

/// One pixel of a tile: linear RGB and its `auto` choices (coherent, incoherent).
type TilePixel = ([f32; 3], [u32; 2]);

/// A rectangle of pixels: columns `x0..x0 + width`, rows `y0..y0 + height` (from the top).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// Columns.
    pub width: u32,
    /// Rows.
    pub height: u32,
}

impl Region {
    /// The whole `width × height` image.
    pub fn full(width: u32, height: u32) -> Region {
        Region {
            x0: 0,
            y0: 0,
            width,
            height,
        }
    }

    /// Whether the region is non-empty and lies inside a `width × height` image.
    pub fn fits(&self, width: u32, height: u32) -> bool {
        self.width > 0
            && self.height > 0
            && u64::from(self.x0) + u64::from(self.width) <= u64::from(width)
            && u64::from(self.y0) + u64::from(self.height) <= u64::from(height)
    }
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
    let full = Region::full(cam.width_px, cam.height_px);
    render_region(scene, prep, queries, full, progress)
}

/// Renders the pixels of `region` (which must lie inside the image: [`Region::fits`]) into
/// an image of the region's size. Every pixel is computed as in the whole image, so regions
/// that tile the image assemble into it bit for bit.
pub fn render_region<Q: RayQueries + ?Sized>(
    scene: &Scene,
    prep: &Prepared,
    queries: &Q,
    region: Region,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> (Image, RenderStats) {
    let cam = scene.camera;
    let (w, h) = (region.width, region.height);
    let tiles_x = w.div_ceil(TILE);
    let tiles_y = h.div_ceil(TILE);
    let total = (tiles_x * tiles_y) as usize;
    let counters = Counters {
        shadow: AtomicU64::new(0),
        shading: AtomicU64::new(0),
    };
    let done = AtomicU64::new(0);
    let start = Instant::now();
    // Tile `t` covers region columns `tx·TILE..` and rows `ty·TILE..`, clipped.
    let tile_pixels = |t: u32| {
        let (tx, ty) = (t % tiles_x, t / tiles_x);
        let xs = region.x0 + tx * TILE..region.x0 + ((tx + 1) * TILE).min(w);
        let ys = region.y0 + ty * TILE..region.y0 + ((ty + 1) * TILE).min(h);
        (xs, ys)
    };
    let tiles: Vec<(u32, Vec<TilePixel>)> = (0..total as u32)
        .into_par_iter()
        .map(|tile| {
            let (xs, ys) = tile_pixels(tile);
            let out = render_tile(scene, prep, queries, &cam, xs, ys, &counters);
            let d = done.fetch_add(1, Ordering::Relaxed) as usize + 1;
            progress(d, total);
            (tile, out)
        })
        .collect();
    let seconds = start.elapsed().as_secs_f64();
    let mut rgb = vec![[0.0f32; 3]; (w as usize) * (h as usize)];
    let mut choice = vec![[0u32; 2]; rgb.len()];
    for (tile, px) in tiles {
        let (xs, ys) = tile_pixels(tile);
        let mut k = 0;
        for j in ys {
            for i in xs.clone() {
                let at = ((j - region.y0) * w + (i - region.x0)) as usize;
                (rgb[at], choice[at]) = px[k];
                k += 1;
            }
        }
    }
    let auto_coherent = choice.iter().map(|c| u64::from(c[0])).sum();
    let auto_incoherent = choice.iter().map(|c| u64::from(c[1])).sum();

    let spp = u64::from(scene.settings.spp.max(1));
    let stats = RenderStats {
        primary_rays: u64::from(w) * u64::from(h) * spp,
        shadow_rays: counters.shadow.into_inner(),
        shading_evaluations: counters.shading.into_inner(),
        seconds,
        auto_coherent,
        auto_incoherent,
    };
    (
        Image {
            width: w,
            height: h,
            rgb,
            model_choice: if auto_coherent + auto_incoherent > 0 {
                choice
            } else {
                Vec::new()
            },
        },
        stats,
    )
}

fn render_tile<Q: RayQueries + ?Sized>(
    scene: &Scene,
    prep: &Prepared,
    queries: &Q,
    cam: &Camera,
    xs: std::ops::Range<u32>,
    ys: std::ops::Range<u32>,
    counters: &Counters,
) -> Vec<TilePixel> {
    let w = cam.width_px;
    let frame = frame_params(scene, prep);
    let spp = frame.spp;
    let mut pixels = Vec::new();
    for j in ys {
        for i in xs.clone() {
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
    let footprint_scale = frame.footprint_scale();
    let mut hits = vec![None; rays.len()];
    queries.closest_hits(&rays, &mut hits, Coherence::Coherent);
    let geo = prep.geometry();
    // Phase 1: the shading point of every hit and the first shadow rays of every light
    // (delta lights: their one ray; area lights: their probes), in (sample, light) order.
    let mut points: Vec<Option<HitPoint>> = Vec::with_capacity(rays.len());
    let mut first: Vec<FirstRays> = Vec::new();
    let mut batch: Vec<Ray> = Vec::new();
    for (idx, hit) in hits.iter().enumerate() {
        let point = hit
            .as_ref()
            .and_then(|h| hit_point(&geo, &diffs[idx], footprint_scale, h));
        if let Some(hp) = &point {
            let m = &prep.materials[hp.material as usize];
            let lk = Lookup::new(prep.scratch_set(hp.material as usize));
            for light in &prep.lights {
                let f = first_rays(&frame, m, &lk, hp, light);
                batch.extend_from_slice(&f.rays[..f.count as usize]);
                first.push(f);
            }
        }
        points.push(point);
    }
    // Phase 2: all of them at once (Embree traces neighbouring pixels' rays towards one
    // light as packets).
    let mut blocked = vec![false; batch.len()];
    queries.occluded_many(&batch, &mut blocked, Coherence::Coherent);
    // Phase 3: shading, in the same order.
    let occ = QueryOcclusion(queries);
    let mut counts = ShadeCounts::default();
    let mut out = Vec::with_capacity(pixels.len());
    let (mut slot, mut ray) = (0usize, 0usize);
    for (p, _) in pixels.iter().enumerate() {
        let mut acc = [0.0f32; 3];
        let before = [counts.auto_coherent, counts.auto_incoherent];
        for k in 0..spp as usize {
            let Some(hp) = &points[p * spp as usize + k] else {
                continue;
            };
            let m = &prep.materials[hp.material as usize];
            let lk = Lookup::new(prep.scratch_set(hp.material as usize));
            let reach = hit_reach(m, &lk, hp.sp.x_um, &hp.fp);
            for light in &prep.lights {
                let f = &first[slot];
                slot += 1;
                let mut bits = 0u32;
                for (r, &b) in blocked[ray..ray + f.count as usize].iter().enumerate() {
                    bits |= u32::from(b) << r;
                }
                ray += f.count as usize;
                counts.shadow_rays += f.count;
                shade_light(
                    &frame,
                    m,
                    &lk,
                    hp,
                    &reach,
                    light,
                    f,
                    bits,
                    &occ,
                    &mut acc,
                    &mut counts,
                );
            }
        }
        out.push((
            pixel_rgb(&frame, acc),
            [
                counts.auto_coherent - before[0],
                counts.auto_incoherent - before[1],
            ],
        ));
    }
    counters
        .shading
        .fetch_add(u64::from(counts.shading), Ordering::Relaxed);
    counters
        .shadow
        .fetch_add(u64::from(counts.shadow_rays), Ordering::Relaxed);
    out
}

/// The kernel's frame record of `scene` (camera, samples, footprint, shadows, spectrum).
pub fn frame_params(scene: &Scene, prep: &Prepared) -> FrameParams {
    let spec = scene.spectrum;
    FrameParams::new(
        scene.camera,
        scene.settings.spp,
        scene.settings.footprint == Footprint::Ellipse,
        scene.settings.shadows,
        spec.mode,
        spec.samples,
        spec.lambda_nm,
        prep.lights.len() as u32,
    )
}

/// Shadow rays through a [`RayQueries`].
struct QueryOcclusion<'q, Q: ?Sized>(&'q Q);

impl<Q: RayQueries + ?Sized> Occlusion for QueryOcclusion<'_, Q> {
    fn occluded(&self, ray: &Ray) -> bool {
        self.0.occluded(ray)
    }
}
