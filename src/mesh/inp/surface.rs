//! `*SURFACE, TYPE=ELEMENT`: element faces (`S<k>`, or every free face)
//! into surface sets.

use super::builder::{kind_name, Member};
use super::deck::{unquote, Keyword, Line};
use super::element_type::{face_count, outward_face};
use super::{data_fields, Reader};
use crate::Result;

impl Reader<'_> {
    /// `*SURFACE, NAME=name[, TYPE=ELEMENT]`: `element-or-set[, S<k>]`.
    pub(super) fn surface(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let name = self.context.name(self.required(line, keyword, "NAME")?);
        if let Some(t) = keyword.param("TYPE") {
            if !t.eq_ignore_ascii_case("ELEMENT") {
                return Err(self.err(
                    line,
                    format!(
                        "*SURFACE, TYPE={t} is not supported: give element faces (TYPE=ELEMENT, \
                         lines 'element or element set, S1…S6'); for a set of nodes use *NSET"
                    ),
                ));
            }
        }
        if data.is_empty() {
            return Err(self.err(line, format!("*SURFACE '{name}' has no data lines")));
        }
        for l in data {
            let fields = data_fields(l);
            if fields.is_empty() || fields.len() > 2 || fields[0].is_empty() {
                return Err(self.err(
                    l,
                    format!(
                        "a *SURFACE line is 'element or element set, face' (e.g. '12, S3'); found '{}'",
                        l.text()
                    ),
                ));
            }
            let members: Vec<Member> = match fields[0].parse::<u64>() {
                Ok(id) => {
                    vec![self
                        .builder
                        .element(self.context.element(id))
                        .ok_or_else(|| {
                            self.err(
                                l,
                                format!("*SURFACE '{name}': no element {id} is defined before"),
                            )
                        })?]
                }
                Err(_) => {
                    let set = self.context.name(unquote(fields[0]));
                    self.builder
                        .element_sets
                        .get(&set)
                        .ok_or_else(|| {
                            self.err(
                                l,
                                format!("*SURFACE '{name}': '{set}' is neither an element id nor an element set defined before ({})", self.missing_set(&set, "element set")),
                            )
                        })?
                        .clone()
                }
            };
            let face = match fields.get(1) {
                None => None,
                Some(f) => Some(self.face_number(l, f)?),
            };
            let label = format!("*SURFACE '{name}'");
            self.add_faces(&name, &label, &members, face, l, fields[0])?;
        }
        Ok(())
    }

    /// Adds face `face` (every free face if `None`) of the volume elements
    /// among `members` to the surface `name`; `label` names the keyword and
    /// `what` the members in the messages of line `l`.
    pub(super) fn add_faces(
        &mut self,
        name: &str,
        label: &str,
        members: &[Member],
        face: Option<usize>,
        l: &Line,
        what: &str,
    ) -> Result<()> {
        if !members.iter().any(|m| matches!(m, Member::Volume(_))) {
            return Err(self.err(
                l,
                format!("{label}: '{what}' holds no C3D4 or C3D8 element, so no face to take"),
            ));
        }
        for &m in members {
            let Member::Volume(e) = m else {
                continue; // surface or line elements have no solid faces
            };
            match face {
                None => self.builder.add_free_faces(name, e),
                Some(s) => {
                    let el = self.builder.volume(e);
                    let local = outward_face(el.kind, s).ok_or_else(|| {
                        self.err(
                            l,
                            format!(
                                "{label}: element {} is a {} with faces S1…S{}, not S{s}",
                                el.id,
                                kind_name(el.kind),
                                face_count(el.kind)
                            ),
                        )
                    })?;
                    self.builder.add_face(name, e, local);
                }
            }
        }
        Ok(())
    }

    /// `S<k>` → `k`.
    fn face_number(&self, line: &Line, field: &str) -> Result<usize> {
        field
            .strip_prefix(['S', 's'])
            .and_then(|k| k.parse::<usize>().ok())
            .filter(|&k| k >= 1)
            .ok_or_else(|| {
                self.err(
                    line,
                    format!("'{field}' is not a face identifier of a solid element (S1, S2, …)"),
                )
            })
    }
}
