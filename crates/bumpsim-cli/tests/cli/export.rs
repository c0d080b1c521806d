//! `bumpsim export`: CalculiX and LS-DYNA decks, one module per deck
//! (the MSD car's CalculiX deck and LS-DYNA include, the bumper spring, the
//! planar car), and the peers they run in.

mod bumper;
mod calculix;
mod links;
mod lsdyna;
mod planar;

use std::process::Command;

use crate::util::*;

/// Whether CalculiX's `ccx` is available (required under `BUMPSIM_REQUIRE_PEERS`).
pub(crate) fn ccx_available() -> bool {
    peer_available("ccx (calculix-ccx)", "sh", &["-c", "command -v ccx"])
}

/// Runs `ccx JOB` in `dir`; fails unless it ends cleanly; returns its log.
pub(crate) fn run_ccx(dir: &std::path::Path, job: &str) -> String {
    let run = Command::new("ccx")
        .arg(job)
        .current_dir(dir)
        .output()
        .unwrap();
    let log = text(&run.stdout);
    assert!(
        run.status.success() && !log.contains("*ERROR"),
        "{job}: {log}"
    );
    log
}

/// Runs `dir/car.inp` in ccx and reads it back with `bumpsim export
/// read-calculix` into `dir/ccx.csv`: its header and rows (time, x1, ...).
pub(crate) fn ccx_histories(dir: &std::path::Path) -> (Vec<String>, Vec<Vec<f64>>) {
    run_ccx(dir, "car");
    let (deck, csv) = (dir.join("car.inp"), dir.join("ccx.csv"));
    let read = bumpsim(&[
        "export",
        "read-calculix",
        deck.to_str().unwrap(),
        "-o",
        csv.to_str().unwrap(),
    ]);
    assert!(read.status.success(), "{}", text(&read.stderr));
    read_csv(&csv)
}

/// Whether python3 with ansys-dyna-core is available.
pub(crate) fn dyna_core_available() -> bool {
    peer_available(
        "ansys-dyna-core",
        "python3",
        &["-c", "import ansys.dyna.core"],
    )
}

/// The verdict of tests/peers/dyna_deck.py on a deck.
pub(crate) fn dyna_core(deck: &std::path::Path, external: &[&str]) -> serde_json::Value {
    let run = Command::new("python3")
        .arg(root().join("tests/peers/dyna_deck.py"))
        .arg(deck)
        .args(external)
        .output()
        .unwrap();
    assert!(run.status.success(), "dyna_deck.py: {}", text(&run.stderr));
    serde_json::from_slice(&run.stdout).unwrap()
}
