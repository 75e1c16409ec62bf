//! `interface` (also `""` and `"none"`): a surface that only bounds a
//! medium; it scatters nothing (the loader leaves such surfaces out unless
//! they emit).

use super::common::{Built, Ctx};
use crate::load::Warnings;
use crate::material::{InterfaceMaterial, MaterialKind};
use lumis_scene::Diagnostic;

pub(super) fn build(_c: &Ctx, _w: &mut Warnings) -> Result<Built, Diagnostic> {
    Ok((MaterialKind::Interface(InterfaceMaterial), vec![]))
}
