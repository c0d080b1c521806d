//! Identification with yielding links on an independent generator of
//! another family (issue 46): `tests/peers/crush_bar.py`, a bumper, a
//! crushing front bar (10 elements), the engine, a crushing rear bar (5
//! elements) and the body, with distributed mass, into a rigid wall at
//! 10 m/s (numpy only). The rear bar is quasi-statically one bilinear link
//! (stiffness 2 MN/m, yield 80 kN, hardening 0.2, unloading 6 k), the
//! truth of the identified chain's link between m1 (bumper, front bar,
//! engine, half the rear bar: 305 kg) and m2 (the body).
//!
//! Why the force-driven chain missed its intervals (evidence, measured
//! here): applying the wall force to m1 and fitting the body alone left
//! a valley along which m1 trades against the yield force, so m1 had to
//! be held; with it held the estimates came within 10 % (Fy1 81.6 kN, k1
//! 1.84 MN/m) but the 95 % intervals ([80.5, 82.8] kN) missed the truth;
//! and on the series with the bumper's contact damped (below) the same
//! search lands on another optimum (k1 0.54 MN/m, Fy1 150.6 kN: the front
//! bar's yield). The generator's undamped contact also rang the 2 kg
//! bumper off the wall (a 440 kN spike, then no force for 5 ms), which no
//! lumped car follows; a bumper beam crushes against a wall, so the
//! contact now has a critical damper.
//!
//! Identified as it ran into the wall ([`bumpsim_ident::links::into_wall`]:
//! the wall force and the body's displacement together, the total mass
//! as the test sheet's ±1 %, nothing held) the car covers its truth:
//! m1, k1, Fy1, r1 and u1 all lie within their 95 % intervals (seed 1,
//! with the link law and the generator's elements elastic until they
//! yield: m1 304.5 kg [289.5, 320.2], k1 1.986 MN/m [1.871, 2.108], Fy1
//! 79.52 kN [75.31, 83.97], r1 0.204 [0.193, 0.215], u1 6.03 [5.78,
//! 6.29]; wall force fit 90.5 %, body 99.86 %). Over noise seeds 2 to 6
//! (the ignored test) 23 of the 25 intervals hold the truth (all 25
//! before that fix); seed 6 lands on another optimum (m1 269.5 kg
//! [265.2, 273.8], Fy1 10.6 kN [2.9, 37.9]: the front bar's load taken
//! by the front table, the link nearly perfectly plastic from the start).
//!
//! Started at the truth (issue 44's lesson, [`truth_car`]), the fit leaves
//! the truth's objective for one a quarter as large (5.5006e3 → 1.3863e3:
//! the body's term 3.874e3 → 29.0, the wall force's 1.627e3 → 1.357e3),
//! but the chain hardly moves (m1 +0.10, m2 −0.38, k1 −0.03, Fy1 −0.22, r1
//! +0.42, u1 +0.06 standard errors; c1 1 → 72 N·s/m, +0.19): the lower
//! objective is the front table's (the front bar's quasi-static bilinear
//! curve is not its dynamic crush force, distributed mass and all), and
//! it predicts a held-out 7 m/s run better than the truth's own lumped car
//! (wall force 90.95 % against 83.78 %, body 99.52 % against 96.40 %). So
//! the objective points at the truth where the truth is a lumped car's,
//! and nothing needs fixing. The 12-start search from a start that knows
//! nothing of the bars reaches 1.3844e3 (0.14 % below the run from the
//! truth, 74.8 % below the truth's), but only 1 of its 12 starts reaches
//! that best (to 1e-6, and within the noise): the basin is found, not
//! often.

use bumpsim_estimate::observer::Silent;
use bumpsim_ident::LoadCase;
use bumpsim_ident::links::barrier::{BarrierLayout, BarrierObjective};
use bumpsim_ident::links::weighting::Weighting;
use bumpsim_ident::links::{LinkIdentification, LinkSettings, identify, into_wall, text};
use std::path::{Path, PathBuf};

fn series() -> Option<PathBuf> {
    seeded(1, "force-driven")
}

/// The generator's series of noise seed `seed` at its 10 m/s, in the
/// folder of the test `owner`.
fn seeded(seed: u64, owner: &str) -> Option<PathBuf> {
    at_speed(seed, 10.0, owner)
}

/// The generator's series of noise seed `seed` at `speed` m/s, written in
/// a folder of the test `owner`'s own: the tests run in parallel threads,
/// and two writing one folder race (one truncates what the other reads).
fn at_speed(seed: u64, speed: f64, owner: &str) -> Option<PathBuf> {
    if !bumpsim_peers::present(
        bumpsim_peers::python_available("numpy"),
        "python3 with numpy",
    ) {
        return None;
    }
    let name = match speed == 10.0 {
        true => format!("crush-bar-{owner}-{seed}"),
        false => format!("crush-bar-{owner}-{seed}-{speed}"),
    };
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join(name);
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/crush_bar.py");
    let args = [seed.to_string(), speed.to_string()];
    let args: Vec<&str> = match speed == 10.0 {
        true => vec![&args[0]],
        false => vec![&args[0], &args[1]],
    };
    bumpsim_peers::generated(&script, &out, &args, "truth.json");
    Some(out)
}

/// The force-driven chain (m1 held), kept for the comparison: measured
/// k1 0.54 MN/m and Fy1 150.6 kN on the damped-contact series (see the
/// module), far from the truth.
#[test]
#[ignore = "the force-driven chain misses the rear bar (k1 0.54 MN/m, Fy1 150.6 kN for 2 MN/m, 80 kN): superseded by the barrier identification below"]
fn a_crushing_bar_gives_its_yield_force_and_stiffnesses_within_their_intervals() {
    let Some(dir) = series() else { return };
    let truth: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("truth.json")).unwrap()).unwrap();
    let text_csv = std::fs::read_to_string(dir.join("crush.csv")).unwrap();
    let rows: Vec<Vec<f64>> = text_csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let step = rows[1][0] - rows[0][0];
    let n = rows.len();
    let case = LoadCase {
        name: "crush-bar".into(),
        start: 0.0,
        step,
        force: rows.iter().map(|r| r[1]).collect(),
        measured: rows.iter().map(|r| r[2]).collect(),
        output_dof: 2,
        initial_velocity: truth["speed"].as_f64().unwrap(),
        window: (0, n - 1),
        compare: Default::default(),
    };
    let total = truth["total_mass"].as_f64().unwrap();
    let peak = case.force.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    // a start that knows nothing of the bars: a quarter of the mass in front,
    // a soft link yielding at the median contact force (a crush plateau)
    let mut contact: Vec<f64> = case
        .force
        .iter()
        .filter(|f| **f < 0.0)
        .map(|f| -f)
        .collect();
    contact.sort_by(f64::total_cmp);
    let plateau = contact
        .get(contact.len() / 2)
        .copied()
        .unwrap_or(0.2 * peak);
    let start = vec![
        0.25 * total,
        0.75 * total,
        100.0,
        3e5,
        0.5 * plateau,
        0.2,
        3.0,
    ];
    // the force on m1 and the body's motion alone leave a valley along
    // which m1 trades against the yield force (the objective changes in
    // its sixth digit): m1 is held at the front's weighed mass (bumper,
    // front bar, engine and half the rear bar), as a study's `fixed` does
    let mut settings = LinkSettings::new(2, 12, start);
    let front = truth["front_mass"].as_f64().unwrap() + 1.0;
    settings.fixed[0] = Some(front);
    settings.start[0] = front;
    let found = identify(std::slice::from_ref(&case), &settings, &Silent).unwrap();
    println!("{}", text(&found));
    assert!(found.fits[0].1 > 99.0, "fit {} %", found.fits[0].1);
    let u = &found.uncertainty;
    let checks = [
        ("k1", 3, truth["stiffness"].as_f64().unwrap()),
        ("Fy1", 4, truth["yield_force"].as_f64().unwrap()),
    ];
    for (name, i, value) in checks {
        let [lo, hi] = u.ci95[i].unwrap_or_else(|| panic!("{name} has no interval"));
        let estimate = found.theta[i];
        let inside = lo <= value && value <= hi;
        println!(
            "{name}: truth {value:.4e}, estimate {estimate:.4e}, 95 % [{lo:.4e}, {hi:.4e}], truth inside: {inside}"
        );
        // the lumped chain's bias (m1 rigid, the bars' waves) is larger than
        // the noise's interval: checked against 10 % of the truth (see the
        // module); the intervals' coverage is printed, not yet reached
        assert!(
            (estimate - value).abs() <= 0.1 * value,
            "{name}: {estimate} vs truth {value}"
        );
    }
}

/// The car identified into the wall from seed `seed`'s series: each of
/// m1, k1, Fy1, r1, u1 with its truth and whether its 95 % interval holds
/// it (the series in the folder of the test `owner`).
fn covered(seed: u64, owner: &str) -> Option<Vec<(&'static str, f64, f64, bool)>> {
    let dir = seeded(seed, owner)?;
    let truth: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("truth.json")).unwrap()).unwrap();
    let case = crush_case(&dir, &truth);
    let total = truth["total_mass"].as_f64().unwrap();
    let peak = case.force.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    // a start that knows nothing of the bars: a quarter of the mass in
    // front, a soft link yielding at 30 % of the peak wall force
    let start = vec![0.25 * total, 0.75 * total, 100.0, 3e5, 0.3 * peak, 0.2, 3.0];
    let settings = bumpsim_ident::links::barrier::BarrierSettings {
        links: LinkSettings::new(2, 12, start),
        knots: 10,
        front_start: None,
        path_knots: 0,
        rebound: None,
        sheet_mass: Some((total, 0.01)),
        path_start: None,
        rebound_start: None,
        weighting: Default::default(),
    };
    let found =
        bumpsim_ident::links::into_wall::identify(std::slice::from_ref(&case), &settings, &Silent)
            .unwrap();
    println!("seed {seed}\n{}", text(&found));
    let [at_truth, best] = objectives(&case, &truth, &found);
    println!(
        "seed {seed}: the 12 starts' best objective {best:.6e} against the truth's {at_truth:.6e} ({:+.2} %); of {} starts {} reached the best to 1e-6, {} its fit within the noise",
        100.0 * (best / at_truth - 1.0),
        found.starts.total,
        found.starts.reached_best,
        found.starts.reached_best_fit
    );
    // the search finds a basin at least as deep as the truth's
    assert!(
        best <= at_truth,
        "seed {seed}: best {best} above the truth's {at_truth}"
    );
    let u = &found.uncertainty;
    let checks = [
        ("m1", 0, truth["front_mass"].as_f64().unwrap() + 1.0),
        ("k1", 3, truth["stiffness"].as_f64().unwrap()),
        ("Fy1", 4, truth["yield_force"].as_f64().unwrap()),
        ("r1", 5, truth["hardening"].as_f64().unwrap()),
        ("u1", 6, truth["unloading"].as_f64().unwrap()),
    ];
    Some(
        checks
            .into_iter()
            .map(|(name, i, value)| {
                let estimate = found.theta[i];
                let interval = u.ci95[i];
                let inside = interval.is_some_and(|[lo, hi]| lo <= value && value <= hi);
                println!(
                    "{name}: truth {value:.4e}, estimate {estimate:.4e}, 95 % {interval:?}, truth inside: {inside}"
                );
                (name, value, estimate, inside)
            })
            .collect(),
    )
}

/// Issue 46: the identified yield force and stiffness (and the rest of
/// the link, and m1) lie within their 95 % intervals of the truth; and
/// (issue 44's lesson) the multi-start's best objective is at most the
/// truth's ([`truth_car`] on the same objective). Measured (seed 1,
/// printed): best 1.384364e3 against the truth's 5.500581e3 (−74.83 %);
/// 1 of the 12 starts reached the best.
#[test]
fn a_crushing_bar_identified_into_the_wall_covers_its_truth() {
    let Some(checks) = covered(1, "covers") else {
        return;
    };
    for (name, value, estimate, inside) in checks {
        assert!(
            inside,
            "{name}: truth {value} outside the interval of {estimate}"
        );
    }
}

/// The intervals' coverage over further noise seeds (about a minute each
/// in a debug build): `cargo test -p bumpsim-ident --test links_generator
/// -- --ignored`.
#[test]
#[ignore = "five identifications: run on demand"]
fn the_intervals_cover_the_truth_over_noise_seeds() {
    let mut missed = vec![];
    for seed in 2..=6 {
        let Some(checks) = covered(seed, "seeds") else {
            return;
        };
        missed.extend(checks.into_iter().filter(|c| !c.3).map(|c| (seed, c.0)));
    }
    println!("missed: {missed:?}");
    // 25 intervals at 95 %: more than 4 misses has a chance below 1 %
    assert!(missed.len() <= 4, "{missed:?}");
}

/// The generator's series in `dir` with its truth.
fn read(dir: &Path) -> (LoadCase, serde_json::Value) {
    let truth: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("truth.json")).unwrap()).unwrap();
    (crush_case(dir, &truth), truth)
}

/// Issue 44's lesson for the barrier fit: started at the generator's
/// truth (the rear bar's link, m1 the mass ahead of its middle, c1 at its
/// bound for the undamped bars, the front table at the front bar's
/// bilinear curve), the fit must not walk away to a lower objective that
/// predicts worse. It descends (the objective at its end at most the
/// truth's, re-evaluated on the identification's own objective by
/// [`objective_at`]), stays within the truth's 95 % intervals, and on a
/// held-out run of the same generator at 7 m/s the identified car
/// predicts the wall force and the body's motion at least as well as the
/// truth's lumped car does (within 1 and 0.5 points of fit). Measured
/// (seed 1, printed): objective 5.500581e3 at the truth, 1.386337e3 at the
/// end (terms wall force, output, prior: 1.6267e3, 3.8739e3, 0 → 1.3573e3,
/// 28.98, 0.0446); the chain's parameters moved by at most 0.42 of their
/// standard errors (r1; m2 −0.38); held-out wall force 90.95 % (truth's
/// lumped car 83.78 %), body 99.52 % (96.40 %).
#[test]
fn a_barrier_fit_started_at_the_truth_stays_and_predicts_no_worse() {
    use bumpsim_ident::links::barrier::{BarrierSettings, run};
    let (Some(dir), Some(held)) = (seeded(1, "stays"), at_speed(1, 7.0, "stays")) else {
        return;
    };
    let ((case, truth), (held, _)) = (read(&dir), read(&held));
    let total = truth["total_mass"].as_f64().unwrap();
    let (layout, truth_theta) = truth_car(&case, &truth);
    let (chain, table) = truth_theta.split_at(7);
    let settings = BarrierSettings {
        links: LinkSettings::new(2, 1, chain.to_vec()),
        knots: 10,
        front_start: Some((layout.knots.clone(), table.to_vec())),
        path_knots: 0,
        rebound: None,
        sheet_mass: Some((total, 0.01)),
        path_start: None,
        rebound_start: None,
        weighting: Default::default(),
    };
    let found = into_wall::identify(std::slice::from_ref(&case), &settings, &Silent).unwrap();
    println!("started at the truth\n{}", text(&found));
    let [at_truth, end] = objectives(&case, &truth, &found);
    println!("objective at the truth {at_truth:.6e}, at the end {end:.6e}");
    let terms = [
        terms_at(&case, total, &layout, &truth_theta),
        terms_at(&case, total, &found_layout(&found), &found.theta),
    ];
    println!(
        "its terms (wall force, output, prior): at the truth [{}], at the end [{}]",
        terms[0].map(|t| format!("{t:.4e}")).join(", "),
        terms[1].map(|t| format!("{t:.4e}")).join(", ")
    );
    let names = ["m1", "m2", "c1", "k1", "Fy1", "r1", "u1"];
    for (i, name) in names.iter().enumerate() {
        let se = found.uncertainty.standard_errors[i];
        let moved = se.map(|se| (found.theta[i] - chain[i]) / se);
        println!(
            "{name}: truth {:.4e}, end {:.4e}, moved {moved:+.2?} standard errors",
            chain[i], found.theta[i]
        );
    }
    // the search descends from the truth (the re-knotting may not raise it)
    assert!(end <= at_truth, "{end} above the truth's {at_truth}");
    for (name, i) in [("m1", 0), ("k1", 3), ("Fy1", 4), ("r1", 5), ("u1", 6)] {
        let interval = found.uncertainty.ci95[i];
        assert!(
            interval.is_some_and(|[lo, hi]| lo <= chain[i] && chain[i] <= hi),
            "{name}: the fit walked from the truth {} to {} ({interval:?})",
            chain[i],
            found.theta[i]
        );
    }
    let lumped = layout.car(&truth_theta).unwrap();
    let fits = |response: &bumpsim_core::chain::ChainResponse| {
        let (a, b) = held.window;
        let force = bumpsim_estimate::fit::percent(&response.force[a..=b], &held.force[a..=b]);
        (force, held.fit(&response.displacement[1]).1)
    };
    let truth_fits = fits(&run(&held, &lumped).unwrap());
    let step = held.step;
    let found_fits = fits(
        &found
            .forward(held.initial_velocity, step, held.window.1 + 1)
            .unwrap(),
    );
    println!(
        "held-out 7 m/s: wall force {:.2} % (truth's lumped car {:.2} %), body {:.2} % ({:.2} %)",
        found_fits.0, truth_fits.0, found_fits.1, truth_fits.1
    );
    assert!(
        found_fits.0 >= truth_fits.0 - 1.0,
        "{found_fits:?} {truth_fits:?}"
    );
    assert!(
        found_fits.1 >= truth_fits.1 - 0.5,
        "{found_fits:?} {truth_fits:?}"
    );
}

/// The generator's series as a load case.
fn crush_case(dir: &Path, truth: &serde_json::Value) -> LoadCase {
    let text_csv = std::fs::read_to_string(dir.join("crush.csv")).unwrap();
    let rows: Vec<Vec<f64>> = text_csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let n = rows.len();
    LoadCase {
        name: "crush-bar".into(),
        start: 0.0,
        step: rows[1][0] - rows[0][0],
        force: rows.iter().map(|r| r[1]).collect(),
        measured: rows.iter().map(|r| r[2]).collect(),
        output_dof: 2,
        initial_velocity: truth["speed"].as_f64().unwrap(),
        window: (0, n - 1),
        compare: Default::default(),
    }
}

/// The generator's truth as the barrier identification's car: the rear
/// bar's link between m1 (the mass ahead of its middle) and the body, c1
/// at its bound (the bars are undamped), the front table at the front
/// bar's bilinear curve read at the 10 knots the identification starts
/// from; its layout and parameters (SI).
fn truth_car(case: &LoadCase, truth: &serde_json::Value) -> (BarrierLayout, Vec<f64>) {
    use bumpsim_core::link::Curve;
    let value = |key: &str| truth[key].as_f64().unwrap();
    let front = |key: &str| truth["front"][key].as_f64().unwrap();
    let (total, m1) = (value("total_mass"), value("front_mass") + 1.0);
    let chain = [
        m1,
        total - m1,
        1.0,
        value("stiffness"),
        value("yield_force"),
        value("hardening"),
        value("unloading"),
    ];
    let (knots, _) = bumpsim_ident::links::barrier::front_start(case, total, 10).unwrap();
    let bar =
        Curve::bilinear(front("stiffness"), front("yield_force"), front("hardening")).unwrap();
    let mut table: Vec<f64> = knots.iter().map(|d| bar.force(*d)).collect();
    table.push(front("unloading") * front("stiffness"));
    let layout = BarrierLayout {
        chain: bumpsim_ident::links::Layout { dof: 2 },
        knots,
        path_knots: vec![],
        rebound: None,
    };
    (layout, [&chain[..], &table].concat())
}

/// The identification's objective Σ r² (each channel over its default
/// floor's scale, the test sheet's mass prior at ±1 %) of the car `theta`
/// on `layout`: what [`into_wall::identify`] reports as `objective` for
/// its optimum, evaluated anywhere.
fn objective_at(case: &LoadCase, total: f64, layout: &BarrierLayout, theta: &[f64]) -> f64 {
    terms_at(case, total, layout, theta).iter().sum()
}

/// [`objective_at`]'s terms: the wall force's, the output's and the
/// prior's.
fn terms_at(case: &LoadCase, total: f64, layout: &BarrierLayout, theta: &[f64]) -> [f64; 3] {
    use bumpsim_estimate::lm::LeastSquares;
    use bumpsim_estimate::prior::{Prior, Priored};
    let cases = std::slice::from_ref(case);
    let scales = Weighting::default().fixed(cases).unwrap().unwrap();
    let fixed = vec![None; layout.count()];
    let objective = BarrierObjective::new(cases, layout.clone(), &fixed, scales);
    let dof = layout.chain.dof;
    let prior = Prior::sum("total mass", (0..dof).collect(), total, 0.01).unwrap();
    let problem = Priored::new(objective, vec![prior], 1.0).unwrap();
    let p: Vec<f64> = theta.iter().map(|v| v.ln()).collect();
    let mut r = vec![0.0; problem.residual_count()];
    assert!(problem.evaluate(&p, &mut r, None), "the car cannot be run");
    let square = |rows: &[f64]| rows.iter().map(|v| v * v).sum::<f64>();
    let force = case.window_len();
    let output = force + case.residual_len();
    [
        square(&r[..force]),
        square(&r[force..output]),
        square(&r[output..]),
    ]
}

/// The layout the identification `found` ended on (its front table's
/// knots after the re-knotting).
fn found_layout(found: &LinkIdentification) -> BarrierLayout {
    let Some(bumpsim_core::link::Curve::Table { points }) = found.front.as_ref().map(|f| f.curve())
    else {
        panic!("a barrier identification has a tabulated front");
    };
    BarrierLayout {
        chain: found.layout,
        knots: points[1..].iter().map(|p| p[0]).collect(),
        path_knots: vec![],
        rebound: None,
    }
}

/// The objective at the end of `found` re-evaluated by [`objective_at`]
/// (checked against the identification's own figure, to 1e-9), and the
/// truth's on the same objective.
fn objectives(case: &LoadCase, truth: &serde_json::Value, found: &LinkIdentification) -> [f64; 2] {
    let total = truth["total_mass"].as_f64().unwrap();
    let end = objective_at(case, total, &found_layout(found), &found.theta);
    assert!(
        (end - found.objective).abs() <= 1e-9 * found.objective,
        "the objective re-evaluated {end} against the identification's {}",
        found.objective
    );
    let (layout, theta) = truth_car(case, truth);
    [objective_at(case, total, &layout, &theta), end]
}
