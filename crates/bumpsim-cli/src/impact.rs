//! `bumpsim impact` and `bumpsim mass-reduction`: argument conversion
//! around the engine's impact request (every car model) and bumpsim-impact's
//! mass reduction.

use crate::planar::speed;
use crate::{Folder, write};
use anyhow::{Context, Result, bail};
use bumpsim_core::units::{Dimension, format_number, format_quantity, short};
use bumpsim_impact::bumper::Bumper;
use bumpsim_impact::reduction::{
    Criterion, Grid, PaperSweep, ReductionError, TwoDof, equivalent_mass,
};
use bumpsim_io::kind::{ModelKind, Role};
use bumpsim_report::html::Html;
use indicatif::ProgressBar;
use std::path::PathBuf;

/// Arguments of `impact`.
#[derive(Debug, clap::Args)]
pub struct ImpactArgs {
    /// The car (TOML or identification JSON); one mass = a rigid vehicle;
    /// or a planar car (TOML with [body], docs/planar.md), which carries its bumper.
    #[arg(long, required_unless_present = "case")]
    car: Option<PathBuf>,
    /// The bumper characteristic (TOML: ramp, plateau, unloading; or curve, unloading);
    /// needed for a 1-D car.
    #[arg(long)]
    bumper: Option<PathBuf>,
    /// A load-case preset (`--case list` lists them; a planar car's are `planar --case list`).
    #[arg(long, conflicts_with_all = ["pendulum", "barrier", "angle", "overlap", "side", "pole", "pole_offset"])]
    case: Option<String>,
    #[command(flatten)]
    face: crate::planar::FaceArgs,
    /// Bumper width, m or with a unit ("1.6 m"): the 1-D car and its bumper become a
    /// symmetric planar car of this width (other layout values: docs/planar.md), for
    /// the planar faces.
    #[arg(long)]
    width: Option<String>,
    /// An impactor (pendulum) of this mass, kg, hits the car at rest.
    #[arg(long, conflicts_with = "barrier", allow_negative_numbers = true)]
    pendulum: Option<f64>,
    /// The car hits a rigid barrier.
    #[arg(long)]
    barrier: bool,
    /// Impact speed: m/s, or with a unit ("8 km/h"); default: the preset's.
    #[arg(long)]
    speed: Option<String>,
    #[command(flatten)]
    uncertain: crate::planar::UncertaintyArgs,
    #[command(flatten)]
    files: crate::output::ResultFiles,
}

impl ImpactArgs {
    /// The car file: needed for everything but `--case list`.
    fn car_path(&self) -> Result<&std::path::Path> {
        self.car
            .as_deref()
            .context("--car FILE is needed (only --case list runs without a car)")
    }
}

impl ImpactArgs {
    /// The request as the engine takes it.
    fn request(&self) -> bumpsim_engine::ImpactRequest<'_> {
        bumpsim_engine::ImpactRequest {
            car: self.car.as_deref(),
            car_text: None,
            bumper: self.bumper.as_deref(),
            case: self.case.as_deref(),
            pendulum: self.pendulum,
            barrier: self.barrier,
            speed: self.speed.as_deref(),
            face: self.face.face(),
            width: self.width.as_deref(),
            setup: bumpsim_engine::Setup::default(),
            uncertainty: self.uncertain.options(),
            report: self.files.report.is_some(),
        }
    }
}

/// Arguments of `mass-reduction`.
#[derive(Debug, clap::Args)]
pub struct ReductionArgs {
    /// Mass carrying the bumper, kg.
    #[arg(long, default_value_t = 650.0, allow_negative_numbers = true)]
    m1: f64,
    /// The other mass, kg.
    #[arg(long, default_value_t = 400.0, allow_negative_numbers = true)]
    m2: f64,
    /// Spring between them, N/m.
    #[arg(long, default_value_t = 4e6, allow_negative_numbers = true)]
    k: f64,
    /// The bumper characteristic (TOML).
    #[arg(long)]
    bumper: PathBuf,
    /// Impact speed into the rigid barrier: m/s or with a unit (default 8 km/h, paper A).
    #[arg(long, default_value = "8 km/h")]
    speed: String,
    /// remaining (paper A figs 5–6) or maximum (fig. 7) deformation.
    #[arg(long, default_value = "remaining")]
    criterion: Criterion,
    /// Also sweep: `car` (k 100..10000 kN/m × M1/(M1+M2) 0.52..0.95 at M1+M2)
    /// or `bumper` (ramp 1000..8000 kN/m × F_max 40..200 kN).
    #[arg(long)]
    sweep: Option<String>,
    /// Grid points per axis of the sweep (with --sweep).
    #[arg(long, default_value_t = 50, value_parser = crate::count::<2_000>, requires = "sweep")]
    points: usize,
    /// Write the result as JSON.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Write the sweep grid as CSV (with --sweep).
    #[arg(short, long, requires = "sweep")]
    output: Option<PathBuf>,
    /// Write SVG plots and an HTML report into this folder.
    #[arg(long)]
    report: Option<PathBuf>,
}

/// Runs `impact`: the car file's kind picks the model (bumpsim_engine's
/// registry), one library request.
pub fn run_impact(args: &ImpactArgs) -> Result<()> {
    if args.case.as_deref() == Some("list") {
        print!("{}", bumpsim_io::protocols::listing(true));
        return Ok(());
    }
    let kind = ModelKind::of_path(args.car_path()?, Role::Car)?;
    let outcome = bumpsim_engine::impact(kind, &args.request())?;
    crate::output::outcome(outcome, &args.files.written())
}

/// Runs `mass-reduction`.
pub fn run_reduction(args: &ReductionArgs) -> Result<()> {
    let bumper = Bumper::read(&args.bumper)?;
    let v0 = speed(&args.speed)?;
    let car = TwoDof {
        m1: args.m1,
        m2: args.m2,
        k: args.k,
    };
    let r = equivalent_mass(&car, &bumper, v0, args.criterion).map_err(|e| match e {
        ReductionError::Mass { key, .. } => anyhow::Error::new(e).context(format!("--{key}")),
        e => anyhow::Error::new(e).context(format!(
            "--m1 {} --m2 {} --k {} with --bumper {} at --speed '{}'",
            short(args.m1),
            short(args.m2),
            short(args.k),
            args.bumper.display(),
            args.speed
        )),
    })?;
    let text = format!(
        "2-DOF car M1 {}, M2 {}, k {} at {} into a rigid barrier ({} criterion):\n  2-DOF deformation: maximum {}, remaining {}\n  equivalent single mass M* = {}, scale factor M*/(M1+M2) = {}\n",
        format_quantity(car.m1, Dimension::Mass),
        format_quantity(car.m2, Dimension::Mass),
        format_quantity(car.k, Dimension::Stiffness),
        format_quantity(v0, Dimension::Velocity),
        if args.criterion == Criterion::Remaining {
            "remaining"
        } else {
            "maximum"
        },
        format_quantity(r.max_compression, Dimension::Length),
        format_quantity(r.remaining_compression, Dimension::Length),
        format_quantity(r.equivalent_mass, Dimension::Mass),
        format_number(r.scale_factor, 4)
    );
    print!("{text}");
    if let Some(path) = &args.json {
        write(path, &serde_json::to_string_pretty(&r)?)?;
    }
    let grid = args
        .sweep
        .as_deref()
        .map(|which| sweep(args, &bumper, &car, v0, which))
        .transpose()?;
    if let (Some(grid), Some(path)) = (&grid, &args.output) {
        write(path, &bumpsim_impact::text::grid_csv(grid))?;
    }
    if let Some(dir) = &args.report {
        let folder = Folder::stage(dir)?;
        let mut page = Html::new("bumpsim mass reduction (paper A)");
        page.heading("Result");
        page.preformatted(&text);
        if let Some(grid) = &grid {
            let svg = bumpsim_report::impact::heat_map(grid).svg()?;
            page.heading("Sweep");
            page.figure(&svg, "scale factor M*/(M1+M2) over the grid");
            folder.write("sweep.svg", &svg)?;
        }
        folder.write("index.html", &page.finish())?;
        folder.commit()?;
    }
    Ok(())
}

fn sweep(
    args: &ReductionArgs,
    bumper: &Bumper,
    car: &TwoDof,
    v0: f64,
    which: &str,
) -> Result<Grid> {
    if args.points < 2 {
        bail!("--points {}: at least 2 per axis", args.points);
    }
    let kind: PaperSweep = which.parse().map_err(|e| anyhow::anyhow!("--sweep {e}"))?;
    let bar = ProgressBar::new(args.points as u64);
    let n = args.points;
    let grid = kind.run(n, (car, bumper), v0, args.criterion, &|| bar.inc(1));
    bar.finish_and_clear();
    let found = grid.values.iter().flatten().flatten().count();
    println!("sweep {which}: {n} × {n} grid, {found} cells with an answer");
    Ok(grid)
}

/// Arguments of `synth`.
#[derive(Debug, clap::Args)]
pub struct SynthArgs {
    /// The series file (TOML: car, seed, `[chain]`, `[[head]]` with name, bumper, mass, speed;
    /// or a planar series: planar_car, seed, `[chain]`, `[[test]]`, see docs/planar.md).
    series: PathBuf,
    /// Output folder: one ISO-MME test and one CSV per head, plus `generated-by.toml`
    /// (planar: also `study.toml` and `start.toml`).
    #[arg(short, long)]
    output: PathBuf,
}

/// Runs `synth`.
pub fn run_synth(args: &SynthArgs) -> Result<()> {
    let made = bumpsim_engine::synth::make(&args.series)?;
    let (heads, provenance, extra) = (made.tests, made.provenance, made.files);
    let existing = std::fs::read_dir(&args.output).is_ok_and(|mut d| d.next().is_some());
    if existing {
        bail!(
            "-o {}: the folder exists and is not empty; choose a new folder",
            args.output.display()
        );
    }
    let folder = Folder::stage(&args.output)?;
    for (name, metadata, channels) in &heads {
        bumpsim_io::output::plain_name(name)?;
        for (relative, text) in bumpsim_io::isomme::files(name, metadata, channels) {
            folder.write(&format!("{name}/{relative}"), &text)?;
        }
        let (time, columns) = bumpsim_signal::process::align(channels)?;
        let output: Vec<bumpsim_io::table::OutputColumn> = channels
            .iter()
            .zip(&columns)
            .map(|(c, values)| bumpsim_io::table::OutputColumn {
                name: &c.code,
                unit: bumpsim_core::units::Unit::si(c.dimension),
                values,
            })
            .collect();
        let csv = folder.path().join(format!("{name}.csv"));
        bumpsim_io::table::write_table(&csv, &time, &output)?;
        crate::output::wrote(format!(
            "wrote {}",
            args.output.join(format!("{name}.csv")).display()
        ));
        for c in channels {
            if let Some(comment) = c.meta("Comments") {
                println!("{name} {}: {comment}", c.code);
            }
        }
    }
    for (name, text) in &extra {
        folder.write(name, text)?;
    }
    folder.write(
        "generated-by.toml",
        &provenance
            .lines()
            .map(|l| {
                if l.starts_with('#') {
                    l.to_string()
                } else {
                    format!("#   {l}")
                }
            })
            .collect::<Vec<_>>()
            .join("\n"),
    )?;
    folder.commit()
}
