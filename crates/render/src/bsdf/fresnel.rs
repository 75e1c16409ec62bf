//! Fresnel equations and the reflect/refract helpers (pbrt-v4 §9.3, §9.4).
//!
//! All angles are given as cosines with respect to a normal `n`; `eta` is the
//! relative index of refraction `eta_t / eta_i` across the interface, measured
//! from the side `n` points to.

use lumis_math::{safe_sqrt, Rgb, Vec3};

/// Mirror `wo` about `n` (both unit, `wo` pointing away from the surface).
#[inline]
pub fn reflect(wo: Vec3, n: Vec3) -> Vec3 {
    -wo + 2.0 * wo.dot(n) * n
}

/// Refract `wi` (pointing away from the surface) through the interface with
/// normal `n` and relative IOR `eta` (inside over outside, where `n` points
/// outside). If `wi` is on the other side of `n`, the interface is seen from
/// inside: `eta` is inverted and `n` flipped.
///
/// Returns the transmitted direction (pointing away, on the opposite side) and
/// the relative IOR `etap` actually crossed, or `None` on total internal
/// reflection.
pub fn refract(wi: Vec3, n: Vec3, eta: f32) -> Option<(Vec3, f32)> {
    let mut cos_i = n.dot(wi);
    let (mut eta, mut n) = (eta, n);
    if cos_i < 0.0 {
        eta = 1.0 / eta;
        cos_i = -cos_i;
        n = -n;
    }
    let sin2_i = (1.0 - cos_i * cos_i).max(0.0);
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return None;
    }
    let cos_t = safe_sqrt(1.0 - sin2_t);
    let wt = -wi / eta + (cos_i / eta - cos_t) * n;
    Some((wt, eta))
}

/// Unpolarized Fresnel reflectance of a dielectric interface. `cos_i` may be
/// negative (incidence from inside), in which case `eta` is inverted. Returns
/// 1 on total internal reflection.
pub fn fr_dielectric(cos_i: f32, eta: f32) -> f32 {
    let mut cos_i = cos_i.clamp(-1.0, 1.0);
    let mut eta = eta;
    if cos_i < 0.0 {
        eta = 1.0 / eta;
        cos_i = -cos_i;
    }
    let sin2_i = 1.0 - cos_i * cos_i;
    let sin2_t = sin2_i / (eta * eta);
    if sin2_t >= 1.0 {
        return 1.0;
    }
    let cos_t = safe_sqrt(1.0 - sin2_t);
    let r_parl = (eta * cos_i - cos_t) / (eta * cos_i + cos_t);
    let r_perp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t);
    (r_parl * r_parl + r_perp * r_perp) / 2.0
}

/// Fresnel reflectance of a conductor with complex IOR `eta + i k` for one
/// wavelength; `cos_i` is clamped to [0, 1] (conductors are opaque). The
/// real-arithmetic form of the complex Fresnel equations (with
/// `a^2 + b^2 = |eta^2 - k^2 - sin^2 + 2 i eta k|`, as in pbrt-v3's
/// `FrConductor`): two square roots and two divisions; the test module keeps
/// the complex-number form to check it against.
pub fn fr_complex(cos_i: f32, eta: f32, k: f32) -> f32 {
    let c = cos_i.clamp(0.0, 1.0);
    let c2 = c * c;
    let s2 = 1.0 - c2;
    let t0 = eta * eta - k * k - s2;
    let a2b2 = (t0 * t0 + 4.0 * eta * eta * k * k).sqrt();
    let t1 = a2b2 + c2;
    // a^2 = (|z| + Re z) / 2, without cancellation when Re z < 0.
    let a2 = if t0 >= 0.0 {
        0.5 * (a2b2 + t0)
    } else {
        2.0 * eta * eta * k * k / (a2b2 - t0)
    };
    let a = a2.max(0.0).sqrt();
    let t2 = 2.0 * c * a;
    let rs = (t1 - t2) / (t1 + t2);
    let t3 = c2 * a2b2 + s2 * s2;
    let t4 = t2 * s2;
    let rp = rs * (t3 - t4) / (t3 + t4);
    let r = 0.5 * (rp + rs);
    if r.is_finite() {
        r
    } else {
        // 0/0 at grazing incidence on an index-matched, lossless medium.
        1.0
    }
}

/// [`fr_complex`] per RGB channel.
pub fn fr_complex_rgb(cos_i: f32, eta: Rgb, k: Rgb) -> Rgb {
    Rgb::new(
        fr_complex(cos_i, eta.r, k.r),
        fr_complex(cos_i, eta.g, k.g),
        fr_complex(cos_i, eta.b, k.b),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Minimal complex arithmetic for the conductor Fresnel term.
    #[derive(Clone, Copy, Debug)]
    struct Complex {
        re: f32,
        im: f32,
    }

    impl Complex {
        const fn new(re: f32, im: f32) -> Self {
            Complex { re, im }
        }
        fn real(re: f32) -> Self {
            Complex { re, im: 0.0 }
        }
        fn add(self, o: Complex) -> Complex {
            Complex::new(self.re + o.re, self.im + o.im)
        }
        fn sub(self, o: Complex) -> Complex {
            Complex::new(self.re - o.re, self.im - o.im)
        }
        fn mul(self, o: Complex) -> Complex {
            Complex::new(
                self.re * o.re - self.im * o.im,
                self.re * o.im + self.im * o.re,
            )
        }
        fn div(self, o: Complex) -> Complex {
            let d = o.re * o.re + o.im * o.im;
            Complex::new(
                (self.re * o.re + self.im * o.im) / d,
                (self.im * o.re - self.re * o.im) / d,
            )
        }
        /// Squared magnitude.
        fn norm(self) -> f32 {
            self.re * self.re + self.im * self.im
        }
        /// Principal square root (non-negative real part).
        fn sqrt(self) -> Complex {
            let n = self.norm().sqrt();
            if n == 0.0 {
                return Complex::real(0.0);
            }
            let t1 = (0.5 * (n + self.re.abs())).sqrt();
            let t2 = 0.5 * self.im / t1;
            if self.re >= 0.0 {
                Complex::new(t1, t2)
            } else {
                Complex::new(t2.abs(), t1.copysign(self.im))
            }
        }
    }

    /// The complex-number form of the conductor Fresnel equations.
    fn fr_complex_reference(cos_i: f32, eta: f32, k: f32) -> f32 {
        let cos_i = cos_i.clamp(0.0, 1.0);
        let eta = Complex::new(eta, k);
        let ci = Complex::real(cos_i);
        let sin2_i = Complex::real(1.0 - cos_i * cos_i);
        let sin2_t = sin2_i.div(eta.mul(eta));
        let cos_t = Complex::real(1.0).sub(sin2_t).sqrt();
        let r_parl = eta.mul(ci).sub(cos_t).div(eta.mul(ci).add(cos_t));
        let r_perp = ci.sub(eta.mul(cos_t)).div(ci.add(eta.mul(cos_t)));
        (r_parl.norm() + r_perp.norm()) / 2.0
    }

    #[test]
    fn real_form_equals_complex_form() {
        let etas = [0.05f32, 0.2, 0.5, 1.0, 1.1, 1.5, 2.4, 3.0];
        let ks = [0.0f32, 0.01, 0.5, 2.4, 3.9, 10.0, 200.0];
        let mut worst = 0.0f32;
        for i in 0..=50 {
            let c = i as f32 / 50.0;
            for &eta in &etas {
                for &k in &ks {
                    if eta == 1.0 && k == 0.0 {
                        continue;
                    }
                    let (a, b) = (fr_complex(c, eta, k), fr_complex_reference(c, eta, k));
                    assert!((a - b).abs() < 5e-6, "cos {c} eta {eta} k {k}: {a} vs {b}");
                    worst = worst.max((a - b).abs());
                }
            }
        }
        println!("largest difference {worst:e}");
    }

    #[test]
    fn glass_at_normal_incidence() {
        assert!((fr_dielectric(1.0, 1.5) - 0.04).abs() < 1e-6);
        // Same from inside.
        assert!((fr_dielectric(-1.0, 1.0 / 1.5) - 0.04).abs() < 1e-6);
        assert!((fr_dielectric(-1.0, 1.5) - 0.04).abs() < 1e-6);
    }

    #[test]
    fn known_values() {
        // Grazing incidence reflects everything.
        assert!((fr_dielectric(0.0, 1.5) - 1.0).abs() < 1e-6);
        // Brewster angle: parallel polarization vanishes, R = r_perp^2 / 2.
        let tb = 1.5f32.atan();
        let (ci, ct) = (tb.cos(), (tb.sin() / 1.5).asin().cos());
        let rs = (ci - 1.5 * ct) / (ci + 1.5 * ct);
        assert!((fr_dielectric(ci, 1.5) - rs * rs / 2.0).abs() < 1e-6);
        // Total internal reflection from inside past the critical angle.
        let crit = (1.0f32 / 1.5).asin();
        assert_eq!(fr_dielectric(-(crit + 0.01).cos(), 1.5), 1.0);
        assert!(fr_dielectric(-(crit - 0.01).cos(), 1.5) < 1.0);
        // Index match: no reflection.
        assert!(fr_dielectric(0.3, 1.0).abs() < 1e-7);
    }

    #[test]
    fn conductor_with_zero_k_is_dielectric() {
        for i in 0..=20 {
            let c = i as f32 / 20.0;
            for eta in [1.2f32, 1.5, 2.4] {
                let a = fr_complex(c, eta, 0.0);
                let b = fr_dielectric(c, eta);
                assert!((a - b).abs() < 1e-5, "cos {c} eta {eta}: {a} vs {b}");
            }
        }
    }

    #[test]
    fn conductor_normal_incidence() {
        // R = ((n-1)^2 + k^2) / ((n+1)^2 + k^2) at normal incidence.
        let (n, k) = (0.2f32, 3.9f32);
        let expect = ((n - 1.0).powi(2) + k * k) / ((n + 1.0).powi(2) + k * k);
        assert!((fr_complex(1.0, n, k) - expect).abs() < 1e-5);
        assert!((fr_complex(0.0, n, k) - 1.0).abs() < 1e-5);
        let r = fr_complex_rgb(1.0, Rgb::splat(n), Rgb::splat(k));
        assert!((r.g - expect).abs() < 1e-5);
    }

    #[test]
    fn snell_and_reflect() {
        let n = Vec3::Z;
        let wi = Vec3::new(0.6, 0.0, 0.8);
        let r = reflect(wi, n);
        assert!((r - Vec3::new(-0.6, 0.0, 0.8)).length() < 1e-6);
        let (wt, etap) = refract(wi, n, 1.5).unwrap();
        assert_eq!(etap, 1.5);
        assert!((wt.length() - 1.0).abs() < 1e-5);
        assert!(wt.z < 0.0);
        // sin_t * eta = sin_i
        assert!((wt.x.abs() * 1.5 - 0.6).abs() < 1e-5);
        assert!(wt.x < 0.0);
        // Reverse path returns the original direction.
        let (back, etap2) = refract(wt, n, 1.5).unwrap();
        assert!((etap2 - 1.0 / 1.5).abs() < 1e-6);
        assert!((back - wi).length() < 1e-5);
        // TIR from inside.
        assert!(refract(Vec3::new(0.9, 0.0, -(0.19f32).sqrt()), n, 1.5).is_none());
    }
}
