//! Issue 44 item 6: from its default (data-derived) start, one start,
//! bumpsim's LM with Nielsen's damping and the geodesic acceleration
//! (`lm::Settings::acceleration`: 17 and 41 Jacobians since 2026-11-30,
//! 18 and 42 before; the trust region, [`Damping::TrustRegion`], 12 and
//! 14) needs no more Jacobians than scipy's `least_squares`
//! (trust-region-reflective, 2-point differences) evaluates from the same
//! start, for the same optimum (objectives within 1e-9, relative: both stop
//! at the same precision, so neither count is bought with a looser
//! tolerance). Since 2026-11-30 (06:00) **the identification's own
//! one-start search meets it by default** (the test at the end): its one LM
//! run (`multistart::alone`) takes the acceleration, where the solver's
//! default, plain steps (which the multi-start stages keep), took 23 and
//! 76; a screening and a polish before that, 31 and 76. See docs/identify.md
//! "Iterations". Counted: scipy's `njev` (the start's Jacobian and one per
//! accepted step, the last point's included); bumpsim's, the normal
//! equations LM forms (`LeastSquares::normal`: the start's and one per
//! accepted step but the last, its iterations: since 2026-11-30 a run that
//! stops forms none at its last point, where nothing uses them), counted
//! on the problem itself. The series is `bench/peers/scipy_identify.py`'s
//! (three synthetic pendulum cases, 500 samples each), written and fitted
//! by `tests/peers/scipy_trf_iterations.py`; skipped without scipy.

use bumpsim_estimate::lm::{self, Damping, LeastSquares, Outcome};
use bumpsim_ident::Study;
use bumpsim_ident::case::Objective;
use bumpsim_ident::estimate::{data_start, search_of};
use nalgebra::{DMatrix, DVector};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::atomic::{AtomicUsize, Ordering};

/// A problem that counts the Jacobians (normal equations) LM asks for, and
/// the `Jᵀv` products; shared counters, so that a multi-start's runs (one
/// problem each) add to the same count.
struct Counted<'a> {
    objective: Objective<'a>,
    jacobians: &'a AtomicUsize,
    products: &'a AtomicUsize,
}

impl LeastSquares for Counted<'_> {
    fn residual_count(&self) -> usize {
        self.objective.residual_count()
    }
    fn parameter_count(&self) -> usize {
        self.objective.parameter_count()
    }
    fn evaluate(&self, p: &[f64], r: &mut [f64], jacobian: Option<&mut DMatrix<f64>>) -> bool {
        self.jacobians
            .fetch_add(usize::from(jacobian.is_some()), Ordering::Relaxed);
        self.objective.evaluate(p, r, jacobian)
    }
    fn normal(
        &self,
        p: &[f64],
        r: &mut [f64],
        jtj: &mut DMatrix<f64>,
        g: &mut DVector<f64>,
    ) -> bool {
        self.jacobians.fetch_add(1, Ordering::Relaxed);
        self.objective.normal(p, r, jtj, g)
    }
    fn transposed(&self, p: &[f64], v: &[f64], product: &mut DVector<f64>) -> bool {
        self.products.fetch_add(1, Ordering::Relaxed);
        self.objective.transposed(p, v, product)
    }
}

fn script() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/scipy_trf_iterations.py")
}

/// The series and its study, written once per target folder.
fn series() -> Option<PathBuf> {
    if !bumpsim_peers::python_available("scipy") {
        return None;
    }
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("scipy-trf-iterations");
    bumpsim_peers::generated(&script(), &out, &[], "study.toml");
    Some(out)
}

/// scipy's Jacobian evaluations and objective from `start` (SI).
fn trf(out: &Path, objective: &str, start: &[f64]) -> (usize, f64) {
    let run = Command::new("python3")
        .arg(script())
        .arg(out)
        .arg(objective)
        .args(start.iter().map(|v| format!("{v:e}")))
        .output()
        .unwrap();
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = String::from_utf8(run.stdout).unwrap();
    let mut words = text.split_whitespace();
    let njev = words.next().unwrap().parse().unwrap();
    (njev, words.next().unwrap().parse().unwrap())
}

/// From the default start, LM with the identification's own solver and
/// (`damping` None) the geodesic acceleration, or with `damping` and none.
fn compare(objective: &str, damping: Option<Damping>) {
    let Some(out) = series() else { return };
    let mut study = Study::read(&out.join("study.toml")).unwrap();
    study.identification.objective = Some(objective.into());
    let cases = study.cases(3).unwrap();
    let settings = study.settings(3).unwrap();
    // the identification's own solver and bounds, the data alone (scipy
    // fits no priors), one start: the data-derived one
    let solver = match damping {
        Some(damping) => lm::Settings {
            damping,
            acceleration: None,
            ..settings.solver
        },
        None => lm::Settings {
            acceleration: Some(lm::ACCELERATION_LIMIT),
            ..settings.solver
        },
    };
    let start = data_start(&cases, 3);
    let log = |v: &[f64]| -> Vec<f64> { v.iter().map(|x| x.ln()).collect() };
    let (jacobians, products) = (AtomicUsize::new(0), AtomicUsize::new(0));
    let problem = Counted {
        objective: Objective::new(&cases, 3, &settings.bounds.fixed),
        jacobians: &jacobians,
        products: &products,
    };
    let outcome = lm::minimise(
        &problem,
        &log(&start),
        &log(&settings.bounds.lower),
        &log(&settings.bounds.upper),
        &solver,
    );
    assert!(outcome.stop.converged(), "{:?}", outcome.stop);
    let counts = (jacobians.into_inner(), products.into_inner());
    assert_eq!(
        counts.0, outcome.iterations,
        "one per accepted step but the last"
    );
    against_scipy(&out, objective, objective, &start, &outcome, counts);
}

/// Issue 44 item 6 (2026-11-29, 21:00): Nielsen's damping
/// with the geodesic acceleration (Transtrum & Sethna 2012; the step
/// `v + a/2`, `a` from the residuals' second directional derivative by one
/// residual evaluation at `p + 0.1 v` and `Jᵀ` of it by the modal form's
/// basis alone; refused when `2‖a‖/‖v‖ > 1`; the gain ratio against the
/// model's decrease along v) takes **17 Jacobians against scipy's 18 on the
/// velocity objective and 41 against 60 on the displacement one** (58 and
/// 147 residual evaluations, 24 and 52 `Jᵀv` products), to the same
/// optimum; until 2026-11-30 LM also formed the normal equations at the
/// point it stopped at, one more (18 and 42; the figures below are of then).
/// By the largest ratio accepted (velocity, displacement): 0.5 26, 54;
/// 0.75 (Transtrum & Sethna's) 22, 42; **1.0 18, 42**; 1.25 18, 37; 1.5 19,
/// 34; 2 17, 33; 3 or none 15 and a displacement run that stops 4e4 times
/// above the optimum. With the gain ratio against the whole step's model
/// decrease instead, 0.75 took 32 and 107. The velocity count has no
/// margin (1.5 gives 19): the acceleration does the displacement's curved
/// valley (77 → 42), not the velocity objective's slow linear creep.
///
/// The trust region, velocity: 13 Jacobians (12 accepted steps; 12 since
/// 2026-11-30, no Jacobian at the last point) against
/// scipy's 18, to the same optimum (scipy's ends 4e-13 above bumpsim's);
/// displacement 15 (14 since 2026-11-30) against 60. Until 2026-11-29 (10:50) the trust region
/// quartered its radius after a refused trial, as scipy's TRF does, and
/// took 23 and 39: both reach 3e-5 above the optimum at their 11th
/// Jacobian, then bumpsim crept along a curved valley with its radius
/// cycling (refused at 2Δ, accepted at ½Δ and at Δ: two short Jacobians
/// per cycle). Halving after a refusal (Madsen, Nielsen & Tingleff 2004,
/// eq. 2.19) takes the step at Δ instead. Measured 2026-11-29, data alone,
/// Jacobians (iterations + 1) of the trust-region variants tried in turn,
/// against scipy TRF's 18 and 60:
///
/// | step scaling, first radius, radius rules | velocity | displacement |
/// |---|---|---|
/// | column norms of J, 100 × ‖D p‖, a refusal halves (**this one**) | **13** | **15** |
/// | the same, a refusal quarters (scipy's; the previous one) | 23 | 39 |
/// | the same, a refusal × 0.3 | 22 | 53 |
/// | the same, a refusal × 0.4 | 16 | 79 |
/// | the same, a refusal × 0.45 | 15 | 106 |
/// | the same, a refusal × 0.55 | 11 | 61 |
/// | the same, a refusal × 0.6 | 11 | 43 |
/// | the same, halving, first radius ‖D p‖ | 14 | 47 |
/// | MINPACK's non-decreasing column norms (`D_k = max(D_k−1, ‖J_i‖)`), halving | 12 | 53 |
/// | MINPACK's non-decreasing column norms, quartering | 22 | 50 |
/// | none (scipy's `x_scale = 1` in log parameters), quartering | 18 | 107 |
/// | none, halving | 30 | 115 |
/// | column norms, quartering, a step at a doubled radius tried (a residual evaluation) after each accepted one that grew it | 18 | 72 |
/// | column norms, Madsen–Nielsen–Tingleff's whole rule (½ Δ when ρ < ¼, `max(Δ, 3‖δ‖)` when ρ > ¾) | 40, 4e-6 above | 70 |
///
/// Earlier rows (iterations, the quartering rule): column norms with first
/// radius ‖D p‖ 27/64; no scaling, first radius ‖p‖ 29 (4e-6 above)/104
/// (2.6 % above); Coleman–Li `√(p − lower)` (scipy's TRF) 17 (7e-6
/// above)/44 (1.6 % above); MINPACK's radius update 27/60; the directional
/// stop only after a Gauss–Newton step 22/38. **The displacement count is
/// erratic in the shrink factor** (0.45: 106, 0.5: 15, 0.55: 61): its
/// narrow valley is crossed in few steps only when the radius happens to
/// fit it, so 15 is a lucky point of one series from one start, not a
/// margin; the velocity count falls steadily from 0.45 on (15, 13, 11,
/// 11). Halving is the textbook factor, and of those measured only 0.5
/// and 0.6 meet both counts. Not tried:
/// geodesic acceleration (Transtrum & Sethna 2012) and Broyden's rank-1
/// updates of J between evaluations both need J or `Jᵀv` for a new vector,
/// and LM's problems hand it only `JᵀJ` and `Jᵀr` (`LeastSquares::normal`,
/// the modal form never stores J); a rank-1 update would also not be a
/// Jacobian in scipy's `njev` sense.
///
/// **Why Nielsen's damping (the default) needs more** (traced 2026-11-29,
/// λ and gain ratio ρ of every trial): on the velocity objective it
/// reaches 1.4e-4 above the optimum at its 7th Jacobian, then creeps with
/// ρ between 0.74 and 0.93, where Nielsen's factor `max(⅓, 1 − (2ρ − 1)³)`
/// lowers λ by only 0.88–0.95 per step (λ from 1.5e-3 to 1.6e-5 of
/// `diag(JᵀJ)` over 16 steps of 6e-2 to 1e-3 in ln θ): 24. On the
/// displacement objective it enters a curved valley at its 12th Jacobian
/// (45 % above the optimum) and follows it for 60 steps of 1–3 % in ln θ
/// (ρ 0.65–0.8, λ 3e-4 falling to 2e-7): 77; the trust region's 15 come
/// from another early path that lands on the optimum from the other side
/// without entering that valley (the luck the table above shows). Nielsen's update with a faster fall
/// of λ after a good step, tried in turn (velocity, displacement): ÷3
/// whenever ρ > ¾ 22, 74; ÷10 whenever ρ > ¾ 20, 75; at most ½ whenever
/// ρ > ½ 21, 84; ÷3 whenever ρ > ½ 19, 77: the velocity count falls to
/// near scipy's 18, the displacement one does not move, so the step rule
/// alone does not cross the valley.
#[test]
fn velocity_iterations_are_no_more_than_scipy_trf_jacobians() {
    compare("velocity", None);
}

#[test]
fn displacement_iterations_are_no_more_than_scipy_trf_jacobians() {
    compare("displacement", None);
}

/// The trust region (halving), not the default, meets the count too.
#[test]
fn the_trust_region_needs_no_more_than_scipy_trf_either() {
    compare("velocity", Some(Damping::TrustRegion));
    compare("displacement", Some(Damping::TrustRegion));
}

/// Not in issue 44's count (velocity and displacement): on the acceleration
/// objective the trust region takes 10 Jacobians against scipy's 24 but
/// stops (its directional rule) 1.6e-4 above scipy's optimum (quartering:
/// 29 Jacobians, 2.1e-4 above), so the like-for-like comparison fails.
#[test]
#[ignore = "open: stops 1.6e-4 above scipy's optimum on the acceleration objective"]
fn acceleration_iterations_are_no_more_than_scipy_trf_jacobians() {
    compare("acceleration", None);
}

/// Issue 44 item 6 as the identification runs it: the search of
/// `identify` (`bumpsim_ident::estimate::search_of`, the study's own
/// settings, unchanged) from its one start, the default one, counted and
/// checked against `identify` itself (the same objective and iterations,
/// bit for bit, where no prior is stated). One start in all is one LM run
/// to the full tolerances (`multistart::alone`, since 2026-11-30), and
/// since 2026-11-30 (06:00) that run takes the geodesic acceleration
/// whatever the solver's `acceleration` (its limit if given, else
/// `lm::ACCELERATION_LIMIT`): **17 Jacobians against scipy's 18 (velocity)
/// and 41 against 60 (displacement)**. Before, with the solver's plain
/// steps (the default of `lm::Settings`, which the multi-start stages keep),
/// 23 and 76; before that a screening run (relative decrease 1e-6) and a
/// polish of its optimum restarting LM's damping, 31 and 76.
#[test]
fn the_identifications_own_start_needs_no_more_than_scipy_trf_jacobians() {
    searched("velocity");
    searched("displacement");
}

/// The identification's own search from its default start, counted.
fn searched(objective: &str) {
    let Some(out) = series() else { return };
    let mut study = Study::read(&out.join("study.toml")).unwrap();
    study.identification.objective = Some(objective.into());
    let cases = study.cases(3).unwrap();
    let settings = study.settings(3).unwrap();
    assert_eq!(settings.solver.acceleration, None, "the solver's default");
    assert_eq!(settings.starts, 1, "the default start alone");
    let (jacobians, products) = (AtomicUsize::new(0), AtomicUsize::new(0));
    let make = || Counted {
        objective: Objective::new(&cases, 3, &settings.bounds.fixed),
        jacobians: &jacobians,
        products: &products,
    };
    let found = search_of(&cases, &settings, &make, &|| {}).unwrap();
    let best = found.best();
    let identified = bumpsim_ident::identify(&cases, &settings, &|| {}).unwrap();
    if identified.stated.is_empty() {
        assert_eq!(best.objective, identified.objective, "identify's own run");
        assert_eq!(best.iterations, identified.iterations, "identify's own run");
    }
    let counts = (jacobians.into_inner(), products.into_inner());
    let label = format!("{objective}, the identification's search");
    against_scipy(
        &out,
        objective,
        &label,
        &data_start(&cases, 3),
        best,
        counts,
    );
}

/// Checks `outcome` (from `start`, SI) and its `(jacobians, products)`
/// against scipy TRF's count and optimum on the same objective.
fn against_scipy(
    out: &Path,
    objective: &str,
    label: &str,
    start: &[f64],
    outcome: &Outcome,
    (jacobians, products): (usize, usize),
) {
    let (njev, value) = trf(out, objective, start);
    eprintln!(
        "{label}: bumpsim {jacobians} Jacobians ({} iterations, {} residual evaluations, {products} products), objective {:e} ({:?}); scipy TRF {njev} Jacobians, {value:e}",
        outcome.iterations, outcome.evaluations, outcome.objective, outcome.stop
    );
    assert!(
        (outcome.objective / value - 1.0).abs() < 1e-9,
        "{label}: objective {:e} against scipy's {value:e}",
        outcome.objective
    );
    assert!(
        jacobians <= njev,
        "{label}: {jacobians} Jacobians against scipy's {njev}"
    );
}
