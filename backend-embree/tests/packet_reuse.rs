//! `Scene::intersect_many` reuses one packet, valid mask and argument record for a whole
//! batch. Nothing may leak from one packet into the next: a lane that hit in one packet and
//! holds a miss, an invalid ray or nothing (short last packet) in the next must report no
//! hit, and every ray must get the same answer as when traced alone.

use scratchwave_embree::{Device, SceneBuilder};
use scratchwave_host::Coherence;
use scratchwave_kernel::ray::Ray;
use scratchwave_testkit::fixtures::{SplitMix64, camera_rays, sphere_with};

#[test]
fn packets_of_a_batch_do_not_leak_into_each_other() {
    let device = Device::new().expect("Embree (run scripts/fetch-embree.sh)");
    let mesh = sphere_with(2_000);
    let mut builder = SceneBuilder::new(&device).expect("scene");
    builder
        .add_triangle_mesh(&mesh.vertices, &mesh.indices)
        .expect("mesh");
    let scene = builder.commit().expect("commit");

    // Camera rays through the sphere's middle (all hit), then every ray replaced at random by
    // a ray pointing away (a miss) or an invalid ray, so lanes change between hit, miss and
    // masked off from packet to packet. 16·37 + 5 rays: the last packet of every width is
    // short.
    let mut rng = SplitMix64::new(9);
    let rays: Vec<Ray> = camera_rays(32, 32, 0.2)
        .into_iter()
        .take(16 * 37 + 5)
        .map(|r| match rng.next_u64() % 4 {
            0 => Ray::new(r.origin, [r.dir[0], r.dir[1], -r.dir[2]]),
            1 => r.with_interval(1.0, f32::NAN),
            _ => r,
        })
        .collect();
    let alone: Vec<_> = rays.iter().map(|r| scene.intersect(r)).collect();
    let hits = alone.iter().filter(|h| h.is_some()).count();
    assert!(
        hits > rays.len() / 3 && hits < rays.len() * 2 / 3,
        "{hits} hits: not a mixed batch"
    );
    for width in [1, 4, 8, 16] {
        for coherence in [Coherence::Coherent, Coherence::Incoherent] {
            let mut batch = vec![None; rays.len()];
            scene.intersect_many(&rays, &mut batch, width, coherence);
            for (i, (b, a)) in batch.iter().zip(&alone).enumerate() {
                match (b, a) {
                    (None, None) => {}
                    (Some(b), Some(a)) => {
                        assert_eq!(b.prim_id, a.prim_id, "width {width}, ray {i}");
                        assert!(
                            (b.t - a.t).abs() <= 1e-6 * a.t,
                            "width {width}, ray {i}: t {} vs {}",
                            b.t,
                            a.t
                        );
                    }
                    _ => panic!("width {width}, ray {i}: batch {b:?}, alone {a:?}"),
                }
            }
        }
    }
}
