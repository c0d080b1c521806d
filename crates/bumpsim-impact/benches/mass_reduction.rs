//! Criterion benchmark of the mass-reduction sweep: 50 × 50 (k, M1/(M1+M2))
//! grid of 2-DOF impacts into a rigid barrier, on all cores (target: under
//! 2 s on two). Figures: docs/benchmarks.md.

use bumpsim_impact::bumper::Bumper;
use bumpsim_impact::reduction::{Criterion as Rule, linspace, sweep_car};
use criterion::{Criterion, criterion_group, criterion_main};

fn benches(c: &mut Criterion) {
    let bumper = Bumper::three_part(2e6, 80e3, 8e6).unwrap();
    let mut group = c.benchmark_group("mass reduction");
    group.sample_size(10);
    group.bench_function("sweep 50 x 50 (k, mass ratio), remaining", |b| {
        b.iter(|| {
            sweep_car(
                1050.0,
                linspace(1e5, 1e7, 50),
                linspace(0.52, 0.95, 50),
                &bumper,
                8.0 / 3.6,
                Rule::Remaining,
                &|| {},
            )
        })
    });
    group.finish();
}

criterion_group!(mass_reduction, benches);
criterion_main!(mass_reduction);
