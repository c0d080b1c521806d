//! Test support shared by every crate's integration tests: whether an
//! independent peer tool is on this machine.
//!
//! bumpsim's tests check its numbers against tools written by others
//! (scipy, statsmodels, mpmath, pyisomme, ansys-dyna-core, CalculiX `ccx`,
//! chromium, Slurm). On a developer's machine without them such a test is
//! skipped with a message naming the missing tool; `scripts/test` installs
//! them all and sets `BUMPSIM_REQUIRE_PEERS`, under which a missing peer
//! fails the test instead, so that CI can never pass by skipping.
//!
//! ```
//! // `true` answers, so this is `true` whatever BUMPSIM_REQUIRE_PEERS says.
//! assert!(bumpsim_peers::peer_available("true", "true", &[]));
//! ```

use std::process::Command;

pub mod recorded;

/// The environment variable under which a missing peer fails the test.
pub const REQUIRE: &str = "BUMPSIM_REQUIRE_PEERS";

/// Whether an independent tool answers `program args` successfully; when it
/// does not, a skip message naming `what`, or a panic when
/// [`REQUIRE`] is set.
pub fn peer_available(what: &str, program: &str, args: &[&str]) -> bool {
    let found = Command::new(program)
        .args(args)
        .output()
        .is_ok_and(|o| o.status.success());
    present(found, what)
}

/// Whether `python3` can import `module` (see [`peer_available`]).
pub fn python_available(module: &str) -> bool {
    let import = format!("import {module}");
    peer_available(
        &format!("python3 with {module}"),
        "python3",
        &["-c", &import],
    )
}

/// The folder `out` a generator script of `tests/peers/` writes (`python3
/// SCRIPT OUT ARGS...`), run once per version of the script: again while
/// `out/marker` is missing or the stamp `out/.generated-by` (a hash of the
/// script's text and its arguments) differs, so the tests of one target
/// folder share one series and a changed generator never leaves a stale
/// one. Panics with the script's stderr when it fails.
///
/// The tests of one binary run on parallel threads and often share a
/// series: a lock per folder serialises its check and generation, so a
/// thread never reads a file another thread's generator is rewriting (a
/// clean checkout's first run would otherwise regenerate the folder once
/// per thread, and a reader could meet a truncated CSV), while series in
/// other folders are generated alongside.
pub fn generated(script: &std::path::Path, out: &std::path::Path, args: &[&str], marker: &str) {
    let folder = folder_lock(out);
    // A generator that panicked in another test leaves the lock poisoned;
    // its stamp was removed before it ran, so the folder counts as stale
    // and the guard is taken regardless.
    let _guard = folder
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let stamp = out.join(".generated-by");
    let version = script_version(script, args);
    let current = std::fs::read_to_string(&stamp).is_ok_and(|s| s == version);
    if current && out.join(marker).is_file() {
        return;
    }
    // a run that fails half-way must not leave a current stamp behind
    let _ = std::fs::remove_file(&stamp);
    let mut all = vec![out.as_os_str()];
    all.extend(args.iter().map(std::ffi::OsStr::new));
    python(script, &all);
    std::fs::write(&stamp, version).unwrap_or_else(|e| panic!("{}: {e}", stamp.display()));
}

/// The lock of one generated folder ([`generated`]), made on first use.
fn folder_lock(out: &std::path::Path) -> std::sync::Arc<std::sync::Mutex<()>> {
    type Locks =
        std::collections::HashMap<std::path::PathBuf, std::sync::Arc<std::sync::Mutex<()>>>;
    static LOCKS: std::sync::Mutex<Option<Locks>> = std::sync::Mutex::new(None);
    let mut locks = LOCKS
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    locks
        .get_or_insert_with(Locks::new)
        .entry(out.to_path_buf())
        .or_default()
        .clone()
}

/// Runs `python3 SCRIPT ARGS...` (a peer of `tests/peers/`) and returns
/// its standard output; panics with the script's stderr when it fails.
/// The one way the tests of every crate run a Python peer.
pub fn python<A: AsRef<std::ffi::OsStr>>(script: &std::path::Path, args: &[A]) -> Vec<u8> {
    let run = Command::new("python3")
        .arg(script)
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("python3 {}: {e}", script.display()));
    assert!(
        run.status.success(),
        "{}: {}",
        script.display(),
        String::from_utf8_lossy(&run.stderr)
    );
    run.stdout
}

/// A hash of `script`'s text, of the repository's peer modules it imports
/// ([`imported`]) and of `args` (FNV-1a, 64 bits: stable across Rust
/// versions, unlike `DefaultHasher`), in hex: a generator whose helper
/// module changed is run again too.
fn script_version(script: &std::path::Path, args: &[&str]) -> String {
    let mut files = vec![script.to_path_buf()];
    imported(script, &mut files);
    let mut hash: u64 = 0xcbf2_9ce4_8422_2325;
    let mut add = |bytes: &[u8]| {
        for byte in bytes {
            hash = (hash ^ u64::from(*byte)).wrapping_mul(0x0100_0000_01b3);
        }
    };
    for file in &files {
        add(&std::fs::read(file).unwrap_or_else(|e| panic!("{}: {e}", file.display())));
    }
    add(args.join("\0").as_bytes());
    format!("{hash:016x}")
}

/// The peer modules `script` imports, transitively, appended to `files`:
/// each `import NAME` / `from NAME import` whose `NAME.py` lies beside the
/// script or in the repository's `tests/peers` or `bench/peers` (where the
/// peers put themselves on `sys.path`). Library modules (numpy, scipy) are
/// not files there and are skipped.
fn imported(script: &std::path::Path, files: &mut Vec<std::path::PathBuf>) {
    let Ok(text) = std::fs::read_to_string(script) else {
        return;
    };
    let here = script.parent().unwrap_or(std::path::Path::new("."));
    let root = here.join("../..");
    let folders = [
        here.to_path_buf(),
        root.join("tests/peers"),
        root.join("bench/peers"),
    ];
    for line in text.lines() {
        let words: Vec<&str> = line.split_whitespace().collect();
        let name = match words.as_slice() {
            ["import", name, ..] | ["from", name, "import", ..] => name.trim_end_matches(','),
            _ => continue,
        };
        let found = folders
            .iter()
            .map(|f| f.join(format!("{name}.py")))
            .find(|p| p.is_file());
        if let Some(path) = found.and_then(|p| p.canonicalize().ok())
            && !files.contains(&path)
        {
            files.push(path.clone());
            imported(&path, files);
        }
    }
}

/// Passes `found` through; when it is `false`, prints the skip message for
/// `what`, or panics when [`REQUIRE`] is set.
pub fn present(found: bool, what: &str) -> bool {
    if !found {
        assert!(
            std::env::var_os(REQUIRE).is_none(),
            "{REQUIRE} is set but {what} is not available"
        );
        eprintln!("skipped: {what} not found (scripts/test installs it)");
    }
    found
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_generator_runs_again_when_its_script_changes() {
        let dir = std::env::temp_dir().join(format!("bumpsim-peers-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let script = dir.join("count.py");
        let out = dir.join("out");
        let body = "import sys, pathlib\np = pathlib.Path(sys.argv[1]); p.mkdir(exist_ok=True)\n";
        let count =
            "c = p / 'runs'; c.write_text(str(int(c.read_text()) + 1 if c.exists() else 1))\n";
        std::fs::write(&script, format!("{body}{count}")).unwrap();
        generated(&script, &out, &[], "runs");
        generated(&script, &out, &[], "runs");
        assert_eq!(std::fs::read_to_string(out.join("runs")).unwrap(), "1");
        std::fs::write(&script, format!("{body}{count}# changed\n")).unwrap();
        generated(&script, &out, &[], "runs");
        assert_eq!(std::fs::read_to_string(out.join("runs")).unwrap(), "2");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_generator_runs_again_when_a_module_it_imports_changes() {
        let dir = std::env::temp_dir().join(format!("bumpsim-peers-import-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (script, helper, out) = (dir.join("gen.py"), dir.join("helper.py"), dir.join("out"));
        let body = "import sys, pathlib\nimport helper  # noqa: E402\np = pathlib.Path(sys.argv[1]); p.mkdir(exist_ok=True)\n";
        let count =
            "c = p / 'runs'; c.write_text(str(int(c.read_text()) + 1 if c.exists() else 1))\n";
        std::fs::write(&script, format!("{body}{count}")).unwrap();
        std::fs::write(&helper, "WINDOW = 1.0\n").unwrap();
        generated(&script, &out, &[], "runs");
        generated(&script, &out, &[], "runs");
        assert_eq!(std::fs::read_to_string(out.join("runs")).unwrap(), "1");
        std::fs::write(&helper, "WINDOW = 0.0998\n").unwrap();
        generated(&script, &out, &[], "runs");
        assert_eq!(std::fs::read_to_string(out.join("runs")).unwrap(), "2");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_program_that_succeeds_is_available() {
        assert!(peer_available("sh", "sh", &["-c", "exit 0"]));
    }

    #[test]
    fn a_failing_or_missing_program_is_not_available_without_require() {
        if std::env::var_os(REQUIRE).is_some() {
            return; // under REQUIRE these would (rightly) panic
        }
        assert!(!peer_available("sh", "sh", &["-c", "exit 3"]));
        assert!(!peer_available("nothing", "/nonexistent/program", &[]));
    }

    #[test]
    fn a_missing_peer_fails_under_require() {
        // A child process, so that this test's environment is untouched.
        let me = std::env::current_exe().expect("test binary path");
        let out = Command::new(me)
            .args(["--exact", "tests::missing_peer_probe", "--ignored"])
            .env(REQUIRE, "1")
            .output()
            .expect("run the test binary");
        assert!(
            !out.status.success(),
            "the probe must panic under {REQUIRE}"
        );
    }

    /// One lock per generated folder: the same path shares it, another
    /// folder has its own (generated alongside).
    #[test]
    fn a_folder_has_one_lock_and_another_folder_its_own() {
        let dir = std::env::temp_dir();
        let (a, b) = (folder_lock(&dir.join("a")), folder_lock(&dir.join("a")));
        let c = folder_lock(&dir.join("c"));
        assert!(std::sync::Arc::ptr_eq(&a, &b));
        assert!(!std::sync::Arc::ptr_eq(&a, &c));
        let _held = a.lock().unwrap();
        assert!(c.try_lock().is_ok(), "another folder waits for nobody");
        assert!(b.try_lock().is_err(), "the same folder waits");
    }

    #[test]
    #[ignore = "run by a_missing_peer_fails_under_require with the variable set"]
    fn missing_peer_probe() {
        peer_available("nothing", "/nonexistent/program", &[]);
    }
}
