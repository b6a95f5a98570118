//! Contact profiles (`[[output.profile]]`): the secondary nodes of one
//! interface that lie within a band of a reference-configuration segment
//! `a → b`, ordered by their abscissa `s = (X − a)·(b − a)/|b − a|` along
//! it. At the end of every load step the profile writes
//! `<name>_<step>.csv` (one row per node, the columns of [`COLUMNS`]) and
//! redraws `<name>.svg`: the [`PLOTTED`] columns against the abscissa, one
//! colour per step so far, the contact pressure in a panel and, with
//! friction, the tangential traction in a second panel below it.
//!
//! With friction the table also holds the tangential traction along the
//! line, the slip bound `μ t_N` and the slipping nodes, and the plot draws
//! them in the second panel (`±μ t_N` dashed, the slipping nodes as
//! crosses on `t_T`): where
//! the traction meets the bound the nodes slip, elsewhere they stick. Without
//! friction those columns are NaN and not drawn.
//!
//! To add a quantity, add one [`Column`] to [`COLUMNS`] (reading the
//! [`Sample`]); list its header in [`PLOTTED`] with a style to draw it.

use std::path::Path;

use super::line_plot::{write_line_plot, Curve, CurveStyle, LinePlot, Panel};
use super::table::write_csv;
use super::units::{Dimension, Units};
use crate::contact::friction::ContactStatus;
use crate::contact::interface::NodeReport;

/// What a column may read at one node of the profile.
#[derive(Clone, Copy, Debug)]
pub struct Sample<'a> {
    pub node: &'a ProfileNode,
    pub report: &'a NodeReport,
    /// Unit direction of the line.
    pub direction: [f64; 3],
    /// The interface's friction coefficient (`None`: frictionless).
    pub friction_coefficient: Option<f64>,
}

impl Sample<'_> {
    /// `t_T` along the line (NaN without friction).
    fn tangential_along_line(&self) -> f64 {
        match self.friction_coefficient {
            Some(_) => (0..3)
                .map(|i| self.report.tangential_traction[i] * self.direction[i])
                .sum(),
            None => f64::NAN,
        }
    }
}

/// One column of the profile tables.
pub struct Column {
    /// CSV header and legend/axis name.
    pub header: &'static str,
    pub value: fn(&Sample) -> f64,
}

/// The columns of every profile table, in order.
pub const COLUMNS: &[Column] = &[
    Column {
        header: "abscissa",
        value: |s| s.node.abscissa,
    },
    Column {
        header: "node",
        value: |s| s.node.node_id as f64,
    },
    Column {
        header: "contact_pressure",
        value: |s| s.report.pressure,
    },
    Column {
        header: "gap",
        value: |s| s.report.gap,
    },
    Column {
        header: "status",
        value: |s| s.report.status.code() as f64,
    },
    Column {
        header: "tangential_traction",
        value: |s| s.tangential_along_line(),
    },
    Column {
        header: "tangential_traction_norm",
        value: |s| match s.friction_coefficient {
            Some(_) => {
                let t = s.report.tangential_traction;
                (t[0] * t[0] + t[1] * t[1] + t[2] * t[2]).sqrt()
            }
            None => f64::NAN,
        },
    },
    Column {
        header: "slip_bound",
        value: |s| match s.friction_coefficient {
            Some(mu) => mu * s.report.pressure,
            None => f64::NAN,
        },
    },
    Column {
        header: "minus_slip_bound",
        value: |s| match s.friction_coefficient {
            Some(mu) => -mu * s.report.pressure,
            None => f64::NAN,
        },
    },
    Column {
        header: "slipping",
        value: |s| match s.report.status {
            ContactStatus::Slip => s.tangential_along_line(),
            _ => f64::NAN,
        },
    },
];

/// The columns drawn in the profile plot, against the abscissa: the
/// header, the legend's name (empty: no legend entry, the two slip bounds
/// named once as `±μ t_N`), the style and the panel (0: the contact
/// pressure; 1, below it: the tangential traction and its bounds).
pub const PLOTTED: &[(&str, &str, CurveStyle, usize)] = &[
    ("contact_pressure", "t_N", CurveStyle::Solid, 0),
    ("tangential_traction", "t_T", CurveStyle::Solid, 1),
    ("slip_bound", "±μ t_N", CurveStyle::Dashed, 1),
    ("minus_slip_bound", "", CurveStyle::Dashed, 1),
    ("slipping", "slipping nodes", CurveStyle::Markers, 1),
];

/// A secondary node on the profile line.
#[derive(Clone, Debug, PartialEq)]
pub struct ProfileNode {
    /// Index among the interface's secondary nodes.
    pub index: usize,
    /// Id in the mesh file.
    pub node_id: u64,
    /// Reference-configuration abscissa along the segment.
    pub abscissa: f64,
}

/// The table of one load step.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct StepProfile {
    pub step_name: String,
    pub time: f64,
    /// One row per profile node, the values of [`COLUMNS`].
    pub rows: Vec<Vec<f64>>,
}

/// A profile along a line of one contact interface.
#[derive(Clone, Debug, PartialEq)]
pub struct Profile {
    /// File stem.
    pub name: String,
    /// Index of the interface among the problem's contacts, and its name.
    pub interface: usize,
    pub interface_name: String,
    /// Unit direction of the segment.
    pub direction: [f64; 3],
    /// The interface's friction coefficient (`None`: frictionless).
    pub friction_coefficient: Option<f64>,
    /// Nodes in the band, by increasing abscissa.
    pub nodes: Vec<ProfileNode>,
    /// Tables of the steps ended so far.
    pub steps: Vec<StepProfile>,
    /// The case's units, for the plot's labels.
    pub units: Units,
}

/// The secondary nodes (indices into `positions`, the reference positions
/// of an interface's nodes) whose distance to the segment `a → b` is at
/// most `width`, with their abscissa, sorted by abscissa (then index).
/// `a ≠ b` is the caller's to check.
pub fn nodes_in_band(
    positions: &[[f64; 3]],
    a: [f64; 3],
    b: [f64; 3],
    width: f64,
) -> Vec<(usize, f64)> {
    let d: Vec<f64> = (0..3).map(|i| b[i] - a[i]).collect();
    let length = d.iter().map(|v| v * v).sum::<f64>().sqrt();
    let mut found: Vec<(usize, f64)> = positions
        .iter()
        .enumerate()
        .filter_map(|(j, x)| {
            let r: Vec<f64> = (0..3).map(|i| x[i] - a[i]).collect();
            let s = (0..3).map(|i| r[i] * d[i]).sum::<f64>() / length;
            let t = s.clamp(0.0, length) / length;
            let distance = (0..3)
                .map(|i| (r[i] - t * d[i]).powi(2))
                .sum::<f64>()
                .sqrt();
            (distance <= width).then_some((j, s))
        })
        .collect();
    found.sort_by(|p, q| p.1.total_cmp(&q.1).then(p.0.cmp(&q.0)));
    found
}

/// A step name as a file-name part: letters, digits, `-` and `_` kept,
/// anything else `_`.
pub fn file_part(step_name: &str) -> String {
    step_name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || c == '-' || c == '_' {
                c
            } else {
                '_'
            }
        })
        .collect()
}

impl Profile {
    /// Record the end of a load step from the interface's node reports.
    pub fn record(&mut self, step_name: &str, time: f64, reports: &[NodeReport]) {
        let rows = self
            .nodes
            .iter()
            .map(|node| {
                let sample = Sample {
                    node,
                    report: &reports[node.index],
                    direction: self.direction,
                    friction_coefficient: self.friction_coefficient,
                };
                COLUMNS.iter().map(|c| (c.value)(&sample)).collect()
            })
            .collect();
        self.steps.push(StepProfile {
            step_name: step_name.to_string(),
            time,
            rows,
        });
    }

    /// Write the last step's `<name>_<step>.csv` and the plot of all steps
    /// so far, `<name>.svg`, into `dir` (atomically).
    pub fn write(&self, dir: &Path) -> crate::Result<()> {
        let Some(last) = self.steps.last() else {
            return Ok(());
        };
        let header: Vec<&str> = COLUMNS.iter().map(|c| c.header).collect();
        let file = format!("{}_{}.csv", self.name, file_part(&last.step_name));
        write_csv(&dir.join(file), &header, &last.rows)?;
        let column = |name: &str| COLUMNS.iter().position(|c| c.header == name);
        #[allow(clippy::expect_used)] // a constant of this file: COLUMNS has an abscissa
        let x = column("abscissa").expect("the abscissa is a column");
        // per panel; series with no finite value (friction's, on a
        // frictionless interface) are neither drawn nor named
        let mut panels: [Vec<Curve>; 2] = Default::default();
        for (k, step) in self.steps.iter().enumerate() {
            for &(name, legend, style, panel) in PLOTTED {
                let Some(y) = column(name) else { continue };
                let points: Vec<(f64, f64)> = step.rows.iter().map(|r| (r[x], r[y])).collect();
                if points.iter().all(|p| !p.1.is_finite()) {
                    continue;
                }
                panels[panel].push(Curve {
                    label: if legend.is_empty() {
                        String::new()
                    } else {
                        format!("{legend}, {} (t = {:.3})", step.step_name, step.time)
                    },
                    points,
                    colour: k,
                    style,
                });
            }
        }
        let [pressure, tangential] = panels;
        let units = &self.units;
        let plot = LinePlot {
            title: format!(
                "{} along a line of interface '{}'",
                if tangential.is_empty() {
                    "Contact pressure"
                } else {
                    "Contact pressure and tangential traction"
                },
                self.interface_name
            ),
            x_label: units.label(
                "abscissa along the line, reference configuration",
                Dimension::Length,
            ),
            y_label: units.label("contact pressure t_N", Dimension::Stress),
            curves: pressure,
            below: if tangential.is_empty() {
                Vec::new()
            } else {
                vec![Panel {
                    y_label: units
                        .label("tangential traction t_T along the line", Dimension::Stress),
                    curves: tangential,
                }]
            },
        };
        write_line_plot(&dir.join(format!("{}.svg", self.name)), &plot)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_selects_and_orders_by_abscissa() {
        let positions = [
            [2.0, 0.05, 0.0],  // in, s = 2
            [0.5, -0.1, 0.0],  // in, s = 0.5
            [1.0, 0.3, 0.0],   // too far from the line
            [-0.05, 0.0, 0.0], // beyond the start, within the band
            [-0.5, 0.0, 0.0],  // beyond the start, outside
            [4.1, 0.0, 0.0],   // beyond the end, within the band
        ];
        let found = nodes_in_band(&positions, [0.0; 3], [4.0, 0.0, 0.0], 0.1);
        let indices: Vec<usize> = found.iter().map(|f| f.0).collect();
        assert_eq!(indices, vec![3, 1, 0, 5]);
        assert!((found[0].1 + 0.05).abs() < 1e-15 && (found[3].1 - 4.1).abs() < 1e-15);
    }

    #[test]
    fn one_table_per_step_and_one_curve_per_step() {
        let mut profile = Profile {
            name: "centre_line".into(),
            interface: 0,
            interface_name: "foundation".into(),
            direction: [1.0, 0.0, 0.0],
            friction_coefficient: None,
            nodes: vec![
                ProfileNode {
                    index: 1,
                    node_id: 11,
                    abscissa: 0.0,
                },
                ProfileNode {
                    index: 0,
                    node_id: 10,
                    abscissa: 0.5,
                },
            ],
            steps: Vec::new(),
            units: Units::default(),
        };
        let report = |gap, pressure| NodeReport {
            gap,
            pressure,
            active: pressure > 0.0,
            status: if pressure > 0.0 {
                ContactStatus::Stick
            } else {
                ContactStatus::Open
            },
            ..Default::default()
        };
        let dir = tempfile::tempdir().unwrap();
        profile.record("half load", 0.5, &[report(0.0, 0.25), report(0.5, 0.0)]);
        profile.write(dir.path()).unwrap();
        profile.record("full", 1.0, &[report(0.0, 0.5), report(1.0, 0.0)]);
        profile.write(dir.path()).unwrap();
        let csv = std::fs::read_to_string(dir.path().join("centre_line_half_load.csv")).unwrap();
        assert_eq!(
            csv,
            "abscissa,node,contact_pressure,gap,status,tangential_traction,tangential_traction_norm,slip_bound,minus_slip_bound,slipping\n\
             0,11,0,0.5,0,NaN,NaN,NaN,NaN,NaN\n\
             0.5,10,0.25,0,1,NaN,NaN,NaN,NaN,NaN\n"
        );
        assert!(dir.path().join("centre_line_full.csv").exists());
        let svg = std::fs::read_to_string(dir.path().join("centre_line.svg")).unwrap();
        assert_eq!(svg.matches("<circle").count(), 4);
        assert!(svg.contains("half load (t = 0.500)") && svg.contains("full (t = 1.000)"));
    }
}
