//! `bumpsim campaign`: the bundled CalculiX campaign run locally and on a
//! real Slurm cluster (scripts/slurm-up), bad input refused before anything
//! runs, retries, failures with reasons, corrupt output, the lock, a
//! controller killed with SIGKILL and restarted, `scancel` of a running
//! task, and 1000-point campaigns.
//!
//! Most tests use a fake solver (a shell script) that logs every
//! invocation, so re-runs are counted; faults are injected per point.

use crate::util::{
    assert_contains, assert_user_error, bumpsim, peer_available, root, scratch, text,
};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output};
use std::time::{Duration, Instant};

/// Whether a Slurm cluster answers; with `BUMPSIM_REQUIRE_SLURM` set (as
/// scripts/test does after scripts/slurm-up) its absence fails the test.
fn slurm_available() -> bool {
    // idle, or busy with other tests' tasks: the node is up either way
    let up = Command::new("sinfo")
        .args(["-h", "-o", "%T"])
        .output()
        .is_ok_and(|o| {
            let states = text(&o.stdout);
            o.status.success()
                && ["idle", "mix", "alloc", "completing"]
                    .iter()
                    .any(|s| states.contains(s))
        });
    if !up {
        assert!(
            std::env::var_os("BUMPSIM_REQUIRE_SLURM").is_none(),
            "BUMPSIM_REQUIRE_SLURM is set but no Slurm cluster answers (scripts/slurm-up starts one)"
        );
        eprintln!(
            "skipped: no Slurm cluster (sbatch/sinfo absent or down; scripts/slurm-up starts one as root)"
        );
    }
    up
}

fn run(args: &[&str]) -> Output {
    let out = bumpsim(args);
    assert!(
        out.status.success(),
        "{args:?}: {}{}",
        text(&out.stdout),
        text(&out.stderr)
    );
    out
}

fn path(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A campaign over `a`, `b` (full factorial + `centre` centre points) whose
/// solver is a logging shell script: it sleeps `sleep` s, fails for good in
/// the folders listed in `fail_always`, once in `fail_once`, writes a
/// corrupt output in `corrupt`, and sleeps 300 s more in `slow` (longer
/// than any test waits: only an abort ends such a run, even when a busy
/// Slurm node starts the second slow run long after the first).
struct Fake {
    dir: PathBuf,
    log: PathBuf,
}

struct Faults<'a> {
    sleep: f64,
    fail_once: &'a [&'a str],
    fail_always: &'a [&'a str],
    corrupt: &'a [&'a str],
    slow: &'a [&'a str],
}

const NO_FAULTS: Faults<'static> = Faults {
    sleep: 0.0,
    fail_once: &[],
    fail_always: &[],
    corrupt: &[],
    slow: &[],
};

impl Fake {
    fn new(test: &str, centre: usize, faults: &Faults, executor: &str) -> Fake {
        let dir = scratch(test);
        let log = dir.join("solver.log");
        std::fs::write(&log, "").unwrap();
        let list = |l: &[&str]| l.join(" ");
        let script = format!(
            "#!/bin/sh\np=$(basename \"$PWD\")\necho \"$p\" >> '{log}'\nsleep {sleep}\n\
             for s in {slow}; do [ \"$p\" = \"$s\" ] && sleep 300; done\n\
             for f in {always}; do [ \"$p\" = \"$f\" ] && exit 3; done\n\
             for f in {once}; do if [ \"$p\" = \"$f\" ] && [ ! -e '{dir}'/once-$p ]; then touch '{dir}'/once-$p; exit 1; fi; done\n\
             for f in {corrupt}; do [ \"$p\" = \"$f\" ] && {{ echo 'time [s],y [m]' > out.csv; echo '0,0' >> out.csv; echo '1,zero' >> out.csv; exit 0; }}; done\n\
             cp in.csv out.csv\n",
            log = log.display(),
            dir = dir.display(),
            sleep = faults.sleep,
            slow = list(faults.slow),
            always = list(faults.fail_always),
            once = list(faults.fail_once),
            corrupt = list(faults.corrupt),
        );
        let solver = dir.join("solver.sh");
        std::fs::write(&solver, script).unwrap();
        Command::new("chmod")
            .arg("+x")
            .arg(&solver)
            .status()
            .unwrap();
        std::fs::write(dir.join("in.tmpl"), "time [s],y [m]\n0,0\n1,{{y}}\n").unwrap();
        let campaign = format!(
            r#"name = "fake"
[design]
kind = "full"
factors = [{{ name = "a", low = 1, high = 2, unit = "m" }}, {{ name = "b", low = 0, high = 1, unit = "m" }}]
centre = {centre}
[derived]
y = "2 * a + b + run_offset"
run_offset = "0 * a"
[template]
file = "in.tmpl"
deck = "in.csv"
[solver]
command = ["{solver}"]
[[response]]
name = "y_max"
reader = "csv"
file = "out.csv"
quantity = "y"
unit = "m"
[executor]
kind = "{executor}"
slots = 2
retries = 2
poll_seconds = 0.3
"#,
            solver = solver.display()
        );
        std::fs::write(dir.join("campaign.toml"), campaign).unwrap();
        run(&[
            "campaign",
            "init",
            path(&dir.join("campaign.toml")),
            "-o",
            path(&dir.join("c")),
        ]);
        Fake { dir, log }
    }

    fn campaign(&self) -> PathBuf {
        self.dir.join("c")
    }

    /// Solver invocations per point folder.
    fn invocations(&self, point: &str) -> usize {
        std::fs::read_to_string(&self.log)
            .unwrap()
            .lines()
            .filter(|l| *l == point)
            .count()
    }

    fn state(&self) -> String {
        std::fs::read_to_string(self.campaign().join("state.toml")).unwrap()
    }

    fn spawn_run(&self, extra: &[&str]) -> Child {
        Command::new(env!("CARGO_BIN_EXE_bumpsim"))
            .args(["campaign", "run", path(&self.campaign())])
            .args(extra)
            .stdout(std::process::Stdio::null())
            .spawn()
            .unwrap()
    }

    /// Waits until `done` points are done (at most 60 s).
    fn wait_done(&self, done: usize) {
        let start = Instant::now();
        while self.state().matches("status = \"done\"").count() < done {
            assert!(
                start.elapsed() < Duration::from_secs(60),
                "{}",
                self.state()
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    fn collect(&self) -> Output {
        run(&["campaign", "collect", path(&self.campaign())])
    }

    fn table(&self) -> String {
        std::fs::read_to_string(self.campaign().join("results/table.csv")).unwrap()
    }
}

/// The `[[point]]` block of run `run` in a state file.
fn point(state: &str, run: usize) -> String {
    let start = state.find(&format!("[[point]]\nrun = {run}\n")).unwrap();
    let rest = &state[start + 9..];
    rest[..rest.find("[[point]]").unwrap_or(rest.len())].to_string()
}

/// The bundled example: 9 CalculiX runs, collected; its regression equals
/// `bumpsim doe fit` on the collected table exactly; the HTML report exists.
#[test]
fn the_bundled_calculix_campaign_runs_locally_and_fits_like_doe_fit() {
    if !peer_available("CalculiX (ccx)", "sh", &["-c", "command -v ccx"]) {
        return;
    }
    let dir = scratch("campaign-example");
    let c = dir.join("c");
    let campaign = root().join("examples/campaign/campaign.toml");
    run(&["campaign", "init", path(&campaign), "-o", path(&c)]);
    let out = run(&["campaign", "run", path(&c)]);
    assert_contains(&text(&out.stdout), &["9 points done, 0 failed"]);
    let out = run(&["campaign", "collect", path(&c)]);
    assert_contains(
        &text(&out.stdout),
        &["x1_max [m]: R²", "d12_max [m]: R²", "table.csv (9 points)"],
    );
    assert!(c.join("results/report/index.html").exists());
    // the .dat (7 significant digits) and .frd (6) readers agree on x1's
    // maximum; the bumpsim-deck and the generic .dat readers exactly
    let table = std::fs::read_to_string(c.join("results/table.csv")).unwrap();
    let header: Vec<&str> = table.lines().next().unwrap().split(',').collect();
    let dat = header.iter().position(|h| *h == "x1_max [m]").unwrap();
    let frd = header.iter().position(|h| *h == "x1_max_frd [m]").unwrap();
    let generic = header.iter().position(|h| *h == "x1_max_dat [m]").unwrap();
    for line in table.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert!((v[dat] - v[frd]).abs() <= 1e-5 * v[dat].abs(), "{line}");
        assert_eq!(v[dat], v[generic], "the two .dat readers: {line}");
    }
    let command = std::fs::read_to_string(c.join("results/fit-command.txt")).unwrap();
    let mut args: Vec<String> = command
        .split_whitespace()
        .skip(1)
        .map(String::from)
        .collect();
    args[2] = path(&c.join("results/table.csv")).into();
    let json = dir.join("doe-fit.json");
    args.extend(["--json".into(), path(&json).into()]);
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    run(&refs);
    let ours = std::fs::read_to_string(c.join("results/model.json")).unwrap();
    assert_eq!(
        ours,
        std::fs::read_to_string(&json).unwrap(),
        "the campaign's model equals doe fit's"
    );
    // a second collect reads the same files again: the same table
    let first = std::fs::read_to_string(c.join("results/table.csv")).unwrap();
    run(&["campaign", "collect", path(&c)]);
    assert_eq!(
        first,
        std::fs::read_to_string(c.join("results/table.csv")).unwrap()
    );
}

/// The campaign over the coupled bumper-car deck of `bumpsim fe`
/// (examples/campaign/bumper.toml): 8 CalculiX runs, collected and fitted;
/// thicker crash-box walls raise the barrier's peak force, a higher yield
/// stress lessens the crush.
#[test]
fn the_fe_bumper_campaign_runs_the_coupled_deck() {
    if !peer_available("CalculiX (ccx)", "sh", &["-c", "command -v ccx"]) {
        return;
    }
    let dir = scratch("campaign-fe-bumper");
    let c = dir.join("c");
    let campaign = root().join("examples/campaign/bumper.toml");
    let out = run(&["campaign", "init", path(&campaign), "-o", path(&c), "--run"]);
    assert_contains(
        &text(&out.stdout),
        &[
            "8 points done, 0 failed",
            "force_peak [N]: R²",
            "x1_min [m]: R²",
        ],
    );
    let table = std::fs::read_to_string(c.join("results/table.csv")).unwrap();
    let header: Vec<&str> = table.lines().next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| h.starts_with(name)).unwrap();
    let (t, sy, force, x1) = (
        column("t_box"),
        column("sy"),
        column("force_peak"),
        column("x1_min"),
    );
    let rows: Vec<Vec<f64>> = table
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    let mean = |pick: &dyn Fn(&Vec<f64>) -> bool, of: usize| {
        let chosen: Vec<f64> = rows.iter().filter(|r| pick(r)).map(|r| r[of]).collect();
        chosen.iter().sum::<f64>() / chosen.len() as f64
    };
    let thick = mean(&|r| r[t] > 1.5e-3, force);
    let thin = mean(&|r| r[t] < 1.5e-3, force);
    assert!(
        thick > thin && thin > 1e4,
        "peak force {thin} N (thin) vs {thick} N (thick)"
    );
    let strong = mean(&|r| r[sy] > 4e7, x1).abs();
    let weak = mean(&|r| r[sy] < 4e7, x1).abs();
    assert!(
        strong < weak && strong > 0.01,
        "crush {strong} m (strong) vs {weak} m (weak)"
    );
}

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
    // other tests run solvers on the same 2 cores; the issue's bound is on
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
    let state = fake.state().replacen(
        "status = \"pending\"\nattempts = 0\n",
        "status = \"submitted\"\nattempts = 1\n",
        1,
    );
    std::fs::write(c.join("state.toml"), state).unwrap();
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

/// Per-point identification (paper C stage 2): each point's "solver" is
/// `bumpsim simulate` of a 2-DOF car whose body mass and front spring are
/// the factors; `collect` identifies a 2-DOF model per point from the
/// simulated force and bumper displacement and appends m1.., c1.., k1..;
/// the identified m2 and k1 recover the factors, and the regression of
/// them runs like `doe fit`.
#[test]
fn collect_identifies_a_model_per_point_and_regresses_its_parameters() {
    let dir = scratch("campaign-identify");
    std::fs::copy(
        root().join("examples/simulate/pendulum-force.csv"),
        dir.join("force.csv"),
    )
    .unwrap();
    std::fs::write(
        dir.join("car.tmpl"),
        "name = \"point {{run}}\"\nmasses = [20.0, {{mb}}]\ndampers = [2.0e4]\nsprings = [{{kf}}]\n",
    )
    .unwrap();
    std::fs::write(
        dir.join("study.tmpl"),
        "[model]\ndof = 2\nlower_bound = 1.0\nstarts = 4\nseed = 1\n[[case]]\nname = \"pendulum {{run}}\"\n\
         force = { path = \"response.csv\", channel = \"force\" }\ndisplacement = { path = \"response.csv\", channel = \"x1\" }\noutput_dof = 1\n",
    )
    .unwrap();
    let campaign = format!(
        r#"name = "identify"
[design]
kind = "full"
factors = [{{ name = "mb", low = 1200, high = 1600, unit = "kg" }}, {{ name = "kf", low = 3e5, high = 7e5, unit = "N/m" }}]
centre = 1
[template]
file = "car.tmpl"
deck = "car.toml"
files = ["force.csv"]
[solver]
command = ["{bin}", "simulate", "--car", "car.toml", "--force", "force.csv", "-o", "response.csv"]
[identify]
study = "study.tmpl"
dof = 2
[[response]]
name = "x1_max"
reader = "csv"
file = "response.csv"
quantity = "x1"
unit = "m"
[regress]
responses = ["m2", "k1", "x1_max"]
"#,
        bin = env!("CARGO_BIN_EXE_bumpsim")
    );
    std::fs::write(dir.join("c.toml"), campaign).unwrap();
    let c = dir.join("c");
    let out = run(&[
        "campaign",
        "init",
        path(&dir.join("c.toml")),
        "-o",
        path(&c),
        "--run",
    ]);
    assert_contains(
        &text(&out.stdout),
        &["5 points done, 0 failed", "m2 [kg]: R²", "k1 [N/m]: R²"],
    );
    let table = std::fs::read_to_string(c.join("results/table.csv")).unwrap();
    let header: Vec<&str> = table.lines().next().unwrap().split(',').collect();
    let column = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (mb, kf, m2, k1) = (
        column("mb [kg]"),
        column("kf [N/m]"),
        column("m2 [kg]"),
        column("k1 [N/m]"),
    );
    for line in table.lines().skip(1) {
        let v: Vec<f64> = line.split(',').map(|x| x.parse().unwrap()).collect();
        assert!(
            (v[m2] / v[mb] - 1.0).abs() < 0.01,
            "m2 {} for body mass {} kg",
            v[m2],
            v[mb]
        );
        assert!(
            (v[k1] / v[kf] - 1.0).abs() < 0.01,
            "k1 {} for front spring {} N/m",
            v[k1],
            v[kf]
        );
    }
}

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

/// The processes (pid, command line) whose working folder lies in `dir`.
fn processes_in(dir: &Path) -> Vec<(u32, String)> {
    let dir = dir.canonicalize().unwrap();
    std::fs::read_dir("/proc")
        .unwrap()
        .flatten()
        .filter_map(|e| {
            let pid: u32 = e.file_name().to_str()?.parse().ok()?;
            let cwd = std::fs::read_link(e.path().join("cwd")).ok()?;
            let command = std::fs::read(e.path().join("cmdline")).ok()?;
            cwd.starts_with(&dir)
                .then(|| (pid, String::from_utf8_lossy(&command).replace('\0', " ")))
        })
        .collect()
}

#[test]
fn abort_stops_local_tasks() {
    abort_stops_the_running_tasks("local");
}

#[test]
fn abort_cancels_slurm_tasks() {
    if slurm_available() {
        abort_stops_the_running_tasks("slurm");
    }
}

/// LS-DYNA `*PARAMETER` users: each point folder gets an include with one
/// `R name value` card per factor and derived quantity, beside the deck.
#[test]
fn lsdyna_parameter_includes_are_written_per_point() {
    let dir = scratch("campaign-parameters");
    std::fs::write(
        dir.join("main.k"),
        "*KEYWORD\n*INCLUDE\nparams.k\n$ run {{run}}\n*END\n",
    )
    .unwrap();
    let campaign = "name = \"p\"\n[design]\nkind = \"full\"\nfactors = [{ name = \"t_rail\", low = 1.5, high = 2.5, unit = \"mm\" }]\n\
                    [derived]\nt2 = \"2 * t_rail\"\n[template]\nfile = \"main.k\"\nlsdyna_parameters = \"params.k\"\n[solver]\ncommand = [\"true\"]\n";
    std::fs::write(dir.join("c.toml"), campaign).unwrap();
    run(&[
        "campaign",
        "init",
        path(&dir.join("c.toml")),
        "-o",
        path(&dir.join("c")),
    ]);
    let params = std::fs::read_to_string(dir.join("c/points/0002/params.k")).unwrap();
    assert_contains(
        &params,
        &[
            "*PARAMETER\n",
            "R t_rail          2.5\n",
            "R t2              5.0\n",
        ],
    );
    let deck = std::fs::read_to_string(dir.join("c/points/0002/main.k")).unwrap();
    assert!(deck.contains("$ run 2\n"), "{deck}");
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
