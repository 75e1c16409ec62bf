//! Normal and bump mapping (pbrt-v4's `NormalMap` and `BumpMap`): they move
//! the shading frame only; the geometric normal is unchanged.

use crate::geometry::SurfaceGeom;
use crate::texture::{TexCtx, TexFloat, Textures, WrapMode};
use lumis_math::{Vec2, Vec3};

#[derive(Clone, Copy, Debug)]
pub enum Shading {
    /// The shape's own shading normal.
    Smooth,
    /// `displacement`: a float texture displacing the surface along its normal.
    Bump(TexFloat),
    /// `normalmap`: tangent-space normals (index into `Textures::normal_maps`).
    NormalMap(u32),
}

impl Shading {
    /// Shading normal (on the side of `ng`) and tangent `dpdu` after mapping.
    pub fn apply(&self, t: &Textures, g: &SurfaceGeom, c: &TexCtx) -> (Vec3, Vec3) {
        let (dpdu, dpdv) = match *self {
            Shading::Smooth => return (g.ns, g.dpdu),
            Shading::Bump(d) => bump(t, g, c, d),
            Shading::NormalMap(id) => normal_map(t, g, id),
        };
        let mut ns = dpdu.cross(dpdv).normalize_or_zero();
        if !ns.is_finite() || ns == Vec3::ZERO {
            return (g.ns, g.dpdu);
        }
        if ns.dot(g.ng) < 0.0 {
            ns = -ns;
        }
        (ns, dpdu)
    }
}

/// The shading tangents with the shading normal as `n`: `dpdu` made
/// perpendicular to `ns`, `dpdv` completing the frame with its own length.
fn shading_tangents(g: &SurfaceGeom) -> (Vec3, Vec3) {
    let ns = g.ns;
    let u = g.dpdu - ns * ns.dot(g.dpdu);
    let u = if u.length_squared() > 0.0 {
        u
    } else {
        lumis_math::Frame::from_normal(ns).s
    };
    let u = u.normalize() * g.dpdu.length().max(1e-12);
    // Oriented so that u x v points along ns.
    let v = ns.cross(u).normalize() * g.dpdv.length().max(1e-12);
    (u, v)
}

fn bump(t: &Textures, g: &SurfaceGeom, c: &TexCtx, d: TexFloat) -> (Vec3, Vec3) {
    let (dpdu, dpdv) = shading_tangents(g);
    let n = g.ns;
    let mut du = 0.5 * (c.dudx.abs() + c.dudy.abs());
    if du == 0.0 {
        du = 0.0005;
    }
    let mut dv = 0.5 * (c.dvdx.abs() + c.dvdy.abs());
    if dv == 0.0 {
        dv = 0.0005;
    }
    let shifted = |dp: Vec3, duv: Vec2| {
        let mut s = *c;
        s.p += dp;
        s.uv += duv;
        d.eval(t, &s)
    };
    let disp = d.eval(t, c);
    let u_disp = shifted(dpdu * du, Vec2::new(du, 0.0));
    let v_disp = shifted(dpdv * dv, Vec2::new(0.0, dv));
    // pbrt-v4 also adds `displace * dndu`; lumis does not track dn/du (zero
    // for flat triangles, a second-order term otherwise).
    (
        dpdu + n * ((u_disp - disp) / du),
        dpdv + n * ((v_disp - disp) / dv),
    )
}

fn normal_map(t: &Textures, g: &SurfaceGeom, id: u32) -> (Vec3, Vec3) {
    let img = &t.normal_maps[id as usize];
    let c = img.bilerp(Vec2::new(g.uv.x, 1.0 - g.uv.y), WrapMode::Repeat);
    let local = Vec3::new(2.0 * c.r - 1.0, 2.0 * c.g - 1.0, 2.0 * c.b - 1.0).normalize_or_zero();
    let (dpdu, dpdv) = shading_tangents(g);
    let x = dpdu.normalize();
    let z = g.ns;
    let y = z.cross(x);
    let ns = (x * local.x + y * local.y + z * local.z).normalize_or_zero();
    let (ulen, vlen) = (dpdu.length(), dpdv.length());
    let u = (dpdu - ns * ns.dot(dpdu)).normalize_or_zero() * ulen;
    let v = ns.cross(u).normalize_or_zero() * vlen;
    (u, v)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::texture::mipmap::Level;
    use crate::texture::{Mapping2D, Texture};
    use lumis_math::Rgb;

    fn geom() -> SurfaceGeom {
        SurfaceGeom {
            p: Vec3::ZERO,
            ng: Vec3::Z,
            ns: Vec3::Z,
            dpdu: Vec3::X,
            dpdv: Vec3::Y,
            uv: Vec2::new(0.3, 0.4),
        }
    }

    #[test]
    fn flat_normal_map_keeps_the_frame_and_a_tilted_one_tilts_it() {
        let mut t = Textures::default();
        let flat = Rgb::new(0.5, 0.5, 1.0);
        let tilted = Rgb::new(0.5 + 0.5 * 0.6, 0.5, 0.5 + 0.5 * 0.8);
        for c in [flat, tilted] {
            t.normal_maps.push(Level {
                width: 1,
                height: 1,
                texels: vec![c],
            });
        }
        let g = geom();
        let c = TexCtx::at(g.p, g.ns, g.uv);
        let (n0, u0) = Shading::NormalMap(0).apply(&t, &g, &c);
        assert!((n0 - Vec3::Z).length() < 1e-6 && (u0 - Vec3::X).length() < 1e-6);
        let (n1, _) = Shading::NormalMap(1).apply(&t, &g, &c);
        assert!((n1 - Vec3::new(0.6, 0.0, 0.8)).length() < 1e-5, "{n1:?}");
    }

    #[test]
    fn bump_of_a_linear_ramp_tilts_the_normal_by_its_slope() {
        // displacement = 0.5 u on a plane with dp/du = x: normal ~ (-0.5, 0, 1).
        let mut t = Textures::default();
        let ramp = t.push(Texture::Image(crate::texture::ImageTexture {
            mipmap: 0,
            mapping: Mapping2D::Uv {
                su: 1.0,
                sv: 1.0,
                du: 0.0,
                dv: 0.0,
            },
            filter: crate::texture::FilterKind::Bilinear,
            wrap: WrapMode::Clamp,
            scale: 1.0,
            invert: false,
            float: true,
        }));
        // A 256-texel horizontal ramp 0 .. 0.5 (exactly linear between texel centres).
        let n = 256;
        t.mipmaps.push(crate::texture::MipMap::new(Level {
            width: n,
            height: 1,
            texels: (0..n)
                .map(|i| Rgb::splat(0.5 * (i as f32 + 0.5) / n as f32))
                .collect(),
        }));
        let g = geom();
        let c = TexCtx::at(g.p, g.ns, g.uv);
        let (ns, _) = Shading::Bump(TexFloat::Tex(ramp)).apply(&t, &g, &c);
        let want = Vec3::new(-0.5, 0.0, 1.0).normalize();
        assert!((ns - want).length() < 1e-3, "{ns:?}");
    }
}
