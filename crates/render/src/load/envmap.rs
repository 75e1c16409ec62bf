//! `LightSource "infinite" "string filename"`: an image environment light.
//!
//! The mapping follows the image's shape: square images are pbrt-v4's
//! equal-area octahedral maps, 2:1 images pbrt-v3's latitude-longitude maps.
//! `"string mapping" [ "equalarea" | "latlong" ]` (a lumis extension, set by
//! the pbrt-v3 upgrade for `mapname`) says it explicitly; with `latlong`,
//! pbrt-v3's `L` is accepted as an RGB multiplier of the map.

use super::spectrum::light_rgb;
use super::Warnings;
use crate::image_io::read_image;
use crate::light::{EnvMapping, GoniometricLight, ImageInfiniteLight, Light};
use lumis_math::sampling::{equal_area_square_to_sphere, latlong_to_sphere};
use lumis_math::transform::uniform_scale;
use lumis_math::{Mat3, Rgb, Transform, Vec2, Vec3};
use lumis_scene::{Diagnostic, Entity, SceneDesc};

pub fn build_image_light(
    desc: &SceneDesc,
    e: &Entity,
    light_to_world: &Transform,
    w: &mut Warnings,
) -> Result<Light, Diagnostic> {
    let p = &e.params;
    let file = p.get_string("filename", "")?;
    let file_loc = p.loc_of("filename").unwrap_or_else(|| e.loc.clone());
    let mapping_loc = p.loc_of("mapping").unwrap_or_else(|| e.loc.clone());
    let explicit = match p.get_opt_string("mapping")?.as_deref() {
        None => None,
        Some("equalarea") => Some(EnvMapping::EqualArea),
        Some("latlong") => Some(EnvMapping::LatLong),
        Some(other) => {
            return Err(Diagnostic::error(
                &mapping_loc,
                format!("unknown environment mapping `{other}`: expected `equalarea` or `latlong`"),
            ))
        }
    };
    let mut multiplier = Rgb::WHITE;
    if p.has("L") {
        if explicit != Some(EnvMapping::LatLong) {
            let loc = p.loc_of("L").unwrap_or_else(|| e.loc.clone());
            return Err(Diagnostic::error(
                &loc,
                "an infinite light takes either `L` or `filename`, not both",
            ));
        }
        multiplier = light_rgb(desc, p, "L")?.unwrap_or(Rgb::WHITE);
    }
    let (path, img) = read_light_image(desc, &file, &file_loc)?;
    let (width, height) = (img.width, img.height);
    let mapping = match explicit {
        Some(EnvMapping::EqualArea) | None if width == height => EnvMapping::EqualArea,
        Some(EnvMapping::LatLong) => EnvMapping::LatLong,
        None if width == 2 * height => EnvMapping::LatLong,
        _ => return Err(Diagnostic::error(
            &file_loc,
            format!(
                "{}: environment image is {width}x{height}; an equal-area map must be square \
                     and a latitude-longitude map 2:1",
                path.display()
            ),
        )
        .with_help(
            "pass `\"string mapping\" \"latlong\"` for a latitude-longitude map of another shape",
        )),
    };
    let scale = p.get_float("scale", 1.0)?;
    let mut texels: Vec<Rgb> = img
        .data
        .chunks_exact(3)
        .map(|c| Rgb::new(c[0], c[1], c[2]).map(|v| v.max(0.0)) * multiplier)
        .collect();
    // pbrt-v4: `scale` multiplies; `illuminance` rescales the map so that an
    // upward-facing (light-space +z) patch receives that illuminance.
    let mut k = scale;
    if p.has("illuminance") {
        let e_v = p.get_float("illuminance", 0.0)?;
        let e_map = upper_illuminance(&texels, width, height, mapping);
        if e_map > 0.0 && e_v > 0.0 {
            k *= e_v / e_map;
        }
    }
    texels.iter_mut().for_each(|t| *t *= k);
    w.unsupported(p, &["portal"], "infinite light", "ignored");
    w.unused(
        p,
        "light \"infinite\"",
        &["L", "scale", "illuminance", "filename", "portal", "mapping"],
    );
    let to_world = rigid_part(light_to_world, &e.loc, w);
    Ok(Light::Image(ImageInfiniteLight::new(
        width, height, texels, mapping, to_world,
    )))
}

/// Reads an image for a light: a located error if it cannot be read or has
/// NaN or infinite pixels.
fn read_light_image(
    desc: &SceneDesc,
    file: &str,
    loc: &lumis_scene::Loc,
) -> Result<(std::path::PathBuf, crate::image_io::RgbImage), Diagnostic> {
    let path = desc.read_path(file);
    let img = read_image(&path).map_err(|err| Diagnostic::error(loc, err.to_string()))?;
    if img.data.iter().any(|v| !v.is_finite()) {
        return Err(Diagnostic::error(
            loc,
            format!(
                "{}: the image has infinite or NaN pixels, unsuitable for a light",
                path.display()
            ),
        ));
    }
    Ok((path, img))
}

/// `LightSource "goniometric"`: `I`, `scale`, `power` and an equal-area
/// square image (its RGB averaged, as pbrt-v4) giving the intensity's
/// directional distribution; the light sits at the transform's origin with
/// the image's pole along its `y` axis. Without `filename`: isotropic, warned.
pub fn build_goniometric(
    desc: &SceneDesc,
    e: &Entity,
    light_to_world: &Transform,
    w: &mut Warnings,
) -> Result<Light, Diagnostic> {
    let p = &e.params;
    let mut i = light_rgb(desc, p, "I")?.unwrap_or(Rgb::WHITE) * p.get_float("scale", 1.0)?;
    let (res, values) = match p.get_opt_string("filename")? {
        Some(file) => {
            let loc = p.loc_of("filename").unwrap_or_else(|| e.loc.clone());
            let (path, img) = read_light_image(desc, &file, &loc)?;
            if img.width != img.height {
                return Err(Diagnostic::error(
                    &loc,
                    format!(
                        "{}: goniometric image is {}x{}; pbrt-v4 needs a square equal-area image",
                        path.display(),
                        img.width,
                        img.height
                    ),
                ));
            }
            let v = img.data.chunks_exact(3).map(|c| (c[0] + c[1] + c[2]) / 3.0);
            (img.width, v.collect())
        }
        None => {
            w.push(Diagnostic::warning(
                &e.loc,
                "goniometric light without \"filename\": emitting like a point light",
            ));
            (1, vec![1.0])
        }
    };
    let mean = values.iter().map(|&v: &f32| v.max(0.0) as f64).sum::<f64>() / values.len() as f64;
    if p.has("power") {
        // pbrt-v4: 4 pi times the image's mean; `I` (unit luminance, or an
        // `rgb` counted as white) and `scale` multiply.
        let k = 4.0 * lumis_math::PI * mean as f32;
        if k > 0.0 {
            i *= p.get_float("power", 0.0)? / k;
        }
    }
    w.unused(
        p,
        "light \"goniometric\"",
        &["I", "scale", "power", "filename"],
    );
    // pbrt-v4 swaps y and z: the image's +z pole is the light's +y axis.
    let swap = Mat3::from_cols(Vec3::X, Vec3::Z, Vec3::Y);
    let to_world = rigid_part(light_to_world, &e.loc, w) * swap;
    Ok(Light::Goniometric(GoniometricLight::new(
        light_to_world.point(Vec3::ZERO),
        i,
        res,
        values,
        to_world,
    )))
}

/// Illuminance at an upward (+z) patch from the map's upper hemisphere:
/// `Σ Y cos(theta) ΔΩ` over texel centres with `z > 0`, `ΔΩ` the texel's
/// exact solid angle. (pbrt-v4 weighs each texel by `2 pi / N` where the
/// texel's solid angle is `4 pi / N`, so its maps come out twice as bright
/// as the illuminance asked for; lumis uses the solid angle.)
pub fn upper_illuminance(texels: &[Rgb], width: u32, height: u32, mapping: EnvMapping) -> f32 {
    let (w, h) = (width as usize, height as usize);
    let mut e = 0.0f64;
    for y in 0..h {
        let solid = match mapping {
            EnvMapping::EqualArea => 4.0 * std::f64::consts::PI / (w * h) as f64,
            EnvMapping::LatLong => {
                let t0 = std::f64::consts::PI * y as f64 / h as f64;
                let t1 = std::f64::consts::PI * (y + 1) as f64 / h as f64;
                2.0 * std::f64::consts::PI / w as f64 * (t0.cos() - t1.cos())
            }
        };
        for x in 0..w {
            let uv = Vec2::new((x as f32 + 0.5) / w as f32, (y as f32 + 0.5) / h as f32);
            let d = match mapping {
                EnvMapping::EqualArea => equal_area_square_to_sphere(uv),
                EnvMapping::LatLong => latlong_to_sphere(uv).0,
            };
            if d.z > 0.0 {
                e += (texels[y * w + x].luminance() * d.z) as f64 * solid;
            }
        }
    }
    e as f32
}

/// The light's rotation (or reflection): the linear part of its transform
/// with a uniform scale divided out. A shear or non-uniform scale would make
/// the map's densities wrong; it is warned about and orthonormalised.
fn rigid_part(t: &Transform, loc: &lumis_scene::Loc, w: &mut Warnings) -> Mat3 {
    let m = Mat3::from_mat4(t.m);
    if let Some(s) = uniform_scale(m, 1e-3) {
        return m * (1.0 / s);
    }
    let (a, b) = (m.x_axis, m.y_axis);
    w.push(Diagnostic::warning(
        loc,
        "the infinite light's transform is not a rotation with uniform scale; using its nearest rotation",
    ));
    let x = a.normalize_or(Vec3::X);
    let y = (b - x * x.dot(b)).normalize_or(x.any_orthonormal_vector());
    let z = x.cross(y) * if m.determinant() < 0.0 { -1.0 } else { 1.0 };
    Mat3::from_cols(x, y, z)
}
