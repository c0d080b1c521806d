//! The 1-D impact integrator against its recorded outputs (issue 31): a
//! refactoring of the integrator must leave every history within 1e-9 of
//! its peak (`bumpsim_peers::recorded`; `tests/data/impact-regression.txt`
//! was written by the commit before the one-engine refactoring).

use bumpsim_core::model::MsdModel;
use bumpsim_impact::bumper::Bumper;
use bumpsim_impact::impact::{ImpactResult, Options, Scenario, simulate};
use bumpsim_peers::recorded::Recording;
use std::path::Path;

fn record(out: &mut Recording, name: &str, r: &ImpactResult) {
    let mut history = |what: &str, values: &[f64]| out.history(&format!("{name}.{what}"), values);
    history("time", &r.time);
    history("force", &r.force);
    history("compression", &r.compression);
    for (i, body) in r.bodies.iter().enumerate() {
        history(&format!("x.{body}"), &r.displacements[i]);
        history(&format!("v.{body}"), &r.velocities[i]);
    }
    let e = &r.energy;
    let scalars = [
        ("contact_time", r.contact_time),
        ("max_compression", r.max_compression),
        ("remaining_compression", r.remaining_compression),
        ("peak_force", r.peak_force),
        ("absorbed_energy", r.absorbed_energy),
        ("step", r.step),
        ("energy.initial", e.initial),
        ("energy.kinetic", e.kinetic),
        ("energy.springs", e.springs),
        ("energy.dampers", e.dampers),
        ("energy.bumper", e.bumper),
    ];
    for (what, value) in scalars {
        out.scalar(&format!("{name}.{what}"), value);
    }
}

#[test]
fn impacts_are_as_recorded() {
    let three = MsdModel::new(
        vec![9.0, 45.0, 1280.0],
        vec![2.5e3, 7e3],
        vec![1.1e6, 3.2e6],
    )
    .unwrap();
    let two = MsdModel::new(vec![14.0, 1300.0], vec![4e3], vec![6e6]).unwrap();
    let rigid = MsdModel::new(vec![1100.0], vec![], vec![]).unwrap();
    let foam = Bumper::three_part(1.5e6, 45e3, 6e6).unwrap();
    let table = Bumper::table(
        vec![0.0, 0.02, 0.05, 0.09, 0.2],
        vec![0.0, 30e3, 42e3, 60e3, 250e3],
        4e6,
    )
    .unwrap();
    let fine = Options {
        safety: 0.2,
        output_step: 5e-5,
        ..Options::default()
    };
    let cases = [
        (
            "barrier-3dof",
            &three,
            &foam,
            Scenario::Barrier { speed: 8.0 / 3.6 },
            Options::default(),
        ),
        (
            "pendulum-2dof",
            &two,
            &table,
            Scenario::Impactor {
                mass: 1100.0,
                speed: 4.0 / 3.6,
            },
            Options::default(),
        ),
        (
            "barrier-rigid-table",
            &rigid,
            &table,
            Scenario::Barrier { speed: 2.5 },
            fine,
        ),
        (
            "pendulum-3dof-fine",
            &three,
            &foam,
            Scenario::Impactor {
                mass: 900.0,
                speed: 2.5,
            },
            fine,
        ),
    ];
    let mut out = Recording::every(20);
    for (name, car, bumper, scenario, options) in cases {
        let r = simulate(car, bumper, scenario, &options).unwrap();
        record(&mut out, name, &r);
    }
    out.check(&Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/impact-regression.txt"));
}
