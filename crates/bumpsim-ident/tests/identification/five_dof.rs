//! Issue 19 on ten synthetic 5-DOF problems with known truth and noise: the
//! model identified by the DOF sweep (1..5, each continued from the one
//! before, 32 starts each) predicts a held-out case within 0.05 percentage
//! points of the truth model's fit, and fits the data at least as well as
//! the truth does, and that in every problem at least a quarter of the
//! 5-DOF starts reach the best fit (within one noise variance,
//! `Starts::reached_best_fit`; printed for each). The search's second level
//! (refinement rounds around the best so far, `bumpsim_ident::search`)
//! makes this hold by construction: 9 to 25 of 32 starts reach it. Most of
//! them are refining starts: of the 16 exploring starts alone only a few
//! (sometimes none) reach the best fit, which is printed too
//! (`Starts::explored_best_fit`) and not asserted.

use bumpsim_core::model::MsdModel;
use bumpsim_ident::case::LoadCase;
use bumpsim_ident::dofs::table;
use bumpsim_ident::estimate::{Identification, Settings};
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};

const STEP: f64 = 4e-4;
const SAMPLES: usize = 200;

fn unit(rng: &mut ChaCha8Rng) -> f64 {
    ((rng.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
}

/// A log-uniform draw in [lo, hi].
fn within(rng: &mut ChaCha8Rng, lo: f64, hi: f64) -> f64 {
    lo * (hi / lo).powf(unit(rng))
}

/// A 5-mass car: a light bumper, heavier masses behind, softer links.
fn car(rng: &mut ChaCha8Rng) -> MsdModel {
    let masses = [
        (20.0, 60.0),
        (80.0, 200.0),
        (200.0, 500.0),
        (300.0, 700.0),
        (500.0, 1000.0),
    ];
    let dampers = [(3e3, 1e4), (5e3, 2e4), (5e3, 2e4), (1e4, 3e4)];
    let springs = [(8e5, 2e6), (4e5, 1e6), (3e5, 8e5), (2e5, 6e5)];
    let mut draw = |ranges: &[(f64, f64)]| -> Vec<f64> {
        ranges.iter().map(|&(lo, hi)| within(rng, lo, hi)).collect()
    };
    MsdModel::new(draw(&masses), draw(&dampers), draw(&springs)).unwrap()
}

/// A half-sine-like pulse case measured on m1 with Gaussian noise (2e-5 m).
fn case(truth: &MsdModel, peak: f64, duration: f64, shape: f64, rng: &mut ChaCha8Rng) -> LoadCase {
    let force = (0..SAMPLES)
        .map(|k| {
            let t = k as f64 * STEP;
            let phase = (std::f64::consts::PI * t / duration).sin().max(0.0);
            if t < duration {
                peak * phase.powf(shape)
            } else {
                0.0
            }
        })
        .collect();
    let mut c = LoadCase {
        name: format!("{duration} s"),
        start: 0.0,
        step: STEP,
        force,
        measured: Vec::new(),
        output_dof: 1,
        initial_velocity: 0.0,
        window: (0, SAMPLES - 1),
        compare: Default::default(),
    };
    c.measured = c.simulate(truth).unwrap();
    for m in &mut c.measured {
        let (a, b) = (unit(rng), unit(rng));
        *m += 2e-5 * (-2.0 * a.ln()).sqrt() * (2.0 * std::f64::consts::PI * b).cos();
    }
    c
}

/// The 1..5 DOF sweep, each model continued from the one before.
fn sweep(cases: &[LoadCase], starts: usize) -> Identification {
    let rows = table(&[1, 2, 3, 4, 5], &|dof| {
        (cases.to_vec(), Settings::new(dof, starts))
    });
    // every order must succeed, not only the last
    let mut models: Vec<Identification> = rows.into_iter().map(Result::unwrap).collect();
    models.pop().unwrap()
}

#[test]
fn ten_five_dof_problems_predict_a_held_out_case_as_the_truth_does() {
    let mut reliable = 0;
    for problem in 0..10u64 {
        let mut rng = ChaCha8Rng::seed_from_u64(100 + problem);
        let truth = car(&mut rng);
        let cases = vec![
            case(&truth, 4.5e4, 0.06, 1.0, &mut rng),
            case(&truth, 3.5e4, 0.07, 1.5, &mut rng),
        ];
        let held_out = case(&truth, 2.5e4, 0.065, 2.0, &mut rng);
        let result = sweep(&cases, 32);
        let truth_objective: f64 = cases
            .iter()
            .map(|c| c.fit(&c.simulate(&truth).unwrap()).0)
            .sum();
        let fit = |m: &MsdModel| held_out.fit(&held_out.simulate(m).unwrap()).1;
        let (identified, reference) = (fit(&result.model), fit(&truth));
        let starts = &result.starts;
        eprintln!(
            "problem {problem}: F {:.4e} m² (truth {truth_objective:.4e} m²), held-out fit {identified:.4} % (truth {reference:.4} %), best fit reached by {} of {} starts ({} of the {} exploring), best objective to 1e-6 by {}",
            result.objective,
            starts.reached_best_fit,
            starts.total,
            starts.explored_best_fit,
            starts.total - starts.refined,
            starts.reached_best
        );
        if 4 * starts.reached_best_fit >= starts.total {
            reliable += 1;
        }
        // the noise is fitted, not more: at most the truth's objective
        // (+0.1 % for the screening tolerance), at least 90 % of it (13
        // parameters fit ≈ 13/400 of the noise)
        assert!(
            result.objective <= 1.001 * truth_objective
                && result.objective >= 0.9 * truth_objective,
            "problem {problem}: {} m² vs truth {truth_objective} m²",
            result.objective
        );
        assert!(
            (identified - reference).abs() <= 0.05,
            "problem {problem}: held-out fit {identified} % vs truth {reference} %"
        );
    }
    assert_eq!(
        reliable, 10,
        "only {reliable} of 10 problems had a quarter of their starts reach the best fit"
    );
}
