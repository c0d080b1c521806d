//! A real Slurm cluster: the bundled campaign like the local executor,
//! faults, `scancel` and a killed controller, a refused `sbatch`, a
//! campaign larger than the cluster's MaxArraySize, and a node failure.

use super::{
    Fake, Faults, NO_FAULTS, path, point, run, scontrol, slurm_cluster, slurm_cluster_alone,
    slurm_node, slurm_resume,
};
use crate::util::{
    assert_contains, assert_user_error, bumpsim, peer_available, root, scratch, text,
};
use std::process::Command;
use std::time::{Duration, Instant};

/// The bundled CalculiX campaign through a real Slurm cluster: the
/// collected table equals the local executor's.
#[test]
fn slurm_runs_the_calculix_campaign_like_the_local_executor() {
    let Some(_cluster) = slurm_cluster() else {
        return;
    };
    if !peer_available("CalculiX (ccx)", "sh", &["-c", "command -v ccx"]) {
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
    let state = super::state_text(&dir.join("slurm"));
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
    let Some(_cluster) = slurm_cluster() else {
        return;
    };
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
    let Some(_cluster) = slurm_cluster() else {
        return;
    };
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

/// The cluster's MaxArraySize (`scontrol show config`).
fn max_array_size() -> usize {
    let out = Command::new("scontrol")
        .args(["show", "config"])
        .output()
        .unwrap();
    text(&out.stdout)
        .lines()
        .filter_map(|l| l.split_once('='))
        .find(|(k, _)| k.trim() == "MaxArraySize")
        .and_then(|(_, v)| v.trim().parse().ok())
        .unwrap()
}

/// The array job ids of a campaign's points, in order of first use.
fn array_jobs(state: &str) -> Vec<String> {
    let mut jobs: Vec<String> = Vec::new();
    for piece in state.split("job = \"slurm:").skip(1) {
        let job = piece[..piece.find('_').unwrap()].to_string();
        if !jobs.contains(&job) {
            jobs.push(job);
        }
    }
    jobs
}

/// `sacct -D` of the given jobs: `JOB_INDEX|STATE` lines, once every one
/// of `expected` tasks has a final state (accounting lags a little).
fn accounting(jobs: &[String], expected: usize) -> String {
    let start = Instant::now();
    loop {
        let out = Command::new("sacct")
            .args([
                "-n",
                "-P",
                "-D",
                "-X",
                "-o",
                "JobID,State",
                "-j",
                &jobs.join(","),
            ])
            .output()
            .unwrap();
        let rows = text(&out.stdout);
        let ended = rows.lines().filter(|l| l.contains("|COMPLETED")).count();
        if ended >= expected || start.elapsed() > Duration::from_secs(20) {
            return rows;
        }
        std::thread::sleep(Duration::from_millis(500));
    }
}

/// A campaign larger than the cluster's MaxArraySize (10 on the test
/// cluster of scripts/slurm-up): its runs are cut into arrays below it
/// (three here), every point runs once, the accounting (`sacct`) records
/// every task COMPLETED, and the table equals the local executor's.
#[test]
fn a_campaign_larger_than_max_array_size_runs_like_the_local_executor() {
    let Some(_cluster) = slurm_cluster() else {
        return;
    };
    let max = max_array_size();
    if max > 50 {
        assert!(
            std::env::var_os("BUMPSIM_REQUIRE_SLURM").is_none(),
            "MaxArraySize {max}: scripts/slurm-up sets 10"
        );
        eprintln!("skipped: MaxArraySize {max} (scripts/slurm-up sets 10)");
        return;
    }
    // three arrays: blocks of max - 1 runs
    let points = 2 * (max - 1) + 3;
    let tables: Vec<String> = ["local", "slurm"]
        .iter()
        .map(|executor| {
            let test = format!("campaign-max-array-{executor}");
            let fake = Fake::new(&test, points - 4, &NO_FAULTS, executor);
            let out = run(&["campaign", "run", path(&fake.campaign())]);
            assert_contains(
                &text(&out.stdout),
                &[&format!("{points} points done, 0 failed")],
            );
            for r in 1..=points {
                assert_eq!(fake.invocations(&format!("{r:04}")), 1, "{}", fake.state());
            }
            if *executor == "slurm" {
                let jobs = array_jobs(&fake.state());
                assert_eq!(jobs.len(), 3, "{}", fake.state());
                let rows = accounting(&jobs, points);
                let completed = rows.lines().filter(|l| l.ends_with("|COMPLETED")).count();
                assert_eq!(completed, points, "{rows}");
            }
            fake.collect();
            fake.table()
        })
        .collect();
    assert_eq!(tables[0], tables[1]);
}

/// Puts the node back in service, whatever the test did (it may be back
/// already: ReturnToService=2).
struct Resume;

impl Drop for Resume {
    fn drop(&mut self) {
        slurm_resume();
    }
}

/// The node fails while tasks run (`scontrol update state=down`, the cluster
/// held alone): Slurm requeues them; the controller records each requeue as
/// an attempt with its cause from the accounting (NODE_FAIL), shows the
/// requeued tasks as queued again, and every point ends done with its
/// solver run once per attempt.
#[test]
fn a_node_failure_requeue_is_recorded_with_its_reason_and_counted() {
    let Some(_cluster) = slurm_cluster_alone() else {
        return;
    };
    let faults = Faults {
        sleep: 3.0,
        ..NO_FAULTS
    };
    let fake = Fake::new("campaign-slurm-node-failure", 0, &faults, "slurm");
    let mut controller = fake.spawn_run(&[]);
    let start = Instant::now();
    while fake.state().matches("status = \"running\"").count() < 2
        || std::fs::read_to_string(&fake.log).unwrap().lines().count() < 2
    {
        assert!(
            start.elapsed() < Duration::from_secs(60),
            "{}",
            fake.state()
        );
        std::thread::sleep(Duration::from_millis(100));
    }
    let _resume = Resume;
    let node = format!("nodename={}", slurm_node());
    scontrol(&[
        "update",
        &node,
        "state=down",
        "reason=bumpsim test: node failure",
    ]);
    let start = Instant::now();
    let status = loop {
        if let Some(status) = controller.try_wait().unwrap() {
            break status;
        }
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "{}",
            fake.state()
        );
        // the node back (ReturnToService may have done it), and the requeued
        // tasks released: Slurm holds them back for 120 s
        slurm_resume();
        for job in array_jobs(&fake.state()) {
            scontrol(&["update", &format!("jobid={job}"), "starttime=now"]);
        }
        std::thread::sleep(Duration::from_millis(300));
    };
    assert!(status.success(), "{}", fake.state());
    let state = fake.state();
    let mut requeued = 0;
    for run in 1..=4 {
        let block = point(&state, run);
        let requeues: u32 = block
            .split("requeues = ")
            .nth(1)
            .and_then(|r| r.lines().next()?.parse().ok())
            .unwrap();
        assert_contains(
            &block,
            &["status = \"done\"", &format!("attempts = {}", 1 + requeues)],
        );
        assert_eq!(
            fake.invocations(&format!("{run:04}")),
            1 + requeues as usize,
            "run {run}: {state}"
        );
        if requeues > 0 {
            assert_contains(
                &block,
                &["requeued by Slurm: a node failure (sacct: NODE_FAIL)"],
            );
            requeued += 1;
        }
    }
    assert!(requeued >= 1, "{state}");
    let rows = accounting(&array_jobs(&state), 4);
    assert!(rows.contains("|NODE_FAIL"), "{rows}");
    fake.collect();
    assert_eq!(fake.table().lines().count(), 1 + 4);
}
