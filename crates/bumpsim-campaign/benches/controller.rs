//! Criterion benchmark of the controller's overhead per point: a 100-point
//! campaign whose solver is `true` (a no-op), run by the local executor
//! with 2 slots; each iteration re-runs it from a pending state. The time
//! per point covers the task process (`sh run-point.sh` + `true`), the exit
//! marker, the polling and the journal's appends (one `fdatasync` per
//! round). The same at 1 000 to 100 000 points, against an `xargs -P2`
//! baseline: bench/campaign_scale.sh. Figures: docs/benchmarks.md.

use bumpsim_campaign::init::init;
use bumpsim_campaign::run::{RunOptions, run};
use bumpsim_campaign::state::{State, Status};
use criterion::{Criterion, criterion_group, criterion_main};
use std::path::Path;
use std::time::{Duration, Instant};

const POINTS: usize = 100;

fn campaign(dir: &Path) {
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(dir.join("deck.tmpl"), "k = {{k}}\n").unwrap();
    let text = format!(
        "name = \"bench\"\n[design]\nkind = \"lhs\"\nruns = {POINTS}\nfactors = [{{ name = \"k\", low = 1, high = 2 }}]\n\
         [template]\nfile = \"deck.tmpl\"\n[solver]\ncommand = [\"true\"]\n[executor]\nslots = 2\n"
    );
    std::fs::write(dir.join("c.toml"), text).unwrap();
    init(&dir.join("c.toml"), &dir.join("c")).unwrap();
}

/// Marks every point pending again (as `init` leaves them).
fn reset(dir: &Path) {
    let mut state = State::read(dir).unwrap();
    for p in &mut state.points {
        p.status = Status::Pending;
        p.attempts = 0;
    }
    state.write(dir).unwrap();
}

fn benches(c: &mut Criterion) {
    let dir = std::env::temp_dir().join(format!("bumpsim-bench-campaign-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    campaign(&dir);
    let folder = dir.join("c");
    let mut group = c.benchmark_group("campaign controller");
    group.sample_size(10);
    group.bench_function("per point, no-op solver, local executor, 2 slots", |b| {
        b.iter_custom(|iterations| {
            let mut total = Duration::ZERO;
            for _ in 0..iterations {
                reset(&folder);
                let start = Instant::now();
                let summary = run(&folder, &RunOptions::default()).unwrap();
                total += start.elapsed() / POINTS as u32;
                assert_eq!(summary.done, POINTS);
            }
            total
        })
    });
    group.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(controller, benches);
criterion_main!(controller);
