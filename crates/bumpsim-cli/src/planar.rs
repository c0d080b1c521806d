//! `bumpsim planar`: argument conversion around the engine's planar
//! impact (angled, offset, corner and pole impacts of the planar car, spec
//! §9); the options shared with `impact` (the faces, the car's uncertainty).

use anyhow::{Context, Result, bail};
use bumpsim_core::units::{Dimension, parse_quantity};
use bumpsim_engine::{Face, ImpactRequest, Setup, Side, UncertaintyOptions};
use bumpsim_io::kind::ModelKind;
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
    #[command(flatten)]
    face: FaceArgs,
    /// A pendulum of this mass, kg, carries the face into the car at rest.
    #[arg(long, conflicts_with = "barrier", allow_negative_numbers = true)]
    pendulum: Option<f64>,
    /// The car hits the fixed face (the default without --pendulum).
    #[arg(long)]
    barrier: bool,
    /// Impact speed: m/s, or with a unit ("15 km/h"); default: the preset's.
    #[arg(long)]
    speed: Option<String>,
    #[command(flatten)]
    setup: SetupArgs,
    #[command(flatten)]
    uncertain: UncertaintyArgs,
    #[command(flatten)]
    files: crate::output::ResultFiles,
}

/// The car's uncertainty options of `impact` and `planar` (issue 39): the
/// results as distributions, and their Sobol indices.
#[derive(Debug, clap::Args)]
pub struct UncertaintyArgs {
    /// The car's uncertainty: an identification's JSON (identify --json; a 1-D
    /// car's of a chain study, a planar car's of a planar study) or a TOML
    /// [uncertainty] table of relative standard deviations and/or a [ranges]
    /// table of uniform factors, "springs[0]" = [0.8, 1.2] (docs/uncertainty.md);
    /// prints each result's median and interval, the JSON gets the force's band.
    #[arg(long, value_name = "FILE")]
    pub uncertainty: Option<PathBuf>,
    /// Draws of the car's parameters (10 to 100000).
    #[arg(
        long,
        default_value_t = bumpsim_impact::propagation::DEFAULT_SAMPLES,
        requires = "uncertainty",
        allow_negative_numbers = true
    )]
    pub samples: usize,
    /// Seed of the draws (and of the Sobol indices' bootstrap).
    #[arg(long, default_value_t = bumpsim_impact::propagation::DEFAULT_SEED, requires = "uncertainty")]
    pub seed: u64,
    /// Level of the equal-tailed intervals and bands, in (0, 1).
    #[arg(
        long,
        default_value_t = 0.9,
        requires = "uncertainty",
        allow_negative_numbers = true
    )]
    pub level: f64,
    /// Also the Sobol first-order and total indices of each result over the
    /// uncertain parameters (taken independent), with 95 % bootstrap intervals.
    #[arg(long, requires = "uncertainty")]
    pub sobol: bool,
    /// Base samples N of the Sobol indices: N (d + 2) impacts for d
    /// parameters (16 to 65536; a power of two).
    #[arg(
        long,
        value_name = "N",
        default_value_t = bumpsim_impact::propagation::DEFAULT_SOBOL_BASE,
        requires = "sobol",
        allow_negative_numbers = true
    )]
    pub sobol_base: usize,
}

/// The test set-up options of `planar`: where the striker starts and how
/// long the run lasts.
#[derive(Debug, Default, clap::Args)]
pub struct SetupArgs {
    /// Initial gap between the striker and its first touch, along x: m, or
    /// with a unit ("50 mm"); the record's time zero stays the first touch,
    /// so it starts at −gap/speed. Default 0.
    #[arg(long, allow_hyphen_values = true)]
    gap: Option<String>,
    /// Longest simulated time from the start: s, or with a unit ("300 ms");
    /// default 1 s (the run stops once the impact is over).
    #[arg(long, allow_hyphen_values = true)]
    duration: Option<String>,
    /// The tyres of both axles: rolling (free-rolling wheels, gear in
    /// neutral) or sliding (locked wheels); default: the preset's condition,
    /// else the car file's.
    #[arg(long, value_parser = ["rolling", "sliding"])]
    tyres: Option<String>,
}

impl SetupArgs {
    /// The set-up as the request takes it.
    fn setup(&self) -> Setup<'_> {
        Setup {
            gap: self.gap.as_deref(),
            duration: self.duration.as_deref(),
            tyres: self.tyres.as_deref(),
        }
    }
}

impl UncertaintyArgs {
    /// The car's uncertainty as the request takes it (`None`: not asked).
    pub fn options(&self) -> Option<UncertaintyOptions<'_>> {
        Some(UncertaintyOptions {
            path: self.uncertainty.as_deref()?,
            samples: self.samples,
            seed: self.seed,
            level: self.level,
            sobol_base: self.sobol.then_some(self.sobol_base),
        })
    }
}

/// The striker's face options of `planar` (and of `impact` with a planar car).
#[derive(Debug, Default, clap::Args)]
pub struct FaceArgs {
    /// Face angle in degrees, counter-clockwise seen from above (plane faces; planar cars).
    #[arg(long, allow_negative_numbers = true, conflicts_with = "pole")]
    angle: Option<f64>,
    /// Overlap in percent of the bumper width (plane faces; default 100; planar cars).
    #[arg(long, allow_negative_numbers = true, conflicts_with = "pole")]
    overlap: Option<f64>,
    /// Side the overlap is measured from: left (+y) or right (−y) (planar cars; with --overlap).
    #[arg(long, conflicts_with = "pole", requires = "overlap")]
    side: Option<Side>,
    /// A pole of this diameter instead of a plane: m, or with a unit ("178 mm") (planar cars).
    #[arg(long)]
    pole: Option<String>,
    /// Lateral position of the pole's axis (y, left positive): m or with a unit (planar cars).
    #[arg(long, requires = "pole", allow_hyphen_values = true)]
    pole_offset: Option<String>,
}

impl FaceArgs {
    /// The face as the request takes it.
    pub fn face(&self) -> Face<'_> {
        Face {
            angle: self.angle,
            overlap: self.overlap,
            side: self.side,
            pole: self.pole.as_deref(),
            pole_offset: self.pole_offset.as_deref(),
        }
    }
}

/// Lists the planar presets: the table's tests.
pub fn list() {
    print!("{}", bumpsim_io::protocols::listing(false));
}

/// Runs `planar`: the planar car's impact, one library request.
pub fn run(args: &Args) -> Result<()> {
    if args.case.as_deref() == Some("list") {
        list();
        return Ok(());
    }
    let Some(path) = &args.car else {
        bail!("--car FILE is needed (a planar car TOML, docs/planar.md)");
    };
    let request = ImpactRequest {
        car: Some(path),
        case: args.case.as_deref(),
        pendulum: args.pendulum,
        barrier: args.barrier,
        speed: args.speed.as_deref(),
        face: args.face.face(),
        setup: args.setup.setup(),
        uncertainty: args.uncertain.options(),
        report: args.files.report.is_some(),
        ..ImpactRequest::default()
    };
    let outcome = bumpsim_engine::impact(ModelKind::Planar, &request)?;
    crate::output::outcome(outcome, &args.files.written())
}

/// A speed option read with its unit.
pub(crate) fn speed(text: &str) -> Result<f64> {
    parse_quantity(text, Dimension::Velocity).with_context(|| format!("--speed '{text}'"))
}
