use super::mapping::Mapping2D;
use super::TexCtx;
use lumis_math::Rgb;

/// pbrt-v4's `bilerp`: bilinear interpolation of four corner values over the
/// mapped `(s, t)`: `v00` at (0, 0), `v10` at (1, 0), `v01` at (0, 1), `v11`
/// at (1, 1) (extrapolated outside the unit square, as pbrt-v4 does).
#[derive(Clone, Copy, Debug)]
pub struct BilerpTexture {
    pub mapping: Mapping2D,
    pub v00: Rgb,
    pub v01: Rgb,
    pub v10: Rgb,
    pub v11: Rgb,
}

impl BilerpTexture {
    pub fn eval(&self, c: &TexCtx) -> Rgb {
        let st = self.mapping.map(c).st;
        let (s, t) = (st.x, st.y);
        self.v00 * ((1.0 - s) * (1.0 - t))
            + self.v10 * (s * (1.0 - t))
            + self.v01 * ((1.0 - s) * t)
            + self.v11 * (s * t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::{Vec2, Vec3};

    #[test]
    fn corners_and_centre() {
        let b = BilerpTexture {
            mapping: Mapping2D::Uv {
                su: 1.0,
                sv: 1.0,
                du: 0.0,
                dv: 0.0,
            },
            v00: Rgb::new(1.0, 0.0, 0.0),
            v01: Rgb::new(0.0, 1.0, 0.0),
            v10: Rgb::new(0.0, 0.0, 1.0),
            v11: Rgb::splat(2.0),
        };
        let at = |u, v| b.eval(&TexCtx::at(Vec3::ZERO, Vec3::Z, Vec2::new(u, v)));
        assert_eq!(at(0.0, 0.0), b.v00);
        assert_eq!(at(0.0, 1.0), b.v01);
        assert_eq!(at(1.0, 0.0), b.v10);
        assert_eq!(at(1.0, 1.0), b.v11);
        // Centre: the mean of the corners; (0.25, 0.5): by hand.
        assert_eq!(at(0.5, 0.5), Rgb::new(0.75, 0.75, 0.75));
        let q = at(0.25, 0.5);
        let want = Rgb::new(0.375 + 0.25, 0.375 + 0.25, 0.125 + 0.25);
        assert!((0..3).all(|k| (q[k] - want[k]).abs() < 1e-6), "{q:?}");
    }
}
