use super::mapping::Mapping3D;
use super::noise::fbm;
use super::TexCtx;
use lumis_math::Rgb;

/// pbrt-v4's `windy` (a float texture; as a spectrum, grey as in pbrt-v3):
/// waves whose height (6 octaves of fBm) is scaled by a slowly varying wind
/// strength (3 octaves of fBm at a tenth of the frequency).
#[derive(Clone, Copy, Debug)]
pub struct WindyTexture {
    pub mapping: Mapping3D,
}

impl WindyTexture {
    pub fn eval(&self, c: &TexCtx) -> Rgb {
        let m = self.mapping.map(c);
        let wind = fbm(m.p * 0.1, m.dpdx * 0.1, m.dpdy * 0.1, 0.5, 3);
        let wave = fbm(m.p, m.dpdx, m.dpdy, 0.5, 6);
        Rgb::splat(wind.abs() * wave)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::{Transform, Vec2, Vec3};

    #[test]
    fn windy_is_wind_strength_times_wave_height() {
        let w = WindyTexture {
            mapping: Mapping3D {
                tex_from_world: Transform::IDENTITY,
            },
        };
        let at = |p: Vec3| w.eval(&TexCtx::at(p, Vec3::Z, Vec2::ZERO)).r;
        let p = Vec3::new(1.3, -0.4, 2.9);
        let wind = fbm(p * 0.1, Vec3::ZERO, Vec3::ZERO, 0.5, 3);
        let wave = fbm(p, Vec3::ZERO, Vec3::ZERO, 0.5, 6);
        assert!((at(p) - wind.abs() * wave).abs() < 1e-6);
        // The origin is a lattice point of every octave: zero.
        assert_eq!(at(Vec3::ZERO), 0.0);
    }
}
