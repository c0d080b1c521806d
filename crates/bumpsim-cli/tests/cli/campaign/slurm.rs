//! A real Slurm cluster: the bundled campaign like the local executor,
//! faults, `scancel` and a killed controller, and a refused `sbatch`.

use super::{Fake, Faults, NO_FAULTS, path, point, run, slurm_available};
use crate::util::{
    assert_contains, assert_user_error, bumpsim, peer_available, root, scratch, text,
};
use std::process::Command;
use std::time::{Duration, Instant};

/// The bundled CalculiX campaign through a real Slurm cluster: the
/// collected table equals the local executor's.
#[test]
fn slurm_runs_the_calculix_campaign_like_the_local_executor() {
    if !slurm_available() || !peer_available("CalculiX (ccx)", "sh", &["-c", "command -v ccx"]) {
        return;
    }
    let dir = scratch("campaign-slurm-example");
    let campaign = root().join("examples/campaign/campaign.toml");
    for executor in ["local", "slurm"] {
        let c = dir.join(executor);
        run(&["campaign", "init", path(&campaign), "-o", path(&c)]);
        let out = run(&["campaign", "run", path(&c), "--executor", executor]);
        assert_contains(&text(&out.stdout), &["9 points done, 0 failed"]);
        run(&["campaign", "collect", path(&c)]);
    }
    let state = std::fs::read_to_string(dir.join("slurm/state.toml")).unwrap();
    assert!(state.contains("job = \"slurm:"), "{state}");
    let table = |e: &str| std::fs::read_to_string(dir.join(e).join("results/table.csv")).unwrap();
    assert_eq!(table("local"), table("slurm"));
}

/// Faults on the real cluster in one campaign of 8 points: point 2 fails
/// once (retried), point 3 always (failed with its reason), point 4 is
/// `scancel`led while running (retried), and the controller is killed with
/// SIGKILL mid-campaign and restarted. Nothing lost, no duplicate rows, no
/// finished point run again.
#[test]
fn slurm_faults_are_retried_recorded_and_survive_a_killed_controller() {
    if !slurm_available() {
        return;
    }
    let faults = Faults {
        sleep: 1.0,
        fail_once: &["0002"],
        fail_always: &["0003"],
        slow: &[],
        corrupt: &[],
    };
    let fake = Fake::new("campaign-slurm-faults", 4, &faults, "slurm");
    // point 4 runs long enough to be cancelled: its own solver sleeps more
    let solver = fake.dir.join("solver.sh");
    let script = std::fs::read_to_string(&solver).unwrap();
    let script = script.replacen("sleep 1\n", "sleep 1\n[ \"$p\" = 0004 ] && [ ! -e cancelled-once ] && touch cancelled-once && sleep 60\n", 1);
    std::fs::write(&solver, script).unwrap();
    let mut controller = fake.spawn_run(&[]);
    let start = Instant::now();
    let job = loop {
        let block = point(&fake.state(), 4);
        if block.contains("status = \"running\"")
            && fake.campaign().join("points/0004/cancelled-once").exists()
        {
            let job = block.split("job = \"slurm:").nth(1).unwrap();
            break job[..job.find('"').unwrap()].to_string();
        }
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "{}",
            fake.state()
        );
        std::thread::sleep(Duration::from_millis(100));
    };
    assert!(
        Command::new("scancel")
            .arg(&job)
            .status()
            .unwrap()
            .success()
    );
    fake.wait_done(2);
    controller.kill().unwrap(); // SIGKILL mid-campaign
    controller.wait().unwrap();
    let out = run(&["campaign", "run", path(&fake.campaign())]);
    assert_contains(&text(&out.stdout), &["7 points done, 1 failed"]);
    let counts: Vec<usize> = (1..=8)
        .map(|r| fake.invocations(&format!("{r:04}")))
        .collect();
    assert_eq!(counts, [1, 2, 3, 2, 1, 1, 1, 1], "{}", fake.state());
    let state = fake.state();
    assert_contains(
        &point(&state, 3),
        &["status = \"failed\"", "attempt 3 of 3: solver exit code 3"],
    );
    // scancel's SIGTERM: Slurm's CANCELLED, or the solver's own exit by
    // the signal when the task shell recorded it first
    let cancelled = point(&state, 4);
    assert_contains(&cancelled, &["status = \"done\"", "attempts = 2"]);
    assert!(
        cancelled.contains("CANCELLED") || cancelled.contains("SIGTERM"),
        "{cancelled}"
    );
    fake.collect();
    let table = fake.table();
    let runs: Vec<&str> = table
        .lines()
        .skip(1)
        .map(|l| l.split(',').next().unwrap())
        .collect();
    assert_eq!(runs, ["1", "2", "4", "5", "6", "7", "8"], "{table}");
}

/// A partition the cluster does not have: `sbatch` refuses, the run stops
/// with its message (exit 2) and every point is still pending, unrun.
#[test]
fn a_refused_sbatch_stops_the_run_with_its_message() {
    if !slurm_available() {
        return;
    }
    let fake = Fake::new("campaign-slurm-refused", 0, &NO_FAULTS, "slurm");
    let spec = fake.campaign().join("campaign.toml");
    let edited = std::fs::read_to_string(&spec).unwrap()
        + "[executor.slurm]\npartition = \"no-such-partition\"\n";
    std::fs::write(&spec, edited).unwrap();
    let out = bumpsim(&["campaign", "run", path(&fake.campaign())]);
    assert_user_error(&out, "sbatch");
    assert_contains(&text(&out.stderr), &["no-such-partition"]);
    assert_eq!(
        fake.state().matches("status = \"pending\"").count(),
        4,
        "{}",
        fake.state()
    );
    assert_eq!(std::fs::read_to_string(&fake.log).unwrap(), "");
}
