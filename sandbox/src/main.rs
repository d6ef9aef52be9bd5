//! The sandbox: renders the demo scene headless to a PNG (the live egui window comes later).

mod demo_scene;

use std::path::PathBuf;

use anyhow::{Context, Result};
use clap::Parser;

/// Renders the POM demo scene to a PNG file.
#[derive(Debug, Parser)]
#[command(name = "sandbox", version, about)]
struct Args {
    /// Where to write the PNG.
    #[arg(long, default_value = "target/sandbox-preview.png")]
    out: PathBuf,
    /// Image size as WIDTHxHEIGHT, each 1..=8192.
    #[arg(long, default_value = "960x540", value_parser = parse_size)]
    size: (u32, u32),
}

fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let (width, height) = text
        .split_once(['x', 'X'])
        .ok_or_else(|| format!("expected WIDTHxHEIGHT, got {text:?}"))?;
    let side = |value: &str| -> Result<u32, String> {
        let parsed: u32 = value
            .trim()
            .parse()
            .map_err(|_| format!("{value:?} is not a whole number of pixels"))?;
        if (1..=8192).contains(&parsed) {
            Ok(parsed)
        } else {
            Err(format!("{parsed} is outside 1..=8192"))
        }
    };
    Ok((side(width)?, side(height)?))
}

fn run(args: &Args) -> Result<()> {
    let (width, height) = args.size;
    let mut app = pom::App::new();
    app.add_plugin(pom::RenderPlugin::headless(width, height));
    demo_scene::spawn(&mut app)?;
    app.update().context("rendering the demo scene")?;
    let image = pom::capture(&app).context("reading the frame back")?;
    if let Some(parent) = args.out.parent().filter(|p| !p.as_os_str().is_empty()) {
        std::fs::create_dir_all(parent)
            .with_context(|| format!("creating {}", parent.display()))?;
    }
    image
        .save(&args.out)
        .with_context(|| format!("writing {}", args.out.display()))?;
    let gpu = app
        .resources
        .get::<pom::GpuContext>()
        .map(|gpu| gpu.adapter_info().name)
        .unwrap_or_default();
    println!("wrote {} ({width}×{height}, {gpu})", args.out.display());
    Ok(())
}

fn main() {
    let args = Args::parse();
    if let Err(error) = run(&args) {
        // One line, no backtrace: the chain of contexts says what failed and why.
        eprintln!("error: {error:#}");
        std::process::exit(1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_parse_and_bad_sizes_are_rejected_with_a_reason() {
        assert_eq!(parse_size("640x480"), Ok((640, 480)));
        assert_eq!(parse_size("1X1"), Ok((1, 1)));
        for bad in ["640", "0x10", "10x0", "axb", "9000x10", "-1x5", ""] {
            assert!(parse_size(bad).is_err(), "{bad:?} was accepted");
        }
    }

    #[test]
    fn unknown_flags_are_rejected() {
        assert!(Args::try_parse_from(["sandbox", "--bogus"]).is_err());
        assert!(Args::try_parse_from(["sandbox", "--size", "12"]).is_err());
    }
}
