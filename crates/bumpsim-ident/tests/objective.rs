//! Issue 44's objective on the bundled example (`examples/identify`, truth
//! in `car-truth.toml`):
//!
//! - `objective = "displacement"` reproduces the figures the README printed
//!   before the objective had a domain (main at 207566a);
//! - the default (velocity, each case weighted by its pre-trigger noise,
//!   intervals from the random walk of the integrated accelerometer noise
//!   plus the residuals' integrated autocorrelation time) gives 95 %
//!   intervals that each contain the true car's value;
//! - the velocity and acceleration residuals' Jacobian (the backward
//!   differences of the exact displacement sensitivities) equals central
//!   differences of the residuals.

use bumpsim_estimate::lm::LeastSquares;
use bumpsim_estimate::observer::Silent;
use bumpsim_ident::case::{Comparison, Domain, Objective};
use bumpsim_ident::{Study, identify};
use nalgebra::DMatrix;
use std::path::Path;

fn example() -> Study {
    Study::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/identify/study.toml"))
        .unwrap()
}

/// `examples/identify/car-truth.toml`, thesis order, SI.
const TRUTH: [f64; 7] = [30.0, 250.0, 1170.0, 8.0e3, 2.5e4, 1.5e6, 6.0e5];

#[test]
fn the_displacement_objective_reproduces_the_recorded_figures() {
    let mut study = example();
    study.identification.objective = Some("displacement".into());
    let cases = study.cases(3).unwrap();
    assert!(cases.iter().all(|c| c.compare.is_thesis()));
    let result = identify(&cases, &study.settings(3).unwrap(), &Silent).unwrap();
    assert!(result.compared.is_none());
    // README at 207566a: objective 6.8728e-5 m², fit 99.45 %, and the table
    let close = |a: f64, b: f64, digits: f64| (a / b - 1.0).abs() < 0.5 * 10f64.powf(1.0 - digits);
    assert!(
        close(result.objective, 6.8728e-5, 5.0),
        "{}",
        result.objective
    );
    assert!(
        close(result.fit_percent, 99.45, 4.0),
        "{}",
        result.fit_percent
    );
    let recorded = [27.59, 420.1, 894.6, 8.625e3, 17.31e3, 1274e3, 756.9e3];
    let intervals = [
        [26.83, 28.37],
        [391.7, 450.5],
        [858.7, 931.9],
        [8.437e3, 8.816e3],
        [16.21e3, 18.49e3],
        [1240e3, 1308e3],
        [748.1e3, 765.8e3],
    ];
    let theta = result.model.parameters();
    for i in 0..7 {
        assert!(close(theta[i], recorded[i], 4.0), "{i}: {}", theta[i]);
        let [lo, hi] = result.uncertainty.ci95[i].unwrap();
        assert!(
            close(lo, intervals[i][0], 4.0) && close(hi, intervals[i][1], 4.0),
            "{i}: {lo} {hi}"
        );
    }
    assert_eq!(result.uncertainty.inflation, 1.0);
}

#[test]
fn the_default_intervals_contain_the_true_car() {
    let study = example();
    let cases = study.cases(3).unwrap();
    assert!(cases.iter().all(|c| c.compare.domain == Domain::Velocity));
    assert!(
        cases
            .iter()
            .all(|c| c.compare.noise.is_some_and(|n| n > 0.0))
    );
    let result = identify(&cases, &study.settings(3).unwrap(), &Silent).unwrap();
    for (i, t) in TRUTH.iter().enumerate() {
        let determined = result.uncertainty.determined[i] == Some(true);
        let ci = result.uncertainty.ci95[i];
        let inside = ci.is_some_and(|[lo, hi]| lo <= *t && *t <= hi);
        assert!(
            inside || !determined,
            "parameter {i}: truth {t}, interval {ci:?}"
        );
    }
    assert!(result.uncertainty.inflation > 1.0);
    assert_eq!(
        result.uncertainty.error_model,
        bumpsim_estimate::uncertainty::Correlation::RandomWalk
    );
}

#[test]
fn the_differenced_jacobian_equals_central_differences() {
    let study = example();
    let loaded = study.cases(3).unwrap();
    let theta = TRUTH.map(|t| t * 1.1);
    let p: Vec<f64> = theta.iter().map(|t| t.ln()).collect();
    for domain in [Domain::Velocity, Domain::Acceleration] {
        let cases: Vec<_> = loaded
            .iter()
            .map(|c| {
                let mut c = c.clone();
                c.compare = Comparison::new(domain, Some(0.5));
                c.window.1 = c.window.0 + 300;
                c
            })
            .collect();
        let objective = Objective::new(&cases, 3, &[]);
        let m = objective.residual_count();
        let (mut r, mut j) = (vec![0.0; m], DMatrix::zeros(m, 7));
        assert!(objective.evaluate(&p, &mut r, Some(&mut j)));
        // the second difference over the sample step amplifies the central
        // difference's rounding by 1/step²: a larger step and tolerance there
        let (h, tolerance) = match domain {
            Domain::Velocity => (1e-6, 1e-5),
            _ => (1e-5, 1e-4),
        };
        for col in 0..7 {
            let (mut up, mut down) = (p.clone(), p.clone());
            up[col] += h;
            down[col] -= h;
            let (mut ru, mut rd) = (vec![0.0; m], vec![0.0; m]);
            assert!(objective.evaluate(&up, &mut ru, None));
            assert!(objective.evaluate(&down, &mut rd, None));
            let scale = j.column(col).amax();
            for k in 0..m {
                let fd = (ru[k] - rd[k]) / (2.0 * h);
                assert!(
                    (fd - j[(k, col)]).abs() <= tolerance * scale,
                    "{domain} column {col} row {k}: exact {} central {fd}",
                    j[(k, col)]
                );
            }
        }
    }
}

/// The bundled study with `extra` lines added before its `[model]` (or
/// into its first case with `case_line`), in a scratch folder.
fn variant(name: &str, before_model: &str, case_line: &str) -> std::path::PathBuf {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/identify");
    let text = std::fs::read_to_string(example.join("study.toml")).unwrap();
    let dir = std::env::temp_dir().join(format!("bumpsim-objective-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let text = text
        .replacen("[model]", &format!("{before_model}\n[model]"), 1)
        .replacen("cfc = 180", &format!("cfc = 180\n{case_line}"), 1)
        .replace("path = \"", &format!("path = \"{}/", example.display()));
    let path = dir.join("study.toml");
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_bad_objective_or_noise_is_refused_naming_the_key() {
    for (name, table, line, expected) in [
        (
            "word",
            "[identification]\nobjective = \"speed\"\n",
            "",
            "[identification] objective \"speed\": expected \"displacement\", \"velocity\" or \"acceleration\"",
        ),
        (
            "number",
            "[identification]\nobjective = 2\n",
            "",
            "objective",
        ),
        (
            "key",
            "[identification]\ndomain = \"velocity\"\n",
            "",
            "domain",
        ),
        ("negative", "", "noise = -1.0", "noise = -1"),
        ("nan", "", "noise = nan", "noise = NaN"),
        ("zero", "", "noise = 0.0", "noise = 0"),
    ] {
        let path = variant(name, table, line);
        let err = Study::read(&path).unwrap_err().to_string();
        assert!(
            err.contains(expected) && err.contains("study.toml"),
            "{name}: {err}"
        );
    }
    // a given noise is the case's weight, in every domain
    let path = variant(
        "given",
        "[identification]\nobjective = \"acceleration\"\n",
        "noise = 2.5",
    );
    let cases = Study::read(&path).unwrap().cases(3).unwrap();
    assert_eq!(
        (cases[0].compare.domain, cases[0].compare.noise),
        (Domain::Acceleration, Some(2.5))
    );
    // integrated from accelerations: the walk starts at the pre-trigger's
    // first sample, its bias removed over the whole pre-trigger (0.05 s)
    let walk = cases[0].compare.integrated.unwrap();
    assert_eq!((walk.lead, walk.bias), (500, Some((0, 500))));
    assert!(cases[1].compare.noise.is_some_and(|n| n != 2.5));
}
