//! Issue 44: do the planar identification's 95 % intervals cover the truth
//! as often as they say? The bundled series (examples/planar/identify: a
//! flat, a 600-mm offset, a pole and a 10° wall test of
//! `car-truth.toml`) is made again under `SERIES` seeds (`bumpsim synth`:
//! bumpsim's impact with contact at a coarser step, anti-alias filter,
//! 20 N load-cell and 0.05 g accelerometer noise, accelerometer biases)
//! and each is identified as the docs do (`bumpsim identify`, the study's
//! 8 starts). The intervals of the nine car parameters (body mass and yaw
//! inertia, each side's chain mass, damper and spring, μ_y) are counted.
//!
//! This is bumpsim's own generator — the model is the family it fits, so
//! the count checks the intervals' error model, not the model family (the
//! independent generator's count is bumpsim-planar's tests/planar/coverage.rs).
//! The coverage is printed and asserted within 85–99 %, with each
//! parameter's RMS of `z = ln(θ̂/θ)/SE(ln θ)` (1 for honest intervals).
//!
//! Measured (2026-11-28, AR(1) inflation): 450 of 450 intervals cover the
//! truth (100 %), RMS z 0.15–0.41: the inflation `(1 + ρ)/(1 − ρ)` was
//! 540–840 at ρ ≈ 0.997 where the scatter asked for about 15–110.
//!
//! Measured (2026-11-29, σ² τ with τ the residuals' integrated
//! autocorrelation time, the priors at their stated spreads; release build,
//! `BUMPSIM_COVERAGE_SERIES=10`, 244 s on 2 cores shared with seven
//! agents): 87 of 90 intervals cover the truth (96.7 %; missed: left spring,
//! right damper, right spring, once each); τ 72–148; RMS z 0.35 (left
//! damper), 0.39 (yaw inertia), 0.52 (left mass), 0.71 (body mass), 0.72
//! (μ_y), 0.80 (right damper), 0.99 (right mass), 1.09 (right spring), 1.10
//! (left spring). Ignored because 50 series take about 20 min in a release
//! build on a loaded machine, beyond the suite's budget: run it with
//! `--ignored` (`BUMPSIM_COVERAGE_SERIES` for fewer).

use crate::util::{bumpsim, root, scratch, text};
use serde_json::Value;
use std::path::Path;

/// Seeds. 50 as in the 1-D coverage test; each series takes one `synth`
/// and one `identify` of the release-optimised binary.
const SERIES: u64 = 50;

/// The truth of `car-truth.toml`, by the identification's names.
const TRUTH: [(&str, f64); 9] = [
    ("body.mass", 1250.0),
    ("body.yaw_inertia", 1900.0),
    ("left.masses[0]", 6.0),
    ("left.dampers[0]", 1500.0),
    ("left.springs[0]", 1.8e6),
    ("right.masses[0]", 9.0),
    ("right.dampers[0]", 2500.0),
    ("right.springs[0]", 1.2e6),
    ("tyres.mu_lateral", 0.8),
];

/// Series `seed` made and identified in `dir`: the result's JSON.
fn identified(dir: &Path, seed: u64) -> Value {
    let example = root().join("examples/planar/identify");
    let here = dir.join(format!("seed-{seed}"));
    std::fs::create_dir_all(&here).unwrap();
    for file in ["car-truth.toml", "start.toml"] {
        std::fs::copy(example.join(file), here.join(file)).unwrap();
    }
    let series = std::fs::read_to_string(example.join("series.toml")).unwrap();
    assert!(series.contains("\nseed = 7\n"), "the bundled series' seed");
    let series = series.replace("\nseed = 7\n", &format!("\nseed = {}\n", 1000 + seed));
    std::fs::write(here.join("series.toml"), series).unwrap();
    let tests = here.join("tests");
    let path = |p: &Path| p.to_str().unwrap().to_string();
    let run = bumpsim(&[
        "synth",
        &path(&here.join("series.toml")),
        "-o",
        &path(&tests),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let json = here.join("r.json");
    let run = bumpsim(&[
        "identify",
        &path(&tests.join("study.toml")),
        "--quiet",
        "--json",
        &path(&json),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    serde_json::from_str(&std::fs::read_to_string(json).unwrap()).unwrap()
}

#[test]
#[ignore = "issue 44: 50 series take ~20 min (release); measured on 10: 87 of 90 (96.7 %), RMS z 0.35-1.10"]
fn planar_intervals_cover_the_truth_of_fifty_seeded_series() {
    let dir = scratch("planar-coverage");
    let clock = std::time::Instant::now();
    let (mut inside, mut total) = (0, 0);
    let mut missed: Vec<(String, u64)> = Vec::new();
    let mut z = [0.0; TRUTH.len()];
    let series = std::env::var("BUMPSIM_COVERAGE_SERIES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(SERIES);
    for seed in 0..series {
        let r = identified(&dir, seed);
        println!(
            "seed {seed}: variance inflation {:.1}",
            r["result"]["inflation"].as_f64().unwrap_or(f64::NAN)
        );
        let parameters = r["result"]["parameters"].as_array().unwrap();
        for (i, (name, truth)) in TRUTH.into_iter().enumerate() {
            let p = parameters.iter().find(|p| p["name"] == name).unwrap();
            let (value, se) = (p["value"].as_f64().unwrap(), p["standard_error"].as_f64());
            z[i] += se
                .map_or(f64::INFINITY, |se| (value / truth).ln() / (se / value))
                .powi(2);
            let covered = p["ci95"]
                .as_array()
                .and_then(|ci| Some((ci[0].as_f64()?, ci[1].as_f64()?)))
                .is_some_and(|(lo, hi)| lo <= truth && truth <= hi);
            inside += usize::from(covered);
            total += 1;
            if !covered {
                missed.push((name.to_string(), seed));
            }
        }
    }
    let share = inside as f64 / total as f64;
    println!(
        "planar coverage of the 95 % intervals: {inside} of {total} ({:.1} %) in {:.0} s",
        100.0 * share,
        clock.elapsed().as_secs_f64()
    );
    let mut by_name: Vec<(String, usize)> = Vec::new();
    for (name, _) in &missed {
        match by_name.iter_mut().find(|(n, _)| n == name) {
            Some((_, count)) => *count += 1,
            None => by_name.push((name.clone(), 1)),
        }
    }
    println!("missed, by parameter: {by_name:?}");
    for ((name, _), z) in TRUTH.iter().zip(z) {
        println!("{name:<20} RMS z {:.3}", (z / series as f64).sqrt());
    }
    assert!(
        (0.85..=0.99).contains(&share),
        "coverage {share}: {inside} of {total}; missed {by_name:?}"
    );
}
