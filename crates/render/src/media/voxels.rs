//! Voxel grids as pbrt-v4 samples them, and the coarse grid of majorants a
//! ray walks through.
//!
//! A [`Voxels`] grid holds `nx * ny * nz` samples over the unit cube (x
//! fastest); a point is interpolated trilinearly between the samples at
//! voxel centres, samples outside the grid counting as zero (so values fade
//! to half at the cube's faces, as in pbrt-v4's `SampledGrid`).

use lumis_math::Vec3;

#[derive(Clone, Debug, PartialEq)]
pub struct Voxels<T> {
    pub n: [usize; 3],
    pub values: Vec<T>,
}

/// What a grid may hold: numbers and colours, added and scaled.
pub trait Sample: Copy + Default {
    fn lerp(a: Self, b: Self, t: f32) -> Self;
    /// The largest component (for majorants).
    fn max_value(self) -> f32;
}

impl Sample for f32 {
    fn lerp(a: f32, b: f32, t: f32) -> f32 {
        a + (b - a) * t
    }
    fn max_value(self) -> f32 {
        self
    }
}

impl Sample for lumis_math::Rgb {
    fn lerp(a: Self, b: Self, t: f32) -> Self {
        a + (b - a) * t
    }
    fn max_value(self) -> f32 {
        self.max_component()
    }
}

impl<T: Sample> Voxels<T> {
    fn at(&self, x: i64, y: i64, z: i64) -> T {
        let [nx, ny, nz] = self.n.map(|v| v as i64);
        if x < 0 || y < 0 || z < 0 || x >= nx || y >= ny || z >= nz {
            return T::default();
        }
        self.values[((z * ny + y) * nx + x) as usize]
    }

    /// The value at `p` in the unit cube.
    pub fn lookup(&self, p: Vec3) -> T {
        let s = [p.x, p.y, p.z];
        let mut i = [0i64; 3];
        let mut d = [0f32; 3];
        for k in 0..3 {
            let c = s[k] * self.n[k] as f32 - 0.5;
            let f = c.floor();
            i[k] = f as i64;
            d[k] = c - f;
        }
        let lx = |y: i64, z: i64| T::lerp(self.at(i[0], y, z), self.at(i[0] + 1, y, z), d[0]);
        let ly = |z: i64| T::lerp(lx(i[1], z), lx(i[1] + 1, z), d[1]);
        T::lerp(ly(i[2]), ly(i[2] + 1), d[2])
    }

    /// An upper bound of [`Voxels::lookup`] over the box `[lo, hi]` of the
    /// unit cube: the largest sample that can weigh on a point in it.
    pub fn max_over(&self, lo: Vec3, hi: Vec3) -> f32 {
        let (lo, hi) = ([lo.x, lo.y, lo.z], [hi.x, hi.y, hi.z]);
        let mut r = [(0i64, 0i64); 3];
        for k in 0..3 {
            let n = self.n[k] as i64;
            let a = ((lo[k] * n as f32 - 0.5).floor() as i64).max(0);
            let b = ((hi[k] * n as f32 - 0.5).floor() as i64 + 1).min(n - 1);
            r[k] = (a, b);
        }
        let mut m = 0.0f32;
        for z in r[2].0..=r[2].1 {
            for y in r[1].0..=r[1].1 {
                for x in r[0].0..=r[0].1 {
                    m = m.max(self.at(x, y, z).max_value());
                }
            }
        }
        m
    }
}

/// Majorants on a coarse grid over the unit cube, walked voxel by voxel.
#[derive(Clone, Debug, PartialEq)]
pub struct Majorants {
    pub res: usize,
    pub values: Vec<f32>,
}

impl Majorants {
    /// `res`^3 cells, each `bound(lo, hi)` over its box.
    pub fn build(res: usize, bound: impl Fn(Vec3, Vec3) -> f32) -> Majorants {
        let mut values = Vec::with_capacity(res * res * res);
        let s = 1.0 / res as f32;
        for z in 0..res {
            for y in 0..res {
                for x in 0..res {
                    let lo = Vec3::new(x as f32, y as f32, z as f32) * s;
                    values.push(bound(lo, lo + Vec3::splat(s)));
                }
            }
        }
        Majorants { res, values }
    }

    /// [`Majorants::walk`] for a world-space ray, carried into the unit
    /// cube by `unit_from_world` (distances along it are unchanged).
    pub fn walk_ray(
        &self,
        unit_from_world: &lumis_math::Transform,
        o: Vec3,
        d: Vec3,
        tmax: f32,
        f: impl FnMut(f32, f32, f32) -> bool,
    ) -> bool {
        self.walk(unit_from_world.point(o), unit_from_world.vector(d), tmax, f)
    }

    /// Calls `f(t0, t1, majorant)` for each cell the ray `o + t d` (unit-cube
    /// coordinates) crosses within `[0, tmax)`, in order, until `f` returns
    /// false. Returns whether the walk reached its end.
    pub fn walk(
        &self,
        o: Vec3,
        d: Vec3,
        tmax: f32,
        mut f: impl FnMut(f32, f32, f32) -> bool,
    ) -> bool {
        let (oa, da) = ([o.x, o.y, o.z], [d.x, d.y, d.z]);
        // Clip to the unit cube.
        let (mut t0, mut t1) = (0.0f32, tmax);
        for k in 0..3 {
            if da[k] == 0.0 {
                if oa[k] < 0.0 || oa[k] > 1.0 {
                    return true;
                }
                continue;
            }
            let (a, b) = ((0.0 - oa[k]) / da[k], (1.0 - oa[k]) / da[k]);
            let (a, b) = if a < b { (a, b) } else { (b, a) };
            t0 = t0.max(a);
            t1 = t1.min(b);
        }
        if !(t0 < t1) {
            return true;
        }
        let n = self.res as i64;
        let p = o + d * t0;
        let pa = [p.x, p.y, p.z];
        let mut cell = [0i64; 3];
        let mut next = [f32::INFINITY; 3];
        let mut step = [0i64; 3];
        let mut delta = [f32::INFINITY; 3];
        for k in 0..3 {
            cell[k] = ((pa[k] * n as f32) as i64).clamp(0, n - 1);
            if da[k] > 0.0 {
                step[k] = 1;
                next[k] = t0 + ((cell[k] + 1) as f32 / n as f32 - pa[k]) / da[k];
                delta[k] = 1.0 / (n as f32 * da[k]);
            } else if da[k] < 0.0 {
                step[k] = -1;
                next[k] = t0 + (cell[k] as f32 / n as f32 - pa[k]) / da[k];
                delta[k] = -1.0 / (n as f32 * da[k]);
            }
        }
        let mut t = t0;
        loop {
            let k = if next[0] < next[1] && next[0] < next[2] {
                0
            } else if next[1] < next[2] {
                1
            } else {
                2
            };
            let end = next[k].min(t1);
            let m = self.values[((cell[2] * n + cell[1]) * n + cell[0]) as usize];
            if end > t && !f(t, end, m) {
                return false;
            }
            if end >= t1 {
                return true;
            }
            t = end;
            cell[k] += step[k];
            if cell[k] < 0 || cell[k] >= n {
                return true;
            }
            next[k] += delta[k];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lookup_interpolates_between_voxel_centres() {
        let g = Voxels {
            n: [2, 1, 1],
            values: vec![1.0f32, 3.0],
        };
        // Centres at x = 0.25 and 0.75; half a voxel outside fades to half.
        assert!((g.lookup(Vec3::new(0.25, 0.5, 0.5)) - 1.0).abs() < 1e-6);
        assert!((g.lookup(Vec3::new(0.5, 0.5, 0.5)) - 2.0).abs() < 1e-6);
        assert!((g.lookup(Vec3::new(1.0, 0.5, 0.5)) - 1.5).abs() < 1e-6);
        assert_eq!(g.max_over(Vec3::ZERO, Vec3::new(0.2, 1.0, 1.0)), 1.0);
        assert_eq!(g.max_over(Vec3::ZERO, Vec3::splat(1.0)), 3.0);
    }

    #[test]
    fn walk_covers_the_clipped_ray_in_order() {
        let m = Majorants::build(4, |lo, _| lo.x);
        let mut segs = Vec::new();
        let done = m.walk(
            Vec3::new(-1.0, 0.3, 0.6),
            Vec3::new(1.0, 0.0, 0.0),
            10.0,
            |a, b, v| {
                segs.push((a, b, v));
                true
            },
        );
        assert!(done);
        assert_eq!(segs.len(), 4);
        assert!((segs[0].0 - 1.0).abs() < 1e-6 && (segs[3].1 - 2.0).abs() < 1e-6);
        for w in segs.windows(2) {
            assert!((w[0].1 - w[1].0).abs() < 1e-6 && w[1].2 > w[0].2);
        }
        // A diagonal ray's segments tile its chord exactly.
        let d = Vec3::new(0.31, 0.57, -0.23);
        let mut len = 0.0;
        let mut last: Option<f32> = None;
        m.walk(Vec3::new(0.1, 0.05, 0.9), d, 100.0, |a, b, _| {
            if let Some(l) = last {
                assert!((a - l).abs() < 1e-5);
            }
            last = Some(b);
            len += b - a;
            true
        });
        assert!(len > 0.5, "{len}");
    }
}
