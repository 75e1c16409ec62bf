//! `disk`: a disk (or annulus, `innerradius`) of `radius` at z = `height`;
//! partial disks (`phimax`) are rendered whole, with a warning.

use super::common::{Built, Ctx};
use crate::geometry::Disk;
use crate::load::Warnings;
use lumis_scene::Diagnostic;

pub(super) fn build(c: &Ctx, w: &mut Warnings) -> Result<Built, Diagnostic> {
    let (e, p) = (c.e, c.p);
    let height = p.get_float("height", 0.0)?;
    let radius = p.get_float("radius", 1.0)?;
    let inner = p.get_float("innerradius", 0.0)?;
    if p.get_float("phimax", 360.0)? < 360.0 {
        w.push(Diagnostic::warning(
            &e.loc,
            "partial disks (phimax) are not supported yet; rendering the full disk",
        ));
    }
    w.unused(
        p,
        "shape \"disk\"",
        &["height", "radius", "innerradius", "phimax"],
    );
    if !(radius > 0.0 && inner >= 0.0 && inner < radius) {
        return Err(Diagnostic::error(
            &e.loc,
            "disk needs radius > innerradius >= 0",
        ));
    }
    Ok(Built::Disk(Disk::new(
        c.xf,
        height,
        radius,
        inner,
        c.s.reverse_orientation,
    )))
}
