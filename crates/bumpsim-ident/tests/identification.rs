//! Integration tests of identification: the exact Jacobian against finite
//! differences (property test), recovery and held-out prediction on a
//! synthetic series, the coverage of the 95 % intervals over 50 noise
//! realisations, the thesis's own start on the bundled example, and bad input.

use bumpsim_core::model::{MsdModel, parameter_count};
use bumpsim_estimate::lm::LeastSquares;
use bumpsim_ident::case::{LoadCase, Objective};
use bumpsim_ident::estimate::{Settings, identify};
use bumpsim_ident::explore::predict;
use bumpsim_ident::study::Study;
use nalgebra::DMatrix;
use proptest::prelude::*;
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};
use std::path::Path;

const STEP: f64 = 2e-4;

fn pulse(samples: usize, peak: f64, duration: f64, shape: f64) -> Vec<f64> {
    (0..samples)
        .map(|k| {
            let t = k as f64 * STEP;
            if t < duration {
                peak * (std::f64::consts::PI * t / duration).sin().powf(shape)
            } else {
                0.0
            }
        })
        .collect()
}

fn case(name: &str, force: Vec<f64>, truth: &MsdModel) -> LoadCase {
    let n = force.len();
    let mut c = LoadCase {
        name: name.into(),
        start: 0.0,
        step: STEP,
        force,
        measured: vec![0.0; n],
        output_dof: 1,
        initial_velocity: 0.0,
        window: (0, n - 1),
        compare: Default::default(),
    };
    c.measured = c.simulate(truth).unwrap();
    c
}

/// Gaussian noise (Box–Muller) from a seeded stream.
fn noise(rng: &mut ChaCha8Rng, sigma: f64) -> f64 {
    let u = |rng: &mut ChaCha8Rng| ((rng.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64;
    let (a, b) = (u(rng), u(rng));
    sigma * (-2.0 * a.ln()).sqrt() * (2.0 * std::f64::consts::PI * b).cos()
}

/// Adds Gaussian noise of `sigma` (m) to every measured sample, drawn in
/// case order from a ChaCha8 stream seeded with `seed`.
fn add_noise(cases: &mut [LoadCase], seed: u64, sigma: f64) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    for c in cases {
        c.measured
            .iter_mut()
            .for_each(|m| *m += noise(&mut rng, sigma));
    }
}

fn truth() -> MsdModel {
    MsdModel::new(vec![40.0, 300.0, 1100.0], vec![6e3, 2e4], vec![1.2e6, 5e5]).unwrap()
}

fn series(truth: &MsdModel) -> Vec<LoadCase> {
    vec![
        case("flat", pulse(400, 4.5e4, 0.06, 1.0), truth),
        case("600 mm", pulse(400, 3.5e4, 0.07, 1.5), truth),
        case("pole", pulse(450, 2.5e4, 0.085, 2.0), truth),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    /// The Jacobian of the fixed-size (1–5 DOF) and dynamic (6 DOF) paths
    /// equals central differences of the residuals in log parameters.
    #[test]
    fn jacobian_equals_finite_differences(dof in 1usize..=6, seed in 0u64..1000, v0 in -2.0f64..2.0) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let mut draw = |lo: f64, hi: f64| lo * (hi / lo).powf((rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64);
        let p = parameter_count(dof);
        let theta: Vec<f64> = (0..p).map(|i| match bumpsim_core::model::parameter_kind(dof, i).0 {
            bumpsim_core::model::ParameterKind::Mass => draw(5.0, 800.0),
            bumpsim_core::model::ParameterKind::Damper => draw(1e2, 3e4),
            bumpsim_core::model::ParameterKind::Spring => draw(1e5, 3e6),
        }).collect();
        let model = MsdModel::from_parameters(dof, &theta).unwrap();
        let mut c = case("p", pulse(150, 2e4, 0.02, 1.0), &model);
        c.initial_velocity = v0;
        c.output_dof = dof;
        c.measured.iter_mut().for_each(|m| *m *= 0.9);
        let cases = [c];
        let objective = Objective::new(&cases, dof, &vec![None; p]);
        let logs: Vec<f64> = theta.iter().map(|t| t.ln()).collect();
        let m = objective.residual_count();
        let mut r = vec![0.0; m];
        let mut jac = DMatrix::zeros(m, p);
        prop_assert!(objective.evaluate(&logs, &mut r, Some(&mut jac)));
        let scale = jac.amax().max(1e-12);
        // the differences' rounding: ≈ ε |r| / h with ε the simulation's
        // relative precision (1e-12 allows for a stiff 6-DOF chain) and h = 1e-3;
        // a 6-DOF case with a tiny Jacobian (amax 2e-8) failed on it alone
        let rounding = 1e-9 * r.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        // Central differences with Richardson extrapolation: h = 2e-3 and 1e-3
        // in log parameters (smaller steps drown in the rounding of a stiff
        // simulation; the h² term is removed instead).
        let central = |i: usize, h: f64| {
            let (mut plus, mut minus) = (logs.clone(), logs.clone());
            plus[i] += h;
            minus[i] -= h;
            let (mut rp, mut rm) = (vec![0.0; m], vec![0.0; m]);
            objective.evaluate(&plus, &mut rp, None);
            objective.evaluate(&minus, &mut rm, None);
            rp.iter().zip(&rm).map(|(a, b)| (a - b) / (2.0 * h)).collect::<Vec<f64>>()
        };
        for i in 0..p {
            let (coarse, fine) = (central(i, 2e-3), central(i, 1e-3));
            for k in 0..m {
                let fd = (4.0 * fine[k] - coarse[k]) / 3.0;
                prop_assert!((jac[(k, i)] - fd).abs() <= 1e-5 * scale + rounding, "dof {dof}, parameter {i}, sample {k}: {} vs {fd}", jac[(k, i)]);
            }
        }
    }
}

#[test]
fn recovers_the_model_and_predicts_a_held_out_case() {
    let truth = truth();
    let mut cases = series(&truth);
    add_noise(&mut cases, 7, 3e-5);
    let held_out = cases.pop().unwrap();
    let result = identify(&cases, &Settings::new(3, 8), &|| {}).unwrap();
    let predicted = &predict(&[held_out], result.model()).unwrap()[0];
    assert!(
        predicted.fit.fit_percent >= 99.5,
        "held-out fit {} %",
        predicted.fit.fit_percent
    );
    for (got, want) in result.model.masses().iter().zip(truth.masses()) {
        assert!((got / want - 1.0).abs() < 0.1, "mass {got} vs {want}");
    }
    assert_eq!(result.starts.failed, 0);
}

#[test]
fn intervals_cover_the_truth_in_at_least_85_percent_of_50_realisations() {
    let truth = truth();
    let clean = series(&truth);
    let theta = truth.parameters();
    let mut covered = vec![0usize; theta.len()];
    let realisations = 50;
    for seed in 0..realisations {
        let mut cases = clean.clone();
        add_noise(&mut cases, 1000 + seed, 5e-5);
        let mut settings = Settings::new(3, 4);
        settings.start = Some(theta.iter().map(|t| t * 1.2).collect());
        let result = identify(&cases, &settings, &|| {}).unwrap();
        for (i, ci) in result.uncertainty.ci95.iter().enumerate() {
            let inside = ci.is_some_and(|[lo, hi]| lo <= theta[i] && theta[i] <= hi);
            if !inside {
                eprintln!(
                    "seed {seed}: {} = {:e} not in {:?} ({:?})",
                    result.uncertainty.names[i],
                    result.model.parameters()[i],
                    ci,
                    result.warnings
                );
            }
            covered[i] += usize::from(inside);
        }
    }
    for (i, &n) in covered.iter().enumerate() {
        assert!(
            n as f64 >= 0.85 * realisations as f64,
            "parameter {i}: interval covered the truth in {n} of {realisations}"
        );
    }
}

fn example_study() -> Study {
    Study::read(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/identify/study.toml"))
        .unwrap()
}

#[test]
fn the_thesis_start_converges_without_nan_on_the_bundled_example() {
    let study = example_study();
    let cases = study.cases(3).unwrap();
    let mut settings = study.settings(3).unwrap();
    settings.starts = 1;
    settings.start = Some(vec![150.0, 500.0, 800.0, 1e2, 2e5, 5e5, 5e5]);
    let result = identify(&cases, &settings, &|| {}).unwrap();
    let all = result.model.parameters();
    assert!(all.iter().all(|v| v.is_finite() && *v >= 1.0), "{all:?}");
    assert!(result.objective.is_finite());
    assert_eq!(result.starts.converged, 1, "stop: {:?}", result.stop);
    // alone it may stop in a local minimum; with a few more starts the best fit is found
    settings.starts = 8;
    let result = identify(&cases, &settings, &|| {}).unwrap();
    assert!(result.fit_percent > 99.0, "fit {}", result.fit_percent);
}

#[test]
fn bad_settings_and_studies_are_clear_errors() {
    let truth = truth();
    let cases = series(&truth);
    let mut settings = Settings::new(3, 1);
    settings.start = Some(vec![1.0; 3]);
    let err = identify(&cases, &settings, &|| {}).unwrap_err().to_string();
    assert!(
        err.contains("start") && err.contains("7 positive values"),
        "{err}"
    );
    // bounds a model cannot take, or NaN, are refused naming the parameter
    for (lower, upper) in [(2e15, f64::INFINITY), (1e-20, 1e-13), (f64::NAN, 10.0)] {
        let mut settings = Settings::new(3, 1);
        settings.bounds.lower[5] = lower;
        settings.bounds.upper[5] = upper;
        let err = identify(&cases, &settings, &|| {}).unwrap_err().to_string();
        assert!(err.contains("k1") && err.contains("N/m"), "{err}");
    }
    let mut short = cases[0].clone();
    short.measured.pop();
    let err = identify(&[short], &Settings::new(3, 1), &|| {})
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("'flat'") && err.contains("400 force samples and 399"),
        "{err}"
    );
    // a case built in code (as the Python binding does) gets the study's limit
    let mut fast = cases[0].clone();
    fast.initial_velocity = 1e300;
    let err = identify(&[fast], &Settings::new(2, 1), &|| {})
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("initial velocity 1.000e300 m/s: expected a finite speed of at most 1000 m/s"),
        "{err}"
    );
    // every parameter fixed: nothing to identify, said as such
    let mut all_fixed = Settings::new(1, 4);
    all_fixed.bounds.fixed = vec![Some(900.0)];
    let err = identify(&cases, &all_fixed, &|| {})
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("every parameter of the 1-DOF model is fixed: nothing is left to identify"),
        "{err}"
    );
    let rigid = identify(&cases, &Settings::new(1, 1), &|| {}).unwrap();
    assert!(
        rigid.objective.is_finite() && rigid.model.masses()[0] > 1.0,
        "a finite rigid mass above its bound"
    );
    let mut deep = cases[0].clone();
    deep.output_dof = 4;
    let err = identify(&[deep], &Settings::new(3, 1), &|| {})
        .unwrap_err()
        .to_string();
    assert!(err.contains("measures DOF 4 of a 3-DOF model"), "{err}");
    let dir = std::env::temp_dir().join(format!("bumpsim-ident-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("study.toml");
    std::fs::write(&path, "[model]\ndof = 2\nmethod = \"taylor1\"\n[[case]]\nname = \"a\"\nforce = { path = \"x.csv\", channel = \"f\" }\n").unwrap();
    let err = Study::read(&path).unwrap_err().to_string();
    assert!(err.contains("study.toml") && err.contains("zoh"), "{err}");
    std::fs::write(&path, "[model]\ndof = 2\n[[case]]\nname = \"a\"\nforce = { path = \"missing.csv\", channel = \"f\" }\ndisplacement = { path = \"missing.csv\", channel = \"x\" }\n").unwrap();
    let err = Study::read(&path)
        .unwrap()
        .cases(2)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("case 'a'") && err.contains("missing.csv"),
        "{err}"
    );
}

#[test]
fn retarget_moves_a_last_output_to_each_model_size() {
    let example = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/identify");
    let text = std::fs::read_to_string(example.join("study.toml")).unwrap();
    let dir = std::env::temp_dir().join(format!("bumpsim-retarget-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("study.toml");
    let text = text
        .replacen("output_dof = 1", "output_dof = \"last\"", 1)
        .replace("path = \"", &format!("path = \"{}/", example.display()));
    std::fs::write(&path, text).unwrap();
    let study = Study::read(&path).unwrap();
    let loaded = study.cases(4).unwrap();
    for dof in 1..=4 {
        let cases = study.retarget(&loaded, dof);
        assert_eq!(cases[0].output_dof, dof, "the case that says \"last\"");
        assert_eq!(cases[1].output_dof, 1, "a case with a number keeps it");
        assert_eq!(
            cases,
            study.cases(dof).unwrap(),
            "the same as reading the files again"
        );
    }
}

/// `bumpsim simulate` (core's simulate), `predict` and the objective that
/// `identify` minimises (with and without its Jacobian) run one zoh
/// discretisation, so they give the same response: to 1e-12 relative of the
/// peak (in fact bit for bit), for a fixed-size (3-DOF) and a dynamic
/// (6-DOF) model, from a moving start.
#[test]
fn simulate_predict_and_identify_give_identical_responses() {
    use bumpsim_core::prelude::{InitialState, Method, UniformSeries, simulate};
    for dof in [3, 6] {
        let masses = (0..dof).map(|i| 30.0 + 200.0 * i as f64).collect();
        let dampers = (1..dof).map(|i| 4e3 * i as f64).collect();
        let springs = (1..dof).map(|i| 1e6 / i as f64).collect();
        let model = MsdModel::new(masses, dampers, springs).unwrap();
        let force = pulse(400, 4e4, 0.05, 1.0);
        let mut c = case("flat", force.clone(), &model);
        c.initial_velocity = 1.5;
        c.output_dof = dof;
        c.measured = vec![0.0; 400];
        let series = UniformSeries::new(0.0, STEP, force).unwrap();
        let core = simulate(
            &model,
            &series,
            Method::Zoh,
            &InitialState::UniformVelocity(1.5),
        )
        .unwrap()
        .displacement[dof - 1]
            .clone();
        let predicted = predict(std::slice::from_ref(&c), &model).unwrap()[0]
            .simulated
            .clone();
        let objective = Objective::new(std::slice::from_ref(&c), dof, &[]);
        let p: Vec<f64> = model.parameters().iter().map(|v| v.ln()).collect();
        let (mut plain, mut with_jacobian) = (vec![0.0; 400], vec![0.0; 400]);
        let mut jac = DMatrix::zeros(400, p.len());
        assert!(objective.evaluate(&p, &mut plain, None));
        assert!(objective.evaluate(&p, &mut with_jacobian, Some(&mut jac)));
        let peak = core.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
        assert!(peak > 1e-3, "the case moves the output: {peak} m");
        for (name, other) in [
            ("predict", &predicted),
            ("identify (residuals)", &plain),
            ("identify (with Jacobian)", &with_jacobian),
        ] {
            for (k, (a, b)) in core.iter().zip(other).enumerate() {
                assert!(
                    (a - b).abs() <= 1e-12 * peak,
                    "{dof}-DOF {name} sample {k}: {a} vs simulate {b}"
                );
            }
        }
    }
}

/// RESULT.json keeps the shape it had before the result held a model: the
/// model's `masses`, `dampers` and `springs` at the top level after `dof`,
/// and the stop reason as the name of the `Stop` variant.
#[test]
fn the_result_serialises_as_before() {
    let truth = MsdModel::new(vec![300.0, 900.0], vec![4e3], vec![8e5]).unwrap();
    let flat = case("flat", pulse(300, 3e4, 0.04, 1.0), &truth);
    let result = identify(&[flat], &Settings::new(2, 2), &|| {}).unwrap();
    let text = serde_json::to_string(&result).unwrap();
    assert!(
        text.starts_with(r#"{"dof":2,"masses":["#),
        "{}",
        &text[..40]
    );
    let at = |key: &str| text.find(&format!("\"{key}\":")).unwrap();
    assert!(at("masses") < at("dampers") && at("dampers") < at("springs"));
    assert!(at("springs") < at("objective"));
    let json: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(json["masses"].as_array().unwrap().len(), 2);
    assert_eq!(json["springs"][0].as_f64(), Some(result.model.springs()[0]));
    assert_eq!(
        json["stop"],
        serde_json::json!(format!("{:?}", result.stop))
    );
    let stop: bumpsim_estimate::lm::Stop = serde_json::from_value(json["stop"].clone()).unwrap();
    assert_eq!(stop, result.stop);
    // the one reader of results gives the same model back
    let car = bumpsim_io::car::Car::parse_json(&json.to_string(), Path::new("r.json")).unwrap();
    assert_eq!(&car.model, result.model());
}

#[test]
fn continuation_from_the_smaller_model_never_loses_its_fit() {
    // data of a 2-mass car with noise: a 3-mass model can only fit the noise
    // better. The 2-mass optimum split in each of its masses starts the
    // 3-mass search where the smaller model ended, so with only the data
    // start and the two split starts the 3-mass objective is at most the
    // 2-mass one (1 % for the stiff link's own response)
    let two_mass = MsdModel::new(vec![60.0, 1200.0], vec![8e3], vec![9e5]).unwrap();
    let mut cases = series(&two_mass);
    add_noise(&mut cases, 11, 2e-5);
    let two = identify(&cases, &Settings::new(2, 8), &|| {}).unwrap();
    // each split start already fits as the 2-mass optimum does
    let objective = Objective::new(&cases, 3, &[None; 8]);
    let mut residuals = vec![0.0; objective.residual_count()];
    for start in bumpsim_ident::search::continuation_starts(&two.model) {
        let logs: Vec<f64> = start.iter().map(|v| v.ln()).collect();
        assert!(objective.evaluate(&logs, &mut residuals, None));
        let cost: f64 = residuals.iter().map(|r| r * r).sum();
        assert!(
            cost <= 1.01 * two.objective,
            "split start {cost} m² vs {} m²",
            two.objective
        );
    }
    let mut settings = Settings::new(3, 3);
    settings.continue_from(&two.model);
    assert_eq!(settings.seeds.len(), 2);
    let three = identify(&cases, &settings, &|| {}).unwrap();
    assert!(
        three.objective <= 1.01 * two.objective,
        "3 masses {} m² vs 2 masses {} m²",
        three.objective,
        two.objective
    );
    let table = bumpsim_ident::text::dof_table(&[two.clone(), three.clone()]);
    let best = if three.bic < two.bic { 3 } else { 2 };
    assert!(
        table.contains(&format!("recommended: {best} DOF (lowest BIC)")),
        "{table}"
    );
    // a seed of the wrong size is refused, naming it
    settings.seeds = vec![vec![1.0; 3]];
    let error = identify(&cases, &settings, &|| {}).unwrap_err().to_string();
    assert!(error.contains("seed start 1"), "{error}");
}

#[test]
fn an_undetermined_stiff_spring_is_named_and_the_merged_model_suggested() {
    // m2 and m3 joined by a spring far stiffer than 10 kHz data resolve
    let stiff =
        MsdModel::new(vec![40.0, 300.0, 1100.0], vec![6e3, 2e4], vec![1.2e6, 5e10]).unwrap();
    let mut cases = series(&stiff);
    add_noise(&mut cases, 5, 2e-5);
    let result = identify(&cases, &Settings::new(3, 8), &|| {}).unwrap();
    let reduction = result.reduction.as_ref().expect("a reduced model");
    assert_eq!(reduction.parameter, "k2", "{}", reduction.statement);
    assert!(
        reduction.relative_objective <= 0.01,
        "{}",
        reduction.statement
    );
    assert!(
        reduction.statement.contains("m2 and m3 move as one"),
        "{}",
        reduction.statement
    );
    assert_eq!(reduction.model.dof(), 2);
    let merged = reduction.model.masses()[1];
    assert!((merged / 1400.0 - 1.0).abs() < 0.1, "m2 + m3 = {merged} kg");
    assert!(result.warnings.contains(&reduction.statement));
    // the parameter is marked, for the JSON, the summary and the report
    let u = &result.uncertainty;
    assert_eq!(u.determined[6], Some(false), "{:?}", u.determined);
    let table = bumpsim_ident::text::parameter_table(&result);
    let k2 = table.lines().find(|l| l.starts_with("k2")).unwrap();
    assert!(
        k2.ends_with("at bound") || k2.ends_with("not determined"),
        "{table}"
    );
    // the free direction trades m2 against m3 (their sum is determined):
    // named with opposite ways, in the JSON's signed components too
    let named = result.warnings.iter().any(|w| {
        let trade = |a: &str, b: &str| {
            w.contains(&format!("raises {a}")) && w.contains(&format!("lowers {b}"))
        };
        trade("m2", "m3") || trade("m3", "m2")
    });
    assert!(named, "{:?}", result.warnings);
    let component = |name: &str| {
        let s = u
            .weakest_direction
            .iter()
            .find(|s| s.parameter == name)
            .unwrap();
        assert!((s.component.powi(2) - s.share).abs() < 1e-12);
        s.component
    };
    assert!(
        component("m2") * component("m3") < 0.0,
        "{:?}",
        u.weakest_direction
    );
    // a well-determined model gets no suggestion, and every parameter is determined
    let determined = identify(&series(&truth()), &Settings::new(3, 8), &|| {}).unwrap();
    assert!(determined.reduction.is_none(), "{:?}", determined.reduction);
    let u = &determined.uncertainty;
    assert_eq!(u.determined, vec![Some(true); 7]);
    let shares: f64 = u.weakest_direction.iter().map(|s| s.share).sum();
    assert!((shares - 1.0).abs() < 1e-9, "{:?}", u.weakest_direction);
    assert!(
        u.weakest_direction
            .windows(2)
            .all(|w| w[0].share >= w[1].share)
    );
}

/// Issue 19: ten synthetic 5-DOF problems.
#[path = "identification/five_dof.rs"]
mod five_dof;

/// The test above on one noise draw, here on eight: which link of the
/// identified 3-DOF model comes out free depends on the draw (the data
/// resolve a 40 kg mass on a 1400 kg one, and a 3-DOF fit may split either),
/// but a reduced model is always suggested, within 1 % of the objective,
/// and it is the 2-DOF model the data resolve.
#[test]
fn the_stiff_spring_reduction_holds_on_eight_noise_draws() {
    let stiff =
        MsdModel::new(vec![40.0, 300.0, 1100.0], vec![6e3, 2e4], vec![1.2e6, 5e10]).unwrap();
    for seed in 1..=8u64 {
        let mut cases = series(&stiff);
        add_noise(&mut cases, seed, 2e-5);
        let result = identify(&cases, &Settings::new(3, 8), &|| {}).unwrap();
        let r = result.reduction.as_ref().expect("a reduced model");
        assert!(r.relative_objective <= 0.01, "seed {seed}: {}", r.statement);
        assert!(
            r.statement.starts_with(&r.parameter) && r.statement.contains("move as one"),
            "seed {seed}: {}",
            r.statement
        );
        let masses = r.model.masses();
        assert!(
            (masses[0] / 40.0 - 1.0).abs() < 0.1 && (masses[1] / 1400.0 - 1.0).abs() < 0.1,
            "seed {seed}: reduced masses {masses:?} kg"
        );
    }
}

/// A ten-sample overlap of force and displacement gave a fit of −2477 %
/// with exit 0 even under `--strict`: a case the model follows worse than
/// the measurement's mean is a warning.
#[test]
fn a_case_fitted_worse_than_its_mean_is_a_warning() {
    let mut cases = series(&truth());
    // a displacement of the wrong sign: no positive model follows it
    for m in &mut cases[0].measured {
        *m = -*m;
    }
    let result = identify(&cases, &Settings::new(2, 2), &|| {}).unwrap();
    let flat = result.cases.iter().find(|c| c.name == "flat").unwrap();
    assert!(flat.fit_percent < 0.0, "{}", flat.fit_percent);
    assert!(
        result
            .warnings
            .iter()
            .any(|w| w.starts_with("case 'flat': fit -") && w.contains("worse than its mean")),
        "{:?}",
        result.warnings
    );
    // the model, pushed to a huge mass by the wrong sign, follows none
    assert!(result.cases.iter().all(|c| c.fit_percent < 0.0));
    // a model that fits gets no such warning
    let good = identify(&series(&truth()), &Settings::new(3, 2), &|| {}).unwrap();
    assert!(
        !good
            .warnings
            .iter()
            .any(|w| w.contains("worse than its mean")),
        "{:?}",
        good.warnings
    );
}

/// One quick identification (one start) whose document the property test
/// below fills with drawn models.
fn identified() -> &'static bumpsim_ident::result::Identification {
    static ONE: std::sync::OnceLock<bumpsim_ident::result::Identification> =
        std::sync::OnceLock::new();
    ONE.get_or_init(|| identify(&series(&truth()), &Settings::new(3, 1), &|| {}).unwrap())
}

/// A positive finite value from 1e-300 to 1e300.
fn positive() -> impl Strategy<Value = f64> {
    (1.0..10.0f64, -300..300i32).prop_map(|(m, e)| m * 10f64.powi(e))
}

/// A drawn chain: 1 to 8 masses, dampers 0 or positive.
fn drawn_model() -> impl Strategy<Value = MsdModel> {
    (1..=8usize).prop_flat_map(|dof| {
        let damper = prop_oneof![Just(0.0), positive()];
        (
            prop::collection::vec(positive(), dof),
            prop::collection::vec(damper, dof - 1),
            prop::collection::vec(positive(), dof - 1),
        )
            .prop_map(|(m, c, k)| MsdModel::new(m, c, k).unwrap())
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Issue 34: the JSON `identify --json` writes, read back as a car file
    /// (`--car result.json`), is the identified car, every value bit for bit.
    #[test]
    fn an_identification_json_reads_back_as_the_same_car(model in drawn_model()) {
        use bumpsim_ident::document::{IdentifyDocument, WithPosterior};
        let mut result = identified().clone();
        result.dof = model.dof();
        result.model = model.clone();
        let document = WithPosterior {
            document: IdentifyDocument::One { result: &result, notes: &[] },
            posterior: None,
        };
        let json = serde_json::to_string_pretty(&document).unwrap();
        let car = bumpsim_io::car::Car::parse_json(&json, Path::new("result.json")).unwrap();
        prop_assert_eq!(car.name, None);
        prop_assert_eq!(car.model, model);
    }
}
