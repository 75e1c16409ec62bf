//! `AreaLightSource "diffuse"` on a shape's primitives: constant `L`, or an
//! image (`string filename`, pbrt-v4 semantics: RGB radiance looked up at
//! the surface's uv, `v` flipped, times `scale`; `L` and `filename` together
//! are an error). `power` rescales the emission so the whole shape emits
//! that power: for an image, through its integral over the surface (pbrt-v4
//! uses the image's mean, which is the same when uv covers the unit square
//! evenly, as on a quad or a cylinder).

use super::spectrum::light_rgb;
use super::Warnings;
use crate::geometry::sample::FlatTriangle;
use crate::geometry::Prim;
use crate::light::area_texture::texel_coverage;
use crate::light::{AreaLight, EmissionImage, TexturedEmission};
use crate::scene::Shapes;
use crate::texture::image::{read_texture_image, Encoding};
use lumis_math::Rgb;
use lumis_scene::{Diagnostic, Entity, SceneDesc};
use std::sync::Arc;

/// Sampling cells of one textured light, over all its primitives (about).
const CELL_BUDGET: f32 = (1 << 20) as f32;

/// One light per primitive, or none (unsupported area light type).
pub fn area_lights(
    desc: &SceneDesc,
    al: &Entity,
    shapes: &Shapes,
    prims: &[Prim],
    w: &mut Warnings,
) -> Result<Vec<AreaLight>, Diagnostic> {
    let p = &al.params;
    if al.ty != "diffuse" {
        w.push(Diagnostic::warning(
            &al.loc,
            format!(
                "area light `{}` is not supported; the shape does not emit",
                al.ty
            ),
        ));
        return Ok(Vec::new());
    }
    let scale = p.get_float("scale", 1.0)?;
    let two_sided = p.get_bool("twosided", false)?;
    let image = match p.get_opt_string("filename")? {
        None => None,
        Some(file) => {
            if let Some(loc) = p.loc_of("L") {
                return Err(Diagnostic::error(
                    &loc,
                    "an area light takes either `L` or `filename`, not both",
                ));
            }
            Some(Arc::new(read_image(desc, al, &file)?))
        }
    };
    let lemit = match image {
        Some(_) => Rgb::splat(scale),
        None => light_rgb(desc, p, "L")?.unwrap_or(Rgb::WHITE) * scale,
    };
    // Sampling cells: up to 32 along a texel's side, fewer when the shape
    // covers many texels, so that one light holds about a million cells.
    let cells_per_texel = image.as_ref().map_or(1.0, |img| {
        let texels: f32 = prims.iter().map(|&p| texel_coverage(img, shapes, p)).sum();
        (CELL_BUDGET / texels.max(1e-6)).sqrt().clamp(1.0, 32.0)
    });
    let mut lights: Vec<AreaLight> = prims
        .iter()
        .map(|&prim| AreaLight {
            prim,
            lemit,
            two_sided,
            flat: FlatTriangle::new(shapes, prim),
            texture: image.as_ref().map(|img| {
                Box::new(TexturedEmission::build(
                    img.clone(),
                    shapes,
                    prim,
                    cells_per_texel,
                ))
            }),
        })
        .collect();
    if p.has("power") {
        let power = p.get_float("power", 0.0)?;
        // pbrt-v4: `power` multiplies `scale` and is meant for a
        // unit-luminance spectrum (an `rgb L` keeps its own luminance on
        // top), while an image's luminance is divided out.
        let l_lum = lemit.luminance();
        let k_e: f32 = lights
            .iter()
            .map(|l| l.power(shapes).luminance())
            .sum::<f32>()
            / l_lum;
        if k_e > 0.0 && l_lum > 0.0 {
            lights.iter_mut().for_each(|l| l.lemit *= power / k_e);
        }
    }
    w.unused(
        p,
        "area light \"diffuse\"",
        &["L", "scale", "twosided", "power", "filename"],
    );
    Ok(lights)
}

/// The image as linear RGB (8-bit files are sRGB-encoded, as pbrt-v4 reads them).
fn read_image(desc: &SceneDesc, al: &Entity, file: &str) -> Result<EmissionImage, Diagnostic> {
    let loc = al
        .params
        .loc_of("filename")
        .unwrap_or_else(|| al.loc.clone());
    let path = desc.read_path(file);
    let level = read_texture_image(&path, Encoding::Srgb).map_err(|e| {
        Diagnostic::error(
            &loc,
            format!("cannot read area light image {}: {e}", path.display()),
        )
    })?;
    if level.texels.iter().any(|t| !t.is_finite()) {
        return Err(Diagnostic::error(
            &loc,
            format!(
                "{}: the image has infinite or NaN pixels, unsuitable for a light",
                path.display()
            ),
        ));
    }
    Ok(EmissionImage::new(level))
}
