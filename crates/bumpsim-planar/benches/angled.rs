//! Criterion benchmark: one 8 km/h angled-barrier impact of a planar car with
//! a 10-segment bumper (target: under 5 ms on one core): the IIHS 30° angle
//! barrier, a 1312 kg two-mass car, free-rolling tyres, bending coupling, the
//! default step (safety 0.05) and output interval (0.1 ms), run until a tenth
//! of the contact time after separation; and the same impact replayed from
//! its segment forces (the planar identification's unit of work). Figures:
//! docs/benchmarks.md.

use bumpsim_core::model::MsdModel;
use bumpsim_impact::bumper::Bumper;
use bumpsim_planar::car::{Axle, Layout, PlanarCar};
use bumpsim_planar::drive::{Drive, Sensor, drive, segment_loads};
use bumpsim_planar::{Face, Settings, Side, Striker, simulate};
use criterion::{Criterion, criterion_group, criterion_main};

fn benches(c: &mut Criterion) {
    let chain = MsdModel::new(vec![12.0, 1300.0], vec![2e3], vec![1.5e6]).unwrap();
    let bumper = Bumper::three_part(3e6, 150e3, 1.2e7).unwrap();
    let mut layout = Layout {
        bending: 1e5,
        ..Layout::default()
    };
    // free-rolling wheels: rolling resistance along, tyre grip across
    for axle in [&mut layout.tyres.front, &mut layout.tyres.rear] {
        *axle = Axle::rolling(0.015, 0.8);
    }
    let car = PlanarCar::symmetric(&chain, &bumper, &layout).unwrap();
    let face = Face::Plane {
        angle: 30f64.to_radians(),
        overlap: 1.0,
        side: Side::Left,
    };
    let striker = Striker::barrier(face, 8.0 / 3.6);
    let mut group = c.benchmark_group("planar");
    group.bench_function("8 km/h 30° angled barrier, 10 segments", |b| {
        b.iter(|| simulate(&car, &striker, &Settings::default()).unwrap())
    });
    // the identification's unit of work: that impact replayed from its 10
    // segment forces (0.1-ms samples, sills and side members measured)
    let r = simulate(&car, &striker, &Settings::default()).unwrap();
    let normal = [-(30f64.to_radians().cos()), -(30f64.to_radians().sin())];
    let loads = segment_loads(&r, normal);
    let sensors = vec![
        Sensor::Body([0.6, 0.7]),
        Sensor::Body([0.6, -0.7]),
        Sensor::Chain(0),
        Sensor::Chain(1),
    ];
    let input = Drive {
        step: 1e-4,
        loads,
        speed: 8.0 / 3.6,
        arm: 1.0,
        sensors,
    };
    let samples = r.time.len();
    group.bench_function(format!("replay of that impact, {samples} samples"), |b| {
        b.iter(|| drive(&car, &input, 0.05).unwrap())
    });
    group.finish();
}

criterion_group!(planar, benches);
criterion_main!(planar);
