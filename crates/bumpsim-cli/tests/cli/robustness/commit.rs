//! Kills mid-write and mid-commit, and outputs inside outputs: a SIGKILL
//! while a file or a folder output is written or moved into place leaves
//! the complete old or the complete new output; an output inside another
//! output of the command is refused before the command runs.

use super::{examples, run_in, snapshot};
use std::path::Path;
use std::process::Command;
use std::time::Duration;

/// A force CSV with `rows` samples (10 kHz, a half-sine pulse).
fn long_force(path: &Path, rows: usize) {
    let mut text = String::from("time [s],force [N]\n");
    for k in 0..rows {
        let f = 4.0e4 * (std::f64::consts::PI * k as f64 / rows as f64).sin();
        text.push_str(&format!("{},{f}\n", k as f64 * 1e-4));
    }
    std::fs::write(path, text).unwrap();
}

/// Runs `args` in `dir` once per delay and kills it (SIGKILL) after that
/// delay: `before` sets the outputs up before each run, `after` checks
/// them after it and says whether to go on (the one kill loop of the
/// kill-mid-write tests below).
fn kill_at(
    dir: &Path,
    args: &[&str],
    delays: impl IntoIterator<Item = Duration>,
    before: &mut dyn FnMut(),
    after: &mut dyn FnMut(Duration) -> bool,
) {
    for delay in delays {
        before();
        let mut child = Command::new(env!("CARGO_BIN_EXE_bumpsim"))
            .args(args)
            .current_dir(dir)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(delay);
        let _ = child.kill(); // SIGKILL on Unix
        let _ = child.wait();
        if !after(delay) {
            break;
        }
    }
}

/// Kills `args` after increasing delays; each time the output must be the
/// complete old file or a complete new one (`complete` decides).
fn kill_during_write(dir: &Path, args: &[&str], output: &str, complete: &dyn Fn(&[u8]) -> bool) {
    let old = b"old complete output\n".to_vec();
    let delays = [50u64, 200, 500, 1000, 2000, 4000].map(Duration::from_millis);
    let before = &mut || std::fs::write(dir.join(output), &old).unwrap();
    kill_at(dir, args, delays, before, &mut |delay| {
        let now = snapshot(&dir.join(output));
        assert!(
            now == old || complete(&now),
            "{args:?} killed after {delay:?} left a partial {output} ({} bytes)",
            now.len()
        );
        true
    });
}

#[test]
fn sigkill_during_a_write_leaves_old_or_new_file() {
    let dir = examples("sigkill");
    let rows = 400_000;
    long_force(&dir.join("long.csv"), rows);
    let simulate = [
        "simulate",
        "--car",
        "ex/simulate/car-3dof.toml",
        "--force",
        "long.csv",
        "-o",
        "keep.csv",
    ];
    kill_during_write(&dir, &simulate, "keep.csv", &|bytes| {
        bytes.ends_with(b"\n") && bytes.iter().filter(|&&b| b == b'\n').count() == rows + 1
    });
    let identify = [
        "identify",
        "ex/identify/study.toml",
        "--starts",
        "2",
        "--quiet",
        "--json",
        "keep.json",
    ];
    kill_during_write(&dir, &identify, "keep.json", &|bytes| {
        serde_json::from_slice::<serde_json::Value>(bytes).is_ok()
    });
}

/// Issue 34: `identify --json rep/index.html --report rep` (and `impact`,
/// `doe fit`, `signal process` alike) ran the whole computation and was
/// refused only when its outputs were committed. The guard now refuses an
/// output inside another output before anything runs, naming both flags:
/// the refused identification ends in a fraction of the allowed one's
/// time and prints no result. A JSON of another kind inside the report
/// folder (README's `--json out/identify/result.json --report
/// out/identify`) is still written, beside the report.
#[test]
fn an_output_inside_another_is_refused_before_the_command_runs() {
    let dir = examples("nested");
    let study = "ex/identify/study.toml";
    let identify = |json: &str, report: &str| {
        let args = [
            "identify", study, "--starts", "40", "--json", json, "--report", report,
        ];
        run_in(&dir, &args)
    };
    let (allowed, took) = identify("rep/result.json", "rep");
    assert_eq!(
        allowed.status.code(),
        Some(0),
        "{}",
        super::stderr(&allowed)
    );
    assert!(dir.join("rep/index.html").is_file() && dir.join("rep/result.json").is_file());
    let (refused, fast) = identify("clash/index.html", "clash");
    let err = super::stderr(&refused);
    assert_eq!(refused.status.code(), Some(2), "{err}");
    assert!(
        err.contains("--json clash/index.html") && err.contains("--report clash"),
        "{err}"
    );
    assert!(refused.stdout.is_empty(), "a result was printed");
    assert!(
        fast * 4 < took,
        "refused after {fast:?}; the run takes {took:?}"
    );
    assert!(!dir.join("clash").exists());
    let flat = "ex/identify/FLAT";
    for args in [
        &[
            "signal",
            "export",
            flat,
            "-c",
            "1",
            "-o",
            "iso/x.csv",
            "--iso-mme",
            "iso",
        ][..],
        &[
            "signal",
            "export",
            flat,
            "-c",
            "1",
            "-o",
            "x.csv",
            "--plot",
            "p",
            "--iso-mme",
            "p/t",
        ],
    ] {
        let (out, _) = run_in(&dir, args);
        let err = super::stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.contains("lies inside --"), "{err}");
        assert!(
            !dir.join("iso").exists() && !dir.join("p").exists() && !dir.join("x.csv").exists()
        );
    }
}

/// The folder's files and their bytes (hidden temporary names left out).
fn folder(path: &Path) -> Vec<(String, Vec<u8>)> {
    let mut files: Vec<(String, Vec<u8>)> = std::fs::read_dir(path)
        .unwrap()
        .flatten()
        .map(|e| (e.file_name().to_string_lossy().into_owned(), e.path()))
        .filter(|(name, _)| !name.starts_with('.'))
        .map(|(name, p)| (name, std::fs::read(p).unwrap()))
        .collect();
    files.sort();
    files
}

/// Issue 34: an existing folder output (`--plot`) was updated file by file
/// when the command committed, so a kill -9 there left old and new plots
/// mixed. Killed at delays across the whole run (start-up, computation,
/// commit), the folder is each time the old plots or the new ones, whole,
/// and the user's own file in it stays.
#[test]
fn sigkill_during_a_folder_commit_leaves_the_old_or_the_new_folder() {
    let dir = examples("sigkill-folder");
    let export = |scale: &str, plot: &str| {
        let args = [
            "signal",
            "export",
            "ex/identify/FLAT",
            "-c",
            "*",
            "--scale",
            scale,
            "-o",
            "x.csv",
            "--plot",
            plot,
        ];
        args.map(String::from)
    };
    for (scale, plot) in [("1", "old"), ("2", "new")] {
        let (out, _) = run_in(&dir, &export(scale, plot).each_ref().map(String::as_str));
        assert_eq!(out.status.code(), Some(0), "{}", super::stderr(&out));
    }
    let notes = ("notes.txt".to_string(), b"mine".to_vec());
    let with_notes = |mut files: Vec<(String, Vec<u8>)>| {
        files.push(notes.clone());
        files.sort();
        files
    };
    let (old, new) = (
        with_notes(folder(&dir.join("old"))),
        with_notes(folder(&dir.join("new"))),
    );
    assert_ne!(old, new);
    // the kill delays span the whole run as this machine runs it now (the
    // fixed 0..120 ms missed its end on a loaded 2-core machine): 20 delays
    // from 0 to 1.5 × an uninterrupted run's time; if still none finished
    // (the load grew), the delay doubles until one does, up to 30 s
    let full = {
        let plots = dir.join("timed");
        crate::util::copy_tree(&dir.join("old"), &plots);
        let started = std::time::Instant::now();
        let (out, _) = run_in(&dir, &export("2", "timed").each_ref().map(String::as_str));
        assert_eq!(out.status.code(), Some(0), "{}", super::stderr(&out));
        started.elapsed()
    };
    let spread = (0..20u32).map(|k| full.mul_f64(1.5 * f64::from(k) / 19.0));
    let longer = (1..=10u32)
        .map(|k| full.mul_f64(1.5 * f64::from(1u32 << k)))
        .take_while(|delay| *delay <= Duration::from_secs(30));
    let plots = dir.join("plots");
    let (mut olds, mut news) = (0, 0);
    let before = &mut || {
        let _ = std::fs::remove_dir_all(&plots);
        crate::util::copy_tree(&dir.join("old"), &plots);
        std::fs::write(plots.join("notes.txt"), "mine").unwrap();
    };
    let args = export("2", "plots");
    let args = args.each_ref().map(String::as_str);
    kill_at(&dir, &args, spread.chain(longer), before, &mut |delay| {
        let now = folder(&plots);
        assert!(
            now == old || now == new,
            "killed after {delay:?}: a mixed folder {:?}",
            now.iter().map(|(n, b)| (n, b.len())).collect::<Vec<_>>()
        );
        if now == old {
            olds += 1
        } else {
            news += 1
        }
        olds + news < 20 || news == 0
    });
    assert!(
        news > 0,
        "no run finished within 30 s of kill delays (an uninterrupted run took {full:?}): {olds} old, {news} new"
    );
}

/// Every file under `path` (hidden names left out) with its bytes, by
/// relative path.
fn tree(path: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    for name in folder_names(path) {
        let p = path.join(&name);
        match p.is_dir() {
            true => out.extend(
                tree(&p)
                    .into_iter()
                    .map(|(n, b)| (format!("{name}/{n}"), b)),
            ),
            false => out.push((name, std::fs::read(p).unwrap())),
        }
    }
    out.sort();
    out
}

/// The names in `path`, hidden ones left out.
fn folder_names(path: &Path) -> Vec<String> {
    std::fs::read_dir(path)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|name| !name.starts_with('.'))
        .collect()
}

/// Issue 44's hostile pass over wave 4's commands: `synth` of a links
/// series (a folder of ISO-MME tests, CSVs and a study) killed at delays
/// across its whole run leaves no folder or the whole one, byte for byte
/// the uninterrupted run's (measured: absent up to 1.5 s, whole from
/// 1.55 s of a 1.7 s debug run). `identify --car` writes through the same
/// temporary file and rename as `--json` (above).
#[test]
fn sigkill_during_a_links_synth_leaves_no_folder_or_the_whole_one() {
    let dir = examples("sigkill-synth");
    let args = ["synth", "ex/links/series.toml", "-o"];
    let started = std::time::Instant::now();
    let (out, _) = run_in(&dir, &[&args[..], &["whole"]].concat());
    assert_eq!(out.status.code(), Some(0), "{}", super::stderr(&out));
    let full = started.elapsed();
    let whole = tree(&dir.join("whole"));
    assert!(whole.len() > 10, "{}", whole.len());
    let (mut absent, mut complete) = (0, 0);
    let delays = (0..16u32).map(|k| full.mul_f64(1.5 * f64::from(k) / 15.0));
    let before = &mut || {
        let _ = std::fs::remove_dir_all(dir.join("out"));
    };
    let killed = [&args[..], &["out"]].concat();
    kill_at(&dir, &killed, delays, before, &mut |delay| {
        match dir.join("out").exists() {
            false => absent += 1,
            true => {
                let now = tree(&dir.join("out"));
                assert!(
                    now == whole,
                    "killed after {delay:?}: a partial series {:?}",
                    now.iter().map(|(n, b)| (n, b.len())).collect::<Vec<_>>()
                );
                complete += 1;
            }
        }
        true
    });
    assert!(absent > 0, "every run finished: the kills came too late");
    println!("{absent} absent, {complete} whole");
}
