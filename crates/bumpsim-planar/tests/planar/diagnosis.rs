//! Issue 44: why a run started at a varied car's truth leaves it
//! (tests/planar/truth_start.rs, `runs_from_the_varied_truths_stay_near_them`,
//! whose doc has the figures). A measurement, not a check: for each series
//! of `BUMPSIM_SEEDS` (default `1`), one run from the yielding truth with the
//! generator's tyre law (as that test), then where the objective gains
//! between the truth and the run's end (per training case, per sensor and
//! per quarter of its window; the priors' share), how much of each sensor's
//! misfit a constant bias of its reading explains, which parameters move and
//! which pairs trade (the run's correlations), and which parameter change
//! costs the forward offset force, the off-centre face's yaw and the
//! objective (each parameter swapped back to the truth alone, and the truth
//! with each one of the run's alone). Switches: `BUMPSIM_GENERATOR_BUMPER=1`
//! puts the truth's bumper on the generator's 31 contact points,
//! `BUMPSIM_TRUTH_SIGMA=0` gives it the generator's instantaneous tyre law.
//! (With the cells' line of action on the bumper line instead of the
//! segment centres, tried and reverted, truth_start.rs has the figures.)
//! `cargo test --release -p bumpsim-planar --test planar
//! diagnosis::measured -- --ignored --nocapture`.

use bumpsim_planar::PlanarCar;
use bumpsim_planar::drive::{drive_substeps, substeps};
use bumpsim_planar::forward::forward;
use bumpsim_planar::identify::{PlanarCase, Unknowns, identify, predict, priors};

/// Per quarter of the window, each sensor's Σ w² (ŝ − s)² of `car` on `case`
/// with the identification's replay step (the template's at 0.25).
fn quarters(car: &PlanarCar, template: &PlanarCar, case: &PlanarCase) -> Vec<[f64; 4]> {
    let n = substeps(template, case.drive.step, 0.25).unwrap();
    let replay = drive_substeps(car, &case.drive, n).unwrap();
    let (a, b) = case.window;
    let len = b - a + 1;
    (0..case.measured.len())
        .map(|s| {
            let mut q = [0.0; 4];
            for k in a..=b {
                let r = case.weight(s) * (replay.sensor_reading[s][k] - case.measured[s][k]);
                q[(4 * (k - a) / len).min(3)] += r * r;
            }
            q
        })
        .collect()
}

/// `car` with its bumper on the generator's 31 points: 31 segments of the
/// same characteristic over 1.653 m (their centres on the points).
pub(super) fn generator_bumper(car: &PlanarCar) -> PlanarCar {
    let mut beam = car.beam().clone();
    beam.width = 1.6 * 31.0 / 30.0;
    beam.segments = vec![beam.segments[0].clone(); 31];
    PlanarCar::new(
        *car.body(),
        car.left().clone(),
        car.right().clone(),
        beam,
        *car.tyres(),
    )
    .unwrap()
}

/// Per sensor of `case`: the constant bias `b` of its reading (an
/// accelerometer's, m/s², seen as `b t²/2` in its displacement; a yaw-rate
/// sensor's, rad/s) that best explains the residual of `car`, and the share
/// of the sensor's Σ w² (ŝ − s)² it explains.
fn biases(car: &PlanarCar, template: &PlanarCar, case: &PlanarCase) -> Vec<(f64, f64)> {
    let n = substeps(template, case.drive.step, 0.25).unwrap();
    let replay = drive_substeps(car, &case.drive, n).unwrap();
    let (a, b) = case.window;
    (0..case.measured.len())
        .map(|s| {
            let twice = case.drive.sensors[s].integrations() == 2;
            let (mut rg, mut gg, mut rr) = (0.0, 0.0, 0.0);
            for k in a..=b {
                let t = k as f64 * case.drive.step;
                let g = if twice { 0.5 * t * t } else { 1.0 };
                // measured − model: the bias the measurement carries
                let r = case.measured[s][k] - replay.sensor_reading[s][k];
                rg += r * g;
                gg += g * g;
                rr += r * r;
            }
            (rg / gg, rg * rg / gg / rr)
        })
        .collect()
}

fn e4(q: &[f64; 4]) -> String {
    q.iter()
        .map(|v| format!("{v:.2e}"))
        .collect::<Vec<_>>()
        .join(" ")
}

fn sensor_name(case: &PlanarCase, s: usize) -> String {
    let text = format!("{:?}", case.drive.sensors[s]);
    text.chars().take(24).collect()
}

#[test]
#[ignore = "a measurement: one run from the truth per seed, about 5 s each in release"]
fn measured() {
    let seeds = std::env::var("BUMPSIM_SEEDS").unwrap_or_else(|_| "1".into());
    for seed in seeds.split(',').map(|s| s.trim().parse::<u64>().unwrap()) {
        let Some(dir) = super::defaults::series(seed) else {
            return;
        };
        // `BUMPSIM_TRUTH_SIGMA` (m, default the search's floor): the
        // truth's relaxation length; 0 gives the generator's own law
        // (instantaneous, `μN tanh(C_α α/μN)`), not estimated
        let sigma: f64 = std::env::var("BUMPSIM_TRUTH_SIGMA")
            .map(|s| s.parse().unwrap())
            .unwrap_or(bumpsim_planar::identify::RELAXATION.0);
        let (_, study, truth, mut setup) = super::truth_start::from_the_yielding_truth(&dir, sigma);
        // `BUMPSIM_GENERATOR_BUMPER=1`: the bumper on the generator's 31
        // contact points (1.653 m wide) instead of the study's 32 segments
        let truth = match std::env::var("BUMPSIM_GENERATOR_BUMPER").is_ok() {
            true => generator_bumper(&truth),
            false => truth,
        };
        setup.template = truth.clone();
        setup.relaxation = sigma > 0.0;
        let run = identify(&study.cases, &setup, &|| {}).unwrap();
        let unknowns = Unknowns::new(&truth, setup.friction, setup.cornering, &study.cases)
            .with_relaxation(setup.relaxation);
        let names = unknowns.names();
        let t0 = unknowns.start();
        let t1: Vec<f64> = run.parameters.iter().map(|p| p.value).collect();
        assert_eq!(t0.len(), t1.len());
        eprintln!(
            "== seed {seed}: objective (data) at the run's end {:.4e} m²",
            run.objective
        );
        // where the objective gains: per case, sensor, quarter
        let (mut total0, mut total1) = (0.0, 0.0);
        for case in &study.cases {
            let (q0, q1) = (
                quarters(&truth, &truth, case),
                quarters(&run.car, &truth, case),
            );
            let w = case.window;
            let t = |k: usize| k as f64 * case.drive.step * 1e3;
            eprintln!(
                "seed {seed} {}: window {:.1}..{:.1} ms (quarters of {:.1} ms)",
                case.name,
                t(w.0),
                t(w.1),
                0.25 * t(w.1 - w.0 + 1)
            );
            let (b0, b1) = (biases(&truth, &truth, case), biases(&run.car, &truth, case));
            for s in 0..q0.len() {
                eprintln!(
                    "seed {seed}   {:<24} a constant bias explains {:.1} % of the truth's misfit ({:+.4} SI), {:.1} % of the run's ({:+.4} SI)",
                    sensor_name(case, s),
                    100.0 * b0[s].1,
                    b0[s].0,
                    100.0 * b1[s].1,
                    b1[s].0
                );
                let (a, b): (f64, f64) = (q0[s].iter().sum(), q1[s].iter().sum());
                total0 += a;
                total1 += b;
                eprintln!(
                    "seed {seed}   {:<24} truth {:.3e} run {:.3e} (run − truth {:+.3e}); by quarter truth {} run {}",
                    sensor_name(case, s),
                    a,
                    b,
                    b - a,
                    e4(&q0[s]),
                    e4(&q1[s])
                );
            }
        }
        let stated = priors(&unknowns, &setup).unwrap();
        let moved0 = bumpsim_estimate::prior::moved(&stated, &unknowns.search(&t0));
        let moved1 = bumpsim_estimate::prior::moved(&stated, &unknowns.search(&t1));
        let noise2 = run.prior_noise * run.prior_noise;
        let (mut p0, mut p1) = (0.0, 0.0);
        for (a, b) in moved0.iter().zip(&moved1) {
            p0 += noise2 * a.z * a.z;
            p1 += noise2 * b.z * b.z;
            eprintln!(
                "seed {seed} prior {:<28} centre {:.4e} spread {:.3}: truth z {:+.2}, run z {:+.2}",
                a.name, a.centre, a.spread, a.z, b.z
            );
        }
        eprintln!(
            "seed {seed} objective: data truth {total0:.4e} run {total1:.4e}; priors (noise {:.3e}) truth {p0:.4e} run {p1:.4e}; total truth {:.4e} run {:.4e}",
            run.prior_noise,
            total0 + p0,
            total1 + p1
        );
        // which parameters move, which pairs trade
        for (i, (n, u)) in names.iter().enumerate() {
            eprintln!(
                "seed {seed} {:<28} truth {:>11.4e} run {:>11.4e} {:<6} {:+7.1} %  se/value {:?}",
                n,
                t0[i],
                t1[i],
                u,
                100.0 * (t1[i] / t0[i] - 1.0),
                run.uncertainty.standard_errors[i].map(|v| (v / t1[i] * 1e3).round() / 1e3)
            );
        }
        let rho = &run.uncertainty.correlation;
        for i in 0..names.len() {
            for j in i + 1..names.len() {
                if let Some(r) = rho[i][j].filter(|r| r.abs() >= 0.7) {
                    eprintln!("seed {seed} ρ({}, {}) = {r:+.3}", names[i].0, names[j].0);
                }
            }
        }
        // what the forward force and the face's yaw lose, parameter by parameter
        let offset = study
            .validation
            .iter()
            .find(|c| c.name == "OFFSET40")
            .unwrap();
        let narrow = study
            .validation
            .iter()
            .find(|c| c.name == "NARROW-OFFSET")
            .unwrap();
        let score = |theta: &[f64]| -> [f64; 4] {
            let car = unknowns.car(theta).unwrap();
            let data: f64 = study
                .cases
                .iter()
                .flat_map(|c| quarters(&car, &truth, c))
                .map(|q| q.iter().sum::<f64>())
                .sum();
            let f = forward(&car, offset).unwrap();
            let force = f.channels.iter().find(|c| c.name == "force").unwrap();
            let rate = f.channels.iter().find(|c| c.name == "yaw rate").unwrap();
            [
                force.fit_percent,
                rate.fit_percent,
                predict(&car, narrow).unwrap().fit.fit_yaw,
                1e6 * data,
            ]
        };
        eprintln!(
            "seed {seed} forward force / yaw rate %, face yaw %, data objective mm²: truth {:.2?} run {:.2?}",
            score(&t0),
            score(&t1)
        );
        for (i, (n, _)) in names.iter().enumerate() {
            let mut back = t1.clone();
            back[i] = t0[i];
            let mut out = t0.clone();
            out[i] = t1[i];
            eprintln!(
                "seed {seed} {:<28} the run with it at the truth {:.2?}; the truth with the run's {:.2?}",
                n,
                score(&back),
                score(&out)
            );
        }
    }
}
