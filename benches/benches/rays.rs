//! Ray and radius-query throughput: Embree (single rays, packets of 8 and 16) against the
//! portable kernel BVH, coherent and random rays, 1 and 2 threads.
//!
//!     cargo bench -p scratchwave-benches --bench rays
//!
//! Scenes: a closed UV sphere of ~10⁶ triangles; 256² camera rays in 4 × 4 tiles (coherent,
//! ~60 % hit) and 65 536 random rays from inside the sphere's bounding cube (incoherent);
//! 10⁵ scratch segments with 10⁴ radius-30 µm queries (~43 segments each). Criterion
//! reports elements (rays or queries) per second; compare ratios within one run.

#![allow(
    missing_docs,
    reason = "criterion_group! generates an undocumented pub fn"
)]

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use rayon::prelude::*;
use scratchwave_embree::{Device, Scene, SceneBuilder, SegmentIndex};
use scratchwave_host::{Coherence, RayQueries, SegmentBvh, SegmentRadiusQuery, TriangleBvh};
use scratchwave_kernel::ray::{Hit, Ray};
use scratchwave_testkit::fixtures::{
    camera_rays, random_points, random_rays, scratch_field, sphere_with,
};
use std::hint::black_box;
use std::time::Duration;

const TRIANGLES: usize = 1_000_000;
const SEGMENTS: usize = 100_000;
const RADIUS: f32 = 30.0;

struct Scenes {
    embree: Scene,
    portable: TriangleBvh,
    coherent: Vec<Ray>,
    random: Vec<Ray>,
}

fn scenes(device: &Device) -> Scenes {
    let mesh = sphere_with(TRIANGLES);
    let mut builder = SceneBuilder::new(device).expect("scene");
    builder
        .add_triangle_mesh(&mesh.vertices, &mesh.indices)
        .expect("mesh");
    Scenes {
        embree: builder.commit().expect("commit"),
        portable: TriangleBvh::new(&mesh.vertices, &mesh.indices).expect("mesh"),
        coherent: camera_rays(256, 256, 0.4),
        random: random_rays(65_536, 1),
    }
}

fn rays(c: &mut Criterion) {
    let device = Device::new().expect("Embree (run scripts/fetch-embree.sh)");
    let s = scenes(&device);
    let mut hits: Vec<Option<Hit>> = vec![None; s.coherent.len()];
    for (name, rays, coherence) in [
        ("coherent", &s.coherent, Coherence::Coherent),
        ("random", &s.random, Coherence::Incoherent),
    ] {
        let mut group = c.benchmark_group(format!("rays/{name}"));
        group
            .sample_size(10)
            .warm_up_time(Duration::from_millis(500))
            .measurement_time(Duration::from_secs(2))
            .throughput(Throughput::Elements(rays.len() as u64));
        for width in [1, 8, 16] {
            group.bench_function(BenchmarkId::new("embree", format!("width {width}")), |b| {
                b.iter(|| {
                    s.embree.intersect_many(
                        black_box(rays),
                        &mut hits[..rays.len()],
                        width,
                        coherence,
                    )
                })
            });
        }
        group.bench_function("portable bvh", |b| {
            b.iter(|| {
                s.portable
                    .closest_hits(black_box(rays), &mut hits[..rays.len()], coherence)
            })
        });
        group.finish();
    }

    // Thread scaling: the rays split into chunks over a rayon pool of 1 or 2 threads.
    let mut group = c.benchmark_group("rays/random threads");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .throughput(Throughput::Elements(s.random.len() as u64));
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        let backends: [(&str, &dyn RayQueries); 2] =
            [("embree", &s.embree), ("portable bvh", &s.portable)];
        for (name, backend) in backends {
            group.bench_function(
                BenchmarkId::new(name, format!("{threads} thread(s)")),
                |b| {
                    b.iter(|| {
                        pool.install(|| {
                            s.random
                                .par_chunks(1024)
                                .zip(hits.par_chunks_mut(1024))
                                .for_each(|(r, h)| {
                                    backend.closest_hits(r, h, Coherence::Incoherent)
                                })
                        })
                    })
                },
            );
        }
    }
    group.finish();
}

fn radius_queries(c: &mut Criterion) {
    let device = Device::new().expect("Embree (run scripts/fetch-embree.sh)");
    let (segments, extent) = scratch_field(SEGMENTS, 7);
    let embree = SegmentIndex::new(&device, &segments).expect("index");
    let portable = SegmentBvh::new(&segments, RADIUS).expect("bvh");
    let points = random_points(10_000, 8, extent);
    let mut group = c.benchmark_group("radius queries");
    group
        .sample_size(10)
        .warm_up_time(Duration::from_millis(500))
        .measurement_time(Duration::from_secs(2))
        .throughput(Throughput::Elements(points.len() as u64));
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool");
        let backends: [(&str, &dyn SegmentRadiusQuery); 2] =
            [("embree", &embree), ("portable bvh", &portable)];
        for (name, backend) in backends {
            group.bench_function(
                BenchmarkId::new(name, format!("{threads} thread(s)")),
                |b| {
                    b.iter(|| {
                        pool.install(|| {
                            points
                                .par_chunks(256)
                                .for_each_init(Vec::new, |out, chunk| {
                                    for &p in chunk {
                                        backend.segments_within(p, RADIUS, out);
                                        black_box(out.len());
                                    }
                                })
                        })
                    })
                },
            );
        }
    }
    group.finish();
}

criterion_group!(benches, rays, radius_queries);
criterion_main!(benches);
