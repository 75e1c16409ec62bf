//! The dielectric coat over a slab of medium that pbrt-v4's coated
//! materials (`coateddiffuse`, `coatedconductor`) share, with pbrt-v4's
//! parameter names and defaults.

use crate::load::texture::TexBuilder;
use crate::material::{Coat, Roughness};
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, ParamSet};

/// Parameters of the coat and slab every coated material has.
pub(super) const COAT: [&str; 5] = ["thickness", "albedo", "g", "maxdepth", "nsamples"];

/// The coat with interface roughness `r` and index of refraction `eta`.
pub(super) fn coat(
    tex: &TexBuilder,
    p: &ParamSet,
    r: Roughness,
    eta: f32,
) -> Result<Coat, Diagnostic> {
    let count = |name: &str, default: i32, min: i32| -> Result<u32, Diagnostic> {
        let v = p.get_int(name, default)?;
        if v < min {
            return Err(Diagnostic::error(
                &p.loc_of(name).unwrap_or_else(lumis_scene::Loc::none),
                format!("`{name}` must be at least {min}, found {v}"),
            ));
        }
        Ok(v as u32)
    };
    Ok(Coat {
        roughness: r,
        eta,
        thickness: tex.float(p, "thickness", 0.01)?,
        albedo: tex.spectrum(p, "albedo", Rgb::BLACK)?,
        g: tex.float(p, "g", 0.0)?,
        max_depth: count("maxdepth", 10, 0)?,
        n_samples: count("nsamples", 1, 1)?,
    })
}
