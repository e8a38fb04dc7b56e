//! The portable BVH against brute force: identical hits (same kernel tests, same hit order),
//! identical occlusion, and exactly the brute-force set for radius queries.

use scratchwave_host::mesh::triangles_of;
use scratchwave_host::{
    Coherence, MeshError, RayQueries, SegmentBvh, SegmentRadiusQuery, TriangleBvh,
};
use scratchwave_kernel::ray::Ray;
use scratchwave_kernel::segment2d::Segment2;
use scratchwave_testkit::fixtures::{
    self, Mesh, camera_rays, random_points, random_rays, sphere_with, triangle_soup,
};
use scratchwave_testkit::reference;

/// Checks closest hits and occlusion of `rays` against brute force. Occlusion needs no
/// second scan: with the closest hit at `t`, a shadow ray ending just before `t` is
/// unoccluded and one ending just after is occluded.
fn check_rays(mesh: &Mesh, rays: &[Ray], what: &str) -> usize {
    let bvh = TriangleBvh::new(&mesh.vertices, &mesh.indices).expect("valid mesh");
    let triangles = triangles_of(&mesh.vertices, &mesh.indices);
    let mut hits = vec![None; rays.len()];
    bvh.closest_hits(rays, &mut hits, Coherence::Incoherent);
    let mut n_hit = 0;
    for (i, (ray, hit)) in rays.iter().zip(&hits).enumerate() {
        let expected = reference::closest_hit(&triangles, ray);
        assert_eq!(*hit, expected, "{what}: ray {i} {ray:?}");
        assert_eq!(
            bvh.occluded(ray),
            expected.is_some(),
            "{what}: occluded {i}"
        );
        if let Some(h) = expected {
            n_hit += 1;
            let before = ray.with_interval(ray.t_near, h.t * 0.999);
            let after = ray.with_interval(ray.t_near, h.t * 1.001);
            assert!(
                !bvh.occluded(&before),
                "{what}: shadow ray {i} ending before the hit"
            );
            assert!(
                bvh.occluded(&after),
                "{what}: shadow ray {i} ending after the hit"
            );
        }
    }
    n_hit
}

#[test]
fn closed_spheres_agree_with_brute_force() {
    // Brute force costs ~10 ms per ray at 10⁶ triangles, hence fewer rays there; the Embree
    // tests compare against this BVH on many more.
    for (triangles, n_rays, side) in [(100, 10_000, 32), (10_000, 2_000, 16), (1_000_000, 40, 4)] {
        let mesh = sphere_with(triangles);
        let hits = check_rays(&mesh, &random_rays(n_rays, 1), "sphere random");
        assert!(hits > n_rays / 10, "{hits} hits of {n_rays}");
        check_rays(&mesh, &camera_rays(side, side, 0.4), "sphere camera");
    }
}

#[test]
fn triangle_soups_agree_with_brute_force() {
    for (triangles, n_rays, side) in [(100, 10_000, 32), (10_000, 2_000, 16), (1_000_000, 40, 4)] {
        let mesh = triangle_soup(triangles, 2);
        let hits = check_rays(&mesh, &random_rays(n_rays, 3), "soup random");
        assert!(hits > n_rays / 10, "{hits} hits of {n_rays}");
        check_rays(&mesh, &camera_rays(side, side, 0.4), "soup camera");
    }
}

#[test]
fn rays_through_shared_edges_and_vertices_tie_break_identically() {
    // A grid of unit squares split into two triangles each; rays aimed exactly at edges and
    // vertices (exactly representable) hit several triangles at the same t.
    let n = 8u32;
    let mut mesh = Mesh::default();
    for y in 0..=n {
        for x in 0..=n {
            mesh.vertices.push([x as f32, y as f32, 1.0]);
        }
    }
    let v = |x: u32, y: u32| y * (n + 1) + x;
    for y in 0..n {
        for x in 0..n {
            mesh.indices.push([v(x, y), v(x + 1, y), v(x + 1, y + 1)]);
            mesh.indices.push([v(x, y), v(x + 1, y + 1), v(x, y + 1)]);
        }
    }
    let mut rays = Vec::new();
    for y in 0..=2 * n {
        for x in 0..=2 * n {
            let (px, py) = (x as f32 * 0.5, y as f32 * 0.5);
            rays.push(Ray::new([px, py, 0.0], [0.0, 0.0, 1.0]));
            rays.push(Ray::new([px, py, 2.0], [0.0, 0.0, -1.0]));
        }
    }
    let hits = check_rays(&mesh, &rays, "grid edges");
    assert_eq!(hits, rays.len());
}

#[test]
fn empty_and_single_triangle_scenes() {
    let empty = TriangleBvh::new(&[], &[]).expect("empty mesh is valid");
    let ray = Ray::new([0.0; 3], [0.0, 0.0, 1.0]);
    assert_eq!(empty.closest_hit(&ray), None);
    assert!(!empty.occluded(&ray));
    let one = Mesh {
        vertices: vec![[-1.0, -1.0, 2.0], [1.0, -1.0, 2.0], [0.0, 1.0, 2.0]],
        indices: vec![[0, 1, 2]],
    };
    assert_eq!(check_rays(&one, &[ray], "one triangle"), 1);
}

#[test]
fn out_of_range_indices_are_rejected() {
    let err = TriangleBvh::new(&[[0.0; 3]; 3], &[[0, 1, 2], [0, 1, 3]]).unwrap_err();
    assert_eq!(
        err,
        MeshError::IndexOutOfRange {
            triangle: 1,
            index: 3,
            vertex_count: 3
        }
    );
}

#[test]
fn radius_queries_return_exactly_the_brute_force_set() {
    let r = 30.0;
    for (n, n_brute, n_sweep) in [
        (1_000, 10_000, 0),
        (10_000, 10_000, 0),
        (100_000, 300, 10_000),
        (1_000_000, 100, 10_000),
    ] {
        let (segments, extent) = fixtures::scratch_field(n, 7);
        let bvh = SegmentBvh::new(&segments, r).expect("valid");
        let (mut got, mut expected) = (Vec::new(), Vec::new());
        let mut total = 0;
        let oracle = reference::SegmentSweep::new(&segments);
        for (k, p) in random_points(n_brute.max(n_sweep), 8, extent)
            .into_iter()
            .enumerate()
        {
            bvh.segments_within(p, r, &mut got);
            got.sort_unstable();
            if k < n_brute {
                reference::segments_within(&segments, p, r, &mut expected);
                assert_eq!(got, expected, "n={n} brute force, query {k} at {p:?}");
                let mut sweep = Vec::new();
                oracle.query(p, r, &mut sweep);
                assert_eq!(sweep, expected, "sweep oracle itself, n={n} query {k}");
            } else {
                oracle.query(p, r, &mut expected);
                assert_eq!(got, expected, "n={n} sweep oracle, query {k} at {p:?}");
            }
            total += got.len();
        }
        let queries = n_brute.max(n_sweep);
        eprintln!(
            "{n} segments: {queries} queries, {:.1} segments per query",
            total as f64 / queries as f64
        );
        assert!(total > queries, "queries must find something");
    }
}

#[test]
fn radius_query_edge_cases() {
    let segs = [
        Segment2::new([0.0, 0.0], [10.0, 0.0]),
        Segment2::new([5.0, 5.0], [5.0, 5.0]),
        Segment2::new([5.0, 5.0], [5.0, 5.0]),
    ];
    let bvh = SegmentBvh::new(&segs, 1.0).expect("valid");
    let mut out = Vec::new();
    // Exactly on the boundary of the closed disc.
    bvh.segments_within([5.0, -3.0], 3.0, &mut out);
    out.sort_unstable();
    assert_eq!(out, [0]);
    bvh.segments_within([5.0, 2.5], 2.5, &mut out);
    out.sort_unstable();
    assert_eq!(out, [0, 1, 2]);
    bvh.segments_within([5.0, 2.5], 0.0, &mut out);
    assert!(out.is_empty());
    bvh.segments_within([-1.0, 0.0], 0.0, &mut out);
    assert!(out.is_empty());
    bvh.segments_within([0.0, 0.0], 0.0, &mut out);
    assert_eq!(out, [0]);
    let empty = SegmentBvh::new(&[], 1.0).expect("valid");
    empty.segments_within([0.0, 0.0], 1e9, &mut out);
    assert!(out.is_empty());
    // Identical segments, many of them: balanced tree, all found.
    let same = vec![Segment2::new([1.0, 1.0], [2.0, 2.0]); 5000];
    let bvh = SegmentBvh::new(&same, 1.0).expect("valid");
    bvh.segments_within([0.0, 0.0], 1.5, &mut out);
    assert_eq!(out.len(), 5000);
    let _ = fixtures::SplitMix64::new(0);
}
