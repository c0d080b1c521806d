//! `bumpsim verdict`: argument conversion around the engine's verdict
//! request (`bumpsim_engine::verdict`, issue 36): one car (a planar car file per end with its
//! `[damageability]`), a protocol set → per test and criterion the verdict
//! and margin, the assumptions, and on request the bumper target region,
//! the probability of passing and the Sobol indices over the car's
//! uncertainty (issue 39).
//! Exit 0 whether the car passes or not (the verdict is the result); 2 on
//! bad input.

use anyhow::{Context, Result};
use bumpsim_io::protocols::Market;
use bumpsim_verdict::pulse::AsiMethod;
use bumpsim_verdict::{sensitivity, text};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};

/// Arguments of `bumpsim verdict`.
#[derive(Debug, clap::Args)]
pub struct Args {
    /// A car file with a [damageability] table (a planar car, or a chain with nonlinear links); give one per end (front, rear).
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

/// Runs `bumpsim verdict`: one library request (the car files' kind picks
/// the model that judges them).
pub fn run(args: &Args) -> Result<()> {
    let market = Market::parse(&args.market).unwrap_or_default();
    if args.list {
        print!("{}", text::protocols_for(market));
        return Ok(());
    }
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
    let ends: Vec<bumpsim_engine::End> = args
        .car
        .iter()
        .zip(limits)
        .map(|(car, limits)| bumpsim_engine::End::File(car, limits))
        .collect();
    let asi_method = args
        .asi_method
        .parse()
        .ok()
        .and_then(AsiMethod::of_year)
        .context("--asi-method: 2010 or 1998")?;
    let uncertainty = args
        .uncertainty
        .as_deref()
        .map(|path| bumpsim_engine::VerdictUncertainty {
            path,
            samples: args.samples,
            seed: args.seed,
            sobol_base: args.sobol.then_some(args.sobol_base),
        });
    let bar = Bar(ProgressBar::hidden());
    let request = bumpsim_engine::VerdictRequest {
        ends: &ends,
        protocols: &args.protocol,
        market,
        margin: args.margin,
        target: args.target,
        sequence: args.sequence,
        asi_method,
        uncertainty,
        report: args.report.is_some(),
        progress: &bar,
        bumper: None,
    };
    let outcome = bumpsim_engine::verdict::verdict(&request)?;
    let files = crate::output::Written {
        json: args.json.as_deref(),
        report: args.report.as_deref(),
        ..Default::default()
    };
    crate::output::outcome(outcome, &files)
}

/// The progress bar over the verdicts the Sobol indices run (drawn only
/// when they run).
struct Bar(ProgressBar);

impl bumpsim_engine::Progress for Bar {
    fn begin(&self, verdicts: u64) {
        let style =
            ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} verdicts ({elapsed})")
                .unwrap_or(ProgressStyle::default_bar());
        self.0.set_style(style.progress_chars("=> "));
        self.0.set_message("Sobol indices");
        self.0.set_length(verdicts);
        self.0
            .set_draw_target(indicatif::ProgressDrawTarget::stderr());
    }

    fn start_finished(&self) {
        self.0.inc(1);
    }

    fn end(&self) {
        self.0.finish_and_clear();
    }
}
