//! `bumpsim signal`: info, export and process on the NHTSA test.

use crate::util::*;

/// The number before `marker` on the line that holds `label`.
fn number_before(stdout: &str, label: &str, marker: &str) -> f64 {
    let line = stdout
        .lines()
        .find(|l| l.contains(label))
        .unwrap_or_else(|| panic!("no '{label}' in {stdout}"));
    let head = &line[..line
        .find(marker)
        .unwrap_or_else(|| panic!("no '{marker}' in {line}"))];
    head.rsplit(['(', ' '])
        .find(|s| !s.is_empty())
        .unwrap()
        .parse()
        .unwrap()
}

#[test]
fn signal_info_lists_the_nhtsa_curves_and_marks_the_invalid_cells() {
    let Some(ev5) = nhtsa_ev5() else { return };
    let run = bumpsim(&["signal", "info", ev5.to_str().unwrap()]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        stdout.contains("634 channels listed, 184 with samples present"),
        "{stdout}"
    );
    assert!(stdout.contains("57.09 km/h") && stdout.contains("1719 kg"));
    for cell in ["347  0-LC-LC0601-XG", "500  0-LC-LC0304-XG"] {
        let line = stdout.lines().find(|l| l.contains(cell)).unwrap();
        assert!(
            line.contains("INVALID") && line.contains("No valid data"),
            "{line}"
        );
    }
    assert!(
        stdout
            .lines()
            .any(|l| l.contains("   93  1-AC-FLLR-XG") && l.contains("present"))
    );
}

#[test]
fn nhtsa_barrier_impulse_matches_the_momentum_change_of_the_test_mass() {
    let Some(_) = nhtsa_ev5() else { return };
    let dir = scratch("nhtsa-process");
    let pipeline = root().join("examples/nhtsa-10146/pipeline.toml");
    let csv = dir.join("signals.csv");
    let plots = dir.join("plots");
    let run = bumpsim(&[
        "signal",
        "process",
        pipeline.to_str().unwrap(),
        "-o",
        csv.to_str().unwrap(),
        "--plot",
        plots.to_str().unwrap(),
    ]);
    let (stdout, stderr) = (text(&run.stdout), text(&run.stderr));
    assert!(run.status.success(), "{stderr}");
    assert!(
        stderr.contains("left out channel 347") && stderr.contains("left out channel 500"),
        "{stderr}"
    );
    let difference = number_before(&stdout, "momentum balance", " %)");
    assert!(
        difference.abs() < 5.0,
        "impulse vs momentum change: {difference} %\n{stdout}"
    );
    assert!(stdout.contains("of 1719 kg"), "{stdout}");
    let peak = number_before(&stdout, "barrier force: peak", " kN at");
    assert!(
        (-800.0..-500.0).contains(&peak),
        "peak barrier force {peak} kN"
    );
    let peak_time = number_before(&stdout, "barrier force: peak", " ms;");
    assert!(
        (20.0..60.0).contains(&peak_time),
        "time of peak {peak_time} ms"
    );
    let crush = number_before(&stdout, "crush: peak", " mm at");
    assert!(
        (500.0..1000.0).contains(&crush),
        "maximum dynamic crush {crush} mm"
    );
    let header = std::fs::read_to_string(&csv)
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .to_string();
    assert_eq!(
        header,
        "time [s],barrier force [N],crossmember velocity [m/s],crush [m]"
    );
    let svg = std::fs::read_to_string(plots.join("barrier_force.svg")).unwrap();
    assert!(svg.contains("force [kN]") && svg.contains("time [ms]"));
}

#[test]
fn signal_export_writes_si_columns_named_by_code() {
    let dir = scratch("signal-export");
    let out = dir.join("lab.csv");
    let mme = dir.join("mme");
    let sample = root().join("tests/data/isomme/LAB01");
    let run = bumpsim(&[
        "signal",
        "export",
        sample.to_str().unwrap(),
        "--channel",
        "P0IMPA*",
        "--channel",
        "längsträger",
        "--cfc",
        "1000",
        "-o",
        out.to_str().unwrap(),
        "--iso-mme",
        mme.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let csv = std::fs::read_to_string(&out).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "time [s],P0IMPA000000FOXA [N],10SIMELE0000ACXA [m/s^2]"
    );
    assert_eq!(csv.lines().count(), 41);
    let again = bumpsim(&["signal", "info", mme.to_str().unwrap()]);
    assert!(
        text(&again.stdout).contains("2 channels listed"),
        "{}",
        text(&again.stdout)
    );
    let refused = bumpsim(&[
        "signal",
        "export",
        sample.to_str().unwrap(),
        "-c",
        "1",
        "-o",
        out.to_str().unwrap(),
        "--iso-mme",
        mme.to_str().unwrap(),
    ]);
    assert_eq!(refused.status.code(), Some(2));
    assert!(text(&refused.stderr).contains("not empty"));
}

#[test]
fn signal_errors_exit_2_with_the_path_and_selector() {
    let sample = root().join("tests/data/isomme/LAB01");
    let out = scratch("signal-errors").join("x.csv");
    let run = bumpsim(&[
        "signal",
        "export",
        sample.to_str().unwrap(),
        "-c",
        "11HEAD*",
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = text(&run.stderr);
    assert!(
        stderr.contains("LAB01")
            && stderr.contains("'11HEAD*'")
            && stderr.contains("matches no channel"),
        "{stderr}"
    );
    let missing = bumpsim(&["signal", "info", "no/such/test.mme"]);
    assert_eq!(missing.status.code(), Some(2));
    assert!(text(&missing.stderr).contains("no/such/test.mme"));
    // a CSV test file's error names the file once, with the line
    let bad = out.with_file_name("bad.csv");
    std::fs::write(&bad, "time [s],f [N]\n0,1\n0.1,x\n").unwrap();
    let run = bumpsim(&["signal", "info", bad.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = text(&run.stderr);
    assert_eq!(stderr.matches("bad.csv").count(), 1, "{stderr}");
    assert!(
        stderr.contains("bad.csv:3: column 'f [N]' holds 'x'"),
        "{stderr}"
    );
}
