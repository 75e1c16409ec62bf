//! Named metals of pbrt-v4 as per-channel complex indices of refraction
//! (the spectral tables and the fit live in `lumis_math::spectrum`).

use lumis_math::spectrum::{conductor_rgb, named};
use lumis_math::Rgb;

/// `(eta, k)` per channel of a named metal, e.g. "Cu" for pbrt-v4's
/// `metal-Cu-eta` / `metal-Cu-k`.
pub fn metal(base: &str) -> Option<(Rgb, Rgb)> {
    let eta = named(&format!("metal-{base}-eta"))?;
    let k = named(&format!("metal-{base}-k"))?;
    Some(conductor_rgb(&eta, &k))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn named_metals() {
        for m in ["Ag", "Al", "Au", "Cu", "CuZn", "MgO", "TiO2"] {
            let (eta, k) = metal(m).unwrap();
            assert!(eta.min_component() > 0.0 && k.min_component() >= 0.0, "{m}");
        }
        assert!(metal("Xx").is_none());
    }
}
