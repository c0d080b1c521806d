//! `bumpsim planar`: argument conversion and output around bumpsim-planar
//! (angled, offset, corner and pole impacts of the planar car, spec §9).

use crate::{Folder, write};
use anyhow::{Context, Result, bail};
use bumpsim_core::units::{Dimension, parse_quantity};
use bumpsim_planar::presets::{PRESETS, find};
use bumpsim_planar::{Face, PlanarCar, Settings, Side, Striker, simulate};
use std::path::PathBuf;

/// Arguments of `planar`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// The planar car (TOML; see docs/planar.md).
    #[arg(long, required_unless_present = "case")]
    car: Option<PathBuf>,
    /// A load-case preset (`--case list` lists them): RCAR, IIHS angle, pole, corner.
    #[arg(long, conflicts_with_all = ["angle", "overlap", "side", "pole", "pole_offset", "pendulum", "barrier"])]
    case: Option<String>,
    /// Face angle in degrees, counter-clockwise seen from above (plane faces).
    #[arg(long, allow_negative_numbers = true, conflicts_with = "pole")]
    angle: Option<f64>,
    /// Overlap in percent of the bumper width (plane faces; default 100).
    #[arg(long, allow_negative_numbers = true, conflicts_with = "pole")]
    overlap: Option<f64>,
    /// Side the overlap is measured from: left (+y) or right (−y).
    #[arg(long, conflicts_with = "pole")]
    side: Option<Side>,
    /// A pole of this diameter instead of a plane: m, or with a unit ("178 mm").
    #[arg(long)]
    pole: Option<String>,
    /// Lateral position of the pole's axis (y, left positive): m or with a unit.
    #[arg(long, requires = "pole", allow_hyphen_values = true)]
    pole_offset: Option<String>,
    /// A pendulum of this mass, kg, carries the face into the car at rest.
    #[arg(long, conflicts_with = "barrier", allow_negative_numbers = true)]
    pendulum: Option<f64>,
    /// The car hits the fixed face (the default without --pendulum).
    #[arg(long)]
    barrier: bool,
    /// Impact speed: m/s, or with a unit ("15 km/h"); default: the preset's.
    #[arg(long)]
    speed: Option<String>,
    /// Write the results and histories as JSON.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Write the time histories as CSV (SI).
    #[arg(long)]
    csv: Option<PathBuf>,
    /// Write SVG plots and an HTML report into this folder.
    #[arg(long)]
    report: Option<PathBuf>,
}

fn quantity(option: &str, text: &str, dimension: Dimension) -> Result<f64> {
    parse_quantity(text, dimension).with_context(|| format!("--{option} '{text}'"))
}

fn face(args: &Args) -> Result<Face> {
    if let Some(diameter) = &args.pole {
        let offset = args.pole_offset.as_deref().unwrap_or("0");
        return Ok(Face::pole_of_diameter(
            quantity("pole", diameter, Dimension::Length)?,
            quantity("pole-offset", offset, Dimension::Length)?,
        ));
    }
    Ok(Face::plane_in_degrees(
        args.angle.unwrap_or(0.0),
        args.overlap.unwrap_or(100.0),
        args.side.unwrap_or(Side::Left),
    ))
}

fn striker(args: &Args) -> Result<(Striker, String)> {
    let given = args
        .speed
        .as_deref()
        .map(|s| quantity("speed", s, Dimension::Velocity))
        .transpose()?;
    if let Some(name) = &args.case {
        let preset = find(name).with_context(|| {
            let names: Vec<&str> = PRESETS.iter().map(|p| p.name).collect();
            format!("--case '{name}': known presets: {}", names.join(", "))
        })?;
        let striker = given.map_or(preset.striker, |v| preset.striker.with_speed(v));
        return Ok((striker, format!("{} [{}]", preset.name, preset.source)));
    }
    let v = given.context("--speed is needed without --case")?;
    let face = face(args)?;
    Ok(match args.pendulum {
        Some(mass) => (Striker::pendulum(face, mass, v), "pendulum".into()),
        None => (Striker::barrier(face, v), "barrier".into()),
    })
}

fn list() {
    for p in PRESETS {
        println!("{:<22} {}  [{}]", p.name, p.description, p.source);
        println!("{:<22} uncertain: {}", "", p.uncertain);
    }
}

/// Runs `planar`.
pub fn run(args: &Args) -> Result<()> {
    if args.case.as_deref() == Some("list") {
        list();
        return Ok(());
    }
    let Some(path) = &args.car else {
        bail!("--car FILE is needed (a planar car TOML, docs/planar.md)");
    };
    let car = PlanarCar::read(path)?;
    let (striker, label) = striker(args)?;
    let result = simulate(&car, &striker, &Settings::default())?;
    result.warnings.iter().for_each(|w| crate::warn(w));
    let name = car
        .name()
        .map_or_else(|| path.display().to_string(), str::to_string);
    let summary = bumpsim_planar::text::summary(&result);
    let heading = format!(
        "{name}: {} ({label})",
        bumpsim_planar::text::striker(&striker)
    );
    println!("{heading}");
    print!("{summary}");
    if let Some(path) = &args.json {
        let json = serde_json::json!({ "car": name, "striker": striker, "result": result });
        write(path, &serde_json::to_string_pretty(&json)?)?;
    }
    if let Some(path) = &args.csv {
        write(path, &bumpsim_planar::text::histories(&result))?;
    }
    if let Some(dir) = &args.report {
        let (html, figures) = bumpsim_report::planar::planar_report(&heading, &summary, &result)?;
        Folder::report(dir, &html, &figures)?;
    }
    Ok(())
}
