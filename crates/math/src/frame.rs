//! Orthonormal frames: local shading space has the normal along +z.

use crate::Vec3;

#[derive(Clone, Copy, Debug)]
pub struct Frame {
    pub s: Vec3,
    pub t: Vec3,
    pub n: Vec3,
}

impl Frame {
    /// A frame around unit vector `n` (Duff et al. 2017, branchless).
    pub fn from_normal(n: Vec3) -> Frame {
        let sign = 1.0f32.copysign(n.z);
        let a = -1.0 / (sign + n.z);
        let b = n.x * n.y * a;
        let s = Vec3::new(1.0 + sign * n.x * n.x * a, sign * b, -sign * n.x);
        let t = Vec3::new(b, sign + n.y * n.y * a, -n.y);
        Frame { s, t, n }
    }

    /// A frame with normal `n` whose first tangent follows `dpdu` as closely as possible.
    pub fn from_normal_tangent(n: Vec3, dpdu: Vec3) -> Frame {
        let s = dpdu - n * n.dot(dpdu);
        let len = s.length();
        if len <= 1e-8 || !len.is_finite() {
            return Frame::from_normal(n);
        }
        let s = s / len;
        Frame {
            s,
            t: n.cross(s),
            n,
        }
    }

    #[inline]
    pub fn to_local(&self, v: Vec3) -> Vec3 {
        Vec3::new(v.dot(self.s), v.dot(self.t), v.dot(self.n))
    }

    #[inline]
    pub fn to_world(&self, v: Vec3) -> Vec3 {
        self.s * v.x + self.t * v.y + self.n * v.z
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn frame_is_orthonormal(x in -1.0f32..1.0, y in -1.0f32..1.0, z in -1.0f32..1.0) {
            let v = Vec3::new(x, y, z);
            prop_assume!(v.length() > 1e-3);
            let n = v.normalize();
            let f = Frame::from_normal(n);
            prop_assert!((f.s.length() - 1.0).abs() < 1e-4);
            prop_assert!((f.t.length() - 1.0).abs() < 1e-4);
            prop_assert!(f.s.dot(f.t).abs() < 1e-4);
            prop_assert!(f.s.dot(n).abs() < 1e-4);
            let w = Vec3::new(0.3, -0.2, 0.9);
            prop_assert!((f.to_world(f.to_local(w)) - w).length() < 1e-4);
        }
    }
}
