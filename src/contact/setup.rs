//! Building contact interfaces from a mesh: the case file, the tests and a
//! library user build them the same way, with [`ContactInterface::rigid`],
//! [`ContactInterface::between_bodies`] and [`ContactInterface::two_pass`]
//! and an [`Enforcement`] (a method with its parameters given or automatic).
//!
//! ## Automatic parameters
//! Without a penalty and a scaling the law's parameters follow the local
//! mesh size: `p = k = E/h_s` at each secondary node, `h_s = √A_s` its own
//! size (the interface's law holds `E/h`, `h = √(mean A_s)`, and each node
//! the factor `h/h_s`), times [`uzawa::AUTOMATIC_FACTOR`] for Uzawa's `ε`.
//! The tangential penalty defaults to the normal penalty when one is given,
//! else to `E/h_s` for the penalty law and [`friction::AUGMENTED_FACTOR`]
//! `E/h_s` where friction sticks exactly (Uzawa, Rockafellar, slack with
//! `exact_stick`, [`ContactInterface::exact_stick`]).
//!
//! `E/h` is the stiffness of one element layer (traction per unit
//! displacement). Against a rigid obstacle it is the secondary body's,
//! `k_s = E_s/h`. Between two bodies both sides deform: the secondary
//! with `k_s = E_s/h`, the primary with `k_p = E_p/h_p` (`h_p = √(A_p/n_p)`
//! its surface's area per node), and the contact sees the two element
//! layers in series, `(1/k_s + 1/k_p)⁻¹`. The law takes twice that, the
//! harmonic mean [`pair_stiffness`] `2 k_s k_p / (k_s + k_p)`: `E/h` for
//! two alike bodies (as before, and as against an obstacle), and twice the
//! softer side's when one side is far stiffer. The stiffer side's value
//! (what the stiffest material's `E` gave) makes the contact a near-rigid
//! constraint on the soft side when the two differ a lot — a stiff die on
//! a soft slab, `k_s/k_p ≈ 2000` in `examples/ironing` — an ill-conditioned
//! tangent on which Newton crawls through the active set (there: 35 cuts
//! and 1691 iterations to reach t = 1.21 of 2, stopped after ten minutes;
//! the harmonic mean runs the whole case in fewer iterations than a
//! hand-set penalty, see its README); nothing is gained by it, since the soft side's
//! own compliance bounds how well the contact can be resolved: a penalty's
//! penetration `t_N/ε` is, with the harmonic mean, about half the
//! compression of one element layer of the softer side, as it is for one
//! body against an obstacle. (The geometric mean `√(k_s k_p)` was tried
//! too: 1060 iterations and 9 cuts in ironing.)

use super::friction::{self, Coulomb, FrictionMultiplier};
use super::interface::{ContactInterface, Primary};
use super::laws::{automatic_parameters, uzawa, NormalLaw};
use super::mortar_contact::MortarSurfaces;
use super::mortar_rigid::MortarObstacle;
use super::obstacle::RigidObstacle;
use super::primary::PrimarySurface;
use super::tributary::tributary_areas;
use crate::assembly::amplitude::Amplitude;
use crate::mesh::Mesh;
use nalgebra::Vector3;

/// How the normal constraint is enforced (the parameters are in
/// [`Enforcement`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    Penalty,
    Uzawa,
    Rockafellar,
    Slack,
}

/// A normal law and Coulomb friction as a user gives them.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Enforcement {
    pub method: Method,
    /// The penalty `p` (`ε` of penalty and Uzawa); `None`: automatic.
    pub penalty: Option<f64>,
    /// The scaling `k` of the Rockafellar laws; `None`: automatic.
    pub scaling: Option<f64>,
    /// Young's modulus `E` of the automatic parameters: that of the body of
    /// the secondary surface.
    pub youngs_modulus: f64,
    /// Young's modulus of the primary surface's body, for contact between
    /// bodies (`None`: the secondary's, or a rigid obstacle).
    pub primary_youngs_modulus: Option<f64>,
    /// Friction coefficient `μ` (`None`: frictionless).
    pub friction_coefficient: Option<f64>,
    /// Tangential penalty `ε_T`; `None`: automatic.
    pub tangential_penalty: Option<f64>,
    /// Exact stick by the tangential augmented Lagrangian (the Lagrangian
    /// methods against a rigid obstacle); `false`: the regularised law.
    pub exact_stick: bool,
    /// How exact stick finds its tangential multiplier (Newton unknowns
    /// by default).
    pub friction_multiplier: FrictionMultiplier,
}

impl From<NormalLaw> for Enforcement {
    /// The law with its parameters given, frictionless.
    fn from(law: NormalLaw) -> Self {
        let (method, penalty, scaling) = match law {
            NormalLaw::Penalty { epsilon } => (Method::Penalty, epsilon, None),
            NormalLaw::Uzawa { epsilon } => (Method::Uzawa, epsilon, None),
            NormalLaw::Rockafellar { p, k } => (Method::Rockafellar, p, Some(k)),
            NormalLaw::Slack { p, k } => (Method::Slack, p, Some(k)),
        };
        Enforcement {
            method,
            penalty: Some(penalty),
            scaling,
            youngs_modulus: 1.0,
            primary_youngs_modulus: None,
            friction_coefficient: None,
            tangential_penalty: None,
            exact_stick: false,
            friction_multiplier: FrictionMultiplier::default(),
        }
    }
}

/// Why an interface cannot be built.
#[derive(Clone, Debug, PartialEq)]
pub enum SetupError {
    /// The mesh has no surface set of this name.
    UnknownSurface(String),
    /// The secondary surface has no nodes or no area.
    NoArea(String),
    /// The surface (secondary or primary) has quadratic faces (Tri6,
    /// Quad8): node-to-surface contact gives a Tri6's corners no share of
    /// a uniform pressure (`∫ N_corner dA = 0`), and a Quad8's a negative
    /// one; they need the mortar method's segment integration.
    QuadraticSurface(String),
    /// The secondary surface's element size `h = √(mean A_s)` is not a
    /// positive finite length (coordinates so large that areas overflow).
    Degenerate { surface: String, element_size: f64 },
    /// A secondary node starts inside the primary side: its reference gap
    /// `g < −tolerance` ([`ContactInterface::check_reference_gaps`]).
    InitialPenetration {
        surface: String,
        /// The node's id in the mesh file.
        node: u64,
        gap: f64,
        tolerance: f64,
    },
    /// A rigid plane with every node of the mesh behind it (height
    /// `(x − p)·n < −tolerance`), and so every secondary gap negative: its
    /// normal points away from the body. `nearest` is the largest height.
    PlaneNormalAway { surface: String, nearest: f64 },
}

impl std::fmt::Display for SetupError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SetupError::UnknownSurface(s) => write!(f, "the mesh has no surface set '{s}'"),
            SetupError::NoArea(s) => write!(f, "surface '{s}' has no area"),
            SetupError::QuadraticSurface(s) => f.write_str(&Self::quadratic_surface_message(s)),
            SetupError::Degenerate {
                surface,
                element_size,
            } => write!(
                f,
                "surface '{surface}' has the element size {element_size} (the square root of its \
                 mean area per node), not a positive finite length"
            ),
            SetupError::InitialPenetration {
                surface,
                node,
                gap,
                tolerance,
            } => write!(
                f,
                "node {node} of surface '{surface}' starts inside the primary side (gap {gap:.3e}, \
                 tolerance {tolerance:.3e}); move the bodies apart, or check the normal"
            ),
            SetupError::PlaneNormalAway { surface, nearest } => write!(
                f,
                "the whole body of surface '{surface}' is behind the plane (every node, the nearest \
                 at {nearest:.3e}), so its normal points away from the body; flip it"
            ),
        }
    }
}

impl std::error::Error for SetupError {}

impl SetupError {
    /// The surface the error is about.
    pub fn surface(&self) -> &str {
        match self {
            SetupError::UnknownSurface(s)
            | SetupError::NoArea(s)
            | SetupError::QuadraticSurface(s) => s,
            SetupError::Degenerate { surface, .. }
            | SetupError::InitialPenetration { surface, .. }
            | SetupError::PlaneNormalAway { surface, .. } => surface,
        }
    }

    /// The message of [`SetupError::QuadraticSurface`] for surface `s`.
    pub fn quadratic_surface_message(s: &str) -> String {
        format!(
            "surface '{s}' has quadratic faces (Tri6/Quad8, of Tet10, Hex20 or Wedge15 \
             elements): node-to-surface contact gives their corner nodes no share of a uniform \
             pressure: give the contact discretisation = \"mortar\" (the default for quadratic \
             faces where mortar takes the pairing), or mesh the contact bodies with linear \
             elements (Gmsh -order 1; C3D4, C3D8)"
        )
    }
}

/// Surface set `name` of `mesh`, or [`SetupError::UnknownSurface`].
fn surface_set<'m>(mesh: &'m Mesh, name: &str) -> Result<&'m crate::mesh::SurfaceSet, SetupError> {
    mesh.surface(name)
        .ok_or_else(|| SetupError::UnknownSurface(name.to_string()))
}

/// [`SetupError::QuadraticSurface`] if a facet of `set` is quadratic.
fn linear_faces(set: &crate::mesh::SurfaceSet) -> Result<(), SetupError> {
    if set.facets.iter().any(|f| f.kind.is_quadratic()) {
        return Err(SetupError::QuadraticSurface(set.name.clone()));
    }
    Ok(())
}

/// The automatic stiffness of a contact between two deformable sides of
/// stiffnesses `k_s` (secondary) and `k_p` (primary): their harmonic mean
/// `2 k_s k_p / (k_s + k_p)`, twice the two sides in series (the module's
/// documentation says why).
pub fn pair_stiffness(k_s: f64, k_p: f64) -> f64 {
    2.0 * k_s * k_p / (k_s + k_p)
}

impl Enforcement {
    /// Set the law, friction and per-node factors of `c` from its
    /// (whole) tributary areas and element size.
    fn apply(&self, c: &mut ContactInterface) {
        let h = c.element_size;
        let (secondary, _) = automatic_parameters(self.youngs_modulus, h);
        // between bodies, both sides' stiffness (the primary's per node of its surface)
        let h_p = match &c.primary {
            Primary::Surface(p) if !p.nodes.is_empty() => {
                let area = p.element_size.powi(2) * p.triangles.len() as f64;
                Some((area / p.nodes.len() as f64).sqrt())
            }
            Primary::Mortar(m) if !m.primary_nodes.is_empty() => {
                let area = m.element_size.powi(2) * m.primary_faces.len() as f64;
                Some((area / m.primary_nodes.len() as f64).sqrt())
            }
            _ => None,
        };
        let base = match (h_p, self.primary_youngs_modulus) {
            (Some(h_p), Some(e_p)) if h_p > 0.0 && h_p.is_finite() => {
                pair_stiffness(secondary, automatic_parameters(e_p, h_p).0)
            }
            _ => secondary,
        };
        let auto = match self.method {
            Method::Uzawa => base * uzawa::AUTOMATIC_FACTOR,
            _ => base,
        };
        let (p, k) = (self.penalty.unwrap_or(auto), self.scaling.unwrap_or(auto));
        c.law = match self.method {
            Method::Penalty => NormalLaw::Penalty { epsilon: p },
            Method::Uzawa => NormalLaw::Uzawa { epsilon: p },
            Method::Rockafellar => NormalLaw::Rockafellar { p, k },
            Method::Slack => NormalLaw::Slack { p, k },
        };
        // automatic parameters follow the local mesh size: E/h_s, h_s = √A_s
        c.node_scale = if self.penalty.is_none() && self.scaling.is_none() {
            c.areas.iter().map(|a| h / a.sqrt().max(1e-300)).collect()
        } else {
            Vec::new()
        };
        c.friction = self.friction_coefficient.map(|mu| Coulomb {
            coefficient: mu,
            // default: the user's normal penalty, else E/h_s (times the
            // exact-stick factor for the laws whose outer loop it speeds)
            tangential_penalty: match (self.tangential_penalty, self.penalty) {
                (Some(eps), _) => eps,
                (None, Some(_)) => p,
                (None, None) if c.exact_stick() => base * friction::AUGMENTED_FACTOR,
                (None, None) => base,
            },
        });
        c.tangential_scale = if self.tangential_penalty.is_none() {
            c.node_scale.clone()
        } else {
            Vec::new()
        };
    }
}

impl ContactInterface {
    /// The nodes of surface `secondary` of `mesh` against `primary`,
    /// enforced by `enforcement`: named after the surface, not moving, each
    /// node with its tributary area, element size `h = √(mean A_s)`; a
    /// primary surface paired in the reference configuration.
    pub fn new(
        mesh: &Mesh,
        secondary: &str,
        primary: Primary,
        enforcement: &Enforcement,
    ) -> Result<Self, SetupError> {
        let set = surface_set(mesh, secondary)?;
        let (nodes, mut areas) = tributary_areas(mesh, set);
        match &primary {
            // the mortar nodes' areas are D_j (where a segment reaches them)
            Primary::Mortar(m) => {
                let d = m.reference_areas(mesh, &nodes).unwrap_or_default();
                for (a, d) in areas.iter_mut().zip(d) {
                    if d > 0.0 {
                        *a = d;
                    }
                }
            }
            // D_j = ∫ Ñ_j dA: every face of the node is integrated
            Primary::MortarRigid(m) => {
                for (a, d) in areas.iter_mut().zip(m.reference_areas(mesh)) {
                    if d > 0.0 {
                        *a = d;
                    }
                }
            }
            _ => linear_faces(set)?,
        }
        let total: f64 = areas.iter().sum();
        if nodes.is_empty() || !(total > 0.0) {
            return Err(SetupError::NoArea(secondary.to_string()));
        }
        let element_size = (total / nodes.len() as f64).sqrt();
        // the automatic parameters E/h need a positive finite h
        if !(element_size > 0.0 && element_size.is_finite()) {
            return Err(SetupError::Degenerate {
                surface: secondary.to_string(),
                element_size,
            });
        }
        let mut c = ContactInterface {
            name: secondary.to_string(),
            surface: secondary.to_string(),
            element_size,
            nodes,
            report_areas: areas.clone(),
            areas,
            secondary_surface: match primary {
                Primary::Surface(_) => PrimarySurface::from_mesh(mesh, secondary),
                Primary::Rigid(_) | Primary::Mortar(_) | Primary::MortarRigid(_) => None,
            },
            primary,
            motion: Vector3::zeros(),
            amplitude: Amplitude::ramp(),
            law: NormalLaw::Penalty { epsilon: 0.0 },
            friction: None,
            tangential_scale: Vec::new(),
            node_scale: Vec::new(),
            multiplier_offset: 0,
            exact_stick_requested: enforcement.exact_stick,
            friction_multiplier: enforcement.friction_multiplier,
            prescribed_axes: Vec::new(),
        };
        enforcement.apply(&mut c);
        if let Primary::Surface(p) = &mut c.primary {
            let zero = vec![0.0; 3 * mesh.num_nodes()];
            p.refresh(&mesh.nodes, &zero, &c.nodes, 0.0, None);
        }
        Ok(c)
    }

    /// Surface `secondary` against surface `primary` of another body
    /// through dual mortar ([`mortar_contact`](super::mortar_contact)):
    /// linear and quadratic faces, each secondary node on its area `D_j`.
    pub fn mortar(
        mesh: &Mesh,
        secondary: &str,
        primary: &str,
        enforcement: &Enforcement,
    ) -> Result<Self, SetupError> {
        let set = surface_set(mesh, secondary)?;
        let nodes = mesh.surface_nodes(set);
        let surfaces = MortarSurfaces::from_mesh(mesh, secondary, primary, &nodes)
            .ok_or_else(|| SetupError::UnknownSurface(primary.to_string()))?;
        let mut c = Self::new(mesh, secondary, Primary::Mortar(surfaces), enforcement)?;
        if let (true, Primary::Mortar(m)) = (c.has_friction(), &mut c.primary) {
            m.track_slip(&mesh.nodes);
        }
        Ok(c)
    }

    /// Surface `secondary` against a rigid obstacle through dual mortar
    /// over the secondary surface ([`mortar_rigid`](super::mortar_rigid)):
    /// linear and quadratic faces, each node on its area `D_j = ∫ Ñ_j dA`
    /// (fixed: see [`moving`](Self::moving)).
    pub fn mortar_rigid(
        mesh: &Mesh,
        secondary: &str,
        obstacle: RigidObstacle,
        enforcement: &Enforcement,
    ) -> Result<Self, SetupError> {
        let set = surface_set(mesh, secondary)?;
        let nodes = mesh.surface_nodes(set);
        let surface = MortarObstacle::from_mesh(mesh, secondary, &nodes, obstacle)
            .ok_or_else(|| SetupError::UnknownSurface(secondary.to_string()))?;
        Self::new(
            mesh,
            secondary,
            Primary::MortarRigid(Box::new(surface)),
            enforcement,
        )
    }

    /// Surface `secondary` against a rigid obstacle (fixed: see
    /// [`moving`](Self::moving)).
    pub fn rigid(
        mesh: &Mesh,
        secondary: &str,
        obstacle: RigidObstacle,
        enforcement: &Enforcement,
    ) -> Result<Self, SetupError> {
        Self::new(mesh, secondary, Primary::Rigid(obstacle), enforcement)
    }

    /// Surface `secondary` against surface `primary` of another body of the
    /// mesh, paired in the reference configuration.
    pub fn between_bodies(
        mesh: &Mesh,
        secondary: &str,
        primary: &str,
        enforcement: &Enforcement,
    ) -> Result<Self, SetupError> {
        let set = surface_set(mesh, primary)?;
        linear_faces(set)?;
        let surface = PrimarySurface::from_mesh(mesh, primary)
            .ok_or_else(|| SetupError::UnknownSurface(primary.to_string()))?;
        Self::new(mesh, secondary, Primary::Surface(surface), enforcement)
    }

    /// The two passes of a symmetric interface between bodies: `secondary`
    /// against `primary`, and `primary` against `secondary` (named
    /// `"{secondary}.reverse"`), each node on half its tributary area (the
    /// parameters are those of the whole area).
    pub fn two_pass(
        mesh: &Mesh,
        secondary: &str,
        primary: &str,
        enforcement: &Enforcement,
    ) -> Result<[Self; 2], SetupError> {
        let forward = Self::between_bodies(mesh, secondary, primary, enforcement)?;
        // the reverse pass's secondary body is the forward pass's primary one
        let swapped = match enforcement.primary_youngs_modulus {
            Some(e_p) => Enforcement {
                youngs_modulus: e_p,
                primary_youngs_modulus: Some(enforcement.youngs_modulus),
                ..*enforcement
            },
            None => *enforcement,
        };
        let reverse = Self::between_bodies(mesh, primary, secondary, &swapped)?
            .named(&format!("{secondary}.reverse"));
        Ok([forward, reverse].map(|mut c| {
            c.areas.iter_mut().for_each(|a| *a *= 0.5);
            c
        }))
    }

    /// The initial penetration accepted by default: `0.01 h`, a hundredth
    /// of the secondary surface's element size.
    pub fn default_penetration_tolerance(&self) -> f64 {
        0.01 * self.element_size
    }

    /// The physics of the reference configuration (`u = 0`, `t = 0`):
    /// [`SetupError::PlaneNormalAway`] for a rigid plane with every node of
    /// the mesh more than `tolerance` behind it (a plane raised into the
    /// body leaves some in front, and is an initial penetration instead),
    /// then [`SetupError::InitialPenetration`] for the first secondary node
    /// with a gap `g < −tolerance`.
    pub fn check_reference_gaps(&self, mesh: &Mesh, tolerance: f64) -> Result<(), SetupError> {
        let zero = vec![0.0; 3 * mesh.num_nodes()];
        let gaps = self.gaps(&mesh.nodes, 0.0, &zero, None);
        let plane = match &self.primary {
            Primary::Rigid(o) => Some(o),
            Primary::MortarRigid(m) => Some(&m.obstacle),
            _ => None,
        };
        if let Some(RigidObstacle::Plane { point, normal }) = plane {
            let height = |x: &[f64; 3]| (Vector3::from(*x) - point).dot(normal);
            if !gaps.is_empty()
                && gaps.iter().all(|&g| g < -tolerance)
                && mesh.nodes.iter().all(|x| height(x) < -tolerance)
            {
                let nearest = mesh
                    .nodes
                    .iter()
                    .map(height)
                    .fold(f64::NEG_INFINITY, f64::max);
                return Err(SetupError::PlaneNormalAway {
                    surface: self.surface.clone(),
                    nearest,
                });
            }
        }
        match gaps.iter().position(|&g| g < -tolerance) {
            Some(j) => Err(SetupError::InitialPenetration {
                surface: self.surface.clone(),
                node: mesh.node_ids[self.nodes[j]],
                gap: gaps[j],
                tolerance,
            }),
            None => Ok(()),
        }
    }

    /// The interface renamed (reports, output).
    pub fn named(self, name: &str) -> Self {
        Self {
            name: name.to_string(),
            ..self
        }
    }

    /// The obstacle translated by `motion · amplitude(t)`.
    pub fn moving(self, motion: Vector3<f64>, amplitude: Amplitude) -> Self {
        Self {
            motion,
            amplitude,
            ..self
        }
    }
}
