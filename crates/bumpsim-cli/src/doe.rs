//! `bumpsim doe`: argument conversion and output around bumpsim-doe.

use crate::write;
use anyhow::{Context, Result, bail};
use bumpsim_core::units::{Dimension, Unit, format_number, format_quantity};
use bumpsim_doe::data::Data;
use bumpsim_doe::design::{self, Design};
use bumpsim_doe::model::{Factor, ModelFile, Response};
use bumpsim_doe::reachable::{LinearMap, cell};
use bumpsim_doe::regression::{fit, terms};
use bumpsim_doe::stiffness::stiffness;
use bumpsim_report::html::Html;
use bumpsim_report::plot::{LinePlot, Series, Style};
use clap::Subcommand;
use std::path::{Path, PathBuf};

/// The `doe` subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Make a design: full, fractional, ccf, ccc, lhs or uniform.
    Design {
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
        /// Runs of an lhs or uniform design.
        #[arg(long, default_value_t = 20)]
        runs: usize,
        /// Seed (lhs, uniform, randomised run order).
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Randomise the run order.
        #[arg(long)]
        randomise: bool,
        /// Output CSV.
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Fit responses against factors (least squares in coded units).
    Fit {
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
        /// Write the model JSON.
        #[arg(long)]
        json: Option<PathBuf>,
        /// Write plots and an HTML report into this folder.
        #[arg(long)]
        report: Option<PathBuf>,
    },
    /// Predict with a model file at physical factor values.
    Predict {
        /// Model JSON (from `doe fit`, or written by hand).
        model: PathBuf,
        /// NAME=VALUE,... in physical units.
        #[arg(long, value_delimiter = ',', required = true)]
        at: Vec<String>,
    },
    /// Stiffness: slope of a linearised force–displacement curve.
    Stiffness {
        /// CSV with a displacement and a force column (`name [unit]` headers).
        curve: PathBuf,
        /// Fit range D0,D1 in the file's displacement unit (default: 10–90 % of the peak force).
        #[arg(long, value_delimiter = ',', allow_negative_numbers = true)]
        range: Option<Vec<f64>>,
    },
    /// Stage 2: append identification results (JSON, one per run) to a design table.
    Collect {
        /// Design table (CSV, one row per run).
        design: PathBuf,
        /// Identification results in run order, comma-separated.
        #[arg(long, value_delimiter = ',', required = true)]
        results: Vec<PathBuf>,
        /// Output CSV: the design columns and m1.., c1.., k1.. (SI).
        #[arg(short, long)]
        output: PathBuf,
    },
    /// The reachable region of two linear responses and the corners of a cell.
    Reach {
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
        #[arg(long, default_value_t = 50_000)]
        samples: usize,
        /// Seed of the samples.
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Write the region plot (SVG) into this folder.
        #[arg(long)]
        plot: Option<PathBuf>,
    },
}

/// Runs a `doe` subcommand.
pub fn run(command: &Command) -> Result<()> {
    match command {
        Command::Design {
            kind,
            factors,
            generators,
            centre,
            runs,
            seed,
            randomise,
            output,
        } => make_design(
            kind, factors, generators, *centre, *runs, *seed, *randomise, output,
        ),
        Command::Fit {
            data,
            factors,
            responses,
            low,
            high,
            interactions,
            squares,
            json,
            report,
        } => {
            let options = FitOptions {
                low,
                high,
                interactions: *interactions,
                squares: *squares,
            };
            run_fit(
                data,
                factors,
                responses,
                &options,
                json.as_deref(),
                report.as_deref(),
            )
        }
        Command::Predict { model, at } => predict(model, at),
        Command::Stiffness { curve, range } => run_stiffness(curve, range.as_deref()),
        Command::Collect {
            design,
            results,
            output,
        } => collect(design, results, output),
        Command::Reach {
            model,
            x,
            y,
            cell,
            samples,
            seed,
            plot,
        } => reach(
            model,
            x,
            y,
            cell.as_deref(),
            *samples,
            *seed,
            plot.as_deref(),
        ),
    }
}

fn parse_factors(specs: &[String]) -> Result<Vec<Factor>> {
    specs
        .iter()
        .map(|s| {
            let parts: Vec<&str> = s.split(':').collect();
            let bad = || format!("--factors '{s}': expected NAME:LOW:HIGH with LOW < HIGH");
            let [name, low, high] = parts[..] else {
                bail!(bad())
            };
            let (low, high): (f64, f64) = (
                low.parse().with_context(bad)?,
                high.parse().with_context(bad)?,
            );
            if low.partial_cmp(&high) != Some(std::cmp::Ordering::Less) {
                bail!(bad());
            }
            Ok(Factor {
                name: name.to_string(),
                low,
                high,
                unit: None,
            })
        })
        .collect()
}

#[allow(clippy::too_many_arguments)]
fn make_design(
    kind: &str,
    specs: &[String],
    generators: &[String],
    centre: usize,
    runs: usize,
    seed: u64,
    randomise: bool,
    output: &Path,
) -> Result<()> {
    let factors = parse_factors(specs)?;
    let names: Vec<&str> = factors.iter().map(|f| f.name.as_str()).collect();
    let design: Design = match kind {
        "full" => design::full_factorial(&names, centre)?,
        "fractional" => {
            let mut columns: Vec<String> = names
                .iter()
                .filter(|n| !generators.iter().any(|g| g.starts_with(&format!("{n}="))))
                .map(|n| n.to_string())
                .collect();
            columns.extend(generators.iter().cloned());
            let refs: Vec<&str> = columns.iter().map(String::as_str).collect();
            let d = design::fractional_factorial(&refs)?;
            let g: Vec<&str> = generators.iter().map(String::as_str).collect();
            println!("resolution {}", design::resolution(&g)?);
            d
        }
        "ccf" | "ccc" => design::central_composite(&names, centre, kind == "ccf")?,
        "lhs" => design::latin_hypercube(&names, runs, seed),
        "uniform" => design::uniform(&names, runs, seed),
        other => bail!("design '{other}': expected full, fractional, ccf, ccc, lhs or uniform"),
    };
    let order = if randomise {
        design::run_order(design.runs.len(), seed)
    } else {
        (0..design.runs.len()).collect()
    };
    let by_name = |n: &String| factors.iter().find(|f| &f.name == n);
    let mut csv = String::from("run,standard order");
    design.factors.iter().for_each(|f| csv += &format!(",{f}"));
    design
        .factors
        .iter()
        .for_each(|f| csv += &format!(",{f} (coded)"));
    csv.push('\n');
    for (run, &i) in order.iter().enumerate() {
        let row = &design.runs[i];
        csv += &format!("{},{}", run + 1, i + 1);
        for (f, z) in design.factors.iter().zip(row) {
            csv += &format!(",{}", by_name(f).map_or(*z, |f| f.physical(*z)));
        }
        row.iter().for_each(|z| csv += &format!(",{z}"));
        csv.push('\n');
    }
    write(output, &csv)?;
    println!(
        "{} runs of {} factors",
        design.runs.len(),
        design.factors.len()
    );
    Ok(())
}

struct FitOptions<'a> {
    low: &'a [f64],
    high: &'a [f64],
    interactions: bool,
    squares: bool,
}

fn column(data: &Data, name: &str, path: &Path) -> Result<Vec<f64>> {
    data.column(name).with_context(|| {
        format!(
            "{}: no column '{name}'; columns: {}",
            path.display(),
            data.names.join(", ")
        )
    })
}

fn run_fit(
    path: &Path,
    factor_names: &[String],
    responses: &[String],
    options: &FitOptions,
    json: Option<&Path>,
    report: Option<&Path>,
) -> Result<()> {
    let data = Data::read(path)?;
    let columns = factor_names
        .iter()
        .map(|f| column(&data, f, path))
        .collect::<Result<Vec<_>>>()?;
    let factors: Vec<Factor> = factor_names
        .iter()
        .zip(&columns)
        .enumerate()
        .map(|(i, (name, values))| {
            let low = options
                .low
                .get(i)
                .copied()
                .unwrap_or_else(|| values.iter().copied().fold(f64::INFINITY, f64::min));
            let high = options
                .high
                .get(i)
                .copied()
                .unwrap_or_else(|| values.iter().copied().fold(f64::NEG_INFINITY, f64::max));
            let unit = data.units[data.names.iter().position(|n| n == name).unwrap_or(0)].clone();
            Factor {
                name: name.clone(),
                low,
                high,
                unit,
            }
        })
        .collect();
    if let Some(f) = factors
        .iter()
        .find(|f| f.low.partial_cmp(&f.high) != Some(std::cmp::Ordering::Less))
    {
        bail!(
            "factor '{}': low {} must be below high {} (a factor that does not vary cannot be fitted)",
            f.name,
            f.low,
            f.high
        );
    }
    let coded: Vec<Vec<f64>> = (0..data.rows.len())
        .map(|r| {
            factors
                .iter()
                .zip(&columns)
                .map(|(f, c)| f.coded(c[r]))
                .collect()
        })
        .collect();
    let names: Vec<String> = factors.iter().map(|f| f.name.clone()).collect();
    let model_terms = terms(factors.len(), options.interactions, options.squares);
    let mut model = ModelFile {
        factors: factors.clone(),
        responses: Vec::new(),
    };
    let mut page = Html::new(&format!("bumpsim DOE fit: {}", path.display()));
    let mut figures = Vec::new();
    for response in responses {
        let y = column(&data, response, path)?;
        let unit = data.units[data.names.iter().position(|n| n == response).unwrap_or(0)].clone();
        let f = fit(&coded, &y, &model_terms, &names)
            .with_context(|| format!("response '{response}'"))?;
        let text = bumpsim_doe::text::fit_text(response, unit.as_deref(), &f);
        print!("{text}");
        page.heading(&format!(
            "{response}{}",
            unit.as_deref().map_or(String::new(), |u| format!(" [{u}]"))
        ));
        page.preformatted(&text);
        figures.extend(bumpsim_report::doe::fit_plots(
            response,
            unit.as_deref().unwrap_or("-"),
            &f,
            &y,
        )?);
        model.responses.push(Response::from_fit(response, unit, &f));
    }
    if let Some(path) = json {
        write(path, &serde_json::to_string_pretty(&model)?)?;
    }
    if let Some(dir) = report {
        for (name, svg, caption) in &figures {
            page.figure(svg, caption);
            write(&dir.join(name), svg)?;
        }
        write(&dir.join("index.html"), &page.finish())?;
    }
    Ok(())
}

fn predict(path: &Path, at: &[String]) -> Result<()> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let model: ModelFile = serde_json::from_str(&text)
        .with_context(|| format!("{}: not a DOE model file", path.display()))?;
    let values = at
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
    let p = model.predict(&values)?;
    for w in &p.warnings {
        println!("warning: {w}");
    }
    for v in &p.values {
        let u = v.unit.clone().unwrap_or_default();
        let interval = |i: Option<[f64; 2]>, what: &str| {
            i.map_or(String::new(), |[a, b]| {
                format!(
                    "; {what} {} .. {}",
                    format_number(a, 4),
                    format_number(b, 4)
                )
            })
        };
        println!(
            "{} = {} {u}{}{}",
            v.name,
            format_number(v.value, 4),
            interval(v.ci95, "95 % CI"),
            interval(v.pi95, "95 % PI")
        );
    }
    Ok(())
}

fn run_stiffness(path: &Path, range: Option<&[f64]>) -> Result<()> {
    if range.is_some_and(|r| r.len() != 2) {
        bail!("--range: expected D0,D1 (two numbers)");
    }
    let data = Data::read(path)?;
    if data.names.len() < 2 {
        bail!(
            "{}: expected a displacement and a force column",
            path.display()
        );
    }
    let unit_of = |i: usize, dim: Dimension| -> Result<Unit> {
        let text = data.units[i].clone().with_context(|| {
            format!(
                "{}: column '{}' needs a unit, e.g. '{} [mm]'",
                path.display(),
                data.names[i],
                data.names[i]
            )
        })?;
        let unit = Unit::parse(&text)
            .with_context(|| format!("{}: column '{}'", path.display(), data.names[i]))?;
        if unit.dimension != dim {
            bail!(
                "{}: column '{}' is in {text}, expected a {}",
                path.display(),
                data.names[i],
                dim.name()
            );
        }
        Ok(unit)
    };
    let (ud, uf) = (
        unit_of(0, Dimension::Length)?,
        unit_of(1, Dimension::Force)?,
    );
    let d: Vec<f64> = data.rows.iter().map(|r| ud.to_si(r[0])).collect();
    let f: Vec<f64> = data.rows.iter().map(|r| uf.to_si(r[1])).collect();
    let s = stiffness(&d, &f, range.map(|r| [ud.to_si(r[0]), ud.to_si(r[1])]))?;
    println!(
        "stiffness {} (line through {} points, {} .. {}; intercept {}; residual RMS {}; R² {})",
        format_quantity(s.slope, Dimension::Stiffness),
        s.points,
        format_quantity(s.range[0], Dimension::Length),
        format_quantity(s.range[1], Dimension::Length),
        format_quantity(s.intercept, Dimension::Force),
        format_quantity(s.residual_rms, Dimension::Force),
        format_number(s.r2, 5)
    );
    Ok(())
}

fn reach(
    path: &Path,
    x: &str,
    y: &str,
    cell_spec: Option<&[f64]>,
    samples: usize,
    seed: u64,
    plot: Option<&Path>,
) -> Result<()> {
    let text =
        std::fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let model: ModelFile = serde_json::from_str(&text)
        .with_context(|| format!("{}: not a DOE model file", path.display()))?;
    if cell_spec.is_some_and(|c| c.len() != 4) {
        bail!("--cell: expected X0,X1,Y0,Y1 (four numbers)");
    }
    let map = LinearMap::from_model(&model, x, y)?;
    let polygon = map.boundary();
    let points = map.samples(samples, seed);
    println!(
        "reachable region of ({x}, {y}): {} vertices; {samples} random factor sets",
        polygon.len()
    );
    for v in &polygon {
        println!(
            "  vertex {} {}",
            format_number(v[0], 6),
            format_number(v[1], 6)
        );
    }
    let corners = cell_spec.map(|c| cell(&map, [c[0], c[1]], [c[2], c[3]]));
    for c in corners.iter().flatten() {
        let factors: Vec<String> = c
            .factors
            .iter()
            .zip(&model.factors)
            .map(|(t, f)| format!("{}={}", f.name, format_number(*t, 4)))
            .collect();
        match c.reachable {
            true => println!(
                "corner ({}, {}): reachable with coded {} (residual {})",
                c.target[0],
                c.target[1],
                factors.join(", "),
                format_number(c.residual, 3)
            ),
            false => println!(
                "corner ({}, {}): UNREACHABLE; closest coded {} misses by {}",
                c.target[0],
                c.target[1],
                factors.join(", "),
                format_number(c.residual, 4)
            ),
        }
    }
    if let Some(dir) = plot {
        let mut p = LinePlot::new(
            "Reachable region",
            Dimension::Dimensionless,
            Dimension::Dimensionless,
        )
        .with_labels(Some(x), Some(y));
        let shown = points.iter().step_by((points.len() / 2000).max(1));
        let (sx, sy): (Vec<f64>, Vec<f64>) = shown.map(|p| (p[0], p[1])).unzip();
        p.add(Series::new("random factor sets", sx, sy, Style::Points));
        let mut closed = polygon.clone();
        closed.push(polygon[0]);
        p.add(Series::new(
            "exact boundary",
            closed.iter().map(|v| v[0]).collect(),
            closed.iter().map(|v| v[1]).collect(),
            Style::Solid,
        ));
        if let Some(c) = cell_spec {
            p.add(Series::new(
                "cell",
                vec![c[0], c[1], c[1], c[0], c[0]],
                vec![c[2], c[2], c[3], c[3], c[2]],
                Style::Dashed,
            ));
        }
        write(&dir.join("reachable.svg"), &p.svg()?)?;
    }
    Ok(())
}

fn collect(design: &Path, results: &[PathBuf], output: &Path) -> Result<()> {
    let table = Data::read(design)?;
    let identified = results
        .iter()
        .map(|r| bumpsim_doe::data::Identified::read(r))
        .collect::<Result<Vec<_>, _>>()?;
    let joined = table
        .with_results(&identified)
        .map_err(|e| anyhow::anyhow!("{}: {e}", design.display()))?;
    write(output, &joined.to_csv())?;
    println!(
        "{} runs × {} columns",
        joined.rows.len(),
        joined.names.len()
    );
    Ok(())
}
