//! `cylinder`: `radius` around z from `zmin` to `zmax`, swept to `phimax` degrees.

use super::common::{Built, Ctx};
use crate::geometry::Cylinder;
use crate::load::Warnings;
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, w: &mut Warnings) -> Result<Built, Diagnostic> {
    let (e, p) = (c.e, c.p);
    let radius = p.get_float("radius", 1.0)?;
    let zmin = p.get_float("zmin", -1.0)?;
    let zmax = p.get_float("zmax", 1.0)?;
    let phimax = p.get_float("phimax", 360.0)?;
    w.unused(
        p,
        "shape \"cylinder\"",
        &["radius", "zmin", "zmax", "phimax"],
    );
    let cyl = Cylinder::new(c.xf, radius, zmin, zmax, phimax, c.s.reverse_orientation);
    if !(radius > 0.0 && cyl.area() > 0.0) {
        return Err(Diagnostic::error(
            &e.loc,
            "cylinder needs radius > 0, zmin != zmax and phimax > 0",
        ));
    }
    Ok(Built::Cylinder(cyl))
}
