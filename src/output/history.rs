//! Time histories (`[[output.history]]`): one nodal quantity recorded after
//! every converged increment, written as `<name>.csv` (time, value) and
//! `<name>.svg` (value against pseudo-time, i.e. the load factor of a ramp).

use std::path::Path;

use super::line_plot::{write_line_plot, Curve, LinePlot};
use super::table::write_csv;
use crate::contact::interface::NodeReport;

/// What a history records at its node.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum HistoryQuantity {
    /// Displacement component `u_i` (0, 1, 2 for x, y, z).
    Displacement(usize),
    /// Signed gap `g` of secondary node `index` of contact interface
    /// `interface` (positive open).
    Gap { interface: usize, index: usize },
    /// Contact pressure `t_N ≥ 0` of a secondary node.
    ContactPressure { interface: usize, index: usize },
}

/// A quantity at one node over the run.
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    /// File stem and plot title.
    pub name: String,
    /// Mesh node index and the node's id in the mesh file.
    pub node: usize,
    pub node_id: u64,
    pub quantity: HistoryQuantity,
    /// Column header and axis label, e.g. `displacement_z`.
    pub label: String,
    /// `(time, value)` of every converged increment so far.
    pub samples: Vec<(f64, f64)>,
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
            samples: Vec::new(),
        }
    }

    /// The quantity in state `u` (displacements first) with the contact
    /// reports `contact[interface][index]` of that state.
    pub fn value(&self, u: &[f64], contact: &[Vec<NodeReport>]) -> f64 {
        match self.quantity {
            HistoryQuantity::Displacement(i) => u[3 * self.node + i],
            HistoryQuantity::Gap { interface, index } => contact[interface][index].gap,
            HistoryQuantity::ContactPressure { interface, index } => {
                contact[interface][index].pressure
            }
        }
    }

    /// Add the sample of a converged increment at pseudo-time `time`.
    pub fn record(&mut self, time: f64, u: &[f64], contact: &[Vec<NodeReport>]) {
        let value = self.value(u, contact);
        self.samples.push((time, value));
    }

    /// Write `<name>.csv` and `<name>.svg` into `dir`, atomically; the
    /// plot starts from `(0, 0)`, the unloaded reference state, for
    /// displacements.
    pub fn write(&self, dir: &Path) -> crate::Result<()> {
        let rows: Vec<Vec<f64>> = self.samples.iter().map(|&(t, v)| vec![t, v]).collect();
        write_csv(
            &dir.join(format!("{}.csv", self.name)),
            &["time", &self.label],
            &rows,
        )?;
        let mut points = Vec::with_capacity(self.samples.len() + 1);
        if matches!(self.quantity, HistoryQuantity::Displacement(_)) {
            points.push((0.0, 0.0));
        }
        points.extend(&self.samples);
        let plot = LinePlot {
            title: format!("{}: {} at node {}", self.name, self.label, self.node_id),
            x_label: "pseudo-time t (load factor)".into(),
            y_label: self.label.clone(),
            curves: vec![Curve {
                label: self.label.clone(),
                points,
                colour: 0,
                style: Default::default(),
            }],
        };
        write_line_plot(&dir.join(format!("{}.svg", self.name)), &plot)
    }
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
        for h in [&mut lift, &mut gap] {
            h.record(0.5, &u, &contact);
            h.record(1.0, &u, &contact);
        }
        assert_eq!(lift.samples, vec![(0.5, 0.3), (1.0, 0.3)]);
        assert_eq!(gap.samples, vec![(0.5, 0.25), (1.0, 0.25)]);
        let dir = tempfile::tempdir().unwrap();
        lift.write(dir.path()).unwrap();
        let csv = std::fs::read_to_string(dir.path().join("lift.csv")).unwrap();
        assert_eq!(csv, "time,displacement_z\n5e-1,3e-1\n1,3e-1\n");
        let svg = std::fs::read_to_string(dir.path().join("lift.svg")).unwrap();
        // the origin and the two samples
        assert_eq!(svg.matches("<circle").count(), 3);
        assert!(svg.contains("node 7"));
    }
}
