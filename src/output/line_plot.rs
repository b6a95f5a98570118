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
    /// Legend entry.
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

/// A whole plot: title, axis labels and curves.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LinePlot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub curves: Vec<Curve>,
}

/// Writes `plot` to `path` (SVG), atomically. The y axis always includes
/// 0; an empty plot (no finite point) is drawn with unit axes and a note.
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

/// The SVG text of the plot.
fn render_line_plot(plot: &LinePlot) -> Result<String, String> {
    let err = |e: plotters::drawing::DrawingAreaErrorKind<std::io::Error>| e.to_string();
    let drawn: Vec<(&Curve, Vec<(f64, f64)>)> = plot
        .curves
        .iter()
        .map(|c| (c, finite_points(c)))
        .filter(|(_, p)| !p.is_empty())
        .collect();
    let all = || drawn.iter().flat_map(|(_, p)| p.iter());
    let x_range = axis_range(all().map(|p| p.0), false);
    let y_range = axis_range(all().map(|p| p.1), true);
    let colours = plot.curves.iter().map(|c| c.colour + 1).max().unwrap_or(1);
    let (width, height) = (900u32, 580u32);
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
        if drawn.is_empty() {
            let grey = BLACK.mix(0.7);
            let style = ("sans-serif", 17)
                .into_text_style(&header)
                .color(&grey)
                .pos(Pos::new(HPos::Center, VPos::Top));
            header
                .draw_text("no values to show", &style, (centre, 45))
                .map_err(err)?;
        }
        let mut chart = ChartBuilder::on(&body)
            .margin(15)
            .margin_top(5)
            .margin_right(30)
            .x_label_area_size(55)
            .y_label_area_size(95)
            .build_cartesian_2d(x_range.0..x_range.1, y_range.0..y_range.1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc(plot.x_label.as_str())
            .y_desc(plot.y_label.as_str())
            .axis_desc_style(("sans-serif", 20))
            .label_style(("sans-serif", 16))
            .draw()
            .map_err(err)?;
        for (curve, points) in &drawn {
            let colour = step_colour(curve.colour, colours);
            let style = colour.stroke_width(2);
            if curve.style == CurveStyle::Markers {
                chart
                    .draw_series(points.iter().map(|&p| Cross::new(p, 6, style)))
                    .map_err(err)?
                    .label(curve.label.as_str())
                    .legend(move |(x, y)| Cross::new((x + 10, y), 6, style));
                continue;
            }
            let dashed = curve.style == CurveStyle::Dashed;
            let series = if dashed {
                chart.draw_series(DashedLineSeries::new(points.iter().copied(), 8, 5, style))
            } else {
                chart.draw_series(LineSeries::new(points.iter().copied(), style))
            }
            .map_err(err)?;
            series.label(curve.label.as_str()).legend(move |(x, y)| {
                let end = if dashed { x + 8 } else { x + 20 };
                PathElement::new(vec![(x, y), (end, y)], style)
            });
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                .map_err(err)?;
        }
        if !drawn.is_empty() {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperLeft)
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .label_font(("sans-serif", 15))
                .draw()
                .map_err(err)?;
        }
        root.present().map_err(err)?;
    }
    Ok(svg)
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
