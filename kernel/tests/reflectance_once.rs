//! `material::Reflectance` forms F once for a material whose reflectance does not depend
//! on the wavelength and per wavelength otherwise; every value must be the bits
//! `Material::reflectance` returns for that wavelength alone.

use glam::Vec3;
use scratchwave_kernel::conductor::Conductor;
use scratchwave_kernel::material::{FresnelAngle, Material, Reflectance};

#[test]
fn reflectance_equals_per_wavelength_calls() {
    let materials = [
        Material::constant(0.73),
        Material::ior(1.2, 7.0, FresnelAngle::ThetaD),
        Material::ior(1.5, 0.0, FresnelAngle::ThetaI),
        Material::ior(0.2, 3.1, FresnelAngle::Normal),
        Material::conductor(Conductor::Gold, FresnelAngle::ThetaD),
        Material::conductor(Conductor::Aluminium, FresnelAngle::ThetaI),
    ];
    let lambdas = [380.0f32, 450.0, 532.0, 610.0, 700.0, 780.0];
    let mut checked = 0;
    for m in &materials {
        for (ti, to) in [(0.0f32, 0.0f32), (0.4, 1.1), (1.5, 0.2), (1.56, 1.56)] {
            let wi = Vec3::new(ti.sin(), 0.0, ti.cos());
            let wo = Vec3::new(-to.sin() * 0.6, to.sin() * 0.8, to.cos());
            let mut r = Reflectance::new(m, wi, wo);
            for &l in &lambdas {
                let want = m.reflectance(wi, wo, l);
                assert_eq!(r.at(l).to_bits(), want.to_bits(), "{m:?} at {l} nm");
                checked += 1;
            }
        }
    }
    // The spectral ones do vary (so forming F once would have been wrong for them).
    let gold = materials[4];
    let (wi, wo) = (Vec3::Z, Vec3::Z);
    assert!(gold.reflectance(wi, wo, 450.0) != gold.reflectance(wi, wo, 700.0));
    println!("{checked} reflectances equal");
}
