//! Hertz's solution for a sphere against a flat half-space (elastic sphere
//! on a rigid plane, or rigid sphere on an elastic half-space), the
//! reference of the contact examples and benchmarks (Johnson, *Contact
//! Mechanics*, 1985, §4.2).

/// Hertz's contact for total force `F`, sphere radius `R` and plane-strain
/// modulus `E* = E/(1 − ν²)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Hertz {
    /// Contact radius `a = (3FR / 4E*)^{1/3}`.
    pub radius: f64,
    /// Peak pressure `p₀ = 3F / (2πa²)`.
    pub peak_pressure: f64,
}

impl Hertz {
    /// The contact for force `force`, sphere `radius`, modulus `e_star`.
    pub fn new(force: f64, radius: f64, e_star: f64) -> Self {
        let a = (3.0 * force * radius / (4.0 * e_star)).powf(1.0 / 3.0);
        Hertz {
            radius: a,
            peak_pressure: 3.0 * force / (2.0 * std::f64::consts::PI * a * a),
        }
    }

    /// Pressure at distance `r` from the axis, `p₀ √(1 − r²/a²)` (0 outside).
    pub fn pressure(&self, r: f64) -> f64 {
        self.peak_pressure * (1.0 - (r / self.radius).powi(2)).max(0.0).sqrt()
    }
}

/// The nodal pressures of an axisymmetric contact about the z axis as
/// `(r, p)`: `r` the current distance of secondary node `nodes[i]` from the
/// axis (reference position `reference` plus displacement `x`), `p` its
/// `pressures[i]`.
pub fn radial_pressures(
    nodes: &[usize],
    reference: &[[f64; 3]],
    x: &[f64],
    pressures: impl IntoIterator<Item = f64>,
) -> Vec<(f64, f64)> {
    nodes
        .iter()
        .zip(pressures)
        .map(|(&s, p)| {
            let (xs, ys) = (reference[s][0] + x[3 * s], reference[s][1] + x[3 * s + 1]);
            (xs.hypot(ys), p)
        })
        .collect()
}

/// The contact radius of measured nodal pressures `(r, p)`: a least-squares
/// fit of Hertz's `p² = p₀² (1 − r²/a²)` (a line in `r²`) over the nodes with
/// `p > threshold`, `a = √(−c₀/c₁)`.
pub fn fitted_contact_radius(nodes: &[(f64, f64)], threshold: f64) -> f64 {
    let fit: Vec<(f64, f64)> = nodes
        .iter()
        .filter(|n| n.1 > threshold)
        .map(|n| (n.0 * n.0, n.1 * n.1))
        .collect();
    let m = fit.len() as f64;
    let sx: f64 = fit.iter().map(|f| f.0).sum();
    let sy: f64 = fit.iter().map(|f| f.1).sum();
    let sxx: f64 = fit.iter().map(|f| f.0 * f.0).sum();
    let sxy: f64 = fit.iter().map(|f| f.0 * f.1).sum();
    let slope = (m * sxy - sx * sy) / (m * sxx - sx * sx);
    let intercept = (sy - slope * sx) / m;
    (-intercept / slope).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fit recovers the radius of an exact Hertz profile, and the force
    /// integrates back: ∫ p 2πr dr = 2π p₀ a²/3 = F.
    #[test]
    fn fit_recovers_an_exact_profile() {
        let h = Hertz::new(2.0, 1.0, 1000.0);
        let nodes: Vec<(f64, f64)> = (0..50)
            .map(|i| {
                let r = h.radius * i as f64 / 50.0;
                (r, h.pressure(r))
            })
            .collect();
        assert!((fitted_contact_radius(&nodes, 0.2 * h.peak_pressure) - h.radius).abs() < 1e-12);
        let force = 2.0 * std::f64::consts::PI * h.peak_pressure * h.radius * h.radius / 3.0;
        assert!((force - 2.0).abs() < 1e-12);
    }
}
