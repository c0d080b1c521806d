//! Issue 46 item 2: nonlinear links in the planar car's side members —
//! the energy balance closes with their plastic work, a flat centred
//! impact reduces to the 1-D chain with the same links, the exact dual
//! Jacobian follows the same law, and the car file reads them.

use bumpsim_core::chain::{Chain, Drive as ChainDrive};
use bumpsim_core::dual::{Dual, Real};
use bumpsim_core::link::{Curve, Link, Unloading};
use bumpsim_impact::bumper::Bumper;
use bumpsim_planar::car::{Axle, Layout, PlanarCar, SideChain, Tyres};
use bumpsim_planar::drive::{Drive, Sensor, drive_substeps, segment_loads, substeps};
use bumpsim_planar::sensitivity::{Parameters, sensor_readings};
use bumpsim_planar::{Face, PlanarResult, Settings, Side, Striker, simulate};

/// A crash box that yields at 40 kN (per side) with 5 % hardening and
/// unloads at twice its elastic slope; a progressive rail behind it.
fn yielding(yield_force: f64) -> Link {
    let curve = Curve::bilinear(2e6, yield_force, 0.05).unwrap();
    Link::new(curve, Unloading::Slope(4e6)).unwrap()
}

fn rail() -> Link {
    Link::new(
        Curve::progressive(3e6, 2e8, 0.3).unwrap(),
        Unloading::Elastic,
    )
    .unwrap()
}

/// The 1-D chain: beam mass, rail mass, body; a yielding box and a rail.
fn chain() -> Chain {
    let links = vec![yielding(8e4), rail()];
    Chain::new(vec![10.0, 40.0, 1300.0], vec![500.0, 2e3], links).unwrap()
}

/// An elastic linear bumper (no plateau in reach): the 1-D front link.
const BUMPER: f64 = 6e6;

fn car() -> PlanarCar {
    car_on(&Layout::default())
}

fn car_on(layout: &Layout) -> PlanarCar {
    let bumper = Bumper::three_part(BUMPER, 1e12, BUMPER).unwrap();
    PlanarCar::symmetric_links(&chain(), &bumper, layout).unwrap()
}

fn flat(car: &PlanarCar, speed: f64, angle: f64) -> PlanarResult {
    let face = Face::plane_in_degrees(angle, 100.0, Side::Left);
    let settings = Settings {
        duration: 0.15,
        output_step: 1e-4,
        stop_after_contact: false,
        ..Settings::default()
    };
    simulate(car, &Striker::barrier(face, speed), &settings).unwrap()
}

/// The balance `E0 = kinetic + springs + bending + dampers + crush +
/// friction + plastic` of a 10° impact on rolling tyres with a bending
/// beam closes within 1e-4 of E0 at every sample (the leapfrog's O(T²)
/// residual; 1e-5 seen), with the plastic work half of it or more: the
/// boxes crush and keep a set.
#[test]
fn the_energy_balance_closes_with_the_plastic_work() {
    let axle = Axle::rolling(0.015, 0.8);
    let layout = Layout {
        bending: 2e4,
        tyres: Tyres {
            front: axle,
            rear: axle,
            slip_speed: 0.05,
        },
        ..Layout::default()
    };
    let r = flat(&car_on(&layout), 30.0 / 3.6, 10.0);
    let e = r.energy;
    let total = e.kinetic + e.springs + e.bending + e.dampers + e.crush + e.friction + e.plastic;
    eprintln!("{e:?}\nsets {:?}", r.link_set);
    assert!((total - e.initial).abs() < 1e-4 * e.initial, "{e:?}");
    assert!(e.max_relative_error < 1e-4, "{e:?}");
    assert!(
        e.friction > 0.0 && e.bending >= 0.0 && e.dampers > 0.0,
        "{e:?}"
    );
    assert!(e.plastic > 0.5 * e.initial, "{e:?}");
    assert_eq!(r.link_set.len(), 4);
    assert!(
        r.link_set[0] > 0.0 && r.link_set[2] > 0.0,
        "{:?}",
        r.link_set
    );
    assert_eq!(
        (r.link_set[1], r.link_set[3]),
        (0.0, 0.0),
        "the rail is elastic"
    );
}

/// Struck flat and centred, the symmetric planar car with identical
/// yielding links both sides is the 1-D chain with the same links (the
/// bumper its elastic front link): peak force and each box's plastic set
/// within 0.1 % (two integrators with their own steps; 2e-4 and 1e-5 seen).
#[test]
fn a_flat_centred_impact_reduces_to_the_1d_chain_with_the_same_links() {
    let speed = 30.0 / 3.6;
    let planar = flat(&car(), speed, 0.0);
    let one = chain().with_front(Link::linear(BUMPER).unwrap());
    let drive = ChainDrive::Barrier {
        speed,
        step: 1e-4,
        samples: 1501,
    };
    let r = one.run(&drive).unwrap();
    let peak = r.force.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    eprintln!(
        "peak {} / {peak} N; sets {:?} / {:?}",
        planar.peak_force, planar.link_set, r.plastic_set
    );
    assert!((planar.peak_force - peak).abs() < 1e-3 * peak);
    for side in [0, 2] {
        let (set, want) = (planar.link_set[side], r.plastic_set[0]);
        assert!(want > 0.05, "the box crushes: {want} m");
        assert!((set - want).abs() < 1e-3 * want, "{set} {want}");
    }
    assert!(planar.yaw.iter().all(|y| y.abs() < 1e-12));
}

/// The replay on dual numbers differentiates the yielding box's four
/// parameters exactly: against central differences of `drive` (relative
/// step 1e-6) within 1e-4 of each column's largest value, and its values
/// are `drive`'s.
#[test]
fn the_dual_jacobian_of_a_yielding_side_member_matches_central_differences() {
    let car = car();
    let (speed, samples) = (12.0 / 3.6, 1500);
    let r = flat(&car, speed, 10.0);
    let normal = [-(10f64.to_radians().cos()), 10f64.to_radians().sin()];
    let mut loads = segment_loads(&r, normal);
    loads.iter_mut().for_each(|l| l.force.truncate(samples));
    let input = Drive {
        step: 1e-4,
        loads,
        speed,
        arm: 1.0,
        sensors: vec![Sensor::Body([0.5, 0.7]), Sensor::Crush(0), Sensor::YawRate],
    };
    let n = substeps(&car, input.step, 0.2).unwrap();
    let box_link = car.left().links[0].clone();
    let base = box_link.parameters();
    let mut p = Parameters::<Dual<4>>::of(&car, &input);
    let seeded: Vec<Dual<4>> = base
        .iter()
        .enumerate()
        .map(|(i, v)| Dual::seeded(*v, i, 1.0))
        .collect();
    p.links[0] = Some(box_link.with_parameters(&seeded));
    let exact = sensor_readings(&car, &p, &input, n, samples).unwrap();
    let value = drive_substeps(&car, &input, n).unwrap().sensor_reading;
    let with = |i: usize, h: f64| {
        let mut v = base.clone();
        v[i] += h;
        let curve = Curve::bilinear(v[0], v[1], v[2]).unwrap();
        let link = Link::new(curve, Unloading::Slope(v[3])).unwrap();
        let left = car.left();
        let side = SideChain::linked(
            left.masses.clone(),
            left.dampers.clone(),
            vec![link, left.links[1].clone()],
        );
        let changed = PlanarCar::new(
            *car.body(),
            side,
            car.right().clone(),
            car.beam().clone(),
            *car.tyres(),
        )
        .unwrap();
        drive_substeps(&changed, &input, n).unwrap().sensor_reading
    };
    for (i, &b) in base.iter().enumerate() {
        let h = 1e-6 * b;
        let (up, down) = (with(i, h), with(i, -h));
        for s in 0..input.sensors.len() {
            let column: Vec<f64> = (0..samples)
                .map(|k| (up[s][k] - down[s][k]) / (2.0 * h))
                .collect();
            let scale = column.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(scale > 0.0, "parameter {i} moves sensor {s}");
            eprintln!("parameter {i} sensor {s}: scale {scale:e}");
            for k in 0..samples {
                let d = exact[s][k].tangent[i];
                assert!(
                    (d - column[k]).abs() <= 1e-4 * scale,
                    "parameter {i} sensor {s} sample {k}: {d} against {}",
                    column[k]
                );
                let peak = value[s].iter().fold(0.0f64, |m, v| m.max(v.abs()));
                assert!((exact[s][k].value() - value[s][k]).abs() <= 1e-12 * peak);
            }
        }
    }
}

/// The car file takes a side member's links as the 1-D links car does,
/// writes them back, mirrors them, and refuses bad values naming the key.
#[test]
fn the_car_file_reads_writes_and_mirrors_links() {
    let car = car();
    let text = car.to_toml();
    assert!(text.contains("curve = \"bilinear\""), "{text}");
    let again = PlanarCar::parse(&text, "c.toml".as_ref()).unwrap();
    assert_eq!(again.left().links[0], car.left().links[0]);
    let (a, b) = (&again.left().links[1], &car.left().links[1]);
    for d in [0.01, 0.2, 0.5] {
        let (x, y) = (a.curve().force(d), b.curve().force(d));
        assert!((x - y).abs() < 1e-9 * y, "{x} {y}");
    }
    let mirrored = car.mirrored();
    assert_eq!(mirrored.left().links, car.right().links);
    let saloon = include_str!("../../../../examples/planar/links.toml");
    assert!(PlanarCar::parse(saloon, "links.toml".as_ref()).is_ok());
    let table = (1..=10_001)
        .map(|i| format!("[{:?}, 1000.0]", i as f64 * 1e-4))
        .collect::<Vec<_>>()
        .join(", ");
    let bad = [
        (
            "yield_force = \"40 kN\"",
            "yield_force = nan",
            "left: link 1: yield_force",
        ),
        (
            "yield_force = \"40 kN\"",
            "yield_force = -4e4",
            "left: link 1: yield_force",
        ),
        (
            "hardening = 0.05",
            "hardening = 2.0",
            "left: link 1: hardening",
        ),
        (
            "unloading = \"2000 N/mm\"",
            "unloading = -1.0",
            "left: link 1: unloading",
        ),
        ("unloading = \"2000 N/mm\"", "unloading = 1e400", "c.toml"),
        ("limit = \"300 mm\"", "limit = inf", "left: link 2: limit"),
        (
            "curve = \"bilinear\"",
            "curve = \"cubic\"",
            "left: link 1: curve",
        ),
        (
            "[[right.links]]\ncurve = \"bilinear\"",
            "[[right.links]]\ncurve = \"table\"\npoints = [[0.01, -5.0]]\nc = \"bilinear\"",
            "right: link 1: c",
        ),
        (
            "dampers = [1000.0, 3000.0]     # N·s/m\n",
            "dampers = [1000.0, 3000.0]\nsprings = [2e6, 3e6]\n",
            "left.springs",
        ),
    ];
    for (from, to, needle) in bad {
        assert!(saloon.contains(from), "{from}");
        let text = saloon.replacen(from, to, 1);
        let e = PlanarCar::parse(&text, "c.toml".as_ref())
            .unwrap_err()
            .to_string();
        assert!(e.contains(needle), "{needle}: {e}");
        assert!(e.starts_with("c.toml"), "{e}");
    }
    // a table of more than MAX_TABLE_POINTS points is refused by name
    let huge = saloon.replacen(
        "curve = \"progressive\"\nstiffness = \"500 N/mm\"\nlimit = \"300 mm\"\nlimit_force = \"300 kN\"",
        &format!("curve = \"table\"\npoints = [{table}]"),
        1,
    );
    assert_ne!(huge, saloon);
    let e = PlanarCar::parse(&huge, "c.toml".as_ref())
        .unwrap_err()
        .to_string();
    // refused by its count before any point is converted
    assert!(
        e.contains("left: link 2") && e.contains("10001 points: at most 10000"),
        "{e}"
    );
}

/// `synth` makes a series of a car whose side members crush (the bundled
/// example): every test records, and its start car keeps the links.
#[test]
fn synth_records_a_series_of_a_car_with_nonlinear_side_members() {
    let dir = std::env::temp_dir().join(format!("bumpsim-links-synth-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let car = std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples/planar/links.toml")
        .canonicalize()
        .unwrap();
    let series = format!(
        "planar_car = {:?}\nseed = 3\n[chain]\nstep = 1e-4\npretrigger = 0.01\nduration = 0.12\n\
         force_noise = 20.0\nacceleration_noise = 0.05\nbiases = [0.0, 0.0]\nsensor = [0.6, 0.7]\n\
         [[test]]\nname = \"FLAT\"\nspeed = \"15 km/h\"\n[[test]]\nname = \"ANGLED\"\nangle = 10.0\nspeed = \"15 km/h\"\n",
        car.display().to_string()
    );
    let path = dir.join("series.toml");
    std::fs::write(&path, series).unwrap();
    let s = bumpsim_planar::series::make_series(&path).unwrap();
    std::fs::remove_dir_all(&dir).ok();
    assert_eq!(s.tests.len(), 2);
    for t in &s.tests {
        let peak = t.channels[0]
            .series
            .values()
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(peak > 0.0, "{}", t.name);
    }
    let start = PlanarCar::parse(&s.start, "start.toml".as_ref()).unwrap();
    assert_eq!(start.left().links.len(), 2);
}
