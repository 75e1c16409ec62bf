use crate::texture::{TexCtx, TexFloat, Textures};
use lumis_math::Vec3;

/// pbrt-v4's `mix`: at each hit one of two materials, chosen with
/// probability `amount` for the second by a deterministic hash of the hit
/// point and direction (so a point looks the same from every path).
#[derive(Clone, Debug)]
pub struct MixMaterial {
    pub materials: [u32; 2],
    pub amount: TexFloat,
}

impl MixMaterial {
    pub fn choose(&self, t: &Textures, c: &TexCtx, wo: Vec3) -> u32 {
        let a = self.amount.eval(t, c);
        if a <= 0.0 {
            return self.materials[0];
        }
        if a >= 1.0 {
            return self.materials[1];
        }
        let h = lumis_math::rng::hash(&[
            c.p.x.to_bits() as u64 | (c.p.y.to_bits() as u64) << 32,
            c.p.z.to_bits() as u64 | (wo.x.to_bits() as u64) << 32,
            wo.y.to_bits() as u64 | (wo.z.to_bits() as u64) << 32,
            self.materials[0] as u64 | (self.materials[1] as u64) << 32,
        ]);
        let u = (h >> 40) as f32 / (1u64 << 24) as f32;
        if a < u {
            self.materials[0]
        } else {
            self.materials[1]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use lumis_math::Vec2;

    #[test]
    fn chooses_by_amount_deterministically() {
        let t = Textures::default();
        let m = MixMaterial {
            materials: [3, 7],
            amount: TexFloat::Const(0.3),
        };
        let mut rng = lumis_math::Pcg32::new(1, 1);
        let n = 40_000;
        let mut second = 0;
        for _ in 0..n {
            let p = Vec3::new(rng.next_f32(), rng.next_f32(), rng.next_f32());
            let c = TexCtx::at(p, Vec3::Z, Vec2::ZERO);
            let a = m.choose(&t, &c, Vec3::Z);
            assert_eq!(a, m.choose(&t, &c, Vec3::Z));
            second += (a == 7) as u32;
        }
        // Binomial: 0.3 n +- 4.5 sigma.
        let f = second as f64 / n as f64;
        assert!((f - 0.3).abs() < 4.5 * (0.21f64 / n as f64).sqrt(), "{f}");
        let c = TexCtx::at(Vec3::ONE, Vec3::Z, Vec2::ZERO);
        let all = MixMaterial {
            amount: TexFloat::Const(1.0),
            ..m.clone()
        };
        assert_eq!(all.choose(&t, &c, Vec3::Z), 7);
    }
}
