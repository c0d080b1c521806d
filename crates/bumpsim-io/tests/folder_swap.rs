//! An existing output folder killed mid-commit (`kill -9`) is entirely the
//! old folder or entirely the new one, never a mix, and the files in it
//! that bumpsim did not write stay.
//!
//! A child process (this test binary again, running `commit_loop` with
//! `BUMPSIM_SWAP_CHILD` set) commits new versions of a folder of many
//! files over and over; the parent kills it after varied delays and reads
//! the folder each time. On tmpfs (`/dev/shm`, where a flush costs
//! nothing) most of a round is the commit itself, so the kills land in it;
//! when a commit moved the files one by one, a kill left files of two
//! versions.

use bumpsim_io::output::{Outputs, StagedFolder};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

const FILES: usize = 300;
const CHILD: &str = "BUMPSIM_SWAP_CHILD";

/// A scratch folder, on tmpfs where there is one.
fn scratch(name: &str) -> PathBuf {
    let shm = Path::new("/dev/shm");
    let base = if shm.is_dir() {
        shm.to_path_buf()
    } else {
        std::env::temp_dir()
    };
    let dir = base.join(format!("bumpsim-swap-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Stages version `version` of the folder: every file holds the version.
fn stage(guard: &Outputs, target: &Path, version: u64) -> StagedFolder {
    let staged = guard.stage_folder(target).unwrap();
    for k in 0..FILES {
        let name = format!("fig/f{k:03}.svg");
        staged
            .write(&name, format!("{version}\n").as_bytes())
            .unwrap();
    }
    staged
        .write("index.html", format!("{version}\n").as_bytes())
        .unwrap();
    staged
}

/// Run as a child only: commits versions 1, 2, ... of `$BUMPSIM_SWAP_CHILD`
/// until it is killed.
#[test]
fn commit_loop() {
    let Some(target) = std::env::var_os(CHILD).map(PathBuf::from) else {
        return;
    };
    let guard = Outputs::new();
    for version in 1.. {
        stage(&guard, &target, version).commit(&guard).unwrap();
    }
}

/// The folder's bumpsim files all hold one version; the user's are there.
fn one_version(target: &Path) -> Result<u64, String> {
    let read = |p: &Path| std::fs::read_to_string(p).map_err(|e| format!("{}: {e}", p.display()));
    let index = read(&target.join("index.html"))?;
    for k in 0..FILES {
        let figure = read(&target.join(format!("fig/f{k:03}.svg")))?;
        if figure != index {
            return Err(format!(
                "f{k:03}.svg holds {figure:?}, index.html {index:?}"
            ));
        }
    }
    let figures = std::fs::read_dir(target.join("fig")).unwrap().count();
    if figures != FILES + 1 {
        return Err(format!(
            "{figures} entries in fig/, not {FILES} and the user's"
        ));
    }
    if read(&target.join("notes.txt"))? != "mine" || read(&target.join("fig/own.txt"))? != "own" {
        return Err("the user's files changed".into());
    }
    index.trim().parse().map_err(|e| format!("{index:?}: {e}"))
}

#[test]
fn a_folder_killed_mid_commit_is_entirely_old_or_entirely_new() {
    let dir = scratch("kill");
    let target = dir.join("report");
    let guard = Outputs::new();
    stage(&guard, &target, 0).commit(&guard).unwrap();
    std::fs::write(target.join("notes.txt"), "mine").unwrap();
    std::fs::write(target.join("fig/own.txt"), "own").unwrap();
    let mut versions = Vec::new();
    for round in 0..40u64 {
        let mut child = Command::new(std::env::current_exe().unwrap())
            .args(["commit_loop", "--exact", "--test-threads=1", "-q"])
            .env(CHILD, &target)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(Duration::from_millis(20 + 7 * (round % 11)));
        child.kill().unwrap(); // SIGKILL
        child.wait().unwrap();
        match one_version(&target) {
            Ok(version) => versions.push(version),
            Err(mixed) => panic!("kill {round} left a mixed folder: {mixed}"),
        }
    }
    assert!(
        versions.iter().any(|&v| v > 0),
        "no kill came after a commit: {versions:?}"
    );
    // the next write removes what the killed runs left beside the folder
    stage(&guard, &target, 99).commit(&guard).unwrap();
    assert_eq!(one_version(&target), Ok(99));
    let hidden: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name())
        .filter(|n| n != "report")
        .collect();
    assert!(hidden.is_empty(), "{hidden:?}");
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Where the swap cannot be one step (no `RENAME_EXCHANGE`), the old
/// folder is renamed aside before the new one moves in; a kill between the
/// two leaves no folder at the target, and the next write puts the old
/// one back before it stages.
#[cfg(target_os = "linux")]
#[test]
fn an_old_folder_left_aside_by_a_kill_is_put_back() {
    let dir = scratch("aside");
    let dead = u32::MAX - 7; // above any pid_max
    let aside = dir.join(format!(".report.{dead}-4.old"));
    std::fs::create_dir_all(&aside).unwrap();
    std::fs::write(aside.join("index.html"), "old").unwrap();
    let target = dir.join("report");
    let guard = Outputs::new();
    let staged = guard.stage_folder(&target).unwrap();
    assert_eq!(std::fs::read(target.join("index.html")).unwrap(), b"old");
    assert!(!aside.exists());
    staged.write("fig.svg", b"new").unwrap();
    staged.commit(&guard).unwrap();
    assert_eq!(std::fs::read(target.join("index.html")).unwrap(), b"old");
    assert_eq!(std::fs::read(target.join("fig.svg")).unwrap(), b"new");
    std::fs::remove_dir_all(&dir).unwrap();
}
