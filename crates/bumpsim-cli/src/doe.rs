//! `bumpsim doe`: argument conversion and output around bumpsim-doe.

use crate::{Folder, write};
use anyhow::{Context, Result, anyhow, bail};
use bumpsim_core::units::short;
use bumpsim_doe::data::Data;
use bumpsim_doe::design::{self, DesignKind, DesignOptions};
use bumpsim_doe::model::{Factor, ModelFile};
use bumpsim_doe::reachable::{LinearMap, cell};
use bumpsim_doe::stiffness::Curve;
use bumpsim_doe::table_fit::{StandardErrors, TableFitSpec, fit_table_weighted};
use bumpsim_doe::text::{prediction_text, reach_text, stiffness_text};
use bumpsim_report::doe::{ResponsePage, fit_report};
use clap::Subcommand;
use std::path::PathBuf;

/// The `doe` subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Make a design: full, fractional, ccf, ccc, lhs or uniform.
    Design(DesignArgs),
    /// Fit responses against factors (least squares in coded units).
    Fit(FitArgs),
    /// Predict with a model file at physical factor values.
    Predict(PredictArgs),
    /// Stiffness: slope of a linearised force–displacement curve.
    Stiffness(StiffnessArgs),
    /// Stage 2: append identification results (JSON, one per run) to a design table.
    Collect(CollectArgs),
    /// The reachable region of two linear responses and the corners of a cell.
    Reach(ReachArgs),
}

/// Arguments of `doe design`.
#[derive(Debug, clap::Args)]
pub struct DesignArgs {
    /// full | fractional | ccf (face-centred composite) | ccc (circumscribed) | lhs | uniform.
    kind: String,
    /// Factors as NAME:LOW:HIGH, comma-separated.
    #[arg(long, value_delimiter = ',', required = true)]
    factors: Vec<String>,
    /// Generators of a fraction, e.g. D=AB,E=AC (factor letters are the factor names).
    #[arg(long, value_delimiter = ',')]
    generators: Vec<String>,
    /// Centre points.
    #[arg(long, default_value_t = 0)]
    centre: usize,
    /// Runs of an lhs or uniform design (default 20).
    #[arg(long, value_parser = crate::count::<1_000_000>)]
    runs: Option<usize>,
    /// Seed (lhs, uniform, randomised run order; default 1).
    #[arg(long)]
    seed: Option<u64>,
    /// Randomise the run order.
    #[arg(long)]
    randomise: bool,
    /// Output CSV.
    #[arg(short, long)]
    output: PathBuf,
}

/// Arguments of `doe fit`.
#[derive(Debug, clap::Args)]
pub struct FitArgs {
    /// Data CSV: factor and response columns (`name [unit]` headers).
    data: PathBuf,
    /// Factor columns, comma-separated.
    #[arg(long, value_delimiter = ',', required = true)]
    factors: Vec<String>,
    /// Response columns, comma-separated.
    #[arg(long, value_delimiter = ',', required = true)]
    responses: Vec<String>,
    /// Low levels (default: the data's minimum), comma-separated.
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    low: Vec<f64>,
    /// High levels (default: the data's maximum).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    high: Vec<f64>,
    /// Add two-factor interactions.
    #[arg(long)]
    interactions: bool,
    /// Add squares.
    #[arg(long)]
    squares: bool,
    /// Standard errors of responses (identified parameters), comma-separated:
    /// RESPONSE=COLUMN, or RESPONSE for the column RESPONSE.se; those
    /// responses are fitted with τ² (REML) and weights 1/(τ² + s²).
    #[arg(long, value_delimiter = ',')]
    se: Vec<String>,
    /// Write the model JSON.
    #[arg(long)]
    json: Option<PathBuf>,
    /// Write plots and an HTML report into this folder.
    #[arg(long)]
    report: Option<PathBuf>,
}

/// Arguments of `doe predict`.
#[derive(Debug, clap::Args)]
pub struct PredictArgs {
    /// Model JSON (from `doe fit`, or written by hand).
    model: PathBuf,
    /// NAME=VALUE,... in physical units.
    #[arg(long, value_delimiter = ',', required = true)]
    at: Vec<String>,
}

/// Arguments of `doe stiffness`.
#[derive(Debug, clap::Args)]
pub struct StiffnessArgs {
    /// CSV with a displacement and a force column (`name [unit]` headers).
    curve: PathBuf,
    /// Fit range D0,D1 in the file's displacement unit (default: 10–90 % of the peak force).
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    range: Option<Vec<f64>>,
}

/// Arguments of `doe collect`.
#[derive(Debug, clap::Args)]
pub struct CollectArgs {
    /// Design table (CSV, one row per run).
    design: PathBuf,
    /// Identification results in run order, comma-separated.
    #[arg(long, value_delimiter = ',', required = true)]
    results: Vec<PathBuf>,
    /// Output CSV: the design columns and m1.., c1.., k1.. (SI).
    #[arg(short, long)]
    output: PathBuf,
}

/// Arguments of `doe reach`.
#[derive(Debug, clap::Args)]
pub struct ReachArgs {
    /// Model JSON with main-effect models of both responses.
    model: PathBuf,
    /// Response on the x axis.
    #[arg(long)]
    x: String,
    /// Response on the y axis.
    #[arg(long)]
    y: String,
    /// Cell X0,X1,Y0,Y1 whose corners need factor sets.
    #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
    cell: Option<Vec<f64>>,
    /// Random factor sets to draw (the thesis: 50,000).
    #[arg(long, default_value_t = 50_000, value_parser = crate::count::<10_000_000>)]
    samples: usize,
    /// Seed of the samples.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Write the region plot (SVG) into this folder.
    #[arg(long)]
    plot: Option<PathBuf>,
}

/// Runs a `doe` subcommand.
pub fn run(command: &Command) -> Result<()> {
    match command {
        Command::Design(args) => make_design(args),
        Command::Fit(args) => run_fit(args),
        Command::Predict(args) => predict(args),
        Command::Stiffness(args) => run_stiffness(args),
        Command::Collect(args) => collect(args),
        Command::Reach(args) => reach(args),
    }
}

fn make_design(args: &DesignArgs) -> Result<()> {
    let factors = args
        .factors
        .iter()
        .map(|s| s.parse::<Factor>().map_err(|e| anyhow!("--factors {e}")))
        .collect::<Result<Vec<_>>>()?;
    let kind: DesignKind = args.kind.parse()?;
    let random = matches!(kind, DesignKind::LatinHypercube | DesignKind::Uniform);
    if args.runs.is_some() && !random {
        bail!("--runs: only an lhs or uniform design takes a number of runs");
    }
    if args.seed.is_some() && !random && !args.randomise {
        bail!("--seed: only an lhs or uniform design or a --randomise'd run order uses a seed");
    }
    let seed = args.seed.unwrap_or(1);
    let names: Vec<&str> = factors.iter().map(|f| f.name.as_str()).collect();
    let options = DesignOptions {
        generators: args.generators.clone(),
        centre: args.centre,
        runs: args.runs.unwrap_or(20),
        seed,
    };
    let (design, resolution) = design::make(kind, &names, &options).map_err(|e| match e {
        design::DesignError::Centre { .. } => {
            anyhow!(e).context(format!("--centre {}", args.centre))
        }
        e => anyhow!(e),
    })?;
    if let Some(resolution) = resolution {
        println!("resolution {resolution}");
    }
    let order = design.order(args.randomise, seed);
    design.check_levels(&factors)?;
    write(&args.output, &design.to_csv(&factors, &order))?;
    println!(
        "{} runs of {} factors",
        design.runs.len(),
        design.factors.len()
    );
    Ok(())
}

fn run_fit(args: &FitArgs) -> Result<()> {
    let path = args.data.as_path();
    let data = Data::read(path)?;
    let spec = TableFitSpec {
        factors: args.factors.clone(),
        responses: args.responses.clone(),
        low: args.low.clone(),
        high: args.high.clone(),
        interactions: args.interactions,
        squares: args.squares,
    };
    let se = args
        .se
        .iter()
        .map(|s| s.parse::<StandardErrors>().context("--se"))
        .collect::<Result<Vec<_>>>()?;
    let (model, fits) =
        fit_table_weighted(&data, &spec, &se).with_context(|| path.display().to_string())?;
    let mut responses = Vec::new();
    for f in &fits {
        let (response, unit) = (f.name.as_str(), f.unit.as_deref());
        let text = f.summary(&se);
        print!("{text}");
        responses.push(ResponsePage {
            heading: format!(
                "{response}{}",
                unit.map_or(String::new(), |u| format!(" [{u}]"))
            ),
            figures: bumpsim_report::doe::fit_plots(
                response,
                unit.unwrap_or("-"),
                &f.fit,
                &f.observed,
            )?,
            text,
        });
    }
    if let Some(path) = &args.json {
        write(path, &serde_json::to_string_pretty(&model)?)?;
    }
    if let Some(dir) = &args.report {
        let terms = [
            ("factors", args.factors.join(", ")),
            ("responses", args.responses.join(", ")),
            ("interactions", args.interactions.to_string()),
            ("squares", args.squares.to_string()),
        ];
        let inputs: Vec<(String, String)> =
            terms.into_iter().map(|(k, v)| (k.to_string(), v)).collect();
        let html = fit_report(&path.display().to_string(), &inputs, &responses);
        let folder = Folder::stage(dir)?;
        for (name, svg, _) in responses.iter().flat_map(|r| &r.figures) {
            folder.write(name, svg)?;
        }
        folder.write("index.html", &html)?;
        folder.commit()?;
    }
    Ok(())
}

fn predict(args: &PredictArgs) -> Result<()> {
    let model = ModelFile::read(&args.model)?;
    let values = args
        .at
        .iter()
        .map(|a| {
            let (name, value) = a
                .split_once('=')
                .with_context(|| format!("--at '{a}': expected NAME=VALUE"))?;
            let value: f64 = value
                .trim()
                .parse()
                .with_context(|| format!("--at '{a}': '{value}' is not a number"))?;
            Ok((name.trim().to_string(), value))
        })
        .collect::<Result<Vec<_>>>()?;
    let prediction = model
        .predict(&values)
        .with_context(|| format!("--at {}", args.at.join(",")))?;
    print!("{}", prediction_text(&prediction));
    Ok(())
}

fn run_stiffness(args: &StiffnessArgs) -> Result<()> {
    let range = match args.range.as_deref() {
        None => None,
        Some(&[d0, d1]) => Some([d0, d1]),
        Some(_) => bail!("--range: expected D0,D1 (two numbers)"),
    };
    let path = &args.curve;
    let data = Data::read(path)?;
    let curve = Curve::from_table(&data).with_context(|| path.display().to_string())?;
    let fit = curve.stiffness(range).with_context(|| match &args.range {
        Some(r) => format!(
            "{} --range {}",
            path.display(),
            r.iter().map(|d| short(*d)).collect::<Vec<_>>().join(",")
        ),
        None => format!("{} (fit range: 10–90 % of the peak force)", path.display()),
    })?;
    print!("{}", stiffness_text(&fit));
    Ok(())
}

fn reach(args: &ReachArgs) -> Result<()> {
    let model = ModelFile::read(&args.model)?;
    let cell_spec = match args.cell.as_deref() {
        None => None,
        Some(&[x0, x1, y0, y1]) => Some([x0, x1, y0, y1]),
        Some(_) => bail!("--cell: expected X0,X1,Y0,Y1 (four numbers)"),
    };
    let (x, y) = (args.x.as_str(), args.y.as_str());
    let map = LinearMap::from_model(&model, x, y)
        .with_context(|| format!("model file {}", args.model.display()))?;
    let polygon = map.boundary();
    let points = map.samples(args.samples, args.seed);
    let corners = match cell_spec {
        Some(c) => cell(&map, [c[0], c[1]], [c[2], c[3]]).context("--cell")?,
        None => Vec::new(),
    };
    let unit = |name: &str| {
        let response = model.responses.iter().find(|r| r.name == name);
        response.and_then(|r| r.unit.as_deref())
    };
    let units = [unit(x), unit(y)];
    let text = reach_text(
        [x, y],
        units,
        &polygon,
        args.samples,
        &corners,
        &model.factors,
    );
    print!("{text}");
    if let Some(dir) = &args.plot {
        let svg = bumpsim_report::doe::reach_plot([x, y], &points, &polygon, cell_spec)?;
        let folder = Folder::stage(dir)?;
        folder.write("reachable.svg", &svg)?;
        folder.commit()?;
    }
    Ok(())
}

fn collect(args: &CollectArgs) -> Result<()> {
    let design = args.design.as_path();
    let table = Data::read(design)?;
    let identified = args
        .results
        .iter()
        .map(|r| bumpsim_doe::data::read_result(r))
        .collect::<Result<Vec<_>, _>>()?;
    let joined = table
        .with_results(&identified)
        .map_err(|e| anyhow::anyhow!("{}: {e}", design.display()))?;
    let errors = args
        .results
        .iter()
        .map(|r| bumpsim_doe::data::read_standard_errors(r))
        .collect::<Result<Vec<_>, _>>()?;
    let (joined, named) = joined.with_standard_errors(&errors);
    if !named.is_empty() {
        println!(
            "standard errors of {} (columns NAME.se; doe fit --se {})",
            named.join(", "),
            named.join(",")
        );
    }
    write(&args.output, &joined.to_csv())?;
    println!(
        "{} runs × {} columns",
        joined.rows.len(),
        joined.names.len()
    );
    Ok(())
}
