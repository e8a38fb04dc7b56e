//! Seeded scratch patterns: determinism, counts, chord tolerance, continuity of curves,
//! orientation statistics and the segment limit.

use scratchwave_host::pattern::{
    Count, Distribution, MAX_SEGMENTS, Orientation, PatternError, ProfileChoice, ScratchPattern,
    Shape,
};
use scratchwave_host::rng::SplitMix64;
use scratchwave_kernel::scratch::{Profile, Scratch};
use std::f64::consts::{PI, TAU};

/// Velinov's benchmark grooves (widths and depths uniform, widths 0.8–6 µm) over a 1 mm
/// square, 100 straight scratches of random orientation.
fn base() -> ScratchPattern {
    ScratchPattern {
        min: [0.0, 0.0],
        max: [1000.0, 1000.0],
        count: Count::Exact(100),
        shape: Shape::Straight {
            length: Distribution::Uniform {
                lo: 50.0,
                hi: 500.0,
            },
        },
        orientation: Orientation::Random,
        width: Distribution::Uniform { lo: 0.8, hi: 6.0 },
        depth: Distribution::Uniform { lo: 0.1, hi: 1.0 },
        profile: ProfileChoice::Alternate,
        chord_tol_um: 0.1,
        max_segments: MAX_SEGMENTS,
    }
}

fn arcs(radius: f64, sweep_rad: Distribution) -> ScratchPattern {
    ScratchPattern {
        shape: Shape::Arc {
            radius: Distribution::Constant(radius),
            sweep_rad,
        },
        ..base()
    }
}

fn walks() -> ScratchPattern {
    ScratchPattern {
        shape: Shape::Walk {
            length: Distribution::LogUniform {
                lo: 20.0,
                hi: 400.0,
            },
            step_um: 5.0,
            turn_sd_rad: 0.1,
        },
        ..base()
    }
}

/// Every field's bits, so that equal means bit-identical (also for −0 and NaN).
fn bits(s: &[Scratch]) -> Vec<u32> {
    s.iter()
        .flat_map(|s| {
            [
                s.center[0].to_bits(),
                s.center[1].to_bits(),
                s.tangent[0].to_bits(),
                s.tangent[1].to_bits(),
                s.half_len.to_bits(),
                s.width.to_bits(),
                s.depth.to_bits(),
                s.profile,
            ]
        })
        .collect()
}

/// Each scratch's polyline (f64) and groove, via `for_each_stroke`.
fn strokes(p: &ScratchPattern, seed: u64) -> Vec<(Vec<[f64; 2]>, f32, f32, Profile)> {
    let mut out = Vec::new();
    p.for_each_stroke(&mut SplitMix64::new(seed), |st| {
        out.push((st.points.to_vec(), st.width, st.depth, st.profile))
    })
    .unwrap();
    out
}

#[test]
fn same_seed_same_bits_other_seed_other_scratches() {
    for p in [base(), arcs(200.0, Distribution::Constant(1.0)), walks()] {
        let a = p.generate(&mut SplitMix64::new(7)).unwrap();
        let b = p.generate(&mut SplitMix64::new(7)).unwrap();
        let c = p.generate(&mut SplitMix64::new(8)).unwrap();
        assert!(!a.is_empty());
        assert_eq!(bits(&a), bits(&b));
        assert_ne!(bits(&a), bits(&c));
    }
}

#[test]
fn generate_is_the_strokes_split_at_their_points() {
    // The segments are exactly `from_endpoints` of consecutive polyline points: the end of
    // segment k and the start of k + 1 are the same f64 point.
    for p in [
        arcs(300.0, Distribution::Uniform { lo: 0.5, hi: 3.0 }),
        walks(),
    ] {
        let segs = p.generate(&mut SplitMix64::new(3)).unwrap();
        let mut expect = Vec::new();
        let mut multi = 0;
        for (pts, w, d, prof) in strokes(&p, 3) {
            assert!(pts.len() >= 2);
            multi += usize::from(pts.len() > 2);
            for k in 0..pts.len() - 1 {
                expect.push(Scratch::from_endpoints(pts[k], pts[k + 1], w, d, prof));
            }
        }
        assert!(multi > 90, "curves should have several segments ({multi})");
        assert_eq!(bits(&segs), bits(&expect));
    }
}

#[test]
fn consecutive_segments_meet_within_f32_rounding() {
    // Measured on the f32 records themselves: the gap between the end of one segment and the
    // start of the next is the rounding of centre and half length, never a real gap.
    for p in [arcs(300.0, Distribution::Constant(2.0)), walks()] {
        let mut n_joins = 0;
        let mut rng = SplitMix64::new(11);
        let mut segs_of = Vec::new();
        p.for_each_stroke(&mut rng, |st| segs_of.push(st.points.len() - 1))
            .unwrap();
        let segs = p.generate(&mut SplitMix64::new(11)).unwrap();
        let mut i = 0;
        for n in segs_of {
            for k in i..i + n - 1 {
                let (_, end) = segs[k].endpoints();
                let (start, _) = segs[k + 1].endpoints();
                let gap = ((end[0] - start[0]).powi(2) + (end[1] - start[1]).powi(2)).sqrt();
                // Coordinates up to ~1500 µm: f32 ulp 1.2e-4; a few roundings.
                assert!(gap < 1e-3, "gap {gap} between segments {k} and {}", k + 1);
                n_joins += 1;
            }
            i += n;
        }
        assert_eq!(i, segs.len());
        assert!(n_joins > 100);
    }
}

#[test]
fn count_from_density_is_density_times_area() {
    // 2 mm × 0.5 mm = 1 mm²; 12345.6/mm² → 12346 scratches.
    let p = ScratchPattern {
        min: [-1000.0, 0.0],
        max: [1000.0, 500.0],
        count: Count::PerMm2(12345.6),
        ..base()
    };
    let s = p.generate(&mut SplitMix64::new(1)).unwrap();
    assert_eq!(s.len(), 12346);
    // Anchors (centres of straight scratches) lie in the region, and fill it.
    let (mut lo, mut hi) = ([f32::MAX; 2], [f32::MIN; 2]);
    for s in &s {
        for a in 0..2 {
            lo[a] = lo[a].min(s.center[a]);
            hi[a] = hi[a].max(s.center[a]);
        }
    }
    assert!(lo[0] >= -1000.0 && hi[0] <= 1000.0 && lo[1] >= 0.0 && hi[1] <= 500.0);
    assert!(lo[0] < -990.0 && hi[0] > 990.0 && lo[1] < 5.0 && hi[1] > 495.0);
}

#[test]
fn widths_depths_and_profiles_follow_their_distributions() {
    let p = ScratchPattern {
        count: Count::Exact(4000),
        ..base()
    };
    let s = p.generate(&mut SplitMix64::new(5)).unwrap();
    let (wlo, whi) = s.iter().fold((f32::MAX, 0f32), |(lo, hi), s| {
        (lo.min(s.width), hi.max(s.width))
    });
    assert!((0.8..0.82).contains(&wlo) && (5.98..=6.0).contains(&whi));
    // Uniform on [0.8, 6): mean 3.4, s.d. of the mean 1.5/√4000 = 0.024.
    let mean = s.iter().map(|s| f64::from(s.width)).sum::<f64>() / s.len() as f64;
    assert!((mean - 3.4).abs() < 0.15, "mean width {mean}");
    assert!(s.iter().all(|s| (0.1..1.0).contains(&s.depth)));
    for (i, s) in s.iter().enumerate() {
        let want = if i % 2 == 1 {
            Profile::Triangle
        } else {
            Profile::Rect
        };
        assert_eq!(s.profile, want as u32);
        assert!((25.0..=250.0).contains(&s.half_len));
    }
}

#[test]
fn arc_chords_honour_the_tolerance_and_are_the_fewest_that_do() {
    for (r, tol) in [(500.0, 0.1), (20.0, 0.05), (3000.0, 0.01), (5.0, 4.0)] {
        let p = ScratchPattern {
            chord_tol_um: tol,
            count: Count::Exact(30),
            ..arcs(r, Distribution::Uniform { lo: 0.1, hi: TAU })
        };
        for (pts, ..) in strokes(&p, 9) {
            let n = pts.len() - 1;
            let mut sweep = 0.0;
            for w in pts.windows(2) {
                let half = 0.5 * ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt();
                // Sagitta of a chord of half length `half` on a circle of radius r.
                let sagitta = r - (r * r - half * half).max(0.0).sqrt();
                assert!(
                    sagitta <= tol * (1.0 + 1e-9),
                    "r {r}: sagitta {sagitta} > {tol}"
                );
                sweep += 2.0 * (half / r).min(1.0).asin();
            }
            // One chord fewer would break the tolerance (or exceed a half turn).
            if n > 1 {
                let phi = sweep / (n - 1) as f64;
                let sagitta = r * (1.0 - (0.5 * phi).cos());
                assert!(sagitta > tol * (1.0 - 1e-9) || phi > PI * (1.0 - 1e-9));
            }
            // All points on one circle of radius r: the chord midpoints' distance pattern is
            // checked through the equal chord lengths.
            let first = (pts[1][0] - pts[0][0]).hypot(pts[1][1] - pts[0][1]);
            for w in pts.windows(2) {
                let l = (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]);
                assert!((l - first).abs() <= 1e-9 * r);
            }
        }
    }
}

#[test]
fn arc_is_centred_and_tangent_to_the_heading_at_its_anchor() {
    // Brushed with no spread: every arc's heading at its arc-length midpoint is +x, so the
    // chord from its first to its last point is parallel to x.
    let p = ScratchPattern {
        orientation: Orientation::Brushed {
            angle_rad: 0.0,
            spread_rad: 0.0,
        },
        ..arcs(100.0, Distribution::Uniform { lo: 0.2, hi: 3.0 })
    };
    let mut left = 0;
    for (pts, ..) in strokes(&p, 4) {
        let (a, b) = (pts[0], pts[pts.len() - 1]);
        assert!((b[1] - a[1]).abs() < 1e-9 * 100.0, "{a:?} → {b:?}");
        assert!(b[0] > a[0]);
        left += usize::from(a[1] > pts[pts.len() / 2][1]);
    }
    // Bending left and right about equally (100 arcs: 50 ± 5 s.d.).
    assert!((25..=75).contains(&left), "{left} of 100 bend left");
}

#[test]
fn brushed_headings_have_the_requested_spread() {
    let (angle, spread) = (0.7, 0.05);
    let n = 20_000;
    let p = ScratchPattern {
        count: Count::Exact(n),
        orientation: Orientation::Brushed {
            angle_rad: angle,
            spread_rad: spread,
        },
        ..base()
    };
    let s = p.generate(&mut SplitMix64::new(21)).unwrap();
    let dev: Vec<f64> = s
        .iter()
        .map(|s| f64::from(s.tangent[1]).atan2(f64::from(s.tangent[0])) - angle)
        .collect();
    let mean = dev.iter().sum::<f64>() / n as f64;
    let sd = (dev.iter().map(|d| (d - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt();
    // Gaussian: the mean has s.d. spread/√n = 3.5e-4, the sample s.d. a relative s.d. of
    // 1/√(2n) = 0.5 %; the bounds are 10 of those.
    assert!(
        mean.abs() < 10.0 * spread / (n as f64).sqrt(),
        "mean {mean}"
    );
    assert!(
        (sd / spread - 1.0).abs() < 10.0 / (2.0 * n as f64).sqrt(),
        "sd {sd}"
    );
    // Gaussian rather than uniform: about 4.55 % beyond 2 s.d. (a uniform spread of the same
    // s.d. has none); binomial s.d. 0.15 %.
    let tail = dev.iter().filter(|d| d.abs() > 2.0 * spread).count() as f64 / n as f64;
    assert!((tail - 0.0455).abs() < 0.01, "tail {tail}");
}

#[test]
fn random_headings_cover_the_circle() {
    let p = ScratchPattern {
        count: Count::Exact(8000),
        ..base()
    };
    let s = p.generate(&mut SplitMix64::new(2)).unwrap();
    let mut bins = [0usize; 8];
    for s in &s {
        let a = f64::from(s.tangent[1])
            .atan2(f64::from(s.tangent[0]))
            .rem_euclid(TAU);
        bins[((a / TAU * 8.0) as usize).min(7)] += 1;
    }
    // 1000 expected per bin, s.d. 30.
    assert!(bins.iter().all(|&b| (800..1200).contains(&b)), "{bins:?}");
}

#[test]
fn circular_polish_tangents_are_perpendicular_to_the_radius() {
    let c = [400.0, 600.0];
    let p = ScratchPattern {
        count: Count::Exact(500),
        orientation: Orientation::Circular { center_um: c },
        ..base()
    };
    let s = p.generate(&mut SplitMix64::new(13)).unwrap();
    for s in &s {
        let r = [f64::from(s.center[0]) - c[0], f64::from(s.center[1]) - c[1]];
        let len = r[0].hypot(r[1]);
        let t = [f64::from(s.tangent[0]), f64::from(s.tangent[1])];
        let cos = (r[0] * t[0] + r[1] * t[1]) / len;
        // f32 centre (ulp 6e-5 µm) over radii ≥ ~1 µm, f32 tangent.
        assert!(
            cos.abs() < 1e-4 * (1.0 + 1.0 / len),
            "cos {cos} at radius {len}"
        );
        // Counter-clockwise: r × t > 0.
        assert!(r[0] * t[1] - r[1] * t[0] > 0.0);
    }
}

#[test]
fn walks_have_their_length_and_steps() {
    let p = ScratchPattern {
        count: Count::Exact(200),
        ..walks()
    };
    for (pts, ..) in strokes(&p, 17) {
        let steps: Vec<f64> = pts
            .windows(2)
            .map(|w| (w[1][0] - w[0][0]).hypot(w[1][1] - w[0][1]))
            .collect();
        let len: f64 = steps.iter().sum();
        assert!((20.0..400.0 + 1e-9).contains(&len), "length {len}");
        assert_eq!(steps.len() as f64, (len / 5.0 - 1e-9).ceil());
        assert!(
            steps
                .iter()
                .all(|s| (s - steps[0]).abs() < 1e-9 && *s <= 5.0 + 1e-9)
        );
    }
}

#[test]
fn too_many_segments_is_an_error_before_allocation() {
    // 10¹⁵ straight scratches.
    let p = ScratchPattern {
        count: Count::Exact(1_000_000_000_000_000),
        ..base()
    };
    match p.generate(&mut SplitMix64::new(1)) {
        Err(PatternError::TooManySegments { estimate, limit }) => {
            assert_eq!(estimate, 1e15);
            assert_eq!(limit, MAX_SEGMENTS);
        }
        other => panic!("{other:?}"),
    }
    // Arcs: full circles of radius 1 m with a 1 nm tolerance need 2π/√(8 tol/r) ≈ 70249
    // chords each (sagitta r δ²/8), 7.0·10⁷ for 1000 of them.
    let p = ScratchPattern {
        chord_tol_um: 1e-3,
        count: Count::Exact(1000),
        ..arcs(1e6, Distribution::Constant(TAU))
    };
    let e = p.generate(&mut SplitMix64::new(1)).unwrap_err();
    assert!(
        matches!(e, PatternError::TooManySegments { estimate, .. } if (7.02e7..7.03e7).contains(&estimate)),
        "{e:?}"
    );
    // A small explicit limit: 100 scratches of up to 80 steps.
    let p = ScratchPattern {
        max_segments: 1000,
        ..walks()
    };
    let e = p.generate(&mut SplitMix64::new(1)).unwrap_err();
    assert_eq!(
        e,
        PatternError::TooManySegments {
            estimate: 8000.0,
            limit: 1000
        }
    );
    assert!(e.to_string().contains("limit of 1000"), "{e}");
    // Exactly at the limit is fine.
    let p = ScratchPattern {
        max_segments: 100,
        ..base()
    };
    assert_eq!(p.generate(&mut SplitMix64::new(1)).unwrap().len(), 100);
}

#[test]
fn invalid_parameters_are_errors_not_panics() {
    let nan = f64::NAN;
    let cases: Vec<(ScratchPattern, &str)> = vec![
        (
            ScratchPattern {
                max: [-1.0, 1000.0],
                ..base()
            },
            "region",
        ),
        (
            ScratchPattern {
                count: Count::PerMm2(nan),
                ..base()
            },
            "density_per_mm2",
        ),
        (
            ScratchPattern {
                width: Distribution::Uniform { lo: 2.0, hi: 1.0 },
                ..base()
            },
            "width",
        ),
        (
            ScratchPattern {
                depth: Distribution::Constant(-0.1),
                ..base()
            },
            "depth",
        ),
        (
            ScratchPattern {
                shape: Shape::Straight {
                    length: Distribution::LogUniform { lo: 0.0, hi: 1.0 },
                },
                ..base()
            },
            "shape.length",
        ),
        (arcs(0.0, Distribution::Constant(1.0)), "shape.radius"),
        (arcs(1.0, Distribution::Constant(7.0)), "shape.sweep"),
        (
            ScratchPattern {
                chord_tol_um: 0.0,
                ..base()
            },
            "chord_tol_um",
        ),
        (
            ScratchPattern {
                orientation: Orientation::Brushed {
                    angle_rad: 0.0,
                    spread_rad: nan,
                },
                ..base()
            },
            "orientation.spread",
        ),
    ];
    for (p, field) in cases {
        match p.generate(&mut SplitMix64::new(1)) {
            Err(PatternError::Invalid { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{field}: {other:?}"),
        }
    }
}
