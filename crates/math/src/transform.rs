//! Affine/projective transforms with cached inverse, as in pbrt.

use crate::{Mat3, Mat4, Vec3};

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Transform {
    pub m: Mat4,
    pub inv: Mat4,
}

impl Default for Transform {
    fn default() -> Self {
        Transform::IDENTITY
    }
}

impl Transform {
    pub const IDENTITY: Transform = Transform {
        m: Mat4::IDENTITY,
        inv: Mat4::IDENTITY,
    };

    /// From a matrix; `None` if it is singular.
    pub fn new(m: Mat4) -> Option<Transform> {
        let det = m.determinant();
        if det == 0.0 || !det.is_finite() {
            return None;
        }
        Some(Transform {
            m,
            inv: m.inverse(),
        })
    }

    pub fn inverse(&self) -> Transform {
        Transform {
            m: self.inv,
            inv: self.m,
        }
    }

    /// `self * other`: applies `other` first.
    pub fn compose(&self, other: &Transform) -> Transform {
        Transform {
            m: self.m * other.m,
            inv: other.inv * self.inv,
        }
    }

    #[inline]
    pub fn point(&self, p: Vec3) -> Vec3 {
        self.m.project_point3(p)
    }

    #[inline]
    pub fn vector(&self, v: Vec3) -> Vec3 {
        self.m.transform_vector3(v)
    }

    /// Normals transform by the inverse transpose.
    #[inline]
    pub fn normal(&self, n: Vec3) -> Vec3 {
        Mat3::from_mat4(self.inv).transpose() * n
    }

    /// True when the transform flips handedness (negative determinant of the 3x3 part).
    pub fn swaps_handedness(&self) -> bool {
        Mat3::from_mat4(self.m).determinant() < 0.0
    }

    /// Whether the last row is `(0, 0, 0, 1)`: no projection.
    pub fn is_affine(&self) -> bool {
        self.m.row(3) == crate::Vec4::new(0.0, 0.0, 0.0, 1.0)
    }
}

/// `s` if the linear map `m` is a rotation (or reflection) times a uniform
/// scale `s > 0`, to a relative `tol`: `s` is the cube root of the columns'
/// length product, each column's length within `tol s` of it and their
/// pairwise dot products under `tol s^2`.
pub fn uniform_scale(m: Mat3, tol: f32) -> Option<f32> {
    let (a, b, c) = (m.x_axis, m.y_axis, m.z_axis);
    let (la, lb, lc) = (a.length(), b.length(), c.length());
    let s = (la * lb * lc).cbrt();
    let t2 = tol * s * s;
    let orthogonal = a.dot(b).abs() < t2 && a.dot(c).abs() < t2 && b.dot(c).abs() < t2;
    let uniform = (la - s).abs() < tol * s && (lb - s).abs() < tol * s;
    (s > 0.0 && orthogonal && uniform).then_some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normal_stays_perpendicular_under_nonuniform_scale() {
        let t = Transform::new(Mat4::from_scale(Vec3::new(2.0, 1.0, 0.5))).unwrap();
        let tangent = Vec3::new(1.0, 1.0, 0.0);
        let n = Vec3::new(1.0, -1.0, 0.0);
        assert!(t.vector(tangent).dot(t.normal(n)).abs() < 1e-6);
    }

    #[test]
    fn singular_is_refused() {
        assert!(Transform::new(Mat4::from_scale(Vec3::new(0.0, 1.0, 1.0))).is_none());
    }
}
