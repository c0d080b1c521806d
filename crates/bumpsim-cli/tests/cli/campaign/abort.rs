//! `campaign abort`: running tasks stopped (SIGTERM locally, `scancel` on
//! Slurm) and their points pending.

use super::{Fake, Faults, NO_FAULTS, path, processes_in, run, slurm_cluster};
use crate::util::{assert_contains, text};
use std::time::{Duration, Instant};

/// `campaign abort` after the controller is stopped: the running tasks are
/// stopped (SIGTERM locally, `scancel` on Slurm) and their points pending.
fn abort_stops_the_running_tasks(executor: &str) {
    let slow = Faults {
        slow: &["0001", "0002", "0003", "0004"],
        ..NO_FAULTS
    };
    let fake = Fake::new(&format!("campaign-abort-{executor}"), 0, &slow, executor);
    let mut controller = fake.spawn_run(&[]);
    let start = Instant::now();
    while fake.state().matches("status = \"running\"").count() < 2 {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "{}",
            fake.state()
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    controller.kill().unwrap();
    controller.wait().unwrap();
    let out = run(&["campaign", "abort", path(&fake.campaign())]);
    assert_contains(&text(&out.stdout), &["cancelled"]);
    let state = fake.state();
    assert_eq!(
        state.matches("cancelled by campaign abort").count(),
        state.matches("attempts = 1").count(),
        "{state}"
    );
    assert!(!state.contains("status = \"running\"") && !state.contains("status = \"submitted\""));
    std::thread::sleep(Duration::from_secs(2));
    // stopped, not finished: no solver got to write its output
    for run in 1..=4 {
        let output = fake.campaign().join(format!("points/{run:04}/out.csv"));
        assert!(!output.exists(), "run {run} finished after the abort");
    }
    // and nothing the solver started lives on (its `sleep` is a child of
    // the solver script, a grandchild of the task)
    let left = processes_in(&fake.campaign());
    assert!(left.is_empty(), "still running in the campaign: {left:?}");
    // and the next run starts them afresh
    std::fs::write(fake.dir.join("solver.sh"), "#!/bin/sh\ncp in.csv out.csv\n").unwrap();
    let out = run(&["campaign", "run", path(&fake.campaign())]);
    assert_contains(&text(&out.stdout), &["4 points done, 0 failed"]);
}

#[test]
fn abort_stops_local_tasks() {
    abort_stops_the_running_tasks("local");
}

#[test]
fn abort_cancels_slurm_tasks() {
    if let Some(_cluster) = slurm_cluster() {
        abort_stops_the_running_tasks("slurm");
    }
}
