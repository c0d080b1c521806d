//! `bumpsim campaign`: the bundled CalculiX campaign run locally and on a
//! real Slurm cluster (scripts/slurm-up), bad input refused before anything
//! runs, retries, failures with reasons, corrupt output, local time limits,
//! the lock, a controller killed with SIGKILL and restarted, a damaged or
//! truncated state repaired, `scancel` of a running task, a node failure,
//! arrays cut to the cluster's MaxArraySize, and 1000-point campaigns.
//!
//! Most tests use a fake solver (a shell script) that logs every
//! invocation, so re-runs are counted; faults are injected per point.
//! One module per concern: the bundled campaigns and real solvers, the
//! controller's faults, the state's repair, a real Slurm cluster, and
//! `campaign abort`.

mod abort;
mod bundled;
mod cases;
mod controller;
mod repair;
mod slurm;

use crate::util::{bumpsim, scratch, text};
use bumpsim_campaign::state::State;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output};
use std::sync::{RwLock, RwLockReadGuard, RwLockWriteGuard};
use std::time::{Duration, Instant};

/// The test cluster: shared by the Slurm tests, held alone by the one that
/// fails its node (which would requeue the others' tasks).
static CLUSTER: RwLock<()> = RwLock::new(());

/// The test cluster, shared with the other Slurm tests (`None`: no cluster).
fn slurm_cluster() -> Option<RwLockReadGuard<'static, ()>> {
    let guard = CLUSTER.read().unwrap_or_else(|e| e.into_inner());
    slurm_available().then_some(guard)
}

/// The test cluster alone (`None`: no cluster).
fn slurm_cluster_alone() -> Option<RwLockWriteGuard<'static, ()>> {
    let guard = CLUSTER.write().unwrap_or_else(|e| e.into_inner());
    slurm_available().then_some(guard)
}

/// Whether a Slurm cluster answers, its node in service (idle, or busy
/// with other tests' tasks; not `idle*`, a node whose slurmd does not
/// answer). With `BUMPSIM_REQUIRE_SLURM` set (as scripts/test does after
/// scripts/slurm-up) the cluster is asked again until 120 s have passed,
/// its node resumed as slurm-up does: a controller on a loaded machine can
/// miss sinfo's timeout, and a node failure leaves the node down. Once 10 s
/// have passed without an answer, scripts/slurm-up runs again (idempotent:
/// what runs is left running; at most once per test process, within 300 s),
/// saying so on the test's stderr even when the test passes: the test
/// cluster's daemons are the fixture, not what these tests test. Still no
/// answer then fails the test, with what sinfo said, what slurm-up printed
/// and the controller's log. Without the variable the test skips at once.
fn slurm_available() -> bool {
    let required = std::env::var_os("BUMPSIM_REQUIRE_SLURM").is_some();
    let start = Instant::now();
    let said = loop {
        let said = sinfo();
        if said.up {
            return true;
        }
        if !required || start.elapsed() > Duration::from_secs(120) {
            break said;
        }
        slurm_resume();
        if start.elapsed() > Duration::from_secs(10) {
            slurm_up(&said);
        }
        std::thread::sleep(Duration::from_secs(1));
    };
    assert!(
        !required,
        "BUMPSIM_REQUIRE_SLURM is set but no Slurm cluster answered in {:.0} s \
         (scripts/slurm-up starts one); sinfo: {}\nscripts/slurm-up again: {}\nslurmctld.log ends:\n{}",
        start.elapsed().as_secs_f64(),
        said.text,
        SLURM_UP.get().map_or("not run", String::as_str),
        log_tail("/var/log/slurm/slurmctld.log", 20)
    );
    eprintln!(
        "skipped: no Slurm cluster (sbatch/sinfo absent or down; scripts/slurm-up starts one as root)"
    );
    false
}

/// What `sinfo -h -o %T` said, and whether it names a node in service.
struct Sinfo {
    up: bool,
    text: String,
}

/// The node states of a node in service (`sinfo -o %T`, whole words: a
/// trailing `*` marks a node whose slurmd does not answer).
const IN_SERVICE: [&str; 4] = ["idle", "mixed", "allocated", "completing"];

fn sinfo() -> Sinfo {
    match bounded("sinfo", &["-h", "-o", "%T"]).output() {
        Ok(o) => {
            let states = text(&o.stdout);
            let up = o.status.success() && states.lines().any(|s| IN_SERVICE.contains(&s.trim()));
            let text = format!(
                "{}; stdout {:?}; stderr {:?}",
                o.status,
                states.trim(),
                text(&o.stderr).trim()
            );
            Sinfo { up, text }
        }
        Err(e) => Sinfo {
            up: false,
            text: format!("not run ({e})"),
        },
    }
}

/// `program ARGS` killed after 15 s: a client waits MessageTimeout (10 s)
/// for a silent controller.
fn bounded(program: &str, args: &[&str]) -> Command {
    let mut command = Command::new("timeout");
    command.args(["-k", "5", "15", program]).args(args);
    command
}

/// What scripts/slurm-up printed when it ran again (once per process).
static SLURM_UP: std::sync::OnceLock<String> = std::sync::OnceLock::new();

/// Runs scripts/slurm-up again, once per test process (other tests wait
/// for it), within 300 s, its output to a file (no daemon it starts can
/// hold a pipe open); says why and what it printed on stderr, uncaptured.
fn slurm_up(said: &Sinfo) {
    SLURM_UP.get_or_init(|| {
        let log = crate::util::scratch("campaign-slurm-up-again").join("slurm-up.log");
        let file = std::fs::File::create(&log).unwrap();
        let status = Command::new("timeout")
            .args(["-k", "10", "300"])
            .arg(crate::util::root().join("scripts/slurm-up"))
            .stdin(std::process::Stdio::null())
            .stdout(file.try_clone().unwrap())
            .stderr(file)
            .status();
        let printed = std::fs::read_to_string(&log).unwrap_or_default();
        let report = format!("{status:?}: {}", printed.trim());
        let _ = writeln!(
            std::io::stderr(),
            "the Slurm cluster did not answer (sinfo: {}); scripts/slurm-up again: {report}\nslurmctld.log ends:\n{}",
            said.text,
            log_tail("/var/log/slurm/slurmctld.log", 20)
        );
        report
    });
}

/// The test cluster's node name (scripts/slurm-up names it `hostname -s`).
fn slurm_node() -> String {
    let out = Command::new("hostname").arg("-s").output();
    text(&out.map(|o| o.stdout).unwrap_or_default())
        .trim()
        .to_string()
}

/// Puts the node back in service; a refusal (the node up already, no
/// controller) is ignored, as the next sinfo says what it is.
fn slurm_resume() {
    scontrol(&[
        "update",
        &format!("nodename={}", slurm_node()),
        "state=resume",
    ]);
}

/// `scontrol ARGS` within 15 s, its refusals ignored (a node already up, a
/// job already running, no controller: what follows says what it is).
fn scontrol(args: &[&str]) {
    let _ = bounded("scontrol", args)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status();
}

/// The last `lines` lines of a log, or why there are none.
fn log_tail(path: &str, lines: usize) -> String {
    match std::fs::read_to_string(path) {
        Ok(log) => {
            let all: Vec<&str> = log.lines().collect();
            all[all.len().saturating_sub(lines)..].join("\n")
        }
        Err(e) => format!("({path}: {e})"),
    }
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
/// Slurm node starts the second slow run long after the first; a stopped
/// `sleep` ends the script too, so a signal that reaches the sleep before
/// the shell cannot let the run go on to write its output).
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
             for s in {slow}; do [ \"$p\" = \"$s\" ] && {{ sleep 300 || exit 143; }}; done\n\
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
        state_text(&self.campaign())
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

/// The state of campaign folder `dir` (its journal, read by the library)
/// as text: a `[[point]]` block per point with its run, status, attempts,
/// requeues, job and reason (`status = "done"`, `attempts = 2`, ...).
fn state_text(dir: &Path) -> String {
    let state = State::read(dir).unwrap_or_else(|e| panic!("{e}"));
    state
        .points
        .iter()
        .map(|p| {
            format!(
                "[[point]]\nrun = {}\nstatus = \"{}\"\nattempts = {}\nrequeues = {}\njob = {:?}\nreason = {:?}\n",
                p.run,
                p.status.name(),
                p.attempts,
                p.requeues,
                p.job,
                p.reason
            )
        })
        .collect()
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

/// The `[[point]]` block of run `run` in a state's text.
fn point(state: &str, run: usize) -> String {
    let start = state.find(&format!("[[point]]\nrun = {run}\n")).unwrap();
    let rest = &state[start + 9..];
    rest[..rest.find("[[point]]").unwrap_or(rest.len())].to_string()
}
