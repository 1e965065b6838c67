//! Small SVG line/point charts (plotters) for the verification report.

use crate::error::{Error, Result};
use plotters::prelude::*;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// A solid line.
    Line,
    /// Markers only.
    Points,
    /// Vertical bars (error bars): the points taken in pairs, (x, low) and (x, high), each
    /// pair drawn as one segment; no legend entry when the label is empty.
    Bars,
}

/// One curve or point set (a line of one point is drawn as a marker).
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Legend label.
    pub label: String,
    /// (x, y) points; non-finite points are dropped.
    pub points: Vec<(f64, f64)>,
    /// Drawing style.
    pub style: Style,
}

/// A chart.
#[derive(Debug, Clone, PartialEq)]
pub struct Chart {
    /// Title.
    pub title: String,
    /// x-axis label with unit.
    pub x_label: String,
    /// y-axis label with unit.
    pub y_label: String,
    /// The data.
    pub series: Vec<Series>,
}

fn range(v: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    });
    if !lo.is_finite() || !hi.is_finite() {
        return (0.0, 1.0);
    }
    let pad = if hi > lo {
        0.05 * (hi - lo)
    } else {
        0.5 * lo.abs().max(1e-12)
    };
    (lo - pad, hi + pad)
}

impl Chart {
    /// The chart as SVG text.
    ///
    /// Errors: plotters drawing failures ([`Error::External`]).
    pub fn svg(&self) -> Result<String> {
        let pts = |s: &Series| {
            s.points
                .iter()
                .copied()
                .filter(|(x, y)| x.is_finite() && y.is_finite())
                .collect::<Vec<_>>()
        };
        let all: Vec<(f64, f64)> = self.series.iter().flat_map(pts).collect();
        let (x0, x1) = range(all.iter().map(|p| p.0));
        let (y0, y1) = range(all.iter().map(|p| p.1));
        let err =
            |e: &dyn std::fmt::Display| Error::External(format!("plotting '{}': {e}", self.title));
        let mut out = String::new();
        {
            let root = SVGBackend::with_string(&mut out, (820, 560)).into_drawing_area();
            root.fill(&WHITE).map_err(|e| err(&e))?;
            let mut chart = ChartBuilder::on(&root)
                .caption(&self.title, ("sans-serif", 20))
                .margin(16)
                .x_label_area_size(48)
                .y_label_area_size(80)
                .build_cartesian_2d(x0..x1, y0..y1)
                .map_err(|e| err(&e))?;
            chart
                .configure_mesh()
                .x_desc(self.x_label.as_str())
                .y_desc(self.y_label.as_str())
                .draw()
                .map_err(|e| err(&e))?;
            for (k, s) in self.series.iter().enumerate() {
                let color = Palette99::pick(k).to_rgba();
                let p = pts(s);
                // A line through one point draws nothing: show the point instead, so the
                // legend never lists a series that is not on the chart.
                let style = if s.style == Style::Line && p.len() < 2 {
                    Style::Points
                } else {
                    s.style
                };
                match style {
                    Style::Bars => {
                        let drawn =
                            chart
                                .draw_series(p.chunks_exact(2).map(|w| {
                                    PathElement::new(vec![w[0], w[1]], color.stroke_width(1))
                                }))
                                .map_err(|e| err(&e))?;
                        if !s.label.is_empty() {
                            drawn.label(s.label.as_str()).legend(move |(x, y)| {
                                PathElement::new(vec![(x + 10, y - 6), (x + 10, y + 6)], color)
                            });
                        }
                    }
                    Style::Line => {
                        chart
                            .draw_series(LineSeries::new(p, color.stroke_width(2)))
                            .map_err(|e| err(&e))?
                            .label(s.label.as_str())
                            .legend(move |(x, y)| {
                                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                            });
                    }
                    Style::Points => {
                        chart
                            .draw_series(p.into_iter().map(|xy| Circle::new(xy, 4, color.filled())))
                            .map_err(|e| err(&e))?
                            .label(s.label.as_str())
                            .legend(move |(x, y)| Circle::new((x + 10, y), 4, color.filled()));
                    }
                }
            }
            chart
                .configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK)
                .position(SeriesLabelPosition::UpperRight)
                .draw()
                .map_err(|e| err(&e))?;
            root.present().map_err(|e| err(&e))?;
        }
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn svg_has_axes_labels_and_both_series() {
        let c = Chart {
            title: "test chart".into(),
            x_label: "time (s)".into(),
            y_label: "delta (m)".into(),
            series: vec![
                Series {
                    label: "analytical".into(),
                    points: vec![(0.0, 0.0), (1.0, 2.0), (2.0, 0.5)],
                    style: Style::Line,
                },
                Series {
                    label: "FE".into(),
                    points: vec![(0.5, 1.0), (f64::NAN, 1.0)],
                    style: Style::Points,
                },
            ],
        };
        let svg = c.svg().unwrap();
        for text in ["test chart", "time (s)", "delta (m)", "analytical", "FE"] {
            assert!(svg.contains(text), "missing {text}");
        }
        assert!(svg.contains("<polyline") || svg.contains("<path"));
        assert!(svg.contains("<circle"));
        assert!(!svg.contains("NaN"));
    }

    /// A figure with one x-point (one speed, one diameter) still draws every series its
    /// legend lists: the one-point analytical "line" becomes a marker.
    #[test]
    fn a_one_point_line_is_drawn_as_a_marker() {
        let c = Chart {
            title: "one point".into(),
            x_label: "v (m/s)".into(),
            y_label: "v after (m/s)".into(),
            series: vec![Series {
                label: "analytical".into(),
                points: vec![(-1.0, 0.3)],
                style: Style::Line,
            }],
        };
        let svg = c.svg().unwrap();
        assert!(svg.contains("analytical"));
        assert!(svg.contains("<circle"), "the single point is not drawn");
    }
}
