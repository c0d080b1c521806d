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

/// A CSV crash test of two channels (force, acceleration) in `dir`.
fn csv_test(dir: &std::path::Path) -> std::path::PathBuf {
    let mut csv = String::from("time [s],F [kN],a [g]\n");
    for i in 0..200 {
        let s = (std::f64::consts::PI * f64::from(i) / 199.0).sin();
        csv += &format!(
            "{:.6},{:.6},{:.6}\n",
            f64::from(i) * 1e-4,
            10.0 * s,
            -2.0 * s
        );
    }
    let path = dir.join("test.csv");
    std::fs::write(&path, csv).unwrap();
    path
}

/// Issue 34: a refused second output leaves no first one behind (one
/// transaction per command), and selectors and signal names that would
/// give a wrong or unreadable table are refused.
#[test]
fn signal_outputs_are_all_or_nothing_and_every_name_is_used_once() {
    let dir = scratch("signal-hostile");
    let test = csv_test(&dir);
    let before = std::fs::read(&test).unwrap();
    let (t, out) = (test.to_str().unwrap(), dir.join("o.csv"));
    let o = out.to_str().unwrap();
    // a plot folder holding a hard link to the input: the CSV was written first
    let plots = dir.join("pl");
    std::fs::create_dir_all(&plots).unwrap();
    std::fs::hard_link(&test, plots.join("F.svg")).unwrap();
    let run = bumpsim(&[
        "signal",
        "export",
        t,
        "-c",
        "F",
        "-o",
        o,
        "--plot",
        plots.to_str().unwrap(),
    ]);
    assert_user_error(&run, "would overwrite the input");
    assert!(!out.exists(), "the refused export left its CSV");
    assert_eq!(std::fs::read(&test).unwrap(), before);
    for (channels, needle) in [
        (&["-c", ""][..], "an empty selector"),
        (&["-c", "1", "-c", "1"], "picked by '1' and again by '1'"),
    ] {
        let run = bumpsim(&[&["signal", "export", t, "-o", o][..], channels].concat());
        assert_user_error(&run, needle);
        assert!(!out.exists(), "{channels:?}");
    }
    let pipeline = dir.join("p.toml");
    let p = pipeline.to_str().unwrap();
    let signal = |name: &str, channels: &str| {
        format!(
            "[[signal]]\nname = {name}\npath = \"test.csv\"\nchannels = [{channels}]\ncombine = \"sum\"\n"
        )
    };
    for (signals, needle) in [
        (
            signal("\"a\"", "\"F\"") + &signal("\"a\"", "\"a\""),
            "already used by 'a'",
        ),
        (
            signal("\"a\"", "\"F\"") + &signal("\"\"", "\"a\""),
            "an empty name",
        ),
        (
            signal("\"a\"", "\"F\"") + &signal("\"a,b\"", "\"a\""),
            "'a,b'",
        ),
        (signal("\"force\"", "\"F\", \"1\""), "it would count twice"),
    ] {
        std::fs::write(&pipeline, signals).unwrap();
        assert_user_error(&bumpsim(&["signal", "process", p, "-o", o]), needle);
        assert!(!out.exists(), "{needle}");
    }
    std::fs::write(&pipeline, signal("\"force\"", "\"F\"")).unwrap();
    let plots = dir.join("plots");
    let inside = plots.join("force.svg");
    let run = bumpsim(&[
        "signal",
        "process",
        p,
        "-o",
        inside.to_str().unwrap(),
        "--plot",
        plots.to_str().unwrap(),
    ]);
    assert_user_error(&run, "two outputs to one path");
    assert!(
        !plots.exists(),
        "the refused command left {}",
        plots.display()
    );
}

/// Issue 34: `signal info` on a FIFO blocked forever, a device was read
/// until memory ran out; both are refused at once.
#[cfg(unix)]
#[test]
fn streams_are_refused_without_blocking() {
    let dir = scratch("signal-fifo");
    let fifo = dir.join("test.csv");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo");
    for args in [
        vec!["signal", "info", fifo.to_str().unwrap()],
        vec!["signal", "info", "/dev/zero"],
    ] {
        let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_bumpsim"))
            .args(&args)
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap();
        let start = std::time::Instant::now();
        while child.try_wait().unwrap().is_none() && start.elapsed().as_secs() < 20 {
            std::thread::sleep(std::time::Duration::from_millis(50));
        }
        if child.try_wait().unwrap().is_none() {
            child.kill().unwrap();
            panic!("{args:?} still runs after 20 s");
        }
        let run = child.wait_with_output().unwrap();
        assert_user_error(&run, "not a regular file");
    }
}

/// Issue 34, a hostile pass: a pipeline whose own `output` is an input (the
/// pipeline itself, a file of the test it reads) ran and printed its
/// signals before the refusal; it is refused before it runs now.
#[test]
fn a_pipeline_output_on_an_input_is_refused_before_it_runs() {
    let dir = scratch("signal-pipeline-output");
    copy_tree(&root().join("examples/identify/FLAT"), &dir.join("FLAT"));
    for output in ["p.toml", "FLAT/FLAT.mme"] {
        let pipeline = format!(
            "output = \"{output}\"\n[[signal]]\nname = \"f\"\npath = \"FLAT\"\nchannels = [\"1\"]\n"
        );
        std::fs::write(dir.join("p.toml"), &pipeline).unwrap();
        let run = bumpsim(&["signal", "process", dir.join("p.toml").to_str().unwrap()]);
        assert_user_error(&run, "refusing to write");
        assert_eq!(text(&run.stdout), "", "{output}: it ran before the refusal");
        assert_eq!(
            std::fs::read_to_string(dir.join("p.toml")).unwrap(),
            pipeline
        );
    }
}

/// `signal export --cfc 1e308` was refused naming the derived cut-off
/// ("cutoff (Hz) = inf"), not the flag; `--cfc 1e-300` exited 0 with the
/// first sample repeated (a filter that no longer filters). Each names
/// `--cfc` and the classes the channel's sample rate allows (10 kHz:
/// 0.0048135 to below 2406.7 in SAE J211-1), and writes nothing.
#[test]
fn a_cfc_class_out_of_range_names_the_flag_and_its_range() {
    let dir = scratch("signal-cfc");
    let test = root().join("examples/identify/FLAT");
    let out = dir.join("o.csv");
    let export = |class: &str| {
        let (test, out) = (test.to_str().unwrap(), out.to_str().unwrap());
        bumpsim(&[
            "signal", "export", test, "-c", "1", "--cfc", class, "-o", out,
        ])
    };
    for class in ["1e308", "1e6", "2406.8", "1e-300", "0"] {
        let run = export(class);
        assert_user_error(&run, "--cfc ");
        let stderr = text(&run.stderr);
        assert!(
            !stderr.contains("inf Hz") && !stderr.contains("cutoff"),
            "{stderr}"
        );
        if class != "0" {
            assert!(
                stderr.contains("from 0.0048135 to below 2406.7")
                    && stderr.contains("sampled at 10000 Hz"),
                "{class}: {stderr}"
            );
        }
        assert!(!out.exists(), "{class}: an output was written");
    }
    let edge = export("2406.6");
    assert_eq!(edge.status.code(), Some(0), "{}", text(&edge.stderr));
}

/// Hostile pass of issue 34: `signal export v10146.EV5 -c 93 -o
/// v10146.093` exited 0 and replaced the channel file it had just read
/// with its CSV. A channel of the EV5 test is an input: refused, unchanged.
#[test]
fn an_ev5_channel_file_is_never_an_output() {
    let Some(ev5) = nhtsa_ev5() else { return };
    let dir = scratch("ev5-channel-output");
    for name in ["v10146.EV5", "v10146.093", "v10146.094"] {
        std::fs::copy(ev5.with_file_name(name), dir.join(name)).unwrap();
    }
    let (test, channel) = (dir.join("v10146.EV5"), dir.join("v10146.093"));
    let before = std::fs::read(&channel).unwrap();
    for out in ["v10146.093", "v10146.094"] {
        let run = bumpsim(&[
            "signal",
            "export",
            test.to_str().unwrap(),
            "-c",
            "93",
            "-o",
            dir.join(out).to_str().unwrap(),
        ]);
        assert_user_error(&run, "input");
    }
    assert_eq!(std::fs::read(&channel).unwrap(), before);
}

/// Hostile pass of issue 34: `--unit kN --unit N` wrote kN and ignored the
/// second; `--iso-6487` without `--cfc` changed nothing. Both are refused.
#[test]
fn flags_that_would_do_nothing_are_refused() {
    let flat = root().join("examples/identify/FLAT/FLAT.mme");
    let out = scratch("signal-ignored-flags").join("o.csv");
    let export = |extra: &[&str]| {
        let mut args = vec!["signal", "export", flat.to_str().unwrap(), "-c", "1"];
        args.extend_from_slice(&["-o", out.to_str().unwrap()]);
        args.extend_from_slice(extra);
        bumpsim(&args)
    };
    let twice = export(&["--unit", "kN", "--unit", "N"]);
    assert_user_error(&twice, "--unit N: kN was asked for force already");
    assert_user_error(&export(&["--iso-6487"]), "--cfc");
    assert!(!out.exists(), "a refused export wrote its output");
}

/// `signal info > /dev/full` said "No space left on device" without saying
/// where (hostile pass of issue 34).
#[test]
fn an_unprintable_standard_output_is_named() {
    let run = std::process::Command::new(env!("CARGO_BIN_EXE_bumpsim"))
        .args(["signal", "info"])
        .arg(root().join("examples/identify/FLAT/FLAT.mme"))
        .stdout(std::fs::File::create("/dev/full").unwrap())
        .output()
        .unwrap();
    assert_user_error(&run, "cannot print the results to standard output");
}
