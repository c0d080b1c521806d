use super::*;
use bumpsim_core::link::Curve;

const CAR: &str = r#"
name = "two links"
masses = [2.0, "80 kg", 1400.0]
dampers = [0.0, "5 Ns/mm"]

[front]
curve = "bilinear"
stiffness = "1500 N/mm"
yield_force = "80 kN"
hardening = 0.1
unloading = "2000 N/mm"

[[links]]
curve = "progressive"
stiffness = "500 N/mm"
limit = "200 mm"
limit_force = "150 kN"

[[links]]
curve = "table"
points = [["50 mm", "60 kN"], [0.15, 9e4]]
unloading = "elastic"
"#;

fn parse(text: &str) -> Result<LinkCar, CarError> {
    LinkCar::parse(text, Path::new("car.toml"))
}

#[test]
fn units_are_converted_to_si() {
    let car = parse(CAR).unwrap();
    assert_eq!(car.name.as_deref(), Some("two links"));
    assert_eq!(car.chain.masses(), &[2.0, 80.0, 1400.0]);
    assert_eq!(car.chain.dampers(), &[0.0, 5000.0]);
    let front = car.chain.front().unwrap();
    assert_eq!(
        front.curve(),
        &Curve::Bilinear {
            stiffness: 1.5e6,
            yield_force: 8e4,
            hardening: 0.1
        }
    );
    assert_eq!(front.unloading(), Unloading::Slope(2e6));
    // progressive: k3 = (F_lim − k δ_lim) / δ_lim³
    let Curve::Progressive { cubic, .. } = car.chain.links()[0].curve() else {
        panic!("not progressive")
    };
    assert!((cubic - (1.5e5 - 5e5 * 0.2) / 0.008).abs() < 1e-6);
    assert!((car.chain.links()[0].curve().force(0.2) - 1.5e5).abs() < 1e-6);
    assert_eq!(car.chain.links()[0].unloading(), Unloading::Elastic);
    assert_eq!(
        car.chain.links()[1].curve(),
        &Curve::Table {
            points: vec![[0.0, 0.0], [0.05, 6e4], [0.15, 9e4]]
        }
    );
}

#[test]
fn hostile_values_are_refused_naming_file_link_and_key() {
    let cases = [
        ("\"1500 N/mm\"", "nan", "car.toml: front link: stiffness"),
        (
            "\"80 kN\"",
            "\"-80 kN\"",
            "car.toml: front link: yield_force = -80000 N",
        ),
        (
            "hardening = 0.1",
            "hardening = 1.5",
            "front link: hardening = 1.5",
        ),
        (
            "\"2000 N/mm\"",
            "\"-1 N/mm\"",
            "front link: unloading = -1000 N/m",
        ),
        ("\"2000 N/mm\"", "\"2000 kN\"", "front link: unloading: "),
        (
            "curve = \"table\"",
            "curve = \"cubic\"",
            "car.toml: link 2: curve: \"cubic\" is not a curve",
        ),
        (
            "[0.15, 9e4]",
            "[0.04, 9e4]",
            "car.toml: link 2: points[2]: deformation 0.04 m after 0.05 m",
        ),
        (
            "[0.15, 9e4]",
            "[0.15, -9e4]",
            "link 2: points[2]: deformation and force must not be negative",
        ),
        (
            "[0.15, 9e4]",
            "[0.15]",
            "link 2: points[2]: expected a pair",
        ),
        (
            "\"150 kN\"",
            "\"50 kN\"",
            "link 1: limit_force: 50000 N: must be at least",
        ),
        ("limit = \"200 mm\"\n", "", "link 1: limit: missing"),
        (
            "hardening = 0.1",
            "hardening = 0.1\nyeild = 1",
            "front link: yeild: unknown key",
        ),
        (
            "\"80 kg\"",
            "inf",
            "car.toml: car: masses[2]: inf is not a finite number",
        ),
        ("\"80 kg\"", "-80.0", "car.toml: m2 = -80 kg"),
        (
            "dampers = [0.0, \"5 Ns/mm\"]",
            "dampers = [0.0]",
            "1 dampers given for 3 masses",
        ),
        (
            "name = ",
            "springs = [1.0]\nname = ",
            "car: springs: unknown key",
        ),
    ];
    for (from, to, expected) in cases {
        if expected.is_empty() {
            continue;
        }
        let text = CAR.replacen(from, to, 1);
        assert_ne!(text, CAR, "{from:?} not in the car");
        let err = parse(&text).unwrap_err().to_string();
        assert!(err.contains(expected), "{from:?} -> {to:?}: {err}");
        assert!(err.starts_with("car.toml: "), "{err}");
    }
}

#[test]
fn linear_readers_refuse_links_and_the_chain_reader_takes_both() {
    let err = crate::car::Car::parse(CAR, Path::new("car.toml"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("bumpsim export lsdyna"), "{err}");
    // a linear car with a typo keeps its message
    let err = crate::car::Car::parse("masses = [1.0]\nspring = [1.0]", Path::new("c.toml"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("unknown field `spring`"), "{err}");
    let dir = std::env::temp_dir().join(format!("bumpsim-link-car-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let links = dir.join("links.toml");
    std::fs::write(&links, CAR).unwrap();
    assert!(matches!(ChainCar::read(&links), Ok(ChainCar::Links(_))));
    let linear = dir.join("linear.toml");
    std::fs::write(
        &linear,
        "masses = [1.0, 2.0]\ndampers = [0.0]\nsprings = [3.0]\n",
    )
    .unwrap();
    assert!(matches!(ChainCar::read(&linear), Ok(ChainCar::Linear(_))));
    let _ = std::fs::remove_dir_all(&dir);
}

/// A second load path and a rebound link: read with their mass and gap,
/// written back by [`LinkCar::to_toml`] to the same chain, refused by key.
#[test]
fn wall_links_are_read_written_back_and_refused_by_key() {
    let walls = format!(
        "{CAR}\n[path]\nmass = 3\ngap = \"30 mm\"\ncurve = \"table\"\npoints = [[0.1, 2e5], [0.3, 3e5]]\nunloading = \"8000 N/mm\"\n\n[rebound]\nmass = 3\ncurve = \"bilinear\"\nstiffness = 1e6\nyield_force = 5e4\nunloading = 1e6\n"
    );
    let car = parse(&walls).unwrap();
    let path = car.chain.path().unwrap();
    assert_eq!((path.mass, path.gap), (2, 0.03));
    let rebound = car.chain.rebound().unwrap();
    assert_eq!((rebound.mass, rebound.gap), (2, 0.0));
    let written = car.to_toml();
    assert!(written.starts_with("kind = \"links\"\n"), "{written}");
    assert_eq!(parse(&written).unwrap(), car, "{written}");
    let refusals = [
        ("mass = 3\ngap", "mass = 4\ngap", "second load path: mass"),
        (
            "gap = \"30 mm\"",
            "gap = \"-30 mm\"",
            "second load path: gap",
        ),
        (
            "[rebound]\nmass = 3\n",
            "[rebound]\n",
            "rebound link: mass: missing",
        ),
        (
            "[rebound]\nmass = 3\n",
            "[rebound]\nmass = 3\nspeed = 2\n",
            "rebound link: speed",
        ),
    ];
    for (from, to, said) in refusals {
        let err = parse(&walls.replacen(from, to, 1)).unwrap_err().to_string();
        assert!(err.contains(said), "{to}: {err}");
    }
}
