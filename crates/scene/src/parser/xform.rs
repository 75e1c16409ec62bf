//! Matrices for the transform directives (pbrt conventions, left-handed look-at).

use super::Builder;
use crate::lexer::{Token, TokenKind};
use crate::loc::Diagnostic;
use lumis_math::{Mat4, Transform, Vec3, Vec4};

impl Builder {
    /// Handles a transform directive; `Ok(false)` if `name` is not one.
    pub(super) fn transform_directive(
        &mut self,
        dir: &Token,
        name: &str,
        args: &[Token],
    ) -> Result<bool, Diagnostic> {
        let before = self.gs.ctm;
        match name {
            "ActiveTransform" => {
                let which = match args.first().map(|t| &t.kind) {
                    Some(TokenKind::Ident(w)) if args.len() == 1 => w.as_str(),
                    _ => {
                        return Err(Diagnostic::error(
                            &dir.loc,
                            "ActiveTransform expects StartTime, EndTime or All",
                        ))
                    }
                };
                let (start, end) = match which {
                    "StartTime" => (true, false),
                    "EndTime" => (false, true),
                    "All" => (true, true),
                    other => {
                        return Err(Diagnostic::error(
                            &args[0].loc,
                            format!(
                            "ActiveTransform expects StartTime, EndTime or All, found `{other}`"
                        ),
                        ))
                    }
                };
                self.gs.active_start = start;
                self.gs.active_end = end;
                return Ok(true);
            }
            "TransformTimes" => {
                // Shutter times of the two transforms: without motion blur they
                // change nothing (a differing end transform is warned about).
                Self::numbers(dir, name, args, 2)?;
                return Ok(true);
            }
            "Identity" => {
                Self::no_args(dir, name, args)?;
                self.gs.ctm = Transform::IDENTITY;
            }
            "Translate" => {
                let v = Self::numbers(dir, name, args, 3)?;
                self.concat(dir, Mat4::from_translation(Vec3::new(v[0], v[1], v[2])))?;
            }
            "Scale" => {
                let v = Self::numbers(dir, name, args, 3)?;
                self.concat(dir, Mat4::from_scale(Vec3::new(v[0], v[1], v[2])))?;
            }
            "Rotate" => {
                let v = Self::numbers(dir, name, args, 4)?;
                let m = rotate(v[0], Vec3::new(v[1], v[2], v[3])).ok_or_else(|| {
                    Diagnostic::error(&dir.loc, "Rotate: the rotation axis is zero")
                })?;
                self.concat(dir, m)?;
            }
            "LookAt" => {
                let v = Self::numbers(dir, name, args, 9)?;
                let p = |k: usize| Vec3::new(v[k], v[k + 1], v[k + 2]);
                let m = look_at(p(0), p(3), p(6))
                    .map_err(|e| Diagnostic::error(&dir.loc, format!("LookAt: {e}")))?;
                let t = Transform::new(m).ok_or_else(|| {
                    Diagnostic::error(&dir.loc, "LookAt: degenerate camera frame")
                })?;
                self.gs.ctm = self.gs.ctm.compose(&t.inverse());
            }
            "Transform" | "ConcatTransform" => {
                let v = Self::numbers(dir, name, args, 16)?;
                let arr: [f32; 16] = v.try_into().expect("16 numbers");
                let m = Mat4::from_cols_array(&arr);
                if name == "Transform" {
                    self.gs.ctm = Transform::IDENTITY;
                }
                self.concat(dir, m)?;
            }
            "CoordinateSystem" => {
                let (s, rest) = Self::strings(dir, name, args, 1, "CoordinateSystem \"name\"")?;
                Self::no_args(dir, name, rest)?;
                self.coord_systems.insert(s[0].0.clone(), self.gs.ctm);
                return Ok(true);
            }
            "CoordSysTransform" => {
                let (s, rest) = Self::strings(dir, name, args, 1, "CoordSysTransform \"name\"")?;
                Self::no_args(dir, name, rest)?;
                match self.coord_systems.get(&s[0].0) {
                    Some(t) => self.gs.ctm = *t,
                    None => self.warn(&s[0].1, format!("unknown coordinate system `{}`", s[0].0)),
                }
            }
            _ => return Ok(false),
        }
        if !(self.gs.active_start && self.gs.active_end) {
            self.warn_once(
                "motion",
                &dir.loc,
                "motion blur is not supported: start and end transforms differ (ActiveTransform); rendering the start-time transform",
            );
            if !self.gs.active_start {
                self.gs.ctm = before;
            }
        }
        Ok(true)
    }

    fn concat(&mut self, dir: &Token, m: Mat4) -> Result<(), Diagnostic> {
        let t = Transform::new(m).ok_or_else(|| {
            Diagnostic::error(&dir.loc, "this transformation is singular (not invertible)")
        })?;
        self.gs.ctm = self.gs.ctm.compose(&t);
        Ok(())
    }
}

/// Rotation by `deg` degrees about `axis`; `None` for a zero axis.
pub(super) fn rotate(deg: f32, axis: Vec3) -> Option<Mat4> {
    let a = axis.try_normalize()?;
    Some(Mat4::from_axis_angle(a, deg.to_radians()))
}

/// pbrt's look-at: the world-from-camera matrix whose columns are right, up,
/// viewing direction and eye. `Err` describes a degenerate input.
pub(super) fn look_at(eye: Vec3, look: Vec3, up: Vec3) -> Result<Mat4, &'static str> {
    let dir = (look - eye)
        .try_normalize()
        .ok_or("the eye and look-at points coincide")?;
    let up = up.try_normalize().ok_or("the up vector is zero")?;
    let right = up
        .cross(dir)
        .try_normalize()
        .ok_or("the up vector and the viewing direction are parallel")?;
    let new_up = dir.cross(right);
    Ok(Mat4::from_cols(
        right.extend(0.0),
        new_up.extend(0.0),
        dir.extend(0.0),
        Vec4::new(eye.x, eye.y, eye.z, 1.0),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotate_90_about_z_maps_x_to_y() {
        let m = rotate(90.0, Vec3::Z).unwrap();
        assert!((m.transform_vector3(Vec3::X) - Vec3::Y).length() < 1e-6);
        assert!(rotate(10.0, Vec3::ZERO).is_none());
    }

    #[test]
    fn look_at_down_minus_z() {
        // Eye at (0,0,5) looking at the origin, y up: dir = -z, right = up x dir = -x.
        let m = look_at(Vec3::new(0.0, 0.0, 5.0), Vec3::ZERO, Vec3::Y).unwrap();
        assert!((m.col(0).truncate() - Vec3::new(-1.0, 0.0, 0.0)).length() < 1e-6);
        assert!((m.col(1).truncate() - Vec3::Y).length() < 1e-6);
        assert!((m.col(2).truncate() - Vec3::new(0.0, 0.0, -1.0)).length() < 1e-6);
        assert_eq!(m.col(3), Vec4::new(0.0, 0.0, 5.0, 1.0));
        assert!(look_at(Vec3::ZERO, Vec3::Y, Vec3::Y).is_err());
        assert!(look_at(Vec3::ZERO, Vec3::ZERO, Vec3::Y).is_err());
    }
}
