use super::mapping::Mapping3D;
use super::noise::fbm;
use super::TexCtx;
use lumis_math::Rgb;

/// pbrt-v4's `marble` (a spectrum texture): bands along the texture-space
/// `y` axis, `t = 0.5 + 0.5 sin(y + variation * fBm)` (point scaled by
/// `scale`), coloured by a piecewise cubic Bezier spline through pbrt's nine
/// grey-blue control colours, times 1.5.
#[derive(Clone, Copy, Debug)]
pub struct MarbleTexture {
    pub mapping: Mapping3D,
    pub octaves: u32,
    pub omega: f32,
    pub scale: f32,
    pub variation: f32,
}

const COLORS: [[f32; 3]; 9] = [
    [0.58, 0.58, 0.6],
    [0.58, 0.58, 0.6],
    [0.58, 0.58, 0.6],
    [0.5, 0.5, 0.5],
    [0.6, 0.59, 0.58],
    [0.58, 0.58, 0.6],
    [0.58, 0.58, 0.6],
    [0.2, 0.2, 0.33],
    [0.58, 0.58, 0.6],
];

/// The colour spline at `t` in [0, 1]: segment `i` is the cubic Bezier with
/// control points `COLORS[i..i + 4]`, evaluated by de Casteljau.
pub fn marble_spline(t: f32) -> Rgb {
    let n_seg = COLORS.len() - 3;
    let first = ((t * n_seg as f32).floor().max(0.0) as usize).min(n_seg - 1);
    let u = t * n_seg as f32 - first as f32;
    let c = |i: usize| Rgb::new(COLORS[i][0], COLORS[i][1], COLORS[i][2]);
    let lerp = |a: Rgb, b: Rgb| a * (1.0 - u) + b * u;
    let (c0, c1, c2, c3) = (c(first), c(first + 1), c(first + 2), c(first + 3));
    let (s0, s1, s2) = (lerp(c0, c1), lerp(c1, c2), lerp(c2, c3));
    let (s0, s1) = (lerp(s0, s1), lerp(s1, s2));
    lerp(s0, s1)
}

impl MarbleTexture {
    pub fn eval(&self, c: &TexCtx) -> Rgb {
        let m = self.mapping.map(c);
        let p = m.p * self.scale;
        let (dx, dy) = (m.dpdx * self.scale, m.dpdy * self.scale);
        let marble = p.y + self.variation * fbm(p, dx, dy, self.omega, self.octaves);
        let t = 0.5 + 0.5 * marble.sin();
        // pbrt-v4 reads the result as an albedo: clamped to [0, 1].
        (marble_spline(t) * 1.5).map(|v| v.clamp(0.0, 1.0))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::{Transform, Vec2, Vec3};

    #[test]
    fn spline_ends_and_joins() {
        let c = |i: usize| Rgb::new(COLORS[i][0], COLORS[i][1], COLORS[i][2]);
        // Six overlapping segments (segment i: colours i..=i+3); a Bezier
        // segment starts at its first control point and ends at its last:
        // t = 0 gives colour 0, t = 1 colour 8, t = 1/6 (start of segment 1)
        // colour 1.
        let close = |a: Rgb, b: Rgb| (0..3).all(|k| (a[k] - b[k]).abs() < 1e-6);
        assert!(close(marble_spline(0.0), c(0)));
        assert!(close(marble_spline(1.0), c(8)));
        assert!(
            close(marble_spline(1.0 / 6.0), c(1)),
            "{:?}",
            marble_spline(1.0 / 6.0)
        );
        // Middle of segment 3 (control points 3..=6): (c3 + 3 c4 + 3 c5 + c6) / 8.
        let want = (c(3) + c(4) * 3.0 + c(5) * 3.0 + c(6)) * 0.125;
        assert!(close(marble_spline(3.5 / 6.0), want));
    }

    #[test]
    fn bands_follow_y_and_stay_in_range() {
        let m = MarbleTexture {
            mapping: Mapping3D {
                tex_from_world: Transform::IDENTITY,
            },
            octaves: 8,
            omega: 0.5,
            scale: 1.0,
            variation: 0.0,
        };
        // Without variation, the colour depends on sin(y) only.
        for y in [0.0f32, 0.7, 2.0, -1.3] {
            let a = m.eval(&TexCtx::at(Vec3::new(0.1, y, 0.2), Vec3::Z, Vec2::ZERO));
            let b = m.eval(&TexCtx::at(Vec3::new(5.3, y, -3.0), Vec3::Z, Vec2::ZERO));
            let want = marble_spline(0.5 + 0.5 * y.sin()) * 1.5;
            assert_eq!(a, b);
            assert!((0..3).all(|k| (a[k] - want[k]).abs() < 1e-6));
        }
        let m = MarbleTexture {
            variation: 0.2,
            ..m
        };
        let mut rng = lumis_math::Pcg32::new(2, 2);
        for _ in 0..1000 {
            let p = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32()) * 20.0;
            let v = m.eval(&TexCtx::at(p, Vec3::Z, Vec2::ZERO));
            assert!((0..3).all(|k| (0.3..=0.9 + 1e-6).contains(&v[k])), "{v:?}");
        }
    }
}
