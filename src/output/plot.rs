//! The Newton convergence plot (`convergence.svg`): relative residual per
//! iteration of every converged step, on a log scale.
//!
//! Drawn with plotters' SVG backend without any font feature: the backend
//! writes text as SVG `<text>` elements (font family `sans-serif`) that the
//! viewer renders with its own fonts, so no font file and no system font
//! library are needed. Plotters only estimates text extents for layout
//! (roughly 0.6 em per character), which is why the label areas are sized
//! generously.

use std::path::Path;

use plotters::coord::combinators::IntoLogRange;
use plotters::prelude::*;

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

/// Residuals below this (or not finite) are not drawn (a residual of
/// exactly zero cannot be shown on a log scale).
const SMALLEST_RESIDUAL: f64 = 1e-300;

/// Writes the convergence plot of `steps` to `path` (SVG), atomically.
///
/// Residuals that are zero, negative, below 1e-300 or not finite are
/// skipped; a step without any drawable residual is left out of the plot.
/// An empty `steps` gives an empty, labelled plot.
pub fn write_convergence_plot(path: &Path, steps: &[StepResiduals]) -> crate::Result<()> {
    let svg = render_convergence_plot(steps)
        .map_err(|message| crate::Error::io("draw", path, std::io::Error::other(message)))?;
    write_atomically(path, |w| w.write_all(svg.as_bytes()))
}

/// The drawable points (iteration, residual) of one step.
fn points(step: &StepResiduals) -> Vec<(i32, f64)> {
    step.residuals
        .iter()
        .enumerate()
        .filter(|(_, r)| r.is_finite() && **r >= SMALLEST_RESIDUAL)
        .map(|(k, r)| (i32::try_from(k).unwrap_or(i32::MAX), *r))
        .collect()
}

/// A colour for each step: a qualitative palette for few steps, a
/// dark-blue → green → yellow gradient (viridis-like) for many.
fn step_colour(index: usize, count: usize) -> RGBColor {
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

/// The log-scale y range: whole decades around the data.
fn y_range(steps: &[Vec<(i32, f64)>]) -> (f64, f64) {
    let values = steps.iter().flatten().map(|p| p.1);
    let (min, max) = values.fold((f64::INFINITY, 0.0f64), |(lo, hi), r| (lo.min(r), hi.max(r)));
    if !(min.is_finite() && max > 0.0) {
        return (1e-10, 1.0);
    }
    let lo = min.log10().floor().clamp(-300.0, 307.0) as i32;
    let mut hi = max.log10().ceil().clamp(-300.0, 308.0) as i32;
    if hi <= lo {
        hi = lo + 1;
    }
    (10f64.powi(lo), 10f64.powi(hi))
}

/// Formats a log-axis tick, e.g. `1e-6`.
fn format_tick(y: &f64) -> String {
    format!("{y:.0e}")
}

/// The SVG text of the plot.
fn render_convergence_plot(steps: &[StepResiduals]) -> Result<String, String> {
    let err = |e: plotters::drawing::DrawingAreaErrorKind<std::io::Error>| e.to_string();
    let drawn: Vec<(usize, Vec<(i32, f64)>)> = steps
        .iter()
        .enumerate()
        .map(|(i, s)| (i, points(s)))
        .filter(|(_, p)| !p.is_empty())
        .collect();
    let all: Vec<Vec<(i32, f64)>> = drawn.iter().map(|(_, p)| p.clone()).collect();
    let (y_lo, y_hi) = y_range(&all);
    let x_hi = all
        .iter()
        .flatten()
        .map(|p| p.0)
        .max()
        .unwrap_or(0)
        .max(1);
    let legend = steps.len() <= MAX_LEGEND_STEPS;

    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (900, 560)).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        let mut chart = ChartBuilder::on(&root)
            .caption("Newton convergence", ("sans-serif", 28))
            .margin(15)
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
                line.label(steps[*index].label.as_str()).legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], colour.stroke_width(2))
                });
            }
            chart
                .draw_series(
                    points
                        .iter()
                        .map(|&p| Circle::new(p, 3, colour.filled())),
                )
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
        } else if !legend {
            let note = format!(
                "{} steps, coloured from the first (dark blue) to the last (yellow)",
                steps.len()
            );
            root.draw_text(
                &note,
                &("sans-serif", 15).into_text_style(&root).color(&BLACK.mix(0.7)),
                (110, 45),
            )
            .map_err(err)?;
        }
        if drawn.is_empty() {
            root.draw_text(
                "no residuals to show",
                &("sans-serif", 18).into_text_style(&root).color(&BLACK.mix(0.6)),
                (380, 270),
            )
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
            step("mixed", &[1.0, f64::NAN, -1.0, f64::INFINITY, 1e-6, 0.0, 5e-324]),
            step("single", &[1e-3]),
        ];
        write_convergence_plot(&path, &steps).unwrap();
        let svg = std::fs::read_to_string(&path).unwrap();
        // Only the drawable residuals of "mixed" and "single" are drawn.
        assert_eq!(svg.matches("<circle").count(), 3);
        assert_eq!(lines_of(&svg, 0, 4), 0);
        assert_eq!(lines_of(&svg, 2, 4), 2);
        assert!(!svg.contains("NaN") && !svg.contains("inf"));

        write_convergence_plot(&path, &[step("all zero", &[0.0])]).unwrap();
        // Extreme but finite residuals keep the axis finite.
        write_convergence_plot(&path, &[step("huge", &[1e308, 1e-300])]).unwrap();
    }

    #[test]
    fn y_range_is_whole_decades() {
        assert_eq!(y_range(&[vec![(0, 0.5), (1, 2e-7)]]), (1e-7, 1.0));
        assert_eq!(y_range(&[vec![(0, 1.0)]]), (1.0, 10.0));
        assert_eq!(y_range(&[]), (1e-10, 1.0));
    }
}
