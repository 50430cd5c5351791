//! Scatter and line plots as PNG (plotters' bitmap backend drawing into a buffer, encoded
//! by `image`; text in the Hack font, embedded).

use std::path::Path;
use std::sync::Once;

use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

use crate::error::BenchError;

/// One point, with an optional text beside it.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotPoint {
    pub x: f64,
    pub y: f64,
    pub label: String,
}

/// Points of one colour with a legend entry; joined by lines when `line` is set.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotSeries {
    pub name: String,
    pub color: RGBColor,
    pub points: Vec<PlotPoint>,
    pub line: bool,
}

/// Titles and axes of a plot.
#[derive(Clone, Debug, PartialEq)]
pub struct PlotSpec {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// Width and height in pixels.
    pub size: (u32, u32),
}

/// A palette of distinct colours for series.
pub const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

const FONT: &str = "sans-serif";

/// Registers the embedded font with plotters (once per process).
pub fn register_plot_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The font is compiled in and known to parse; a failure would only lose text.
        let _ = register_font(FONT, FontStyle::Normal, epaint_default_fonts::HACK_REGULAR);
    });
}

fn axis(v: f64, log: bool) -> f64 {
    if log { v.max(1e-9).log10() } else { v }
}

fn tick(v: f64, log: bool) -> String {
    if !log {
        return format!("{v:.3}").trim_end_matches('0').trim_end_matches('.').to_string();
    }
    let x = 10f64.powf(v);
    if x >= 100.0 {
        format!("{x:.0}")
    } else if x >= 1.0 {
        format!("{x:.1}")
    } else {
        format!("{x:.3}")
    }
}

/// Draws `series` and writes the PNG.
///
/// # Errors
/// [`BenchError::Plot`] when drawing or writing fails.
pub fn write_plot(path: &Path, spec: &PlotSpec, series: &[PlotSeries]) -> Result<(), BenchError> {
    register_plot_font();
    let fail = |reason: String| BenchError::Plot { path: path.to_owned(), reason };
    let (w, h) = spec.size;
    let mut buf = vec![255u8; (w * h * 3) as usize];
    {
        let root = BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| fail(e.to_string()))?;
        let pts = series.iter().flat_map(|s| &s.points).filter(|p| p.x.is_finite() && p.y.is_finite());
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for p in pts {
            let (x, y) = (axis(p.x, spec.log_x), axis(p.y, spec.log_y));
            x0 = x0.min(x);
            x1 = x1.max(x);
            y0 = y0.min(y);
            y1 = y1.max(y);
        }
        if x0 > x1 {
            (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
        }
        let pad = |lo: f64, hi: f64| {
            let d = (hi - lo).abs().max(1e-3);
            (lo - 0.08 * d, hi + 0.15 * d)
        };
        let (x0, x1) = pad(x0, x1);
        let (y0, y1) = pad(y0, y1);
        let mut chart = ChartBuilder::on(&root)
            .caption(&spec.title, (FONT, 22))
            .margin(14)
            .x_label_area_size(48)
            .y_label_area_size(64)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(|e| fail(e.to_string()))?;
        let (log_x, log_y) = (spec.log_x, spec.log_y);
        chart
            .configure_mesh()
            .x_desc(&spec.x_label)
            .y_desc(&spec.y_label)
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 16))
            .x_label_formatter(&|v| tick(*v, log_x))
            .y_label_formatter(&|v| tick(*v, log_y))
            .draw()
            .map_err(|e| fail(e.to_string()))?;
        for s in series {
            let color = s.color;
            let pts: Vec<(f64, f64, String)> = s
                .points
                .iter()
                .filter(|p| p.x.is_finite() && p.y.is_finite())
                .map(|p| (axis(p.x, log_x), axis(p.y, log_y), p.label.clone()))
                .collect();
            if s.line && pts.len() > 1 {
                chart
                    .draw_series(LineSeries::new(pts.iter().map(|(x, y, _)| (*x, *y)), color.stroke_width(2)))
                    .map_err(|e| fail(e.to_string()))?;
            }
            chart
                .draw_series(pts.iter().map(|(x, y, label)| {
                    EmptyElement::at((*x, *y))
                        + Circle::new((0, 0), 5, color.filled())
                        + Text::new(label.clone(), (7, -14), (FONT, 13).into_font().color(&color))
                }))
                .map_err(|e| fail(e.to_string()))?
                .label(s.name.clone())
                .legend(move |(x, y)| Circle::new((x + 8, y), 5, color.filled()));
        }
        chart
            .configure_series_labels()
            .label_font((FONT, 14))
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .position(SeriesLabelPosition::LowerRight)
            .draw()
            .map_err(|e| fail(e.to_string()))?;
        root.present().map_err(|e| fail(e.to_string()))?;
    }
    let image = image::RgbImage::from_raw(w, h, buf).ok_or_else(|| fail("buffer size".into()))?;
    image.save(path).map_err(|e| fail(e.to_string()))
}

/// Draws `lines` of text onto an RGB image (labels of image sheets).
pub fn draw_labels(
    image: &mut image::RgbImage,
    labels: &[(i32, i32, String)],
    size: u32,
) -> Result<(), String> {
    register_plot_font();
    let (w, h) = image.dimensions();
    let root = BitMapBackend::with_buffer(image.as_mut(), (w, h)).into_drawing_area();
    for (x, y, text) in labels {
        root.draw(&Text::new(text.clone(), (*x, *y), (FONT, size).into_font().color(&BLACK)))
            .map_err(|e| e.to_string())?;
    }
    root.present().map_err(|e| e.to_string())
}
