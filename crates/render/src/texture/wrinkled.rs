use super::mapping::Mapping3D;
use super::noise::turbulence;
use super::TexCtx;
use lumis_math::Rgb;

/// pbrt-v4's `wrinkled` (a float texture; as a spectrum, grey as in
/// pbrt-v3): turbulence, the sum of `|noise|` octaves, of the point in
/// texture space.
#[derive(Clone, Copy, Debug)]
pub struct WrinkledTexture {
    pub mapping: Mapping3D,
    pub octaves: u32,
    pub omega: f32,
}

impl WrinkledTexture {
    pub fn eval(&self, c: &TexCtx) -> Rgb {
        let m = self.mapping.map(c);
        Rgb::splat(turbulence(m.p, m.dpdx, m.dpdy, self.omega, self.octaves))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::{Transform, Vec2, Vec3};

    #[test]
    fn wrinkled_is_turbulence_in_texture_space() {
        // A texture space scaled by 2: the texture at p is turbulence at 2p.
        let to_tex = Transform::new(lumis_math::Mat4::from_scale(Vec3::splat(2.0))).unwrap();
        let w = WrinkledTexture {
            mapping: Mapping3D {
                tex_from_world: to_tex,
            },
            octaves: 5,
            omega: 0.6,
        };
        let p = Vec3::new(0.31, 0.77, -0.18);
        let v = w.eval(&TexCtx::at(p, Vec3::Z, Vec2::ZERO)).r;
        let want = turbulence(p * 2.0, Vec3::ZERO, Vec3::ZERO, 0.6, 5);
        assert!((v - want).abs() < 1e-6 && v > 0.0, "{v} {want}");
    }
}
