//! `*CONTACT PAIR` → `[[contact]]`: `secondary, primary` → `surface`,
//! `primary`; the interaction's `HARD` → the exact Lagrangian
//! (`rockafellar`), `LINEAR` slope `K` → `penalty` with `penalty = K`;
//! `*FRICTION` `μ, λ` → `friction_coefficient = μ`, `tangential_penalty =
//! λ` (CalculiX's stick slope, traction per elastic slip); `LAGRANGE` or
//! `EXACT` → `exact_stick`; `SLIP TOLERANCE` → the default tangential
//! penalty `E/h`.
//!
//! The discretisation ([`discretisation`]): dual mortar
//! (`discretisation = "mortar"`) when the deck asks for it (`TYPE=MORTAR`,
//! `LINMORTAR`, `PGMORTAR`, `PGLINMORTAR`) or when either surface has
//! quadratic faces (Tri6/Quad8 of C3D10, C3D20, C3D15), on which
//! node-to-surface contact gives a face's corners no share of a uniform
//! pressure; node-to-surface otherwise (no `TYPE=`, `NODE TO SURFACE`,
//! `SURFACE TO SURFACE`). Mortar takes the pair's `*FRICTION` (Coulomb on
//! the weighted slip).

use super::super::schema::{ContactMethod, ContactSpec, DiscretisationSpec};
use crate::mesh::inp::physics::{ContactPairDef, Overclosure, PairType, Physics};
use crate::mesh::Mesh;
use crate::Result;

/// `[[contact]]` of the contact pairs, and a note on each mortar pair.
pub(super) fn contacts(
    physics: &Physics,
    mesh: &Mesh,
    notes: &mut Vec<String>,
) -> Result<Vec<ContactSpec>> {
    let mut out = Vec::new();
    for pair in &physics.contact_pairs {
        let i = physics
            .interactions
            .iter()
            .find(|i| i.name.eq_ignore_ascii_case(&pair.interaction))
            .ok_or_else(|| {
                pair.at.error(format!(
                    "*CONTACT PAIR: no *SURFACE INTERACTION named '{}'",
                    pair.interaction
                ))
            })?;
        let discretisation = discretisation(pair, mesh)?;
        let (method, penalty) = match i.overclosure {
            Overclosure::Hard => (ContactMethod::Rockafellar, None),
            Overclosure::Linear { slope } => (ContactMethod::Penalty, Some(slope)),
        };
        let friction = i.friction.filter(|f| f.mu != 0.0);
        if let Some(f) = friction {
            if f.exact && method == ContactMethod::Penalty {
                return Err(i.at.error(format!(
                    "*SURFACE INTERACTION '{}': exact stick (*FRICTION, LAGRANGE) needs HARD contact, not LINEAR",
                    i.name
                )));
            }
            if f.slip_tolerance.is_some() && f.stick_slope.is_none() {
                notes.push(format!(
                    "*FRICTION of '{}': SLIP TOLERANCE is read as the default tangential penalty E/h",
                    i.name
                ));
            }
        }
        if let Some(why) = discretisation {
            notes.push(mortar_note(pair, why));
        }
        out.push(ContactSpec {
            name: None,
            surface: pair.secondary.clone(),
            obstacle: None,
            primary: Some(pair.primary.clone()),
            method,
            penalty,
            scaling: None,
            friction_coefficient: friction.map(|f| f.mu),
            tangential_penalty: friction.and_then(|f| f.stick_slope),
            exact_stick: friction.map(|f| f.exact),
            friction_multiplier: None,
            initial_penetration_tolerance: None,
            two_pass: false,
            discretisation: Some(match discretisation {
                Some(_) => DiscretisationSpec::Mortar,
                None => DiscretisationSpec::NodeToSurface,
            }),
        });
    }
    if out
        .iter()
        .any(|c| c.discretisation == Some(DiscretisationSpec::NodeToSurface))
    {
        notes.push(
            "*CONTACT PAIR: node-to-surface contact of the secondary (first) surface's nodes on the primary (second) surface; HARD is the exact Lagrangian, LINEAR a penalty with the deck's slope, the *FRICTION stick slope the tangential penalty".into(),
        );
    }
    Ok(out)
}

/// Why a pair takes mortar contact.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum WhyMortar {
    /// `TYPE=MORTAR` (or a variant) asks for it.
    Asked,
    /// A surface of the pair has quadratic faces.
    Quadratic,
}

/// `Some(why)` when `pair` takes dual mortar contact, `None` for
/// node-to-surface; an error at the pair's line when the deck asks for
/// node-to-surface on quadratic faces.
fn discretisation(pair: &ContactPairDef, mesh: &Mesh) -> Result<Option<WhyMortar>> {
    let quadratic = [&pair.secondary, &pair.primary].into_iter().find(|name| {
        mesh.surface(name)
            .is_some_and(|s| s.facets.iter().any(|f| f.kind.is_quadratic()))
    });
    match (&pair.pair_type, quadratic) {
        (PairType::Mortar(_), _) => Ok(Some(WhyMortar::Asked)),
        (PairType::NodeToSurface, Some(name)) => Err(pair.at.error(format!(
            "*CONTACT PAIR, TYPE=NODE TO SURFACE: surface '{name}' has quadratic faces \
             (Tri6/Quad8, of C3D10, C3D20 or C3D15 elements), and node-to-surface contact gives \
             their corner nodes no share of a uniform pressure: remove TYPE=NODE TO SURFACE \
             (a pair with quadratic faces then takes mortar contact) or give TYPE=MORTAR, or mesh \
             the contact bodies with linear elements (C3D4, C3D8)"
        ))),
        (_, Some(_)) => Ok(Some(WhyMortar::Quadratic)),
        (_, None) => Ok(None),
    }
}

/// The note on a mortar pair: why, and what a CalculiX variant becomes.
fn mortar_note(pair: &ContactPairDef, why: WhyMortar) -> String {
    let why = match (&pair.pair_type, why) {
        (PairType::Mortar(t), _) if t == "MORTAR" => "TYPE=MORTAR".to_string(),
        (PairType::Mortar(t), _) => format!(
            "TYPE={t}, read as MORTAR: our multipliers are dual ones on the faces' (transformed) \
             shape functions, one per node, whatever CalculiX's variant"
        ),
        _ => "its surfaces have quadratic faces (Tri6/Quad8), on which node-to-surface \
              contact gives the corners no share of a uniform pressure"
            .to_string(),
    };
    format!(
        "*CONTACT PAIR {}, {} (line {}): dual mortar contact (discretisation = \"mortar\"): {why}",
        pair.secondary, pair.primary, pair.at.line
    )
}
