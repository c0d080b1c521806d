//! Criterion benchmarks of the verdict and the bumper-target search on the
//! worked example (`examples/verdict/`): the bundled planar car's front in
//! 49 CFR 581 and the RCAR bumper test (six front tests). Figures and the
//! impacts-per-second target (≥ 1000 on 2 cores): docs/benchmarks.md.

use bumpsim_verdict::prelude::*;
use bumpsim_verdict::protocol::select;
use bumpsim_verdict::target::search;
use criterion::{Criterion, criterion_group, criterion_main};
use std::path::Path;

fn setup() -> Setup {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/verdict/car.toml");
    let car = bumpsim_planar::PlanarCar::read(&path).unwrap();
    let end = CarEnd::new(car, Damageability::read(&path).unwrap()).unwrap();
    Setup::new(vec![end], select(&["part581", "rcar-bumper"]).unwrap(), 0.0).unwrap()
}

fn benches(c: &mut Criterion) {
    let setup = setup();
    let mut group = c.benchmark_group("verdict");
    group.sample_size(10);
    group.bench_function("verdict, 6 front tests (581 and RCAR bumper)", |b| {
        b.iter(|| verdict(&setup).unwrap())
    });
    for test in &setup.tests {
        if let Some(end) = setup.end(test.end) {
            group.bench_function(format!("impact {}", test.name), |b| {
                b.iter(|| bumpsim_verdict::verdict::run(end, test, &setup.settings).unwrap())
            });
        }
    }
    let options = TargetOptions::default();
    group.bench_function("target search, 12 rows x 9 levels, 1 % tolerance", |b| {
        b.iter(|| {
            let region = search(&setup, &options).unwrap();
            eprintln!(
                "{} impacts in {:.2} s: {:.0} impacts/s",
                region.impacts,
                region.seconds,
                region.rate()
            );
            region
        })
    });
    group.finish();
}

criterion_group!(verdict_benches, benches);
criterion_main!(verdict_benches);
