//! Multiple importance sampling heuristics (Veach & Guibas 1995).

/// Balance heuristic weight of technique f among f and g.
#[inline]
pub fn balance_heuristic(nf: f32, pf: f32, ng: f32, pg: f32) -> f32 {
    let f = nf * pf;
    let g = ng * pg;
    if f.is_infinite() {
        return if g.is_infinite() { 0.5 } else { 1.0 };
    }
    if f + g <= 0.0 {
        return 0.0;
    }
    f / (f + g)
}

/// Power heuristic (exponent 2) weight of technique f among f and g.
#[inline]
pub fn power_heuristic(nf: f32, pf: f32, ng: f32, pg: f32) -> f32 {
    let f = nf * pf;
    let g = ng * pg;
    if f.is_infinite() {
        return if g.is_infinite() { 0.5 } else { 1.0 };
    }
    if g.is_infinite() {
        return 0.0;
    }
    let (f2, g2) = (f * f, g * g);
    if f2 + g2 <= 0.0 {
        return 0.0;
    }
    if !(f2 + g2).is_finite() {
        // Both huge: fall back to the ratio, which is scale-free.
        let r = g / f;
        return 1.0 / (1.0 + r * r);
    }
    f2 / (f2 + g2)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn weights_sum_to_one() {
        for &(a, b) in &[(1.0, 2.0), (0.1, 5.0), (3.0, 3.0), (1e20, 1e21)] {
            let s = balance_heuristic(1.0, a, 1.0, b) + balance_heuristic(1.0, b, 1.0, a);
            assert!((s - 1.0).abs() < 1e-6);
            let s = power_heuristic(1.0, a, 1.0, b) + power_heuristic(1.0, b, 1.0, a);
            assert!((s - 1.0).abs() < 1e-6, "{s}");
        }
    }

    #[test]
    fn infinite_density_takes_all() {
        assert_eq!(balance_heuristic(1.0, f32::INFINITY, 1.0, 3.0), 1.0);
        assert_eq!(power_heuristic(1.0, 3.0, 1.0, f32::INFINITY), 0.0);
        assert_eq!(power_heuristic(1.0, 2.0, 1.0, 1.0), 0.8);
    }
}
