//! What the acceleration structures store per primitive ([`PrimInfo`]) and
//! what a closest-hit query returns ([`Hit`]).

use crate::geometry::{Prim, SurfaceGeom};

/// A primitive with what it is made of.
#[derive(Clone, Copy, Debug)]
pub struct PrimInfo {
    pub prim: Prim,
    pub material: u32,
    /// Index of its area light, or `NO_LIGHT`.
    pub light: u32,
}

pub const NO_LIGHT: u32 = u32::MAX;

/// A surface hit with everything shading needs.
#[derive(Clone, Copy, Debug)]
pub struct Hit {
    pub t: f32,
    pub geom: SurfaceGeom,
    pub material: u32,
    pub light: Option<u32>,
    pub prim: Prim,
}

impl Hit {
    #[inline]
    pub fn new(t: f32, geom: SurfaceGeom, info: PrimInfo) -> Hit {
        Hit {
            t,
            geom,
            material: info.material,
            light: (info.light != NO_LIGHT).then_some(info.light),
            prim: info.prim,
        }
    }
}
