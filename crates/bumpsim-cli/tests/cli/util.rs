//! Helpers shared by the command tests: paths, scratch folders, running
//! the real binary and checking its output.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../..")
}

pub fn example(name: &str) -> PathBuf {
    root().join("examples/simulate").join(name)
}

pub fn scratch(test: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("cli")
        .join(test);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

pub fn bumpsim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bumpsim"))
        .args(args)
        .output()
        .unwrap()
}

/// The binary run in `dir` (its relative paths are `dir`'s).
pub fn bumpsim_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_bumpsim"))
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap()
}

pub fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// Fails unless the run was refused as a user error (exit code 2) whose
/// message contains `needle`.
pub fn assert_user_error(run: &Output, needle: &str) {
    let stderr = text(&run.stderr);
    assert_eq!(run.status.code(), Some(2), "{stderr}");
    assert!(stderr.contains(needle), "missing '{needle}' in:\n{stderr}");
}

/// `synth` of `series` with each `(old, new, needle)` edit made in turn
/// (written in `dir`): refused with `needle` and no output folder left.
pub fn synth_refuses_each(dir: &Path, series: &str, cases: &[(&str, &str, &str)]) {
    for (k, &(old, new, needle)) in cases.iter().enumerate() {
        assert!(series.contains(old), "{old}");
        let file = dir.join(format!("hostile-{k}.toml"));
        std::fs::write(&file, series.replacen(old, new, 1)).unwrap();
        let out = dir.join(format!("out-{k}"));
        let run = bumpsim(&["synth", file.to_str().unwrap(), "-o", out.to_str().unwrap()]);
        assert_user_error(&run, needle);
        assert!(!out.exists(), "{new}: a refused series left its folder");
    }
}

/// Fails unless every expected piece is in `output`.
pub fn assert_contains(output: &str, expected: &[&str]) {
    for piece in expected {
        assert!(output.contains(piece), "missing '{piece}' in:\n{output}");
    }
}

pub fn simulate(car: &Path, force: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "simulate",
        "--car",
        car.to_str().unwrap(),
        "--force",
        force.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    bumpsim(&args)
}

/// NHTSA test 10146 from `../shared` beside the repository, or from
/// `$BUMPSIM_SHARED` (a work tree elsewhere).
pub fn nhtsa_ev5() -> Option<PathBuf> {
    let shared = std::env::var_os("BUMPSIM_SHARED").map_or(root().join("../shared"), PathBuf::from);
    let path = shared.join("data/nhtsa-10146/v10146.EV5");
    if !path.exists() {
        eprintln!(
            "SKIPPED: {} is absent (NHTSA test 10146 is read from ../shared)",
            path.display()
        );
        return None;
    }
    Some(path)
}

/// Copies a folder tree.
pub fn copy_tree(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap().flatten() {
        let target = to.join(entry.file_name());
        if entry.path().is_dir() {
            copy_tree(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), &target).unwrap();
        }
    }
}

/// Reads a bumpsim CSV into its header and rows of numbers.
pub fn read_csv(path: &Path) -> (Vec<String>, Vec<Vec<f64>>) {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    (
        header,
        lines
            .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
            .collect(),
    )
}

pub use bumpsim_peers::peer_available;

/// Headless Chromium, where the report tests render pages (skipped
/// without it, a failure under `BUMPSIM_REQUIRE_PEERS`).
pub fn chromium() -> Option<PathBuf> {
    let found = ["/usr/bin/chromium", "/usr/bin/chromium-browser"]
        .into_iter()
        .map(PathBuf::from)
        .find(|p| p.exists());
    bumpsim_peers::present(found.is_some(), "chromium");
    found
}

/// A probe that writes, into the page, the text boxes whose content is
/// wider than the box.
const OVERFLOW_PROBE: &str = "<script>addEventListener('load',()=>{const wide=[...document.querySelectorAll('pre,p,td,th,figcaption,li,div,h2')].filter(e=>e.scrollWidth>e.clientWidth+1).map(e=>e.tagName+': '+e.textContent.slice(0,60));const o=document.createElement('output');o.id='overflow';o.textContent=JSON.stringify(wide);document.body.appendChild(o)});</script>";

/// The text boxes of the HTML `page` wider than their box, as Chromium
/// lays it out at 1280 × 900 (a JSON list; `[]` when none).
pub fn overflowing(browser: &Path, page: &Path) -> String {
    let probed = page.with_file_name("probed.html");
    let html = std::fs::read_to_string(page).unwrap();
    let html = html.replace("</body>", &format!("{OVERFLOW_PROBE}</body>"));
    std::fs::write(&probed, html).unwrap();
    let dom = Command::new(browser)
        .args(["--headless", "--no-sandbox", "--disable-gpu"])
        .arg("--window-size=1280,900")
        .arg(format!(
            "--user-data-dir={}",
            page.with_file_name("profile").display()
        ))
        .arg("--dump-dom")
        .arg(format!(
            "file://{}",
            probed.canonicalize().unwrap().display()
        ))
        .output()
        .unwrap();
    let dom = text(&dom.stdout);
    let found = dom.split("<output id=\"overflow\">").nth(1);
    let found = found.and_then(|rest| rest.split("</output>").next());
    found
        .unwrap_or_else(|| panic!("{}: the probe did not run:\n{dom}", page.display()))
        .to_string()
}
