//! Recorded outputs (issue 46): the commands that pick a model — identify,
//! predict, impact, planar, synth, export, verdict — run on the bundled
//! examples, and their stdout, stderr, exit code and every written file
//! (JSON, CSV, TOML, decks, SVG, HTML, ISO-MME) must equal, byte for byte,
//! the copies under `tests/recorded/` made on main before the front ends
//! moved their model choice into the library. This is what "the chain's and
//! the planar car's results are byte-identical before and after the move"
//! means, checked on every test run.
//!
//! Masked on both sides (wall-clock only): the run time after `iterations;`
//! (stdout, HTML), the `time` column of the DOF table and the JSON's
//! `"run_time"`. Paths are relative: the commands run in a scratch folder
//! in which `ex` links to `examples/` and outputs go to `out/`.
//!
//! Files over 16 kB (history JSON and CSV, synthetic channels, reports with
//! figures) are recorded as `NAME.digest`: their masked length and 64-bit
//! FNV-1a hash, so the repository holds kilobytes, not megabytes.
//!
//! `BUMPSIM_RECORD=1` rewrites the recordings (only when a change of output
//! is intended; say so in the commit).

use crate::util::{bumpsim_in, root, scratch, text};
use std::path::{Path, PathBuf};

/// The runs, in order (later ones read earlier ones' outputs): a name and
/// the arguments.
#[rustfmt::skip]
const RUNS: &[(&str, &[&str])] = &[
    (
        "identify-chain",
        &[
            "identify", "ex/identify/study.toml", "--starts", "4", "--quiet", "--json",
            "out/identify/result.json", "--sensitivity", "out/identify/sensitivity.csv",
            "--report", "out/identify/report",
        ],
    ),
    (
        "identify-dofs",
        &[
            "identify", "ex/identify/study.toml", "--dof", "1..3", "--starts", "2", "--quiet",
            "--json", "out/identify/dofs.json",
        ],
    ),
    (
        "identify-chain-car-refused",
        &["identify", "ex/identify/study.toml", "--car", "out/no.toml"],
    ),
    (
        "predict-chain",
        &[
            "predict", "out/identify/result.json", "ex/identify/study.toml", "--json",
            "out/predict/fits.json", "--plot", "out/predict/plots",
        ],
    ),
    (
        "predict-chain-car",
        &["predict", "ex/identify/car-truth.toml", "ex/identify/study.toml", "--case", "pole"],
    ),
    (
        "impact-chain",
        &[
            "impact", "--car", "ex/identify/car-truth.toml", "--bumper",
            "ex/impact/bumper-a.toml", "--barrier", "--speed", "8 km/h", "--json",
            "out/impact/chain.json", "--csv", "out/impact/chain.csv",
        ],
    ),
    (
        "impact-identified",
        &[
            "impact", "--car", "out/identify/result.json", "--bumper", "ex/impact/bumper-b.toml",
            "--pendulum", "1450", "--speed", "6 km/h", "--json", "out/impact/identified.json",
        ],
    ),
    (
        "impact-chain-no-bumper",
        &["impact", "--car", "ex/identify/car-truth.toml", "--barrier", "--speed", "8 km/h"],
    ),
    (
        "impact-planar-car",
        &[
            "impact", "--car", "ex/planar/saloon.toml", "--case", "rcar-structural-front",
            "--json", "out/impact/planar.json",
        ],
    ),
    (
        "planar",
        &[
            "planar", "--car", "ex/planar/saloon.toml", "--case", "rcar-structural-front",
            "--json", "out/planar/front.json", "--csv", "out/planar/front.csv", "--report",
            "out/planar/report",
        ],
    ),
    (
        "planar-offset",
        &[
            "planar", "--car", "ex/planar/saloon.toml", "--angle", "-10", "--overlap", "40",
            "--side", "right", "--speed", "15 km/h", "--json", "out/planar/offset.json",
        ],
    ),
    ("synth-chain", &["synth", "ex/identify/series.toml", "-o", "out/synth-chain"]),
    ("synth-planar", &["synth", "ex/planar/identify/series.toml", "-o", "out/synth-planar"]),
    (
        "identify-planar",
        &[
            "identify", "out/synth-planar/study.toml", "--starts", "2", "--quiet", "--json",
            "out/planar-id/result.json", "--car", "out/planar-id/car.toml", "--report",
            "out/planar-id/report",
        ],
    ),
    (
        "identify-planar-dof-refused",
        &["identify", "out/synth-planar/study.toml", "--dof", "2"],
    ),
    (
        "predict-planar",
        &[
            "predict", "out/planar-id/car.toml", "out/synth-planar/study.toml", "--json",
            "out/planar-id/predict.json",
        ],
    ),
    (
        "predict-planar-car-on-chain-study",
        &["predict", "out/planar-id/car.toml", "ex/identify/study.toml"],
    ),
    (
        "predict-planar-json-refused",
        &["predict", "out/planar-id/result.json", "out/synth-planar/study.toml"],
    ),
    (
        "predict-chain-car-on-planar-study",
        &["predict", "ex/identify/car-truth.toml", "out/synth-planar/study.toml"],
    ),
    (
        "export-lsdyna",
        &["export", "lsdyna", "ex/simulate/car-3dof.toml", "-o", "out/export/car.k"],
    ),
    (
        "export-calculix-identified",
        &["export", "calculix", "out/identify/result.json", "-o", "out/export/car.inp"],
    ),
    (
        "export-bumper",
        &[
            "export", "bumper", "ex/impact/bumper-a.toml", "--solver", "lsdyna", "-o",
            "out/export/bumper.k",
        ],
    ),
    (
        "export-planar-lsdyna",
        &[
            "export", "planar", "ex/planar/saloon.toml", "--solver", "lsdyna", "-o",
            "out/export/planar.k",
        ],
    ),
    (
        "export-planar-calculix",
        &[
            "export", "planar", "ex/planar/saloon.toml", "--solver", "calculix", "-o",
            "out/export/planar.inp",
        ],
    ),
    (
        "verdict",
        &[
            "verdict", "--car", "ex/verdict/car.toml", "--protocol", "part581,rcar-bumper",
            "--json", "out/verdict/verdict.json",
        ],
    ),
    (
        "verdict-identified",
        &[
            "verdict", "--car", "out/planar-id/car.toml", "--damageability",
            "ex/verdict/damageability.toml", "--protocol", "part581-barrier-front",
        ],
    ),
];

fn recorded() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/recorded")
}

/// Every file under `dir`, relative to it, sorted.
fn files(dir: &Path) -> Vec<PathBuf> {
    fn walk(base: &Path, dir: &Path, out: &mut Vec<PathBuf>) {
        let Ok(entries) = std::fs::read_dir(dir) else {
            return;
        };
        for entry in entries {
            let path = entry.unwrap().path();
            if path.is_dir() {
                walk(base, &path, out);
            } else {
                out.push(path.strip_prefix(base).unwrap().to_path_buf());
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

/// The text with its wall-clock times replaced by `T` (see the module doc).
fn masked(text: &str) -> String {
    let mut out = String::new();
    let mut in_dof_table = false;
    for line in text.split_inclusive('\n') {
        let mut line = line.to_string();
        if let Some(at) = line.find("iterations; ") {
            let start = at + "iterations; ".len();
            let end = line[start..]
                .find(['<', '\n'])
                .map_or(line.len(), |e| start + e);
            line.replace_range(start..end, "T");
        }
        if let Some(at) = line.find("\"run_time\": ") {
            let start = at + "\"run_time\": ".len();
            let end = line[start..]
                .find([',', '\n'])
                .map_or(line.len(), |e| start + e);
            line.replace_range(start..end, "T");
        }
        let trimmed = line.trim_end();
        if trimmed.starts_with(" DOF") && trimmed.ends_with(" time") {
            in_dof_table = true;
        } else if in_dof_table
            && trimmed
                .split_whitespace()
                .next()
                .is_none_or(|w| w.parse::<usize>().is_err())
        {
            in_dof_table = false;
        } else if in_dof_table {
            // the last two words: the run time and its unit
            let words: Vec<&str> = trimmed.split_whitespace().collect();
            if words.len() > 2 {
                let keep = trimmed
                    .rfind(words[words.len() - 2])
                    .map_or(trimmed, |i| &trimmed[..i]);
                line = format!("{keep}T\n");
            }
        }
        out.push_str(&line);
    }
    out
}

/// The bytes as compared: text masked, anything else as is.
fn comparable(bytes: Vec<u8>) -> Vec<u8> {
    match String::from_utf8(bytes) {
        Ok(text) => masked(&text).into_bytes(),
        Err(e) => e.into_bytes(),
    }
}

/// Largest file recorded whole.
const WHOLE: usize = 16 * 1024;

/// The length and FNV-1a (64 bit) hash of the bytes, as `NAME.digest` holds.
fn digest(bytes: &[u8]) -> Vec<u8> {
    let hash = bytes.iter().fold(0xcbf2_9ce4_8422_2325_u64, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    });
    format!("{} bytes, fnv1a64 {hash:016x}\n", bytes.len()).into_bytes()
}

/// The recorded name of an output file and what is recorded for it.
fn record(file: &Path, bytes: Vec<u8>) -> (PathBuf, Vec<u8>) {
    let bytes = comparable(bytes);
    match bytes.len() > WHOLE {
        true => {
            let mut name = file.as_os_str().to_owned();
            name.push(".digest");
            (PathBuf::from(name), digest(&bytes))
        }
        false => (file.to_path_buf(), bytes),
    }
}

#[test]
fn the_commands_write_what_main_wrote() {
    let dir = scratch("recorded");
    std::os::unix::fs::symlink(root().join("examples"), dir.join("ex")).unwrap();
    std::fs::create_dir_all(dir.join("out/runs")).unwrap();
    for (name, args) in RUNS {
        let run = bumpsim_in(&dir, args);
        let status = format!("exit {:?}\n", run.status.code());
        let stderr = text(&run.stderr);
        std::fs::write(dir.join(format!("out/runs/{name}.stdout")), &run.stdout).unwrap();
        std::fs::write(
            dir.join(format!("out/runs/{name}.stderr")),
            status + &stderr,
        )
        .unwrap();
    }
    let got = dir.join("out");
    if std::env::var_os("BUMPSIM_RECORD").is_some() {
        let _ = std::fs::remove_dir_all(recorded());
        for file in files(&got) {
            let (name, bytes) = record(&file, std::fs::read(got.join(&file)).unwrap());
            let to = recorded().join(name);
            std::fs::create_dir_all(to.parent().unwrap()).unwrap();
            std::fs::write(to, bytes).unwrap();
        }
        return;
    }
    let now: Vec<(PathBuf, PathBuf, Vec<u8>)> = files(&got)
        .into_iter()
        .map(|file| {
            let (name, bytes) = record(&file, std::fs::read(got.join(&file)).unwrap());
            (file, name, bytes)
        })
        .collect();
    let names: Vec<PathBuf> = now.iter().map(|(_, name, _)| name.clone()).collect();
    let mut want_files = files(&recorded());
    let mut got_files = names.clone();
    want_files.sort();
    got_files.sort();
    assert_eq!(
        want_files, got_files,
        "the commands wrote other files than were recorded"
    );
    let mut differ = Vec::new();
    for (file, name, now) in &now {
        let want = std::fs::read(recorded().join(name)).unwrap();
        if &want != now {
            differ.push(format!(
                "{} (now in {})",
                file.display(),
                got.join(file).display()
            ));
        }
    }
    assert!(
        differ.is_empty(),
        "outputs differ from the recorded ones:\n{}",
        differ.join("\n")
    );
}

#[test]
fn a_declared_kind_picks_the_model_as_the_legacy_detection_did() {
    let dir = scratch("declared-kind");
    let examples = root().join("examples");
    for head in ["FLAT", "P600", "POLE"] {
        std::os::unix::fs::symlink(examples.join("identify").join(head), dir.join(head)).unwrap();
    }
    let study = std::fs::read_to_string(examples.join("identify/study.toml")).unwrap();
    std::fs::write(
        dir.join("declared.toml"),
        format!("kind = \"chain\"\n{study}"),
    )
    .unwrap();
    std::fs::write(dir.join("legacy.toml"), &study).unwrap();
    std::fs::write(dir.join("tank.toml"), format!("kind = \"tank\"\n{study}")).unwrap();
    let car = std::fs::read_to_string(examples.join("planar/saloon.toml")).unwrap();
    std::fs::write(dir.join("saloon.toml"), format!("kind = \"planar\"\n{car}")).unwrap();
    let identify = |study: &str| bumpsim_in(&dir, &["identify", study, "--starts", "2", "--quiet"]);
    let (declared, legacy) = (identify("declared.toml"), identify("legacy.toml"));
    assert_eq!(
        declared.status.code(),
        Some(0),
        "{}",
        text(&declared.stderr)
    );
    assert_eq!(
        masked(&text(&declared.stdout)),
        masked(&text(&legacy.stdout))
    );
    crate::util::assert_user_error(
        &identify("tank.toml"),
        "kind = \"tank\" is not a model bumpsim has (known: chain, planar, links)",
    );
    let planar = |car: &str| {
        bumpsim_in(
            &dir,
            &["impact", "--car", car, "--case", "rcar-structural-front"],
        )
    };
    let declared = planar("saloon.toml");
    assert_eq!(
        declared.status.code(),
        Some(0),
        "{}",
        text(&declared.stderr)
    );
    let legacy = planar(examples.join("planar/saloon.toml").to_str().unwrap());
    assert_eq!(
        text(&declared.stdout),
        text(&legacy.stdout).replace(
            examples.join("planar/saloon.toml").to_str().unwrap(),
            "saloon.toml"
        )
    );
}
