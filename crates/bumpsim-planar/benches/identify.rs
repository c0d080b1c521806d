//! Criterion benchmark: the bundled planar identification (issue 32's speed
//! target: under 1 s on 2 cores). The series of
//! `examples/planar/identify/series.toml` made in memory (`make_series`),
//! its four training tests conditioned as the study conditions them (CFC
//! 180, time zero before the force onset), identified from the series'
//! start with lateral grip, 8 starts, seed 1 — the work `bumpsim identify
//! out/planar-series/study.toml` does after reading its files. Figures:
//! docs/benchmarks.md.

use bumpsim_planar::PlanarCar;
use bumpsim_planar::cases::TestChannels;
use bumpsim_planar::identify::{PlanarCase, Setup, identify};
use bumpsim_planar::series::make_series;
use criterion::{Criterion, criterion_group, criterion_main};
use std::path::Path;

fn training() -> (Vec<PlanarCase>, Setup) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/planar/identify");
    let series = make_series(&root.join("series.toml")).unwrap();
    let cases = series
        .tests
        .iter()
        .filter(|t| t.name != "OFFSET-RIGHT")
        .map(|t| TestChannels::of(t).case().unwrap().0)
        .collect();
    let start = PlanarCar::parse(&series.start, Path::new("start.toml")).unwrap();
    let setup = Setup {
        friction: true,
        ..Setup::new(start)
    };
    (cases, setup)
}

fn benches(c: &mut Criterion) {
    let (cases, setup) = training();
    let mut group = c.benchmark_group("planar");
    group.sample_size(10);
    group.bench_function("identification of the bundled series, 8 starts", |b| {
        b.iter(|| identify(&cases, &setup, &|| {}).unwrap())
    });
    group.finish();
}

criterion_group!(planar, benches);
criterion_main!(planar);
