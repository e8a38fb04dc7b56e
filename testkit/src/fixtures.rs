//! Deterministic scenes, rays and segment sets for tests, benchmarks and the conformance
//! suite. Everything is seeded; the same call gives the same data on every machine.

use scratchwave_kernel::ray::Ray;
use scratchwave_kernel::segment2d::Segment2;

use scratchwave_host::generate::{HalfLength, ProfileMix, ScratchRecipe, Uniform};
pub use scratchwave_host::rng::SplitMix64;
use scratchwave_kernel::scratch::{Profile, Scratch};

/// An indexed triangle mesh.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Mesh {
    /// Vertex positions.
    pub vertices: Vec<[f32; 3]>,
    /// One vertex-index triple per triangle, counter-clockwise seen from outside.
    pub indices: Vec<[u32; 3]>,
}

/// A closed UV sphere centred at the origin: `2·segments·(rings − 1)` triangles, every edge
/// shared by two triangles (rays through edges produce exact `t` ties).
///
/// # Panics
/// If `rings < 2` or `segments < 3`.
pub fn uv_sphere(rings: u32, segments: u32, radius: f32) -> Mesh {
    assert!(rings >= 2 && segments >= 3, "degenerate sphere");
    let mut vertices = vec![[0.0, 0.0, radius]];
    for i in 1..rings {
        let theta = core::f32::consts::PI * i as f32 / rings as f32;
        for j in 0..segments {
            let phi = core::f32::consts::TAU * j as f32 / segments as f32;
            vertices.push([
                radius * theta.sin() * phi.cos(),
                radius * theta.sin() * phi.sin(),
                radius * theta.cos(),
            ]);
        }
    }
    vertices.push([0.0, 0.0, -radius]);
    let south = vertices.len() as u32 - 1;
    let ring = |i: u32, j: u32| 1 + (i - 1) * segments + j % segments;
    let mut indices = Vec::with_capacity((2 * segments * (rings - 1)) as usize);
    for j in 0..segments {
        indices.push([0, ring(1, j), ring(1, j + 1)]);
    }
    for i in 1..rings - 1 {
        for j in 0..segments {
            let (a, b, c, d) = (
                ring(i, j),
                ring(i, j + 1),
                ring(i + 1, j),
                ring(i + 1, j + 1),
            );
            indices.push([a, c, d]);
            indices.push([a, d, b]);
        }
    }
    for j in 0..segments {
        indices.push([south, ring(rings - 1, j + 1), ring(rings - 1, j)]);
    }
    Mesh { vertices, indices }
}

/// A unit UV sphere with about `triangles` triangles (at least 12).
pub fn sphere_with(triangles: usize) -> Mesh {
    let rings = ((triangles as f64 / 4.0).sqrt().round() as u32).max(2);
    uv_sphere(rings, 2 * rings, 1.0)
}

/// `n` independent random triangles in `[-1, 1]³`, edges up to `8/√n` long so that a ray
/// crossing the cube meets a few of them whatever `n` is. No shared edges.
pub fn triangle_soup(n: usize, seed: u64) -> Mesh {
    let mut rng = SplitMix64::new(seed);
    let size = 8.0 / (n.max(1) as f32).sqrt();
    let mut vertices = Vec::with_capacity(3 * n);
    for _ in 0..n {
        let c = [
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
            rng.range(-1.0, 1.0),
        ];
        for _ in 0..3 {
            let d = rng.direction();
            let s = size * rng.range(0.3, 1.0);
            vertices.push([c[0] + s * d[0], c[1] + s * d[1], c[2] + s * d[2]]);
        }
    }
    let indices = (0..n as u32)
        .map(|i| [3 * i, 3 * i + 1, 3 * i + 2])
        .collect();
    Mesh { vertices, indices }
}

/// Incoherent rays: origins uniform in `[-1.5, 1.5]³`, directions uniform on the sphere.
pub fn random_rays(n: usize, seed: u64) -> Vec<Ray> {
    let mut rng = SplitMix64::new(seed);
    (0..n)
        .map(|_| {
            let o = [
                rng.range(-1.5, 1.5),
                rng.range(-1.5, 1.5),
                rng.range(-1.5, 1.5),
            ];
            Ray::new(o, rng.direction())
        })
        .collect()
}

/// Coherent primary rays of a `width × height` pinhole camera at `(0, 0, -3)` looking
/// along +z, with image-plane half-extent `half_extent` at distance 1 (0.4 frames the unit
/// sphere). Emitted in 4 × 4 pixel tiles, so any aligned run of 4, 8 or 16 rays is a compact
/// screen-space block (a good packet).
///
/// # Panics
/// If `width` or `height` is not a multiple of 4.
pub fn camera_rays(width: usize, height: usize, half_extent: f32) -> Vec<Ray> {
    assert!(
        width.is_multiple_of(4) && height.is_multiple_of(4),
        "tiles are 4 × 4"
    );
    let mut rays = Vec::with_capacity(width * height);
    for ty in (0..height).step_by(4) {
        for tx in (0..width).step_by(4) {
            for y in ty..ty + 4 {
                for x in tx..tx + 4 {
                    let u = ((x as f32 + 0.5) / width as f32 * 2.0 - 1.0) * half_extent;
                    let v = ((y as f32 + 0.5) / height as f32 * 2.0 - 1.0) * half_extent;
                    rays.push(Ray::new([0.0, 0.0, -3.0], [u, v, 1.0]));
                }
            }
        }
    }
    rays
}

/// `n` segments with centres uniform in the square `[0, extent)²`, uniform directions and
/// lengths uniform in `[0, max_len)`: the straight scratches of [`ScratchRecipe`] (seeded
/// by `seed`), as bare segments.
pub fn random_segments(n: usize, seed: u64, extent: f32, max_len: f32) -> Vec<Segment2> {
    ScratchRecipe {
        count: n,
        unit: 1.0,
        center: [0.5 * extent, 0.5 * extent],
        side: extent,
        outliers: None,
        half_length: HalfLength::Uniform(Uniform::new(0.0, 0.5 * max_len)),
        width: Uniform::new(1.0, 0.0),
        depth: Uniform::new(0.1, 0.0),
        profile: ProfileMix::Only(Profile::Rect),
    }
    .generate(&mut SplitMix64::new(seed))
    .iter()
    .map(Scratch::segment)
    .collect()
}

/// `n` points uniform in `[0, extent)²`.
pub fn random_points(n: usize, seed: u64, extent: f32) -> Vec<[f32; 2]> {
    let mut rng = SplitMix64::new(seed);
    (0..n)
        .map(|_| [rng.range(0.0, extent), rng.range(0.0, extent)])
        .collect()
}

/// A scratch field of `n` segments at density 0.01 per µm² (square side 10 µm·√n), lengths
/// below 50 µm: a radius-30 µm query (3σ of the default coherence window) finds a few tens of
/// segments whatever `n` is. Returns the segments and the side length.
pub fn scratch_field(n: usize, seed: u64) -> (Vec<Segment2>, f32) {
    let extent = 10.0 * (n as f32).sqrt();
    (random_segments(n, seed, extent, 50.0), extent)
}

/// `count` scratches in a 200 µm square around the origin, rectangular and V profiles
/// alternating, half lengths 5–65 µm, widths 0.5–2.5 µm, depths 0.05–0.55 µm (xorshift, fixed
/// seed): the throughput example's and the SPIR-V determinism test's table scratches.
pub fn table_scratches(count: usize) -> Vec<Scratch> {
    let mut state = 0x2545_f491_4f6c_dd1d_u64;
    let mut next = move || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    (0..count)
        .map(|i| {
            let c = [200.0 * next() - 100.0, 200.0 * next() - 100.0];
            let angle = std::f64::consts::PI * next();
            let half = 5.0 + 60.0 * next();
            let d = [half * angle.cos(), half * angle.sin()];
            let profile = if i % 2 == 0 {
                Profile::Rect
            } else {
                Profile::Triangle
            };
            Scratch::from_endpoints(
                [c[0] - d[0], c[1] - d[1]],
                [c[0] + d[0], c[1] + d[1]],
                0.5 + 2.0 * next() as f32,
                0.05 + 0.5 * next() as f32,
                profile,
            )
        })
        .collect()
}
