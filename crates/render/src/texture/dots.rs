use super::mapping::Mapping2D;
use super::noise::noise2;
use super::{TexCtx, TexRgb, Textures};
use lumis_math::{Rgb, Vec2};

/// pbrt-v4's `dots`: polka dots of radius 0.35 on the unit cells of the
/// mapped `(s, t)` around integer points; noise decides which cells have a
/// dot and shifts each dot's centre by up to 0.15. `inside` on the dots,
/// `outside` elsewhere. (pbrt-v4's own code passes the two textures to its
/// constructor in swapped order, so there `inside` shows outside the dots;
/// lumis follows the parameters' documented meaning.)
#[derive(Clone, Copy, Debug)]
pub struct DotsTexture {
    pub mapping: Mapping2D,
    pub inside: TexRgb,
    pub outside: TexRgb,
}

const RADIUS: f32 = 0.35;

/// `st` lies on a dot.
pub fn inside_polka_dot(st: Vec2) -> bool {
    let s_cell = (st.x + 0.5).floor();
    let t_cell = (st.y + 0.5).floor();
    if noise2(s_cell + 0.5, t_cell + 0.5) <= 0.0 {
        return false;
    }
    let max_shift = 0.5 - RADIUS;
    let s_center = s_cell + max_shift * noise2(s_cell + 1.5, t_cell + 2.8);
    let t_center = t_cell + max_shift * noise2(s_cell + 4.5, t_cell + 9.8);
    (st - Vec2::new(s_center, t_center)).length_squared() < RADIUS * RADIUS
}

impl DotsTexture {
    pub fn eval(&self, t: &Textures, c: &TexCtx) -> Rgb {
        if inside_polka_dot(self.mapping.map(c).st) {
            self.inside.eval(t, c)
        } else {
            self.outside.eval(t, c)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dots_sit_in_the_cells_noise_selects() {
        let (mut with, mut without) = (0, 0);
        for i in -10..10 {
            for j in -10..10 {
                let (s, t) = (i as f32, j as f32);
                let has_dot = noise2(s + 0.5, t + 0.5) > 0.0;
                // The dot's centre is within 0.15 of the lattice point, so
                // the point itself is inside the dot exactly when there is one.
                assert_eq!(inside_polka_dot(Vec2::new(s, t)), has_dot, "{i} {j}");
                // 0.49 from the lattice point along both axes (distance 0.69,
                // or 0.49 - 0.15 along each axis at best): never on a dot.
                assert!(!inside_polka_dot(Vec2::new(s + 0.49, t + 0.49)));
                if has_dot {
                    with += 1;
                } else {
                    without += 1;
                }
            }
        }
        assert!(with > 50 && without > 50, "{with} {without}");
    }

    #[test]
    fn inside_and_outside_textures() {
        use lumis_math::Vec3;
        let d = DotsTexture {
            mapping: Mapping2D::Uv {
                su: 1.0,
                sv: 1.0,
                du: 0.0,
                dv: 0.0,
            },
            inside: TexRgb::Const(Rgb::splat(0.9)),
            outside: TexRgb::Const(Rgb::splat(0.1)),
        };
        let t = Textures::default();
        let mut seen = [false; 2];
        for i in 0..10 {
            let uv = Vec2::new(i as f32, 3.0);
            let v = d.eval(&t, &TexCtx::at(Vec3::ZERO, Vec3::Z, uv)).r;
            let inside = inside_polka_dot(uv);
            assert_eq!(v, if inside { 0.9 } else { 0.1 });
            seen[inside as usize] = true;
        }
        assert!(seen[0] && seen[1]);
    }
}
