//! The Newton convergence plot (`convergence.svg`): relative residual per
//! iteration of every converged step, on a log scale, with the residual
//! tolerance that ends Newton's iterations as a dashed line.
//!
//! Drawn with plotters' SVG backend without any font feature: the backend
//! writes text as SVG `<text>` elements (font family `sans-serif`) that the
//! viewer renders with its own fonts, so no font file and no system font
//! library are needed. Without a font feature plotters only estimates text
//! extents for its layout (a fixed width per character), which is why the
//! label areas are sized generously.

use std::path::Path;

use plotters::coord::combinators::IntoLogRange;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::write_atomically;

/// The residual history of one converged step.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct StepResiduals {
    /// Shown in the legend, e.g. `"step 3, t = 0.30"`.
    pub label: String,
    /// Pseudo-time at the end of the increment: the colour of its line on
    /// the colour bar when there are too many increments for a legend.
    pub time: f64,
    /// Relative force residual per Newton iteration: entry `k` is plotted at
    /// iteration `k` (so entry 0, if the caller records it, is the residual
    /// of the initial guess, before any correction).
    pub residuals: Vec<f64>,
}

/// Up to this many steps get their own colour and a legend entry; more are
/// coloured by their pseudo-time along a gradient, with a colour bar
/// instead of the legend.
const MAX_LEGEND_STEPS: usize = 12;

/// At most this many decades are shown below the largest residual; smaller
/// residuals are not drawn (they are zero for any practical purpose, and an
/// unbounded log axis would have no usable ticks).
const MAX_DECADES: i32 = 30;

/// Writes the convergence plot of `steps` to `path` (SVG), atomically.
///
/// Residuals that are zero, negative or not finite are skipped, and so are
/// residuals more than 30 decades below the largest one (or outside
/// 1e-300‥1e300); a step without any drawable residual is left out of the
/// plot, but keeps its colour.
/// An empty `steps` gives an empty, labelled plot.
pub fn write_convergence_plot(path: &Path, steps: &[StepResiduals]) -> crate::Result<()> {
    write_convergence_plot_with_tolerance(path, steps, None)
}

/// [`write_convergence_plot`] with the relative residual `tolerance`
/// (`[solver] residual_tolerance`: Newton converges once the relative
/// residual is below it) drawn as a dashed horizontal line, named beside
/// the chart; the y axis reaches down to it.
pub fn write_convergence_plot_with_tolerance(
    path: &Path,
    steps: &[StepResiduals],
    tolerance: Option<f64>,
) -> crate::Result<()> {
    let svg = render_convergence_plot(steps, tolerance)
        .map_err(|message| crate::Error::io("draw", path, std::io::Error::other(message)))?;
    write_atomically(path, |w| w.write_all(svg.as_bytes()))
}

/// The drawable points (iteration, residual) of one step: residuals within
/// the decades `lo..=hi`.
fn points(step: &StepResiduals, (lo, hi): (i32, i32)) -> Vec<(i32, f64)> {
    let (min, max) = (10f64.powi(lo), 10f64.powi(hi));
    step.residuals
        .iter()
        .enumerate()
        .filter(|(_, r)| r.is_finite() && **r >= min && **r <= max)
        .map(|(k, r)| (i32::try_from(k).unwrap_or(i32::MAX), *r))
        .collect()
}

/// A colour for each step: a qualitative palette for few steps, a
/// dark-blue → green → yellow gradient (viridis-like) for many.
pub(crate) fn step_colour(index: usize, count: usize) -> RGBColor {
    const PALETTE: [(u8, u8, u8); MAX_LEGEND_STEPS] = [
        (31, 119, 180),
        (255, 127, 14),
        (44, 160, 44),
        (214, 39, 40),
        (148, 103, 189),
        (140, 86, 75),
        (227, 119, 194),
        (127, 127, 127),
        (188, 189, 34),
        (23, 190, 207),
        (0, 0, 128),
        (128, 0, 0),
    ];
    if count <= MAX_LEGEND_STEPS {
        let (r, g, b) = PALETTE[index % PALETTE.len()];
        return RGBColor(r, g, b);
    }
    gradient_colour(index as f64 / (count - 1).max(1) as f64)
}

/// The colour at `fraction` (0 … 1, clamped) of the dark-blue → green →
/// yellow gradient (viridis-like).
pub(crate) fn gradient_colour(fraction: f64) -> RGBColor {
    const GRADIENT: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    let fraction = if fraction.is_finite() {
        fraction.clamp(0.0, 1.0)
    } else {
        0.0
    };
    let t = fraction * (GRADIENT.len() - 1) as f64;
    let i = (t.floor() as usize).min(GRADIENT.len() - 2);
    let f = t - i as f64;
    let mix = |a: f64, b: f64| (a + (b - a) * f).round().clamp(0.0, 255.0) as u8;
    let (a, b) = (GRADIENT[i], GRADIENT[i + 1]);
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// The decades `(lo, hi)` of the log-scale y axis: whole decades around
/// the positive finite residuals, at most [`MAX_DECADES`] below the largest,
/// within 1e-300‥1e300. Without any such residual, `(-10, 0)`.
fn y_decades<'a>(residuals: impl Iterator<Item = &'a f64>) -> (i32, i32) {
    let (min, max) = residuals
        .filter(|r| r.is_finite() && **r > 0.0)
        .fold((f64::INFINITY, 0.0f64), |(lo, hi), &r| {
            (lo.min(r), hi.max(r))
        });
    if max <= 0.0 {
        return (-10, 0);
    }
    let hi = (max.log10().ceil() as i32).clamp(-299, 300);
    let lo = (min.log10().floor() as i32).clamp((hi - MAX_DECADES).max(-300), hi - 1);
    (lo, hi)
}

/// Formats a log-axis tick, e.g. `1e-6`.
fn format_tick(y: &f64) -> String {
    format!("{y:.0e}")
}

/// The colour of each step: the palette for few steps, else its
/// pseudo-time's place between the first and the last step's on the
/// gradient of the colour bar.
fn colours(steps: &[StepResiduals]) -> Vec<RGBColor> {
    if steps.len() <= MAX_LEGEND_STEPS {
        return (0..steps.len())
            .map(|i| step_colour(i, steps.len()))
            .collect();
    }
    let (lo, hi) = time_range(steps);
    steps
        .iter()
        .enumerate()
        .map(|(i, s)| {
            if hi > lo && s.time.is_finite() {
                gradient_colour((s.time - lo) / (hi - lo))
            } else {
                step_colour(i, steps.len())
            }
        })
        .collect()
}

/// The first and last finite pseudo-time of `steps`.
fn time_range(steps: &[StepResiduals]) -> (f64, f64) {
    steps
        .iter()
        .map(|s| s.time)
        .filter(|t| t.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), t| {
            (lo.min(t), hi.max(t))
        })
}

/// The colour of the tolerance line.
const TOLERANCE_COLOUR: RGBColor = RGBColor(90, 90, 90);

/// The SVG text of the plot: the chart on the left; on its right, the
/// legend (few steps) or a colour bar of the pseudo-time (many steps),
/// beside the data and never over it, and under it the tolerance line's
/// name.
fn render_convergence_plot(
    steps: &[StepResiduals],
    tolerance: Option<f64>,
) -> Result<String, String> {
    let err = |e: plotters::drawing::DrawingAreaErrorKind<std::io::Error>| e.to_string();
    let tolerance = tolerance.filter(|t| t.is_finite() && *t > 0.0);
    let decades = y_decades(
        steps
            .iter()
            .flat_map(|s| s.residuals.iter())
            .chain(tolerance.iter()),
    );
    let drawn: Vec<(usize, Vec<(i32, f64)>)> = steps
        .iter()
        .enumerate()
        .map(|(i, s)| (i, points(s, decades)))
        .filter(|(_, p)| !p.is_empty())
        .collect();
    let x_hi = drawn
        .iter()
        .flat_map(|(_, p)| p.iter().map(|p| p.0))
        .max()
        .unwrap_or(0)
        .max(1);
    // A factor 2 of margin at both ends, so that the markers there are not
    // cut and the end decades get their tick labels.
    let y_lo = 0.5 * 10f64.powi(decades.0);
    let y_hi = 2.0 * 10f64.powi(decades.1);
    let legend = steps.len() <= MAX_LEGEND_STEPS;
    let colour = colours(steps);
    // many lines: thinner, smaller markers, so that they stay apart
    let (stroke, marker) = if legend { (2, 3) } else { (1, 2) };
    let (width, height) = (1100u32, 600u32);
    let centre = width as i32 / 2;

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let (header, body) = root.split_vertically(70);
        let title = ("sans-serif", 28)
            .into_text_style(&header)
            .pos(Pos::new(HPos::Center, VPos::Top));
        header
            .draw_text("Newton convergence", &title, (centre, 10))
            .map_err(err)?;
        let note = if drawn.is_empty() {
            Some("no residuals to show".to_string())
        } else if !legend {
            Some(format!(
                "{} increments, coloured by their pseudo-time (colour bar)",
                steps.len()
            ))
        } else {
            None
        };
        if let Some(note) = note {
            let grey = BLACK.mix(0.7);
            let style = ("sans-serif", 17)
                .into_text_style(&header)
                .color(&grey)
                .pos(Pos::new(HPos::Center, VPos::Top));
            header.draw_text(&note, &style, (centre, 45)).map_err(err)?;
        }
        let (chart_area, side) = body.split_horizontally(width as i32 - SIDE_WIDTH);
        let mut chart = ChartBuilder::on(&chart_area)
            .margin(15)
            .margin_top(5)
            .x_label_area_size(55)
            .y_label_area_size(85)
            .build_cartesian_2d(0..x_hi, (y_lo..y_hi).log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("Newton iteration")
            .y_desc("relative residual")
            .x_labels((x_hi as usize + 1).min(20))
            .y_label_formatter(&format_tick)
            .axis_desc_style(("sans-serif", 20))
            .label_style(("sans-serif", 16))
            .draw()
            .map_err(err)?;

        if let Some(t) = tolerance.filter(|t| (y_lo..=y_hi).contains(t)) {
            chart
                .draw_series(DashedLineSeries::new(
                    [(0, t), (x_hi, t)],
                    10,
                    6,
                    TOLERANCE_COLOUR.stroke_width(2),
                ))
                .map_err(err)?;
            let y = side.dim_in_pixel().1 as i32 - 40;
            draw_tolerance_key(&side, y, t).map_err(err)?;
        }
        for (index, points) in &drawn {
            let c = colour[*index];
            chart
                .draw_series(LineSeries::new(
                    points.iter().copied(),
                    c.stroke_width(stroke),
                ))
                .map_err(err)?;
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, marker, c.filled())))
                .map_err(err)?;
        }
        if drawn.is_empty() {
        } else if legend {
            let text = ("sans-serif", 15)
                .into_text_style(&side)
                .pos(Pos::new(HPos::Left, VPos::Center));
            for (row, (index, _)) in drawn.iter().enumerate() {
                let y = 25 + 22 * row as i32;
                let c = colour[*index];
                side.draw(&PathElement::new(vec![(5, y), (29, y)], c.stroke_width(2)))
                    .map_err(err)?;
                side.draw_text(&steps[*index].label, &text, (37, y))
                    .map_err(err)?;
            }
        } else {
            draw_time_bar(&side, time_range(steps)).map_err(err)?;
        }
        root.present().map_err(err)?;
    }
    Ok(svg)
}

/// The tolerance line's key at height `y` of the column beside the chart:
/// dashes and `Newton tolerance 1e-8`.
fn draw_tolerance_key<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    y: i32,
    tolerance: f64,
) -> Result<(), plotters::drawing::DrawingAreaErrorKind<DB::ErrorType>> {
    let stroke = TOLERANCE_COLOUR.stroke_width(2);
    area.draw(&PathElement::new(vec![(5, y), (14, y)], stroke))?;
    area.draw(&PathElement::new(vec![(20, y), (29, y)], stroke))?;
    let text = ("sans-serif", 15)
        .into_text_style(area)
        .pos(Pos::new(HPos::Left, VPos::Center));
    area.draw_text(&format!("Newton tolerance {tolerance:e}"), &text, (37, y))
}

/// The width of the column beside the chart (legend or colour bar).
const SIDE_WIDTH: i32 = 250;

/// A vertical colour bar of the pseudo-time `lo … hi` (bottom to top) with
/// five ticks and its name.
fn draw_time_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    (lo, hi): (f64, f64),
) -> Result<(), plotters::drawing::DrawingAreaErrorKind<DB::ErrorType>> {
    let (top, bottom, left, right) = (40, area.dim_in_pixel().1 as i32 - 80, 20, 50);
    let bands = 100;
    for k in 0..bands {
        let y0 = bottom - (bottom - top) * k / bands;
        let y1 = bottom - (bottom - top) * (k + 1) / bands;
        let c = gradient_colour((k as f64 + 0.5) / bands as f64);
        area.draw(&Rectangle::new([(left, y1), (right, y0)], c.filled()))?;
    }
    area.draw(&Rectangle::new(
        [(left, top), (right, bottom)],
        BLACK.stroke_width(1),
    ))?;
    let text = ("sans-serif", 15)
        .into_text_style(area)
        .pos(Pos::new(HPos::Left, VPos::Center));
    for k in 0..=4 {
        let y = bottom - (bottom - top) * k / 4;
        let t = lo + (hi - lo) * k as f64 / 4.0;
        area.draw(&PathElement::new(vec![(right, y), (right + 6, y)], BLACK))?;
        area.draw_text(&format!("{t:.4}"), &text, (right + 10, y))?;
    }
    let name = ("sans-serif", 17)
        .into_text_style(area)
        .pos(Pos::new(HPos::Left, VPos::Top));
    area.draw_text("pseudo-time t", &name, (left, 10))?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step(label: &str, residuals: &[f64]) -> StepResiduals {
        StepResiduals {
            label: label.to_string(),
            time: label.len() as f64,
            residuals: residuals.to_vec(),
        }
    }

    /// Polylines drawn in the colour of step `index` of `count`.
    fn lines_of(svg: &str, index: usize, count: usize) -> usize {
        let c = step_colour(index, count);
        let stroke = format!("stroke=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
        svg.split("<polyline")
            .skip(1)
            .filter(|p| p[..p.find("/>").unwrap()].contains(&stroke))
            .count()
    }

    #[test]
    fn one_line_per_step_with_legend() {
        let steps = vec![
            step("step 1, t = 0.5", &[1.0, 3e-2, 4e-5, 2e-10]),
            step("step 2, t = 1.0", &[1.0, 0.2, 1e-3, 1e-7, 1e-13]),
            step("step 3 <final>", &[0.5, 1e-4]),
        ];
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("convergence.svg");
        write_convergence_plot(&path, &steps).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.contains("<svg"));
        assert!(svg.trim_end().ends_with("</svg>"));
        // One line per step plus its legend sample, and one marker per point.
        for i in 0..3 {
            assert_eq!(lines_of(&svg, i, 3), 2, "step {i}");
        }
        assert_eq!(svg.matches("<circle").count(), 4 + 5 + 2);
        for text in [
            "Newton convergence",
            "Newton iteration",
            "relative residual",
            "step 1, t = 0.5",
            "step 3 &lt;final&gt;",
            "1e-13",
        ] {
            assert!(svg.contains(text), "missing {text}");
        }
    }

    /// 100 increments: coloured by pseudo-time (not by index: the first 90
    /// in t < 0.1, the last 10 up to t = 1), a colour bar from the first to
    /// the last time instead of the legend.
    #[test]
    fn many_steps_are_coloured_by_pseudo_time_with_a_colour_bar() {
        let steps: Vec<StepResiduals> = (0..100)
            .map(|i| StepResiduals {
                label: format!("step {i}"),
                time: if i < 90 {
                    0.001 * i as f64
                } else {
                    0.1 * (i - 90) as f64 + 0.1
                },
                residuals: vec![1.0, 10f64.powi(-2 - i % 5), 1e-9],
            })
            .collect();
        let svg = render_convergence_plot(&steps, None).unwrap();
        assert!(!svg.contains("step 7<"));
        assert!(svg.contains("100 increments") && svg.contains("pseudo-time t"));
        // the bar's ends: the first and the last time
        let texts: Vec<&str> = text_elements(&svg).into_iter().map(|t| t.1).collect();
        assert!(
            texts.contains(&"0.0000") && texts.contains(&"1.0000"),
            "{texts:?}"
        );
        assert_eq!(svg.matches("<circle").count(), 300);
        let colour = colours(&steps);
        assert_eq!(colour[0], RGBColor(68, 1, 84));
        assert_eq!(colour[99], RGBColor(253, 231, 37));
        // t = 0.089 of 1: near the start of the gradient, though step 89 of 100
        assert_eq!(colour[89], gradient_colour(0.089));
        let stroke = |c: RGBColor| format!("stroke=\"#{:02X}{:02X}{:02X}\"", c.0, c.1, c.2);
        assert!(svg.contains(&stroke(colour[99])));
    }

    #[test]
    fn empty_zero_and_non_finite_residuals() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("empty.svg");
        write_convergence_plot(&path, &[]).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        assert!(svg.contains("<svg") && svg.contains("no residuals to show"));

        let steps = vec![
            step("zeros", &[0.0, 0.0]),
            step("empty", &[]),
            step(
                "mixed",
                &[1.0, f64::NAN, -1.0, f64::INFINITY, 1e-6, 0.0, 5e-324],
            ),
            step("single", &[1e-3]),
        ];
        write_convergence_plot(&path, &steps).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        // Only the drawable residuals of "mixed" and "single" are drawn.
        assert_eq!(svg.matches("<circle").count(), 3);
        assert_eq!(lines_of(&svg, 0, 4), 0);
        assert_eq!(lines_of(&svg, 2, 4), 2);
        assert!(!svg.contains("NaN") && !svg.contains("inf"));

        // Residuals far below the largest are not drawn.
        let svg = render_convergence_plot(&[step("deep", &[1.0, 1e-5, 1e-40])], None).unwrap();
        assert_eq!(svg.matches("<circle").count(), 2);

        write_convergence_plot(&path, &[step("all zero", &[0.0])]).unwrap();
        // Extreme but finite residuals keep the axis finite.
        write_convergence_plot(&path, &[step("huge", &[1e308, 1e-300])]).unwrap();
    }

    /// The `(x, y)` points of every `<polyline>` drawn in `colour`.
    fn polylines_in(svg: &str, colour: RGBColor) -> Vec<Vec<(f64, f64)>> {
        let stroke = format!(
            "stroke=\"#{:02X}{:02X}{:02X}\"",
            colour.0, colour.1, colour.2
        );
        svg.split("<polyline")
            .skip(1)
            .map(|p| &p[..p.find("/>").unwrap()])
            .filter(|p| p.contains(&stroke))
            .map(|p| {
                let start = p.find("points=\"").unwrap() + 8;
                p[start..start + p[start..].find('"').unwrap()]
                    .split_whitespace()
                    .map(|xy| {
                        let (x, y) = xy.split_once(',').unwrap();
                        (x.parse().unwrap(), y.parse().unwrap())
                    })
                    .collect()
            })
            .collect()
    }

    /// Every `<text>` element: its attributes and its content.
    fn text_elements(svg: &str) -> Vec<(&str, &str)> {
        svg.split("<text")
            .skip(1)
            .map(|t| {
                let (attributes, rest) = t.split_once('>').unwrap_or((t, ""));
                (attributes, rest.split('<').next().unwrap().trim())
            })
            .collect()
    }

    /// The `y` attribute of the `<text>` whose content is `content`.
    fn text_y(svg: &str, content: &str) -> f64 {
        let (element, _) = text_elements(svg)
            .into_iter()
            .find(|t| t.1 == content)
            .unwrap_or_else(|| panic!("no text {content}"));
        let start = element.find(" y=\"").unwrap() + 4;
        element[start..start + element[start..].find('"').unwrap()]
            .parse()
            .unwrap()
    }

    /// The tolerance 1e-8 is a dashed line across the chart at the height
    /// of the axis's `1e-8` tick (to the pixel), and is named; the axis
    /// reaches down to it though every residual is above it.
    #[test]
    fn the_tolerance_line_is_at_the_tolerance() {
        let steps = [step("step 1", &[1.0, 1e-3, 1e-6])];
        let svg = render_convergence_plot(&steps, Some(1e-8)).unwrap();
        assert!(svg.contains("Newton tolerance 1e-8"));
        let chart_right = f64::from(1100 - SIDE_WIDTH);
        let dashes: Vec<Vec<(f64, f64)>> = polylines_in(&svg, TOLERANCE_COLOUR)
            .into_iter()
            .filter(|d| d.iter().all(|p| p.0 < chart_right))
            .collect();
        assert!(dashes.len() > 10, "{} dashes", dashes.len());
        let tick = text_y(&svg, "1e-8");
        for (x, y) in dashes.iter().flatten() {
            assert!(
                (y - tick).abs() <= 1.0,
                "dash at ({x}, {y}), tick 1e-8 at {tick}"
            );
        }
        // from the first iteration to the last
        let xs = dashes.iter().flatten().map(|p| p.0);
        let span = xs.clone().fold(f64::NEG_INFINITY, f64::max) - xs.fold(f64::INFINITY, f64::min);
        assert!(span > 0.9 * (chart_right - 100.0 - 15.0), "span {span}");
        // without a tolerance, no line and no key
        let svg = render_convergence_plot(&steps, None).unwrap();
        assert!(polylines_in(&svg, TOLERANCE_COLOUR).is_empty());
        assert!(!svg.contains("tolerance"));
    }

    #[test]
    fn y_axis_spans_whole_decades() {
        assert_eq!(y_decades([0.5, 2e-7, 0.0, f64::NAN].iter()), (-7, 0));
        assert_eq!(y_decades([1.0].iter()), (-1, 0));
        assert_eq!(y_decades([].iter()), (-10, 0));
        assert_eq!(y_decades([1e308, 5e-324].iter()), (270, 300));
        assert_eq!(y_decades([1.0, 1e-100].iter()), (-30, 0));
    }
}
