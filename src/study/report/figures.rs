//! Files of the paper's parametric figures ([`crate::analytic::parametric`]): CSV tables and
//! SVG plots.

use crate::analytic::parametric::Figure;
use crate::error::{Error, Result};
use std::path::Path;

/// The CSV text of figure `f`: header `x_column,eta (label),…` (η dimensionless), one row per x.
pub fn csv(f: &Figure) -> Result<String> {
    f.check_finite()?;
    let mut s = String::from(f.x_column);
    for (label, _) in &f.curves {
        s.push_str(&format!(",eta [{label}]"));
    }
    s.push('\n');
    for (i, x) in f.x.iter().enumerate() {
        s.push_str(&format!("{}", x * f.x_scale));
        for (_, ys) in &f.curves {
            s.push_str(&format!(",{:.6}", ys[i]));
        }
        s.push('\n');
    }
    Ok(s)
}

/// The SVG plot of figure `f` (plotters).
pub fn svg(f: &Figure) -> Result<String> {
    use plotters::prelude::*;
    f.check_finite()?;
    let xs: Vec<f64> = f.x.iter().map(|x| x * f.x_scale).collect();
    let (x0, x1) = (xs[0], xs[xs.len() - 1]);
    let ymax = f
        .curves
        .iter()
        .flat_map(|(_, ys)| ys.iter().copied())
        .fold(0.0_f64, f64::max);
    let ymax = if ymax > 0.0 { 1.1 * ymax } else { 1.0 };
    let mut out = String::new();
    let plot_err = |e: &dyn std::fmt::Display| Error::External(format!("plotting {}: {e}", f.name));
    {
        let root = SVGBackend::with_string(&mut out, (800, 560)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| plot_err(&e))?;
        let mut chart = ChartBuilder::on(&root)
            .caption(f.title, ("sans-serif", 22))
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(64)
            .build_cartesian_2d(x0..x1, 0.0..ymax)
            .map_err(|e| plot_err(&e))?;
        chart
            .configure_mesh()
            .x_desc(f.x_label)
            .y_desc("energy dissipation factor eta (-)")
            .draw()
            .map_err(|e| plot_err(&e))?;
        for (k, (label, ys)) in f.curves.iter().enumerate() {
            let color = Palette99::pick(k).to_rgba();
            chart
                .draw_series(LineSeries::new(
                    xs.iter().copied().zip(ys.iter().copied()),
                    color.stroke_width(2),
                ))
                .map_err(|e| plot_err(&e))?
                .label(label.as_str())
                .legend(move |(x, y)| {
                    PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                });
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .position(SeriesLabelPosition::LowerRight)
            .draw()
            .map_err(|e| plot_err(&e))?;
        root.present().map_err(|e| plot_err(&e))?;
    }
    Ok(out)
}

/// Writes `DIR/name.csv` and `DIR/name.svg` of figure `f` (each atomically).
pub fn write(f: &Figure, dir: &Path) -> Result<()> {
    crate::atomic::write_atomic(dir.join(format!("{}.csv", f.name)), csv(f)?.as_bytes())?;
    crate::atomic::write_atomic(dir.join(format!("{}.svg", f.name)), svg(f)?.as_bytes())
}
