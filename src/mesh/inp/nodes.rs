//! `*NODE` and `*ELEMENT` blocks: their data lines parsed side by side,
//! the nodes and elements added in order.

use super::builder::kind_name;
use super::deck::{Keyword, Line};
use super::element_type::{self, element_type, Shape};
use super::{data_fields, Reader};
use crate::Result;
use rayon::prelude::*;

impl Reader<'_> {
    /// `*NODE`: `id, x[, y[, z]]` (missing coordinates are 0).
    pub(super) fn nodes(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        self.no_input(line, keyword)?;
        if let Some(system) = keyword.param("SYSTEM") {
            if !system.eq_ignore_ascii_case("R") {
                return Err(self.err(
                    line,
                    format!("*NODE, SYSTEM={system} is not supported: give Cartesian coordinates (SYSTEM=R)"),
                ));
            }
        }
        let nset = keyword.param("NSET").map(|n| self.context.name(n));
        // the lines parsed side by side, then added in order (the first
        // error in the deck's order is the one reported)
        let parsed: Vec<Result<(u64, [f64; 3])>> =
            data.par_iter().map(|l| self.node_line(l)).collect();
        let mut added = Vec::with_capacity(data.len());
        for (l, p) in data.iter().zip(parsed) {
            let (id, x) = p?;
            let id = self.context.node(id);
            let x = match &self.context.transform {
                Some(t) => t.apply(x),
                None => x,
            };
            self.max_node = self.max_node.max(id);
            added.push(self.builder.add_node(id, x).map_err(|m| self.err(l, m))?);
        }
        if let Some(name) = nset {
            self.builder.node_sets.entry(&name).extend(added);
        }
        Ok(())
    }

    /// A `*NODE` data line: `id, x, y, z` (missing coordinates are 0).
    fn node_line(&self, l: &Line) -> Result<(u64, [f64; 3])> {
        let fields = data_fields(l);
        if fields.len() < 2 || fields.len() > 4 {
            return Err(self.err(
                l,
                format!(
                    "a *NODE line is 'id, x, y, z'; found {} fields in '{}'",
                    fields.len(),
                    l.text()
                ),
            ));
        }
        let id = self.id(l, fields[0], "node id")?;
        let mut x = [0.0; 3];
        for ((c, f), axis) in x.iter_mut().zip(&fields[1..]).zip(["x", "y", "z"]) {
            *c = self.number(l, f)?;
            if let Some(fault) = crate::input::coordinate_fault(*c) {
                return Err(self.err(l, format!("the {axis} coordinate of node {id} {fault}")));
            }
        }
        Ok((id, x))
    }

    /// `*ELEMENT, TYPE=…`: `id, n1, …, nk`, continued on the next line after
    /// a trailing comma.
    pub(super) fn elements(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        self.no_input(line, keyword)?;
        let type_name = self.required(line, keyword, "TYPE")?.to_ascii_uppercase();
        let element = element_type(&type_name).map_err(|m| self.err(line, m))?;
        if let Shape::Volume(kind) = element.shape {
            if let Some(note) = element_type::variant_note(&type_name, kind_name(kind)) {
                if !self.notes.contains(&note) {
                    self.notes.push(note);
                }
            }
        }
        let elset = keyword.param("ELSET").map(|n| self.context.name(n));
        // an element per line, parsed side by side; a line ending with a
        // comma continues on the next one (then the lines are joined in
        // order first)
        let mut records: Vec<(&Line, Vec<&str>)> = Vec::new();
        let continued = data.iter().any(|l| l.text().trim_end().ends_with(','));
        let parsed: Vec<Result<(u64, Vec<u64>)>> = if continued {
            let mut i = 0;
            while i < data.len() {
                let first = &data[i];
                let mut fields = data_fields(first);
                while fields.len() < element.nodes + 1
                    && data[i].text().trim_end().ends_with(',')
                    && i + 1 < data.len()
                {
                    i += 1;
                    fields.extend(data_fields(&data[i]));
                }
                i += 1;
                records.push((first, fields));
            }
            records
                .par_iter()
                .map(|(first, fields)| self.element_line(first, fields, &type_name, element.nodes))
                .collect()
        } else {
            data.par_iter()
                .map(|l| self.element_line(l, &data_fields(l), &type_name, element.nodes))
                .collect()
        };
        let firsts: Vec<&Line> = if continued {
            records.iter().map(|(first, _)| *first).collect()
        } else {
            data.iter().collect()
        };
        let mut added = Vec::with_capacity(parsed.len());
        for (first, p) in firsts.into_iter().zip(parsed) {
            let (id, nodes) = p?;
            let id = self.context.element(id);
            let nodes: Vec<u64> = nodes.iter().map(|&n| self.context.node(n)).collect();
            self.max_element = self.max_element.max(id);
            let member = self
                .builder
                .add_element(id, element.shape, &nodes)
                .map_err(|m| self.err(first, m))?;
            added.push(member);
        }
        if let Some(name) = elset {
            self.builder.element_sets.entry(&name).extend(added);
        }
        Ok(())
    }

    /// An element's fields (`id` and its `nodes` node ids) read from the
    /// line `first` (where it starts).
    fn element_line(
        &self,
        first: &Line,
        fields: &[&str],
        type_name: &str,
        nodes: usize,
    ) -> Result<(u64, Vec<u64>)> {
        if fields.len() != nodes + 1 {
            return Err(self.err(
                first,
                format!(
                    "a {type_name} element line is 'id' and {nodes} node ids; found {} fields",
                    fields.len()
                ),
            ));
        }
        let id = self.id(first, fields[0], "element id")?;
        let ids = fields[1..]
            .iter()
            .map(|f| self.id(first, f, "node id"))
            .collect::<Result<Vec<u64>>>()?;
        Ok((id, ids))
    }
}
