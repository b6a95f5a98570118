//! Time histories (`[[output.history]]`): one nodal quantity, or the
//! reaction force on a surface set, recorded after every converged
//! increment, written as `<name>.csv` (time, value or x, y, z components)
//! and `<name>.svg` (against pseudo-time, i.e. the load factor of a ramp,
//! or against another history's quantity, its `x`: a force–displacement
//! curve).

use std::path::Path;

use super::describe::counted;
use super::line_plot::{write_line_plot, Curve, LinePlot};
use super::reaction_moment::reaction_moment;
use super::table::write_csv;
use super::units::{Dimension, Units};
use crate::contact::interface::NodeReport;

/// What a history records at its node (or on its surface).
#[derive(Clone, Debug, PartialEq)]
pub enum HistoryQuantity {
    /// Displacement component `u_i` (0, 1, 2 for x, y, z).
    Displacement(usize),
    /// Signed gap `g` of secondary node `index` of contact interface
    /// `interface` (positive open).
    Gap { interface: usize, index: usize },
    /// Contact pressure `t_N ≥ 0` of a secondary node.
    ContactPressure { interface: usize, index: usize },
    /// `Σ (f_int − f_ext)` over the nodes of a surface set, its three
    /// components: the reaction force where displacements are prescribed
    /// (as `reaction_forces` in `summary.json`).
    ReactionForce { surface: String, nodes: Vec<usize> },
    /// Component `component` (0, 1, 2) of that sum over the nodes of the
    /// surface set or node set `set`: one column.
    ReactionComponent {
        set: String,
        nodes: Vec<usize>,
        component: usize,
    },
    /// `Σ (x_a − c) × r_a` over the nodes of the set `set` at their
    /// current positions ([`reaction_moment`]): its x, y, z components
    /// (`component` `None`) or one of them. `reference` holds the nodes'
    /// reference positions; `centre` is `c` (`None`: the nodes' current
    /// centroid).
    ReactionMoment {
        set: String,
        nodes: Vec<usize>,
        reference: Vec<[f64; 3]>,
        centre: Option<[f64; 3]>,
        component: Option<usize>,
    },
}

/// The axis letters of components 0, 1, 2.
const AXES: [&str; 3] = ["x", "y", "z"];

impl HistoryQuantity {
    /// The quantity in words with its symbol, for titles and axis labels:
    /// `displacement u_z`, `gap g`, `contact pressure t_N`, `reaction
    /// force`, `reaction force F_z`.
    pub fn words(&self) -> String {
        match self {
            HistoryQuantity::Displacement(i) => format!("displacement u_{}", AXES[*i]),
            HistoryQuantity::Gap { .. } => "gap g".into(),
            HistoryQuantity::ContactPressure { .. } => "contact pressure t_N".into(),
            HistoryQuantity::ReactionForce { .. } => "reaction force".into(),
            HistoryQuantity::ReactionComponent { component, .. } => {
                format!("reaction force F_{}", AXES[*component])
            }
            HistoryQuantity::ReactionMoment { component, .. } => match component {
                None => "reaction moment".into(),
                Some(c) => format!("reaction moment M_{}", AXES[*c]),
            },
        }
    }

    /// Zero in the unloaded reference state: displacements and reactions
    /// (a gap or a pressure need not be).
    fn zero_at_reference(&self) -> bool {
        matches!(
            self,
            HistoryQuantity::Displacement(_)
                | HistoryQuantity::ReactionForce { .. }
                | HistoryQuantity::ReactionComponent { .. }
                | HistoryQuantity::ReactionMoment { .. }
        )
    }
}

/// A quantity at one node (or a surface set's reaction force) over the run.
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    /// File stem.
    pub name: String,
    /// Mesh node index and the node's id in the mesh file (a reaction
    /// force: the surface's first node).
    pub node: usize,
    pub node_id: u64,
    pub quantity: HistoryQuantity,
    /// The quantity as the case names it, e.g. `displacement_z`: the
    /// column header of a scalar quantity (a reaction force's columns:
    /// `reaction_x`, `_y`, `_z`).
    pub label: String,
    /// The history of one column whose value is the x axis instead of the
    /// pseudo-time (`x = "<history>"`), recorded beside this one: its
    /// value is the first of every sample's values, its name the CSV
    /// column's.
    pub x: Option<Box<History>>,
    /// `(time, values)` of every converged increment so far: one value, or
    /// the x, y, z components of a reaction force, after the x axis's
    /// value when there is one.
    pub samples: Vec<(f64, Vec<f64>)>,
    /// The case's units, for the plot's labels.
    pub units: Units,
}

impl History {
    /// A history with no sample yet.
    pub fn new(
        name: String,
        node: usize,
        node_id: u64,
        quantity: HistoryQuantity,
        label: String,
    ) -> Self {
        History {
            name,
            node,
            node_id,
            quantity,
            label,
            x: None,
            samples: Vec::new(),
            units: Units::default(),
        }
    }

    /// The same history with the plot labelled in `units`.
    pub fn with_units(self, units: Units) -> Self {
        History { units, ..self }
    }

    /// The same history plotted against `x`'s quantity (a history of one
    /// column, its own `x` ignored) instead of the pseudo-time.
    pub fn against(self, x: &History) -> Self {
        let x = History {
            x: None,
            samples: Vec::new(),
            ..x.clone()
        };
        History {
            x: Some(Box::new(x)),
            ..self
        }
    }

    /// The dimension of the quantity.
    pub fn dimension(&self) -> Dimension {
        match self.quantity {
            HistoryQuantity::Displacement(_) | HistoryQuantity::Gap { .. } => Dimension::Length,
            HistoryQuantity::ContactPressure { .. } => Dimension::Stress,
            HistoryQuantity::ReactionForce { .. } | HistoryQuantity::ReactionComponent { .. } => {
                Dimension::Force
            }
            HistoryQuantity::ReactionMoment { .. } => Dimension::Moment,
        }
    }

    /// The column headers of the quantity itself.
    fn own_columns(&self) -> Vec<String> {
        match self.quantity {
            HistoryQuantity::ReactionForce { .. } => ["reaction_x", "reaction_y", "reaction_z"]
                .map(String::from)
                .to_vec(),
            HistoryQuantity::ReactionMoment {
                component: None, ..
            } => ["moment_x", "moment_y", "moment_z"]
                .map(String::from)
                .to_vec(),
            _ => vec![self.label.clone()],
        }
    }

    /// The column headers after `time`: the x axis's history's name, if
    /// any, then the quantity's.
    pub fn columns(&self) -> Vec<String> {
        self.x
            .iter()
            .map(|x| x.name.clone())
            .chain(self.own_columns())
            .collect()
    }

    /// Where the history reads, for the logs: `at node <id> (x, y, z)` or
    /// `on surface '<name>' (<n> nodes)`, and `, against '<x>'` with an x
    /// axis.
    pub fn location(&self, nodes: &[[f64; 3]]) -> String {
        let place = self.reading(nodes);
        match &self.x {
            Some(x) => format!("{place}, against '{}'", x.name),
            None => place,
        }
    }

    /// Where the quantity is read, for [`Self::location`].
    fn reading(&self, nodes: &[[f64; 3]]) -> String {
        match &self.quantity {
            HistoryQuantity::ReactionForce { surface, nodes } => {
                format!("on surface '{surface}' ({} nodes)", nodes.len())
            }
            HistoryQuantity::ReactionComponent { set, nodes, .. } => {
                format!("on set '{set}' ({} nodes)", nodes.len())
            }
            HistoryQuantity::ReactionMoment {
                set, nodes, centre, ..
            } => match centre {
                Some(c) => format!(
                    "on set '{set}' ({} nodes) about ({}, {}, {})",
                    nodes.len(),
                    c[0],
                    c[1],
                    c[2]
                ),
                None => format!(
                    "on set '{set}' ({} nodes) about its current centroid",
                    nodes.len()
                ),
            },
            _ => {
                let x = nodes[self.node];
                format!("at node {} ({}, {}, {})", self.node_id, x[0], x[1], x[2])
            }
        }
    }

    /// Where the history reads, in a title: `at node <id>`, `on surface
    /// '<name>'`, `on set '<name>'`.
    fn place(&self) -> String {
        match &self.quantity {
            HistoryQuantity::ReactionForce { surface, .. } => format!("on surface '{surface}'"),
            HistoryQuantity::ReactionComponent { set, .. }
            | HistoryQuantity::ReactionMoment { set, .. } => format!("on set '{set}'"),
            _ => format!("at node {}", self.node_id),
        }
    }

    /// The quantity in state `u` (displacements first) with the residual
    /// `f_int − f_ext` and the contact reports `contact[interface][index]`
    /// of that state (the x axis's value not included).
    pub fn value(&self, u: &[f64], residual: &[f64], contact: &[Vec<NodeReport>]) -> Vec<f64> {
        match &self.quantity {
            HistoryQuantity::Displacement(i) => vec![u[3 * self.node + i]],
            HistoryQuantity::Gap { interface, index } => vec![contact[*interface][*index].gap],
            HistoryQuantity::ContactPressure { interface, index } => {
                vec![contact[*interface][*index].pressure]
            }
            HistoryQuantity::ReactionForce { nodes, .. } => {
                (0..3).map(|d| set_sum(nodes, residual, d)).collect()
            }
            HistoryQuantity::ReactionComponent {
                nodes, component, ..
            } => vec![set_sum(nodes, residual, *component)],
            HistoryQuantity::ReactionMoment {
                nodes,
                reference,
                centre,
                component,
                ..
            } => {
                let m = reaction_moment(nodes, reference, *centre, u, residual);
                match component {
                    None => m.to_vec(),
                    Some(c) => vec![m[*c]],
                }
            }
        }
    }

    /// Add the sample of a converged increment at pseudo-time `time`: the
    /// x axis's value, if any, then the quantity's.
    pub fn record(&mut self, time: f64, u: &[f64], residual: &[f64], contact: &[Vec<NodeReport>]) {
        let x = self.x.iter().flat_map(|x| x.value(u, residual, contact));
        let value = x.chain(self.value(u, residual, contact)).collect();
        self.samples.push((time, value));
    }

    /// Whether `samples` (a checkpoint's) have this history's columns: an
    /// error in words if not (an `x` added or removed since).
    pub fn check_restored(&self, samples: &[(f64, Vec<f64>)]) -> Result<(), String> {
        let columns = self.columns();
        match samples.iter().find(|(_, v)| v.len() != columns.len()) {
            None => Ok(()),
            Some((_, v)) => Err(format!(
                "the checkpoint's history '{}' has {} after time, the case's {} ({}); \
                 a restart needs the same [[output.history]] tables (with the same `x`): \
                 run the case from the start",
                self.name,
                counted(v.len(), "column"),
                columns.len(),
                columns.join(", ")
            )),
        }
    }

    /// Write `<name>.csv` and `<name>.svg` into `dir`, atomically.
    pub fn write(&self, dir: &Path) -> crate::Result<()> {
        let columns = self.columns();
        let rows: Vec<Vec<f64>> = self
            .samples
            .iter()
            .map(|(t, v)| std::iter::once(*t).chain(v.iter().copied()).collect())
            .collect();
        let header: Vec<&str> = std::iter::once("time")
            .chain(columns.iter().map(String::as_str))
            .collect();
        write_csv(&dir.join(format!("{}.csv", self.name)), &header, &rows)?;
        write_line_plot(&dir.join(format!("{}.svg", self.name)), &self.plot())
    }

    /// The plot: one curve per column of the quantity against the
    /// pseudo-time or the x axis's quantity, from `(0, 0)`, the unloaded
    /// reference state, when both coordinates are zero there
    /// (displacements and reaction forces).
    pub fn plot(&self) -> LinePlot {
        let from_origin = self.quantity.zero_at_reference()
            && self
                .x
                .as_ref()
                .is_none_or(|x| x.quantity.zero_at_reference());
        let offset = usize::from(self.x.is_some());
        let own = self.own_columns();
        let curves = (0..own.len())
            .map(|c| {
                let mut points = Vec::with_capacity(self.samples.len() + 1);
                if from_origin {
                    points.push((0.0, 0.0));
                }
                points.extend(self.samples.iter().filter_map(|(t, v)| {
                    let x = if self.x.is_some() { v.first() } else { Some(t) };
                    Some((*x?, *v.get(offset + c)?))
                }));
                Curve {
                    label: self.curve_label(c),
                    points,
                    colour: c,
                    style: Default::default(),
                }
            })
            .collect();
        let words = self.quantity.words();
        let (title, x_label) = match &self.x {
            Some(x) => (
                format!(
                    "{} {} against {} {}",
                    capitalised(&words),
                    self.place(),
                    x.quantity.words(),
                    x.place()
                ),
                self.units.label(&x.quantity.words(), x.dimension()),
            ),
            None => (
                format!("{} {}", capitalised(&words), self.place()),
                "pseudo-time t (load factor)".into(),
            ),
        };
        LinePlot {
            title,
            x_label,
            y_label: self.units.label(&words, self.dimension()),
            curves,
            below: Vec::new(),
        }
    }

    /// The legend entry of column `c` of the quantity: `F_x`, `F_y`,
    /// `F_z` for a reaction force's, the history's name otherwise.
    fn curve_label(&self, c: usize) -> String {
        match self.quantity {
            HistoryQuantity::ReactionForce { .. } => format!("F_{}", AXES[c]),
            HistoryQuantity::ReactionMoment {
                component: None, ..
            } => format!("M_{}", AXES[c]),
            _ => self.name.clone(),
        }
    }
}

/// `text` with its first letter upper-case.
fn capitalised(text: &str) -> String {
    let mut chars = text.chars();
    chars.next().map_or_else(String::new, |first| {
        first.to_uppercase().chain(chars).collect()
    })
}

/// `Σ_n r[3n + d]`: component `d` of the residual summed over `nodes`
/// (the reaction force where they are prescribed).
fn set_sum(nodes: &[usize], residual: &[f64], d: usize) -> f64 {
    nodes.iter().map(|&n| residual[3 * n + d]).sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_and_writes_displacement_and_gap() {
        let report = |gap, pressure| NodeReport {
            gap,
            pressure,
            active: pressure > 0.0,
            ..Default::default()
        };
        let mut lift = History::new(
            "lift".into(),
            1,
            7,
            HistoryQuantity::Displacement(2),
            "displacement_z".into(),
        );
        let mut gap = History::new(
            "gap".into(),
            1,
            7,
            HistoryQuantity::Gap {
                interface: 0,
                index: 1,
            },
            "gap".into(),
        );
        let u = [0.0, 0.0, 0.0, 0.1, 0.2, 0.3];
        let contact = vec![vec![report(0.0, 2.0), report(0.25, 0.0)]];
        let residual = [0.0; 6];
        for h in [&mut lift, &mut gap] {
            h.record(0.5, &u, &residual, &contact);
            h.record(1.0, &u, &residual, &contact);
        }
        assert_eq!(lift.samples, vec![(0.5, vec![0.3]), (1.0, vec![0.3])]);
        assert_eq!(gap.samples, vec![(0.5, vec![0.25]), (1.0, vec![0.25])]);
        let dir = tempfile::tempdir().unwrap();
        lift.write(dir.path()).unwrap();
        let csv = std::fs::read_to_string(dir.path().join("lift.csv")).unwrap();
        assert_eq!(csv, "time,displacement_z\n0.5,0.3\n1,0.3\n");
        let svg = std::fs::read_to_string(dir.path().join("lift.svg")).unwrap();
        // the origin and the two samples
        assert_eq!(svg.matches("<circle").count(), 3);
        assert!(svg.contains("Displacement u_z at node 7"));
        assert!(svg.contains("pseudo-time t (load factor)"));
    }

    #[test]
    fn records_and_writes_a_reaction_force() {
        let mut reaction = History::new(
            "push".into(),
            0,
            1,
            HistoryQuantity::ReactionForce {
                surface: "top".into(),
                nodes: vec![0, 2],
            },
            "reaction_force".into(),
        );
        let residual = [1.0, 2.0, 3.0, 100.0, 100.0, 100.0, 0.5, 0.25, -1.0];
        reaction.record(1.0, &[0.0; 9], &residual, &[]);
        assert_eq!(reaction.samples, vec![(1.0, vec![1.5, 2.25, 2.0])]);
        let nodes = [[0.0; 3]; 3];
        assert_eq!(reaction.location(&nodes), "on surface 'top' (2 nodes)");
        let dir = tempfile::tempdir().unwrap();
        reaction.write(dir.path()).unwrap();
        let csv = std::fs::read_to_string(dir.path().join("push.csv")).unwrap();
        assert_eq!(csv, "time,reaction_x,reaction_y,reaction_z\n1,1.5,2.25,2\n");
        let svg = std::fs::read_to_string(dir.path().join("push.svg")).unwrap();
        // three curves from the origin: 2 points each
        assert_eq!(svg.matches("<circle").count(), 6);
        assert_eq!(reaction.plot().title, "Reaction force on surface 'top'");
        for text in [
            "Reaction force on surface &apos;top&apos;",
            "F_x",
            "F_z",
            "reaction force",
        ] {
            assert!(svg.contains(text), "missing {text}");
        }
        // no units declared: no unit and no dimension in the label
        assert!(!svg.contains("reaction force (") && !svg.contains("()"));
    }

    /// A reaction component against a displacement: the CSV's second
    /// column is the displacement, the plot's points are (u, F) from the
    /// origin, labelled in words with the units.
    #[test]
    fn a_history_against_another_quantity() {
        let depth = History::new(
            "depth".into(),
            1,
            7,
            HistoryQuantity::Displacement(2),
            "displacement_z".into(),
        );
        let units = Units {
            length: Some("mm".into()),
            force: Some("N".into()),
        };
        let mut force = History::new(
            "force".into(),
            0,
            1,
            HistoryQuantity::ReactionComponent {
                set: "bottom".into(),
                nodes: vec![0, 1],
                component: 2,
            },
            "reaction_force_z".into(),
        )
        .with_units(units)
        .against(&depth);
        let residual = [0.0, 0.0, 1.5, 0.0, 0.0, 0.25];
        force.record(0.5, &[0.0, 0.0, 0.0, 0.0, 0.0, -0.01], &residual, &[]);
        force.record(1.0, &[0.0, 0.0, 0.0, 0.0, 0.0, -0.02], &residual, &[]);
        assert_eq!(force.samples[1], (1.0, vec![-0.02, 1.75]));
        // a checkpoint's samples of the history without its x do not fit
        assert!(force.check_restored(&force.samples).is_ok());
        let message = force.check_restored(&[(0.5, vec![1.75])]).unwrap_err();
        assert!(
            message.contains("has 1 column after time, the case's 2 (depth, reaction_force_z)"),
            "{message}"
        );
        let plot = force.plot();
        assert_eq!(
            plot.curves[0].points,
            vec![(0.0, 0.0), (-0.01, 1.75), (-0.02, 1.75)]
        );
        assert_eq!(plot.x_label, "displacement u_z (mm)");
        assert_eq!(plot.y_label, "reaction force F_z (N)");
        assert_eq!(
            plot.title,
            "Reaction force F_z on set 'bottom' against displacement u_z at node 7"
        );
        assert_eq!(
            force.location(&[[0.0; 3]; 2]),
            "on set 'bottom' (2 nodes), against 'depth'"
        );
        let dir = tempfile::tempdir().unwrap();
        force.write(dir.path()).unwrap();
        let csv = std::fs::read_to_string(dir.path().join("force.csv")).unwrap();
        assert_eq!(
            csv,
            "time,depth,reaction_force_z\n0.5,-0.01,1.75\n1,-0.02,1.75\n"
        );
    }
}
