//! The planar car's FE export (issue 15, item 6): the CalculiX deck run in
//! ccx against `drive`, the LS-DYNA include's cards and its parse in
//! ansys-dyna-core, bad options.

use super::*;

use bumpsim_planar::drive::{Drive, Load, Sensor, drive};
use bumpsim_planar::export::{Forces, PlanarExport, calculix_deck, lsdyna_include, read_calculix};

fn ccx_available() -> bool {
    peer_available("ccx (calculix-ccx)", "sh", &["-c", "command -v ccx"])
}

/// A half-sine of `peak` N over `duration` s, then zero, sampled every `step` s up to `end` s.
fn half_sine(peak: f64, duration: f64, step: f64, end: f64) -> Vec<f64> {
    let n = (end / step).round() as usize + 1;
    (0..n)
        .map(|k| {
            let t = k as f64 * step;
            if t < duration {
                peak * (std::f64::consts::PI * t / duration).sin()
            } else {
                0.0
            }
        })
        .collect()
}

/// Runs the CalculiX deck of `car` under `input` in ccx (mm-s-t units, an
/// id offset, attachment nodes of the user's on both sides) and compares body
/// x, y, yaw, a sensor's x and the chain masses' u with `drive`: returns the
/// largest difference of each history relative to its peak.
fn ccx_against_drive(
    car: &PlanarCar,
    input: &Drive,
    name: &str,
    spacing: f64,
) -> Vec<(String, f64)> {
    let reference = drive(car, input, 0.5).unwrap();
    let options = PlanarExport {
        spacing,
        units: bumpsim_export::UnitSystem::MmSTonne,
        speed: Some(input.speed),
        forces: Some(Forces {
            step: input.step,
            loads: input.loads.clone(),
        }),
        id_offset: 500,
        attach: [vec![7], vec![8, 9]],
        ..Default::default()
    };
    let mut deck = calculix_deck(car, &options).unwrap();
    // the user's attachment nodes, here free nodes without mass: tied by the deck
    deck = format!(
        "*NODE\n7, 2.0, 0.5, 0.0\n8, 2.0, -0.5, 0.0\n9, 2.0, -0.6, 0.0\n*BOUNDARY\n7, 3, 3\n8, 3, 3\n9, 3, 3\n{deck}"
    );
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR"))
        .join("planar-export")
        .join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("car.inp"), &deck).unwrap();
    let run = Command::new("ccx")
        .arg("car")
        .current_dir(&dir)
        .output()
        .unwrap();
    let log = String::from_utf8_lossy(&run.stdout);
    assert!(run.status.success() && !log.contains("*ERROR"), "{log}");
    let fe = read_calculix(car, &options, &dir.join("car.dat")).unwrap();
    let at: Vec<usize> = fe
        .time
        .iter()
        .map(|t| (t / input.step).round() as usize)
        .collect();
    assert_eq!(
        at.len(),
        reference.time.len() - 1,
        "one result per sample after 0"
    );
    let pick = |h: &[f64]| at.iter().map(|&k| h[k]).collect::<Vec<f64>>();
    let Sensor::Body(sensor) = input.sensors[0] else {
        panic!("a body sensor")
    };
    let mut histories = vec![
        ("x".to_string(), pick(&reference.x), fe.x.clone()),
        ("y".to_string(), pick(&reference.y), fe.y.clone()),
        ("yaw".to_string(), pick(&reference.yaw), fe.yaw.clone()),
        (
            "sensor x".to_string(),
            pick(&reference.sensor_x[0]),
            fe.sensor_x(sensor),
        ),
    ];
    for (i, (a, b)) in reference.chains.iter().zip(&fe.chains).enumerate() {
        histories.push((format!("u{}", i + 1), pick(a), b.clone()));
    }
    histories
        .into_iter()
        .map(|(what, a, b)| (what, largest_difference(&a, &b) / peak(&a)))
        .collect()
}

#[test]
fn calculix_deck_in_ccx_matches_drive_within_one_percent_of_peak() {
    if !ccx_available() {
        return;
    }
    let car = asymmetric_car(0.0);
    let (step, end) = (2e-4, 0.15);
    let offset = Drive {
        step,
        loads: vec![Load {
            lateral: 0.4,
            anchor: None,
            cell: None,
            direction: [-1.0, 0.0],
            force: half_sine(1e3, 0.06, step, end),
        }],
        speed: 8.0 / 3.6,
        arm: 1.0,
        sensors: vec![Sensor::Body([-1.0, 0.7])],
    };
    let angle = 30f64.to_radians();
    let angled = Drive {
        loads: vec![
            Load {
                lateral: -0.3,
                anchor: None,
                cell: None,
                direction: [-angle.cos(), angle.sin()],
                force: half_sine(1.5e3, 0.05, step, end),
            },
            Load {
                lateral: 0.6,
                anchor: None,
                cell: None,
                direction: [-1.0, 0.0],
                force: half_sine(5e2, 0.08, step, end),
            },
        ],
        speed: 0.0,
        ..offset.clone()
    };
    // a side without masses: the beam's right end sits on the body
    let one_sided = PlanarCar::new(
        *car.body(),
        car.left().clone(),
        SideChain::default(),
        car.beam().clone(),
        *car.tyres(),
    )
    .unwrap();
    // the chain masses crush past each other's nodes (0.01 mm apart): a
    // spring along the nodes' line (SPRINGA) turned over there
    let crossed = 1e-5;
    let crush = drive(&car, &offset, 0.5).unwrap().chains[0]
        .iter()
        .fold(0.0f64, |m, u| m.max(u.abs()));
    assert!(crush > 10.0 * crossed, "crush {crush} m");
    let cases = [
        ("offset", &car, offset.clone(), 0.1),
        ("angled", &car, angled.clone(), 0.1),
        ("one-sided", &one_sided, angled, 0.1),
        ("crossed", &car, offset, crossed),
    ];
    for (name, car, input, spacing) in cases {
        let errors = ccx_against_drive(car, &input, name, spacing);
        eprintln!("{name}: {errors:?}");
        for (what, error) in errors {
            assert!(
                error < 0.01,
                "{name}: {what} differs by {error:.4} of its peak"
            );
        }
    }
}

/// An LS-DYNA include of the asymmetric car with loads, speed, outputs and
/// attachment nodes on both sides.
fn planar_include(units: bumpsim_export::UnitSystem) -> String {
    let options = PlanarExport {
        units,
        origin: [1.0, 0.2, 0.45],
        id_offset: 9_000_000,
        attach: [vec![101, 102], vec![201]],
        speed: Some(-8.0 / 3.6),
        forces: Some(Forces {
            step: 1e-3,
            loads: vec![Load {
                lateral: 0.4,
                anchor: None,
                cell: None,
                direction: [-0.9, 0.3],
                force: half_sine(2e4, 0.02, 1e-3, 0.03),
            }],
        }),
        output_interval: Some(1e-4),
        title: "asymmetric planar car".into(),
        ..Default::default()
    };
    lsdyna_include(&asymmetric_car(0.0), &options).unwrap()
}

/// Data lines of a keyword's cards (comments left out).
fn card_lines<'a>(deck: &'a str, keyword: &str) -> Vec<Vec<&'a str>> {
    let mut out = vec![];
    let mut current: Option<Vec<&str>> = None;
    for line in deck.lines().filter(|l| !l.starts_with('$')) {
        if line.starts_with('*') {
            out.extend(current.take());
            current = (line.trim() == keyword).then(Vec::new);
        } else if let Some(lines) = current.as_mut() {
            lines.push(line);
        }
    }
    out.extend(current);
    out
}

fn field(line: &str, column: usize, width: usize) -> f64 {
    line[column..(column + width).min(line.len())]
        .trim()
        .parse()
        .unwrap()
}

#[test]
fn lsdyna_include_carries_the_cars_mass_inertia_and_links_in_every_unit_system() {
    use bumpsim_export::UnitSystem;
    let car = asymmetric_car(0.0);
    for units in [UnitSystem::Si, UnitSystem::MmSTonne, UnitSystem::MmMsKg] {
        let deck = planar_include(units);
        assert!(
            deck.lines().all(|l| l.len() <= 80),
            "a line beyond 80 columns"
        );
        assert!(!deck.contains("inf") && !deck.contains("NaN"));
        let body = &card_lines(&deck, "*CONSTRAINED_NODAL_RIGID_BODY_INERTIA_SPC")[0];
        let mass = field(body[2], 30, 10) / units.mass();
        let yaw = field(body[3], 50, 10) / (units.mass() * units.length().powi(2));
        assert!((mass - 1250.0).abs() < 1e-6 * 1250.0, "{mass}");
        assert!((yaw - 1900.0).abs() < 1e-6 * 1900.0, "{yaw}");
        // planar: z, roll and pitch fixed at the centre of mass
        assert_eq!((field(body[1], 10, 10), field(body[1], 20, 10)), (3.0, 4.0));
        let chain: f64 = card_lines(&deck, "*ELEMENT_MASS")
            .iter()
            .map(|c| field(c[0], 16, 16) / units.mass())
            .sum();
        assert!(
            (chain - 27.0).abs() < 1e-9 * 27.0,
            "chain masses {chain} kg"
        );
        let springs: Vec<f64> = card_lines(&deck, "*MAT_SPRING_ELASTIC")
            .iter()
            .map(|c| field(c[0], 10, 10) / units.stiffness())
            .collect();
        let expected: Vec<f64> = car
            .left()
            .springs
            .iter()
            .chain(&car.right().springs)
            .copied()
            .collect();
        for (a, b) in springs.iter().zip(&expected) {
            assert!((a - b).abs() < 1e-6 * b, "{a} vs {b}");
        }
        assert_eq!(springs.len(), 3);
        assert_eq!(
            card_lines(&deck, "*CONSTRAINED_JOINT_TRANSLATIONAL").len(),
            3
        );
        assert_eq!(card_lines(&deck, "*ELEMENT_DISCRETE")[0].len(), 6);
        // the front forces: left and right, x and y
        assert_eq!(card_lines(&deck, "*LOAD_NODE_POINT").len(), 4);
    }
}

#[test]
fn planar_export_refuses_bad_options_naming_them() {
    use bumpsim_planar::export::PlanarExportError;
    let car = asymmetric_car(0.0);
    let clash = PlanarExport {
        attach: [vec![5], vec![]],
        ..Default::default()
    };
    let err = lsdyna_include(&car, &clash).unwrap_err();
    assert!(
        err.to_string().contains("clashes with the include's nodes"),
        "{err}"
    );
    let twice = PlanarExport {
        id_offset: 1000,
        attach: [vec![5], vec![5]],
        ..Default::default()
    };
    let err = calculix_deck(&car, &twice).unwrap_err();
    assert!(err.to_string().contains("node 5 is given twice"), "{err}");
    let load = |force: Vec<f64>, direction| Load {
        lateral: 0.1,
        anchor: None,
        cell: None,
        direction,
        force,
    };
    let bad = [
        (load(vec![1.0, f64::NAN], [-1.0, 0.0]), "load[0].force[1]"),
        (load(vec![1.0, 2.0], [0.0, 0.0]), "load[0].direction"),
        (load(vec![1.0], [-1.0, 0.0]), "at least two samples"),
    ];
    let anchored = Load {
        anchor: Some([2.1, 0.0]),
        ..load(vec![1.0, 2.0], [-1.0, 0.0])
    };
    let bad = bad.into_iter().chain([(anchored, "load[0].anchor")]);
    for (load, needle) in bad {
        let options = PlanarExport {
            forces: Some(Forces {
                step: 1e-3,
                loads: vec![load],
            }),
            ..Default::default()
        };
        let err = calculix_deck(&car, &options).unwrap_err();
        assert!(err.to_string().contains(needle), "{err}");
    }
    let far = PlanarExport {
        units: bumpsim_export::UnitSystem::MmSTonne,
        origin: [1e307, 0.0, 0.0],
        ..Default::default()
    };
    let err = lsdyna_include(&car, &far).unwrap_err();
    assert!(matches!(err, PlanarExportError::Export(_)), "{err}");
    let spacing = PlanarExport {
        spacing: -0.1,
        ..Default::default()
    };
    let err = lsdyna_include(&car, &spacing).unwrap_err();
    assert!(err.to_string().contains("spacing = -0.1 m"), "{err}");
    let big = PlanarExport {
        id_offset: 99_999_990,
        ..Default::default()
    };
    assert!(
        lsdyna_include(&car, &big)
            .unwrap_err()
            .to_string()
            .contains("8-column")
    );
}

#[test]
fn lsdyna_include_parses_in_ansys_dyna_core_with_every_id_defined() {
    if !peer_available(
        "ansys-dyna-core",
        "python3",
        &["-c", "import ansys.dyna.core"],
    ) {
        return;
    }
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("planar-export");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("planar.k");
    std::fs::write(&path, planar_include(bumpsim_export::UnitSystem::MmSTonne)).unwrap();
    let script = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/dyna_deck.py");
    let run = Command::new("python3")
        .arg(script)
        .arg(&path)
        .args(["101", "102", "201"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(run.status.success(), "dyna_deck.py: {stderr}");
    let verdict: serde_json::Value = serde_json::from_slice(&run.stdout).unwrap();
    for empty in ["unprocessed", "errors", "undefined"] {
        assert_eq!(verdict[empty], serde_json::json!([]), "{empty}: {verdict}");
    }
    assert_eq!(verdict["strings"], 0, "raw keywords: {verdict}");
    let keywords = verdict["keywords"].to_string();
    for kind in [
        "ConstrainedNodalRigidBodyInertiaSpc",
        "ConstrainedJointTranslational",
    ] {
        assert!(keywords.contains(kind), "{kind} missing: {keywords}");
    }
}

/// A car whose side members crush (nonlinear links) is refused by both
/// decks, naming the side's links: they would carry each link's initial
/// slope, a different car.
#[test]
fn nonlinear_side_members_are_refused_by_the_decks_not_linearised() {
    let file =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/planar/links.toml");
    let car = PlanarCar::read(&file).unwrap();
    assert!(!car.left().links.is_empty());
    let options = PlanarExport::default();
    for message in [
        calculix_deck(&car, &options).unwrap_err().to_string(),
        lsdyna_include(&car, &options).unwrap_err().to_string(),
    ] {
        assert!(
            message.contains("left.links") && message.contains("linear side members only"),
            "{message}"
        );
    }
}
