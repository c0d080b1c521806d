//! The guard's refusals, staging, links and the clean-up after a killed run.

use super::*;
#[cfg(unix)]
use std::os::unix::fs::FileTypeExt;
use std::path::{Path, PathBuf};

/// `planar --json x --csv x` wrote both to x with exit 0: the CSV
/// silently replaced the JSON.
#[test]
fn one_path_cannot_take_two_outputs() {
    let dir = temp("twice");
    let mut guard = Outputs::new();
    let out = dir.join("same.json");
    guard.claim(&out).unwrap();
    guard.claim(&dir.join("other.csv")).unwrap();
    let err = guard.claim(&dir.join(".").join("same.json")).unwrap_err();
    assert!(matches!(err, OutputError::Twice { .. }), "{err}");
    assert!(err.to_string().contains("two outputs"), "{err}");
    // a hard link to an existing output is the same file
    std::fs::write(&out, "x").unwrap();
    std::fs::hard_link(&out, dir.join("link.json")).unwrap();
    let mut guard = Outputs::new();
    guard.claim(&out).unwrap();
    assert!(guard.claim(&dir.join("link.json")).is_err());
}

fn temp(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("bumpsim-output-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

#[test]
fn inputs_links_and_folders_are_refused() {
    let dir = temp("refuse");
    let input = dir.join("in.toml");
    std::fs::write(&input, "a").unwrap();
    std::fs::hard_link(&input, dir.join("link.toml")).unwrap();
    let test = dir.join("TEST");
    std::fs::create_dir_all(test.join("Channel")).unwrap();
    std::fs::write(test.join("Channel/T.001"), "1").unwrap();
    std::fs::hard_link(test.join("Channel/T.001"), dir.join("t-link")).unwrap();
    let mut g = Outputs::new();
    g.input(&input);
    g.input(&test);
    for bad in [
        input.clone(),
        dir.join("link.toml"),
        dir.join("./sub/../in.toml"),
        test.join("Channel/T.001"),
        test.join("Channel/new.csv"),
        dir.join("t-link"),
    ] {
        assert!(g.write_file(&bad, b"x").is_err(), "{}", bad.display());
    }
    assert_eq!(std::fs::read(&input).unwrap(), b"a");
    assert_eq!(std::fs::read(test.join("Channel/T.001")).unwrap(), b"1");
    g.write_file(&dir.join("out/deep.csv"), b"ok").unwrap();
    assert_eq!(std::fs::read(dir.join("out/deep.csv")).unwrap(), b"ok");
    assert!(matches!(
        g.check_folder(&input),
        Err(OutputError::NotAFolder { .. }) | Err(OutputError::OnInput { .. })
    ));
    assert!(matches!(
        g.check_file(&dir.join("out")),
        Err(OutputError::IsAFolder { .. })
    ));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn staged_folders_appear_only_on_commit() {
    let dir = temp("stage");
    let g = Outputs::new();
    let target = dir.join("report");
    std::fs::create_dir_all(&target).unwrap();
    std::fs::write(target.join("index.html"), "old").unwrap();
    std::fs::write(target.join("keep.txt"), "mine").unwrap();
    {
        let staged = g.stage_folder(&target).unwrap();
        staged.write("index.html", b"new").unwrap();
        // dropped: a failed run
    }
    assert_eq!(std::fs::read(target.join("index.html")).unwrap(), b"old");
    let staged = g.stage_folder(&target).unwrap();
    staged.write("index.html", b"new").unwrap();
    staged.write("fig/a.svg", b"<svg/>").unwrap();
    assert!(staged.write("../escape", b"x").is_err());
    staged.commit(&g).unwrap();
    assert_eq!(std::fs::read(target.join("index.html")).unwrap(), b"new");
    assert_eq!(std::fs::read(target.join("keep.txt")).unwrap(), b"mine");
    assert!(target.join("fig/a.svg").is_file());
    let fresh = dir.join("fresh");
    let staged = g.stage_folder(&fresh).unwrap();
    staged.write("a", b"1").unwrap();
    staged.commit(&g).unwrap();
    assert!(fresh.join("a").is_file());
    let leftovers: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with('.'))
        .collect();
    assert!(leftovers.is_empty(), "{leftovers:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--json /dev/full` replaced the device node by a regular file; an
/// output link was replaced by a file; two case names that map to one
/// plot name lost a plot; `--json rep/index.html --report rep` lost the
/// JSON. Each is now refused or written through.
#[cfg(unix)]
#[test]
fn special_files_links_same_names_and_claimed_files() {
    let dir = temp("special");
    let mut g = Outputs::new();
    let device = Path::new("/dev/null");
    assert!(matches!(
        g.write_file(device, b"x"),
        Err(OutputError::NotAFile { .. })
    ));
    assert!(
        std::fs::metadata(device)
            .unwrap()
            .file_type()
            .is_char_device()
    );
    let target = dir.join("target.json");
    std::fs::write(&target, "old").unwrap();
    std::os::unix::fs::symlink(&target, dir.join("link.json")).unwrap();
    g.write_file(&dir.join("link.json"), b"new").unwrap();
    assert!(
        std::fs::symlink_metadata(dir.join("link.json"))
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read(&target).unwrap(), b"new");
    let report = dir.join("report");
    g.claim(&report.join("index.html")).unwrap();
    g.claim(&report).unwrap();
    let staged = g.stage_folder(&report).unwrap();
    staged.write("fit-a_b.svg", b"1").unwrap();
    assert!(matches!(
        staged.write("fit-a_b.svg", b"2"),
        Err(OutputError::SameName { .. })
    ));
    staged.write("index.html", b"<html/>").unwrap();
    assert!(matches!(staged.commit(&g), Err(OutputError::Twice { .. })));
    assert!(!report.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

/// kill -9 during a write left `.out.csv.PID-N.tmp` and
/// `.report.PID-N.staging/` for good; the next write of the same output
/// removes those of processes that no longer run.
#[cfg(target_os = "linux")]
#[test]
fn a_killed_run_s_temporary_files_go_with_the_next_write() {
    let dir = temp("stale");
    let dead = u32::MAX - 7; // above any pid_max
    let stale_file = dir.join(format!(".out.csv.{dead}-3.tmp"));
    std::fs::write(&stale_file, "half").unwrap();
    let stale_folder = dir.join(format!(".report.{dead}-0.staging"));
    std::fs::create_dir_all(stale_folder.join("fig")).unwrap();
    let alive = dir.join(format!(".out.csv.{}-9.tmp", std::process::id()));
    std::fs::write(&alive, "mine").unwrap();
    let unrelated = dir.join(".out.csv.notes.tmp");
    std::fs::write(&unrelated, "user").unwrap();
    let g = Outputs::new();
    g.write_file(&dir.join("out.csv"), b"x").unwrap();
    g.stage_folder(&dir.join("report"))
        .unwrap()
        .commit(&g)
        .unwrap();
    assert!(!stale_file.exists() && !stale_folder.exists());
    assert!(alive.exists() && unrelated.exists());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn plain_names() {
    for bad in ["", "..", "/abs", "../../x", "a/b", ".hidden"] {
        assert!(plain_name(bad).is_err(), "{bad}");
    }
    assert!(plain_name("HEAD-1").is_ok());
}

/// `doe fit --json rep/index.html --report rep` wrote the JSON, then
/// refused the report: one command's outputs are now one transaction.
#[test]
fn a_transaction_moves_all_outputs_or_none() {
    use super::transaction::{Pending, Transaction};
    use super::write::write_temp;
    let dir = temp("transaction");
    let mut g = Outputs::new();
    let json = dir.join("rep/index.html");
    std::fs::write(dir.join("kept.csv"), "old").unwrap();
    g.claim(&json).unwrap();
    let mut t = Transaction::default();
    t.push(Pending::File(write_temp(&json, b"{}").unwrap()));
    t.push(Pending::File(
        write_temp(&dir.join("kept.csv"), b"new").unwrap(),
    ));
    let staged = g.stage_folder(&dir.join("rep")).unwrap();
    staged.write("index.html", b"<html/>").unwrap();
    t.push(Pending::Folder(staged));
    let err = t.commit(&g).unwrap_err();
    assert!(matches!(err, OutputError::Twice { .. }), "{err}");
    assert!(!json.exists());
    assert!(
        !dir.join("rep").exists(),
        "the folder made for the JSON stays"
    );
    assert_eq!(std::fs::read(dir.join("kept.csv")).unwrap(), b"old");
    // an input registered after the output was written is still refused
    let late = dir.join("late.toml");
    std::fs::write(&late, "input").unwrap();
    let mut t = Transaction::default();
    t.push(Pending::File(write_temp(&late, b"output").unwrap()));
    t.push(Pending::File(write_temp(&dir.join("a.csv"), b"a").unwrap()));
    g.input(&late);
    assert!(matches!(t.commit(&g), Err(OutputError::OnInput { .. })));
    assert_eq!(std::fs::read(&late).unwrap(), b"input");
    assert!(!dir.join("a.csv").exists());
    let mut t = Transaction::default();
    t.push(Pending::File(write_temp(&dir.join("a.csv"), b"a").unwrap()));
    t.push(Pending::File(
        write_temp(&dir.join("kept.csv"), b"new").unwrap(),
    ));
    assert_eq!(t.commit(&g).unwrap(), 2);
    assert_eq!(std::fs::read(dir.join("kept.csv")).unwrap(), b"new");
    let hidden: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .filter(|e| e.file_name().to_string_lossy().starts_with('.'))
        .collect();
    assert!(hidden.is_empty(), "{hidden:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--json rep/index.html --report rep` was refused only when the command
/// committed, after its computation: an output inside another is now
/// refused when it is claimed, naming both options; a file of another
/// kind inside a report folder (`--json rep/result.json`) stays allowed.
#[test]
fn an_output_inside_another_is_refused_when_claimed() {
    let dir = temp("nested");
    let report = Shape::Folder(&["html", "svg"]);
    let refused = |first: (&str, &str, Shape), second: (&str, &str, Shape)| {
        let mut g = Outputs::new();
        g.claim_as(&dir.join(first.1), first.0, first.2).unwrap();
        g.claim_as(&dir.join(second.1), second.0, second.2).err()
    };
    for (a, b) in [
        (
            ("--report", "rep", report),
            ("--json", "rep/index.html", Shape::File),
        ),
        (
            ("--json", "rep/INDEX.HTML", Shape::File),
            ("--report", "rep", report),
        ),
        (("--plot", "rep/p", report), ("--report", "rep", report)),
        (
            ("--iso-mme", "t", Shape::Folder(&[])),
            ("--json", "t/r.json", Shape::File),
        ),
        (("--work", "w", Shape::Checked), ("--report", "w/r", report)),
        (
            ("--json", "a.json", Shape::File),
            ("--csv", "a.json/b.csv", Shape::File),
        ),
    ] {
        let err = refused(a, b).expect("refused").to_string();
        assert!(
            err.contains(a.0) && err.contains(b.0) && err.contains("two outputs to one path"),
            "{err}"
        );
    }
    let allowed = refused(
        ("--report", "rep", report),
        ("--json", "rep/result.json", Shape::File),
    );
    assert!(allowed.is_none(), "{allowed:?}");
    let work = refused(
        ("--work", "w", Shape::Checked),
        ("--json", "w/r.json", Shape::File),
    );
    assert!(work.is_none(), "{work:?}");
    assert!(
        refused(
            ("--report", "rep", report),
            ("--json", "rep2/a.html", Shape::File)
        )
        .is_none()
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `--report .` would swap the working folder itself away (and carry the
/// staging folder into itself): refused, as is a folder above it.
#[test]
fn the_working_folder_is_not_an_output_folder() {
    let g = Outputs::new();
    let here = std::env::current_dir().unwrap();
    for path in [Path::new("."), here.as_path(), here.parent().unwrap()] {
        let err = g.check_folder(path).unwrap_err();
        assert!(
            matches!(err, OutputError::HoldsWorkingFolder { .. }),
            "{err}"
        );
        assert!(StagedFolder::new(path).is_err());
    }
    assert!(g.check_folder(&here.join("below")).is_ok());
}

/// An EV5 test's channel files `<stem>.NNN` are inputs with the `.EV5`
/// (`signal export v10146.EV5 -c 93 -o v10146.093` replaced the channel it
/// had read: hostile pass of issue 34); other files beside it are not.
#[test]
fn an_ev5_test_s_channel_files_are_inputs() {
    let dir = temp("ev5");
    std::fs::write(dir.join("v10146.EV5"), "header").unwrap();
    for name in ["v10146.001", "V10146.093", "other.001", "v10146.csv"] {
        std::fs::write(dir.join(name), "1").unwrap();
    }
    let mut g = Outputs::new();
    g.input(&dir.join("v10146.EV5"));
    for bad in ["v10146.001", "V10146.093", "v10146.EV5"] {
        assert!(g.write_file(&dir.join(bad), b"x").is_err(), "{bad}");
    }
    g.write_file(&dir.join("other.001"), b"ok").unwrap();
    g.write_file(&dir.join("v10146.csv"), b"ok").unwrap();
    assert_eq!(std::fs::read(dir.join("V10146.093")).unwrap(), b"1");
    std::fs::remove_dir_all(&dir).unwrap();
}
