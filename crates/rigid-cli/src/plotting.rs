//! Figures of time series, one panel per quantity stacked vertically, written as SVG or PNG
//! (chosen by the file's extension) with plotters; the text is set in DejaVu Sans, embedded in
//! the binary, so a PNG needs no system font.

use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// One panel: curves against time.
pub struct Panel {
    /// The caption (quantity and unit).
    pub title: String,
    /// The y-axis label (unit).
    pub y_label: String,
    /// `(name, values, colour)`; a legend is drawn when there are 2 to [`LEGEND_ALL`] named
    /// curves; with more, see [`legend_choice`].
    pub curves: Vec<(String, Vec<f64>, RGBColor)>,
}

/// The most named curves a legend lists in full.
pub const LEGEND_ALL: usize = 12;
/// With more named curves than [`LEGEND_ALL`], how many the legend names.
pub const LEGEND_TOP: usize = 6;

/// The curves a legend names when a panel has more than [`LEGEND_ALL`] named ones: the
/// [`LEGEND_TOP`] with the largest peak `|value|` (non-finite values ignored), largest first
/// (ties: the earlier curve), leaving out those that stay at 0 (so none when all do). `None`
/// when the panel has at most [`LEGEND_ALL`] named curves (all are named).
#[must_use]
pub fn legend_choice(curves: &[(String, Vec<f64>, RGBColor)]) -> Option<Vec<usize>> {
    let named: Vec<usize> = (0..curves.len())
        .filter(|&i| !curves[i].0.is_empty())
        .collect();
    if named.len() <= LEGEND_ALL {
        return None;
    }
    let peak = |i: usize| {
        curves[i]
            .1
            .iter()
            .filter(|x| x.is_finite())
            .fold(0.0f64, |m, x| m.max(x.abs()))
    };
    let mut order: Vec<usize> = named.into_iter().filter(|&i| peak(i) > 0.0).collect();
    order.sort_by(|&a, &b| peak(b).total_cmp(&peak(a)).then(a.cmp(&b)));
    order.truncate(LEGEND_TOP);
    Some(order)
}

/// A colour per curve index (Tableau 10).
#[must_use]
pub fn color(i: usize) -> RGBColor {
    const C: [(u8, u8, u8); 10] = [
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
    ];
    let (r, g, b) = C[i % C.len()];
    RGBColor(r, g, b)
}

/// `[lo, hi]` of the values, widened so that it is never empty.
fn range<'a>(series: impl IntoIterator<Item = &'a Vec<f64>>) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in series.into_iter().flatten().filter(|x| x.is_finite()) {
        lo = lo.min(*x);
        hi = hi.max(*x);
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return (-1.0, 1.0);
    }
    let pad = ((hi - lo) * 0.05)
        .max(hi.abs().max(lo.abs()) * 1e-3)
        .max(1e-12);
    (lo - pad, hi + pad)
}

fn register_font() {
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        // a font that is valid by construction (it ships inside the `dejavu` crate)
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

type Error = Box<dyn std::error::Error>;

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    t: &[f64],
    p: &Panel,
) -> Result<(), Error>
where
    DB::ErrorType: 'static,
{
    let t_end = t.last().copied().unwrap_or(1.0).max(1e-9);
    let (lo, hi) = range(p.curves.iter().map(|c| &c.1));
    let mut chart = ChartBuilder::on(area)
        .caption(&p.title, ("sans-serif", 17))
        .margin(8)
        .x_label_area_size(34)
        .y_label_area_size(78)
        .build_cartesian_2d(0.0..t_end, lo..hi)?;
    let span = (hi - lo).abs().max(hi.abs()).max(1e-300);
    let fmt = move |y: &f64| {
        if (1e-2..1e5).contains(&span) {
            format!("{y:.3}")
        } else {
            format!("{y:.2e}")
        }
    };
    chart
        .configure_mesh()
        .x_desc("t (s)")
        .y_desc(&p.y_label)
        .y_label_formatter(&fmt)
        .label_style(("sans-serif", 13))
        .draw()?;
    let line = |xy: (i32, i32), c: RGBColor| PathElement::new(vec![xy, (xy.0 + 18, xy.1)], c);
    let named = p.curves.iter().filter(|c| !c.0.is_empty()).count();
    let mut legend = (2..=LEGEND_ALL).contains(&named);
    if let Some(top) = legend_choice(&p.curves) {
        // too many for one legend: the others thin and light grey, then the top ones over
        // them, each in its own colour and named
        let grey = RGBColor(200, 200, 200);
        for (i, (_, ys, _)) in p.curves.iter().enumerate() {
            if !top.contains(&i) {
                chart.draw_series(LineSeries::new(
                    t.iter().copied().zip(ys.iter().copied()),
                    grey.stroke_width(1),
                ))?;
            }
        }
        for (rank, &i) in top.iter().enumerate() {
            let (name, ys, _) = &p.curves[i];
            let c = color(rank);
            chart
                .draw_series(LineSeries::new(
                    t.iter().copied().zip(ys.iter().copied()),
                    c.stroke_width(2),
                ))?
                .label(name.as_str())
                .legend(move |xy| line(xy, c));
        }
        let others = p.curves.len() - top.len();
        let note = if top.is_empty() {
            format!("{others} curves in grey, unnamed: all stay at 0")
        } else {
            format!(
                "{others} others in grey, unnamed (named: the {} largest peak |value|)",
                top.len()
            )
        };
        chart
            .draw_series(std::iter::empty::<PathElement<(f64, f64)>>())?
            .label(note)
            .legend(move |xy| line(xy, grey));
        legend = true;
    } else {
        for (name, ys, color) in &p.curves {
            let color = *color;
            let series = chart.draw_series(LineSeries::new(
                t.iter().copied().zip(ys.iter().copied()),
                color.stroke_width(2),
            ))?;
            if !name.is_empty() {
                series
                    .label(name.as_str())
                    .legend(move |xy| line(xy, color));
            }
        }
    }
    if legend {
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .label_font(("sans-serif", 12))
            .border_style(BLACK)
            .background_style(WHITE.mix(0.8))
            .draw()?;
    }
    Ok(())
}

fn draw_all<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    t: &[f64],
    panels: &[Panel],
) -> Result<(), Error>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE)?;
    let areas = root.split_evenly((panels.len().max(1), 1));
    for (a, p) in areas.iter().zip(panels) {
        draw_panel(a, t, p)?;
    }
    root.present()?;
    Ok(())
}

/// `Ok` for a path ending in `.svg` or `.png` (case-insensitive), the formats the figures are written in.
///
/// # Errors
/// Any other extension, naming the path.
pub fn check_format(path: &std::path::Path) -> Result<(), String> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("svg" | "png") => Ok(()),
        _ => Err(format!(
            "--plot {}: the figure is written as SVG or PNG, by the extension (.svg or .png)",
            path.display()
        )),
    }
}

/// Draw `panels` against `t` into `path`: SVG, or PNG for a `.png` name. Written atomically.
///
/// # Errors
/// A drawing error, or the file cannot be written.
pub fn save(path: &Path, t: &[f64], panels: &[Panel]) -> Result<(), String> {
    register_font();
    let size = (1000u32, 280 * panels.len().max(1) as u32);
    let err = |e: Error| format!("cannot draw {}: {e}", path.display());
    let png = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    let bytes = if png {
        let mut buf = vec![0u8; (size.0 * size.1 * 3) as usize];
        draw_all(
            BitMapBackend::with_buffer(&mut buf, size).into_drawing_area(),
            t,
            panels,
        )
        .map_err(err)?;
        let mut out = Vec::new();
        let mut enc = png::Encoder::new(&mut out, size.0, size.1);
        enc.set_color(png::ColorType::Rgb);
        enc.set_depth(png::BitDepth::Eight);
        let mut w = enc.write_header().map_err(|e| err(e.into()))?;
        w.write_image_data(&buf).map_err(|e| err(e.into()))?;
        w.finish().map_err(|e| err(e.into()))?;
        out
    } else {
        let mut s = String::new();
        draw_all(
            SVGBackend::with_string(&mut s, size).into_drawing_area(),
            t,
            panels,
        )
        .map_err(err)?;
        s.into_bytes()
    };
    crate::util::write_atomic(path, &bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn curves(peaks: &[f64]) -> Vec<(String, Vec<f64>, RGBColor)> {
        peaks
            .iter()
            .enumerate()
            // a curve from 0 to -peak and back: its peak |value| is `peak`
            .map(|(i, p)| (format!("c{i}"), vec![0.0, -p, 0.5 * p], color(i)))
            .collect()
    }

    #[test]
    fn legend_names_the_six_largest_peaks_and_never_a_curve_at_zero() {
        assert_eq!(legend_choice(&curves(&[1.0; 12])), None, "12: all named");
        let peaks = [
            0.1, 5.0, 0.2, 3.0, 0.0, 7.0, 0.3, 3.0, 0.4, 9.0, 0.5, 0.6, 2.0, 0.7,
        ];
        assert_eq!(
            legend_choice(&curves(&peaks)),
            Some(vec![9, 5, 1, 3, 7, 12])
        );
        // two non-zero curves among 14: only they are named
        let mut two = [0.0; 14];
        two[4] = 1.0;
        two[2] = 2.0;
        assert_eq!(legend_choice(&curves(&two)), Some(vec![2, 4]));
        assert_eq!(legend_choice(&curves(&[0.0; 13])), Some(vec![]));
    }
}
