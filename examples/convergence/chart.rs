//! The log-log chart of relative RMSE against seconds, one line per method, drawn with
//! plotters into an RGB buffer and written as a PNG (atomically).

use super::methods::Run;
use photon_maps::render::image::write_atomically;
use plotters::prelude::*;
use std::path::Path;

/// Line colours, in the order of the methods run (the default order: path tracing, SPPM,
/// progressive disc, cube and ball, final gather, progressive final gather).
const COLOURS: [RGBColor; 7] = [
    RGBColor(0, 0, 0),
    RGBColor(214, 39, 40),
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
];

/// Registers the font the labels are drawn with (plotters draws no text without one).
pub fn register_font(path: &Path) -> Result<(), String> {
    let bytes = std::fs::read(path).map_err(|e| format!("font {}: {e}", path.display()))?;
    // plotters keeps the font for the life of the program.
    let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
    plotters::style::register_font("sans-serif", FontStyle::Normal, bytes)
        .map_err(|_| format!("font {}: not a TrueType/OpenType font", path.display()))
}

/// The time axis's label for a study whose seconds are `clock` ("Cpu": CPU time over the
/// threads; otherwise wall time) on `threads` threads.
pub fn seconds_axis(clock: &str, threads: usize) -> String {
    if clock == "Cpu" {
        format!("rendering seconds, CPU time / {threads} threads")
    } else {
        format!("rendering seconds, wall time ({threads} threads)")
    }
}

/// Draws `runs` of scene `title` into `path` (800 × 500 PNG); `floor` is the reference's own
/// noise, drawn as a dashed line; `seconds` labels the time axis.
pub fn draw(path: &Path, title: &str, runs: &[Run], floor: f64, seconds: &str) -> Result<(), String> {
    let (width, height) = (800u32, 500u32);
    let mut buffer = vec![255u8; (width * height * 3) as usize];
    let points = runs.iter().flat_map(|r| r.samples.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for s in points.filter(|s| s.seconds > 0.0 && s.rel_rmse > 0.0) {
        x0 = x0.min(s.seconds);
        x1 = x1.max(s.seconds);
        y0 = y0.min(s.rel_rmse);
        y1 = y1.max(s.rel_rmse);
    }
    if x0 > x1 {
        return Err(format!("{title}: nothing to plot"));
    }
    let y0 = y0.min(floor.max(f64::MIN_POSITIVE));
    {
        let area = BitMapBackend::with_buffer(&mut buffer, (width, height)).into_drawing_area();
        let fail = |e: &dyn std::fmt::Display| format!("{title}: chart: {e}");
        let mut chart = ChartBuilder::on(&area)
            .caption(format!("{title}: relative RMSE vs seconds"), ("sans-serif", 22))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(
                (x0 * 0.8..x1 * 1.25).log_scale(),
                (y0 * 0.8..y1 * 1.25).log_scale(),
            )
            .map_err(|e| fail(&e))?;
        chart
            .configure_mesh()
            .x_desc(seconds)
            .y_desc("relative RMSE")
            .label_style(("sans-serif", 14))
            .draw()
            .map_err(|e| fail(&e))?;
        for (run, colour) in runs.iter().zip(COLOURS.iter().cycle()) {
            let line: Vec<(f64, f64)> = thin(run)
                .into_iter()
                .filter(|&(x, y)| x > 0.0 && y > 0.0)
                .collect();
            let style = ShapeStyle::from(colour).stroke_width(2);
            chart
                .draw_series(LineSeries::new(line, style))
                .map_err(|e| fail(&e))?
                .label(run.method.label())
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], style));
        }
        if floor > 0.0 {
            for (level, label, shade) in [
                (floor, "reference's own noise σ (subtracted)", 0.5),
                (3.0 * floor, "3σ: lower errors are not judged", 0.25),
            ] {
                let dashes = DashedLineSeries::new(
                    vec![(x0 * 0.8, level), (x1 * 1.25, level)],
                    6,
                    4,
                    BLACK.mix(shade).into(),
                );
                chart
                    .draw_series(dashes)
                    .map_err(|e| fail(&e))?
                    .label(label)
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.mix(shade)));
            }
        }
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 14))
            .position(SeriesLabelPosition::LowerLeft)
            .draw()
            .map_err(|e| fail(&e))?;
        area.present().map_err(|e| fail(&e))?;
    }
    write_atomically(path, |w| {
        let mut encoder = png::Encoder::new(w, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header().map_err(std::io::Error::other)?;
        writer.write_image_data(&buffer).map_err(std::io::Error::other)?;
        writer.finish().map_err(std::io::Error::other)
    })
    .map_err(|e| format!("{}: {e}", path.display()))
}

/// At most about 200 points per line, evenly spaced in log time (a path tracer's run has one
/// sample per pass, thousands of them).
fn thin(run: &Run) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    let mut next = 0.0f64;
    for s in &run.samples {
        if s.seconds <= 0.0 {
            continue;
        }
        let t = s.seconds.ln();
        if out.is_empty() || t >= next {
            out.push((s.seconds, s.rel_rmse));
            next = t + 0.02;
        }
    }
    if let (Some(last), Some(s)) = (out.last(), run.samples.last())
        && last.0 != s.seconds
    {
        out.push((s.seconds, s.rel_rmse));
    }
    out
}
