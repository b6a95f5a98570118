//! Cattaneo–Mindlin partial slip of two identical elastic spheres, the
//! reference of `examples/cattaneo-mindlin` (shared by its `main.rs` and by
//! `tests/cattaneo_mindlin.rs`): Mindlin (1949), Johnson, *Contact
//! Mechanics* (1985) §7.2.
//!
//! Two identical spheres pressed by `P` and then sheared by `Q < μP`:
//! identical materials uncouple the normal and tangential problems, so the
//! pressure stays Hertz's `p(r) = p₀ √(1 − r²/a²)` and the tangential
//! traction, along the load, is
//! ```text
//! q(r) = μ p₀ [√(1 − r²/a²) − (c/a) √(1 − r²/c²)]   r ≤ c (stick)
//! q(r) = μ p₀ √(1 − r²/a²) = μ p(r)                 c ≤ r ≤ a (slip)
//! c = a (1 − Q/(μP))^{1/3}
//! ```
//! The deficit `μp − q = μ p₀ (c/a) √(1 − r²/c²)` inside the stick circle
//! is a half-ellipse in `r` like Hertz's pressure, so the stick radius of
//! computed tractions is fitted as Hertz's contact radius is:
//! `(μp − q)² = A − B r²` over the nodes whose deficit is well above zero,
//! `c = √(A/B)` ([`fitted_contact_radius`]).

// included with `#[path]` by the example and the test; each uses a part
#![allow(dead_code)]

use signorini::contact::friction::ContactStatus;
use signorini::contact::hertz::{fitted_contact_radius, Hertz};
use signorini::material::{Mat3, Material};
use signorini::output::ConvergedIncrement;

/// Mindlin's partial slip for normal force `P`, tangential force `Q`,
/// friction coefficient `μ`, on Hertz's contact of `P`.
#[derive(Clone, Copy, Debug)]
pub struct Mindlin {
    pub hertz: Hertz,
    pub mu: f64,
    /// `Q/(μP)`.
    pub ratio: f64,
    /// Stick radius `c = a (1 − Q/(μP))^{1/3}`.
    pub stick_radius: f64,
}

impl Mindlin {
    /// Two identical spheres of radius `radius`, modulus `E`, ratio `ν`:
    /// Hertz with `R* = R/2` and `E* = E/(2(1 − ν²))`.
    pub fn two_spheres(force: f64, tangential: f64, mu: f64, radius: f64, e: f64, nu: f64) -> Self {
        let hertz = Hertz::new(force, 0.5 * radius, e / (2.0 * (1.0 - nu * nu)));
        let ratio = tangential / (mu * force);
        Mindlin {
            hertz,
            mu,
            ratio,
            stick_radius: hertz.radius * (1.0 - ratio).max(0.0).cbrt(),
        }
    }

    /// `q(r)` (see the module's documentation), 0 outside the contact.
    pub fn traction(&self, r: f64) -> f64 {
        let (a, c) = (self.hertz.radius, self.stick_radius);
        let slip = self.mu * self.hertz.pressure(r);
        if r < c {
            slip - self.mu * self.hertz.peak_pressure * (c / a) * (1.0 - (r / c).powi(2)).sqrt()
        } else {
            slip
        }
    }
}

/// One secondary node of the contact at the end of an increment.
#[derive(Clone, Copy, Debug)]
pub struct NodeSample {
    /// Distance from the contact's centre (current configuration).
    pub r: f64,
    /// Abscissa along the load axis from the centre, and the reference `y`
    /// (0 on the symmetry plane, which holds the load axis).
    pub x: f64,
    pub y_reference: f64,
    /// Contact pressure `t_N`.
    pub pressure: f64,
    /// The tangential traction along the load, on the body that resists it:
    /// `q = −t_T · x̂`…
    pub traction: f64,
    /// …and across it, `−t_T · ŷ` (zero in Mindlin's solution; the exact
    /// solution for `ν ≠ 0` has some in the slip annulus, Munisamy, Hills
    /// and Nowell 1994).
    pub traction_y: f64,
    pub status: ContactStatus,
}

/// The stick radius of the closed nodes among `nodes`: the least-squares
/// fit of the deficit `(μp − q)² = A − B r²` over the nodes whose deficit
/// exceeds 0.2 of the largest, `c = √(A/B)` (NaN with fewer than 3 such).
pub fn fitted_stick_radius<'a>(nodes: impl Iterator<Item = &'a NodeSample>) -> f64 {
    let deficit: Vec<(f64, f64)> = nodes
        .filter(|n| n.status != ContactStatus::Open)
        .map(|n| (n.r, FRICTION * n.pressure - n.traction))
        .collect();
    let largest = deficit.iter().map(|d| d.1).fold(0.0, f64::max);
    let fitted = deficit.iter().filter(|d| d.1 > 0.2 * largest).count();
    if fitted >= 3 {
        fitted_contact_radius(&deficit, 0.2 * largest)
    } else {
        f64::NAN
    }
}

impl NodeSample {
    /// The angle from the load direction `+x`, in degrees, `0 … 180` (the
    /// half model's `|y|`).
    pub fn angle(&self) -> f64 {
        self.y_reference.abs().atan2(self.x).to_degrees()
    }
}

/// What one increment of the example shows against Mindlin.
#[derive(Clone, Debug)]
pub struct Comparison {
    pub time: f64,
    pub iterations: usize,
    /// Normal and tangential force on the whole contact (twice the half model's).
    pub force: f64,
    pub tangential: f64,
    pub mindlin: Mindlin,
    /// Poisson's ratio of the spheres (read from the case's material).
    pub poisson_ratio: f64,
    pub nodes: Vec<NodeSample>,
    /// The fitted stick radius (NaN without a stick zone to fit).
    pub stick_radius: f64,
    /// The contact radius fitted to the pressures (`p²` against `r²` over
    /// `p > 0.2 p₀`, as `examples/two-spheres`).
    pub contact_radius: f64,
    /// The outermost sticking and the innermost slipping closed node.
    pub outermost_stick: f64,
    pub innermost_slip: f64,
}

/// The example's geometry and friction (case.toml, spheres.geo); `E` and
/// `ν` are read from the case's material ([`elastic_constants`]).
pub const RADIUS: f64 = 1.0;
pub const FRICTION: f64 = 0.3;

/// Young's modulus and Poisson's ratio of an isotropic linear elastic
/// material, from its tangent at `F = I`: `ℂ₁₁ = λ + 2μ`, `ℂ₁₂ = λ`, so
/// `ν = ℂ₁₂/(ℂ₁₁ + ℂ₁₂)` and `E = (ℂ₁₁ − ℂ₁₂)(1 + ν)` (`ℂ₁₁ − ℂ₁₂ = 2μ`).
pub fn elastic_constants(material: &dyn Material) -> (f64, f64) {
    let (_, c) = material.stress_and_tangent(&Mat3::identity());
    let (c11, c12) = (c[(0, 0)], c[(0, 1)]);
    let nu = c12 / (c11 + c12);
    ((c11 - c12) * (1.0 + nu), nu)
}

impl Comparison {
    /// The secondary nodes of interface 0 of a converged increment of the
    /// half model (symmetry plane `y = 0`, load along `+x`), and their fit.
    pub fn of(inc: &ConvergedIncrement) -> Self {
        let interface = inc.problem.contacts.interface(0);
        let reports = &inc.contact_fields.reports[0];
        let summary = inc.contact_fields.summaries.values().next();
        let (force, tangential) = summary.map_or((0.0, 0.0), |s| {
            (2.0 * s.force[2].abs(), -2.0 * s.tangential_force[0])
        });
        let mesh = &inc.problem.model.mesh;
        // Hertz and Mindlin are small-strain theories: their radii are
        // material (reference) coordinates. The deformed positions would
        // move every node inwards by Hertz's radial surface displacement,
        // u_r(a) = -(1-2ν)(1+ν) a p0/(3E) at the edge (Johnson, Contact
        // Mechanics, 1985, eq. 3.41b; -1.3 % of a here), and along x by
        // the shear's elastic displacement.
        let current = |s: usize| [mesh.nodes[s][0], mesh.nodes[s][1]];
        // the contact's centre on the load axis: the closed nodes' centroid
        // in x, weighted by their normal force
        let (mut weighted, mut total) = (0.0, 0.0);
        for (&s, (r, &area)) in interface
            .nodes
            .iter()
            .zip(reports.iter().zip(&interface.areas))
        {
            weighted += area * r.pressure * current(s)[0];
            total += area * r.pressure;
        }
        let centre = if total > 0.0 { weighted / total } else { 0.0 };
        let nodes: Vec<NodeSample> = interface
            .nodes
            .iter()
            .zip(reports)
            .map(|(&s, r)| {
                let [x, y] = current(s);
                NodeSample {
                    r: (x - centre).hypot(y),
                    x: x - centre,
                    y_reference: mesh.nodes[s][1],
                    pressure: r.pressure,
                    traction: -r.tangential_traction[0],
                    traction_y: -r.tangential_traction[1],
                    status: r.status,
                }
            })
            .collect();
        let (youngs_modulus, poisson_ratio) = elastic_constants(&*inc.problem.model.materials[0]);
        let mindlin = Mindlin::two_spheres(
            force,
            tangential,
            FRICTION,
            RADIUS,
            youngs_modulus,
            poisson_ratio,
        );
        let stick_radius = fitted_stick_radius(nodes.iter());
        let pressures: Vec<(f64, f64)> = nodes.iter().map(|n| (n.r, n.pressure)).collect();
        let contact_radius = fitted_contact_radius(&pressures, 0.2 * mindlin.hertz.peak_pressure);
        let outermost_stick = nodes
            .iter()
            .filter(|n| n.status == ContactStatus::Stick)
            .map(|n| n.r)
            .fold(0.0, f64::max);
        let innermost_slip = nodes
            .iter()
            .filter(|n| n.status == ContactStatus::Slip)
            .map(|n| n.r)
            .fold(f64::INFINITY, f64::min);
        Comparison {
            time: inc.record.time,
            iterations: inc.record.iterations,
            force,
            tangential,
            mindlin,
            poisson_ratio,
            nodes,
            stick_radius,
            contact_radius,
            outermost_stick,
            innermost_slip,
        }
    }

    /// Ring means of `q` against Mindlin's `q` averaged over the same
    /// nodes, rings of width `a/10` up to `r < 0.8 a`: `(r_mid, mean, mindlin)`.
    pub fn rings(&self) -> Vec<(f64, f64, f64)> {
        self.rings_of(|_| true, &self.mindlin)
    }

    /// [`rings`](Self::rings) over the nodes that `keep` keeps, against
    /// `reference` (diagnostics: a sector of the contact, a fitted `c`).
    pub fn rings_of(
        &self,
        keep: impl Fn(&NodeSample) -> bool,
        reference: &Mindlin,
    ) -> Vec<(f64, f64, f64)> {
        let a = self.mindlin.hertz.radius;
        (0..8)
            .filter_map(|ring| {
                let (lo, hi) = (ring as f64 * 0.1 * a, (ring + 1) as f64 * 0.1 * a);
                let inside: Vec<&NodeSample> = self
                    .nodes
                    .iter()
                    .filter(|n| n.r >= lo && n.r < hi && keep(n))
                    .collect();
                if inside.is_empty() {
                    return None;
                }
                let k = inside.len() as f64;
                let mean = inside.iter().map(|n| n.traction).sum::<f64>() / k;
                let mindlin = inside.iter().map(|n| reference.traction(n.r)).sum::<f64>() / k;
                Some((0.5 * (lo + hi), mean, mindlin))
            })
            .collect()
    }

    /// The largest ring error over `μ p₀`.
    pub fn worst_ring(&self) -> f64 {
        self.worst_of(&self.rings())
    }

    /// The largest error of `rings` over `μ p₀`.
    pub fn worst_of(&self, rings: &[(f64, f64, f64)]) -> f64 {
        let scale = self.mindlin.mu * self.mindlin.hertz.peak_pressure;
        rings
            .iter()
            .map(|(_, mean, reference)| (mean - reference).abs() / scale)
            .fold(0.0, f64::max)
    }

    /// Diagnostics of the ring error, not the reported figure: per sector
    /// of the angle from `+x` (45° each) the fitted stick radius and the
    /// worst ring; the ring errors against Mindlin's `q` with the fitted
    /// stick radius instead of `c = a (1 − Q/(μP))^{1/3}`; the traction
    /// across the load, `q_y`, at the sticking and at the slipping nodes,
    /// and its fit `q_y = A sin 2φ` (Mindlin's `A = 0`; for `ν ≠ 0` the
    /// exact slip in the annulus is not parallel to `x`, Munisamy, Hills
    /// and Nowell 1994).
    pub fn diagnostics(&self) -> String {
        let m = &self.mindlin;
        let scale = m.mu * m.hertz.peak_pressure;
        let mut text = format!("ν = {}\n", self.poisson_ratio);
        for sector in 0..4 {
            let (lo, hi) = (45.0 * sector as f64, 45.0 * (sector + 1) as f64);
            let keep = |n: &NodeSample| n.angle() >= lo && (n.angle() < hi || hi == 180.0);
            let c = fitted_stick_radius(self.nodes.iter().filter(|n| keep(n)));
            let rings = self.rings_of(keep, m);
            text += &format!(
                "  sector {lo:>3}°…{hi:>3}°: stick radius {c:.5} ({:+.2} % of Mindlin's), \
                 worst ring {:.2} % of μp0, rings {}\n",
                100.0 * (c / m.stick_radius - 1.0),
                100.0 * self.worst_of(&rings),
                percentages(&rings, scale)
            );
        }
        let fitted = Mindlin {
            stick_radius: self.stick_radius,
            ..*m
        };
        let rings = self.rings_of(|_| true, &fitted);
        text += &format!(
            "  against Mindlin's q with the fitted c = {:.5}: worst ring {:.2} %, rings {}\n",
            self.stick_radius,
            100.0 * self.worst_of(&rings),
            percentages(&rings, scale)
        );
        for status in [ContactStatus::Stick, ContactStatus::Slip] {
            // least squares of q_y = A sin 2φ, φ = atan2(y, x)
            let (mut qq, mut qs, mut ss, mut k) = (0.0, 0.0, 0.0, 0.0);
            for n in self.nodes.iter().filter(|n| n.status == status) {
                let sin = (2.0 * n.y_reference.atan2(n.x)).sin();
                qq += n.traction_y.powi(2);
                qs += n.traction_y * sin;
                ss += sin * sin;
                k += 1.0;
            }
            text += &format!(
                "  q_y at the {status:?} nodes: rms {:.2} % of μp0, fit q_y = {:+.2} % of μp0 × sin 2φ\n",
                100.0 * (qq / k).sqrt() / scale,
                100.0 * qs / ss / scale
            );
        }
        text.trim_end().to_string()
    }

    /// One line of figures.
    pub fn describe(&self) -> String {
        let m = &self.mindlin;
        format!(
            "t = {:.3}: P = {:.5}, Q/(μP) = {:.4}, a = {:.5} (fit {:+.2} %), p0 = {:.3}; \
             stick radius {:.5} (fit) vs Mindlin {:.5} ({:+.2} %; c/a of the fits {:+.2} % from \
             Mindlin's), outermost stick node {:.5}, innermost slip node {:.5}; ring means \
             within {:.2} % of μp0; {} iterations",
            self.time,
            self.force,
            m.ratio,
            m.hertz.radius,
            100.0 * (self.contact_radius / m.hertz.radius - 1.0),
            m.hertz.peak_pressure,
            self.stick_radius,
            m.stick_radius,
            100.0 * (self.stick_radius / m.stick_radius - 1.0),
            100.0
                * (self.stick_radius / self.contact_radius / (1.0 - m.ratio).max(0.0).cbrt() - 1.0),
            self.outermost_stick,
            self.innermost_slip,
            100.0 * self.worst_ring(),
            self.iterations
        )
    }
}

/// The ring errors `(mean − Mindlin)/scale` in percent after each ring's
/// middle `r`, one line.
fn percentages(rings: &[(f64, f64, f64)], scale: f64) -> String {
    rings
        .iter()
        .map(|(r, mean, reference)| format!("{r:.4}: {:+.2}", 100.0 * (mean - reference) / scale))
        .collect::<Vec<_>>()
        .join(", ")
}
