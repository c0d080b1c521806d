//! Integration tests of the planar car (issue 15): reduction to the 1-D
//! impact, mirror symmetry, momentum and energy balances, bad input, and an
//! independent scipy oracle (tests/peers/scipy_planar_wall.py).

use bumpsim_core::model::MsdModel;
use bumpsim_impact::bumper::Bumper;
use bumpsim_impact::impact::{self, Options, Scenario};
use bumpsim_planar::car::{Axle, Beam, Body, Layout, SideChain, Tyres};
use bumpsim_planar::{Face, PlanarCar, PlanarResult, Settings, Side, Striker, simulate};
use proptest::prelude::*;
use std::path::PathBuf;
use std::process::Command;

fn chain() -> MsdModel {
    MsdModel::new(vec![8.0, 40.0, 1250.0], vec![3e3, 8e3], vec![1.2e6, 3e6]).unwrap()
}

fn bumper() -> Bumper {
    Bumper::three_part(1.5e6, 45e3, 6e6).unwrap()
}

fn peak(v: &[f64]) -> f64 {
    v.iter().fold(0.0, |a, b| a.max(b.abs()))
}

fn largest_difference(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y).abs())
        .fold(0.0, f64::max)
}

/// An asymmetric car: different chains, segments and axles, bending, friction.
fn asymmetric_car(mu: f64) -> PlanarCar {
    let body = Body {
        mass: 1250.0,
        yaw_inertia: 1900.0,
        cg_behind_bumper: 2.05,
        wheelbase: 2.6,
        cg_behind_front_axle: 1.15,
        track: 1.52,
    };
    let left = SideChain {
        masses: vec![4.0, 18.0],
        dampers: vec![2e3, 6e3],
        springs: vec![1.1e6, 2.5e6],
        links: Vec::new(),
    };
    let right = SideChain {
        masses: vec![5.0],
        dampers: vec![3e3],
        springs: vec![1.6e6],
        links: Vec::new(),
    };
    let segments = (0..8)
        .map(|j| Bumper::three_part(2e5 + 1e4 * j as f64, 7e3 + 300.0 * j as f64, 9e5).unwrap())
        .collect();
    let beam = Beam {
        width: 1.6,
        side_member_spacing: 1.0,
        segments,
        bending: 8e4,
        block: None,
    };
    let tyres = Tyres {
        front: Axle::sliding(0.1 * mu, mu),
        rear: Axle::sliding(0.8 * mu, mu),
        slip_speed: 0.05,
    };
    PlanarCar::new(body, left, right, beam, tyres).unwrap()
}

/// A plane at `degrees` covering `overlap` from `side`.
fn plane(degrees: f64, overlap: f64, side: Side) -> Face {
    Face::Plane {
        angle: degrees.to_radians(),
        overlap,
        side,
    }
}

fn rcar_left() -> Face {
    plane(10.0, 0.4, Side::Left)
}

#[test]
fn symmetric_car_reproduces_the_1d_impact() {
    let (chain, bumper) = (chain(), bumper());
    let layout = Layout {
        bending: 5e4,
        ..Layout::default()
    };
    let car = PlanarCar::symmetric(&chain, &bumper, &layout).unwrap();
    let cases = [
        (
            Scenario::Barrier { speed: 8.0 / 3.6 },
            Striker::barrier(Face::flat(), 8.0 / 3.6),
        ),
        (
            Scenario::Impactor {
                mass: 1450.0,
                speed: 6.0 / 3.6,
            },
            Striker::pendulum(Face::flat(), 1450.0, 6.0 / 3.6),
        ),
    ];
    for (scenario, striker) in cases {
        let one = impact::simulate(&chain, &bumper, scenario, &Options::default()).unwrap();
        let settings = Settings {
            step: Some(one.step),
            ..Settings::default()
        };
        let planar = simulate(&car, &striker, &settings).unwrap();
        let (f, d) = (one.peak_force, one.max_compression);
        assert!(
            (planar.peak_force - f).abs() <= 1e-6 * f,
            "{} vs {f} N",
            planar.peak_force
        );
        assert!(
            (planar.max_compression - d).abs() <= 1e-6 * d,
            "{} vs {d} m",
            planar.max_compression
        );
        let n = one.force.len().min(planar.force.len());
        assert!(n > 100, "{n} samples in common");
        assert!(largest_difference(&one.force[..n], &planar.force[..n]) <= 1e-6 * f);
        let crush = &planar.crush[3][..n];
        assert!(largest_difference(&one.compression[..n], crush) <= 1e-6 * d);
        assert!(
            peak(&planar.yaw) < 1e-12 && peak(&planar.y) < 1e-12,
            "no turning"
        );
        let (left, right) = (&planar.side_force_left, &planar.side_force_right);
        assert!(largest_difference(left, right) <= 1e-9 * f);
    }
}

fn mirrored_matches(a: &PlanarResult, b: &PlanarResult) {
    let f = a.peak_force;
    assert!(f > 1e3, "a real impact: {f} N");
    assert_eq!(a.time.len(), b.time.len());
    let neg = |v: &[f64]| v.iter().map(|x| -x).collect::<Vec<_>>();
    let tol = |v: &[f64]| 1e-9 * peak(v).max(1e-300);
    assert!(largest_difference(&a.x, &b.x) <= tol(&a.x));
    assert!(
        largest_difference(&a.y, &neg(&b.y)) <= tol(&a.y),
        "y mirrors"
    );
    assert!(
        largest_difference(&a.yaw, &neg(&b.yaw)) <= tol(&a.yaw),
        "yaw mirrors"
    );
    assert!(largest_difference(&a.force_y, &neg(&b.force_y)) <= 1e-9 * f);
    assert!(largest_difference(&a.side_force_left, &b.side_force_right) <= 1e-9 * f);
    assert!(largest_difference(&a.side_force_right, &b.side_force_left) <= 1e-9 * f);
    let segments = a.crush.len();
    for j in 0..segments {
        let (da, db) = (&a.crush[j], &b.crush[segments - 1 - j]);
        assert!(
            largest_difference(da, db) <= 1e-9 * a.max_compression,
            "segment {j}"
        );
    }
    assert!(
        peak(&a.yaw) > 1e-4,
        "the case really turns the car: {} rad",
        peak(&a.yaw)
    );
}

#[test]
fn mirror_case_mirrors_the_response() {
    let car = asymmetric_car(0.7);
    let strikers = [
        Striker::barrier(rcar_left(), 15.0 / 3.6),
        Striker::pendulum(plane(-20.0, 0.15, Side::Right), 1400.0, 5.0 / 3.6),
        Striker::barrier(
            Face::Pole {
                radius: 0.1778 / 2.0,
                lateral: 0.31,
            },
            8.0 / 3.6,
        ),
    ];
    for striker in strikers {
        let a = simulate(&car, &striker, &Settings::default()).unwrap();
        let b = simulate(&car.mirrored(), &striker.mirrored(), &Settings::default()).unwrap();
        mirrored_matches(&a, &b);
    }
}

#[test]
fn without_friction_momentum_is_conserved_and_balanced() {
    let car = asymmetric_car(0.0);
    // a flat face at 40 % overlap: the guide carries no force, so car and
    // pendulum keep their linear momentum exactly
    let offset = plane(0.0, 0.4, Side::Left);
    let r = simulate(
        &car,
        &Striker::pendulum(offset, 1450.0, 6.0 / 3.6),
        &Settings::default(),
    )
    .unwrap();
    let (p0, p) = (r.momentum.initial_linear, r.momentum.final_linear);
    let scale = p0[0].hypot(p0[1]);
    assert!(
        (p[0] - p0[0]).hypot(p[1] - p0[1]) <= 1e-6 * scale,
        "{p:?} vs {p0:?}"
    );
    assert!(peak(&r.yaw) > 1e-3, "the offset hit turns the car");
    // the angular momentum about the origin changes by the guide's couple only,
    // and both change with the barrier's impulse in the fixed cases
    let strikers = [
        Striker::pendulum(offset, 1450.0, 6.0 / 3.6),
        Striker::barrier(rcar_left(), 15.0 / 3.6),
        Striker::barrier(
            Face::Pole {
                radius: 0.15,
                lateral: -0.4,
            },
            8.0 / 3.6,
        ),
    ];
    for striker in strikers {
        let r = simulate(&car, &striker, &Settings::default()).unwrap();
        let m = r.momentum;
        eprintln!(
            "residuals: linear {:.1e}, angular {:.1e}",
            m.linear_residual, m.angular_residual
        );
        assert!(r.momentum.linear_residual <= 1e-6, "{:?}", r.momentum);
        assert!(r.momentum.angular_residual <= 1e-6, "{:?}", r.momentum);
    }
    // a frictionless angled wall pushes along its normal only: the momentum
    // along the wall is conserved
    let r = simulate(
        &car,
        &Striker::barrier(rcar_left(), 15.0 / 3.6),
        &Settings::default(),
    )
    .unwrap();
    let t = [10f64.to_radians().sin(), -10f64.to_radians().cos()];
    let along = |p: [f64; 2]| p[0] * t[0] + p[1] * t[1];
    let (p0, p) = (r.momentum.initial_linear, r.momentum.final_linear);
    assert!((along(p) - along(p0)).abs() <= 1e-6 * p0[0].abs());
}

#[test]
fn energy_balance_closes_in_every_kind_of_case() {
    let car = asymmetric_car(0.8);
    let corner = plane(0.0, 0.15, Side::Right);
    let strikers = [
        Striker::barrier(rcar_left(), 15.0 / 3.6),
        Striker::barrier(plane(-30.0, 1.0, Side::Left), 8.0 / 3.6),
        Striker::pendulum(corner, 1400.0, 5.0 / 3.6),
        Striker::barrier(
            Face::Pole {
                radius: 0.09,
                lateral: 0.0,
            },
            8.0 / 3.6,
        ),
    ];
    for striker in strikers {
        let r = simulate(&car, &striker, &Settings::default()).unwrap();
        let e = r.energy;
        assert!(e.max_relative_error <= 1e-3, "{striker:?}: {e:?}");
        assert!(e.friction > 0.0 && e.crush > 0.0, "{e:?}");
        // locked wheels can hold the car against the 30° wall: the contact
        // then lasts, which is a warning, not an error
        assert!(r.contact_start.is_some());
        assert!(
            r.warnings.iter().all(|w| w.contains("raise the duration")),
            "{:?}",
            r.warnings
        );
        assert!(
            r.time
                .iter()
                .chain(&r.force)
                .chain(&r.yaw)
                .all(|v| v.is_finite())
        );
    }
}

#[test]
fn bad_input_gets_clear_errors_never_nan() {
    let car = asymmetric_car(0.5);
    let run = |s: Striker| {
        simulate(&car, &s, &Settings::default())
            .unwrap_err()
            .to_string()
    };
    let right = |overlap| plane(6.0, overlap, Side::Right);
    assert!(run(Striker::barrier(right(1.2), 2.0)).contains("overlap"));
    assert!(run(Striker::barrier(right(-0.1), 2.0)).contains("0 < overlap ≤ 1"));
    assert!(run(Striker::barrier(right(0.02), 2.0)).contains("never touches"));
    let far_pole = Face::Pole {
        radius: 0.15,
        lateral: 1.5,
    };
    assert!(run(Striker::barrier(far_pole, 2.0)).contains("cannot hit"));
    assert!(run(Striker::barrier(Face::flat(), f64::NAN)).contains("speed"));
    assert!(run(Striker::pendulum(Face::flat(), 0.0, 2.0)).contains("striker mass"));
    let settings = Settings {
        safety: 2.0,
        ..Settings::default()
    };
    let err = simulate(&car, &Striker::barrier(Face::flat(), 2.0), &settings).unwrap_err();
    assert!(err.to_string().contains("safety"), "{err}");
    // too short a duration: a warning, finite numbers
    let short = Settings {
        duration: 0.01,
        ..Settings::default()
    };
    let r = simulate(&car, &Striker::barrier(Face::flat(), 2.0), &short).unwrap();
    assert!(
        r.warnings.iter().any(|w| w.contains("raise the duration")),
        "{:?}",
        r.warnings
    );
    assert!(r.force.iter().all(|f| f.is_finite()));
    let json = serde_json::to_string(&r).unwrap();
    assert!(json.contains("\"line_of_action\"") && !json.contains("NaN"));
}

#[test]
fn oblique_flat_hit_has_the_line_of_action_on_the_struck_side() {
    let car = asymmetric_car(0.0);
    let offset = plane(0.0, 0.4, Side::Left);
    let r = simulate(
        &car,
        &Striker::barrier(offset, 8.0 / 3.6),
        &Settings::default(),
    )
    .unwrap();
    let i = r
        .force
        .iter()
        .enumerate()
        .fold(0, |b, (i, f)| if *f > r.force[b] { i } else { b });
    let line = r.line_of_action[i].unwrap();
    // the four left segments of 0.2 m cover y = 0 .. 0.8 m
    assert!(line > 0.1 && line < 0.8, "{line} m");
    assert!(r.side_force_left[i] > r.side_force_right[i]);
    assert!(r.max_crush[7] > 0.0 && r.max_crush[0] == 0.0);
    assert!(r.peak_yaw_rate > 0.0, "hit on the left, turns left");
}

use bumpsim_peers::peer_available;

fn scipy_available() -> bool {
    peer_available("python3 with scipy", "python3", &["-c", "import scipy"])
}

#[test]
fn point_spring_into_an_angled_wall_matches_scipy_newton_euler() {
    if !scipy_available() {
        return;
    }
    let (mass, inertia, k, a, angle, speed) = (1100.0, 1500.0, 8e5, 1.9, 25f64.to_radians(), 2.5);
    // two segments of a 1.2 m bumper: the left one (y0 = 0.3 m) alone meets the wall
    let body = Body {
        mass,
        yaw_inertia: inertia,
        cg_behind_bumper: a,
        wheelbase: 2.5,
        cg_behind_front_axle: 1.2,
        track: 1.4,
    };
    let spring = Bumper::three_part(k, 1e12, k).unwrap();
    let beam = Beam {
        width: 1.2,
        side_member_spacing: 0.9,
        segments: vec![spring.clone(), spring],
        bending: 0.0,
        block: None,
    };
    let none = SideChain::default();
    let car = PlanarCar::new(body, none.clone(), none, beam, Tyres::default()).unwrap();
    let face = Face::Plane {
        angle,
        overlap: 0.5,
        side: Side::Left,
    };
    let settings = Settings {
        duration: 0.15,
        output_step: 1e-3,
        stop_after_contact: false,
        ..Settings::default()
    };
    let r = simulate(&car, &Striker::barrier(face, speed), &settings).unwrap();
    assert!(
        r.max_crush[0] == 0.0 && r.max_crush[1] > 0.0,
        "one point spring only"
    );
    let dir = std::env::temp_dir().join(format!("bumpsim-planar-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let params = dir.join("wall.json");
    let json = format!(
        "{{\"mass\": {mass}, \"yaw_inertia\": {inertia}, \"stiffness\": {k}, \"a\": {a}, \"y0\": 0.3, \"angle\": {angle}, \"speed\": {speed}, \"times\": {:?}}}",
        r.time
    );
    std::fs::write(&params, json).unwrap();
    let text = scipy_peer("scipy_planar_wall.py", &params);
    let rows: Vec<Vec<f64>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), r.time.len());
    for (column, ours) in [(1, &r.x), (2, &r.y), (3, &r.yaw)] {
        let theirs: Vec<f64> = rows.iter().map(|row| row[column]).collect();
        let worst = largest_difference(ours, &theirs) / peak(&theirs);
        eprintln!("column {column}: largest difference {worst:.2e} of the peak");
        assert!(worst <= 5e-3, "column {column}: {worst:e} of the peak");
        assert!(peak(&theirs) > 1e-3, "column {column} moves");
    }
    std::fs::remove_dir_all(&dir).ok();
}

fn any_side() -> impl Strategy<Value = Side> {
    prop_oneof![Just(Side::Left), Just(Side::Right)]
}

fn any_face() -> impl Strategy<Value = Face> {
    prop_oneof![
        (-100.0..100.0f64, -0.5..1.5f64, any_side())
            .prop_map(|(angle, overlap, side)| plane(angle, overlap, side)),
        (-0.1..0.5f64, -2.0..2.0f64).prop_map(|(radius, lateral)| Face::Pole { radius, lateral }),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Any face at any speed and pendulum mass, sensible or not: a clear
    /// error, or a result whose numbers are all finite and whose energy
    /// closes, or a warning that it does not. Within the low-speed
    /// programme (≤ 16 km/h; a barrier, or a pendulum of 1 kg or more) it
    /// closes, refined as `impact` refines. A pendulum of a few kg rattles
    /// against the car's 4 kg tip, each rebound starting mid-step: a 9.5 kg
    /// one at 3.3 m/s into a pole closed to 0.13 % at safety 0.05
    /// (proptest, CI of 2026-12-02), and a scan of 0.5–100 kg up to 0.33 %
    /// (2 kg, 3.3 m/s, a 0.1 m pole 0.38 m off centre); refined three
    /// times, every case of the scan closed within 0.1 %.
    #[test]
    fn any_striker_gives_an_error_or_finite_numbers(
        face in any_face(),
        speed in -2.0..12.0f64,
        mass in prop_oneof![Just(None), (-100.0..3000.0f64).prop_map(Some)],
        mu in 0.0..1.2f64,
    ) {
        let car = asymmetric_car(mu);
        let striker = match mass {
            None => Striker::barrier(face, speed),
            Some(m) => Striker::pendulum(face, m, speed),
        };
        let settings = Settings { duration: 0.4, refine: 3, ..Settings::default() };
        match simulate(&car, &striker, &settings) {
            Err(e) => prop_assert!(!e.to_string().is_empty()),
            Ok(r) => {
                let series = [&r.x, &r.y, &r.yaw, &r.force, &r.side_force_left, &r.side_force_right];
                prop_assert!(series.iter().all(|s| s.iter().all(|v| v.is_finite())));
                prop_assert!(r.line_of_action.iter().flatten().all(|v| v.is_finite()));
                // within the low-speed programme the balance closes to 0.1 %;
                // beyond it (a weak bumper crushed far past the striker, a
                // pendulum of grams) it closes or the result says it does not
                let closes = r.energy.max_relative_error < 1e-3;
                let warned = r.warnings.iter().any(|w| w.contains("energy balance"));
                let programme = speed <= 16.0 / 3.6 && mass.is_none_or(|m| m >= 1.0);
                prop_assert!(closes || (!programme && warned), "{:?}", r.energy);
            }
        }
    }
}

/// A pendulum of a few kg rattles against the car's 4 kg tip, each
/// rebound starting mid-step: at safety 0.05 the balance stays open and
/// warns; refined, the run halves its step until it closes, and then warns
/// of nothing. A given step is never refined.
#[test]
fn a_light_pendulum_refines_its_step_until_the_balance_closes() {
    use bumpsim_planar::simulate::ENERGY_TOLERANCE;
    let car = asymmetric_car(0.0);
    let open = |refine: u32, step: Option<f64>| {
        let settings = Settings {
            duration: 0.4,
            refine,
            step,
            ..Settings::default()
        };
        [(2.0, 3.3), (1.0, 4.4), (5.0, 3.3), (2.0, 4.4)]
            .into_iter()
            .map(|(mass, speed)| {
                let face = Face::Pole {
                    radius: 0.05,
                    lateral: -0.38,
                };
                simulate(&car, &Striker::pendulum(face, mass, speed), &settings).unwrap()
            })
            .collect::<Vec<_>>()
    };
    let (coarse, refined) = (open(0, None), open(3, None));
    let warned = |r: &PlanarResult| r.warnings.iter().any(|w| w.contains("energy balance"));
    assert!(
        coarse
            .iter()
            .all(|r| r.energy.max_relative_error > ENERGY_TOLERANCE)
    );
    for (c, r) in coarse.iter().zip(&refined) {
        assert!(warned(c), "{:?}", c.warnings);
        assert!(
            r.energy.max_relative_error < ENERGY_TOLERANCE,
            "{:?}",
            r.energy
        );
        assert!(!warned(r), "{:?}", r.warnings);
        assert!(r.step < 0.6 * c.step, "{} s against {} s", r.step, c.step);
    }
    let given = open(3, Some(coarse[0].step));
    assert!((given[0].step - coarse[0].step).abs() < 1e-12 * coarse[0].step);
    assert!(
        given[0]
            .warnings
            .iter()
            .any(|w| w.contains("the given step"))
    );
}

#[test]
fn a_stiff_beam_that_chatters_off_the_face_still_completes_the_impact() {
    // bending 1e8 N/m (far above the segments' slopes) makes the beam bounce
    // off the face within the first millisecond; the run used to stop there
    // with the car still closing at full speed, as if it had passed through
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/planar/saloon.toml"),
    )
    .unwrap();
    let stiff = text.replacen("bending = 2e4", "bending = 1e8", 1);
    assert_ne!(stiff, text, "the example names its bending stiffness");
    let car = PlanarCar::parse(&stiff, std::path::Path::new("stiff.toml")).unwrap();
    for face in [rcar_left(), Face::pole_of_diameter(0.178, 0.0)] {
        let r = simulate(
            &car,
            &Striker::barrier(face, 15.0 / 3.6),
            &Settings::default(),
        )
        .unwrap();
        let contact = r.contact_end.unwrap() - r.contact_start.unwrap();
        assert!(contact > 0.02, "{face:?}: contact {contact} s");
        let end = r.velocity_x.last().copied().unwrap();
        assert!(end < 0.0, "{face:?}: the car still closes at {end} m/s");
        assert!(
            r.energy.max_relative_error < 1e-3,
            "{face:?}: {:?}",
            r.energy
        );
    }
}

#[path = "planar/bands.rs"]
mod bands;
#[path = "planar/block.rs"]
mod block;
#[path = "planar/bumper_fit.rs"]
mod bumper_fit;
#[path = "planar/cells.rs"]
mod cells;
#[path = "planar/coverage.rs"]
mod coverage;
#[path = "planar/crash_box.rs"]
mod crash_box;
#[path = "planar/defaults.rs"]
mod defaults;
#[path = "planar/diagnosis.rs"]
mod diagnosis;
#[path = "planar/export.rs"]
mod export;
#[path = "planar/files.rs"]
mod files;
#[path = "planar/identification.rs"]
mod identification;
#[path = "planar/independent.rs"]
mod independent;
#[path = "planar/links.rs"]
mod links;
#[path = "planar/pole_contact.rs"]
mod pole_contact;
#[path = "planar/progressive.rs"]
mod progressive;
#[path = "planar/regression.rs"]
mod regression;
#[path = "planar/same_objective.rs"]
mod same_objective;
#[path = "planar/sensors.rs"]
mod sensors;
#[path = "planar/split.rs"]
mod split;
#[path = "planar/truth_start.rs"]
mod truth_start;
#[path = "planar/tyres.rs"]
mod tyres;
#[path = "planar/yaw_rate.rs"]
mod yaw_rate;

/// Runs the peer script `tests/peers/SCRIPT` on the parameter file `params`
/// and returns what it prints (the planar tests' scipy oracles).
fn scipy_peer(script: &str, params: &std::path::Path) -> String {
    let script = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/peers")
        .join(script);
    let out = Command::new("python3")
        .arg(&script)
        .arg(params)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}
