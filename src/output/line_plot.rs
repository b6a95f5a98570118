//! A plain x–y line plot (SVG) of a few labelled curves, for the time
//! histories and contact profiles of [`super::history`] and
//! [`super::profile`].
//!
//! Drawn like the convergence plot ([`super::plot`]): plotters' SVG backend
//! without a font feature, text left to the viewer.

use std::path::Path;

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::plot::step_colour;
use super::write_atomically;

/// One curve: points joined in the order given, each marked by a dot.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Curve {
    /// Legend entry (empty: none, e.g. the second of a pair of bounds).
    pub label: String,
    /// `(x, y)`; points with a non-finite coordinate are left out.
    pub points: Vec<(f64, f64)>,
    /// Colour: entry `colour` of the palette for `colours` curves (curves
    /// of one load step share a colour).
    pub colour: usize,
    pub style: CurveStyle,
}

/// How a curve is drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CurveStyle {
    /// A solid line with a dot at each point.
    #[default]
    Solid,
    /// A dashed line with a dot at each point.
    Dashed,
    /// Crosses at the points, no line (a set of nodes, e.g. the slipping ones).
    Markers,
}

/// A whole plot: title, axis labels and curves; optionally more panels
/// stacked below, sharing the x axis (e.g. a friction profile's
/// tangential tractions under its pressures).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LinePlot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub curves: Vec<Curve>,
    pub below: Vec<Panel>,
}

/// A panel under the first: its own y axis and curves.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Panel {
    pub y_label: String,
    pub curves: Vec<Curve>,
}

/// Writes `plot` to `path` (SVG), atomically. Each y axis includes 0; an
/// empty plot (no finite point) is drawn with unit axes and a note.
pub fn write_line_plot(path: &Path, plot: &LinePlot) -> crate::Result<()> {
    let svg = render_line_plot(plot)
        .map_err(|message| crate::Error::io("draw", path, std::io::Error::other(message)))?;
    write_atomically(path, |w| w.write_all(svg.as_bytes()))
}

/// The finite points of a curve.
fn finite_points(curve: &Curve) -> Vec<(f64, f64)> {
    curve
        .points
        .iter()
        .copied()
        .filter(|(x, y)| x.is_finite() && y.is_finite())
        .collect()
}

/// `(lo, hi)` of `values` with a margin of 5 % of the span on each side,
/// widened by ±1 (or by 10 % of the value) when the span is zero.
fn axis_range(values: impl Iterator<Item = f64>, include_zero: bool) -> (f64, f64) {
    let init = if include_zero {
        (0.0, 0.0)
    } else {
        (f64::INFINITY, f64::NEG_INFINITY)
    };
    let (lo, hi) = values.fold(init, |(lo, hi), v| (lo.min(v), hi.max(v)));
    if !(lo.is_finite() && hi.is_finite()) {
        return (0.0, 1.0);
    }
    let span = hi - lo;
    if span > 0.0 {
        (lo - 0.05 * span, hi + 0.05 * span)
    } else {
        let pad = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
        (lo - pad, hi + pad)
    }
}

/// A curve to draw and its finite points.
type Drawn<'a> = (&'a Curve, Vec<(f64, f64)>);

/// The SVG text of the plot: the title on top, the panels stacked under it
/// (sharing the x range, the x axis named under the last), each with its
/// legend in a column on its right, beside the data and never over it.
fn render_line_plot(plot: &LinePlot) -> Result<String, String> {
    let err = |e: plotters::drawing::DrawingAreaErrorKind<std::io::Error>| e.to_string();
    let first = Panel {
        y_label: plot.y_label.clone(),
        curves: plot.curves.clone(),
    };
    let panels: Vec<&Panel> = std::iter::once(&first).chain(&plot.below).collect();
    // per panel, the curves with a finite point and those points
    let drawn: Vec<Vec<Drawn>> = panels
        .iter()
        .map(|panel| {
            panel
                .curves
                .iter()
                .map(|c| (c, finite_points(c)))
                .filter(|(_, p)| !p.is_empty())
                .collect()
        })
        .collect();
    let x_range = axis_range(
        drawn
            .iter()
            .flatten()
            .flat_map(|(_, p)| p.iter().map(|p| p.0)),
        false,
    );
    let colours = panels
        .iter()
        .flat_map(|p| p.curves.iter().map(|c| c.colour + 1))
        .max()
        .unwrap_or(1);
    let panel_height = if panels.len() == 1 { 510 } else { 400 };
    let (width, height) = (1100u32, 70 + panel_height * panels.len() as u32);
    let centre = width as i32 / 2;

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let (header, body) = root.split_vertically(70);
        let title = ("sans-serif", 26)
            .into_text_style(&header)
            .pos(Pos::new(HPos::Center, VPos::Top));
        header
            .draw_text(&plot.title, &title, (centre, 10))
            .map_err(err)?;
        if drawn.iter().all(Vec::is_empty) {
            let grey = BLACK.mix(0.7);
            let style = ("sans-serif", 17)
                .into_text_style(&header)
                .color(&grey)
                .pos(Pos::new(HPos::Center, VPos::Top));
            header
                .draw_text("no values to show", &style, (centre, 45))
                .map_err(err)?;
        }
        let areas = body.split_evenly((panels.len(), 1));
        for (k, ((panel, curves), area)) in panels.iter().zip(&drawn).zip(&areas).enumerate() {
            let last = k + 1 == panels.len();
            let (chart_area, legend_area) = area.split_horizontally(LEGEND_LEFT);
            let y_range = axis_range(curves.iter().flat_map(|(_, p)| p.iter().map(|p| p.1)), true);
            let mut chart = ChartBuilder::on(&chart_area)
                .margin(10)
                .margin_right(20)
                .x_label_area_size(if last { 55 } else { 30 })
                .y_label_area_size(95)
                .build_cartesian_2d(x_range.0..x_range.1, y_range.0..y_range.1)
                .map_err(err)?;
            let mut mesh = chart.configure_mesh();
            mesh.y_desc(panel.y_label.as_str())
                .axis_desc_style(("sans-serif", 19))
                .label_style(("sans-serif", 15));
            if last {
                mesh.x_desc(plot.x_label.as_str());
            }
            mesh.draw().map_err(err)?;
            let mut legend: Vec<(&str, RGBColor, CurveStyle)> = Vec::new();
            for (curve, points) in curves {
                let colour = step_colour(curve.colour, colours);
                let style = colour.stroke_width(2);
                if !curve.label.is_empty() {
                    legend.push((curve.label.as_str(), colour, curve.style));
                }
                match curve.style {
                    CurveStyle::Markers => {
                        chart
                            .draw_series(points.iter().map(|&p| Cross::new(p, 6, style)))
                            .map_err(err)?;
                        continue;
                    }
                    CurveStyle::Dashed => chart.draw_series(DashedLineSeries::new(
                        points.iter().copied(),
                        8,
                        5,
                        style,
                    )),
                    CurveStyle::Solid => {
                        chart.draw_series(LineSeries::new(points.iter().copied(), style))
                    }
                }
                .map_err(err)?;
                chart
                    .draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                    .map_err(err)?;
            }
            draw_legend(&legend_area, &legend).map_err(err)?;
        }
        root.present().map_err(err)?;
    }
    Ok(svg)
}

/// Where the legend column starts, in pixels from the left of a panel.
const LEGEND_LEFT: i32 = 790;

/// A panel's legend, one entry a line from the top of `area` (a column
/// beside the chart): the curve's line, dashes or cross, then its label;
/// entries that do not fit are counted in a last line.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    entries: &[(&str, RGBColor, CurveStyle)],
) -> Result<(), plotters::drawing::DrawingAreaErrorKind<DB::ErrorType>> {
    const ROW: i32 = 20;
    let rows = ((area.dim_in_pixel().1 as i32 - 30) / ROW).max(1) as usize;
    let text = ("sans-serif", 14)
        .into_text_style(area)
        .pos(Pos::new(HPos::Left, VPos::Center));
    let shown = if entries.len() > rows {
        rows - 1
    } else {
        entries.len()
    };
    for (i, &(label, colour, style)) in entries.iter().take(shown).enumerate() {
        let y = 20 + ROW * i as i32;
        let stroke = colour.stroke_width(2);
        match style {
            CurveStyle::Solid => area.draw(&PathElement::new(vec![(4, y), (28, y)], stroke))?,
            CurveStyle::Dashed => {
                area.draw(&PathElement::new(vec![(4, y), (12, y)], stroke))?;
                area.draw(&PathElement::new(vec![(18, y), (26, y)], stroke))?;
            }
            CurveStyle::Markers => area.draw(&Cross::new((16, y), 6, stroke))?,
        }
        area.draw_text(label, &text, (36, y))?;
    }
    if shown < entries.len() {
        let y = 20 + ROW * shown as i32;
        let more = format!("… and {} more", entries.len() - shown);
        area.draw_text(&more, &text, (36, y))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn curves_markers_and_labels() {
        let plot = LinePlot {
            title: "lift <centre>".into(),
            x_label: "pseudo-time t".into(),
            y_label: "displacement_z".into(),
            curves: vec![
                Curve {
                    label: "press".into(),
                    points: vec![(0.0, 0.0), (0.5, 0.1), (1.0, f64::NAN), (1.0, 0.3)],
                    colour: 0,
                    style: CurveStyle::Solid,
                },
                Curve {
                    label: "second series".into(),
                    points: vec![(0.0, -0.2), (1.0, 0.2)],
                    colour: 1,
                    style: CurveStyle::Dashed,
                },
            ],
            below: Vec::new(),
        };
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("lift.svg");
        write_line_plot(&path, &plot).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.trim_end().ends_with("</svg>"));
        // one dot per finite point, the NaN left out
        assert_eq!(svg.matches("<circle").count(), 3 + 2);
        for text in [
            "lift &lt;centre&gt;",
            "pseudo-time t",
            "displacement_z",
            "press",
            "second series",
        ] {
            assert!(svg.contains(text), "missing {text}");
        }
        assert!(!svg.contains("NaN"));
    }

    /// The `x` attribute of every SVG element `tag` (`<circle cx=…`, `<text x=…`).
    fn xs(svg: &str, tag: &str, attribute: &str) -> Vec<(f64, String)> {
        svg.split(&format!("<{tag} "))
            .skip(1)
            .filter_map(|e| {
                let start = e.find(&format!("{attribute}=\"")).unwrap() + attribute.len() + 2;
                let x: f64 = e[start..start + e[start..].find('"').unwrap()]
                    .parse()
                    .ok()?;
                let text = e
                    .split('>')
                    .nth(1)
                    .unwrap_or("")
                    .split('<')
                    .next()
                    .unwrap_or("")
                    .trim();
                Some((x, text.to_string()))
            })
            .collect()
    }

    /// Two panels share the x axis, each with its y label; every legend
    /// entry is right of every data point (the legend never covers data),
    /// also when the data reach the right edge.
    #[test]
    fn stacked_panels_and_legends_beside_the_data() {
        let curve = |label: &str, y: f64, style| Curve {
            label: label.into(),
            points: (0..=20).map(|i| (i as f64, y * i as f64)).collect(),
            colour: 0,
            style,
        };
        let plot = LinePlot {
            title: "profile".into(),
            x_label: "abscissa (mm)".into(),
            y_label: "contact pressure (N/mm²)".into(),
            curves: vec![curve("pressure curve", 1.0, CurveStyle::Solid)],
            below: vec![Panel {
                y_label: "tangential traction (N/mm²)".into(),
                curves: vec![
                    curve("traction curve", -0.3, CurveStyle::Solid),
                    curve("bound curve", 0.3, CurveStyle::Dashed),
                    curve("slipping curve", 0.2, CurveStyle::Markers),
                ],
            }],
        };
        let svg = render_line_plot(&plot).unwrap();
        for text in [
            "contact pressure (N/mm²)",
            "tangential traction (N/mm²)",
            "abscissa (mm)",
        ] {
            assert_eq!(svg.matches(text).count(), 1, "{text}");
        }
        let dots = xs(&svg, "circle", "cx");
        assert_eq!(dots.len(), 3 * 21);
        let rightmost = dots.iter().map(|d| d.0).fold(0.0, f64::max);
        let legend: Vec<(f64, String)> = xs(&svg, "text", "x")
            .into_iter()
            .filter(|t| t.1.ends_with(" curve"))
            .collect();
        assert_eq!(legend.len(), 4);
        for (x, label) in legend {
            assert!(
                x > rightmost,
                "legend '{label}' at x = {x}, data up to {rightmost}"
            );
        }
    }

    /// A curve without a label is drawn (its dots) but has no legend
    /// entry: ±μ t_N named once for its two dashed bounds.
    #[test]
    fn an_unlabelled_curve_has_no_legend_entry() {
        let bound = |label: &str, sign: f64| Curve {
            label: label.into(),
            points: vec![(0.0, sign), (1.0, sign)],
            colour: 0,
            style: CurveStyle::Dashed,
        };
        let svg = |second: &str| {
            render_line_plot(&LinePlot {
                curves: vec![bound("±μ t_N", 1.0), bound(second, -1.0)],
                ..Default::default()
            })
            .unwrap()
        };
        let (unlabelled, labelled) = (svg(""), svg("−μ t_N"));
        assert_eq!(unlabelled.matches("<circle").count(), 4);
        assert_eq!(unlabelled.matches("±μ t_N").count(), 1);
        // the labelled second curve adds its legend sample (two dashes)
        // and its name, nothing else
        assert_eq!(
            labelled.matches("<polyline").count(),
            unlabelled.matches("<polyline").count() + 2
        );
        assert_eq!(
            labelled.matches("<text").count(),
            unlabelled.matches("<text").count() + 1
        );
    }

    #[test]
    fn empty_plot_is_drawn() {
        let svg = render_line_plot(&LinePlot::default()).unwrap();
        assert!(svg.contains("no values to show"));
    }

    #[test]
    fn axis_ranges() {
        assert_eq!(axis_range([1.0, 3.0].into_iter(), false), (0.9, 3.1));
        // zero included: 0 … 2 plus 5 %
        assert_eq!(axis_range([1.0, 2.0].into_iter(), true), (-0.1, 2.1));
        assert_eq!(axis_range([2.0].into_iter(), false), (1.8, 2.2));
        assert_eq!(axis_range(std::iter::empty(), true), (-1.0, 1.0));
        assert_eq!(axis_range(std::iter::empty(), false), (0.0, 1.0));
    }
}
