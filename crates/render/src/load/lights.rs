//! `LightSource` directives: point, spot, distant, infinite (constant; with
//! an image in `envmap.rs`).

use super::spectrum::light_rgb;
use super::Warnings;
use crate::light::*;
use lumis_math::{Frame, Rgb, Vec3, PI};
use lumis_scene::{Diagnostic, SceneDesc};

/// Also appends each light's medium (the outside medium in effect at its
/// `LightSource`) to `light_media`.
pub fn build_lights(
    desc: &SceneDesc,
    media: &super::medium::BuiltMedia,
    lights: &mut Vec<Light>,
    light_media: &mut Vec<crate::media::LightMedium>,
    w: &mut Warnings,
) -> Result<(), Diagnostic> {
    for ld in &desc.lights {
        let medium = crate::media::LightMedium::In(media.id(&ld.medium)?);
        let e = &ld.entity;
        let p = &e.params;
        let xf = ld.light_to_world;
        let scale = p.get_float("scale", 1.0)?;
        let light = match e.ty.as_str() {
            "point" => {
                let mut i = light_rgb(desc, p, "I")?.unwrap_or(Rgb::WHITE) * scale;
                if p.has("power") {
                    // pbrt-v4: `power` multiplies `scale` and the spectrum of
                    // unit luminance (an `rgb` counts as white: its own
                    // luminance is not divided out).
                    i *= p.get_float("power", 0.0)? / (4.0 * PI);
                }
                let from = p.get_point3("from", Vec3::ZERO)?;
                w.unused(p, "light \"point\"", &["I", "scale", "power", "from"]);
                Light::Point(PointLight {
                    pos: xf.point(from),
                    intensity: i,
                })
            }
            "spot" => {
                let i = light_rgb(desc, p, "I")?.unwrap_or(Rgb::WHITE) * scale;
                let from = p.get_point3("from", Vec3::ZERO)?;
                let to = p.get_point3("to", Vec3::Z)?;
                let cone = p.get_float("coneangle", 30.0)?;
                let delta = p.get_float("conedeltaangle", 5.0)?;
                let dir = xf.vector(to - from).normalize_or_zero();
                if dir == Vec3::ZERO {
                    return Err(Diagnostic::error(
                        &e.loc,
                        "spot light `from` and `to` coincide",
                    ));
                }
                let mut l = SpotLight {
                    pos: xf.point(from),
                    frame: Frame::from_normal(dir),
                    intensity: i,
                    cos_falloff_end: cone.to_radians().cos(),
                    cos_falloff_start: (cone - delta).to_radians().cos(),
                };
                if p.has("power") {
                    // As for point lights: the cone's solid-angle factor only.
                    let (c0, c1) = (l.cos_falloff_start, l.cos_falloff_end);
                    let k_e = 2.0 * PI * ((1.0 - c0) + (c0 - c1) / 2.0);
                    l.intensity *= p.get_float("power", 0.0)? / k_e;
                }
                w.unused(
                    p,
                    "light \"spot\"",
                    &[
                        "I",
                        "scale",
                        "power",
                        "from",
                        "to",
                        "coneangle",
                        "conedeltaangle",
                    ],
                );
                Light::Spot(l)
            }
            "distant" => {
                let mut l = light_rgb(desc, p, "L")?.unwrap_or(Rgb::WHITE) * scale;
                let from = p.get_point3("from", Vec3::ZERO)?;
                let to = p.get_point3("to", Vec3::Z)?;
                let dir = xf.vector(from - to).normalize_or_zero();
                if dir == Vec3::ZERO {
                    return Err(Diagnostic::error(
                        &e.loc,
                        "distant light `from` and `to` coincide",
                    ));
                }
                if p.has("illuminance") {
                    // pbrt-v4: illuminance perpendicular to the light.
                    l *= p.get_float("illuminance", 0.0)?;
                }
                w.unused(
                    p,
                    "light \"distant\"",
                    &["L", "scale", "from", "to", "illuminance"],
                );
                Light::Distant(DistantLight {
                    w_light: dir,
                    l,
                    scene_center: Vec3::ZERO,
                    scene_radius: 1.0,
                })
            }
            "infinite" => {
                if p.has("filename") {
                    lights.push(super::envmap::build_image_light(desc, e, &xf, w)?);
                    light_media.push(medium);
                    continue;
                }
                let mut l = light_rgb(desc, p, "L")?.unwrap_or(Rgb::WHITE) * scale;
                if p.has("illuminance") {
                    // Illuminance of a constant environment on an upward
                    // surface is pi * L (pbrt-v4: for unit-luminance L).
                    l *= p.get_float("illuminance", 0.0)? / PI;
                }
                w.unsupported(p, &["portal"], "infinite light", "ignored");
                w.unused(
                    p,
                    "light \"infinite\"",
                    &["L", "scale", "illuminance", "filename", "portal"],
                );
                Light::Infinite(UniformInfiniteLight {
                    l,
                    scene_center: Vec3::ZERO,
                    scene_radius: 1.0,
                })
            }
            "goniometric" => super::envmap::build_goniometric(desc, e, &xf, w)?,
            other => {
                for q in p.unused() {
                    q.mark_used();
                }
                w.push(Diagnostic::warning(
                    &e.loc,
                    format!("light `{other}` is not supported yet; skipped"),
                ));
                continue;
            }
        };
        lights.push(light);
        light_media.push(medium);
    }
    Ok(())
}
