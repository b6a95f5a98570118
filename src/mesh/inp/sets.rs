//! `*ELSET` and `*NSET`: set members by id, by name or by `GENERATE`
//! ranges; why a set named is not found.

use super::deck::{unquote, Keyword, Line};
use super::{data_fields, Reader};
use crate::Result;

impl Reader<'_> {
    /// Why the set `name` (as the mesh would have it) is not found: a
    /// qualified name whose instance does not exist says so.
    pub(super) fn missing_set(&self, name: &str, kind: &str) -> String {
        if let Some((instance, _)) = name.split_once('.') {
            if self.instance_named(instance).is_none() {
                let have: Vec<&str> = self.instances.iter().map(|i| i.name.as_str()).collect();
                return format!(
                    "'{name}' names the instance '{instance}', which no *INSTANCE defines before it (instances: {})",
                    if have.is_empty() { "none".into() } else { have.join(", ") }
                );
            }
        }
        format!("no {kind} '{name}' is defined before it")
    }

    /// The members a set's data lines list: ids (`by_id`) and names of sets
    /// of the same kind defined before (`by_name`), or with `GENERATE` the
    /// ranges `first, last[, step]` (ids that nothing has are skipped, but a
    /// range must hold one). `what` is the keyword and the kind of item,
    /// e.g. `("*NSET", "node")`.
    fn set_members<'b, T: Clone + 'b>(
        &self,
        set: SetBlock,
        by_id: impl Fn(u64) -> Option<T>,
        by_name: impl Fn(&str) -> Option<&'b [T]>,
    ) -> Result<Vec<T>> {
        let SetBlock {
            line,
            keyword,
            data,
            name,
            kind,
        } = set;
        let (what, item) = kind.words();
        let generate = keyword.has("GENERATE");
        let mut members = Vec::new();
        for l in data {
            let fields = data_fields(l);
            if generate {
                if fields.len() < 2 || fields.len() > 3 {
                    return Err(self.err(
                        l,
                        format!(
                            "a GENERATE line is 'first, last[, step]'; found {} fields",
                            fields.len()
                        ),
                    ));
                }
                let first = self.id(l, fields[0], "first id")?;
                let last = self.id(l, fields[1], "last id")?;
                let step = match fields.get(2) {
                    Some(f) => self.id(l, f, "step")?,
                    None => 1,
                };
                if last < first {
                    return Err(self.err(
                        l,
                        format!("GENERATE from {first} to {last}: the last id must not be smaller than the first"),
                    ));
                }
                // counted over the whole deck before any id is listed
                self.deck.generated(l, (last - first) / step + 1)?;
                members.extend((first..=last).step_by(step as usize).filter_map(&by_id));
                continue;
            }
            for f in fields.iter().filter(|f| !f.is_empty()) {
                match f.parse::<u64>() {
                    Ok(id) => members.push(by_id(id).ok_or_else(|| {
                        self.err(
                            l,
                            format!("{what} '{name}' lists {item} {id}, which no *{} defines (before it)", item.to_ascii_uppercase()),
                        )
                    })?),
                    Err(_) => {
                        let set = self.context.name(unquote(f));
                        let named = by_name(&set).ok_or_else(|| {
                            let why = if set.contains('.') {
                                format!(": {}", self.missing_set(&set, &format!("{item} set")))
                            } else {
                                String::new()
                            };
                            self.err(
                                l,
                                format!("{what} '{name}' lists '{set}', which is neither a defined {item} id nor the name of an earlier {item} set{why}"),
                            )
                        })?;
                        // a set named n times copies it n times: counted with GENERATE's
                        self.deck.generated(l, named.len() as u64)?;
                        members.extend_from_slice(named)
                    }
                }
            }
        }
        if generate && members.is_empty() {
            return Err(self.err(
                line,
                format!("{what} '{name}': the GENERATE ranges hold no defined id"),
            ));
        }
        Ok(members)
    }

    /// `*ELSET, ELSET=name[, GENERATE]`.
    pub(super) fn element_set(
        &mut self,
        line: &Line,
        keyword: &Keyword,
        data: &[Line],
    ) -> Result<()> {
        let name = self.context.name(self.required(line, keyword, "ELSET")?);
        let b = &self.builder;
        let c = &self.context;
        let members = self.set_members(
            SetBlock::new(SetKind::Element, line, keyword, data, &name),
            |id| b.element(c.element(id)),
            |set| b.element_sets.get(set).map(Vec::as_slice),
        )?;
        self.builder.element_sets.entry(&name).extend(members);
        Ok(())
    }

    /// `*NSET, NSET=name[, GENERATE]` or `*NSET, NSET=name, ELSET=set`.
    pub(super) fn node_set(&mut self, line: &Line, keyword: &Keyword, data: &[Line]) -> Result<()> {
        let name = self.context.name(self.required(line, keyword, "NSET")?);
        let b = &self.builder;
        let c = &self.context;
        let mut nodes = Vec::new();
        if let Some(elset) = keyword.param("ELSET") {
            let elset = &c.name(elset);
            let members = b.element_sets.get(elset).ok_or_else(|| {
                self.err(
                    line,
                    format!("*NSET '{name}': no element set '{elset}' is defined before"),
                )
            })?;
            nodes = b.member_nodes(members);
        }
        nodes.extend(self.set_members(
            SetBlock::new(SetKind::Node, line, keyword, data, &name),
            |id| b.node(c.node(id)),
            |set| b.node_sets.get(set).map(Vec::as_slice),
        )?);
        self.builder.node_sets.entry(&name).extend(nodes);
        Ok(())
    }
}

/// The lines of a `*ELSET` or `*NSET` block and what it defines.
struct SetBlock<'a> {
    /// The keyword line and its parsed keyword.
    line: &'a Line,
    keyword: &'a Keyword,
    /// The data lines after it.
    data: &'a [Line],
    /// The set's name.
    name: &'a str,
    kind: SetKind,
}

impl<'a> SetBlock<'a> {
    fn new(
        kind: SetKind,
        line: &'a Line,
        keyword: &'a Keyword,
        data: &'a [Line],
        name: &'a str,
    ) -> Self {
        Self {
            line,
            keyword,
            data,
            name,
            kind,
        }
    }
}

/// The kind of set a block defines.
#[derive(Clone, Copy)]
enum SetKind {
    Node,
    Element,
}

impl SetKind {
    /// The keyword and the kind of item: `("*NSET", "node")`.
    fn words(self) -> (&'static str, &'static str) {
        match self {
            SetKind::Node => ("*NSET", "node"),
            SetKind::Element => ("*ELSET", "element"),
        }
    }
}
