//! The controller with the fake solver on the local executor: input
//! refused before anything runs, retries and failures, a killed controller
//! resumed, the lock, a task started but not recorded, 1000 points, and
//! input hashes deciding what runs again.

use super::{Fake, Faults, NO_FAULTS, path, point, run};
use crate::util::{assert_contains, assert_user_error, bumpsim, scratch, text};
use std::process::Command;
use std::time::{Duration, Instant};

/// Unknown names, a placeholder with no factor, a solver not on PATH and
/// sbatch missing under executor = "slurm": exit 2 before anything runs.
#[test]
fn bad_input_is_refused_before_anything_is_submitted() {
    let fake = Fake::new("campaign-bad-input", 0, &NO_FAULTS, "local");
    let dir = &fake.dir;
    let campaign = std::fs::read_to_string(dir.join("campaign.toml")).unwrap();
    let init = |name: &str, text: &str| {
        let file = dir.join(format!("{name}.toml"));
        std::fs::write(&file, text).unwrap();
        bumpsim(&["campaign", "init", path(&file), "-o", path(&dir.join(name))])
    };
    let out = init("unknown", &campaign.replace("2 * a + b", "2 * a + t_rail"));
    assert_user_error(&out, "derived.y: unknown name 't_rail' (factors: a, b)");
    std::fs::write(
        dir.join("in2.tmpl"),
        "time [s],y [m]\n0,0\n1,{{ t_rail }}\n",
    )
    .unwrap();
    let out = init("placeholder", &campaign.replace("in.tmpl", "in2.tmpl"));
    assert_user_error(
        &out,
        "in2.tmpl:3: placeholder {{t_rail}} has no factor or derived quantity",
    );
    let solver = fake.dir.join("solver.sh");
    let out = init(
        "solver",
        &campaign.replace(path(&solver), "no-such-solver-x9"),
    );
    assert_user_error(&out, "solver 'no-such-solver-x9' not found on PATH");
    for name in ["unknown", "placeholder", "solver"] {
        assert!(!dir.join(name).exists(), "{name}: nothing written");
    }
    // sbatch missing: refused before any point is submitted
    let out = Command::new(env!("CARGO_BIN_EXE_bumpsim"))
        .args([
            "campaign",
            "run",
            path(&fake.campaign()),
            "--executor",
            "slurm",
        ])
        .env("PATH", "/nonexistent")
        .output()
        .unwrap();
    assert_user_error(
        &out,
        "executor = \"slurm\" needs 'sbatch' not found on PATH",
    );
    assert_eq!(std::fs::read_to_string(&fake.log).unwrap(), "");
    assert!(fake.state().matches("status = \"pending\"").count() == 4);
}

/// One point fails once (retried, done), one always (failed with its
/// reason after 3 attempts), one writes a corrupt output (failed, not
/// retried, never a zero); the rest complete and are collected.
#[test]
fn local_failures_are_retried_recorded_and_never_read_as_zeros() {
    let faults = Faults {
        fail_once: &["0002"],
        fail_always: &["0003"],
        corrupt: &["0004"],
        ..NO_FAULTS
    };
    let fake = Fake::new("campaign-local-faults", 2, &faults, "local");
    let out = bumpsim(&["campaign", "run", path(&fake.campaign())]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert_contains(&text(&out.stdout), &["4 points done, 2 failed"]);
    assert_eq!(
        [
            fake.invocations("0001"),
            fake.invocations("0002"),
            fake.invocations("0003"),
            fake.invocations("0004")
        ],
        [1, 2, 3, 1]
    );
    let state = fake.state();
    assert_contains(&point(&state, 2), &["status = \"done\"", "attempts = 2"]);
    assert_contains(
        &point(&state, 3),
        &[
            "status = \"failed\"",
            "attempts = 3",
            "attempt 3 of 3: solver exit code 3 (see points/0003/solver.log)",
        ],
    );
    assert_contains(
        &point(&state, 4),
        &[
            "status = \"failed\"",
            "output: point 4: response 'y_max'",
            "zero",
        ],
    );
    let status = text(&run(&["campaign", "status", path(&fake.campaign())]).stdout);
    assert_contains(
        &status,
        &[
            "6 points: 4 done, 2 failed",
            "run 3: failed: attempt 3 of 3",
        ],
    );
    let out = fake.collect();
    assert_contains(
        &text(&out.stderr),
        &["run 3 left out of the table: failed", "run 4 left out"],
    );
    let table = fake.table();
    assert_eq!(table.lines().count(), 1 + 4, "{table}");
    assert!(
        !table
            .lines()
            .any(|l| l.starts_with("3,") || l.starts_with("4,")),
        "{table}"
    );
    // a second run has nothing to do; --retry-failed gives failures new attempts
    let out = run(&["campaign", "run", path(&fake.campaign())]);
    assert_contains(&text(&out.stdout), &["(0 tasks submitted by this run)"]);
    assert_eq!(fake.invocations("0001"), 1);
}

/// The controller killed with SIGKILL mid-campaign and restarted: no
/// finished point runs again, the tasks in flight are adopted, all collected.
#[test]
fn a_killed_controller_resumes_without_rerunning_finished_points() {
    let fake = Fake::new(
        "campaign-local-kill",
        4,
        &Faults {
            sleep: 0.4,
            ..NO_FAULTS
        },
        "local",
    );
    let mut controller = fake.spawn_run(&[]);
    fake.wait_done(3);
    controller.kill().unwrap(); // SIGKILL
    controller.wait().unwrap();
    assert!(
        fake.campaign().join(".lock").exists(),
        "the killed controller left its lock"
    );
    let status = text(&run(&["campaign", "status", path(&fake.campaign())]).stdout);
    assert_contains(&status, &["controller: none running (stale lock of pid"]);
    let out = run(&["campaign", "run", path(&fake.campaign())]);
    assert_contains(&text(&out.stdout), &["8 points done, 0 failed"]);
    for run in 1..=8 {
        assert_eq!(
            fake.invocations(&format!("{run:04}")),
            1,
            "point {run}: {}",
            fake.state()
        );
    }
    fake.collect();
    assert_eq!(fake.table().lines().count(), 1 + 8);
}

/// A second controller on a running campaign is refused (and so is `init`
/// over it); the first finishes undisturbed.
#[test]
fn a_second_controller_is_refused() {
    let fake = Fake::new(
        "campaign-lock",
        0,
        &Faults {
            sleep: 0.5,
            ..NO_FAULTS
        },
        "local",
    );
    let mut first = fake.spawn_run(&["--slots", "1"]);
    let start = Instant::now();
    while !fake.campaign().join(".lock").exists() {
        assert!(start.elapsed() < Duration::from_secs(20));
        std::thread::sleep(Duration::from_millis(10));
    }
    let second = bumpsim(&["campaign", "run", path(&fake.campaign())]);
    assert_user_error(&second, "the campaign is run by another controller (pid");
    let reinit = bumpsim(&[
        "campaign",
        "init",
        path(&fake.dir.join("campaign.toml")),
        "-o",
        path(&fake.campaign()),
    ]);
    assert_user_error(&reinit, "another controller");
    assert!(first.wait().unwrap().success());
    assert_eq!(
        (1..=4)
            .map(|r| fake.invocations(&format!("{r:04}")))
            .sum::<usize>(),
        4
    );
}

/// 1000 points: init, status and a state write each well under 1 s; a run
/// with a no-op solver finishes them all.
#[test]
fn a_thousand_point_campaign_is_handled_quickly() {
    let dir = scratch("campaign-1000");
    std::fs::write(dir.join("deck.tmpl"), "k = {{k}}\n").unwrap();
    let campaign = "name = \"big\"\n[design]\nkind = \"lhs\"\nruns = 1000\nfactors = [{ name = \"k\", low = 1, high = 2 }]\n[template]\nfile = \"deck.tmpl\"\n[solver]\ncommand = [\"true\"]\n[executor]\nslots = 2\n";
    std::fs::write(dir.join("c.toml"), campaign).unwrap();
    let c = dir.join("c");
    let timed = |args: &[&str]| {
        let start = Instant::now();
        let out = run(args);
        (out, start.elapsed())
    };
    let (_, init) = timed(&[
        "campaign",
        "init",
        path(&dir.join("c.toml")),
        "-o",
        path(&c),
    ]);
    let (out, status) = timed(&["campaign", "status", path(&c)]);
    assert_contains(&text(&out.stdout), &["1000 points: 0 done"]);
    // init writes and fsyncs 1000 folders: 0.3 s alone, seconds while the
    // other tests run solvers on the same 2 cores; the bound is on
    // the state file and status
    assert!(
        init < Duration::from_secs(15),
        "init of 1000 points took {init:?}"
    );
    assert!(
        status < Duration::from_secs(1),
        "status of 1000 points took {status:?}"
    );
    let (out, _) = timed(&["campaign", "run", path(&c)]);
    assert_contains(&text(&out.stdout), &["1000 points done, 0 failed"]);
    let (out, status) = timed(&["campaign", "status", path(&c)]);
    assert_contains(&text(&out.stdout), &["1000 points: 1000 done"]);
    assert!(
        status < Duration::from_secs(1),
        "status of 1000 points took {status:?}"
    );
}

/// A controller killed after recording a submission but before recording
/// its job id: the restarted one finds the running task and adopts it
/// instead of starting the point twice.
#[test]
fn a_task_started_but_not_recorded_is_adopted_not_rerun() {
    let fake = Fake::new(
        "campaign-adopt",
        0,
        &Faults {
            sleep: 1.0,
            ..NO_FAULTS
        },
        "local",
    );
    let c = fake.campaign();
    let mut orphan = Command::new("sh")
        .arg(c.join("run-point.sh"))
        .arg(c.join("points/0001"))
        .spawn()
        .unwrap();
    // the state as that controller left it: run 1 submitted, no job id
    let mut state = bumpsim_campaign::state::State::read(&c).unwrap();
    state.points[0].status = bumpsim_campaign::state::Status::Submitted;
    state.points[0].attempts = 1;
    state.write(&c).unwrap();
    let out = run(&["campaign", "run", path(&c)]);
    assert_contains(
        &text(&out.stdout),
        &["4 points done, 0 failed (3 tasks submitted by this run)"],
    );
    assert!(orphan.wait().unwrap().success());
    assert_eq!(fake.invocations("0001"), 1, "{}", fake.state());
    assert_contains(
        &point(&fake.state(), 1),
        &["attempts = 1", "job = \"local:"],
    );
}

/// Input hashes decide what runs again: re-initialising an unchanged
/// campaign keeps every finished point; a point whose deck changed runs
/// again, alone; `--retry-failed` gives failed points new attempts.
#[test]
fn input_hashes_decide_what_runs_again() {
    let fake = Fake::new(
        "campaign-hashes",
        0,
        &Faults {
            fail_always: &["0004"],
            ..NO_FAULTS
        },
        "local",
    );
    let c = fake.campaign();
    run(&["campaign", "run", path(&c)]);
    let reinit = run(&[
        "campaign",
        "init",
        path(&fake.dir.join("campaign.toml")),
        "-o",
        path(&c),
    ]);
    assert_contains(
        &text(&reinit.stdout),
        &["4 points (3 kept from the earlier state"],
    );
    // the failed point starts afresh after init (3 attempts), the done ones stay
    let out = run(&["campaign", "run", path(&c)]);
    assert_contains(
        &text(&out.stdout),
        &["3 points done, 1 failed (3 tasks submitted by this run)"],
    );
    // a deck edited by hand: that point alone runs again
    let deck = c.join("points/0002/in.csv");
    std::fs::write(
        &deck,
        std::fs::read_to_string(&deck)
            .unwrap()
            .replace("1,", "1.0,"),
    )
    .unwrap();
    let out = run(&["campaign", "run", path(&c)]);
    assert_contains(&text(&out.stdout), &["(1 tasks submitted by this run)"]);
    assert_eq!(
        [
            fake.invocations("0001"),
            fake.invocations("0002"),
            fake.invocations("0003")
        ],
        [1, 2, 1]
    );
    assert_eq!(fake.invocations("0004"), 6);
    let out = run(&["campaign", "run", path(&c), "--retry-failed"]);
    assert_contains(
        &text(&out.stdout),
        &["3 points done, 1 failed (3 tasks submitted by this run)"],
    );
    assert_eq!(fake.invocations("0004"), 9);
}

/// A hanging solver on the local executor: its task's process group is
/// ended at the campaign's time limit (`[executor] time`, Slurm's form),
/// retried, then failed with the reason; the other points run once, and
/// nothing of the hung task lives on. `status --json` shows it all.
#[test]
fn a_hanging_local_task_is_timed_out_retried_and_failed_with_its_reason() {
    let slow = Faults {
        slow: &["0002"],
        ..NO_FAULTS
    };
    let fake = Fake::new("campaign-timeout", 0, &slow, "local");
    let c = fake.campaign();
    let spec = c.join("campaign.toml");
    let text_now = std::fs::read_to_string(&spec).unwrap();
    // [executor] is the campaign file's last table
    let limited = text_now.replace("retries = 2", "retries = 1") + "time = \"0:02\"\n";
    std::fs::write(&spec, limited).unwrap();
    let start = Instant::now();
    let out = run(&["campaign", "run", path(&c)]);
    let took = start.elapsed();
    assert_contains(&text(&out.stdout), &["3 points done, 1 failed"]);
    assert!(
        took >= Duration::from_secs(4) && took < Duration::from_secs(30),
        "two attempts of 2 s took {took:?}"
    );
    let counts: Vec<usize> = (1..=4)
        .map(|r| fake.invocations(&format!("{r:04}")))
        .collect();
    assert_eq!(counts, [1, 2, 1, 1], "{}", fake.state());
    let reason = "attempt 2 of 2: time limit 0:02 reached: the task's process group was terminated";
    assert_contains(
        &point(&fake.state(), 2),
        &["status = \"failed\"", "attempts = 2", reason],
    );
    let left = super::processes_in(&c);
    assert!(left.is_empty(), "still running in the campaign: {left:?}");
    let out = run(&["campaign", "status", path(&c), "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json["counts"]["done"], 3, "{json}");
    assert_eq!(json["counts"]["failed"], 1, "{json}");
    assert_eq!(json["runs"][1]["attempts"], 2, "{json}");
    assert_eq!(json["runs"][1]["status"], "failed", "{json}");
    assert!(
        json["runs"][1]["reason"].as_str().unwrap().contains(reason),
        "{json}"
    );
    assert_eq!(json["controller"], serde_json::Value::Null, "{json}");
}

/// `init --run` takes the executor and slots of `run`: a campaign file
/// asking for Slurm runs on the local executor, one task at a time (four
/// points of 0.5 s take at least 2 s), every point once, then collects.
#[test]
fn init_run_takes_the_executor_and_slots() {
    let half_second = Faults {
        sleep: 0.5,
        ..NO_FAULTS
    };
    let fake = Fake::new("campaign-init-run-executor", 0, &half_second, "slurm");
    let campaign = fake.dir.join("campaign.toml");
    let c = fake.campaign();
    let start = Instant::now();
    let out = run(&[
        "campaign",
        "init",
        path(&campaign),
        "-o",
        path(&c),
        "--run",
        "--executor",
        "local",
        "--slots",
        "1",
    ]);
    let took = start.elapsed();
    assert_contains(
        &text(&out.stdout),
        &[
            "4 points done, 0 failed (4 tasks submitted",
            "table.csv (4 points)",
        ],
    );
    assert!(took >= Duration::from_secs(2), "one slot: {took:?}");
    let state = fake.state();
    assert_eq!(state.matches("job = \"local:").count(), 4, "{state}");
    for r in 1..=4 {
        assert_eq!(fake.invocations(&format!("{r:04}")), 1, "{state}");
    }
}
