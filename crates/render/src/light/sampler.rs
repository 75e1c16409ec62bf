//! Chooses a light in proportion to its power (luminance).

use super::Light;
use crate::geometry::Shapes;

#[derive(Clone, Debug, Default)]
pub struct LightSampler {
    /// Cumulative distribution over lights, `cdf[i]` = P(index <= i).
    cdf: Vec<f32>,
    pmf: Vec<f32>,
}

impl LightSampler {
    pub fn new(lights: &[Light], shapes: &Shapes) -> LightSampler {
        let mut w: Vec<f64> = lights
            .iter()
            .map(|l| l.power(shapes).luminance().max(0.0) as f64)
            .collect();
        let total: f64 = w.iter().sum();
        if !(total > 0.0) || !total.is_finite() {
            w.iter_mut().for_each(|x| *x = 1.0);
        }
        let total: f64 = w.iter().sum();
        let mut acc = 0.0;
        let mut cdf = Vec::with_capacity(w.len());
        for x in &w {
            acc += x / total;
            cdf.push(acc as f32);
        }
        if let Some(last) = cdf.last_mut() {
            *last = 1.0;
        }
        let pmf = w.iter().map(|x| (x / total) as f32).collect();
        LightSampler { cdf, pmf }
    }

    pub fn is_empty(&self) -> bool {
        self.cdf.is_empty()
    }

    /// Returns (light index, probability).
    #[inline]
    pub fn sample(&self, u: f32) -> Option<(u32, f32)> {
        if self.cdf.is_empty() {
            return None;
        }
        let i = self
            .cdf
            .partition_point(|&c| c <= u)
            .min(self.cdf.len() - 1);
        // Skip zero-probability entries that share the same cdf value.
        let p = self.pmf[i];
        if p == 0.0 {
            return None;
        }
        Some((i as u32, p))
    }

    #[inline]
    pub fn pmf(&self, light: u32) -> f32 {
        self.pmf.get(light as usize).copied().unwrap_or(0.0)
    }
}
