//! The Newton convergence plot (`convergence.svg`): relative residual per
//! iteration of every converged step, on a log scale.
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
    /// Relative force residual per Newton iteration: entry `k` is plotted at
    /// iteration `k` (so entry 0, if the caller records it, is the residual
    /// of the initial guess, before any correction).
    pub residuals: Vec<f64>,
}

/// Up to this many steps get their own colour and a legend entry; more are
/// coloured along a gradient from the first to the last step, without
/// legend.
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
    let svg = render_convergence_plot(steps)
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
    const GRADIENT: [(f64, f64, f64); 5] = [
        (68.0, 1.0, 84.0),
        (59.0, 82.0, 139.0),
        (33.0, 145.0, 140.0),
        (94.0, 201.0, 98.0),
        (253.0, 231.0, 37.0),
    ];
    if count <= MAX_LEGEND_STEPS {
        let (r, g, b) = PALETTE[index % PALETTE.len()];
        return RGBColor(r, g, b);
    }
    let t = index as f64 / (count - 1).max(1) as f64 * (GRADIENT.len() - 1) as f64;
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

/// The SVG text of the plot.
fn render_convergence_plot(steps: &[StepResiduals]) -> Result<String, String> {
    let err = |e: plotters::drawing::DrawingAreaErrorKind<std::io::Error>| e.to_string();
    let decades = y_decades(steps.iter().flat_map(|s| s.residuals.iter()));
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
    let (width, height) = (900u32, 580u32);
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
                "{} steps, coloured from the first (dark blue) to the last (yellow)",
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

        let mut chart = ChartBuilder::on(&body)
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

        for (index, points) in &drawn {
            let colour = step_colour(*index, steps.len());
            let line = chart
                .draw_series(LineSeries::new(
                    points.iter().copied(),
                    colour.stroke_width(2),
                ))
                .map_err(err)?;
            if legend {
                line.label(steps[*index].label.as_str())
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                    });
            }
            chart
                .draw_series(points.iter().map(|&p| Circle::new(p, 3, colour.filled())))
                .map_err(err)?;
        }

        if legend && !drawn.is_empty() {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
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

    fn step(label: &str, residuals: &[f64]) -> StepResiduals {
        StepResiduals {
            label: label.to_string(),
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

    #[test]
    fn many_steps_use_a_gradient_without_legend() {
        let steps: Vec<StepResiduals> = (0..30)
            .map(|i| step(&format!("step {i}"), &[1.0, 10f64.powi(-2 - i % 5), 1e-9]))
            .collect();
        let svg = render_convergence_plot(&steps).unwrap();
        assert!(!svg.contains("step 7<"));
        assert!(svg.contains("30 steps"));
        assert_eq!(svg.matches("<circle").count(), 90);
        assert_eq!(step_colour(0, 30), RGBColor(68, 1, 84));
        assert_eq!(step_colour(29, 30), RGBColor(253, 231, 37));
        assert_eq!(lines_of(&svg, 0, 30), 1);
        assert_eq!(lines_of(&svg, 29, 30), 1);
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
        let svg = render_convergence_plot(&[step("deep", &[1.0, 1e-5, 1e-40])]).unwrap();
        assert_eq!(svg.matches("<circle").count(), 2);

        write_convergence_plot(&path, &[step("all zero", &[0.0])]).unwrap();
        // Extreme but finite residuals keep the axis finite.
        write_convergence_plot(&path, &[step("huge", &[1e308, 1e-300])]).unwrap();
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
