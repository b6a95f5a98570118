//! The `[[material]]` tables: one material model per element, and the
//! [`Model`] they make with the mesh.

use super::schema::{ContactMethod, ContactSpec, DiscretisationSpec, MaterialModel};
use super::Case;
use crate::assembly::kernel::KernelFailure;
use crate::assembly::pattern::NodeGraph;
use crate::assembly::Model;
use crate::material::{self, Kinematics, Material};
use crate::problem::SolverSettings;
use crate::solve::ordering::EarlyDissection;
use crate::solve::settings::Strategy;
use crate::{Error, Result};
use std::sync::Arc;

/// The materials, and the index into them of each element's.
type ElementMaterials = (Vec<Arc<dyn Material>>, Vec<usize>);

/// Whether `[[contact]]` `c` between two bodies takes the condensed path
/// under `strategy = "auto"` as far as the case file tells before the
/// problem is built ([`crate::problem::condensed::not_applicable`]): every
/// material small-strain, node-to-surface or dual mortar, frictionless or
/// with Coulomb friction (mortar's since session 22), not uzawa, and not
/// penalty with mortar (`discretisation` is set on reading the case, its
/// default included); then its factor is ordered on the elements' graph,
/// and the dissection of that graph starts early
/// ([`crate::problem::dissects_element_graph`]). Not told here: a body no
/// prescribed displacement holds, a follower pressure, and mortar's exact
/// stick at a secondary node whose components are all prescribed (left to
/// Newton under `auto`). A wrong guess costs the unused dissection on the
/// idle core (and Newton's own dissection of the coupled pattern waits for
/// METIS's lock if that one still runs).
fn condensed_pair(c: &ContactSpec, small_strain: bool) -> bool {
    let mortar = c.discretisation == Some(DiscretisationSpec::Mortar);
    let law = match c.method {
        ContactMethod::Uzawa => false,
        ContactMethod::Penalty => !mortar,
        ContactMethod::Rockafellar | ContactMethod::Slack => true,
    };
    c.primary.is_some() && small_strain && law
}

impl Case {
    /// The material model of `[[material]]` `i`, validated.
    fn material(&self, i: usize) -> Result<Arc<dyn Material>> {
        let key = format!("material[{i}]");
        Ok(match &self.spec.material[i].model {
            MaterialModel::Ogden(c) => Arc::new(material::Ogden::new(
                c.mu.clone(),
                c.alpha.clone(),
                c.bulk_modulus,
                &key,
            )?),
            MaterialModel::LinearElastic(c) => Arc::new(material::LinearElastic::new(
                c.youngs_modulus,
                c.poisson_ratio,
                &key,
            )?),
            MaterialModel::SaintVenantKirchhoff(c) => Arc::new(
                material::SaintVenantKirchhoff::new(c.youngs_modulus, c.poisson_ratio, &key)?,
            ),
            MaterialModel::NeoHookean(c) => Arc::new(material::NeoHookean::new(
                c.youngs_modulus,
                c.poisson_ratio,
                &key,
            )?),
        })
    }

    /// The materials and the index of each element's: exactly one per
    /// element.
    pub(super) fn element_materials(&self) -> Result<ElementMaterials> {
        let spec = &self.spec;
        let mesh = &self.mesh;
        let mut materials: Vec<Arc<dyn Material>> = Vec::new();
        let mut element_material: Vec<Option<usize>> = vec![None; mesh.elements.len()];
        for (i, m) in spec.material.iter().enumerate() {
            let key = format!("material[{i}].region");
            let region = self.region(&key, &m.region)?;
            materials.push(self.material(i)?);
            for &e in &region.elements {
                if let Some(j) = element_material[e] {
                    return Err(self.err(format!(
                        "{key}: element {} of region '{}' already has the material of material[{j}] (region '{}'); give each element one material",
                        mesh.elements[e].id, m.region, spec.material[j].region
                    )));
                }
                element_material[e] = Some(i);
            }
        }
        let element_material = element_material
            .iter()
            .enumerate()
            .map(|(e, m)| m.ok_or_else(|| self.without_material(e)))
            .collect::<Result<Vec<_>>>()?;
        Ok((materials, element_material))
    }

    /// Element `e` has no material: the regions that hold it, and the fix.
    fn without_material(&self, e: usize) -> Error {
        let mesh = &self.mesh;
        let regions: Vec<&str> = mesh
            .regions
            .iter()
            .filter(|r| r.elements.contains(&e))
            .map(|r| r.name.as_str())
            .collect();
        self.err(format!(
            "element {} (region {}) has no material: add a [[material]] with region = \"{}\"",
            mesh.elements[e].id,
            regions.join(", "),
            regions.first().copied().unwrap_or("default")
        ))
    }

    /// The model of the mesh and its materials, and the nested dissection
    /// of the elements' graph, started on the idle core as soon as that
    /// graph exists if the run will order it so; without
    /// `whole_pattern`, a distributed run's process's, whose pattern waits
    /// for the partition ([`Model::with_graph_of`]).
    pub(super) fn model(
        &self,
        materials: Vec<Arc<dyn Material>>,
        element_material: Vec<usize>,
        whole_pattern: bool,
    ) -> Result<(Model, Option<EarlyDissection>)> {
        let spec = &self.spec;
        let mesh = &self.mesh;
        let defaults = SolverSettings::default();
        let small_strain = (materials.iter()).all(|m| m.kinematics() == Kinematics::SmallStrain);
        let strategy = spec.solver.strategy.unwrap_or(defaults.strategy);
        let auto = strategy == Strategy::Auto;
        let dissect = crate::problem::dissects_element_graph(
            spec.solver.linear.unwrap_or(defaults.linear),
            strategy,
            3 * mesh.num_nodes(),
            (spec.contact.iter())
                .map(|c| c.obstacle.is_some() || auto && condensed_pair(c, small_strain)),
        );
        let mut dissection = None;
        let on_graph = |graph: &NodeGraph| {
            if dissect {
                dissection = Some(EarlyDissection::start(graph));
            }
        };
        let model = Model::with_graph_of(
            mesh.clone(),
            materials,
            element_material,
            on_graph,
            whole_pattern,
        );
        let model = model.map_err(|f| {
            let (quadrature_point, det_j) = match f.failure {
                KernelFailure::ReferenceInverted {
                    quadrature_point,
                    det_j,
                } => (quadrature_point, det_j),
                KernelFailure::Inverted {
                    quadrature_point,
                    det_f,
                } => (quadrature_point, det_f),
            };
            Error::InvertedElement {
                element: mesh.elements[f.element].id,
                quadrature_point,
                det_j,
                in_reference: true,
                what: if det_j == 0.0 {
                    "degenerate"
                } else {
                    "inverted"
                },
            }
        })?;
        Ok((model, dissection))
    }
}

#[cfg(test)]
mod tests {
    use crate::problem::condensed::{choose, Path};

    /// The early dissection is started exactly where the run takes the
    /// condensed path ([`choose`]), on examples/two-spheres (two linear
    /// elastic bodies): node-to-surface frictionless and with Coulomb
    /// friction (condensed under `auto` since session 20), dual mortar
    /// frictionless (session 21) and with friction (session 22; the guess
    /// said Newton until session 24), none of them under `monolithic`
    /// (whose pattern with the contact couplings is another graph).
    #[test]
    fn auto_dissects_early_for_bodies_it_condenses() {
        let folder = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/two-spheres");
        let text = std::fs::read_to_string(folder.join("case.toml")).unwrap();
        // whether the dissection started early, and whether the run
        // takes the condensed path: the guess must be the path
        let early = |text: &str| {
            let case = crate::case::from_toml(text, &folder).unwrap();
            let problem = case.build_problem().unwrap();
            let path = choose(&problem).unwrap().path;
            let started = problem.dissection.is_some();
            assert_eq!(started, path == Path::Condensed, "{text}");
            started
        };
        let monolithic = |text: &str| format!("{text}\n[solver]\nstrategy = \"monolithic\"\n");
        let frictional = |text: &str| {
            let with = text.replace(
                "penalty = 1000.0",
                "penalty = 1000.0\nfriction_coefficient = 0.3",
            );
            assert_ne!(with, text);
            with
        };
        let mortar = text.replace(
            "discretisation = \"node_to_surface\"",
            "discretisation = \"mortar\"",
        );
        assert_ne!(mortar, text);
        for variant in [
            text.clone(),
            frictional(&text),
            mortar.clone(),
            frictional(&mortar),
            // without the key: mortar, the default between bodies
            text.replace("discretisation = \"node_to_surface\"", ""),
        ] {
            assert!(early(&variant), "{variant}");
            assert!(!early(&monolithic(&variant)), "{variant}");
        }
    }
}
