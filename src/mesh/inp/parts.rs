//! `*PART … *END PART` and `*INSTANCE`: the parts kept, the instances
//! placed (their transforms), the part's keywords read in their context.

use super::assembly::{Context, Instance, Part, Transform};
use super::builder::Member;
use super::deck::{Keyword, Line};
use super::{data_fields, Reader};
use crate::Result;

impl Reader<'_> {
    /// The first block after `b` whose keyword is `*<end>`.
    fn find_end(&self, b: usize, end: &str) -> Result<Option<usize>> {
        for j in b + 1..self.blocks.len() {
            let (line, _) = self.lines(j);
            if self.deck.keyword(line)?.name == end {
                return Ok(Some(j));
            }
        }
        Ok(None)
    }

    /// `*PART, NAME=…`: its blocks kept until an instance places it.
    pub(super) fn part(&mut self, b: usize, keyword: &Keyword) -> Result<usize> {
        let (line, _) = self.lines(b);
        let name = self.required(line, keyword, "NAME")?.to_string();
        let end = self
            .find_end(b, "END PART")?
            .ok_or_else(|| self.err(line, format!("*PART '{name}' has no *END PART after it")))?;
        if self
            .parts
            .iter()
            .any(|p| p.name.eq_ignore_ascii_case(&name))
        {
            return Err(self.err(line, format!("*PART '{name}' is defined twice")));
        }
        for j in b + 1..end {
            let (inner, _) = self.lines(j);
            let k = self.deck.keyword(inner)?;
            if matches!(k.name.as_str(), "PART" | "INSTANCE" | "ASSEMBLY" | "STEP") {
                return Err(self.err(
                    inner,
                    format!(
                        "*{} inside *PART '{name}': close the part with *END PART first",
                        k.name
                    ),
                ));
            }
        }
        self.parts.push(Part {
            name,
            blocks: b + 1..end,
        });
        Ok(end + 1)
    }

    /// `*INSTANCE, NAME=…, PART=…` with its optional translation and
    /// rotation lines: the part's keywords read in the instance's context.
    pub(super) fn instance(&mut self, b: usize, keyword: &Keyword) -> Result<usize> {
        let (line, data) = self.lines(b);
        let name = self.required(line, keyword, "NAME")?.to_string();
        let part_name = keyword.param("PART").ok_or_else(|| {
            self.err(
                line,
                format!("*INSTANCE '{name}' needs PART=<name>: an instance places a *PART (an instance with its own nodes is not supported)"),
            )
        })?;
        let part = self
            .parts
            .iter()
            .find(|p| p.name.eq_ignore_ascii_case(part_name))
            .cloned()
            .ok_or_else(|| {
                let have: Vec<&str> = self.parts.iter().map(|p| p.name.as_str()).collect();
                self.err(
                    line,
                    format!(
                        "*INSTANCE '{name}': no *PART named '{part_name}' is defined before it (parts: {})",
                        if have.is_empty() { "none".into() } else { have.join(", ") }
                    ),
                )
            })?;
        if self.instance_named(&name).is_some() {
            return Err(self.err(line, format!("*INSTANCE '{name}' is defined twice")));
        }
        let transform = self.transform(data)?;
        let end = self.find_end(b, "END INSTANCE")?.ok_or_else(|| {
            self.err(
                line,
                format!("*INSTANCE '{name}' has no *END INSTANCE after it"),
            )
        })?;
        if end > b + 1 {
            let (inner, _) = self.lines(b + 1);
            return Err(self.err(
                inner,
                format!("keywords inside *INSTANCE '{name}' are not supported: define the mesh in its *PART"),
            ));
        }
        let context = Context {
            instance: Some(name.clone()),
            node_offset: self.max_node,
            element_offset: self.max_element,
            transform: Some(transform),
        };
        let (nodes, elements) = self.builder.counts();
        let outer = std::mem::replace(&mut self.context, context.clone());
        for j in part.blocks.clone() {
            let (l, d) = self.lines(j);
            self.keyword(l, d)?;
        }
        self.context = outer;
        let (nodes_after, elements_after) = self.builder.counts();
        self.builder
            .node_sets
            .entry(&name)
            .extend(nodes..nodes_after);
        self.builder
            .element_sets
            .entry(&name)
            .extend((elements..elements_after).map(Member::Volume));
        self.instances.push(Instance {
            name,
            context: Context {
                transform: None,
                ..context
            },
        });
        Ok(end + 1)
    }

    /// The instance called `name` (case ignored).
    pub(super) fn instance_named(&self, name: &str) -> Option<&Instance> {
        self.instances
            .iter()
            .find(|i| i.name.eq_ignore_ascii_case(name))
    }

    /// The transform of an `*INSTANCE`'s data lines: `tx, ty, tz` and
    /// `ax, ay, az, bx, by, bz, angle`.
    fn transform(&self, data: &[Line]) -> Result<Transform> {
        if data.len() > 2 {
            return Err(self.err(
                &data[2],
                "an *INSTANCE has at most two data lines (translation, rotation)".into(),
            ));
        }
        let numbers = |l: &Line, n: usize, what: &str| -> Result<Vec<f64>> {
            let fields = data_fields(l);
            if fields.len() != n {
                return Err(self.err(
                    l,
                    format!(
                        "the {what} line of an *INSTANCE has {n} numbers; found {}",
                        fields.len()
                    ),
                ));
            }
            fields.iter().map(|f| self.number(l, f)).collect()
        };
        let translation = match data.first() {
            Some(l) => numbers(l, 3, "translation")?,
            None => vec![0.0; 3],
        };
        let rotation = match data.get(1) {
            Some(l) => Some(numbers(l, 7, "rotation (a, b, angle)")?),
            None => None,
        };
        Transform::new(
            [translation[0], translation[1], translation[2]],
            rotation.map(|r| [r[0], r[1], r[2], r[3], r[4], r[5], r[6]]),
        )
        .map_err(|m| self.err(&data[1], format!("*INSTANCE rotation: {m}")))
    }
}
