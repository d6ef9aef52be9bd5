//! The PNG chart: median main-pass time of every method × shadow mode per image size (bars,
//! with the p10–p90 range as a line), and the sample-count sweep.

use std::path::Path;

use anyhow::{Context, Result, anyhow};
use plotters::prelude::*;

use super::report::CaseResult;

const SIZE: (u32, u32) = (1400, 600);
const FONT: &str = "sans-serif";
const PALETTE: [RGBColor; 4] = [
    RGBColor(66, 114, 196),
    RGBColor(237, 125, 49),
    RGBColor(112, 173, 71),
    RGBColor(165, 90, 170),
];

fn register_font() -> Result<()> {
    // egui's default font, already in the build: no system fonts needed.
    plotters::style::register_font(FONT, FontStyle::Normal, epaint_default_fonts::UBUNTU_LIGHT)
        .map_err(|_| anyhow!("the embedded chart font does not parse"))
}

// Short enough for 15 groups side by side: "pom S" is POM with soft shadows.
fn bar_label(case: &CaseResult) -> String {
    let shadows = match case.shadows.as_str() {
        "off" => "",
        "hard" => " H",
        "soft" => " S",
        other => other,
    };
    format!("{}{shadows}", case.method)
}

/// One series per image size and path the frames ran, by size, then in the order the paths
/// ran; named by the size, and the path too where the cases ran on more than one.
fn series<'a>(cases: impl IntoIterator<Item = &'a CaseResult>) -> Vec<(Series, String)> {
    let mut series: Vec<Series> = Vec::new();
    for case in cases {
        let key = ((case.width, case.height), case.path);
        if !series.contains(&key) {
            series.push(key);
        }
    }
    series.sort_by_key(|(size, _)| *size);
    let several_paths = series.iter().any(|(_, path)| *path != series[0].1);
    series
        .into_iter()
        .map(|key @ ((width, height), path)| {
            let name = if several_paths {
                format!("{width}x{height} {path}")
            } else {
                format!("{width}x{height}")
            };
            (key, name)
        })
        .collect()
}

/// An image size and the path the frames ran.
type Series = ((u32, u32), &'static str);

fn in_series(case: &CaseResult, (size, path): Series) -> bool {
    (case.width, case.height) == size && case.path == path
}

/// Draws the chart for `cases` into `path` (PNG), titled with `adapter`.
pub fn write_chart(path: &Path, adapter: &str, cases: &[CaseResult]) -> Result<()> {
    register_font()?;
    let mut pixels = vec![0_u8; (SIZE.0 * SIZE.1 * 3) as usize];
    draw(&mut pixels, adapter, cases)
        .map_err(|error| anyhow!("drawing {}: {error}", path.display()))?;
    // plotters draws into memory; the image crate (already used for every PNG) encodes it.
    let chart = image::RgbImage::from_raw(SIZE.0, SIZE.1, pixels)
        .context("the chart buffer has the wrong size")?;
    Ok(pom::files::write_png(path, &chart)?)
}

fn draw(
    pixels: &mut [u8],
    adapter: &str,
    cases: &[CaseResult],
) -> std::result::Result<(), Box<dyn std::error::Error>> {
    let root = BitMapBackend::with_buffer(pixels, SIZE).into_drawing_area();
    root.fill(&WHITE)?;
    let root = root.titled(
        &format!("GPU main pass, median ms (bars) and p10-p90 (lines) on {adapter}"),
        (FONT, 20),
    )?;
    let (left, right) = root.split_horizontally(900);
    // The seed port's forward rows would add a path that neither chart shows.
    let series = series(
        cases
            .iter()
            .filter(|c| c.group == "methods" || c.group == "samples"),
    );

    let methods: Vec<&CaseResult> = cases.iter().filter(|c| c.group == "methods").collect();
    let labels: Vec<String> = {
        let mut labels: Vec<String> = methods.iter().map(|c| bar_label(c)).collect();
        labels.dedup();
        let mut seen = Vec::new();
        labels.retain(|l| {
            let new = !seen.contains(l);
            seen.push(l.clone());
            new
        });
        labels
    };
    let top = methods.iter().map(|c| c.spread.p90_ms).fold(0.0, f64::max) * 1.1;
    let mut chart = ChartBuilder::on(&left)
        .margin(10)
        .x_label_area_size(90)
        .y_label_area_size(60)
        .caption("every method x shadows (H hard, S soft)", (FONT, 16))
        .build_cartesian_2d(-0.5..labels.len().max(1) as f64 - 0.5, 0.0..top.max(1e-6))?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(labels.len().max(1))
        .x_label_formatter(&|x| labels.get(x.floor() as usize).cloned().unwrap_or_default())
        .x_label_style(TextStyle::from((FONT, 11).into_font()).transform(FontTransform::Rotate90))
        .y_desc("ms")
        .label_style((FONT, 12))
        .draw()?;
    let width = 0.8 / series.len().max(1) as f64;
    for (index, (key, name)) in series.iter().enumerate() {
        let color = PALETTE[index % PALETTE.len()];
        let bars: Vec<(f64, &CaseResult)> = methods
            .iter()
            .filter(|c| in_series(c, *key))
            .filter_map(|c| {
                let label = bar_label(c);
                let bar = labels.iter().position(|l| *l == label)?;
                Some((bar as f64 - 0.4 + width * index as f64, *c))
            })
            .collect();
        chart
            .draw_series(bars.iter().map(|(x, c)| {
                Rectangle::new(
                    [(*x, 0.0), (*x + width * 0.9, c.spread.median_ms)],
                    color.filled(),
                )
            }))?
            .label(name.as_str())
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 10, y + 5)], color.filled()));
        chart.draw_series(bars.iter().map(|(x, c)| {
            let middle = *x + width * 0.45;
            PathElement::new(
                vec![(middle, c.spread.p10_ms), (middle, c.spread.p90_ms)],
                BLACK.stroke_width(1),
            )
        }))?;
    }
    chart
        .configure_series_labels()
        .label_font((FONT, 12))
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;

    let sweep: Vec<&CaseResult> = cases.iter().filter(|c| c.group == "samples").collect();
    let max_x = sweep.iter().map(|c| c.max_samples).max().unwrap_or(1);
    let top = sweep.iter().map(|c| c.spread.median_ms).fold(0.0, f64::max) * 1.1;
    let mut chart = ChartBuilder::on(&right)
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .caption("POM, max_samples sweep", (FONT, 16))
        .build_cartesian_2d(0u32..max_x + 1, 0.0..top.max(1e-6))?;
    chart
        .configure_mesh()
        .x_desc("max_samples")
        .y_desc("ms")
        .label_style((FONT, 12))
        .draw()?;
    for (index, (key, name)) in series.iter().enumerate() {
        let color = PALETTE[index % PALETTE.len()];
        let points: Vec<(u32, f64)> = sweep
            .iter()
            .filter(|c| in_series(c, *key))
            .map(|c| (c.max_samples, c.spread.median_ms))
            .collect();
        chart
            .draw_series(LineSeries::new(points.clone(), color.stroke_width(2)))?
            .label(name.as_str())
            .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 12, y)], color));
        chart.draw_series(points.iter().map(|p| Circle::new(*p, 3, color.filled())))?;
    }
    chart
        .configure_series_labels()
        .label_font((FONT, 12))
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()?;
    root.present()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn case(size: (u32, u32), path: &'static str) -> CaseResult {
        CaseResult::example("methods", size, path, "prepass+opaque", 1.0)
    }

    #[test]
    fn a_series_per_size_and_path_named_for_the_path_only_when_there_are_two() {
        let names = |cases: &[CaseResult]| -> Vec<String> {
            series(cases).into_iter().map(|(_, name)| name).collect()
        };
        let (small, large) = ((64, 36), (96, 54));
        let one = [case(large, "deferred"), case(small, "deferred")];
        assert_eq!(names(&one), ["64x36", "96x54"]);
        let both = [
            case(small, "forward"),
            case(large, "forward"),
            case(small, "deferred"),
            case(large, "deferred"),
        ];
        assert_eq!(
            names(&both),
            [
                "64x36 forward",
                "64x36 deferred",
                "96x54 forward",
                "96x54 deferred"
            ]
        );
    }
}
