//! Texture coordinate mappings (pbrt-v4's TextureMapping2D): st and its
//! screen-space derivatives from the evaluation context.

use super::TexCtx;
use lumis_math::{Transform, Vec2, Vec3, INV_2PI, INV_PI, PI};

#[derive(Clone, Copy, Debug)]
pub struct TexCoord2D {
    pub st: Vec2,
    /// (ds/dx, dt/dx) and (ds/dy, dt/dy).
    pub dst_dx: Vec2,
    pub dst_dy: Vec2,
}

#[derive(Clone, Copy, Debug)]
pub enum Mapping2D {
    /// `s = su u + du`, `t = sv v + dv`.
    Uv { su: f32, sv: f32, du: f32, dv: f32 },
    /// Angles of the point seen from the texture space origin.
    Spherical { tex_from_world: Transform },
    /// Angle around and height along the texture space z axis.
    Cylindrical { tex_from_world: Transform },
    /// Projection onto two texture-space vectors.
    Planar {
        tex_from_world: Transform,
        vs: Vec3,
        vt: Vec3,
        ds: f32,
        dt: f32,
    },
}

/// A point in 3D texture space and its screen-space derivatives.
#[derive(Clone, Copy, Debug)]
pub struct TexCoord3D {
    pub p: Vec3,
    pub dpdx: Vec3,
    pub dpdy: Vec3,
}

/// pbrt-v4's TextureMapping3D: the shading point in the texture's own space
/// (the CTM at its `Texture` directive).
#[derive(Clone, Copy, Debug)]
pub struct Mapping3D {
    pub tex_from_world: Transform,
}

impl Mapping3D {
    pub fn map(&self, c: &TexCtx) -> TexCoord3D {
        let m = &self.tex_from_world;
        TexCoord3D {
            p: m.point(c.p),
            dpdx: m.vector(c.dpdx),
            dpdy: m.vector(c.dpdy),
        }
    }
}

impl Mapping2D {
    pub fn map(&self, c: &TexCtx) -> TexCoord2D {
        match *self {
            Mapping2D::Uv { su, sv, du, dv } => TexCoord2D {
                st: Vec2::new(su * c.uv.x + du, sv * c.uv.y + dv),
                dst_dx: Vec2::new(su * c.dudx, sv * c.dvdx),
                dst_dy: Vec2::new(su * c.dudy, sv * c.dvdy),
            },
            Mapping2D::Spherical { tex_from_world } => {
                let pt = tex_from_world.point(c.p);
                let (dpdx, dpdy) = (tex_from_world.vector(c.dpdx), tex_from_world.vector(c.dpdy));
                let x2y2 = (pt.x * pt.x + pt.y * pt.y).max(1e-20);
                let r2 = (x2y2 + pt.z * pt.z).max(1e-20);
                let rxy = x2y2.sqrt();
                // s = theta / pi, t = phi / 2pi.
                let dsdp = Vec3::new(pt.x * pt.z / rxy, pt.y * pt.z / rxy, -rxy) * (INV_PI / r2);
                let dtdp = Vec3::new(-pt.y, pt.x, 0.0) * (INV_2PI / x2y2);
                let v = pt.normalize_or_zero();
                let theta = v.z.clamp(-1.0, 1.0).acos();
                let mut phi = v.y.atan2(v.x);
                if phi < 0.0 {
                    phi += 2.0 * PI;
                }
                TexCoord2D {
                    st: Vec2::new(theta * INV_PI, phi * INV_2PI),
                    dst_dx: Vec2::new(dsdp.dot(dpdx), dtdp.dot(dpdx)),
                    dst_dy: Vec2::new(dsdp.dot(dpdy), dtdp.dot(dpdy)),
                }
            }
            Mapping2D::Cylindrical { tex_from_world } => {
                let pt = tex_from_world.point(c.p);
                let (dpdx, dpdy) = (tex_from_world.vector(c.dpdx), tex_from_world.vector(c.dpdy));
                let x2y2 = (pt.x * pt.x + pt.y * pt.y).max(1e-20);
                let dsdp = Vec3::new(-pt.y, pt.x, 0.0) * (INV_2PI / x2y2);
                let dtdp = Vec3::Z;
                TexCoord2D {
                    st: Vec2::new((PI + pt.y.atan2(pt.x)) * INV_2PI, pt.z),
                    dst_dx: Vec2::new(dsdp.dot(dpdx), dtdp.dot(dpdx)),
                    dst_dy: Vec2::new(dsdp.dot(dpdy), dtdp.dot(dpdy)),
                }
            }
            Mapping2D::Planar {
                tex_from_world,
                vs,
                vt,
                ds,
                dt,
            } => {
                let v = tex_from_world.point(c.p);
                let (dpdx, dpdy) = (tex_from_world.vector(c.dpdx), tex_from_world.vector(c.dpdy));
                TexCoord2D {
                    st: Vec2::new(ds + v.dot(vs), dt + v.dot(vt)),
                    dst_dx: Vec2::new(vs.dot(dpdx), vt.dot(dpdx)),
                    dst_dy: Vec2::new(vs.dot(dpdy), vt.dot(dpdy)),
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ctx(p: Vec3, uv: Vec2) -> TexCtx {
        TexCtx {
            p,
            n: Vec3::Z,
            uv,
            dpdx: Vec3::new(0.01, 0.0, 0.0),
            dpdy: Vec3::new(0.0, 0.02, 0.0),
            dudx: 0.1,
            dudy: 0.0,
            dvdx: 0.0,
            dvdy: 0.2,
        }
    }

    #[test]
    fn uv_and_planar() {
        let c = ctx(Vec3::new(1.0, 2.0, 3.0), Vec2::new(0.25, 0.5));
        let m = Mapping2D::Uv {
            su: 2.0,
            sv: 4.0,
            du: 0.5,
            dv: 0.0,
        };
        let t = m.map(&c);
        assert_eq!(t.st, Vec2::new(1.0, 2.0));
        assert_eq!(t.dst_dx, Vec2::new(0.2, 0.0));
        assert_eq!(t.dst_dy, Vec2::new(0.0, 0.8));
        let m = Mapping2D::Planar {
            tex_from_world: Transform::IDENTITY,
            vs: Vec3::X,
            vt: Vec3::Y,
            ds: 0.0,
            dt: 1.0,
        };
        let t = m.map(&c);
        assert_eq!(t.st, Vec2::new(1.0, 3.0));
        assert_eq!(t.dst_dy, Vec2::new(0.0, 0.02));
    }

    #[test]
    fn spherical_and_cylindrical() {
        let c = ctx(Vec3::new(0.0, 1.0, 0.0), Vec2::ZERO);
        let s = Mapping2D::Spherical {
            tex_from_world: Transform::IDENTITY,
        }
        .map(&c);
        assert!((s.st - Vec2::new(0.5, 0.25)).length() < 1e-6, "{:?}", s.st);
        // Moving along +x at (0, 1, 0) decreases phi: dt/dx = -0.01 / 2pi.
        assert!((s.dst_dx.y + 0.01 * INV_2PI).abs() < 1e-6, "{s:?}");
        let cy = Mapping2D::Cylindrical {
            tex_from_world: Transform::IDENTITY,
        }
        .map(&ctx(Vec3::new(-1.0, 0.0, 0.7), Vec2::ZERO));
        assert!((cy.st.x - 1.0).abs() < 1e-6 && (cy.st.y - 0.7).abs() < 1e-6);
    }
}
