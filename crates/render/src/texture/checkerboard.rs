use super::mapping::{Mapping2D, Mapping3D};
use super::{TexCtx, TexRgb, Textures};
use lumis_math::Rgb;

/// pbrt-v4's `checkerboard`: `tex1` on squares (2D, over a 2D mapping) or
/// cubes (3D, `dimension 3`, in the texture's own space) whose integer
/// coordinates sum to an even number, `tex2` on the others, box-filtered
/// over the footprint (closed-form integral of the checkerboard against a box).
#[derive(Clone, Copy, Debug)]
pub struct CheckerboardTexture {
    pub mapping: Mapping2D,
    /// Set for the 3D checkerboard (then `mapping` is unused).
    pub map3d: Option<Mapping3D>,
    pub tex1: TexRgb,
    pub tex2: TexRgb,
}

impl CheckerboardTexture {
    /// Weight of `tex2`.
    fn weight(&self, c: &TexCtx) -> f32 {
        let r = |a: f32, b: f32| 1.5 * a.abs().max(b.abs());
        if let Some(m) = self.map3d {
            let tc = m.map(c);
            let (p, dx, dy) = (tc.p, tc.dpdx, tc.dpdy);
            let s = filtered_sign(p.x, r(dx.x, dy.x))
                * filtered_sign(p.y, r(dx.y, dy.y))
                * filtered_sign(p.z, r(dx.z, dy.z));
            return 0.5 - 0.5 * s;
        }
        let tc = self.mapping.map(c);
        let ds = r(tc.dst_dx.x, tc.dst_dy.x);
        let dt = r(tc.dst_dx.y, tc.dst_dy.y);
        0.5 - filtered_sign(tc.st.x, ds) * filtered_sign(tc.st.y, dt) * 0.5
    }

    pub fn eval(&self, t: &Textures, c: &TexCtx) -> Rgb {
        let w = self.weight(c);
        let a = if w < 1.0 {
            self.tex1.eval(t, c)
        } else {
            Rgb::BLACK
        };
        let b = if w > 0.0 {
            self.tex2.eval(t, c)
        } else {
            Rgb::BLACK
        };
        a * (1.0 - w) + b * w
    }
}

/// Mean over `[x - r, x + r]` of the square wave that is +1 on even unit
/// intervals and -1 on odd ones.
pub fn filtered_sign(x: f32, r: f32) -> f32 {
    if (x - r).floor() == (x + r).floor() {
        return if (x.floor() as i64).rem_euclid(2) == 0 {
            1.0
        } else {
            -1.0
        };
    }
    // Antiderivative of the square wave: a triangle wave of period 2.
    let prim = |x: f32| {
        let m = x.rem_euclid(2.0);
        if m < 1.0 {
            m
        } else {
            2.0 - m
        }
    };
    (prim(x + r) - prim(x - r)) / (2.0 * r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cubes_in_3d() {
        use lumis_math::{Transform, Vec2, Vec3};
        let c = CheckerboardTexture {
            mapping: Mapping2D::Uv {
                su: 1.0,
                sv: 1.0,
                du: 0.0,
                dv: 0.0,
            },
            map3d: Some(Mapping3D {
                tex_from_world: Transform::IDENTITY,
            }),
            tex1: TexRgb::Const(Rgb::splat(1.0)),
            tex2: TexRgb::Const(Rgb::splat(0.0)),
        };
        let t = Textures::default();
        let at = |x: f32, y: f32, z: f32| {
            c.eval(&t, &TexCtx::at(Vec3::new(x, y, z), Vec3::Z, Vec2::ZERO))
                .r
        };
        assert_eq!(at(0.5, 0.5, 0.5), 1.0);
        assert_eq!(at(1.5, 0.5, 0.5), 0.0);
        assert_eq!(at(1.5, 1.5, 0.5), 1.0);
        assert_eq!(at(1.5, 1.5, 1.5), 0.0);
        assert_eq!(at(-0.5, 0.5, 0.5), 0.0);
    }

    #[test]
    fn filtered_sign_is_the_box_mean_of_the_square_wave() {
        assert_eq!(filtered_sign(0.5, 0.1), 1.0);
        assert_eq!(filtered_sign(1.5, 0.1), -1.0);
        assert_eq!(filtered_sign(-0.5, 0.1), -1.0);
        // Straddling the edge at 1 symmetrically: mean 0.
        assert!(filtered_sign(1.0, 0.25).abs() < 1e-5);
        // [0.75, 1.25]: a quarter at +1, a quarter at -1 -> 0; [0.5, 1.25]: (0.5 - 0.25) / 0.75.
        assert!((filtered_sign(0.875, 0.375) - 1.0 / 3.0).abs() < 1e-5);
        // Numerical check over many points.
        for i in 0..50 {
            let x = -3.0 + i as f32 * 0.137;
            let r = 0.05 + 0.03 * i as f32;
            let n = 20000;
            let mut s = 0.0f64;
            for k in 0..n {
                let xx = x - r + 2.0 * r * (k as f32 + 0.5) / n as f32;
                s += if (xx.floor() as i64).rem_euclid(2) == 0 {
                    1.0
                } else {
                    -1.0
                };
            }
            let num = (s / n as f64) as f32;
            assert!((filtered_sign(x, r) - num).abs() < 2e-3, "x {x} r {r}");
        }
    }
}
