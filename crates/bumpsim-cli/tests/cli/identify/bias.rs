//! Issue 44: a case's bias window (`bias = [t0, t1]` in s; default the
//! pre-trigger) removes the sensors' constant biases and starts the random
//! walk the intervals count. Hostile windows exit 2 naming the case and the
//! key; a window inside the pre-trigger runs.

use crate::util::*;

/// The bundled study with `bias = VALUE` in its first case, in `dir`.
fn with_bias(dir: &std::path::Path, value: &str) -> std::path::PathBuf {
    let study = std::fs::read_to_string(root().join("examples/identify/study.toml")).unwrap();
    let study = study.replacen("cfc = 180\n", &format!("cfc = 180\nbias = {value}\n"), 1);
    copy_tree(&root().join("examples/identify"), dir);
    let path = dir.join("study.toml");
    std::fs::write(&path, study).unwrap();
    path
}

#[test]
fn hostile_bias_windows_exit_2_naming_the_case_and_key() {
    let dir = scratch("identify-bias-hostile");
    for (bias, expected) in [
        (
            "[5.0, 6.0]",
            "'flat': channel P0IMPA000000FOXP: step 'bias': the bias window [5, 6] s reaches beyond the record",
        ),
        (
            "[0.01, -0.01]",
            "'flat': bias = [0.01, -0.01]: expected two finite times in s, the first below the second",
        ),
        (
            "[nan, 0.0]",
            "'flat': bias = [NaN, 0]: expected two finite times",
        ),
        ("\"pre\"", "expected an array of exactly 2 numbers"),
        ("[-0.01]", "expected an array of exactly 2 numbers"),
        (
            "[-0.03, 0.0, 0.01]",
            "expected an array of exactly 2 numbers",
        ),
    ] {
        let study = with_bias(&dir, bias);
        let run = bumpsim(&[
            "identify",
            study.to_str().unwrap(),
            "--starts",
            "1",
            "--quiet",
        ]);
        assert_user_error(&run, expected);
    }
}

#[test]
fn a_bias_window_inside_the_pre_trigger_runs() {
    let dir = scratch("identify-bias-window");
    let study = with_bias(&dir, "[-0.03, 0.0]");
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--starts",
        "2",
        "--quiet",
    ]);
    let printed = text(&run.stdout) + &text(&run.stderr);
    assert_eq!(run.status.code(), Some(0), "{printed}");
    assert!(
        printed.contains("intervals from the integrated noise's random walk"),
        "{printed}"
    );
}
