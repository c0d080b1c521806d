//! `bumpsim verdict`: argument conversion and output around
//! bumpsim-verdict (issue 36): one car (a planar car file per end with its
//! `[damageability]`), a protocol set → per test and criterion the verdict
//! and margin, the assumptions, and on request the bumper target region,
//! the probability of passing and the Sobol indices over the car's
//! uncertainty (issue 39).
//! Exit 0 whether the car passes or not (the verdict is the result); 2 on
//! bad input.

use crate::{Folder, write};
use anyhow::{Context, Result};
use bumpsim_io::protocols::Market;
use bumpsim_verdict::prelude::*;
use bumpsim_verdict::pulse::AsiMethod;
use bumpsim_verdict::{probability, protocol, sensitivity, target, text};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};

/// Arguments of `bumpsim verdict`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// A planar car file with a [damageability] table; give one per end (front, rear).
    #[arg(long, value_name = "CAR.toml", required_unless_present = "list")]
    car: Vec<PathBuf>,
    /// The clearances and limits of a car file that has no [damageability]
    /// table (an identified car): a file with that table alone; one per
    /// --car, in the same order.
    #[arg(long, value_name = "LIMITS.toml")]
    damageability: Vec<PathBuf>,
    /// Protocols or tests, comma-separated: lab, part581, cmvss215, r42, rcar-bumper,
    /// rcar-structural, iihs-1990s, iihs-bumper, a test name, or all.
    #[arg(long, value_delimiter = ',', default_value = "all")]
    protocol: Vec<String>,
    /// List the protocols, their tests, sources and uncertainties, and stop.
    #[arg(long)]
    list: bool,
    /// The vehicle's target market: it sets the RCAR barrier's lower edge
    /// (north-america 455 mm, europe 405 mm; `--list` says what is checked).
    #[arg(long, default_value = "north-america", value_parser = ["north-america", "europe"])]
    market: String,
    /// Least margin each criterion must keep, a share of its limit (0.1: 10 %).
    #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
    margin: f64,
    /// Also search the region of bumper characteristics that passes every test.
    #[arg(long)]
    target: bool,
    /// Run the tests in the order listed on one car per end, each from the
    /// damage (the bumper's permanent set) the earlier ones left, as 49 CFR
    /// 581.5(a) runs the pendulum and then the barrier impacts; without it
    /// each test runs alone on an undamaged car.
    #[arg(long)]
    sequence: bool,
    /// Write the verdict (and the target region) as JSON.
    #[arg(long, value_name = "OUT.json")]
    json: Option<PathBuf>,
    /// Write an HTML report (the table with colours, top views, forces,
    /// crush, the target corridor) and its SVG figures into this folder.
    #[arg(long, value_name = "DIR")]
    report: Option<PathBuf>,
    /// The car's uncertainty: a planar identification's JSON (identify --json)
    /// or a TOML [uncertainty] table of relative standard deviations and/or a
    /// [ranges] table of uniform factors ("bumper.force" = [0.8, 1.2]); gives
    /// each criterion its probability of passing.
    #[arg(long, value_name = "FILE")]
    uncertainty: Option<PathBuf>,
    /// Draws of the car's parameters for the probability of passing.
    #[arg(
        long,
        default_value_t = 200,
        requires = "uncertainty",
        allow_negative_numbers = true
    )]
    samples: usize,
    /// Seed of the draws (and of the Sobol indices' bootstrap).
    #[arg(long, default_value_t = 1, requires = "uncertainty")]
    seed: u64,
    /// Also the Sobol first-order and total indices of each judged
    /// criterion's value over the uncertainty's parameters (taken
    /// independent), with 95 % bootstrap intervals.
    #[arg(long, requires = "uncertainty")]
    sobol: bool,
    /// How the ASI averages the accelerations: 2010 (EN 1317-1:2010, a
    /// 4-pole phaseless 13 Hz Butterworth low-pass) or 1998 (EN 1317-1:1998,
    /// 50 ms moving averages from first contact).
    #[arg(long, value_name = "YEAR", default_value = "2010", value_parser = ["2010", "1998"])]
    asi_method: String,
    /// Base samples N of the Sobol indices: the verdict runs N (d + 2)
    /// times for d parameters (16 to 8192; a power of two).
    #[arg(
        long,
        value_name = "N",
        default_value_t = sensitivity::DEFAULT_BASE,
        requires = "sobol",
        allow_negative_numbers = true
    )]
    sobol_base: usize,
}

/// Runs `bumpsim verdict`.
pub fn run(args: &Args) -> Result<()> {
    let market = Market::parse(&args.market).unwrap_or_default();
    if args.list {
        print!("{}", text::protocols_for(market));
        return Ok(());
    }
    let names: Vec<&str> = args.protocol.iter().map(String::as_str).collect();
    let tests = protocol::select_in(&names, market).context("--protocol")?;
    let limits: Vec<Option<&Path>> = match args.damageability.len() {
        0 => vec![None; args.car.len()],
        n if n == args.car.len() => args
            .damageability
            .iter()
            .map(|p| Some(p.as_path()))
            .collect(),
        n => anyhow::bail!(
            "--damageability given {n} times for {} --car: give one per --car, in the same order, or none",
            args.car.len()
        ),
    };
    let ends = args
        .car
        .iter()
        .zip(limits)
        .map(|(path, limits)| CarEnd::read(path, limits))
        .collect::<Result<Vec<_>, _>>()?;
    let mut setup = Setup::new(ends, tests, args.margin)?;
    setup.sequence = args.sequence;
    setup.asi_method = args
        .asi_method
        .parse()
        .ok()
        .and_then(AsiMethod::of_year)
        .context("--asi-method: 2010 or 1998")?;
    let mut v = verdict(&setup)?;
    let mut indices = None;
    if let Some(path) = &args.uncertainty {
        let u = Uncertainty::read(path)?;
        let settings = sensitivity::Settings::new(args.sobol_base, args.seed);
        if args.sobol {
            sensitivity::check(&setup, &u, &settings)?;
        }
        let sampling = Sampling {
            samples: args.samples,
            seed: args.seed,
        };
        probability::propagate(&setup, &mut v, &u, sampling)?;
        if args.sobol {
            indices = Some(sobol_indices(&setup, &v, &u, &settings)?);
        }
    }
    let region = match args.target {
        true => Some(target::search(&setup, &TargetOptions::default())?),
        false => None,
    };
    let mut document = serde_json::json!({ "verdict": v, "target": region });
    // only with --sobol: the document of a plain verdict stays as Python's
    if let (Some(s), Some(fields)) = (&indices, document.as_object_mut()) {
        fields.insert("sensitivity".into(), serde_json::to_value(s)?);
    }
    let json = serde_json::to_string_pretty(&document)?;
    if let Some(path) = &args.json {
        write(path, &json)?;
    }
    if let Some(dir) = &args.report {
        let (html, figures) =
            bumpsim_report::verdict::verdict_report(&v, region.as_ref(), indices.as_ref())?;
        Folder::viewed_report(dir, &html, figures, (json, args.json.as_deref()), &[])?;
    }
    print!("{}", text::table(&v));
    if let Some(r) = &region {
        print!("{}", text::region(r));
    }
    if let Some(s) = &indices {
        print!("{}", sensitivity::table(s));
    }
    Ok(())
}

/// The Sobol indices with a progress bar over the verdicts they run.
fn sobol_indices(
    setup: &Setup,
    v: &Verdict,
    u: &Uncertainty,
    settings: &sensitivity::Settings,
) -> Result<sensitivity::Sensitivity> {
    let bar = ProgressBar::new(sensitivity::evaluations(u, settings.base) as u64);
    let style = ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} verdicts ({elapsed})")
        .unwrap_or(ProgressStyle::default_bar());
    bar.set_style(style.progress_chars("=> "));
    bar.set_message("Sobol indices");
    let s = sensitivity::sensitivity(setup, v, u, settings, &|| bar.inc(1));
    bar.finish_and_clear();
    s.context("--sobol")
}
