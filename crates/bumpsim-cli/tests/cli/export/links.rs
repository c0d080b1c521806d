//! `bumpsim export` of a car file with nonlinear links (issue 46;
//! examples/links/car.toml): both decks through the export crate's chain
//! writers, the CalculiX deck run in `ccx`, and the commands that read
//! linear cars only refusing the file with exit code 2.

use super::{ccx_available, ccx_histories, dyna_core, dyna_core_available};
use crate::util::*;
use bumpsim_core::chain::{Drive, Frame};
use bumpsim_io::link_car::LinkCar;
use std::path::Path;

fn links_car() -> std::path::PathBuf {
    root().join("examples/links/car.toml")
}

/// A half-sine push on m1: 150 kN for 30 ms, then 50 ms at rest, every
/// 0.1 ms (it yields the tabulated link, 60 kN at 20 mm); as CSV and samples.
fn push(dir: &Path) -> (std::path::PathBuf, Vec<f64>) {
    let samples: Vec<f64> = (0..=800)
        .map(|k| {
            let t = k as f64 * 1e-4;
            match t < 0.03 {
                true => 1.5e5 * (std::f64::consts::PI * t / 0.03).sin(),
                false => 0.0,
            }
        })
        .collect();
    let mut csv = String::from("time [s],force [N]\n");
    for (k, f) in samples.iter().enumerate() {
        csv.push_str(&format!("{:.4},{f}\n", k as f64 * 1e-4));
    }
    let path = dir.join("push.csv");
    std::fs::write(&path, csv).unwrap();
    (path, samples)
}

#[test]
fn both_decks_of_a_car_with_links_are_written_by_the_chain_writers() {
    let dir = scratch("export-links");
    let car = links_car();
    let deck = dir.join("car.k");
    let run = bumpsim(&[
        "export",
        "lsdyna",
        car.to_str().unwrap(),
        "-o",
        deck.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("critical explicit time step of the car alone: 2.813 ms"));
    let k = std::fs::read_to_string(&deck).unwrap();
    // yielding front link and tabulated link: inelastic; progressive elastic
    assert_eq!(k.matches("*MAT_SPRING_INELASTIC").count(), 2, "{k}");
    assert_eq!(k.matches("*MAT_SPRING_NONLINEAR_ELASTIC").count(), 1, "{k}");
    let inp = dir.join("car.inp");
    let run = bumpsim(&[
        "export",
        "calculix",
        car.to_str().unwrap(),
        "-o",
        inp.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let deck = std::fs::read_to_string(&inp).unwrap();
    assert!(
        deck.contains("*PLASTIC") && deck.contains("EFRONT"),
        "{deck}"
    );
}

#[test]
fn commands_for_linear_cars_refuse_a_car_with_links() {
    let car = links_car();
    let run = bumpsim(&[
        "simulate",
        "--car",
        car.to_str().unwrap(),
        "--force",
        example("pendulum-force.csv").to_str().unwrap(),
        "-o",
        scratch("links-refused").join("r.csv").to_str().unwrap(),
    ]);
    assert_user_error(&run, "a chain with nonlinear links");
    assert_user_error(
        &run,
        "`bumpsim export lsdyna` and `bumpsim export calculix` read this file",
    );
    let bumper = root().join("examples/impact/bumper-a.toml");
    let run = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--bumper",
        bumper.to_str().unwrap(),
        "--barrier",
        "--speed",
        "15 km/h",
    ]);
    // impact runs such a car (the engine's request) but has no use for a bumper file
    assert_user_error(
        &run,
        "--bumper: a car with nonlinear links carries its crush zone in its own file",
    );
}

/// Both CalculiX decks of the example (the transient under a push on m1)
/// run cleanly in ccx and read back as three finite mass histories, the
/// yielding links' bricks included. (Their motion is compared with
/// `Chain::run` in barrier runs by bumpsim-export's tests/chain_decks.rs.)
#[test]
fn the_calculix_deck_of_a_car_with_links_runs_in_ccx() {
    if !ccx_available() {
        return;
    }
    let dir = scratch("export-links-ccx");
    let (force, samples) = push(&dir);
    let inp = dir.join("car.inp");
    let car = links_car();
    let run = bumpsim(&[
        "export",
        "calculix",
        car.to_str().unwrap(),
        "--force",
        force.to_str().unwrap(),
        "-o",
        inp.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let (header, rows) = ccx_histories(&dir);
    assert_eq!(header, ["time [s]", "x1 [m]", "x2 [m]", "x3 [m]"]);
    // ccx prints from the first increment on
    assert_eq!(rows.len() + 1, samples.len());
    assert!(rows.iter().flatten().all(|v| v.is_finite()));
    // pushed rearwards, every mass has moved rearwards by the end
    let last = rows.last().unwrap();
    assert!(last[1..].iter().all(|x| *x > 0.0), "{last:?}");
}

/// Without its front link (which pulls in ccx, never in bumpsim) the
/// example's CalculiX transient follows `Chain::run` under the same push:
/// every mass within 2 % of m1's peak displacement, the tabulated link
/// yielding. At the default 0.1 m node spacing: the springs are `SPRING2`
/// on the axis's degree of freedom, which a crush beyond the spacing does
/// not turn over (the `SPRINGA`s before them did: a linear car of the same
/// masses under this push put ccx's m1 35 % beyond `simulate` and scipy's
/// `solve_ivp` at 10 ms).
#[test]
fn without_its_front_link_the_calculix_run_follows_chain_run() {
    if !ccx_available() {
        return;
    }
    let dir = scratch("export-links-chain-run");
    let full = std::fs::read_to_string(links_car()).unwrap();
    let (head, rest) = full.split_once("[front]").unwrap();
    let car_text = format!("{head}{}", &rest[rest.find("[[links]]").unwrap()..]);
    let car_path = dir.join("car.toml");
    std::fs::write(&car_path, &car_text).unwrap();
    let car = LinkCar::parse(&car_text, &car_path).unwrap();
    assert!(car.chain.front().is_none());
    let (force, samples) = push(&dir);
    let inp = dir.join("car.inp");
    let run = bumpsim(&[
        "export",
        "calculix",
        car_path.to_str().unwrap(),
        "--force",
        force.to_str().unwrap(),
        "-o",
        inp.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let (_, theirs) = ccx_histories(&dir);
    let drive = Drive::Force {
        force: &samples,
        step: 1e-4,
        initial_velocity: 0.0,
        frame: Frame::Rearward,
    };
    let ours = car.chain.run(&drive).unwrap();
    assert!(ours.plastic_set[1] > 1e-3, "{:?}", ours.plastic_set);
    // the progressive link 1 crushes beyond the 0.1 m between its nodes
    let crush = (ours.displacement[0].iter().zip(&ours.displacement[1]))
        .fold(0.0_f64, |m, (x1, x2)| m.max(x1 - x2));
    assert!(crush > 0.1, "link 1's largest crush {crush} m");
    // ccx prints from the first increment on: its row k is our sample k + 1
    assert_eq!(theirs.len() + 1, ours.displacement[0].len());
    let peak = ours.displacement[0]
        .iter()
        .fold(0.0_f64, |m, x| m.max(x.abs()));
    for mass in 0..3 {
        let worst = theirs
            .iter()
            .zip(&ours.displacement[mass][1..])
            .fold(0.0_f64, |m, (row, x)| m.max((row[mass + 1] - x).abs()));
        assert!(
            worst <= 0.02 * peak,
            "m{} differs by {worst} m, m1's peak {peak} m",
            mass + 1
        );
    }
}

/// The example's LS-DYNA include parses in ansys-dyna-core: every keyword
/// read, no id undefined, the inelastic and nonlinear elastic springs there.
#[test]
fn the_lsdyna_include_of_a_car_with_links_parses_in_dyna_core() {
    if !dyna_core_available() {
        return;
    }
    let dir = scratch("export-links-dyna");
    let deck = dir.join("car.k");
    let car = links_car();
    let args = [
        "export",
        "lsdyna",
        car.to_str().unwrap(),
        "-o",
        deck.to_str().unwrap(),
    ];
    let run = bumpsim(&args);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let verdict = dyna_core(&deck, &[]);
    for empty in ["unprocessed", "errors", "undefined"] {
        assert_eq!(verdict[empty], serde_json::json!([]), "{empty}: {verdict}");
    }
    let keywords = verdict["keywords"].to_string();
    for kind in [
        "MatSpringInelastic",
        "MatSpringNonlinearElastic",
        "MatDamperViscous",
    ] {
        assert!(keywords.contains(kind), "{kind} missing: {keywords}");
    }
}

/// The links car of the wall-link tests: the example's masses and links,
/// a second load path on m2 (a table, elastic along it) after 150 mm and a
/// rebound link on m3 (progressive, elastic) after 100 mm.
const WALLED: &str = r#"kind = "links"
name = "links car with a second load path and a rebound link"
masses = ["6 kg", "180 kg", "1250 kg"]
dampers = ["0.5 Ns/mm", "2 Ns/mm"]

[front]
curve = "bilinear"
stiffness = "1500 N/mm"
yield_force = "80 kN"
hardening = 0.05
unloading = "2000 N/mm"

[[links]]
curve = "progressive"
stiffness = "500 N/mm"
limit = "300 mm"
limit_force = "420 kN"
unloading = "elastic"

[[links]]
curve = "table"
points = [["20 mm", "60 kN"], ["120 mm", "110 kN"], ["400 mm", "140 kN"]]
unloading = "4000 N/mm"

[path]
mass = 2
gap = "150 mm"
curve = "table"
points = [["30 mm", "60 kN"], ["200 mm", "120 kN"], ["800 mm", "150 kN"]]
unloading = "elastic"

[rebound]
mass = 3
gap = "100 mm"
curve = "progressive"
stiffness = "200 N/mm"
limit = "500 mm"
limit_force = "725 kN"
unloading = "elastic"
"#;

/// The number before `unit` in the line of `text` that starts with `label`.
fn printed(text: &str, label: &str, after: &str, unit: &str) -> f64 {
    let line = text
        .lines()
        .find(|l| l.trim_start().starts_with(label))
        .unwrap_or_else(|| panic!("no '{label}' in {text}"));
    let rest = &line[line.find(after).unwrap() + after.len()..];
    rest[..rest.find(unit).unwrap()].trim().parse().unwrap()
}

/// What ccx shows of a links car's barrier run beside `bumpsim impact
/// --barrier`: the peak barrier force (N), the front link's and the second
/// path's plastic sets (m), and each wall-side link's largest force (front,
/// path, rebound; N).
struct AgainstImpact {
    ccx_peak: f64,
    impact_peak: f64,
    ccx_sets: [f64; 2],
    impact_sets: [f64; 2],
    most: [f64; 3],
    /// What `export` printed on stderr (its warnings).
    warnings: String,
}

/// Runs the car at `car_path` into the barrier at `speed` (km/h) for
/// `samples` steps of 0.1 ms in `impact --barrier` and as a CalculiX deck
/// (every mass at −speed along the axis, a zero force, the front link on
/// the held barrier node) in ccx; ccx's side: the car's links replayed on
/// ccx's crush histories (the front link on m1's, each wall link on its
/// mass's past its gap), as bumpsim reads a crush.
fn against_impact(dir: &Path, car_path: &Path, speed: f64, samples: usize) -> AgainstImpact {
    let text_of_car = std::fs::read_to_string(car_path).unwrap();
    let car = LinkCar::parse(&text_of_car, car_path).unwrap();
    let speed = format!("{speed} km/h");
    let impact = bumpsim(&[
        "impact",
        "--car",
        car_path.to_str().unwrap(),
        "--barrier",
        "--speed",
        &speed,
    ]);
    assert!(impact.status.success(), "{}", text(&impact.stderr));
    let out = text(&impact.stdout);
    let impact_peak = 1e3 * printed(&out, "peak barrier force", "force", "kN");
    let set = |label: &str| 1e-3 * printed(&out, label, "plastic set", "mm");
    let path_set = match car.chain.path() {
        Some(p) if matches!(p.link.unloading(), bumpsim_core::link::Unloading::Slope(_)) => {
            set("second load path")
        }
        _ => 0.0,
    };
    let impact_sets = [set("front link (crush zone)"), path_set];
    let mut csv = String::from("time [s],force [N]\n");
    for k in 0..=samples {
        csv.push_str(&format!("{:.4},0\n", k as f64 * 1e-4));
    }
    let force = dir.join("rest.csv");
    std::fs::write(&force, csv).unwrap();
    let inp = dir.join("car.inp");
    let run = bumpsim(&[
        "export",
        "calculix",
        car_path.to_str().unwrap(),
        "--initial-velocity",
        &format!("-{speed}"),
        "--force",
        force.to_str().unwrap(),
        "-o",
        inp.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let warnings = text(&run.stderr);
    let (_, rows) = ccx_histories(dir);
    assert_eq!(rows.len(), samples, "ccx runs to the end");
    let chain = &car.chain;
    let (front, p, r) = (
        chain.front().unwrap(),
        chain.path().unwrap(),
        chain.rebound().unwrap(),
    );
    let mut states = [bumpsim_core::link::LinkState::default(); 3];
    let mut most = [0.0_f64; 3];
    let wall = rows.iter().map(|row| {
        let [a, b, c] = &mut states;
        let forces = [
            front.force(-row[1], a),
            p.link.force(-row[1 + p.mass] - p.gap, b),
            r.link.force(-row[1 + r.mass] - r.gap, c),
        ]
        .map(|f| f.max(0.0));
        for (m, f) in most.iter_mut().zip(forces) {
            *m = m.max(f);
        }
        forces.iter().sum::<f64>()
    });
    let ccx_peak = wall.fold(0.0_f64, f64::max);
    AgainstImpact {
        ccx_peak,
        impact_peak,
        ccx_sets: [states[0].plastic_set(front), states[1].plastic_set(&p.link)],
        impact_sets,
        most,
        warnings,
    }
}

/// A links car with a second load path and a rebound link exported to
/// CalculiX as a barrier run and run in ccx ([`against_impact`]): the
/// peak barrier force and the front link's residual crush within 2 % of
/// `bumpsim impact --barrier`.
#[test]
fn a_car_with_wall_links_in_ccx_reproduces_impact_within_two_percent() {
    if !ccx_available() {
        return;
    }
    let dir = scratch("export-links-walls");
    let car_path = dir.join("car.toml");
    std::fs::write(&car_path, WALLED).unwrap();
    let c = against_impact(&dir, &car_path, 40.0, 2500);
    let ([theirs, peak], [their_set, set]) = (
        [c.ccx_peak, c.impact_peak],
        [c.ccx_sets[0], c.impact_sets[0]],
    );
    eprintln!("walls: ccx {theirs} N, set {their_set} m; impact {peak} N, set {set} m");
    assert!(
        c.most[1] > 1e4 && c.most[2] > 1e4,
        "both wall links act: {:?} N",
        c.most
    );
    assert!(
        (theirs - peak).abs() <= 0.02 * peak,
        "peak {theirs} N, impact {peak} N"
    );
    assert!(
        (their_set - set).abs() <= 0.02 * set,
        "set {their_set} m, impact {set} m"
    );
}

/// Issue 46's "exported decks run" on the real car: the car `identify
/// --car` writes for NHTSA 10146 (a 20-knot front table that softens to
/// 0.1 kN, a yielding second path from 0 m, a yielding rebound link after
/// 0.69 m) exported to CalculiX at the test's 57.09 km/h and run for
/// 150 ms: ccx runs to the end, and the peak barrier force and the
/// residual crush of the front link and of the second path lie within
/// 2 % of `bumpsim impact --barrier`. (Before: ccx stopped at 28.4 ms.)
#[test]
fn the_identified_nhtsa_car_in_ccx_reproduces_impact_within_two_percent() {
    if !ccx_available() {
        return;
    }
    let Some(ev5) = nhtsa_ev5() else { return };
    let dir = scratch("export-links-nhtsa");
    let study = crate::identify_links::links_study(&dir, &ev5);
    let car_path = dir.join("car.toml");
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--car",
        car_path.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let c = against_impact(&dir, &car_path, 57.09, 1500);
    // its front table softens at 1.43e7 N/m, steeper than its unloading:
    // a fall asks no stiffer unloading of the solvers, so every link is exact
    assert!(!c.warnings.contains("APPROXIMATE"), "{}", c.warnings);
    eprintln!(
        "nhtsa: ccx {} N, sets {:?} m; impact {} N, sets {:?} m; largest forces {:?} N",
        c.ccx_peak, c.ccx_sets, c.impact_peak, c.impact_sets, c.most
    );
    assert!(
        c.most.iter().all(|f| *f > 1e4),
        "every wall-side link acts: {:?} N",
        c.most
    );
    assert!(
        (c.ccx_peak - c.impact_peak).abs() <= 0.02 * c.impact_peak,
        "peak {} N, impact {} N",
        c.ccx_peak,
        c.impact_peak
    );
    for (theirs, ours) in c.ccx_sets.iter().zip(c.impact_sets) {
        assert!(ours > 0.1, "a set worth comparing: {ours} m");
        assert!(
            (theirs - ours).abs() <= 0.02 * ours,
            "set {theirs} m, impact {ours} m"
        );
    }
}

/// The same car's LS-DYNA include parses in ansys-dyna-core with every id
/// defined; the path's curve (id 3n + 3 = 12) is zero up to its 150 mm gap
/// and in tension.
#[test]
fn the_lsdyna_include_of_a_car_with_wall_links_parses_in_dyna_core() {
    if !dyna_core_available() {
        return;
    }
    let dir = scratch("export-links-walls-dyna");
    let car_path = dir.join("car.toml");
    std::fs::write(&car_path, WALLED).unwrap();
    let deck = dir.join("car.k");
    let run = bumpsim(&[
        "export",
        "lsdyna",
        car_path.to_str().unwrap(),
        "-o",
        deck.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let verdict = dyna_core(&deck, &[]);
    for empty in ["unprocessed", "errors", "undefined"] {
        assert_eq!(verdict[empty], serde_json::json!([]), "{empty}: {verdict}");
    }
    // force against elongation: compression beyond the gap, zero before
    // it and in tension
    let curve = |id: &str| -> Vec<[f64; 2]> {
        let points = verdict["curves"][id].as_array().expect(id);
        let value = |v: &serde_json::Value, i: usize| v[i].as_f64().unwrap();
        points.iter().map(|p| [value(p, 0), value(p, 1)]).collect()
    };
    let path = curve("12");
    let at = path.iter().position(|p| p[0] == -0.15).expect("the gap");
    assert!(path[at..].iter().all(|p| p[1] == 0.0), "{path:?}");
    assert!(path[..at].iter().all(|p| p[1] < 0.0), "{path:?}");
    assert_eq!(path.last(), Some(&[10.0, 0.0]));
    assert!(
        verdict["curves"]["13"].is_array(),
        "the rebound link's curve"
    );
}
