//! `bumpsim impact` of a car with nonlinear links (issue 46): the engine's
//! request runs the chain of `bumpsim_core::chain` into the rigid barrier;
//! its figures are checked against the chain run directly, the energy
//! balance against ½ M V², and the options it has no use for are refused
//! by name with exit code 2. A pendulum into the car is checked against
//! an independent integration of the same chain (scipy, tests/peers).

use crate::util::*;
use bumpsim_core::chain::Drive;
use bumpsim_io::link_car::LinkCar;

mod pendulum;

const SPEED: f64 = 15.0 / 3.6;

#[test]
fn impact_runs_a_links_car_into_the_barrier_with_its_plastic_set_and_energy_balance() {
    let dir = scratch("impact-links");
    let car = root().join("examples/links/car.toml");
    let (json, csv, report) = (dir.join("r.json"), dir.join("r.csv"), dir.join("report"));
    let run = bumpsim(&[
        "impact",
        "--car",
        car.to_str().unwrap(),
        "--barrier",
        "--speed",
        "15 km/h",
        "--json",
        json.to_str().unwrap(),
        "--csv",
        csv.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "links example: yielding crash boxes, 3 masses: rigid barrier at 15.00 km/h\n",
            "  peak barrier force ",
            "  front link (crush zone): largest compression ",
            "  link 2: largest compression ",
            "plastic set ",
            "dissipated ",
        ],
    );
    // the same chain run directly: the request's figures are its figures
    let chain = LinkCar::parse(&std::fs::read_to_string(&car).unwrap(), &car)
        .unwrap()
        .chain;
    let doc: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let samples = doc["contact_time"].as_f64().unwrap() / 1e-4;
    let direct = chain
        .run(&Drive::Barrier {
            speed: SPEED,
            step: 1e-4,
            samples: samples as usize + 10,
        })
        .unwrap();
    let peak = direct.force.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    let close = |a: f64, b: f64, what: &str| {
        assert!(
            (a - b).abs() <= 1e-9 * b.abs().max(1e-9),
            "{what}: {a} vs {b}"
        );
    };
    close(doc["peak_force"].as_f64().unwrap(), peak, "peak force");
    let links = doc["links"].as_array().unwrap();
    assert_eq!(links[0]["name"], "front");
    for (j, set) in direct.plastic_set.iter().enumerate() {
        close(
            links[j + 1]["plastic_set"].as_f64().unwrap(),
            *set,
            "plastic set",
        );
    }
    // the yielding crash box keeps a set; the elastic link 1 none
    assert!(links[0]["plastic_set"].as_f64().unwrap() > 0.01, "{doc}");
    assert_eq!(links[1]["plastic_set"].as_f64().unwrap(), 0.0);
    // the elastic link keeps no history: its compression is read from the samples
    assert!(
        links[1]["max_compression"].as_f64().unwrap() > 1e-4,
        "{doc}"
    );
    // the balance closes on the initial ½ M V² (1 % of it: the leapfrog's O(T²))
    let e = &doc["energy"];
    let total: f64 = chain.masses().iter().sum();
    let initial = 0.5 * total * SPEED * SPEED;
    close(e["initial"].as_f64().unwrap(), initial, "initial energy");
    let sum: f64 = ["kinetic", "stored", "viscous", "plastic", "wall"]
        .iter()
        .map(|k| e[k].as_f64().unwrap())
        .sum();
    assert!((sum - initial).abs() < 0.01 * initial, "{sum} vs {initial}");
    let dissipated = doc["dissipated"].as_f64().unwrap();
    let plastic = e["plastic"].as_f64().unwrap();
    close(
        dissipated,
        e["viscous"].as_f64().unwrap() + plastic,
        "dissipated work",
    );
    // the crash box's set was crushed at no less than its 80 kN yield force
    let set = links[0]["plastic_set"].as_f64().unwrap();
    assert!(
        plastic >= 0.9 * 80e3 * set,
        "plastic work {plastic} J, set {set} m"
    );
    assert_eq!(doc["kind"], "links");
    let (header, rows) = read_csv(&csv);
    assert_eq!(header[..2], ["time [s]", "force [N]"]);
    assert!(rows.len() as f64 >= samples, "{}", rows.len());
    for file in ["index.html", "force.svg", "energy.svg"] {
        assert!(report.join(file).is_file(), "{file}");
    }
}

#[test]
fn impact_refuses_what_a_links_car_has_no_use_for_by_name() {
    let dir = scratch("impact-links-refused");
    let car = root().join("examples/links/car.toml");
    let car = car.to_str().unwrap();
    let bumper = root().join("examples/impact/bumper-a.toml");
    let bumper = bumper.to_str().unwrap();
    let refused: &[(&[&str], &str)] = &[
        (
            &["--pendulum", "1500", "--speed", "8 km/h", "--angle", "10"],
            "--angle: a car with nonlinear links runs into a flat rigid barrier",
        ),
        (
            &["--barrier", "--speed", "8 km/h", "--bumper", bumper],
            "--bumper: a car with nonlinear links carries its crush zone",
        ),
        (
            &["--barrier", "--speed", "8 km/h", "--angle", "10"],
            "--angle: a car with nonlinear links runs into a flat rigid barrier",
        ),
        (
            &["--barrier", "--speed", "8 km/h", "--width", "1.5"],
            "--width: a car with nonlinear links",
        ),
        (&["--barrier"], "the speed is needed"),
    ];
    for (extra, needle) in refused {
        let args: Vec<&str> = ["impact", "--car", car]
            .iter()
            .chain(*extra)
            .copied()
            .collect();
        assert_user_error(&bumpsim(&args), needle);
    }
    // written before `kind = "links"`: declared as the chain, still the links chain
    let legacy = dir.join("legacy.toml");
    let file = std::fs::read_to_string(root().join("examples/links/car.toml")).unwrap();
    std::fs::write(
        &legacy,
        file.replace("kind = \"links\"", "kind = \"chain\""),
    )
    .unwrap();
    let run = bumpsim(&[
        "impact",
        "--car",
        legacy.to_str().unwrap(),
        "--barrier",
        "--speed",
        "8 km/h",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
}
