//! Criterion benchmarks of the verdict and the bumper-target search on the
//! worked example (`examples/verdict/`): the bundled planar car's front in
//! 49 CFR 581 and the RCAR bumper test (six front tests). Figures and the
//! impacts-per-second target (≥ 1000 on 2 cores): docs/benchmarks.md.
//!
//! The search's throughput is in impacts (criterion's `elem/s`: every
//! candidate runs all six tests to their end); each search also prints its
//! impacts per second of wall time and, on Linux, per second of the
//! process's CPU time (what a loaded machine does not change).

use bumpsim_verdict::prelude::*;
use bumpsim_verdict::protocol::select;
use bumpsim_verdict::target::{search, search_settings};
use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use std::path::Path;

fn setup() -> Setup {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/verdict/car.toml");
    let car = bumpsim_planar::PlanarCar::read(&path).unwrap();
    let end = CarEnd::new(car, Damageability::read(&path).unwrap()).unwrap();
    Setup::new(vec![end], select(&["part581", "rcar-bumper"]).unwrap(), 0.0).unwrap()
}

/// The process's CPU time (user and system), s; None off Linux.
fn cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // fields after the command's closing parenthesis; utime and stime are
    // the 14th and 15th fields, in clock ticks (100 per second)
    let rest = &stat[stat.rfind(')')? + 2..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    let ticks: f64 = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

fn benches(c: &mut Criterion) {
    let setup = setup();
    let mut group = c.benchmark_group("verdict");
    group.sample_size(10);
    group.bench_function("verdict, 6 front tests (581 and RCAR bumper)", |b| {
        b.iter(|| verdict(&setup).unwrap())
    });
    let coarse = search_settings(&setup.settings);
    for test in &setup.tests {
        if let Some(end) = setup.end(test.end) {
            group.bench_function(format!("impact {}", test.name), |b| {
                b.iter(|| bumpsim_verdict::verdict::run(end, test, &setup.settings).unwrap())
            });
            group.bench_function(format!("search impact {}", test.name), |b| {
                b.iter(|| bumpsim_verdict::verdict::run(end, test, &coarse).unwrap())
            });
        }
    }
    let options = TargetOptions::default();
    let impacts = search(&setup, &options).unwrap().impacts;
    group.throughput(Throughput::Elements(impacts as u64));
    group.bench_function("target search, 12 rows x 9 levels, 1 % tolerance", |b| {
        b.iter(|| {
            let cpu = cpu_seconds();
            let region = search(&setup, &options).unwrap();
            let per_cpu = cpu
                .zip(cpu_seconds())
                .map(|(a, b)| format!(", {:.0} per CPU second", region.impacts as f64 / (b - a)))
                .unwrap_or_default();
            eprintln!(
                "{} impacts in {:.2} s: {:.0} impacts/s{per_cpu}",
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
