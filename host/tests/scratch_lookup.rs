//! The scratch lookup (and its grid) returns exactly the brute-force set "every scratch
//! within r of x0", and the models give the same values through it as through a plain slice.

use glam::Vec2;
use scratchwave_host::ScratchLookup;
use scratchwave_kernel::scratch::{Scratch, ScratchSet, ScratchSlice};

use scratchwave_kernel::table::{Model, TableParams, TableQuery, evaluate};
use scratchwave_testkit::fixtures::SplitMix64;

/// `n` scratches over a square of side `extent` µm, lengths from 0 to 400 µm.
fn field(n: usize, extent: f32, seed: u64) -> Vec<Scratch> {
    let mut r = SplitMix64::new(seed);
    (0..n)
        .map(|_| {
            let c = [extent * r.next_f32(), extent * r.next_f32()];
            let a = std::f32::consts::TAU * r.next_f32();
            let h = 200.0 * r.next_f32() * r.next_f32();
            Scratch {
                center: c,
                tangent: [a.cos(), a.sin()],
                half_len: h,
                width: 1.0,
                depth: 0.2,
                ..Scratch::default()
            }
        })
        .collect()
}

fn collect<S: ScratchSet>(s: &S, x: Vec2, r: f32) -> Vec<[u32; 4]> {
    let mut v = Vec::new();
    s.for_each_near(x, r, |sc| {
        v.push([
            sc.center[0].to_bits(),
            sc.center[1].to_bits(),
            sc.tangent[0].to_bits(),
            sc.half_len.to_bits(),
        ])
    });
    v.sort_unstable();
    v
}

#[test]
fn lookup_equals_brute_force() {
    let mut total_queries = 0;
    for (n, extent) in [
        (1_000usize, 2_000.0f32),
        (10_000, 6_000.0),
        (100_000, 20_000.0),
    ] {
        let scratches = field(n, extent, n as u64);
        let lookup = ScratchLookup::new(&scratches, 10.0);
        let brute = ScratchSlice {
            scratches: &scratches,
        };
        let mut r = SplitMix64::new(7 + n as u64);
        let queries = if n == 100_000 { 2_000 } else { 5_000 };
        let mut found = 0;
        for _ in 0..queries {
            let x = Vec2::new(extent * r.next_f32(), extent * r.next_f32());
            let radius = [30.0, 60.0, 200.0][(r.next_f32() * 3.0) as usize % 3];
            let a = collect(&lookup.set(), x, radius);
            assert_eq!(a, collect(&brute, x, radius), "n={n} x={x} r={radius}");
            found += a.len();
        }
        assert!(
            found > queries,
            "the test should exercise non-empty answers (n={n}: {found})"
        );
        total_queries += queries;
    }
    assert!(total_queries >= 10_000);
}

#[test]
fn grid_equals_brute_force() {
    let mut found = 0;
    for (n, extent, seed) in [(2_000usize, 3_000.0f32, 1u64), (20_000, 12_000.0, 2)] {
        let scratches = field(n, extent, seed);
        let lookup = ScratchLookup::new(&scratches, 10.0);
        let data = lookup.grid(10.0, 64 * n).expect("grid within budget");
        assert_eq!(data.header.radius, 60.0);
        let grid = data.set(&lookup);
        let brute = ScratchSlice {
            scratches: &scratches,
        };
        let mut r = SplitMix64::new(seed + 100);
        for q in 0..4_000 {
            // Points beyond the field too (outside the grid), and radii below, at and
            // above the grid's (the last go to the BVH).
            let x = Vec2::new(
                extent * (1.2 * r.next_f32() - 0.1),
                extent * (1.2 * r.next_f32() - 0.1),
            );
            let radius = [0.0, 25.0, 60.0, 90.0][q % 4];
            let a = collect(&grid, x, radius);
            assert_eq!(a, collect(&brute, x, radius), "n={n} x={x} r={radius}");
            found += a.len();
        }
    }
    assert!(found > 4_000, "non-empty answers expected: {found}");
    // A budget too small for the cells leaves the BVH alone.
    let scratches = field(100, 100_000.0, 3);
    let lookup = ScratchLookup::new(&scratches, 10.0);
    assert!(lookup.grid(10.0, 1_000).is_none());
    assert!(ScratchLookup::new(&[], 10.0).grid(10.0, 1 << 20).is_none());
}

#[test]
fn models_agree_through_lookup_and_slice() {
    let scratches = field(3_000, 600.0, 99);
    let lookup = ScratchLookup::new(&scratches, 10.0);
    let brute = ScratchSlice {
        scratches: &scratches,
    };
    let mut r = SplitMix64::new(5);
    for model in [Model::Werner, Model::WernerBlended, Model::Velinov] {
        let p = TableParams {
            model: model as u32,
            base_gaussian: 1,
            sigma_um: 10.0,
            ..Default::default()
        };
        for _ in 0..500 {
            let (a, b) = (0.3 * (r.next_f32() - 0.5), 0.3 * (r.next_f32() - 0.5));
            let q = TableQuery {
                wi: [0.0, 0.0, 1.0],
                wo: [a, b, (1.0 - a * a - b * b).sqrt()],
                lambda_nm: 550.0,
                x: [600.0 * r.next_f32(), 600.0 * r.next_f32()],
                material: scratchwave_kernel::material::Material::constant(1.0),
                ..Default::default()
            };
            let (x, y) = (evaluate(&p, &q, &lookup.set()), evaluate(&p, &q, &brute));
            // Same terms summed in another order: the rounding difference scales with the
            // summands, bounded by n·Σ|S_k|² ≥ (Σ|S_k|)² (the incoherent model's value).
            let mut near = 0;
            brute.for_each_near(Vec2::from_array(q.x), 60.0, |_| near += 1);
            let incoherent = TableParams {
                model: Model::Velinov as u32,
                ..p
            };
            let scale = near as f32 * evaluate(&incoherent, &q, &brute);
            assert!(
                (x - y).abs() <= 1e-5 * (x.abs().max(y.abs()) + scale) + 1e-30,
                "{model:?}: {x} vs {y}"
            );
        }
    }
}
