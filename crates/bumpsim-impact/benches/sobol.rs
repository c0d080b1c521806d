//! Criterion benchmark of issue 39's Sobol' indices of an impact output: the
//! peak force of a 1-D pendulum impact on a 2-mass car behind a three-part
//! bumper over six parameters, 10 000 base samples (80 000 impacts) on all
//! cores (target: under 10 s on two). The indices themselves are checked
//! against SALib in `tests/sobol_impact.rs`. Figures: docs/benchmarks.md.

use bumpsim_estimate::sobol::{Settings, indices};
use criterion::{Criterion, criterion_group, criterion_main};

#[path = "sobol/model.rs"]
mod model;

fn benches(c: &mut Criterion) {
    let inputs = model::inputs();
    let mut group = c.benchmark_group("sobol");
    group.sample_size(10);
    group.bench_function("peak force, 6 parameters x 10 000 base samples", |b| {
        b.iter(|| indices(&inputs, &model::peak_force, &Settings::new(10_000, 1)))
    });
    group.finish();
}

criterion_group!(sobol, benches);
criterion_main!(sobol);
