//! Issue 48 (round 3), refusals that name what to fix: a study given as a
//! folder is named as such (it said "refusing to write inside the input
//! folder ."), and a report or plot folder that holds an input of the kind
//! it writes names that input (it named only the folder, or ran the whole
//! identification before refusing).

use super::{examples, run_in, snapshot, stderr, user_error};

#[test]
fn a_folder_given_as_the_study_is_named_as_such() {
    let dir = examples("study-folder");
    user_error(
        &dir,
        &["identify", ".", "--json", "out.json"],
        ".: is a folder; the study (a TOML file) must be a file",
    );
    user_error(
        &dir,
        &["identify", "ex/identify", "--json", "out.json"],
        "ex/identify: is a folder; the study",
    );
    assert!(!dir.join("out.json").exists());
}

#[test]
fn a_report_or_plot_folder_holding_an_input_of_its_kind_names_the_clash() {
    let dir = examples("report-clash");
    let study = dir.join("ex/identify/study.toml");
    std::fs::copy(&study, dir.join("ex/identify/index.html")).unwrap();
    let before = snapshot(&dir.join("ex/identify/index.html"));
    let needle = "--report ex/identify: refusing to write: the folder holds the input \
                  ex/identify/index.html, and this output writes html, svg, png files";
    user_error(
        &dir,
        &[
            "identify",
            "ex/identify/index.html",
            "--report",
            "ex/identify",
        ],
        needle,
    );
    // in the working folder itself the clash comes first, not "holds the working folder"
    let inside = dir.join("ex/identify");
    user_error(
        &inside,
        &["identify", "index.html", "--report", "."],
        "--report .: refusing to write: the folder holds the input index.html",
    );
    // a plot folder holding an input named like one of its plots
    std::fs::copy(&study, dir.join("ex/identify/predict-push.svg")).unwrap();
    let (out, _) = run_in(
        &dir,
        &[
            "predict",
            "ex/identify/car-truth.toml",
            "ex/identify/predict-push.svg",
            "--plot",
            "ex/identify",
        ],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("--plot ex/identify: refusing to write: the folder holds the input"),
        "{}",
        stderr(&out)
    );
    assert_eq!(snapshot(&dir.join("ex/identify/index.html")), before);
}
