//! Aiming caustic photons at perfectly specular objects (an equivalent of
//! Jensen's projection maps): caustic photons leave area, point and spot
//! lights only in the cones subtended by the bounding spheres of specular
//! shapes. Every caustic path starts with a hit on a specular shape, so
//! nothing is lost; each photon's flux is divided by the density it was
//! really sampled with, so photons no longer have equal power and the seed's
//! q_1 uses each photon's own flux (`N L_e cos DeltaA / (Phi alpha)` with
//! `Phi / N` replaced by the flux the photon carries).

use crate::geometry::Prim;
use crate::geometry::{offset_ray_origin, transform_box, Aabb, Ray};
use crate::light::{EmitCull, Light};
use crate::material::Material;
use crate::scene::{PrimInfo, Scene};
use lumis_math::sampling::{
    square_to_uniform_cone, square_to_uniform_sphere, uniform_cone_pdf, UNIFORM_SPHERE_PDF,
};
use lumis_math::{Frame, Rgb, Vec2, Vec3};
use std::collections::BTreeMap;

/// What a render's caustic photons head for (`aimcaustics`) and what
/// skips those that cannot reach a specular shape: found once per render,
/// since both read every primitive of the scene.
#[derive(Clone, Debug, Default)]
pub struct Aims {
    pub aim: Option<Targets>,
    pub starts: Option<Targets>,
}

impl Aims {
    pub fn new(scene: &Scene, aim_caustics: bool) -> Aims {
        Aims {
            aim: aim_caustics
                .then(|| Targets::from_scene(scene))
                .filter(|t| !t.is_empty()),
            starts: match scene.has_media() {
                true => None,
                false => Targets::starts(scene),
            },
        }
    }
}

/// Bounding spheres of the specular shapes.
#[derive(Clone, Debug, Default)]
pub struct Targets {
    spheres: Vec<(Vec3, f32)>,
}

/// Above this many shapes a caustic path can start at, [`Targets::starts`]
/// gives up: a photon that misses them all tests every one (a few
/// nanoseconds each), and that must stay well below the traversal it may
/// save (a few hundred) where most photons do not miss.
const MAX_STARTS: usize = 16;

impl Targets {
    /// The perfectly specular shapes, which aimed photons head for.
    pub fn from_scene(scene: &Scene) -> Targets {
        let mut t = Targets::of(scene, Material::is_specular, false);
        t.spheres.retain(|s| s.1 > 0.0);
        t
    }

    /// Every shape whose material can have a delta lobe: a caustic photon
    /// whose first ray misses them all ends unstored at its first hit, so
    /// it need not be traced ([`Targets::may_hit`]). None where there are
    /// more than [`MAX_STARTS`] of them or a bound is not finite.
    pub fn starts(scene: &Scene) -> Option<Targets> {
        let mut t = Targets::of(scene, |m| !m.never_delta(), true);
        let finite = t
            .spheres
            .iter()
            .all(|(c, r)| c.is_finite() && r.is_finite());
        // Empty shapes (a point's box) cannot be hit.
        t.spheres.retain(|s| s.1 > 0.0);
        (finite && t.spheres.len() <= MAX_STARTS).then_some(t)
    }

    /// Whether `ray` (of any `tmax`) may meet one of the spheres: false only
    /// when it misses each by a margin (a thousandth of its radius, and of
    /// the distance, for rounding), so a ray that hits one of the shapes is
    /// never refused.
    pub fn may_hit(&self, ray: &Ray) -> bool {
        let inv_len2 = 1.0 / ray.d.length_squared();
        (self.spheres.iter()).any(|&(c, r)| meets(ray, inv_len2, c, r).is_some())
    }

    /// A key that orders rays by where they meet the spheres: the first
    /// sphere along the ray that it may hit (as [`Targets::may_hit`]), and
    /// in its 30 low bits the Morton code of the ray's point nearest that
    /// sphere's centre, on a 1024^3 grid over the sphere's box. Rays of
    /// close keys meet the same part of the same shape first. None if the
    /// ray may hit none.
    pub fn order_key(&self, ray: &Ray) -> Option<u32> {
        let inv_len2 = 1.0 / ray.d.length_squared();
        let mut best: Option<(f32, usize)> = None;
        for (k, &(c, r)) in self.spheres.iter().enumerate() {
            if let Some(s) = meets(ray, inv_len2, c, r) {
                if best.is_none_or(|b| s < b.0) {
                    best = Some((s, k));
                }
            }
        }
        let (s, k) = best?;
        let p = ray.o + ray.d * s;
        let (c, r) = self.spheres[k];
        let cell = |x: f32, cx: f32| {
            let u = (x - (cx - r)) / (2.0 * r);
            spread3((u.clamp(0.0, 1.0) * 1023.0) as u32)
        };
        let code = cell(p.x, c.x) | cell(p.y, c.y) << 1 | cell(p.z, c.z) << 2;
        Some(((k as u32) << 30) | code)
    }

    /// One sphere per shape (a whole mesh, a sphere, a disk) kept by its
    /// material, in a stable order: its box's bounding sphere, or with
    /// `tight` (world shapes) the sphere about the box's centre that
    /// reaches the farthest vertex of its triangles, the far side of its
    /// spheres and the farthest corner of its other primitives' boxes (a
    /// box's bounding sphere has `sqrt 3` times a sphere's radius, three
    /// times its solid angle). An instanced object's boxes are placed by
    /// each instance. Empty and non-finite ones are left for the caller.
    fn of(scene: &Scene, keep: impl Fn(&Material) -> bool, tight: bool) -> Targets {
        let kept = |prims: &'_ [PrimInfo]| -> Vec<PrimInfo> {
            prims
                .iter()
                .filter(|p| keep(&scene.materials[p.material as usize]))
                .copied()
                .collect()
        };
        let shape_boxes = |prims: &[PrimInfo]| {
            let mut boxes: BTreeMap<(u8, u32), Aabb> = BTreeMap::new();
            for p in prims {
                let b = boxes.entry(p.prim.shape()).or_insert(Aabb::EMPTY);
                *b = b.union(&scene.shapes.bounds(p.prim));
            }
            boxes
        };
        let world = kept(&scene.world.prims);
        let world_boxes = shape_boxes(&world);
        let mut reach: BTreeMap<(u8, u32), f32> = BTreeMap::new();
        for p in world.iter().filter(|_| tight) {
            let key = p.prim.shape();
            let c = world_boxes[&key].center();
            let far = farthest(scene, p.prim, c);
            let e = reach.entry(key).or_insert(0.0);
            *e = e.max(far);
        }
        let mut spheres: Vec<(Vec3, f32)> = world_boxes
            .iter()
            .map(|(key, b)| {
                let (c, r) = b.bounding_sphere();
                (c, reach.get(key).map_or(r, |&far| far.min(r)))
            })
            .collect();
        let objects: Vec<Vec<Aabb>> = scene
            .instances
            .objects
            .iter()
            .map(|o| shape_boxes(&kept(&o.prims)).into_values().collect())
            .collect();
        for inst in &scene.instances.instances {
            let xf = &inst.world_from_object;
            spheres.extend(
                objects[inst.object as usize]
                    .iter()
                    .map(|b| transform_box(xf, b).bounding_sphere()),
            );
        }
        Targets { spheres }
    }

    pub fn is_empty(&self) -> bool {
        self.spheres.is_empty()
    }

    /// The spheres: centre and radius.
    pub fn spheres(&self) -> &[(Vec3, f32)] {
        &self.spheres
    }

    /// Cosine of the half-angle of target `t` seen from `from`; None if `from` is inside it.
    fn cos_max(&self, from: Vec3, t: usize) -> Option<(Vec3, f32)> {
        let (c, r) = self.spheres[t];
        let d = c - from;
        let d2 = d.length_squared();
        if d2 <= r * r {
            return None;
        }
        Some((d / d2.sqrt(), (1.0 - r * r / d2).max(0.0).sqrt()))
    }

    /// A direction towards a target chosen uniformly.
    pub fn sample(&self, from: Vec3, uc: f32, u: Vec2) -> Vec3 {
        let t = ((uc * self.spheres.len() as f32) as usize).min(self.spheres.len() - 1);
        match self.cos_max(from, t) {
            None => square_to_uniform_sphere(u),
            Some((axis, cos_max)) => {
                Frame::from_normal(axis).to_world(square_to_uniform_cone(u, cos_max))
            }
        }
    }

    /// Density of [`Targets::sample`] for direction `w` from `from`.
    pub fn pdf(&self, from: Vec3, w: Vec3) -> f32 {
        let n = self.spheres.len() as f32;
        let mut p = 0.0;
        for t in 0..self.spheres.len() {
            p += match self.cos_max(from, t) {
                None => UNIFORM_SPHERE_PDF,
                Some((axis, cos_max)) if w.dot(axis) >= cos_max => uniform_cone_pdf(cos_max),
                Some(_) => 0.0,
            };
        }
        p / n
    }
}

/// Where `ray` may meet sphere `(c, r)`, padded as [`padded_r2`] pads it:
/// `Some(0)` from inside it, `Some(s)` where the line's point nearest the
/// centre, `o + s d`, is ahead of the origin and within the padded radius;
/// else None.
#[inline(always)]
fn meets(ray: &Ray, inv_len2: f32, c: Vec3, r: f32) -> Option<f32> {
    let oc = c - ray.o;
    let d2 = oc.length_squared();
    let r2 = padded_r2(r, d2);
    if d2 <= r2 {
        return Some(0.0);
    }
    let t = oc.dot(ray.d);
    let s = t * inv_len2;
    // Ahead of the origin, and its centre within `r` of the line.
    (t > 0.0 && (oc - ray.d * s).length_squared() <= r2).then_some(s)
}

/// A start sphere's squared radius `r` as [`Targets::may_hit`] and
/// `Targets`' [`EmitCull::cone_may_pass`] both pad it against rounding: by a thousandth
/// of the radius and a millionth of the squared distance `d2` to it.
#[inline(always)]
pub(super) fn padded_r2(r: f32, d2: f32) -> f32 {
    (r * 1.001) * (r * 1.001) + 1e-6 * d2
}

impl EmitCull for Targets {
    /// Whether some ray from `o` at the polar angle (`sin_t`, `cos_t`)
    /// about the unit `n` may meet one of the spheres as
    /// [`Targets::may_hit`] tests them: false only when none can, by a
    /// margin of a few thousandths of a radian and of the squared distance,
    /// well above the rounding of a sampled direction (up to about 6e-4
    /// radians near the horizon) and of `may_hit`'s own test.
    fn cone_may_pass(&self, o: Vec3, n: Vec3, sin_t: f32, cos_t: f32) -> bool {
        self.spheres.iter().any(|&(c, r)| {
            let oc = c - o;
            let d2 = oc.length_squared();
            let r2 = padded_r2(r, d2);
            if d2 <= r2 * 1.01 {
                return true;
            }
            // The largest `oc . w` over the unit directions `w` of the cone,
            // plus the margin; `may_hit` needs `(oc . w)^2 >= d2 - r2` with
            // `oc . w > 0`.
            let len = d2.sqrt();
            let a = oc.dot(n);
            let m = sin_t * (d2 - a * a).max(0.0).sqrt() + cos_t * a + 4e-3 * len;
            m > 0.0 && m * m >= d2 - r2 - 1e-3 * d2
        })
    }
}

/// The distance from `c` to the farthest point of primitive `prim`, or a
/// bound of it: its vertices, a sphere's far side, its box's corners.
fn farthest(scene: &Scene, prim: Prim, c: Vec3) -> f32 {
    let shapes = &scene.shapes;
    if let Some(v) = shapes.triangle_vertices(prim) {
        return v.iter().map(|v| (*v - c).length()).fold(0.0, f32::max);
    }
    if let Prim::Sphere(i) = prim {
        let s = &shapes.spheres[i as usize];
        return (s.center - c).length() + s.world_radius;
    }
    let b = shapes.bounds(prim);
    (0..8)
        .map(|k| {
            let pick = |bit: usize, lo: f32, hi: f32| if k >> bit & 1 == 0 { lo } else { hi };
            let v = Vec3::new(
                pick(0, b.min.x, b.max.x),
                pick(1, b.min.y, b.max.y),
                pick(2, b.min.z, b.max.z),
            );
            (v - c).length()
        })
        .fold(0.0, f32::max)
}

/// An aimed emission: the ray, the flux it carries divided by its density
/// (including the light-choice probability `pmf`) and the emitted radiance. None for lights that are
/// not aimed (distant, infinite: the caller uses ordinary emission).
pub fn aimed_emission(
    scene: &Scene,
    targets: &Targets,
    light: &Light,
    pmf: f32,
    u_pos: Vec2,
    uc: f32,
    u_dir: Vec2,
) -> Option<Option<(Ray, Rgb, Rgb)>> {
    let emit =
        |from: Vec3, n: Vec3, le: &dyn Fn(Vec3) -> Rgb, pdf_pos: f32| -> Option<(Ray, Rgb, Rgb)> {
            let w = targets.sample(from, uc, u_dir);
            let pdf_dir = targets.pdf(from, w);
            let l = le(w);
            if pdf_dir <= 0.0 || l.is_black() {
                return None;
            }
            let cos = if n == Vec3::ZERO { 1.0 } else { n.dot(w).abs() };
            let side = if n.dot(w) < 0.0 { -n } else { n };
            let o = if n == Vec3::ZERO {
                from
            } else {
                offset_ray_origin(from, side)
            };
            Some((Ray::new(o, w), l * (cos / (pdf_pos * pdf_dir * pmf)), l))
        };
    Some(match light {
        Light::Area(a) => {
            let sp = a.sample_point(&scene.shapes, u_pos);
            emit(sp.p, sp.n, &|w| a.l(sp.n, sp.uv, w), sp.pdf)
        }
        Light::Point(p) => emit(p.pos, Vec3::ZERO, &|_| p.intensity, 1.0),
        Light::Goniometric(g) => emit(g.pos, Vec3::ZERO, &|w| g.i(w), 1.0),
        Light::Spot(s) => emit(s.pos, Vec3::ZERO, &|w| s.i(w), 1.0),
        Light::Distant(_) | Light::Infinite(_) | Light::Image(_) => return None,
    })
}

/// Luminance of the flux (times N) a caustic photon would carry had it left
/// light `li` at `p` (normal `n`) in direction `w`: what a gather ray that
/// reached the light there needs for its q_1. The light's own emission
/// densities, with the aimed direction density when photons are aimed.
pub fn emitted_flux(
    scene: &Scene,
    targets: Option<&Targets>,
    li: u32,
    p: Vec3,
    n: Vec3,
    w: Vec3,
    le_lum: f32,
) -> f32 {
    let pmf = scene.light_sampler.pmf(li);
    let light = &scene.lights[li as usize];
    // Only area-light photons are aimed (and need the density).
    let aimed_pdf = match light {
        Light::Area(_) => targets.map(|t| t.pdf(p, w)),
        _ => None,
    };
    light.emitted_flux(&scene.shapes, pmf, p, n, w, le_lum, aimed_pdf)
}

/// The 10 low bits of `x` spread to every third bit (a Morton code's axis).
fn spread3(x: u32) -> u32 {
    let mut x = x & 0x3ff;
    x = (x | x << 16) & 0x0300_00ff;
    x = (x | x << 8) & 0x0300_f00f;
    x = (x | x << 4) & 0x030c_30c3;
    (x | x << 2) & 0x0924_9249
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The key names the first sphere a ray may meet, and rays that pass
    /// near each other there get keys that share their high bits.
    #[test]
    fn order_keys_follow_the_first_sphere_and_the_point() {
        let t = Targets {
            spheres: vec![
                (Vec3::new(0.0, 0.0, 5.0), 1.0),
                (Vec3::new(0.0, 0.0, 2.0), 0.5),
            ],
        };
        let up = |x: f32, y: f32| Ray::new(Vec3::new(x, y, 0.0), Vec3::new(0.0, 0.0, 1.0));
        // Through both: the nearer (index 1) first; beside the small one,
        // the large one (index 0); beside both, none.
        assert_eq!(t.order_key(&up(0.1, 0.0)).map(|k| k >> 30), Some(1));
        assert_eq!(t.order_key(&up(0.8, 0.0)).map(|k| k >> 30), Some(0));
        assert_eq!(t.order_key(&up(1.5, 0.0)), None);
        // Backwards: the spheres are behind the origin.
        let back = Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, -1.0));
        assert_eq!(t.order_key(&back), None);
        // Close points share more leading bits than far ones.
        let k = |x: f32| t.order_key(&up(x, 0.3)).unwrap();
        let shared = |a: u32, b: u32| (a ^ b).leading_zeros();
        assert!(shared(k(0.01), k(0.02)) > shared(k(0.01), k(-0.4)));
        // From inside a sphere: its own key, at the origin's cell.
        let inside = Ray::new(Vec3::new(0.0, 0.0, 5.5), Vec3::new(1.0, 0.0, 0.0));
        assert_eq!(t.order_key(&inside).map(|k| k >> 30), Some(0));
    }

    #[test]
    fn spread3_spreads_ten_bits() {
        assert_eq!(spread3(0b11), 0b1001);
        assert_eq!(spread3(0x3ff), 0x0924_9249);
        assert_eq!(spread3(0x400), 0);
    }
}
