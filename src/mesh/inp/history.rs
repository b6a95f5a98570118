//! The history keywords of a deck: `*STEP … *END STEP`, `*STATIC`,
//! `*BOUNDARY`, `*CLOAD`, `*DLOAD`/`*DSLOAD` and the output requests.

use super::deck::{unquote, Keyword, Line};
use super::physics::*;
use super::{data_fields, Reader};
use crate::Result;

/// The dofs of the `*BOUNDARY` types of solid nodes (1-based): `ENCASTRE`
/// and `PINNED` fix all three translations, `XSYMM` … the normal one.
fn boundary_type(name: &str) -> Option<(usize, usize)> {
    match name.to_ascii_uppercase().as_str() {
        "ENCASTRE" | "PINNED" => Some((1, 3)),
        "XSYMM" => Some((1, 1)),
        "YSYMM" => Some((2, 2)),
        "ZSYMM" => Some((3, 3)),
        _ => None,
    }
}

impl Reader<'_> {
    /// The step being read, or an error for `keyword` outside one.
    fn current_step(&mut self, line: &Line, keyword: &Keyword) -> Result<&mut StepDef> {
        let message = format!("*{} outside a *STEP", keyword.name);
        let error = self.err(line, message);
        self.step.as_mut().ok_or(error)
    }

    /// `*STEP[, NAME=…][, NLGEOM[=YES|NO]]`.
    pub(super) fn step(&mut self, line: &Line, keyword: &Keyword) -> Result<()> {
        if let Some(open) = &self.step {
            return Err(self.err(
                line,
                format!(
                    "*STEP inside *STEP '{}': close it with *END STEP first",
                    open.name
                ),
            ));
        }
        self.refuse(line, keyword, &["PERTURBATION"])?;
        if let Some(a) = keyword.param("AMPLITUDE") {
            if !a.eq_ignore_ascii_case("RAMP") {
                return Err(self.err(line, format!("*STEP, AMPLITUDE={a} is not supported: loads are ramped over the step (RAMP)")));
            }
        }
        let nlgeom = keyword.has("NLGEOM")
            && !keyword
                .param("NLGEOM")
                .is_some_and(|v| v.eq_ignore_ascii_case("NO"));
        self.step = Some(StepDef {
            name: keyword
                .param("NAME")
                .map(str::to_string)
                .unwrap_or_else(|| format!("Step-{}", self.physics.steps.len() + 1)),
            nlgeom,
            increments: [None; 4],
            direct: false,
            time_points: None,
            new_boundaries: false,
            new_cloads: false,
            new_pressures: false,
            boundaries: Vec::new(),
            cloads: Vec::new(),
            pressures: Vec::new(),
            gravities: Vec::new(),
            outputs: Vec::new(),
            at: self.deck.locate(line),
        });
        Ok(())
    }

    /// `*STATIC[, DIRECT][, TIME POINTS=…]`: `initial, period, min, max`.
    pub(super) fn static_step(
        &mut self,
        line: &Line,
        keyword: &Keyword,
        data: &[Line],
    ) -> Result<()> {
        self.refuse(line, keyword, &["RIKS", "STABILIZE"])?;
        let values = if data.is_empty() {
            Vec::new()
        } else {
            self.one_line(line, keyword, data, 4)?
        };
        let step = self.current_step(line, keyword)?;
        for (k, v) in values.into_iter().enumerate() {
            step.increments[k] = (v != 0.0).then_some(v);
        }
        step.direct = keyword.has("DIRECT");
        step.time_points = keyword.param("TIME POINTS").map(str::to_string);
        Ok(())
    }

    pub(super) fn end_step(&mut self, line: &Line) -> Result<()> {
        let step = self
            .step
            .take()
            .ok_or_else(|| self.err(line, "*END STEP without a *STEP before it".into()))?;
        self.physics.steps.push(step);
        Ok(())
    }

    /// A node set name as the mesh has it, for a node reference of a data
    /// line: a set, a node id or `instance.id` (an implicit set
    /// `node:<global id>`).
    fn node_target(&mut self, l: &Line, field: &str, what: &str) -> Result<String> {
        let field = unquote(field);
        let id = match field.rsplit_once('.').map(|(i, id)| (i, id.parse::<u64>())) {
            Some((instance, Ok(id))) => {
                let i = self.instance_named(instance).ok_or_else(|| {
                    self.err(
                        l,
                        format!("{what}: '{field}': {}", self.missing_set(field, "instance")),
                    )
                })?;
                Some(i.context.node(id))
            }
            _ => field.parse::<u64>().ok().map(|id| self.context.node(id)),
        };
        if let Some(id) = id {
            let index = self
                .builder
                .node(id)
                .ok_or_else(|| self.err(l, format!("{what}: no node {id} is defined")))?;
            let name = format!("node:{id}");
            let set = self.builder.node_sets.entry(&name);
            if set.is_empty() {
                set.push(index);
            }
            return Ok(name);
        }
        let name = self.context.name(field);
        self.builder
            .node_sets
            .canonical(&name)
            .map(str::to_string)
            .ok_or_else(|| {
                self.err(
                    l,
                    format!("{what}: {}", self.missing_set(&name, "node set (*NSET)")),
                )
            })
    }

    /// A dof field, 1 to 3 (translations).
    fn dof(&self, l: &Line, field: &str, what: &str) -> Result<usize> {
        let dof = self.id(l, field, "degree of freedom")?;
        if dof > 3 {
            return Err(self.err(
                l,
                format!("{what}: degree of freedom {dof} is not a translation (1, 2, 3), which is all a solid node has"),
            ));
        }
        Ok(dof as usize)
    }

    /// `OP=NEW` (or the default `MOD`) of a load or boundary keyword.
    fn op_new(&self, line: &Line, keyword: &Keyword) -> Result<bool> {
        match keyword.param("OP") {
            None => Ok(false),
            Some(op) if op.eq_ignore_ascii_case("MOD") => Ok(false),
            Some(op) if op.eq_ignore_ascii_case("NEW") => Ok(true),
            Some(op) => Err(self.err(
                line,
                format!("*{}, OP={op}: OP is MOD or NEW", keyword.name),
            )),
        }
    }

    /// `*BOUNDARY[, OP=…][, AMPLITUDE=…]`: `nodes, first[, last[, value]]`
    /// or `nodes, ENCASTRE|PINNED|XSYMM|YSYMM|ZSYMM`; dofs 4–6 of a range
    /// from 1 are dropped (a solid node has no rotation).
    pub(super) fn boundary(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        self.refuse(line, keyword, &["FIXED", "USER", "SUBMODEL"])?;
        if let Some(t) = keyword.param("TYPE") {
            if !t.eq_ignore_ascii_case("DISPLACEMENT") {
                return Err(self.err(line, format!("*BOUNDARY, TYPE={t} is not supported: displacements (TYPE=DISPLACEMENT) are")));
            }
        }
        let new = self.op_new(line, keyword)?;
        let amplitude = keyword.param("AMPLITUDE").map(str::to_string);
        let mut records = Vec::new();
        for l in data {
            let f = data_fields(l);
            if f.len() < 2 || f.len() > 4 {
                return Err(self.err(l, format!("a *BOUNDARY line is 'node or node set, first dof[, last dof[, value]]'; found '{}'", l.text())));
            }
            let nodes = self.node_target(l, f[0], "*BOUNDARY")?;
            let (first, last, value) = match boundary_type(f[1]) {
                Some((a, b)) => (a, b, 0.0),
                None => {
                    let first = self.id(l, f[1], "first degree of freedom")? as usize;
                    let last = match f.get(2).filter(|s| !s.is_empty()) {
                        Some(s) => self.id(l, s, "last degree of freedom")? as usize,
                        None => first,
                    };
                    let value = match f.get(3) {
                        Some(s) => self.number(l, s)?,
                        None => 0.0,
                    };
                    if last < first {
                        return Err(self.err(
                            l,
                            format!("*BOUNDARY: the last dof {last} is before the first {first}"),
                        ));
                    }
                    self.dof(l, &first.to_string(), "*BOUNDARY")?;
                    (first, last.min(3), value)
                }
            };
            for dof in first..=last {
                records.push(BoundaryDef {
                    nodes: nodes.clone(),
                    dof: dof - 1,
                    value,
                    amplitude: amplitude.clone(),
                    at: self.deck.locate(l),
                });
            }
        }
        match self.step.as_mut() {
            Some(step) => {
                step.new_boundaries |= new;
                step.boundaries.extend(records);
            }
            None => {
                if amplitude.is_some() {
                    return Err(self.err(
                        line,
                        "*BOUNDARY, AMPLITUDE= outside a step: give it in the step".into(),
                    ));
                }
                self.physics.initial_boundaries.extend(records)
            }
        }
        Ok(())
    }

    /// `*CLOAD[, OP=…][, AMPLITUDE=…]`: `nodes, dof, force per node`.
    pub(super) fn cload(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        self.refuse(line, keyword, &["FOLLOWER", "USER"])?;
        let new = self.op_new(line, keyword)?;
        let amplitude = keyword.param("AMPLITUDE").map(str::to_string);
        let mut records = Vec::new();
        for l in data {
            let f = data_fields(l);
            if f.len() != 3 {
                return Err(self.err(
                    l,
                    format!(
                        "a *CLOAD line is 'node or node set, dof, magnitude'; found '{}'",
                        l.text()
                    ),
                ));
            }
            records.push(CloadDef {
                nodes: self.node_target(l, f[0], "*CLOAD")?,
                dof: self.dof(l, f[1], "*CLOAD")? - 1,
                value: self.number(l, f[2])?,
                amplitude: amplitude.clone(),
                at: self.deck.locate(l),
            });
        }
        let step = self.current_step(line, keyword)?;
        step.new_cloads |= new;
        step.cloads.extend(records);
        Ok(())
    }

    /// `*DLOAD`: `elset or element, P<k>, p` (the implicit surface
    /// `<elset>:S<k>`); `*DSLOAD`: `surface, P, p`.
    pub(super) fn pressure(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        self.refuse(line, keyword, &["USER", "FOLLOWER"])?;
        let new = self.op_new(line, keyword)?;
        let amplitude = keyword.param("AMPLITUDE").map(str::to_string);
        let dsload = keyword.name == "DSLOAD";
        let mut records = Vec::new();
        let mut gravities = Vec::new();
        for l in data {
            let f = data_fields(l);
            if !dsload && f.get(1).is_some_and(|t| t.eq_ignore_ascii_case("GRAV")) {
                gravities.push(self.gravity(l, &f, amplitude.clone())?);
                continue;
            }
            if f.len() != 3 {
                return Err(self.err(
                    l,
                    format!(
                        "a *{} line is '{}, P{}, pressure'; found '{}'",
                        keyword.name,
                        if dsload { "surface" } else { "element set" },
                        if dsload { "" } else { "<face>" },
                        l.text()
                    ),
                ));
            }
            let label = f[1].to_ascii_uppercase();
            let surface = if dsload {
                if label != "P" {
                    return Err(self.err(
                        l,
                        format!(
                            "*DSLOAD load type {} is not supported: P (pressure) is",
                            f[1]
                        ),
                    ));
                }
                self.surface_name(l, f[0], "*DSLOAD")?
            } else {
                let face = label
                    .strip_prefix('P')
                    .and_then(|k| k.parse::<usize>().ok())
                    .filter(|&k| k >= 1)
                    .ok_or_else(|| self.err(l, format!("*DLOAD load type {} is not supported: P1…P6 (pressure on face S1…S6) and GRAV (gravity) are", f[1])))?;
                self.face_surface(l, f[0], face)?
            };
            records.push(PressureDef {
                surface,
                value: self.number(l, f[2])?,
                amplitude: amplitude.clone(),
                at: self.deck.locate(l),
            });
        }
        let step = self.current_step(line, keyword)?;
        step.new_pressures |= new;
        step.pressures.extend(records);
        step.gravities.extend(gravities);
        Ok(())
    }

    /// A `*DLOAD` gravity line `elset, GRAV, g, n₁, n₂, n₃`.
    fn gravity(&self, l: &Line, f: &[&str], amplitude: Option<String>) -> Result<GravityDef> {
        if f.len() != 6 {
            return Err(self.err(
                l,
                format!(
                    "a *DLOAD gravity line is 'element set, GRAV, magnitude, n1, n2, n3'; found '{}'",
                    l.text()
                ),
            ));
        }
        let field = unquote(f[0]);
        if field.parse::<u64>().is_ok() {
            return Err(self.err(
                l,
                format!("*DLOAD, GRAV on element {field}: give an element set (*ELSET) instead of an element number"),
            ));
        }
        let set = self.context.name(field);
        if self.builder.element_sets.get(&set).is_none() {
            return Err(self.err(
                l,
                format!("*DLOAD: {}", self.missing_set(&set, "element set (*ELSET)")),
            ));
        }
        let elements = self
            .builder
            .element_sets
            .canonical(&set)
            .unwrap_or(&set)
            .to_string();
        let g = self.number(l, f[2])?;
        let n = [
            self.number(l, f[3])?,
            self.number(l, f[4])?,
            self.number(l, f[5])?,
        ];
        let length = n.iter().map(|x| x * x).sum::<f64>().sqrt();
        if !(length > 0.0 && length.is_finite()) {
            return Err(self.err(
                l,
                "*DLOAD, GRAV: the direction (n1, n2, n3) has zero length; give the direction of gravity, e.g. 0, 0, -1".into(),
            ));
        }
        Ok(GravityDef {
            elements,
            acceleration: n.map(|x| g * x / length),
            amplitude,
            at: self.deck.locate(l),
        })
    }

    /// The implicit surface `<elset>:S<k>` (or `element:<id>:S<k>`) of a
    /// `*DLOAD` line, made on first use.
    fn face_surface(&mut self, l: &Line, field: &str, face: usize) -> Result<String> {
        let field = unquote(field);
        let (name, members) = match field.parse::<u64>() {
            Ok(id) => {
                let id = self.context.element(id);
                let m = self
                    .builder
                    .element(id)
                    .ok_or_else(|| self.err(l, format!("*DLOAD: no element {id} is defined")))?;
                (format!("element:{id}:S{face}"), vec![m])
            }
            Err(_) => {
                let set = self.context.name(field);
                let members = self
                    .builder
                    .element_sets
                    .get(&set)
                    .cloned()
                    .ok_or_else(|| {
                        self.err(
                            l,
                            format!("*DLOAD: {}", self.missing_set(&set, "element set (*ELSET)")),
                        )
                    })?;
                let canonical = self
                    .builder
                    .element_sets
                    .canonical(&set)
                    .unwrap_or(&set)
                    .to_string();
                (format!("{canonical}:S{face}"), members)
            }
        };
        if self.builder.surfaces.get(&name).is_none() {
            self.add_faces(&name, "*DLOAD", &members, Some(face), l, field)?;
        }
        Ok(name)
    }

    /// `*NODE FILE`, `*EL FILE`, `*CONTACT FILE`, `*NODE PRINT, NSET=…`
    /// (and Abaqus's `*NODE OUTPUT`, `*ELEMENT OUTPUT`): variable names.
    pub(super) fn output(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let kind = match keyword.name.as_str() {
            "NODE FILE" | "NODE OUTPUT" => OutputKind::NodeFile,
            "EL FILE" | "ELEMENT OUTPUT" => OutputKind::ElementFile,
            "CONTACT FILE" => OutputKind::ContactFile,
            _ => {
                let set = self.required(line, keyword, "NSET")?.to_string();
                OutputKind::NodePrint(self.node_target(line, &set, "*NODE PRINT")?)
            }
        };
        let variables = data
            .iter()
            .flat_map(|l| data_fields(l))
            .filter(|f| !f.is_empty())
            .map(|f| f.to_ascii_uppercase())
            .collect();
        let at = self.deck.locate(line);
        self.current_step(line, keyword)?.outputs.push(OutputDef {
            kind,
            variables,
            at,
        });
        Ok(())
    }
}
