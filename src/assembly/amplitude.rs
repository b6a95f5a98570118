//! Amplitudes: the factors in pseudo-time that scale loads, prescribed
//! displacements and obstacle motions.

/// A piecewise-linear function of pseudo-time, constant beyond its first
/// and last points.
#[derive(Clone, Debug, PartialEq)]
pub struct Amplitude {
    points: Vec<(f64, f64)>,
}

impl Amplitude {
    /// From `(time, value)` points with strictly increasing times. The
    /// caller validates the input (see [`crate::case`]).
    pub fn new(points: Vec<(f64, f64)>) -> Self {
        Amplitude { points }
    }
    /// The default: 0 at time 0, 1 at time 1 and after.
    pub fn ramp() -> Self {
        Amplitude::new(vec![(0.0, 0.0), (1.0, 1.0)])
    }
    /// Value at time `t`.
    pub fn value(&self, t: f64) -> f64 {
        let p = &self.points;
        if p.is_empty() {
            return 1.0;
        }
        if t <= p[0].0 {
            return p[0].1;
        }
        for w in p.windows(2) {
            let ((t0, v0), (t1, v1)) = (w[0], w[1]);
            if t <= t1 {
                return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
            }
        }
        p[p.len() - 1].1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn amplitude_interpolates_and_holds() {
        let a = Amplitude::new(vec![(0.0, 0.0), (1.0, 2.0), (3.0, -2.0)]);
        assert_eq!(a.value(-1.0), 0.0);
        assert!((a.value(0.5) - 1.0).abs() < 1e-15);
        assert!((a.value(2.0) - 0.0).abs() < 1e-15);
        assert_eq!(a.value(10.0), -2.0);
    }
}
