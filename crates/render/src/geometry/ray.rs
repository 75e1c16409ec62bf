use lumis_math::Vec3;

#[derive(Clone, Copy, Debug)]
pub struct Ray {
    pub o: Vec3,
    pub d: Vec3,
    pub tmax: f32,
}

impl Ray {
    #[inline]
    pub fn new(o: Vec3, d: Vec3) -> Ray {
        Ray {
            o,
            d,
            tmax: f32::INFINITY,
        }
    }
    #[inline]
    pub fn at(&self, t: f32) -> Vec3 {
        self.o + t * self.d
    }
}

/// Moves a hit point off its surface along `n` (oriented to the side the new
/// ray leaves from) by a few ULPs, so the new ray cannot re-hit the surface it
/// starts on (Wächter & Binder, Ray Tracing Gems ch. 6). Works at any scale.
#[inline]
pub fn offset_ray_origin(p: Vec3, n: Vec3) -> Vec3 {
    const ORIGIN: f32 = 1.0 / 32.0;
    const FLOAT_SCALE: f32 = 1.0 / 65536.0;
    const INT_SCALE: f32 = 256.0;
    let off = |pc: f32, nc: f32| -> f32 {
        if pc.abs() < ORIGIN {
            return pc + FLOAT_SCALE * nc;
        }
        let of_i = (INT_SCALE * nc) as i32;
        let bits = pc.to_bits() as i32;
        let moved = if pc < 0.0 { bits - of_i } else { bits + of_i };
        f32::from_bits(moved as u32)
    };
    Vec3::new(off(p.x, n.x), off(p.y, n.y), off(p.z, n.z))
}

/// Ray from `p` (on a surface with normal `ng`) in direction `d`, offset to the correct side.
#[inline]
pub fn spawn_ray(p: Vec3, ng: Vec3, d: Vec3) -> Ray {
    let n = if ng.dot(d) < 0.0 { -ng } else { ng };
    Ray::new(offset_ray_origin(p, n), d)
}

/// Ray from `p` towards `target` stopping just short of it (for shadow rays).
#[inline]
pub fn spawn_ray_to(p: Vec3, ng: Vec3, target: Vec3) -> Ray {
    let d0 = target - p;
    let n = if ng.dot(d0) < 0.0 { -ng } else { ng };
    let o = offset_ray_origin(p, n);
    let d = target - o;
    Ray {
        o,
        d,
        tmax: 1.0 - 1e-4,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn offset_moves_to_the_normal_side() {
        for &p in &[
            Vec3::new(1000.0, -3.0, 0.001),
            Vec3::new(-1e-6, 5.0, -200.0),
        ] {
            let n = Vec3::new(0.3, -0.5, 0.81).normalize();
            let q = offset_ray_origin(p, n);
            assert!((q - p).dot(n) > 0.0);
            assert!((q - p).length() < 1e-3 * (1.0 + p.length()));
        }
    }
}
