//! `bumpsim planar`: argument conversion and output around bumpsim-planar
//! (angled, offset, corner and pole impacts of the planar car, spec §9).

use crate::{Folder, write};
use anyhow::{Context, Result, bail};
use bumpsim_core::names::printable;
use bumpsim_core::units::{Dimension, parse_quantity, short};
use bumpsim_planar::car::{PlanarError, TyreLaw};
use bumpsim_planar::document::{IdentificationDocument, ImpactDocument};
use bumpsim_planar::identify::{Prediction, predict};
use bumpsim_planar::presets::{PlanarPreset, StrikerSpec};
use bumpsim_planar::study::PlanarStudy;
use bumpsim_planar::uncertainty::Planar;
use bumpsim_planar::{PlanarCar, Settings, Side, Striker, bands, simulate};
use bumpsim_report::planar::CasePage;
use indicatif::ProgressBar;
use std::path::{Path, PathBuf};

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
    /// The simulation settings these options give.
    fn settings(&self) -> Result<Settings> {
        let mut settings = Settings::default();
        if let Some(gap) = &self.gap {
            settings.gap = quantity("gap", gap, Dimension::Length)?;
        }
        if let Some(duration) = &self.duration {
            settings.duration = quantity("duration", duration, Dimension::Time)?;
        }
        Ok(settings)
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
    /// The face options given, by name.
    pub fn names(&self) -> Vec<&'static str> {
        [
            (self.angle.is_some(), "--angle"),
            (self.overlap.is_some(), "--overlap"),
            (self.side.is_some(), "--side"),
            (self.pole.is_some(), "--pole"),
            (self.pole_offset.is_some(), "--pole-offset"),
        ]
        .into_iter()
        .filter_map(|(given, name)| given.then_some(name))
        .collect()
    }

    /// Whether any face option is given.
    pub fn given(&self) -> bool {
        self.angle.is_some()
            || self.overlap.is_some()
            || self.side.is_some()
            || self.pole.is_some()
            || self.pole_offset.is_some()
    }
}

/// A planar impact as `planar` and `impact` name it.
pub struct ImpactRequest<'a> {
    /// The car file (for its name in messages).
    pub path: &'a Path,
    /// The planar car.
    pub car: PlanarCar,
    /// A planar preset.
    pub case: Option<&'a str>,
    /// The face.
    pub face: &'a FaceArgs,
    /// A pendulum mass, kg.
    pub pendulum: Option<f64>,
    /// The speed as given.
    pub speed: Option<&'a str>,
    /// The set-up (gap, duration).
    pub setup: &'a SetupArgs,
    /// The car's uncertainty.
    pub uncertain: &'a UncertaintyArgs,
    /// Result files.
    pub files: &'a crate::output::ResultFiles,
}

fn quantity(option: &str, text: &str, dimension: Dimension) -> Result<f64> {
    parse_quantity(text, dimension).with_context(|| format!("--{option} '{text}'"))
}

/// The tyre law the run uses: `--tyres`, else the preset's, else none (the car's).
fn tyre_law(request: &ImpactRequest, preset: Option<&PlanarPreset>) -> Option<(TyreLaw, String)> {
    match (request.setup.tyres.as_deref(), preset) {
        (Some("sliding"), _) => Some((TyreLaw::Sliding, "sliding (locked wheels, --tyres)".into())),
        (Some(_), _) => Some((TyreLaw::Rolling, "free rolling (--tyres)".into())),
        (None, Some(p)) => Some((bumpsim_planar::presets::tyres(p), p.tyres_why.to_string())),
        (None, None) => None,
    }
}

fn striker(request: &ImpactRequest) -> Result<(Striker, String, Option<&'static PlanarPreset>)> {
    let face = request.face;
    let length = |option, text: &Option<String>| {
        text.as_deref()
            .map(|t| quantity(option, t, Dimension::Length))
            .transpose()
    };
    let spec = StrikerSpec {
        case: request.case.map(str::to_string),
        angle: face.angle,
        overlap: face.overlap,
        side: face.side,
        pole: length("pole", &face.pole)?,
        pole_offset: length("pole-offset", &face.pole_offset)?,
        pendulum: request.pendulum,
        speed: request
            .speed
            .map(|s| quantity("speed", s, Dimension::Velocity))
            .transpose()?,
        car_mass: Some(request.car.total_mass()),
    };
    let (striker, preset) = spec.striker().context("--case or --speed")?;
    let label = match (preset, request.pendulum) {
        (Some(p), _) => format!("{} [{}]", p.name, p.source),
        (None, Some(_)) => "pendulum".into(),
        (None, None) => "barrier".into(),
    };
    Ok((striker, label, preset))
}

/// Lists the planar presets: the table's tests.
pub fn list() {
    print!("{}", bumpsim_io::protocols::listing(false));
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
    run_impact(&ImpactRequest {
        path,
        car: PlanarCar::read(path)?,
        case: args.case.as_deref(),
        face: &args.face,
        pendulum: args.pendulum,
        speed: args.speed.as_deref(),
        setup: &args.setup,
        uncertain: &args.uncertain,
        files: &args.files,
    })
}

/// Names the option behind a refused face or set-up value, with the value
/// as given (the library names the parameter in its own unit: the overlap
/// as a fraction, the angle in radians, the pole by its radius).
fn name_option(error: PlanarError, request: &ImpactRequest) -> anyhow::Error {
    let PlanarError::Parameter { name, .. } = &error else {
        return error.into();
    };
    let (face, setup) = (request.face, request.setup);
    let option = match name.as_str() {
        "overlap" => face.overlap.map(|v| {
            format!(
                "--overlap {}: the overlap, in percent of the bumper width, must lie in 0 < overlap ≤ 100",
                short(v)
            )
        }),
        "barrier angle" => face.angle.map(|v| {
            format!(
                "--angle {}: the face angle, in degrees, must lie within ±80",
                short(v)
            )
        }),
        "pole radius" => face
            .pole
            .as_ref()
            .map(|v| format!("--pole '{v}' (the pole's diameter; its radius is half of it)")),
        "pole lateral position" => face.pole_offset.as_ref().map(|v| format!("--pole-offset '{v}'")),
        "gap" => setup.gap.as_ref().map(|v| format!("--gap '{v}'")),
        "duration" | "duration / output step" => {
            setup.duration.as_ref().map(|v| format!("--duration '{v}'"))
        }
        _ => None,
    };
    match option {
        Some(option) => anyhow::Error::new(error).context(option),
        None => error.into(),
    }
}

/// Simulates a planar impact and writes its outputs.
pub fn run_impact(request: &ImpactRequest) -> Result<()> {
    let path = request.path;
    let (striker, label, preset) = striker(request)?;
    let law = tyre_law(request, preset);
    let car = &match (&law, request.setup.tyres.is_some()) {
        (Some((law, _)), true) => request.car.clone().with_tyre_law(*law),
        _ => bumpsim_planar::presets::prepared(&request.car, preset),
    };
    let settings = request.setup.settings()?;
    let uncertain = crate::planar::uncertain::Uncertain::<Planar>::read(request.uncertain, car)?;
    let result = simulate(car, &striker, &settings).map_err(|e| name_option(e, request))?;
    result.warnings.iter().for_each(|w| crate::warn(w));
    let name = car
        .name()
        .map_or_else(|| path.display().to_string(), str::to_string);
    let run = |c: &PlanarCar| simulate(c, &striker, &settings).ok();
    let predicted = uncertain.map(|u| u.run(car, &result, &run)).transpose()?;
    let summary = bumpsim_planar::text::summary(&result)
        + &predicted.as_ref().map_or(String::new(), |p| p.text.clone());
    let heading = format!(
        "{name}: {} ({label})",
        bumpsim_planar::text::striker(&striker)
    );
    println!("{}", printable(&heading));
    if let Some((_, why)) = &law {
        println!("  tyres: {why}");
    }
    print!("{summary}");
    let document = ImpactDocument {
        car: &name,
        striker: &striker,
        result: &result,
        body: Some(car.body()),
    };
    let document = crate::planar::uncertain::with(serde_json::to_value(document)?, &predicted)?;
    let json = serde_json::to_string_pretty(&document)?;
    if let Some(path) = &request.files.json {
        write(path, &json)?;
    }
    if let Some(path) = &request.files.csv {
        write(path, &bumpsim_planar::text::histories(&result))?;
    }
    if let Some(dir) = &request.files.report {
        let peak = bumpsim_planar::picture::peak_sample(&result);
        let view = bumpsim_planar::picture::top_view(car, &striker, &result, peak)?;
        let (html, mut figures) = bumpsim_report::planar::planar_report(
            &heading,
            &crate::planar::uncertain::summary(&summary, &predicted),
            &result,
            Some(&view),
        )?;
        crate::planar::uncertain::pages(&predicted, &heading, &mut figures)?;
        Folder::viewed_report(
            dir,
            &html,
            figures,
            (json, request.files.json.as_deref()),
            &[],
        )?;
    }
    Ok(())
}

/// What `identify` does with a planar study (`[model] planar = ...`).
pub struct IdentifyOptions<'a> {
    /// The study file.
    pub study: &'a Path,
    /// Starts and seed instead of the study's.
    pub starts: Option<usize>,
    /// Seed of the random starts.
    pub seed: Option<u64>,
    /// JSON result.
    pub json: Option<&'a Path>,
    /// Report folder.
    pub report: Option<&'a Path>,
    /// The identified car as a planar car file.
    pub car: Option<&'a Path>,
    /// No progress bar.
    pub quiet: bool,
}

/// `identify` on a planar study: identifies, prints the summary, predicts
/// the validation cases and writes the outputs.
pub fn run_identify(options: &IdentifyOptions) -> Result<()> {
    let mut study = PlanarStudy::read(options.study)?;
    study.notes.iter().for_each(|n| println!("note: {n}"));
    study.setup.starts = options.starts.unwrap_or(study.setup.starts);
    study.setup.seed = options.seed.unwrap_or(study.setup.seed);
    let bar = match options.quiet {
        true => ProgressBar::hidden(),
        false => ProgressBar::new(study.setup.starts as u64),
    };
    let result = study.identified(&|| bar.inc(1));
    bar.finish_and_clear();
    let result = result.context("planar identification")?;
    let fitted: Vec<Prediction> = study
        .cases
        .iter()
        .map(|c| predict(&result.car, c))
        .collect::<Result<_, _>>()?;
    let mut validation: Vec<Prediction> = study
        .validation
        .iter()
        .map(|c| predict(&result.car, c))
        .collect::<Result<_, _>>()?;
    let validation_fits: Vec<_> = validation.iter().map(|p| p.fit.clone()).collect();
    let mut forward =
        forward_predictions(&result.car, study.cases.iter().chain(&study.validation))?;
    let bands = bands::attach(
        &result,
        &study.cases,
        (&study.validation, &mut validation),
        &mut forward,
    )?;
    let summary = bumpsim_planar::text::identification_summary(&result, &validation_fits)
        + &bumpsim_planar::text::forward_lines(&forward)
        + &bands.lines();
    print!("{summary}");
    // printed in the summary's band lines
    crate::count_warnings(bands.statements().len());
    // printed in the summary, as the 1-D identification prints its own
    crate::count_warnings(
        bumpsim_planar::text::identification_warnings(&result, &validation_fits).len(),
    );
    for w in forward
        .iter()
        .flat_map(bumpsim_planar::document::forward_warnings)
    {
        crate::warn(&w);
    }
    let document = IdentificationDocument {
        result: &result,
        validation: &validation_fits,
        forward: &forward,
        notes: &study.notes,
        bands: Some(&bands),
    };
    let json = serde_json::to_string_pretty(&document)?;
    if let Some(path) = options.json {
        write(path, &json)?;
    }
    if let Some(path) = options.car {
        write(path, &result.car.to_toml())?;
    }
    if let Some(dir) = options.report {
        let inputs = std::fs::read_to_string(options.study).unwrap_or_default();
        let pages: Vec<CasePage> = fitted
            .iter()
            .map(|p| (p, false))
            .chain(validation.iter().map(|p| (p, true)))
            .map(|(prediction, validation)| CasePage {
                prediction,
                validation,
                forward: forward.iter().find(|f| f.case == prediction.fit.name),
            })
            .collect();
        let warnings: Vec<String> = forward
            .iter()
            .flat_map(bumpsim_planar::document::forward_warnings)
            .collect();
        let (html, figures) = bumpsim_report::planar::identification_report(
            (&summary, &warnings),
            &inputs,
            &study.notes,
            &pages,
        )?;
        Folder::viewed_report(dir, &html, figures, (json, options.json), &[options.study])?;
    }
    Ok(())
}

/// What `predict` does with a planar car and a planar study.
pub struct PredictOptions<'a> {
    /// The planar car file.
    pub car: &'a Path,
    /// The planar study.
    pub study: &'a Path,
    /// The cases to predict (all when empty).
    pub cases: &'a [String],
    /// SVG plots of x and yaw per case.
    pub plot: Option<&'a Path>,
    /// The fits as JSON.
    pub json: Option<&'a Path>,
}

/// `predict` with a planar car: replays the study's cases (fitted and
/// validation alike) with the car's measured forces and prints each fit of
/// x and yaw, as the chain's `predict` prints its fits.
pub fn run_predict(options: &PredictOptions) -> Result<()> {
    let car = PlanarCar::read(options.car)?;
    let study = PlanarStudy::read(options.study)?;
    study.notes.iter().for_each(|n| println!("note: {n}"));
    let predictions: Vec<Prediction> = study
        .named(options.cases)?
        .into_iter()
        .map(|c| predict(&car, c))
        .collect::<Result<_, _>>()?;
    if let Some(f) = predictions
        .iter()
        .map(|p| &p.fit)
        .find(|f| !(f.fit_x.is_finite() && f.fit_yaw.is_finite()))
    {
        bail!(
            "case '{}': the replay with {} is not finite (fit x {} %, yaw {} %): the car cannot be integrated at the study's sample interval",
            f.name,
            options.car.display(),
            f.fit_x,
            f.fit_yaw
        );
    }
    for p in &predictions {
        let f = &p.fit;
        println!(
            "{}: fit x {} %  yaw {} %  (peak yaw {} deg)",
            f.name,
            bumpsim_core::units::format_number(f.fit_x, 4),
            bumpsim_core::units::format_number(f.fit_yaw, 4),
            bumpsim_core::units::format_number(f.peak_yaw.to_degrees(), 4)
        );
    }
    let name = car
        .name()
        .map_or_else(|| options.car.display().to_string(), str::to_string);
    let fits: Vec<_> = predictions.iter().map(|p| p.fit.clone()).collect();
    let forward = forward_predictions(&car, study.named(options.cases)?.into_iter())?;
    print!("{}", bumpsim_planar::text::forward_lines(&forward));
    let document = bumpsim_planar::document::predictions(&name, &fits, &forward, &study.notes);
    document
        .predictions
        .warnings
        .iter()
        .for_each(|w| crate::warn(w));
    if let Some(path) = options.json {
        write(path, &serde_json::to_string_pretty(&document)?)?;
    }
    if let Some(dir) = options.plot {
        let folder = Folder::stage(dir)?;
        for p in &predictions {
            for (name, svg, _) in bumpsim_report::planar::case_figures(p, false)? {
                folder.write(&format!("predict-{name}"), &svg)?;
            }
        }
        folder.commit()?;
    }
    Ok(())
}

/// The forward predictions of the cases that give their striker.
fn forward_predictions<'a>(
    car: &PlanarCar,
    cases: impl Iterator<Item = &'a bumpsim_planar::identify::PlanarCase>,
) -> Result<Vec<bumpsim_planar::forward::Forward>> {
    cases
        .filter(|c| c.striker.is_some())
        .map(|c| Ok(bumpsim_planar::forward::forward(car, c)?))
        .collect()
}

/// The car's uncertainty carried through an impact (issue 39), for
/// `planar` and `impact`: the options read and checked before anything
/// runs, the prediction and Sobol indices called, their text, JSON and
/// report page.
pub(crate) mod uncertain {
    use super::UncertaintyArgs;
    use anyhow::Result;
    use bumpsim_impact::prediction::{self, HistoryBand, Outputs, Sampling};
    use bumpsim_impact::propagation::{Propagated, Propagation, PropagationError};
    use bumpsim_impact::uncertainty::{Model, UncertaintyError};
    use bumpsim_report::plot::{Band, LinePlot, Series, Style};
    use serde_json::Value;

    /// The checked options and the uncertainty they read.
    pub(crate) struct Uncertain<M: Model> {
        propagation: Propagation<M>,
    }

    /// What a prediction gave: its lines and the library's results.
    pub(crate) struct Predicted<M> {
        /// The lines printed after the summary.
        pub text: String,
        out: Propagated<M>,
    }

    /// The flag a refusal of the propagation names.
    fn flag(error: &PropagationError) -> String {
        match error {
            PropagationError::Sampling(UncertaintyError::Value { key, .. }) => format!("--{key}"),
            PropagationError::Sampling(_) => "--samples".into(),
            PropagationError::Sobol(_) => "--sobol, --sobol-base".into(),
            _ => "--uncertainty".into(),
        }
    }

    impl<M: Model> Uncertain<M> {
        /// The options of `args` checked against `car` (`None`: no --uncertainty).
        pub(crate) fn read(args: &UncertaintyArgs, car: &M::Car) -> Result<Option<Self>> {
            let Some(path) = &args.uncertainty else {
                return Ok(None);
            };
            let sampling = Sampling {
                samples: args.samples,
                seed: args.seed,
                level: args.level,
            };
            let base = args.sobol.then_some(args.sobol_base);
            let propagation = Propagation::read(path, sampling, base, car).map_err(|e| {
                let flag = flag(&e);
                anyhow::Error::new(e).context(flag)
            })?;
            Ok(Some(Uncertain { propagation }))
        }

        /// The prediction of `run` over the uncertainty (and the Sobol
        /// indices when asked); `nominal` is `run`'s result for `car`.
        pub(crate) fn run<R: Outputs>(
            &self,
            car: &M::Car,
            nominal: &R,
            run: &(dyn Fn(&M::Car) -> Option<R> + Sync),
        ) -> Result<Predicted<M>> {
            let out = self.propagation.run(car, nominal, run)?;
            let text = out.lines();
            Ok(Predicted { text, out })
        }
    }

    /// `document` with the prediction and the Sobol indices beside its results.
    pub(crate) fn with<M: Model>(
        mut document: Value,
        predicted: &Option<Predicted<M>>,
    ) -> Result<Value> {
        if let Some(p) = predicted {
            p.out.insert_into(&mut document)?;
        }
        Ok(document)
    }

    /// The report's summary: the results, then their distributions and
    /// where the bands are (the uncertainty page was not reachable from the
    /// report's index).
    pub(crate) fn summary<M>(summary: &str, predicted: &Option<Predicted<M>>) -> String {
        match predicted {
            Some(p) => format!(
                "{summary}\n{}\nBands of the histories over the draws: uncertainty.html in this folder.\n",
                p.text
            ),
            None => summary.to_string(),
        }
    }

    /// Adds the report's uncertainty page (`uncertainty.html`: the lines and
    /// each history's band around the nominal curve) and its figures.
    pub(crate) fn pages<M>(
        predicted: &Option<Predicted<M>>,
        title: &str,
        figures: &mut Vec<(String, String)>,
    ) -> Result<()> {
        let Some(p) = predicted else {
            return Ok(());
        };
        let mut page =
            bumpsim_report::html::Html::new(&format!("{title}: over the car's uncertainty"));
        page.heading("Results as distributions");
        page.preformatted(&p.text);
        for b in &p.out.prediction.bands {
            let svg = band_plot(b).svg()?;
            let caption = format!(
                "{}: nominal (solid) and the {} band over the draws (shaded, pointwise)",
                b.name,
                prediction::percent(b.band.level)
            );
            page.figure(&svg, &caption);
            figures.push((format!("{}-band.svg", b.name.replace(' ', "-")), svg));
        }
        figures.push(("uncertainty.html".into(), page.finish()));
        Ok(())
    }

    /// A history's nominal curve over its shaded band.
    fn band_plot(b: &HistoryBand) -> LinePlot {
        let time = bumpsim_core::units::Dimension::Time;
        let mut plot = LinePlot::new(&format!("{} band", b.name), time, b.dimension);
        let tail = prediction::percent((1.0 - b.band.level) / 2.0);
        let head = prediction::percent((1.0 + b.band.level) / 2.0);
        let nominal = Series::new("nominal", b.time.clone(), b.nominal.clone(), Style::Solid);
        plot.add(nominal).band(Band {
            name: format!("{tail} to {head}"),
            x: b.time.clone(),
            low: b.band.low.clone(),
            high: b.band.high.clone(),
        });
        plot
    }
}
