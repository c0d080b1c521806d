//! The Sobol' indices of the verdict's criteria (issue 39, item 3) against
//! an independent route: the exact variance decomposition of the 49 CFR
//! 581 barrier test's bumper crush over the bumper's force scale and the
//! body's mass, by Gauss–Hermite quadrature of deterministic verdicts on
//! cars built through the public constructors (not through the
//! uncertainty's name→part mapping); a parameter the test cannot feel
//! (the tyres' lateral friction in a square full-width impact) has a total
//! index of zero; the indices do not depend on the thread count; hostile
//! settings are refused naming the option.

use bumpsim_estimate::sobol::Settings;
use bumpsim_verdict::prelude::*;
use bumpsim_verdict::protocol::select;
use bumpsim_verdict::sensitivity::{Sensitivity, sensitivity};
use std::path::{Path, PathBuf};

fn example() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/verdict/car.toml")
}

fn end() -> CarEnd {
    let car = bumpsim_planar::PlanarCar::read(&example()).unwrap();
    CarEnd::new(car, Damageability::read(&example()).unwrap()).unwrap()
}

fn setup(end: CarEnd) -> Setup {
    Setup::new(vec![end], select(&["part581-barrier-front"]).unwrap(), 0.0).unwrap()
}

/// Probabilists' Gauss–Hermite rule of 7 points (Abramowitz & Stegun
/// 25.4.46 scaled to N(0, 1)): exact for polynomials to degree 13.
const NODES: [f64; 7] = [
    -3.750_439_717_725_742,
    -2.366_759_410_734_541,
    -1.154_405_394_739_968,
    0.0,
    1.154_405_394_739_968,
    2.366_759_410_734_541,
    3.750_439_717_725_742,
];
const WEIGHTS: [f64; 7] = [
    5.482_688_559_722_184e-4,
    3.075_712_396_758_65e-2,
    0.240_123_178_605_012_7,
    0.457_142_857_142_857_1,
    0.240_123_178_605_012_7,
    3.075_712_396_758_65e-2,
    5.482_688_559_722_184e-4,
];

/// The bumper crush of the barrier test with the bumper's force scaled by
/// `force` and the body's mass by `mass`.
fn crush(force: f64, mass: f64) -> f64 {
    let e = end();
    let segments = e.car.beam().segments.iter();
    let scaled = segments.map(|s| bumpsim_planar::car::scaled(s, force).unwrap());
    let e = e.with_segments(scaled.collect()).unwrap();
    let c = &e.car;
    let mut body = *c.body();
    body.mass *= mass;
    let (left, right, beam) = (c.left().clone(), c.right().clone(), c.beam().clone());
    let car = bumpsim_planar::PlanarCar::new(body, left, right, beam, *c.tyres()).unwrap();
    let e = CarEnd::new(car, e.limits.clone()).unwrap();
    let v = bumpsim_verdict::verdict(&setup(e)).unwrap();
    let c = v.tests[0]
        .criteria
        .iter()
        .find(|c| c.name == "bumper stroke");
    c.unwrap().value
}

/// Exact first-order indices of (force, mass) by quadrature:
/// `Var(E[Y | Xᵢ]) / Var(Y)`.
fn exact(sd: [f64; 2]) -> [f64; 2] {
    let grid: Vec<Vec<f64>> = (NODES.iter())
        .map(|zf| {
            let row = NODES
                .iter()
                .map(|zm| crush((sd[0] * zf).exp(), (sd[1] * zm).exp()));
            row.collect()
        })
        .collect();
    let mean = |f: &dyn Fn(usize, usize) -> f64| {
        let cells = (0..7).flat_map(|i| (0..7).map(move |j| (i, j)));
        cells
            .map(|(i, j)| WEIGHTS[i] * WEIGHTS[j] * f(i, j))
            .sum::<f64>()
    };
    let m = mean(&|i, j| grid[i][j]);
    let variance = mean(&|i, j| (grid[i][j] - m).powi(2));
    let conditional = |i: usize, by_force: bool| {
        let cell = |k: usize| if by_force { grid[i][k] } else { grid[k][i] };
        (0..7).map(|k| WEIGHTS[k] * cell(k)).sum::<f64>()
    };
    let first = |by_force: bool| {
        let v = (0..7).map(|i| WEIGHTS[i] * (conditional(i, by_force) - m).powi(2));
        v.sum::<f64>() / variance
    };
    [first(true), first(false)]
}

fn uncertainty(spreads: &[(&str, f64)]) -> Uncertainty {
    let spreads = spreads.iter().map(|(n, s)| (n.to_string(), *s)).collect();
    Uncertainty::independent("spreads", spreads).unwrap()
}

fn indices(u: &Uncertainty, settings: &Settings) -> Sensitivity {
    let setup = setup(end());
    let v = bumpsim_verdict::verdict(&setup).unwrap();
    sensitivity(&setup, &v, u, settings, &|| {}).unwrap()
}

#[test]
fn the_gauss_hermite_rule_integrates_the_normal_moments() {
    let moment = |p: i32| (0..7).map(|k| WEIGHTS[k] * NODES[k].powi(p)).sum::<f64>();
    for (p, exact) in [
        (0, 1.0),
        (2, 1.0),
        (4, 3.0),
        (6, 15.0),
        (8, 105.0),
        (12, 10395.0),
    ] {
        assert!(
            (moment(p) - exact).abs() < 1e-12 * exact,
            "E z^{p} = {}",
            moment(p)
        );
    }
}

/// The bumper crush's indices equal the quadrature's within 0.05 and
/// within their bootstrap half-widths (S1 0.784 ± 0.21 against 0.805,
/// ST 0.811 ± 0.19 against 0.807 for the force; the mass's 0.197 ± 0.11
/// and 0.193 ± 0.05 against 0.193); the tyres' lateral friction has no
/// share: its total index is 0 within its half-width.
#[test]
fn the_crush_indices_equal_the_exact_decomposition_and_an_unused_parameter_has_none() {
    let sd = [0.15, 0.1];
    let u = uncertainty(&[
        ("bumper.force", sd[0]),
        ("body.mass", sd[1]),
        ("tyres.mu_lateral", 0.3),
    ]);
    let s = indices(&u, &Settings::new(128, 1));
    assert_eq!(s.evaluations, 128 * 5);
    let c = s.criteria.iter().find(|c| c.criterion == "bumper stroke");
    let i = c.unwrap().indices.as_ref().unwrap();
    let exact = exact(sd);
    assert!(exact[0] > 0.3 && exact[1] > 0.1, "both matter: {exact:?}");
    for k in 0..2 {
        let (ours, conf) = (i.first[k], i.first_conf[k]);
        assert!(
            (ours - exact[k]).abs() <= conf.min(0.05),
            "{}: S1 {ours} ± {conf} against the quadrature's {}",
            i.names[k],
            exact[k]
        );
        // two inputs matter: ST of one is 1 − S1 of the other
        let (total, conf) = (i.total[k], i.total_conf[k]);
        let expected = 1.0 - exact[1 - k];
        assert!(
            (total - expected).abs() <= conf.min(0.05),
            "{}: ST {total} ± {conf} against {expected}",
            i.names[k]
        );
    }
    assert!(
        i.total[2].abs() <= i.total_conf[2].max(1e-9) && i.total[2].abs() < 1e-3,
        "the lateral friction: ST {} ± {}",
        i.total[2],
        i.total_conf[2]
    );
}

/// The same indices on one thread and on four.
#[test]
fn the_indices_do_not_depend_on_the_thread_count() {
    let u = uncertainty(&[("bumper.force", 0.1)]);
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| indices(&u, &Settings::new(16, u64::MAX)))
    };
    assert_eq!(run(1), run(4));
}

#[test]
fn hostile_settings_are_refused_naming_the_option() {
    let setup = setup(end());
    let v = bumpsim_verdict::verdict(&setup).unwrap();
    let u = uncertainty(&[("bumper.force", 0.1)]);
    for base in [0, 1, 15, 8193, usize::MAX] {
        let e = sensitivity(&setup, &v, &u, &Settings::new(base, 1), &|| {}).unwrap_err();
        assert!(e.to_string().starts_with("sobol-base = "), "{base}: {e}");
    }
    // the Sobol sequence is balanced only over a power of two
    for (base, powers) in [(17, "16 or 32"), (100, "64 or 128"), (8191, "4096 or 8192")] {
        let e = sensitivity(&setup, &v, &u, &Settings::new(base, 1), &|| {}).unwrap_err();
        let e = e.to_string();
        let head = format!("sobol-base = {base} samples: a power of two ({powers})");
        assert!(e.starts_with(&head), "{e}");
    }
    let names = ["masses", "dampers", "springs"].iter().flat_map(|w| {
        ["left", "right"].map(|side| (0..2).map(move |i| format!("{side}.{w}[{i}]")))
    });
    let many: Vec<(String, f64)> = names
        .flatten()
        .map(|n| (n, 0.1))
        .chain([("body.mass".into(), 0.1)])
        .collect();
    let u = Uncertainty::independent("many", many).unwrap();
    let e = sensitivity(&setup, &v, &u, &Settings::new(16, 1), &|| {}).unwrap_err();
    assert!(
        e.to_string()
            .contains("13 parameters: Sobol indices take at most 12"),
        "{e}"
    );
}

/// A test of an end without a car judges nothing: no indices, no verdict run.
#[test]
fn a_test_not_assessed_has_no_indices_and_runs_nothing() {
    let tests = select(&["part581-barrier-rear"]).unwrap();
    let setup = Setup::new(vec![end()], tests, 0.0).unwrap();
    let v = bumpsim_verdict::verdict(&setup).unwrap();
    let u = uncertainty(&[("bumper.force", 0.1)]);
    let runs = std::sync::atomic::AtomicUsize::new(0);
    let progress = || {
        runs.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    };
    let s = sensitivity(&setup, &v, &u, &Settings::new(16, 1), &progress).unwrap();
    assert!(s.criteria.is_empty() && s.evaluations == 0);
    assert_eq!(runs.into_inner(), 0);
}
