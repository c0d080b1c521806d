//! CalculiX decks of the MSD car: a run against `simulate`, and the deck
//! included in a model that has its own `Nall`.

use super::{ccx_available, ccx_histories, run_ccx};
use crate::util::*;

#[test]
fn calculix_run_of_the_exported_deck_matches_simulate() {
    if !ccx_available() {
        return;
    }
    let dir = scratch("calculix");
    let deck = dir.join("car.inp");
    let force = example("pendulum-force.csv");
    let export = bumpsim(&[
        "export",
        "calculix",
        example("car-3dof.toml").to_str().unwrap(),
        "--force",
        force.to_str().unwrap(),
        "-o",
        deck.to_str().unwrap(),
    ]);
    assert!(export.status.success(), "{}", text(&export.stderr));
    let ccx = ccx_histories(&dir);
    let sim_csv = dir.join("sim.csv");
    let sim = simulate(
        &example("car-3dof.toml"),
        &force,
        &["-o", sim_csv.to_str().unwrap()],
    );
    assert!(sim.status.success());
    let ((_, ours), (header, theirs)) = (read_csv(&sim_csv), ccx);
    assert_eq!(&header[..2], ["time [s]", "x1 [m]"]);
    // ccx prints from the first increment on: its row k is our row k + 1
    assert_eq!(theirs.len() + 1, ours.len());
    let peak = ours.iter().fold(0.0_f64, |m, r| m.max(r[2].abs()));
    let mut worst = 0.0_f64;
    for (a, b) in theirs.iter().zip(&ours[1..]) {
        assert!((a[0] - b[0]).abs() < 1e-9, "time {} vs {}", a[0], b[0]);
        worst = worst.max((a[1] - b[2]).abs());
    }
    assert!(
        worst <= 0.01 * peak,
        "m1 differs by {worst} m, peak {peak} m"
    );
}

/// ccx's equation count and the bumper's lateral displacements (nodes 2, 3)
/// of `main.inp` in `dir` with `include` pasted before the step.
fn bumper_under_lateral_load(
    dir: &std::path::Path,
    name: &str,
    include: &str,
) -> (usize, Vec<f64>) {
    let deck = format!(
        "*NODE, NSET=Nall\n1, 0.0, 0.0, 0.0\n2, 0.0, 1.0, 0.0\n3, 0.0, 2.0, 0.0\n\
         *ELEMENT, TYPE=SPRINGA, ELSET=Ebumper\n1, 1, 2\n2, 2, 3\n*SPRING, ELSET=Ebumper\n\n1000.0\n\
         *BOUNDARY\n1, 1, 3\nNall, 1, 1\nNall, 3, 3\n{include}\
         *STEP\n*STATIC\n*CLOAD\n3, 2, 10.0\n*NODE PRINT, NSET=Nall\nU\n*END STEP\n"
    );
    std::fs::write(dir.join(format!("{name}.inp")), deck).unwrap();
    let log = run_ccx(dir, name);
    let equations = log
        .split("number of equations")
        .nth(1)
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("{name}: no equation count in {log}"));
    let dat = std::fs::read_to_string(dir.join(format!("{name}.dat"))).unwrap();
    let lateral = dat
        .lines()
        .map(|l| l.split_whitespace().collect::<Vec<_>>())
        .filter(|w| w.len() == 4 && (w[0] == "2" || w[0] == "3"))
        .map(|w| w[2].parse().unwrap())
        .collect();
    (equations, lateral)
}

#[test]
fn a_calculix_car_included_in_a_model_with_its_own_nall_leaves_that_model_alone() {
    if !ccx_available() {
        return;
    }
    let dir = scratch("calculix-include");
    let car = example("car-3dof.toml");
    let export = |prefix: &str| {
        let run = bumpsim(&[
            "export",
            "calculix",
            car.to_str().unwrap(),
            "-o",
            dir.join("car.inp").to_str().unwrap(),
            "--id-offset",
            "1000",
            "--initial-velocity",
            "1",
            "--prefix",
            prefix,
        ]);
        assert!(run.status.success(), "{}", text(&run.stderr));
    };
    // the bumper alone: two springs of 1000 N/m in y under 10 N
    let (alone, response) = bumper_under_lateral_load(&dir, "alone", "");
    assert_eq!(response.len(), 2);
    assert!(
        (response[0] - 0.01).abs() < 1e-9 && (response[1] - 0.02).abs() < 1e-9,
        "{response:?}"
    );
    // with the car included (its last mass grounded by the user: a static step)
    export("BUMPSIM_");
    let include = "*INCLUDE, INPUT=car.inp\n*BOUNDARY\n1003, 1, 1\n";
    let (with_car, response_with_car) = bumper_under_lateral_load(&dir, "with-car", include);
    assert_eq!(
        with_car,
        alone + 2,
        "the car adds its two free masses' x only"
    );
    assert_eq!(response_with_car.len(), 2);
    for (a, b) in response.iter().zip(&response_with_car) {
        assert!(
            (a - b).abs() <= 1e-12 * a.abs(),
            "{response:?} vs {response_with_car:?}"
        );
    }
    // control: without a prefix the car's set is NALL, the user's Nall: the
    // car's cross-axis constraints then hold the bumper, as before issue 16
    export("");
    let (clashed, clashed_response) = bumper_under_lateral_load(&dir, "clashed", include);
    assert!(clashed < with_car && clashed_response.iter().all(|u| u.abs() < 1e-12));
}

/// Issue 34: `read-calculix car.inp -o car.dat` replaced the results it
/// reads (the `.dat` beside the deck is an input as much as the deck).
#[test]
fn read_calculix_never_writes_over_the_results_it_reads() {
    let dir = scratch("calculix-own-dat");
    let deck = dir.join("car.inp");
    let export = bumpsim(&[
        "export",
        "calculix",
        example("car-3dof.toml").to_str().unwrap(),
        "-o",
        deck.to_str().unwrap(),
    ]);
    assert!(export.status.success(), "{}", text(&export.stderr));
    let dat = dir.join("car.dat");
    std::fs::write(&dat, "the results of a long run\n").unwrap();
    std::fs::hard_link(&dat, dir.join("linked.csv")).unwrap();
    for output in ["car.dat", "./car.dat", "linked.csv"] {
        let path = dir.join(output);
        let read = bumpsim(&[
            "export",
            "read-calculix",
            deck.to_str().unwrap(),
            "-o",
            path.to_str().unwrap(),
        ]);
        assert_user_error(&read, "would overwrite the input");
        assert_eq!(
            std::fs::read_to_string(&dat).unwrap(),
            "the results of a long run\n"
        );
    }
}

/// A linear car that crushes far beyond the default 0.1 m node spacing
/// (issue 46: ccx's m1 35 % off with `SPRINGA`s, whose force acts along the
/// current line between the nodes and turns over once they cross): its
/// deck, run in ccx under `bumpsim impact`'s barrier force on m1 at the
/// impact's speed, reproduces the impact's link forces and the crush left
/// at its end within 2 %, along a negative axis at the default spacing.
#[test]
fn a_crush_beyond_the_node_spacing_runs_as_impact_does() {
    if !ccx_available() {
        return;
    }
    let dir = scratch("calculix-deep-crush");
    let (car, bumper) = (dir.join("car.toml"), dir.join("bumper.toml"));
    let springs = [1.5e5, 3.0e5];
    std::fs::write(
        &car,
        "name = \"soft\"\nmasses = [300.0, 400.0, 800.0]\ndampers = [3000.0, 5000.0]\nsprings = [1.5e5, 3.0e5]\n",
    )
    .unwrap();
    std::fs::write(
        &bumper,
        "name = \"soft\"\nramp = 2.0e6\nplateau = 60.0e3\nunloading = 4.0e6\n",
    )
    .unwrap();
    let impact_csv = dir.join("impact.csv");
    let path = |p: &std::path::Path| p.to_str().unwrap().to_string();
    let run = bumpsim(&[
        "impact",
        "--car",
        &path(&car),
        "--bumper",
        &path(&bumper),
        "--barrier",
        "--speed",
        "30 km/h",
        "--csv",
        &path(&impact_csv),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let (header, ours) = read_csv(&impact_csv);
    let column = |name: &str| header.iter().position(|h| h == name).unwrap();
    let x = ["x m1 [m]", "x m2 [m]", "x m3 [m]"].map(column);
    let force_csv = dir.join("force.csv");
    let rows: String = ours
        .iter()
        .map(|r| format!("{},{}\n", r[0], r[1]))
        .collect();
    std::fs::write(&force_csv, format!("time [s],force [N]\n{rows}")).unwrap();
    let deck = dir.join("car.inp");
    let speed = format!("{}", -30.0 / 3.6);
    let export = bumpsim(&[
        "export",
        "calculix",
        &path(&car),
        "--force",
        &path(&force_csv),
        "--initial-velocity",
        &speed,
        "--axis=-y",
        "-o",
        &path(&deck),
    ]);
    assert!(export.status.success(), "{}", text(&export.stderr));
    let (_, theirs) = ccx_histories(&dir);
    // ccx prints from the first increment on: its row k is the impact's k + 1
    assert_eq!(theirs.len() + 1, ours.len());
    // crush of link j: the impact along the travel, ccx along the model's +x (rearwards)
    let impact_crush = |r: &Vec<f64>, j: usize| r[x[j + 1]] - r[x[j]];
    let ccx_crush = |r: &Vec<f64>, j: usize| r[j + 1] - r[j + 2];
    for (j, k) in springs.iter().enumerate() {
        let peak = |crush: &dyn Fn(&Vec<f64>) -> f64, rows: &[Vec<f64>]| {
            rows.iter().map(|r| k * crush(r)).fold(0.0, f64::max)
        };
        let (a, b) = (
            peak(&|r| impact_crush(r, j), &ours),
            peak(&|r| ccx_crush(r, j), &theirs),
        );
        // the test would pass a SPRINGA if the crush stayed within the spacing
        assert!(a / k > 0.15, "link {}: crush {} m", j + 1, a / k);
        assert!(
            (b - a).abs() <= 0.02 * a,
            "link {}: peak force {b} N in ccx, {a} N in impact",
            j + 1
        );
        let (a, b) = (
            impact_crush(ours.last().unwrap(), j),
            ccx_crush(theirs.last().unwrap(), j),
        );
        assert!(
            (b - a).abs() <= 0.02 * a.abs(),
            "link {}: crush at the end {b} m in ccx, {a} m in impact",
            j + 1
        );
    }
}
