//! `sphere`: `radius`, optionally cut by `zmin`/`zmax` and swept to `phimax` degrees.

use super::common::{Built, Ctx};
use crate::geometry::Sphere;
use crate::load::Warnings;
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, w: &mut Warnings) -> Result<Built, Diagnostic> {
    let (e, p) = (c.e, c.p);
    let radius = p.get_float("radius", 1.0)?;
    let zmin = p.get_float("zmin", -radius)?;
    let zmax = p.get_float("zmax", radius)?;
    let phimax = p.get_float("phimax", 360.0)?;
    w.unused(p, "shape \"sphere\"", &["radius", "zmin", "zmax", "phimax"]);
    if !(radius > 0.0) {
        return Err(Diagnostic::error(
            &p.loc_of("radius").unwrap_or(e.loc.clone()),
            "sphere radius must be positive",
        ));
    }
    let sphere = Sphere::partial(c.xf, radius, zmin, zmax, phimax, c.s.reverse_orientation);
    if !(sphere.area() > 0.0) {
        return Err(Diagnostic::error(
            &e.loc,
            "this sphere has no surface left (zmin = zmax or phimax = 0)",
        ));
    }
    Ok(Built::Sphere(sphere))
}
