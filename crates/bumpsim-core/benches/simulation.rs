//! Criterion benchmarks of the simulation hot loop (state propagation) and of
//! a full response (forces, accelerations, exact energies).
//!
//! Figures are recorded in docs/benchmarks.md.

use bumpsim_core::prelude::*;
use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use std::hint::black_box;

fn chain(dof: usize) -> MsdModel {
    let masses = (0..dof).map(|i| 150.0 + 100.0 * i as f64).collect();
    MsdModel::new(masses, vec![2e3; dof - 1], vec![5e5; dof - 1]).unwrap()
}

fn force(samples: usize) -> UniformSeries {
    let values = (0..samples)
        .map(|i| 4e4 * (i as f64 * 0.005).sin().max(0.0))
        .collect();
    UniformSeries::new(0.0, 1e-4, values).unwrap()
}

fn propagate(c: &mut Criterion) {
    let mut group = c.benchmark_group("propagate");
    for (dof, samples) in [(3, 1000), (3, 100_000), (10, 1000)] {
        let discrete = DiscreteModel::new(&chain(dof), Method::Zoh, 1e-4).unwrap();
        let force = force(samples);
        let initial = vec![0.0; 2 * dof];
        let mut states = vec![0.0; samples * 2 * dof];
        group.throughput(Throughput::Elements(samples as u64 - 1));
        group.bench_function(BenchmarkId::new(format!("{dof}dof"), samples), |b| {
            b.iter(|| {
                discrete
                    .propagate(black_box(&initial), black_box(force.values()), &mut states)
                    .unwrap();
                black_box(states[states.len() - 1])
            })
        });
    }
    group.finish();
}

fn full_response(c: &mut Criterion) {
    let mut group = c.benchmark_group("simulate");
    for dof in [3, 10] {
        let simulator = Simulator::new(&chain(dof), Method::Zoh, 1e-4).unwrap();
        let force = force(1000);
        group.throughput(Throughput::Elements(999));
        group.bench_function(BenchmarkId::new(format!("{dof}dof_response"), 1000), |b| {
            b.iter(|| {
                simulator
                    .run(black_box(&force), &InitialState::Rest)
                    .unwrap()
            })
        });
    }
    group.finish();
    c.bench_function("discretise/zoh_3dof_with_energy_integrals", |b| {
        let car = chain(3);
        b.iter(|| Simulator::new(black_box(&car), Method::Zoh, 1e-4).unwrap())
    });
}

/// The Rust side of the Python package's benchmark (issue 18,
/// bench/python_simulate_timing.py): a 1e6-sample force given as sample
/// times and values, turned into a series, discretised and simulated with
/// the full response, exactly the calls `bumpsim.simulate` makes.
fn from_times_1e6(c: &mut Criterion) {
    let samples = 1_000_000;
    let car = chain(3);
    let times: Vec<f64> = (0..samples).map(|i| i as f64 * 1e-4).collect();
    let values = force(samples).values().to_vec();
    let mut group = c.benchmark_group("simulate");
    group.sample_size(10);
    group.bench_function(BenchmarkId::new("3dof_response_from_times", samples), |b| {
        b.iter(|| {
            let force = UniformSeries::from_times(black_box(&times), values.clone()).unwrap();
            Simulator::new(&car, Method::Zoh, force.step())
                .unwrap()
                .run(&force, &InitialState::UniformVelocity(0.0))
                .unwrap()
        })
    });
    group.finish();
}

criterion_group!(benches, propagate, full_response, from_times_1e6);
criterion_main!(benches);
