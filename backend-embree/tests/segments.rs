//! Embree's scratch radius query against brute force (and the portable BVH): exactly the
//! same set of segments on 10⁴ queries for each of 10³ … 10⁶ segments.

use scratchwave_embree::{Device, SegmentIndex};
use scratchwave_host::{SegmentBvh, SegmentRadiusQuery};
use scratchwave_kernel::segment2d::Segment2;
use scratchwave_testkit::fixtures::{random_points, scratch_field};
use scratchwave_testkit::reference;

const RADIUS: f32 = 30.0;

/// Runs `queries` queries; the first `brute` against plain brute force, the rest against the
/// sorted-sweep oracle (itself checked against brute force in scratchwave-cpu's tests).
fn check(n: usize, queries: usize, brute: usize) {
    let device = Device::new().expect("Embree");
    let (segments, extent) = scratch_field(n, 31);
    let embree = SegmentIndex::new(&device, &segments).expect("index");
    let portable = SegmentBvh::new(&segments, RADIUS).expect("bvh");
    let sweep = reference::SegmentSweep::new(&segments);
    let (mut got, mut expected, mut other) = (Vec::new(), Vec::new(), Vec::new());
    let mut found = 0;
    for (k, p) in random_points(queries, 32, extent).into_iter().enumerate() {
        embree.segments_within(p, RADIUS, &mut got);
        got.sort_unstable();
        if k < brute {
            reference::segments_within(&segments, p, RADIUS, &mut expected);
        } else {
            sweep.query(p, RADIUS, &mut expected);
        }
        assert_eq!(got, expected, "{n} segments, query {k} at {p:?}");
        portable.segments_within(p, RADIUS, &mut other);
        other.sort_unstable();
        assert_eq!(other, expected, "portable, {n} segments, query {k}");
        found += got.len();
    }
    eprintln!(
        "{n} segments: {queries} queries ({brute} brute force), {:.1} per query, all identical",
        found as f64 / queries as f64
    );
    assert!(found > queries);
}

#[test]
fn thousand_segments() {
    check(1_000, 10_000, 10_000);
}

#[test]
fn ten_thousand_segments() {
    check(10_000, 10_000, 10_000);
}

#[test]
fn hundred_thousand_segments() {
    check(100_000, 10_000, 300);
}

#[test]
fn million_segments() {
    check(1_000_000, 10_000, 100);
}

#[test]
fn boundary_degenerate_and_invalid_queries() {
    let device = Device::new().expect("Embree");
    let segs = [
        Segment2::new([0.0, 0.0], [10.0, 0.0]),
        Segment2::new([5.0, 5.0], [5.0, 5.0]),
        Segment2::new([5.0, 5.0], [5.0, 5.0]),
    ];
    let index = SegmentIndex::new(&device, &segs).expect("index");
    assert_eq!(index.segments(), &segs);
    let mut out = Vec::new();
    // Exactly on the boundary of the closed disc.
    index.segments_within([5.0, -3.0], 3.0, &mut out);
    assert_eq!(out, [0]);
    index.segments_within([5.0, 2.5], 2.5, &mut out);
    out.sort_unstable();
    assert_eq!(out, [0, 1, 2]);
    index.segments_within([0.0, 0.0], 0.0, &mut out);
    assert_eq!(out, [0]);
    for (p, r) in [
        ([f32::NAN, 0.0], 1.0),
        ([0.0, 0.0], -1.0),
        ([0.0, 0.0], f32::INFINITY),
    ] {
        index.segments_within(p, r, &mut out);
        assert!(out.is_empty(), "{p:?} {r}");
    }
    let empty = SegmentIndex::new(&device, &[]).expect("empty index");
    empty.segments_within([0.0, 0.0], 1e9, &mut out);
    assert!(out.is_empty());
}

#[test]
fn queries_run_concurrently() {
    let device = Device::new().expect("Embree");
    let (segments, extent) = scratch_field(20_000, 41);
    let index = SegmentIndex::new(&device, &segments).expect("index");
    let points = random_points(2_000, 42, extent);
    let serial: Vec<Vec<u32>> = points
        .iter()
        .map(|&p| {
            let mut v = Vec::new();
            index.segments_within(p, RADIUS, &mut v);
            v.sort_unstable();
            v
        })
        .collect();
    std::thread::scope(|s| {
        for part in 0..4 {
            let (index, points, serial) = (&index, &points, &serial);
            s.spawn(move || {
                let mut v = Vec::new();
                for i in (part..points.len()).step_by(4) {
                    index.segments_within(points[i], RADIUS, &mut v);
                    v.sort_unstable();
                    assert_eq!(v, serial[i]);
                }
            });
        }
    });
}
