//! Fresnel reflectance of a smooth dielectric interface.

/// Fraction of unpolarised light reflected at a smooth interface from a medium of index 1 into one
/// of relative index `ior` (> 0), for `cos_incident` = cos of the angle between the incoming ray
/// (reversed) and the normal, in [0, 1].
///
/// The exact Fresnel equations averaged over both polarisations (not Schlick's approximation): at
/// normal incidence this is ((n−1)/(n+1))² (0.0204 for water), at grazing incidence 1, and 1
/// whenever total internal reflection occurs (`ior` < 1 beyond the critical angle).
pub fn fresnel_dielectric(cos_incident: f32, ior: f32) -> f32 {
    let cos_i = cos_incident.clamp(0.0, 1.0);
    let sin_t2 = (1.0 - cos_i * cos_i) / (ior * ior);
    if sin_t2 >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin_t2).sqrt();
    let rs = (cos_i - ior * cos_t) / (cos_i + ior * cos_t);
    let rp = (ior * cos_i - cos_t) / (ior * cos_i + cos_t);
    0.5 * (rs * rs + rp * rp)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn known_values_of_air_to_water() {
        let n = 1.333;
        assert!((fresnel_dielectric(1.0, n) - ((n - 1.0) / (n + 1.0)).powi(2)).abs() < 1e-6);
        assert!((fresnel_dielectric(0.0, n) - 1.0).abs() < 1e-6);
        // Brewster's angle: p-polarised reflection vanishes, leaving half of rs².
        let brewster = n.atan();
        let r = fresnel_dielectric(brewster.cos(), n);
        let cos_t = (1.0 - brewster.sin().powi(2) / (n * n)).sqrt();
        let rs = (brewster.cos() - n * cos_t) / (brewster.cos() + n * cos_t);
        assert!((r - 0.5 * rs * rs).abs() < 1e-5);
        // Monotonic from normal to grazing.
        let mut last = 0.0;
        for i in 0..=100 {
            let f = fresnel_dielectric(1.0 - i as f32 / 100.0, n);
            assert!(f >= last - 1e-6);
            last = f;
        }
    }

    #[test]
    fn total_internal_reflection_from_inside_water() {
        // From water to air, beyond the critical angle asin(1/1.333) = 48.6 degrees.
        let inside = 1.0 / 1.333;
        assert_eq!(fresnel_dielectric(50f32.to_radians().cos(), inside), 1.0);
        assert!(fresnel_dielectric(40f32.to_radians().cos(), inside) < 1.0);
    }
}
