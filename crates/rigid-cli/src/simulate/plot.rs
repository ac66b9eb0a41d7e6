//! The `--plot` figure: body angular velocity, energy error and momentum error against time.

use plotters::prelude::*;
use rigid::body::{State, Summary};
use std::path::Path;

/// Decimated time series for the figure.
#[derive(Default)]
pub struct Samples {
    t: Vec<f64>,
    w: [Vec<f64>; 3],
    energy: Vec<f64>,
    momentum: Vec<f64>,
}

impl Samples {
    /// Records the state at `t`, with the signed relative energy error and the relative
    /// angular-momentum error of `s`.
    pub fn push(&mut self, t: f64, x: &State, s: &Summary) {
        self.t.push(t);
        for (k, w) in self.w.iter_mut().enumerate() {
            w.push(x.twist.w[k]);
        }
        let scale = s.energy0.abs().max(s.kinetic0.abs());
        let de = s.energy - s.energy0;
        self.energy.push(if scale > 0.0 { de / scale } else { de });
        self.momentum.push(s.relative_momentum_error());
    }
}

/// `[lo, hi]` of the values, widened so that it is never empty.
fn range<'a>(series: impl IntoIterator<Item = &'a Vec<f64>>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in series.into_iter().flatten() {
        lo = lo.min(*x);
        hi = hi.max(*x);
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return (-1.0, 1.0);
    }
    let pad = ((hi - lo) * 0.05)
        .max(hi.abs().max(lo.abs()) * 1e-3)
        .max(1e-300);
    (lo - pad, hi + pad)
}

type Panel<'a> = DrawingArea<SVGBackend<'a>, plotters::coord::Shift>;

fn panel(
    area: &Panel,
    title: &str,
    t: &[f64],
    curves: &[(&str, &Vec<f64>, RGBColor)],
) -> Result<(), Box<dyn std::error::Error>> {
    let t_end = t.last().copied().unwrap_or(1.0).max(1e-300);
    let (lo, hi) = range(curves.iter().map(|c| c.1));
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 18))
        .margin(8)
        .x_label_area_size(30)
        .y_label_area_size(80)
        .build_cartesian_2d(0.0..t_end, lo..hi)?;
    chart
        .configure_mesh()
        .x_desc("t (s)")
        .y_label_formatter(&|y| format!("{y:.3e}"))
        .draw()?;
    for (name, ys, color) in curves {
        let color = *color;
        chart
            .draw_series(LineSeries::new(
                t.iter().copied().zip(ys.iter().copied()),
                color,
            ))?
            .label(*name)
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
    }
    if curves.len() > 1 {
        chart
            .configure_series_labels()
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .draw()?;
    }
    Ok(())
}

/// Draws the three panels into the SVG file `path`.
pub fn draw(path: &Path, s: &Samples) -> Result<(), Box<dyn std::error::Error>> {
    let root = SVGBackend::new(path, (900, 900)).into_drawing_area();
    root.fill(&WHITE)?;
    let areas = root.split_evenly((3, 1));
    panel(
        &areas[0],
        "body angular velocity (rad/s)",
        &s.t,
        &[
            ("ωx", &s.w[0], RED),
            ("ωy", &s.w[1], GREEN),
            ("ωz", &s.w[2], BLUE),
        ],
    )?;
    panel(
        &areas[1],
        "relative energy error (E - E₀)/E₀",
        &s.t,
        &[("", &s.energy, BLACK)],
    )?;
    panel(
        &areas[2],
        "relative angular momentum error |L - L₀|/|L₀|",
        &s.t,
        &[("", &s.momentum, BLACK)],
    )?;
    root.present()?;
    Ok(())
}
