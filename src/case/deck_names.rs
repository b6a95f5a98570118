//! The set names of a case file on an Abaqus/CalculiX deck
//! (`mesh.file = "block.inp"`) compared without regard to case, as Abaqus
//! compares its names: `surface = "top"` names the deck's `*SURFACE,
//! NAME=TOP`. Each name of the case file that the deck does not have as
//! written, but has in another case, is replaced by the deck's spelling once,
//! after reading, so that every later look-up (and every message) uses it.
//! A Gmsh mesh's physical names stay case-sensitive, as in Gmsh; a name
//! that differs there only in case gets a "did you mean".

use super::schema::CaseFile;
use crate::mesh::Mesh;

/// `name` replaced by the one of `have` equal to it but for case, if
/// `have` does not hold `name` itself.
fn match_case(name: &mut String, have: &[String]) {
    if have.contains(name) {
        return;
    }
    if let Some(deck) = have.iter().find(|h| h.eq_ignore_ascii_case(name)) {
        *name = deck.clone();
    }
}

/// Every region, surface-set and node-set name of `spec` spelt as `mesh`
/// (read from a deck) spells it. The keys that name a set of the mesh are
/// all here: a new one must be added.
pub(super) fn match_deck_case(spec: &mut CaseFile, mesh: &Mesh) {
    let regions = mesh.region_names();
    let surfaces = mesh.surface_names();
    let node_sets = mesh.node_set_names();
    let region = |n: &mut String| match_case(n, &regions);
    let surface = |n: &mut String| match_case(n, &surfaces);
    let nodes = |n: &mut String| match_case(n, &node_sets);
    spec.material.iter_mut().for_each(|m| region(&mut m.region));
    for d in &mut spec.displacement {
        d.surface.iter_mut().for_each(surface);
        d.nodes.iter_mut().for_each(nodes);
    }
    spec.pressure
        .iter_mut()
        .for_each(|p| surface(&mut p.surface));
    for b in &mut spec.body_force {
        b.region.iter_mut().for_each(region);
    }
    spec.nodal_force
        .iter_mut()
        .for_each(|n| nodes(&mut n.nodes));
    for c in &mut spec.contact {
        surface(&mut c.surface);
        c.primary.iter_mut().for_each(surface);
    }
    for h in &mut spec.output.history {
        h.surface.iter_mut().for_each(surface);
        h.nodes.iter_mut().for_each(nodes);
    }
}
