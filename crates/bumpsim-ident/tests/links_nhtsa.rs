//! Issue 46 on NHTSA test 10146 (2018 Camry, 57 km/h into the load-cell
//! barrier): the chain with yielding links against the linear chain on the
//! example study, and the identified car alone run into a rigid barrier at
//! the test's speed; the plastic sets print with their intervals.
//!
//! Why the force-driven chain (the first test) cannot predict the barrier,
//! with its numbers (2 masses, 8 starts): it applies the measured barrier
//! force to m1 and sees only the crossmember, so m1 and the first link are
//! free to do whatever moves the crossmember right. Its best fit (98.75 %)
//! puts m1 at its 100 kg bound, the damper c1 and k1 at theirs (100
//! kN/mm; before the law's fix 99 kN/mm with an interval over six
//! decades), and throws m1 through its link (plastic set 1015 mm,
//! interval ±962 m; before 1017 mm, ±375 m): m1 rebounds while the
//! prescribed force still pushes it. The front zone read off m1's travel
//! then rebuilds a barrier force that fits 1.8 % and a crossmember ΔV of
//! −21.97 m/s for −18.43 (19.2 % off, the unloading returns the energy;
//! before the link law kept a bilinear link elastic until it yields:
//! 1.4 % and −22.06 m/s).
//! The masses sum to 1759 kg; the test sheet's 1719 kg was not used.
//!
//! The second test identifies the car as it ran into the barrier
//! (`links::into_wall`): the wall force and the crossmember in one
//! objective, each channel scaled by a stated model-error floor (10 % of
//! the wall force's spread, 1 % of the crossmember's: the default
//! weighting; the one-path car [`PLAIN`] by its own residual, maximum
//! likelihood), the sheet's mass as a prior, the front zone a tabulated
//! curve whose knots follow its reach. Its forward run is the identified
//! car, so force and ΔV are what it fits (numbers at the tests).
//!
//! What the two channels say, measured on the raw data (the 174 valid
//! barrier Fx cells summed, the accelerometers integrated from 57.09 km/h,
//! pre-trigger bias removed; numbers without the CFC 60 filter):
//!
//! - **The mass.** Over 0–120 ms the barrier's impulse is 32.86 kN·s and
//!   the crossmember's ΔV −18.43 m/s: 1783 kg against the sheet's 1719
//!   (+3.7 %). It is not the crossmember's place in the car: at 290 ms,
//!   long after separation, the impulse is 32.42 kN·s, the crossmember's
//!   ΔV −18.13 m/s (1788 kg) and the engine's (channel 95, top of engine)
//!   −17.80 m/s (1821 kg): both accelerometers put the car's ΔV at
//!   17.8–18.1 m/s where the cells over the sheet's mass give 18.9. The
//!   load cells' sum and the sheet's mass disagree by 4–6 %. With the mass
//!   held to the sheet, a wall force of a perfect shape but 3.7 % low
//!   would fit 93.9 %: that much of the 90 % target is spent before any
//!   shape error.
//! - **A second load path.** The engine's accelerometer falls from
//!   13.4 m/s at 20 ms to −1.4 m/s at 40 ms (about 100 g) and then stays
//!   near rest (0.44 m of travel, −0.5 m/s until 120 ms) while the
//!   crossmember goes on to 0.745 m at 75 ms and rebounds at −2.5 m/s; the
//!   wall force's 600–700 kN peak at 28–35 ms is the engine striking the
//!   barrier, and the crossmember's deceleration dips while it does.
//!   Kamal's engine path.
//! - **After separation.** The force falls below 35 kN after 100 ms and
//!   to zero by 120 ms: a tail of 100 → 0 kN over the body's last 70 mm of
//!   rebound, softer than the crush zone's first unloading (450 → 100 kN
//!   over about 25 mm, 75–90 ms). One unloading slope per link follows one
//!   of the two; the identified cars drop to zero at 85–92 ms.
//!
//! The data are read from `../shared` beside the repository or from
//! `$BUMPSIM_SHARED`; the test skips with a message when they are absent.

use bumpsim_core::chain::Drive;
use bumpsim_estimate::observer::Silent;
use bumpsim_ident::links::barrier::BarrierSettings;
use bumpsim_ident::links::weighting::{FLOOR, Weighting};
use bumpsim_ident::links::{Layout, LinkSettings, identify, text};
use bumpsim_ident::{Settings, Study, identify as identify_linear};
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The example study with its data paths pointing at the shared folder.
fn study() -> Option<Study> {
    let shared = std::env::var_os("BUMPSIM_SHARED").map_or(root().join("../shared"), PathBuf::from);
    let ev5 = shared.join("data/nhtsa-10146/v10146.EV5");
    if !ev5.exists() {
        eprintln!(
            "SKIPPED: {} is absent (NHTSA test 10146 is read from ../shared or $BUMPSIM_SHARED)",
            ev5.display()
        );
        return None;
    }
    let text = std::fs::read_to_string(root().join("examples/nhtsa-10146/study.toml")).unwrap();
    let text = text.replace("../../../shared", shared.to_str().unwrap());
    // one folder per call: the tests run in parallel threads of one process,
    // and one's write must not truncate the file the other reads
    static CALLS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let call = CALLS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let dir =
        std::env::temp_dir().join(format!("bumpsim-links-nhtsa-{}-{call}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("study.toml");
    std::fs::write(&path, text).unwrap();
    Some(Study::read(&path).unwrap())
}

#[test]
fn nhtsa_10146_with_yielding_links_fits_and_predicts_the_barrier() {
    let Some(study) = study() else { return };
    let dof: usize = std::env::var("LINKS_DOF")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(2);
    let cases = study.cases(dof).unwrap();
    let case = &cases[0];
    let linear = identify_linear(
        &cases,
        &Settings {
            starts: 8,
            ..study.settings(dof).unwrap()
        },
        &|| {},
    )
    .unwrap();
    let peak = case.force.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    let layout = Layout { dof };
    let start = layout.start_from(&linear.model, 0.5 * peak);
    let starts = std::env::var("LINKS_STARTS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(8);
    let mut settings = LinkSettings::new(dof, starts, start);
    // m1 carries the front structure and the engine: at least 100 kg (a
    // lighter m1 lets the force past the yield throw it through the car)
    settings.lower[0] = 100.0;
    settings.start[0] = settings.start[0].max(100.0);
    let found = identify(&cases, &settings, &Silent).unwrap();
    println!(
        "linear fit {:.2} %\n{}",
        linear.cases[0].fit_percent,
        text(&found)
    );
    let fit = found.fits[0].1;
    let verdict = bumpsim_ident::links::verdict::compare(&linear, &found);
    println!("{}", verdict.reasons.join("\n"));
    // forward: the identified car alone into a rigid wall at the test's speed
    let samples = case.force.len();
    let drive = Drive::Barrier {
        speed: case.initial_velocity,
        step: case.step,
        samples,
    };
    let _ = drive;
    let run = found
        .forward(case.initial_velocity, case.step, samples)
        .unwrap();
    let (a, b) = case.window;
    let force_fit = bumpsim_estimate::fit::percent(&run.force[a..=b], &case.force[a..=b]);
    let last = dof - 1;
    let h = case.step;
    let measured_dv = (case.measured[b] - case.measured[b - 1]) / h - case.initial_velocity;
    let predicted_dv = run.velocity[last][b] - case.initial_velocity;
    let dv_error = (predicted_dv - measured_dv).abs() / measured_dv.abs();
    println!(
        "forward into a rigid wall at {:.2} m/s: force fit {force_fit:.2} %, crossmember ΔV {predicted_dv:.3} m/s (measured {measured_dv:.3} m/s, {:.2} % off)",
        case.initial_velocity,
        100.0 * dv_error
    );
    // measured on this test (2 DOF, 8 starts): fit 98.75 % against the
    // linear chain's 96.52 %, and BIC on the effective residuals prefers
    // the yielding links. Its forward run is printed, not asserted (force
    // fit 1.8 %, ΔV 19.2 % off: see the module); the car identified into
    // the barrier (the second test) is the one that predicts.
    assert!(fit >= 98.5, "fit {fit} %");
    assert!(fit > linear.cases[0].fit_percent + 2.0);
    assert!(verdict.yielding, "{:?}", verdict.reasons);
    assert!(run.force.iter().all(|f| f.is_finite() && *f <= 0.0));
    assert!(
        run.energy_error() < 0.01,
        "forward energy balance {}",
        run.energy_error()
    );
    assert_eq!(found.plastic_sets.len(), dof - 1);
}

/// What the car identified into the barrier gives: its fit %, the
/// forward run's force fit % and crossmember ΔV error (fraction), and the
/// identification.
struct Barrier {
    fit: f64,
    force_fit: f64,
    dv_error: f64,
    found: bumpsim_ident::links::LinkIdentification,
}

/// How the car is identified into the barrier: front knots, second-path
/// knots (0: none), the rebound link's mass (1-based, 0: none), starts,
/// the spread of the sheet's mass prior (sd of ln M) and the channels'
/// weighting (`LINKS_SCALES` overrides it).
struct Config {
    knots: usize,
    path_knots: usize,
    rebound: usize,
    starts: usize,
    spread: f64,
    weighting: Weighting,
}

/// 16 front knots, no second path, no rebound link, 4 starts, the sheet's
/// mass ±1 %, each channel weighted by its own residual (maximum
/// likelihood: this one-path car follows the crossmember, not the force).
const PLAIN: Config = Config {
    knots: 16,
    path_knots: 0,
    rebound: 0,
    starts: 4,
    spread: 0.01,
    weighting: Weighting::Likelihood,
};

/// Kamal's two paths with the force's tail: 20 front knots on m1, an
/// 8-knot second path from the body, a rebound link on the body, 12
/// starts, the sheet's mass ±0.3 %.
const TWO_PATHS: Config = Config {
    knots: 20,
    path_knots: 8,
    rebound: 2,
    starts: 12,
    spread: 0.003,
    weighting: Weighting::Floor(FLOOR),
};

/// The channels' weighting ([`bumpsim_ident::links::weighting`]):
/// `LINKS_SCALES=ml` each channel's own residual (maximum likelihood),
/// `signal` each channel's spread (a floor of 1 for both),
/// `floor:F,Y` a model-error floor of F of the force's spread and Y of
/// the crossmember's, `default` the library's (10 % of the force's, 1 % of
/// the crossmember's: `weighting::FLOOR`); the configuration's otherwise.
fn weighting(config: &Config) -> Weighting {
    let var = std::env::var("LINKS_SCALES").unwrap_or_default();
    match var.as_str() {
        "ml" => Weighting::Likelihood,
        "signal" => Weighting::Floor([1.0, 1.0]),
        floor if floor.starts_with("floor:") => {
            let f: Vec<f64> = floor[6..].split(',').map(|v| v.parse().unwrap()).collect();
            Weighting::Floor([f[0], *f.last().unwrap()])
        }
        "default" => Weighting::default(),
        _ => config.weighting.clone(),
    }
}

/// The car identified as it ran into the barrier (`links::into_wall`):
/// the wall force and the crossmember together, the test sheet's 1719 kg
/// as a prior, 2 masses, as `config` says (`LINKS_DOF`, `LINKS_KNOTS`,
/// `LINKS_STARTS`, `LINKS_PATH_KNOTS`, `LINKS_REBOUND`,
/// `LINKS_MASS_SPREAD`, `LINKS_SEED` change it; `LINKS_DUMP=file` writes the measured
/// and forward force and crossmember). The forward run into a rigid wall
/// is the identified car itself.
fn barrier(config: &Config) -> Option<Barrier> {
    let study = study()?;
    let number = |name: &str, default: usize| {
        std::env::var(name)
            .ok()
            .and_then(|v| v.parse().ok())
            .unwrap_or(default)
    };
    let (dof, knots, starts) = (
        number("LINKS_DOF", 2),
        number("LINKS_KNOTS", config.knots),
        number("LINKS_STARTS", config.starts),
    );
    let cases = study.cases(dof).unwrap();
    let case = &cases[0];
    let linear = identify_linear(
        &cases,
        &Settings {
            starts: 8,
            ..study.settings(dof).unwrap()
        },
        &|| {},
    )
    .unwrap();
    let peak = case.force.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    let start = Layout { dof }.start_from(&linear.model, 0.5 * peak);
    let mut links = LinkSettings::new(dof, starts, start);
    links.lower[0] = 100.0;
    links.start[0] = links.start[0].max(100.0);
    links.seed = number("LINKS_SEED", 1) as u64;
    let mass = study.sheet_mass().unwrap().unwrap();
    // the test sheet weighs the car: ±1 % (`LINKS_MASS_SPREAD` widens it)
    let spread = std::env::var("LINKS_MASS_SPREAD")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(config.spread);
    let settings = BarrierSettings {
        links,
        knots,
        front_start: None,
        path_knots: number("LINKS_PATH_KNOTS", config.path_knots),
        // LINKS_REBOUND=j: a rebound link on mass j (1-based), 0 none
        rebound: number("LINKS_REBOUND", config.rebound).checked_sub(1),
        sheet_mass: Some((mass, spread)),
        path_start: None,
        rebound_start: None,
        weighting: weighting(config),
    };
    let settings = match std::env::var("LINKS_FROM").as_deref() {
        // one start at the optimum of [`TWO_PATHS`] (its settings, the
        // variables above aside): a polishing of it under this objective
        Ok("two-paths") => {
            let two = |v: f64| if v == 0.0 { None } else { Some(v as usize - 1) };
            let from = BarrierSettings {
                links: LinkSettings {
                    starts: TWO_PATHS.starts,
                    ..settings.links.clone()
                },
                knots: TWO_PATHS.knots,
                path_knots: TWO_PATHS.path_knots,
                rebound: two(TWO_PATHS.rebound as f64),
                sheet_mass: Some((mass, TWO_PATHS.spread)),
                ..settings.clone()
            };
            let optimum =
                bumpsim_ident::links::into_wall::identify(&cases, &from, &Silent).unwrap();
            println!("the two paths' optimum:\n{}", text(&optimum));
            let mut again = bumpsim_ident::links::into_wall::started_at(&optimum, &settings);
            again.links.starts = 1;
            again
        }
        _ => settings,
    };
    let mut found = bumpsim_ident::links::into_wall::identify(&cases, &settings, &Silent).unwrap();
    if let Some(mass) = number("LINKS_REBOUND_AFTER", 0).checked_sub(1) {
        let again = bumpsim_ident::links::into_wall::with_rebound(&found, &settings, mass);
        println!("first stage:\n{}", text(&found));
        found = bumpsim_ident::links::into_wall::identify(&cases, &again, &Silent).unwrap();
    }
    println!(
        "linear fit {:.2} %\n{}",
        linear.cases[0].fit_percent,
        text(&found)
    );
    let run = found
        .forward(case.initial_velocity, case.step, case.window.1 + 1)
        .unwrap();
    let (a, b) = case.window;
    let force_fit = bumpsim_estimate::fit::percent(&run.force[a..=b], &case.force[a..=b]);
    let h = case.step;
    let measured_dv = (case.measured[b] - case.measured[b - 1]) / h - case.initial_velocity;
    let predicted_dv = run.velocity[dof - 1][b] - case.initial_velocity;
    let dv_error = (predicted_dv - measured_dv).abs() / measured_dv.abs();
    println!(
        "forward into a rigid wall at {:.2} m/s: force fit {force_fit:.2} %, crossmember ΔV {predicted_dv:.3} m/s (measured {measured_dv:.3} m/s, {:.2} % off)",
        case.initial_velocity,
        100.0 * dv_error
    );
    if let Some(path) = std::env::var_os("LINKS_DUMP") {
        // time s, measured and forward wall force N, crossmember m (measured,
        // forward), m1 m
        let y = &run.displacement[dof - 1];
        let rows: String = (a..=b)
            .map(|k| {
                let t = k as f64 * h;
                let (f, g, m) = (case.force[k], run.force[k], case.measured[k]);
                let x1 = run.displacement[0][k];
                format!("{t},{f},{g},{m},{},{x1}\n", y[k])
            })
            .collect();
        std::fs::write(path, rows).unwrap();
    }
    // the likelihood with each channel's variance at its maximum (its
    // scale s: n ln s per channel) and the prior: comparable between
    // optima whose objectives are scaled differently
    let lengths = [case.window_len(), case.residual_len()];
    let concentrated: f64 = found
        .scales
        .iter()
        .map(|s| lengths[0] as f64 * s[0].ln() + lengths[1] as f64 * s[1].ln())
        .sum::<f64>()
        + found.moved.iter().map(|m| 0.5 * m.z * m.z).sum::<f64>();
    println!("concentrated negative log-likelihood {concentrated:.2} (scales in SI)");
    // the barrier's impulse over the crossmember's ΔV: the mass the two
    // channels imply, against the test sheet's
    let impulse: f64 = case.force[a..=b].iter().sum::<f64>() * h;
    println!(
        "barrier impulse {impulse:.0} N·s over the crossmember's ΔV: {:.0} kg (test sheet {mass:.0} kg)",
        impulse / measured_dv
    );
    assert!(
        run.energy_error() < 0.01,
        "energy balance {}",
        run.energy_error()
    );
    Some(Barrier {
        fit: found.fits[0].1,
        force_fit,
        dv_error,
        found,
    })
}

/// Issue 46's acceptance where it holds (measured, 2 masses, 16 knots, 4
/// starts, with the link law elastic below its elastic limit): the
/// crossmember fits 99.07 % (the linear chain 96.52 %), the forward run's
/// crossmember ΔV is 0.47 % off (−18.52 for −18.43 m/s), the plastic sets
/// print with their intervals (front zone 503.6 mm [476.8, 530.4], link 1
/// 213.1 mm [187.5, 238.6]) and the test sheet's mass is kept (1744 kg,
/// +1.5 prior sd). The forward force fits 83.60 %: see the test below.
/// (Exact Jacobian, round 4; with forward differences 99.07 %, 0.44 %,
/// 83.58 %, the same optimum.)
/// (Before the law's fix, which took a set of a bilinear link
/// before it yielded: 99.71 %, 0.88 %, force 82.0 %.)
#[test]
fn nhtsa_10146_identified_into_the_barrier_fits_and_predicts_delta_v() {
    let Some(b) = barrier(&PLAIN) else { return };
    assert!(b.fit >= 99.0, "fit {} %", b.fit);
    assert!(b.dv_error <= 0.03, "ΔV {} % off", 100.0 * b.dv_error);
    assert!(b.force_fit >= 75.0, "force fit {} %", b.force_fit);
    for set in &b.found.plastic_sets {
        let [lo, hi] = set
            .ci95
            .unwrap_or_else(|| panic!("{set:?} has no interval"));
        // a crush zone's set between nothing and a metre, its interval holding it
        assert!(
            lo <= set.value && set.value <= hi && (-1e-9..1.0).contains(&set.value),
            "{set:?}"
        );
    }
    assert!(
        b.found.moved.iter().all(|m| m.z.abs() < 3.0),
        "{:?}",
        b.found.moved
    );
}

/// Issue 46's forward force (≥ 90 %) together with the rest, measured
/// (round 5, the default weighting: a model-error floor of 10 % of the
/// wall force's spread and 1 % of the crossmember's, `weighting::FLOOR`;
/// searched under the first start's residual scales, polished under the
/// floors) on [`TWO_PATHS`]: crossmember 99.70 %, forward force 92.48 %,
/// ΔV 0.77 % off, the plastic sets with their intervals (front zone
/// 594.9 mm [569.4, 620.4], second path 741.9 mm [739.1, 744.6], rebound
/// link 1.1 mm [−11.2, 13.5], link 1 0), the masses 1767 kg: +2.8 % over
/// the sheet (+9.2 sd of its ±0.3 % prior), between the sheet's 1719 kg
/// and the load cells' impulse over the crossmember's ΔV (1783 kg), as
/// asserted. (Round 4, each channel scaled by its own residual: 99.48 %,
/// 92.65 %, 0.24 %, 1749 kg.)
///
/// **The weighting, decided (round 5).** Each row a variant of the round-4
/// table below (2 masses, seed 1, release build); crossmember fit /
/// forward force / ΔV off / masses (prior sd); ✗ where the acceptance or
/// the test's mass bound (−1 %..+3.7 %) fails:
///
/// | variant | likelihood (round 4) | floors 10 % / 1 % (the default) | one floor of 5 % | signal spread (round 4) |
/// |---|---|---|---|---|
/// | [`TWO_PATHS`] | 99.48 / 92.65 / 0.24 / 1749 | 99.70 / 92.48 / 0.77 / 1767 (+9.2) | 97.24 ✗ / 94.79 / 1.61 / 1801 ✗ | 96.21 ✗ / 93.12 / 2.58 / 1719 |
/// | no rebound | 99.55 / 88.76 ✗ / 1.48 / 1757 | 99.42 / 90.08 / 1.12 / 1759 (+7.7) | 96.04 ✗ / 93.77 / 0.49 / 1805 ✗ | 96.32 ✗ / 92.25 / 1.72 / 1720 |
/// | ±0.5 % | 99.76 / 87.82 ✗ / 0.37 / 1778 | 99.53 / 90.22 / 0.89 / 1786 ✗ (+7.7), the front's set without interval ✗ | 97.35 ✗ / 94.40 / 1.76 / 1759 | 96.03 ✗ / 90.30 / 0.37 / 1721 |
/// | 16 knots | 99.88 / 89.15 ✗ / 0.40 / 1719 | 99.74 / 91.62 / 0.98 / 1723 (+0.7) | 99.07 / 93.72 / 0.19 / 1771 | 94.95 ✗ / 90.72 / 1.98 / 1720 |
/// | 16 knots, no rebound | 99.02 / 89.82 ✗ / 0.00 / 1732 | 99.38 / 89.35 ✗ / 0.75 / 1760 (+7.9) | 94.84 ✗ / 93.86 / 1.04 / 1816 ✗ | 95.22 ✗ / 90.62 / 1.32 / 1720 |
/// | 16 knots, ±1 % | 99.84 / 90.22 / 0.48 / 1735 | 99.71 / 91.39 / 0.21 / 1815 ✗ (+5.4) | 95.78 ✗ / 94.36 / 0.08 / 1824 ✗ | 95.23 ✗ / 90.63 / 1.01 / 1726 |
/// | 16 knots, rebound on m1 | 99.79 / 91.25 / 0.70 / 1734 | 99.73 / 91.81 / 0.54 / 1728 (+1.7) | 97.51 ✗ / 93.04 / 3.79 ✗ / 1750 | 98.36 ✗ / 93.11 / 1.43 / 1719 |
/// | [`PLAIN`] (one path) | 99.08 / 83.60 ✗ / 0.47 / 1744 | 99.25 / 80.77 ✗ / 0.14 / 1773 (+3.1) | 94.70 ✗ / 88.98 ✗ / 3.53 ✗ / 1843 ✗ | 95.03 ✗ / 91.61 / 0.87 / 1729 |
/// | [`PLAIN`], rebound on m1 | 96.72 ✗ / 91.51 / 2.20 / 1808 ✗ | 97.53 ✗ / 81.21 ✗ / 0.51 / 1775 | 95.13 ✗ / 89.32 ✗ / 2.30 / 1825 ✗ | – |
///
/// On the seven two-path variants the floors hold the crossmember ≥ 99 %
/// in all seven and the force ≥ 90 % in six (the likelihood three, the
/// signal spread none at ≥ 99 %); ΔV stays within 1.2 %. Why this rule:
/// on a crash test the residual is model error, not noise, so each
/// channel's scale is the error a lumped car is expected to leave in it,
/// stated (the load cells' sum carries the structure's ripple, the doubly
/// integrated crossmember is smooth), with the pre-trigger noise in
/// quadrature; the likelihood instead lets the channel fitted best
/// outweigh the other, and one floor for both (5 %, or the signal spread
/// with its prior then dominant) gives up the crossmember. The floors
/// searched from the start (not under the first start's residual scales)
/// stopped the 16-knot car at 96.45 % / 76.37 % and [`PLAIN`] at 97.52 % /
/// 80.91 %. Still open: the masses leave the test's bound in two variants
/// (the floors weigh the load cells, whose impulse says 1783 kg, more),
/// one variant's force is 89.35 %, and a third mass (a rate term) was not
/// measured in time (a 3-mass run did not finish in 15 min on the loaded
/// machine). [`PLAIN`] keeps the likelihood: one path does not reach 90 %
/// under any rule, and its test is the crossmember's.
///
/// Where the force was lost (`LINKS_DUMP`, [`PLAIN`], 83.58 %), each
/// 10 ms window's share of the force's squared error: 0–10 ms 9 % (the
/// first knot's 52 kN where the bumper gives 10–45 kN), 40–60 ms 34 %
/// and 70–80 ms 15 % (m1 stops crushing at 65 ms at 544 mm while the
/// body goes on to 746 mm: from 40 ms on m1 moves 58 mm, under two knots,
/// so a wall force read off m1's crush alone cannot follow the 45 Hz
/// ripple nor hold 460–490 kN to 73 ms), 90–120 ms 29 % (one unloading
/// slope ends the force at 93 ms, the measured tail runs to 117 ms).
/// Loading to the peak (10–40 ms) is 6 %. So the loss is the second
/// path's (the body's crush into the wall) and the tail's, not the
/// loading curve's nor the rate's.
///
/// The variants (`LINKS_*`; a rebound link on mass j: elastic–perfectly
/// plastic, plateau `Ft`, slope `kt`, gap `gt`), 2 masses, seed 1, each
/// channel scaled by its own residual (`LINKS_SCALES=ml`), measured in round 4 with the exact Jacobian (release build, 3–32 s
/// each); the forward-difference figures of round 3 in brackets where
/// they differ by more than 0.1 point:
///
/// | configuration | crossmember | forward force | ΔV off | masses (prior sd) | set intervals |
/// |---|---|---|---|---|---|
/// | [`PLAIN`] (16 knots, 4 starts, ±1 %) | 99.08 % | 83.60 % | 0.47 % | 1744 kg (+1.5) | yes |
/// | rebound on m1 | 96.72 % | 91.51 % | 2.20 % | 1808 kg (+5.0) | yes |
/// | `LINKS_REBOUND_AFTER=1` ([`PLAIN`], then the rebound link from its optimum) | 99.75 % | 80.38 % [79.76] | 0.39 % | 1772 kg (+3.1) | yes |
/// | path 8 knots, 12 starts, ±0.3 %, no rebound | 99.02 % | 89.82 % | 0.00 % | 1732 kg (+2.6) | yes |
/// | the same, rebound on m1 | 99.79 % [99.52] | 91.25 % [89.72] | 0.70 % [1.66] | 1734 kg (+2.9) [1763, +8.5] | yes [no] |
/// | the same, rebound on m2 | 99.88 % | 89.15 % | 0.40 % | 1719 kg (−0.1) | yes |
/// | the same, ±1 % | 99.84 % [99.53] | 90.22 % [86.18] | 0.48 % [1.08] | 1735 kg (+0.9) [1784, +3.7] | yes (a set of −1e-17 m) [no] |
/// | the same, 20 knots, ±0.5 % | 99.76 % [98.31] | 87.82 % [83.00] | 0.37 % [0.18] | 1778 kg (+6.8) [1734, +1.8] | yes [no] |
/// | 20 knots, path 8, 12 starts, ±0.3 %, no rebound | 99.55 % | 88.76 % | 1.48 % | 1757 kg (+7.2) | yes |
/// | [`TWO_PATHS`] (the same with the rebound on m2) | 99.48 % [99.73] | 92.65 % [90.31] | 0.24 % [1.14] | 1749 kg (+5.9) [1703, −3.1] | yes |
///
/// (The two "no gap" rows of round 3 are gone: the gap is a parameter now.)
/// **The optimum is not robust with exact derivatives either**: four of
/// the seven two-path rows stay under 90 %, and most rows are round 3's
/// to the digit, so the forward differences were not what moved it.
///
/// **Why: the objective, not the search.** `LINKS_FROM=two-paths` starts
/// one run at the [`TWO_PATHS`] optimum (its tables re-knotted to the
/// variant's, `into_wall::started_at`) and polishes it under the
/// variant's objective. Compared by the concentrated negative
/// log-likelihood `Σ n ln s` over the two channels plus the prior's
/// `z²/2` (printed; lower is better; the objectives themselves are
/// scaled differently):
///
/// | variant | its own search: force, −ln L | one run from the two paths' optimum: force, −ln L |
/// |---|---|---|
/// | [`TWO_PATHS`] itself | 92.65 %, 6164.3 | 86.47 % (crossmember 99.75 %), 6122.0 |
/// | ±0.5 % | 87.82 %, 3418.9 | 87.68 %, 5796.1 |
/// | 16 knots | 89.15 %, 2836.5 | 89.43 %, 2949.5 |
/// | 16 knots, no rebound | 89.82 %, 7411.6 | 89.87 %, 4210.9 |
/// | no rebound | 88.76 %, 3972.0 | 90.36 %, 8400.1 |
///
/// Re-polished under its own objective, the 92.65 % car walks to a
/// better likelihood that predicts the force at 86.47 %: the likelihood
/// (each channel scaled by its own residual) trades the wall force for
/// the crossmember's sub-percent residuals (its residual halved outweighs
/// the force's grown by 1.8). Where the search's own optimum beats the
/// run from the good car (±0.5 %, 16 knots, no rebound), it predicts
/// no better (the no-rebound run from the good car keeps 90.36 % at a
/// far worse likelihood). The one search miss (16 knots without rebound:
/// the run from the good car reaches a far better likelihood) gains
/// 0.05 point of force. So
/// the ≥ 90 % is the alternating scale-and-polish procedure's stopping
/// point, not the objective's optimum; a robust ≥ 90 % needs an
/// objective that weighs the wall force as the acceptance does, not more
/// starts.
///
/// **The trade-off, measured (round 4).** With each channel held at its measured
/// signal's spread instead (`LINKS_SCALES=signal`, then
/// `BarrierSettings.scales`, now `Weighting::Floor([1.0, 1.0])`, searched
/// under those scales: each channel weighed by its fit %, not
/// re-estimated):
///
/// | configuration | crossmember | forward force | ΔV off | masses (prior sd) |
/// |---|---|---|---|---|
/// | [`PLAIN`] | 95.03 % | 91.61 % | 0.87 % | 1729 kg (+0.6) |
/// | [`TWO_PATHS`] | 96.21 % | 93.12 % | 2.58 % | 1719 kg (+0.1) |
/// | the same, no rebound | 96.32 % | 92.25 % | 1.72 % | 1720 kg (+0.1) |
/// | the same, ±0.5 % | 96.03 % | 90.30 % | 0.37 % | 1721 kg (+0.2) |
/// | 16 knots | 94.95 % | 90.72 % | 1.98 % | 1720 kg (+0.2) |
/// | 16 knots, no rebound | 95.22 % | 90.62 % | 1.32 % | 1720 kg (+0.1) |
/// | 16 knots, ±1 % | 95.23 % | 90.63 % | 1.01 % | 1726 kg (+0.4) |
/// | 16 knots, rebound on m1 | 98.36 % | 93.11 % | 1.43 % | 1719 kg (0.0) |
///
/// The force holds ≥ 90 % in every variant and the sheet's mass is kept,
/// but the crossmember falls under 99 %: this 2-mass car with two paths
/// does not reach both figures at once, and the channels' weighting picks
/// the point on that front. The maximum-likelihood weighting (the
/// default until round 5) sits at the crossmember's end, where the force at 90 % is a
/// matter of where the search stops.
#[test]
fn nhtsa_10146_identified_into_the_barrier_predicts_the_force() {
    let Some(b) = barrier(&TWO_PATHS) else { return };
    assert!(b.force_fit >= 90.0, "force fit {} %", b.force_fit);
    assert!(b.fit >= 99.0, "fit {} %", b.fit);
    assert!(b.dv_error <= 0.03, "ΔV {} % off", 100.0 * b.dv_error);
    for set in &b.found.plastic_sets {
        let [lo, hi] = set
            .ci95
            .unwrap_or_else(|| panic!("{set:?} has no interval"));
        assert!(
            lo <= set.value && set.value <= hi && (-1e-9..1.0).contains(&set.value),
            "{set:?}"
        );
    }
    // the masses between the test sheet's (−1 %) and the load cells'
    // impulse over the crossmember's ΔV (1783 kg, +3.7 %): the two
    // channels' disagreement (see the module)
    let mass = &b.found.moved[0];
    let ratio = mass.estimate / mass.centre;
    assert!((0.99..=1.037).contains(&ratio), "{mass:?}");
}
