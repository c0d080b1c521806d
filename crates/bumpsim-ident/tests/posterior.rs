//! Issue 39's posterior of an identified chain: its 90 % intervals cover
//! the truth in 85–95 % of 50 synthetic noise draws, and on a 3-mass case
//! it agrees with emcee (Foreman-Mackey et al. 2013, an independent
//! implementation of the same sampler) run on the same log density within
//! Monte Carlo error.

use bumpsim_core::model::MsdModel;
use bumpsim_estimate::sampler::LogDensity;
use bumpsim_ident::posterior::{density, posterior, sampling};
use bumpsim_ident::{LoadCase, Settings, identify};
use rand_chacha::ChaCha8Rng;
use rand_core::SeedableRng;
use rayon::prelude::*;
use std::io::{BufRead, BufReader, Write};
use std::process::{Command, Stdio};
use synthetic::gauss;

mod synthetic;

/// Two pulses on `truth` with white noise of deviation `sigma`, `n`
/// samples `step` apart.
fn cases(truth: &MsdModel, seed: u64, sigma: f64, (n, step): (usize, f64)) -> Vec<LoadCase> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    [(3e4, 0.05), (2e4, 0.08)]
        .iter()
        .enumerate()
        .map(|(i, &(peak, duration))| {
            let mut case = synthetic::pulse(truth, i, (peak, duration, 1.0), (n, step));
            case.measured
                .iter_mut()
                .for_each(|m| *m += sigma * gauss(&mut rng));
            case
        })
        .collect()
}

#[test]
fn ninety_percent_posterior_intervals_cover_the_truth_in_85_to_95_percent_of_50_draws() {
    let truth = MsdModel::new(vec![40.0, 1100.0], vec![5e3], vec![8e5]).unwrap();
    let theta = truth.parameters();
    let covered: Vec<Vec<bool>> = (0..50u64)
        .into_par_iter()
        .map(|seed| {
            let cases = cases(&truth, 100 + seed, 2e-4, (300, 2e-4));
            let settings = Settings::new(2, 4);
            let result = identify(&cases, &settings, &|| {}).unwrap();
            let mut run = sampling(&result, seed);
            run.ensemble.walkers = 16;
            run.ensemble.steps = 1500;
            run.ensemble.burn = 300;
            let post = posterior(&cases, &settings, &result, &run).unwrap();
            (0..theta.len())
                .map(|i| {
                    let [low, high] = post.ci90[i].unwrap();
                    low <= theta[i] && theta[i] <= high
                })
                .collect()
        })
        .collect();
    let per_parameter: Vec<usize> = (0..theta.len())
        .map(|i| covered.iter().filter(|c| c[i]).count())
        .collect();
    let all: usize = per_parameter.iter().sum();
    let share = all as f64 / (50 * theta.len()) as f64;
    eprintln!("covered of 50 (m1, m2, c1, k1): {per_parameter:?}; {share:.3} overall");
    assert!((0.85..=0.95).contains(&share), "{share}");
    for (i, &c) in per_parameter.iter().enumerate() {
        assert!((39..=49).contains(&c), "parameter {i}: {c} of 50");
    }
}

/// emcee runs its sampler; each batch of proposals is written to us, one
/// point per line, and the log densities read back (vectorised).
const EMCEE: &str = r#"
import sys, numpy as np, emcee
walkers, steps, burn, seed = (int(v) for v in sys.argv[1:5])
start = np.array([[float(v) for v in line.split()] for line in iter(sys.stdin.readline, "\n")])
def density(points):
    for p in points:
        sys.stdout.write(" ".join(repr(float(v)) for v in p) + "\n")
    sys.stdout.write("\n"); sys.stdout.flush()
    return np.array([float(sys.stdin.readline()) for _ in points])
sampler = emcee.EnsembleSampler(walkers, start.shape[1], density, vectorize=True,
                                moves=emcee.moves.StretchMove(a=2.0))
sampler.random_state = np.random.RandomState(seed).get_state()
sampler.run_mcmc(start, steps)
chain = sampler.get_chain(discard=burn, flat=True)
tau = emcee.autocorr.integrated_time(sampler.get_chain(discard=burn), quiet=True)
sys.stdout.write("done\n")
sys.stdout.write(" ".join(repr(float(v)) for v in chain.mean(axis=0)) + "\n")
sys.stdout.write(" ".join(repr(float(v)) for v in chain.std(axis=0)) + "\n")
for q in (5, 95):
    sys.stdout.write(" ".join(repr(float(v)) for v in np.percentile(chain, q, axis=0)) + "\n")
sys.stdout.write(" ".join(repr(float(v)) for v in tau) + "\n")
sys.stdout.flush()
"#;

/// Runs emcee on `density` from `starts`: mean, sd, 5 % and 95 %
/// quantiles and τ of each log parameter.
fn emcee<D: LogDensity>(
    density: &(dyn Fn() -> D + Sync),
    starts: &[Vec<f64>],
    (steps, burn, seed): (usize, usize, u64),
) -> Vec<Vec<f64>> {
    let mut child = Command::new("python3")
        .args(["-c", EMCEE])
        .args([starts.len(), steps, burn, seed as usize].map(|v| v.to_string()))
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .spawn()
        .unwrap();
    let mut input = child.stdin.take().unwrap();
    let mut output = BufReader::new(child.stdout.take().unwrap());
    let row = |p: &[f64]| {
        p.iter()
            .map(|v| format!("{v:e}"))
            .collect::<Vec<_>>()
            .join(" ")
    };
    for s in starts {
        writeln!(input, "{}", row(s)).unwrap();
    }
    writeln!(input).unwrap();
    let parse =
        |l: &str| -> Vec<f64> { l.split_whitespace().map(|v| v.parse().unwrap()).collect() };
    let mut batch = Vec::new();
    loop {
        let mut line = String::new();
        assert!(
            output.read_line(&mut line).unwrap() > 0,
            "emcee ended early"
        );
        match line.trim() {
            "done" => break,
            "" => {
                let answers: Vec<String> = batch
                    .par_drain(..)
                    .map_init(density, |d, p: Vec<f64>| format!("{:e}", d.log_density(&p)))
                    .collect();
                writeln!(input, "{}", answers.join("\n")).unwrap();
                input.flush().unwrap();
            }
            text => batch.push(parse(text)),
        }
    }
    let summary: Vec<Vec<f64>> = output.lines().map(|l| parse(&l.unwrap())).collect();
    assert!(child.wait().unwrap().success());
    summary
}

/// Steps of both runs, and their burn-in.
const STEPS: usize = 12_000;
const BURN: usize = 2000;

#[test]
fn a_three_mass_posterior_agrees_with_emcee_on_the_same_density() {
    if !bumpsim_peers::python_available("emcee") {
        return;
    }
    let truth = MsdModel::new(
        vec![30.0, 250.0, 1170.0],
        vec![8e3, 2.5e4],
        vec![1.5e6, 6e5],
    )
    .unwrap();
    let cases = cases(&truth, 7, 1e-4, (100, 2e-3));
    let settings = Settings::new(3, 8);
    let result = identify(&cases, &settings, &|| {}).unwrap();
    let mut run = sampling(&result, 3);
    run.ensemble.walkers = 16;
    run.ensemble.steps = STEPS;
    run.ensemble.burn = BURN;
    let post = posterior(&cases, &settings, &result, &run).unwrap();
    eprint!("{}", bumpsim_ident::posterior::lines(&post, &result));
    // emcee from the same kind of starts: our own first draws
    let optimum = density(&cases, &settings, &result).1;
    let starts: Vec<Vec<f64>> = (0..16)
        .map(|w| post.draws[w].iter().map(|v| v.ln()).collect())
        .collect();
    assert_eq!(starts[0].len(), optimum.len());
    let make = || density(&cases, &settings, &result).0;
    let reference = emcee(&make, &starts, (STEPS, BURN, 3));
    let (mean, sd, low, high, tau) = (
        &reference[0],
        &reference[1],
        &reference[2],
        &reference[3],
        &reference[4],
    );
    let d = &post.diagnostics;
    for i in 0..optimum.len() {
        let ours: Vec<f64> = post.draws.iter().map(|t| t[i].ln()).collect();
        let n = ours.len() as f64;
        let our_mean = ours.iter().sum::<f64>() / n;
        // Monte Carlo error of each mean: sd/√(effective draws), emcee's
        // from its own τ over its draws
        let ours_error = sd[i] / d.effective_draws[i].sqrt();
        let theirs_error = sd[i] / (16.0 * (STEPS - BURN) as f64 / tau[i]).sqrt();
        let error = (ours_error.powi(2) + theirs_error.powi(2)).sqrt();
        let [our_low, our_high] = post.ci90[i].unwrap().map(f64::ln);
        eprintln!(
            "{}: mean {our_mean:.5} vs emcee {:.5} (MC error {error:.1e}); 90 % {our_low:.4} .. {our_high:.4} vs {:.4} .. {:.4}; τ {:.0} vs {:.0}",
            post.names[i], mean[i], low[i], high[i], d.autocorrelation_time[i], tau[i]
        );
        assert!((our_mean - mean[i]).abs() < 4.0 * error, "mean {i}");
        // a 5 % quantile's MC error is about 2.1 sd/√ESS for a Gaussian
        assert!(
            (our_low - low[i]).abs() < 4.0 * 2.1 * error,
            "5 % quantile {i}"
        );
        assert!(
            (our_high - high[i]).abs() < 4.0 * 2.1 * error,
            "95 % quantile {i}"
        );
    }
}
