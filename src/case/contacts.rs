//! The `[[obstacle]]` and `[[contact]]` tables, validated into rigid
//! obstacles and contact interfaces.

use super::schema::{
    CaseFile, ContactMethod, ContactSpec, DiscretisationSpec, FrictionMultiplierSpec,
    MaterialModel, ObstacleShape,
};
use super::{not_positive, Case};
use crate::contact::friction::FrictionMultiplier;
use crate::contact::interface::ContactInterface;
use crate::contact::setup::{Enforcement, Method, SetupError};
use crate::contact::{RigidObstacle, TriangulatedSurface};
use crate::mesh::Mesh;
use crate::problem::Problem;
use crate::solve::settings::Strategy;
use crate::{Error, Result};
use nalgebra::Vector3;
use std::collections::HashSet;

/// What the secondary nodes of a `[[contact]]` touch.
enum Target<'a> {
    /// The `[[obstacle]]` at this index.
    Obstacle(usize),
    /// The surface set of another body.
    Surface(&'a str),
}

/// The words a reverse pass's errors add to the contact's key.
const REVERSE_PASS: &str = " (two_pass: the reverse pass)";

impl Case {
    /// The `[[obstacle]]` at index `i`, validated.
    pub(super) fn obstacle(&self, i: usize) -> Result<RigidObstacle> {
        let o = &self.spec.obstacle[i];
        let with_key = |e: Error| self.err(format!("obstacle[{i}] ('{}'): {e}", o.name));
        let v = Vector3::from;
        Ok(match &o.shape {
            ObstacleShape::Plane { point, normal } => {
                RigidObstacle::plane(v(*point), v(*normal)).map_err(with_key)?
            }
            ObstacleShape::Sphere { center, radius } => {
                RigidObstacle::sphere(v(*center), *radius).map_err(with_key)?
            }
            ObstacleShape::Cylinder {
                point,
                axis,
                radius,
            } => RigidObstacle::cylinder(v(*point), v(*axis), *radius).map_err(with_key)?,
            ObstacleShape::Stl { file } => RigidObstacle::Triangulated(
                TriangulatedSurface::from_stl(&self.dir().join(file))
                    .map_err(|e| self.file_error(&format!("obstacle[{i}].file"), e))?,
            ),
            ObstacleShape::Gmsh { file, surface } => {
                let mesh = crate::mesh::gmsh::read_surface_msh(&self.dir().join(file))
                    .map_err(|e| self.file_error(&format!("obstacle[{i}].file"), e))?;
                RigidObstacle::Triangulated(TriangulatedSurface::from_surface_facets(
                    &mesh, surface,
                )?)
            }
        })
    }

    /// The `[[contact]]` interfaces, validated against the mesh and the
    /// obstacles, with automatic parameters where none are given. The
    /// checks run in the order a user reads the table: the surfaces, the
    /// passes, the enforcement's keys, the pairing, then each pass's
    /// set-up and its reference gaps.
    pub(super) fn contacts(&self, problem: &Problem) -> Result<Vec<ContactInterface>> {
        let mut out = Vec::new();
        for (i, c) in self.spec.contact.iter().enumerate() {
            let key = format!("contact[{i}]");
            self.surface(&format!("{key}.surface"), &c.surface)?;
            let target = self.contact_target(&key, c)?;
            let name = c.name.clone().unwrap_or_else(|| c.surface.clone());
            self.check_two_pass(&key, c, &target, &name)?;
            let enforcement = self.enforcement(&key, c, &target, problem)?;
            if let Target::Surface(primary) = target {
                self.check_not_self_paired(&key, c, primary)?;
            }
            for (interface, pass, against) in self.passes(&key, c, &target, &name, &enforcement)? {
                self.check_initial_gaps(&key, c, &target, &interface, pass, &against)?;
                out.push(interface);
            }
        }
        Ok(out)
    }

    /// Young's modulus of the body under surface set `surface`: of the
    /// stiffest material among the elements that hold one of its nodes (of
    /// the stiffest material of all without such elements).
    fn youngs_of(&self, problem: &Problem, surface: &str) -> f64 {
        let model = &problem.model;
        let stiffest = |e: &mut dyn Iterator<Item = usize>| {
            e.map(|m| model.materials[m].reference_youngs_modulus())
                .fold(0.0f64, f64::max)
        };
        // a mask, not the set: every node of every element is looked up
        let on_surface = self.surface_nodes(surface).map(|nodes| {
            let mut marked = vec![false; self.mesh.nodes.len()];
            (nodes.iter()).for_each(|&n| marked.get_mut(n).into_iter().for_each(|m| *m = true));
            stiffest(
                &mut self
                    .mesh
                    .elements
                    .iter()
                    .zip(&model.element_material)
                    .filter(|(e, _)| e.nodes.iter().any(|&n| marked[n]))
                    .map(|(_, &m)| m),
            )
        });
        match on_surface {
            Some(e) if e > 0.0 => e,
            _ => stiffest(&mut (0..model.materials.len())),
        }
    }

    /// The nodes of surface set `surface` (`None` where the mesh has none).
    fn surface_nodes(&self, surface: &str) -> Option<HashSet<usize>> {
        self.mesh.surface(surface).map(|set| {
            set.facets
                .iter()
                .flat_map(|f| f.nodes.iter().copied())
                .collect()
        })
    }

    /// What the secondary nodes of `[[contact]]` `key` touch: the
    /// `[[obstacle]]` it names, or the primary surface of another body.
    fn contact_target<'a>(&self, key: &str, c: &'a ContactSpec) -> Result<Target<'a>> {
        let spec = &self.spec;
        match (&c.obstacle, &c.primary) {
            (Some(name), None) => {
                let index = spec
                    .obstacle
                    .iter()
                    .position(|o| &o.name == name)
                    .ok_or_else(|| {
                        let have: Vec<&str> = spec.obstacle.iter().map(|o| o.name.as_str()).collect();
                        self.err(format!(
                            "{key}.obstacle: no [[obstacle]] named '{name}'; {}",
                            crate::error::suggest::listing(name, &have, "none")
                        ))
                    })?;
                Ok(Target::Obstacle(index))
            }
            (None, Some(name)) => {
                self.surface(&format!("{key}.primary"), name)?;
                if name == &c.surface {
                    return Err(self.err(format!(
                        "{key}.primary = '{name}' is the secondary surface itself; name the surface of the other body"
                    )));
                }
                // validated as a primary surface (triangles) here, built by the constructors
                self.primary_surface(&format!("{key}.primary"), name)?;
                Ok(Target::Surface(name))
            }
            _ => Err(self.err(format!(
                "{key}: give either `obstacle` (a rigid [[obstacle]] name) or `primary` (a surface set of another body), not {}",
                if c.obstacle.is_some() { "both" } else { "neither" }
            ))),
        }
    }

    /// `two_pass` (the primary surface's nodes also against the secondary
    /// surface's triangles, each pass on half of every node's tributary
    /// area): between bodies only, with a method without multiplier
    /// unknowns, and with a reverse pass `name.reverse` no other contact
    /// is called.
    fn check_two_pass(
        &self,
        key: &str,
        c: &ContactSpec,
        target: &Target,
        name: &str,
    ) -> Result<()> {
        if !c.two_pass {
            return Ok(());
        }
        if !matches!(target, Target::Surface(_)) {
            return Err(self.err(format!(
                "{key}.two_pass applies to contact between deformable bodies only (with `primary`); \
                 remove it, or name the other body's surface with `primary` instead of `obstacle`"
            )));
        }
        // two passes constrain the same motion twice (at least where
        // nodes coincide: the stacked blocks' 41 constraints have rank
        // 37), and a multiplier unknown per constraint makes the saddle
        // system singular (`tests/two_pass.rs`): only the methods
        // without multiplier unknowns
        if matches!(c.method, ContactMethod::Rockafellar | ContactMethod::Slack) {
            return Err(self.err(format!(
                "{key}.two_pass needs method = \"uzawa\" or \"penalty\" (method is \"{}\"): the two passes \
                 constrain the same motion twice, which makes the multiplier system of rockafellar and slack \
                 singular; uzawa reaches the same Lagrangian solution without multiplier unknowns",
                if matches!(c.method, ContactMethod::Slack) {
                    "slack"
                } else {
                    "rockafellar"
                }
            )));
        }
        let reverse = format!("{name}.reverse");
        match self
            .spec
            .contact
            .iter()
            .position(|o| o.name.as_deref().unwrap_or(&o.surface) == reverse)
        {
            Some(j) => Err(self.err(format!(
                "{key}.two_pass names its reverse pass '{reverse}', which is the name of contact[{j}]; rename one of them"
            ))),
            None => Ok(()),
        }
    }

    /// The enforcement of `[[contact]]` `key`: its method, penalties and
    /// friction keys, each checked (positive, finite, and given together
    /// where one needs another), with the bodies' Young's moduli for the
    /// automatic penalties.
    fn enforcement(
        &self,
        key: &str,
        c: &ContactSpec,
        target: &Target,
        problem: &Problem,
    ) -> Result<Enforcement> {
        let positive = |v: Option<f64>, name: &str| -> Result<Option<f64>> {
            match v {
                Some(x) if !(x > 0.0 && x.is_finite()) => {
                    Err(self.err(not_positive(&format!("{key}.{name}"), x)))
                }
                v => Ok(v),
            }
        };
        let friction_coefficient = self.friction_coefficient(key, c)?;
        if c.discretisation == Some(DiscretisationSpec::Mortar) {
            self.mortar_supported(key, c)?;
        }
        let enforcement = Enforcement {
            method: match c.method {
                ContactMethod::Penalty => Method::Penalty,
                ContactMethod::Uzawa => Method::Uzawa,
                ContactMethod::Rockafellar => Method::Rockafellar,
                ContactMethod::Slack => Method::Slack,
            },
            penalty: positive(c.penalty, "penalty")?,
            scaling: positive(c.scaling, "scaling")?,
            youngs_modulus: self.youngs_of(problem, &c.surface),
            primary_youngs_modulus: match target {
                Target::Surface(primary) => Some(self.youngs_of(problem, primary)),
                Target::Obstacle(_) => None,
            },
            friction_coefficient,
            tangential_penalty: positive(c.tangential_penalty, "tangential_penalty")?,
            exact_stick: exact_stick(c),
            friction_multiplier: match (c.friction_multiplier, c.method) {
                (Some(FrictionMultiplierSpec::Newton), _) => FrictionMultiplier::Newton,
                (None, ContactMethod::Rockafellar | ContactMethod::Slack) => {
                    FrictionMultiplier::Newton
                }
                _ => FrictionMultiplier::Outer,
            },
        };
        self.check_stick_keys(key, c)?;
        Ok(enforcement)
    }

    /// `friction_coefficient` of `[[contact]]` `key`: non-negative and
    /// finite, and given wherever `tangential_penalty` is.
    fn friction_coefficient(&self, key: &str, c: &ContactSpec) -> Result<Option<f64>> {
        match (c.friction_coefficient, c.tangential_penalty) {
            (None, Some(_)) => Err(self.err(format!(
                "{key}.tangential_penalty is given without {key}.friction_coefficient; \
                 add the friction coefficient or remove the tangential penalty"
            ))),
            (Some(mu), _) if !(mu >= 0.0 && mu.is_finite()) => Err(self.err(
                super::not_non_negative(&format!("{key}.friction_coefficient"), mu, ""),
            )),
            (mu, _) => Ok(mu),
        }
    }

    /// `friction_multiplier` and `exact_stick = true` of `[[contact]]`
    /// `key`: only where exact stick applies (friction, and a method with
    /// multipliers to augment), and `"newton"` only with the methods whose
    /// normal multipliers are unknowns of Newton.
    fn check_stick_keys(&self, key: &str, c: &ContactSpec) -> Result<()> {
        if let Some(spec) = c.friction_multiplier {
            let why = if !exact_stick(c) {
                Some(if c.exact_stick == Some(false) {
                    "it applies to exact stick only: remove exact_stick = false or this key"
                } else {
                    "it applies to exact stick only, which needs friction and method rockafellar, slack or uzawa: give friction_coefficient, or remove this key"
                })
            } else if spec == FrictionMultiplierSpec::Newton
                && !matches!(c.method, ContactMethod::Rockafellar | ContactMethod::Slack)
            {
                Some("the tangential multipliers are unknowns of Newton beside the normal ones, which this method does not have: use friction_multiplier = \"outer\" or method = \"rockafellar\" or \"slack\"")
            } else {
                None
            };
            if let Some(why) = why {
                return Err(self.err(format!("{key}.friction_multiplier: {why}")));
            }
        }
        if c.exact_stick == Some(true) {
            let why = if c.friction_coefficient.is_none() {
                Some("it needs friction: give friction_coefficient")
            } else if matches!(c.method, ContactMethod::Penalty) {
                Some("the penalty method keeps the regularised law: use method = \"rockafellar\", \"slack\" or \"uzawa\"")
            } else {
                None
            };
            if let Some(why) = why {
                return Err(self.err(format!("{key}.exact_stick = true: {why}")));
            }
        }
        Ok(())
    }

    /// The same surface under another name (or one holding it) as the
    /// primary of `[[contact]]` `key`: refused, after the checks of the
    /// keys, which name the case file's mistake first.
    fn check_not_self_paired(&self, key: &str, c: &ContactSpec, primary: &str) -> Result<()> {
        let secondary = self.surface_nodes(&c.surface).unwrap_or_default();
        let primary_nodes = self.surface_nodes(primary).unwrap_or_default();
        if !secondary.is_empty() && secondary.is_subset(&primary_nodes) {
            return Err(self.err(format!(
                "{key}: self-paired surface: every node of the secondary surface '{}' is also on the \
                 primary surface '{primary}' (the same surface under another name, or one holding it), \
                 so each node would contact its own facets; name as primary the surface of the other \
                 body",
                c.surface
            )));
        }
        Ok(())
    }

    /// The interfaces of `[[contact]]` `key`, each with the words its
    /// errors add (`""`, or the reverse pass's) and what it touches: one
    /// pass, or with `two_pass` also the primary surface's nodes against
    /// the secondary surface's triangles.
    fn passes(
        &self,
        key: &str,
        c: &ContactSpec,
        target: &Target,
        name: &str,
        enforcement: &Enforcement,
    ) -> Result<Vec<(ContactInterface, &'static str, String)>> {
        let mesh = &self.mesh;
        let mortar = c.discretisation == Some(DiscretisationSpec::Mortar);
        let setup = |e: SetupError| self.setup_error(key, c, e);
        Ok(match *target {
            Target::Obstacle(index) => {
                let o = &self.spec.obstacle[index];
                let motion = o.motion.map(Vector3::from).unwrap_or_else(Vector3::zeros);
                let amplitude =
                    self.amplitude(&format!("obstacle[{index}].amplitude"), &o.amplitude)?;
                let obstacle = self.obstacle(index)?;
                let interface = if mortar {
                    ContactInterface::mortar_rigid(mesh, &c.surface, obstacle, enforcement)
                } else {
                    ContactInterface::rigid(mesh, &c.surface, obstacle, enforcement)
                };
                let interface = interface.map_err(setup)?;
                vec![(
                    interface.named(name).moving(motion, amplitude),
                    "",
                    format!("obstacle '{}'", o.name),
                )]
            }
            Target::Surface(primary) if c.two_pass => {
                let [forward, back] =
                    ContactInterface::two_pass(mesh, &c.surface, primary, enforcement)
                        .map_err(setup)?;
                vec![
                    (
                        forward.named(name),
                        "",
                        format!("primary surface '{primary}'"),
                    ),
                    (
                        back.named(&format!("{name}.reverse")),
                        REVERSE_PASS,
                        format!("primary surface '{}'", c.surface),
                    ),
                ]
            }
            Target::Surface(primary) => {
                let interface = if mortar {
                    ContactInterface::mortar(mesh, &c.surface, primary, enforcement)
                } else {
                    ContactInterface::between_bodies(mesh, &c.surface, primary, enforcement)
                };
                let interface = interface.map_err(setup)?;
                vec![(
                    interface.named(name),
                    "",
                    format!("primary surface '{primary}'"),
                )]
            }
        })
    }

    /// A set-up error of `[[contact]]` `key` in the case file's words,
    /// naming the pass where it is the reverse one.
    fn setup_error(&self, key: &str, c: &ContactSpec, e: SetupError) -> Error {
        let s = e.surface();
        let pass = if *s == c.surface { "" } else { REVERSE_PASS };
        self.err(match e {
            SetupError::NoArea(_) => format!("{key}{pass}: surface '{s}' has no area"),
            SetupError::Degenerate { element_size, .. } => format!(
                "{key}{pass}: surface '{s}' has the element size {} (the square root of its \
                 mean area per node), not a positive finite length; check the mesh's coordinates",
                crate::input::number(element_size)
            ),
            SetupError::UnknownSurface(_) => {
                format!("{key}{pass}: the mesh has no surface set '{s}'")
            }
            SetupError::QuadraticSurface(_) => {
                format!("{key}: {}", SetupError::quadratic_surface_message(s))
            }
            // the reference gaps are checked per pass, below
            _ => format!("{key}{pass}: {e}"),
        })
    }

    /// A surface that starts inside what it touches (beyond
    /// `initial_penetration_tolerance`, by default the interface's) is a
    /// set-up error of `[[contact]]` `key`'s pass `pass`.
    fn check_initial_gaps(
        &self,
        key: &str,
        c: &ContactSpec,
        target: &Target,
        interface: &ContactInterface,
        pass: &str,
        against: &str,
    ) -> Result<()> {
        let tolerance = c
            .initial_penetration_tolerance
            .unwrap_or_else(|| interface.default_penetration_tolerance());
        if !(tolerance >= 0.0 && tolerance.is_finite()) {
            return Err(self.err(super::not_non_negative(
                &format!("{key}.initial_penetration_tolerance"),
                tolerance,
                " (the largest initial penetration accepted, a length)",
            )));
        }
        let plane = match target {
            Target::Obstacle(index) => Some(&self.spec.obstacle[*index]),
            Target::Surface(_) => None,
        };
        interface
            .check_reference_gaps(&self.mesh, tolerance)
            .map_err(|e| self.reference_gap_error(e, key, pass, against, plane))
    }

    /// The message of a failed [`check_reference_gaps`](ContactInterface::check_reference_gaps)
    /// of `[[contact]]` `key` (its pass `pass`, against `against`; the
    /// `[[obstacle]]` it names, whose normal a flipped plane gives).
    fn reference_gap_error(
        &self,
        e: SetupError,
        key: &str,
        pass: &str,
        against: &str,
        obstacle: Option<&super::schema::ObstacleSpec>,
    ) -> Error {
        match (e, obstacle.map(|o| (&o.name, &o.shape))) {
            (
                SetupError::PlaneNormalAway { nearest, .. },
                Some((name, ObstacleShape::Plane { normal, .. })),
            ) => self.err(format!(
                "{key}: obstacle normal pointing away: the whole body is behind plane \
                 '{name}' (every node, the nearest at {nearest:.3e}), so its normal points away \
                 from the body; flip it: normal = [{}, {}, {}]",
                -normal[0] + 0.0,
                -normal[1] + 0.0,
                -normal[2] + 0.0
            )),
            (
                SetupError::InitialPenetration {
                    surface,
                    node,
                    gap,
                    tolerance,
                },
                _,
            ) => self.err(format!(
                "{key}{pass}: node {node} of surface '{surface}' starts inside {against} (gap {gap:.3e}, tolerance {tolerance:.3e}); \
                 move the bodies apart, or check the normal (an obstacle's must point toward the body)"
            )),
            (e, _) => self.err(format!("{key}{pass}: {e}")),
        }
    }

    /// `Ok` where `[[contact]]` `key` (`c`) may take `discretisation =
    /// "mortar"`: between two bodies or against any rigid obstacle, with or
    /// without friction, one pass; else the error naming the key.
    fn mortar_supported(&self, key: &str, c: &ContactSpec) -> Result<()> {
        match mortar_refusal(c) {
            Some(why) => Err(self.err(format!("{key}.discretisation = \"mortar\" with {why}"))),
            None => Ok(()),
        }
    }
}

/// Why `[[contact]]` `c` cannot take dual mortar, in the user's words;
/// `None` where it can.
fn mortar_refusal(c: &ContactSpec) -> Option<&'static str> {
    c.two_pass.then_some(
        "`two_pass`: mortar contact has one pass (its forces balance on both surfaces); \
         remove two_pass",
    )
}

/// Why the default of `[[contact]]` `c` on linear faces is node-to-surface
/// rather than dual mortar, in the user's words; `None` where it is mortar.
/// `curved` tells whether `c`'s obstacle (if any) is not a plane. Mortar is
/// the default wherever it takes the pairing and keeps the run on the path
/// node-to-surface would take under `strategy = "auto"`
/// ([`crate::problem::condensed::not_applicable`]); node-to-surface where
/// mortar refuses the pairing (`two_pass`) or would leave the condensed
/// path for Newton's, which factorises at every iteration: against a
/// curved or triangulated obstacle (mortar's weighted gap is not affine
/// there), with Coulomb friction against an obstacle (mortar's slip
/// relative to the obstacle is Newton's path only) and with penalty
/// (mortar's force `D_j ε ⟨−g⟩` changes with the current area `D_j`).
/// Also node-to-surface against a plane where the run is on Newton's path
/// anyway (`newton`: a finite-strain material, or `strategy =
/// "monolithic"`): there mortar's conditions are node-to-surface's (on a
/// plane with linear faces `g̃_j = D_j g(x_j)`), and Newton on its rows,
/// which carry their derivatives, took 2.3× the CPU of node-to-surface on
/// examples/ogden-plate (session 26, one run each).
fn node_to_surface_default(c: &ContactSpec, curved: bool, newton: bool) -> Option<&'static str> {
    let friction = c.friction_coefficient.is_some_and(|mu| mu > 0.0);
    if c.two_pass {
        Some("`two_pass` (mortar contact has one pass: its forces balance on both surfaces)")
    } else if curved {
        Some(
            "a curved or triangulated obstacle on the condensed path (mortar's weighted gap is \
             not affine there: Newton's path; node-to-surface's is condensed, one factorisation \
             per run)",
        )
    } else if c.obstacle.is_some() && friction {
        Some(
            "Coulomb friction against an obstacle on the condensed path (mortar's is Newton's \
             path only; node-to-surface's is condensed, one factorisation per run)",
        )
    } else if c.method == ContactMethod::Penalty {
        Some(
            "`method = \"penalty\"` on the condensed path (mortar's penalty force changes with \
             the current area: Newton's path; node-to-surface's is condensed, one factorisation \
             per run)",
        )
    } else if c.obstacle.is_some() && newton {
        Some(
            "a plane on Newton's path (a finite-strain material or strategy = \"monolithic\": \
             there mortar's conditions on linear faces are node-to-surface's, and Newton on its \
             rows, which carry their derivatives, costs about twice as much)",
        )
    } else {
        None
    }
}

/// The default `discretisation` of every `[[contact]]` of `spec` that does
/// not give one, on `mesh`: `"mortar"` (dual mortar) on linear faces
/// wherever mortar takes the pairing and keeps the run's path
/// ([`node_to_surface_default`]), and on quadratic faces (Tri6/Quad8:
/// node-to-surface gives their corner nodes no share of a uniform
/// pressure, and refuses them) wherever mortar takes the pairing
/// ([`mortar_refusal`]); else `"node_to_surface"`, with a note for the log
/// saying why (on quadratic faces node-to-surface's refusal then says what
/// to change). An explicit `discretisation` is kept as given.
pub(crate) fn default_discretisations(spec: &mut CaseFile, mesh: &Mesh, notes: &mut Vec<String>) {
    let curved: HashSet<String> = (spec.obstacle.iter())
        .filter(|o| !matches!(o.shape, ObstacleShape::Plane { .. }))
        .map(|o| o.name.clone())
        .collect();
    let newton = spec.solver.strategy == Some(Strategy::Monolithic)
        || !(spec.material.iter()).all(|m| matches!(m.model, MaterialModel::LinearElastic(_)));
    for (i, c) in spec.contact.iter_mut().enumerate() {
        if c.discretisation.is_some() {
            continue;
        }
        let quadratic = (mesh.surface(&c.surface))
            .is_some_and(|s| s.facets.iter().any(|f| f.kind.is_quadratic()));
        let why = match quadratic {
            true => mortar_refusal(c).map(|_| "`two_pass`"),
            false => {
                let curved = c.obstacle.as_ref().is_some_and(|o| curved.contains(o));
                node_to_surface_default(c, curved, newton)
            }
        };
        c.discretisation = Some(match why {
            None => DiscretisationSpec::Mortar,
            Some(why) => {
                let name = c.name.as_deref().unwrap_or(&c.surface);
                notes.push(format!(
                    "contact[{i}] '{name}' takes discretisation = \"node_to_surface\": the \
                     default, dual mortar, does not take {why}; give discretisation to choose"
                ));
                DiscretisationSpec::NodeToSurface
            }
        });
    }
}

/// Whether `[[contact]]` `c` sticks exactly: as its `exact_stick` says,
/// by default where the method has multipliers to augment and there is
/// friction (`μ > 0` with rockafellar, slack or uzawa; the regularised
/// law with penalty or `μ = 0`, where exact stick has nothing to act on).
pub(crate) fn exact_stick(c: &ContactSpec) -> bool {
    c.exact_stick.unwrap_or_else(|| {
        c.friction_coefficient.is_some_and(|mu| mu > 0.0)
            && !matches!(c.method, ContactMethod::Penalty)
    })
}
