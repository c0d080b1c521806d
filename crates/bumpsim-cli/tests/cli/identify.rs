//! `bumpsim identify` and `bumpsim predict`: the bundled example, reports,
//! the NHTSA fit and errors.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

use crate::util::*;

mod band;
mod bias;
mod hostile;
mod posterior;
mod sheet;

fn identify_example() -> PathBuf {
    root().join("examples/identify/study.toml")
}

/// The bundled example in `dir` with `[identification] objective =
/// "displacement"` (the thesis's objective, the default before issue 44).
fn displacement_example(dir: &std::path::Path) -> PathBuf {
    copy_tree(&root().join("examples/identify"), dir);
    let path = dir.join("study.toml");
    let study = std::fs::read_to_string(&path).unwrap();
    let study = format!("[identification]\nobjective = \"displacement\"\n\n{study}");
    std::fs::write(&path, study).unwrap();
    path
}

#[test]
fn identify_the_bundled_example_writes_json_and_a_report() {
    let dir = scratch("identify-example");
    let json = dir.join("result.json");
    let report = dir.join("report");
    let run = bumpsim(&[
        "identify",
        identify_example().to_str().unwrap(),
        "--starts",
        "8",
        "--json",
        json.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "3-DOF model",
            "m1",
            "kg",
            "N/mm",
            "Ns/mm",
            "95 % interval",
            "fit",
        ],
    );
    let result: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    assert_eq!(result["dof"], 3);
    for key in ["masses", "dampers", "springs"] {
        assert!(
            result[key]
                .as_array()
                .is_some_and(|a| a.iter().all(|v| v.as_f64().is_some_and(|x| x >= 1.0))),
            "{key}"
        );
    }
    assert!(result["objective"].as_f64().is_some_and(f64::is_finite));
    let cases = result["cases"].as_array().unwrap();
    assert_eq!(cases.len(), 3);
    for case in cases {
        assert!(case["fit_percent"].as_f64().unwrap() > 97.0, "{case}");
        assert!(case["sse"].as_f64().is_some() && case["name"].is_string());
    }
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert!(html.contains("<svg") && html.contains("bumpsim 0.1.0"));
    let predict = bumpsim(&[
        "predict",
        json.to_str().unwrap(),
        identify_example().to_str().unwrap(),
        "--case",
        "pole",
    ]);
    let out = text(&predict.stdout);
    assert!(
        predict.status.success() && out.starts_with("pole: fit"),
        "{out}{}",
        text(&predict.stderr)
    );
}

#[test]
fn the_identification_report_renders_in_headless_chromium() {
    let Some(browser) = chromium() else { return };
    let dir = scratch("report-browser");
    let report = dir.join("report");
    let run = bumpsim(&[
        "identify",
        identify_example().to_str().unwrap(),
        "--dof",
        "2,3",
        "--starts",
        "4",
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let page = format!(
        "file://{}",
        report.join("index.html").canonicalize().unwrap().display()
    );
    let headless = |profile: &str, extra: &[&str]| {
        Command::new(&browser)
            .args([
                "--headless",
                "--no-sandbox",
                "--disable-gpu",
                "--enable-logging=stderr",
                "--v=0",
            ])
            .arg(format!("--user-data-dir={}", dir.join(profile).display()))
            .args(extra)
            .arg(&page)
            .output()
            .unwrap()
    };
    let dom = headless("profile-dom", &["--dump-dom"]);
    let (html, log) = (text(&dom.stdout), text(&dom.stderr));
    assert!(
        html.contains("bumpsim identification") && html.trim_end().ends_with("</html>"),
        "page did not load"
    );
    let svg_files = std::fs::read_dir(&report)
        .unwrap()
        .flatten()
        .filter(|e| e.path().extension().is_some_and(|x| x == "svg"))
        .count();
    let figures: Vec<&str> = html.split("<figure class=\"plot\"").skip(1).collect();
    assert_eq!(figures.len(), svg_files, "every plot is in the page");
    for figure in &figures {
        assert!(
            figure.contains("<svg") && figure.contains("<polyline"),
            "a plot is empty"
        );
    }
    let console: Vec<&str> = log
        .lines()
        .filter(|l| l.contains("CONSOLE") || l.contains("Uncaught"))
        .collect();
    assert!(console.is_empty(), "console errors: {console:?}");
    let artefacts = Path::new(env!("CARGO_TARGET_TMPDIR")).join("artefacts");
    std::fs::create_dir_all(&artefacts).unwrap();
    let shot = artefacts.join("identification-report.png");
    let screenshot = headless(
        "profile-shot",
        &[
            "--window-size=1200,2400",
            &format!("--screenshot={}", shot.display()),
        ],
    );
    assert!(screenshot.status.success(), "{}", text(&screenshot.stderr));
    assert!(
        std::fs::metadata(&shot).unwrap().len() > 10_000,
        "screenshot kept at {}",
        shot.display()
    );
}

#[test]
fn nhtsa_two_dof_fit_and_the_dof_table() {
    let Some(_) = nhtsa_ev5() else { return };
    let dir = scratch("identify-nhtsa");
    let json = dir.join("result.json");
    let study = root().join("examples/nhtsa-10146/study.toml");
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--dof",
        "1..3",
        "--json",
        json.to_str().unwrap(),
        "--quiet",
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert!(
        stdout.contains(" DOF   objective m²     fit %          AIC          BIC       time"),
        "{stdout}"
    );
    let result: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let results = result["results"].as_array().unwrap();
    assert_eq!(results.len(), 3);
    // the 1-DOF car's mass (about 1882 kg) is 9 % off the test sheet's 1719 kg
    // (`mass` in the study): said, not silent (issue 44)
    let warnings = results[0]["warnings"].to_string();
    assert!(
        warnings.contains("off the test sheet's 1719.0 kg"),
        "{warnings}"
    );
    let two = &results[1];
    assert_eq!(two["dof"], 2);
    let fit = two["cases"][0]["fit_percent"].as_f64().unwrap();
    assert!(fit >= 96.0, "2-DOF fit {fit} %");
    // the recommended DOF is the one with the lowest BIC, in print and JSON
    let bic = |r: &serde_json::Value| r["bic"].as_f64().unwrap();
    let lowest = results
        .iter()
        .min_by(|a, b| bic(a).total_cmp(&bic(b)))
        .unwrap();
    assert_eq!(result["recommended_dof"], lowest["dof"]);
    let line = format!("recommended: {} DOF (lowest BIC)", lowest["dof"]);
    assert!(stdout.contains(&line), "{stdout}");
    // the recommended model's undetermined parameters are named under the
    // recommendation, not only among that model's warnings (issue 44)
    let recommended = results
        .iter()
        .find(|r| r["dof"] == result["recommended_dof"])
        .unwrap();
    let undetermined: Vec<&str> = recommended["uncertainty"]["names"]
        .as_array()
        .unwrap()
        .iter()
        .zip(recommended["uncertainty"]["determined"].as_array().unwrap())
        .filter(|(_, d)| d.as_bool() == Some(false))
        .map(|(n, _)| n.as_str().unwrap())
        .collect();
    assert!(!undetermined.is_empty(), "{stdout}");
    // none determined (2 DOF: k1 at its bound) is said plainly
    let fixed = recommended["uncertainty"]["fixed"].as_array().unwrap();
    let all = undetermined.len() == fixed.iter().filter(|f| f.as_bool() == Some(false)).count();
    let named = match all {
        true => format!(
            "data determine none of its parameters ({};",
            undetermined.join(", ")
        ),
        false => format!("data do not determine its {}", undetermined.join(", ")),
    };
    assert!(stdout.contains(&named), "{stdout}");
    // 3 masses are one too many for this plastic crash: a spring is
    // undetermined (k2 today; k1 at another 3-DOF optimum the same within
    // the noise) and the merged 2-mass model fits as well (docs/identify.md
    // quotes it)
    let reduction = &results[2]["reduction"];
    let pair = match reduction["parameter"].as_str() {
        Some("k1") => "m1 and m2",
        Some("k2") => "m2 and m3",
        other => panic!("reduction of {other:?}: {stdout}"),
    };
    assert!(reduction["relative_objective"].as_f64().unwrap() <= 0.01);
    let p_value = reduction["p_value"].as_f64().unwrap();
    assert!((0.0..=1.0).contains(&p_value), "F-test p = {p_value}");
    assert!(stdout.contains(&format!("{pair} move as one")), "{stdout}");
    // that spring is marked not determined in the JSON, by index and name
    let u = &results[2]["uncertainty"];
    let names = u["names"].as_array().unwrap();
    let spring = names
        .iter()
        .position(|n| n == &reduction["parameter"])
        .unwrap();
    assert_eq!(u["determined"][spring], false, "{u}");
    let direction = u["weakest_direction"].as_array().unwrap();
    assert!(
        !direction.is_empty() && direction[0]["share"].as_f64().unwrap() > 0.0,
        "{u}"
    );
    // the DOF table never gets worse with a further mass: continuation
    let objective = |r: &serde_json::Value| r["objective"].as_f64().unwrap();
    for pair in results.windows(2) {
        assert!(
            objective(&pair[1]) <= 1.01 * objective(&pair[0]),
            "{stdout}"
        );
    }
}

#[test]
fn identify_errors_exit_2() {
    let missing = bumpsim(&["identify", "no/such/study.toml"]);
    assert_eq!(missing.status.code(), Some(2));
    assert!(text(&missing.stderr).contains("no/such/study.toml"));
    let bad_dof = bumpsim(&[
        "identify",
        identify_example().to_str().unwrap(),
        "--dof",
        "0",
    ]);
    assert_user_error(&bad_dof, "--dof '0'");
    let unknown_case = bumpsim(&["predict", "no.json", identify_example().to_str().unwrap()]);
    assert_eq!(unknown_case.status.code(), Some(2));
}

#[test]
fn a_partial_identification_report_still_renders_and_says_what_failed() {
    let dir = scratch("partial-report");
    let example = root().join("examples/identify");
    let study = std::fs::read_to_string(example.join("study.toml"))
        .unwrap()
        .replace(
            "dof = 3",
            "dof = [1, 2]\nfixed = { k1 = 1e16 }   # no model can be simulated with this spring",
        )
        .replace("path = \"", &format!("path = \"{}/", example.display()));
    let path = dir.join("study.toml");
    std::fs::write(&path, study).unwrap();
    let report = dir.join("report");
    let run = bumpsim(&[
        "identify",
        path.to_str().unwrap(),
        "--starts",
        "2",
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ]);
    // a failed DOF does not end the sweep: the others are reported and
    // written, and the command then exits 2 saying which failed
    assert_eq!(run.status.code(), Some(2), "{}", text(&run.stderr));
    assert!(
        text(&run.stderr).contains("2-DOF model: all 2 starts failed")
            && text(&run.stderr).contains("1 of the 2 models failed (DOF 2"),
        "{}",
        text(&run.stderr)
    );
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert!(
        html.contains("1-DOF model")
            && html.contains("class=\"failure\"")
            && html.contains("all 2 starts failed")
    );
    let Some(browser) = chromium() else { return };
    let page = format!(
        "file://{}",
        report.join("index.html").canonicalize().unwrap().display()
    );
    let dom = Command::new(browser)
        .args(["--headless", "--no-sandbox", "--disable-gpu", "--dump-dom"])
        .arg(format!("--user-data-dir={}", dir.join("profile").display()))
        .arg(page)
        .output()
        .unwrap();
    let rendered = text(&dom.stdout);
    assert!(
        rendered.contains("Failed: 2-DOF model: all 2 starts failed")
            && rendered.trim_end().ends_with("</html>"),
        "the failure is shown in the rendered page"
    );
    // the failure is part of the answer, before any plot
    let result = rendered.split("<h2>Result</h2>").nth(1).unwrap_or("");
    let answer = result.split("<figure").next().unwrap_or("");
    assert!(
        answer.contains("Failed: 2-DOF model") && answer.contains("The 1-DOF model"),
        "the answer names the model and the failed order"
    );
}

// Channel selection notes reach `identify`'s output, JSON and report, and
// `predict`'s output; unknown parameter names in a study are user errors.

/// The values of an ISO-MME channel file of the bundled example, as written.
fn iso_mme_values(path: &Path) -> Vec<String> {
    std::fs::read_to_string(path)
        .unwrap()
        .lines()
        .filter(|l| !l.contains(':') && !l.trim().is_empty())
        .map(|l| l.trim().to_string())
        .collect()
}

/// The bundled example copied into `dir`, with the flat test also written
/// as an NHTSA EV5 test holding, besides its force and its two side-member
/// accelerometers, a third side-member accelerometer marked `No valid data`
/// and a fourth whose file is missing or unusable. The flat case reads its
/// accelerometers with the wildcard `1-AC-SIME*-XG`, which must leave both
/// out (same data as the bundled study, so the same result). The sample
/// interval is written `100.00000000000001` µs so that the EV5 time base is
/// bit-identical to the ISO-MME one (`100 × 1e-6` is one ulp below 1e-4,
/// which puts the sample at t = 0 a hair before 0 and into the pre-trigger
/// bias). Returns the study file.
fn example_with_an_invalid_channel(dir: &Path) -> PathBuf {
    copy_tree(&root().join("examples/identify"), dir);
    let flat = dir.join("FLAT/Channel");
    let row = |vehicle: &str, curve: usize, kind: &str, location: &str, unit: &str, note: &str| {
        format!(
            "{vehicle}|{curve}|{kind}|00|{location}|XG|SEC|{unit}|0|S|01/JAN/2020|1|1|0|-500|1599|100.00000000000001|AM|P|{note}\n"
        )
    };
    let mut ev5 = String::from("----- TEST -----\nV5|FLAT as EV5\n----- INSTRUMENTATION -----\n");
    ev5 += &row("P", 1, "LC", "IMPA", "N", "PENDULUM LOAD CELL X");
    ev5 += &row("1", 2, "AC", "SIMELE", "m/s**2", "SIDE MEMBER LEFT X");
    ev5 += &row("1", 3, "AC", "SIMERI", "m/s**2", "SIDE MEMBER RIGHT X");
    ev5 += &row("1", 4, "AC", "SIMEXX", "m/s**2", "No valid data");
    ev5 += &row("1", 5, "AC", "SIMEYY", "m/s**2", "SIDE MEMBER SPARE X");
    std::fs::write(dir.join("FLAT.EV5"), ev5).unwrap();
    let curves = [
        (1, "FLAT.001"),
        (2, "FLAT.002"),
        (3, "FLAT.003"),
        (4, "FLAT.001"),
    ];
    for (curve, source) in curves {
        let values = iso_mme_values(&flat.join(source));
        assert_eq!(values.len(), 2100);
        let lines: String = values
            .iter()
            .enumerate()
            .map(|(k, v)| format!("{}\t{v}\n", (k as f64 - 500.0) * 1e-4))
            .collect();
        std::fs::write(dir.join(format!("FLAT.{curve:03}")), lines).unwrap();
    }
    let study = std::fs::read_to_string(dir.join("study.toml")).unwrap();
    let flat_case = r#"force = { path = "FLAT/FLAT.mme", channel = "P0IMPA000000FOXP" }
acceleration = [
  { path = "FLAT/FLAT.mme", channel = "10SIMELE0000ACXP" },
  { path = "FLAT/FLAT.mme", channel = "10SIMERI0000ACXP" },
]"#;
    assert!(study.contains(flat_case));
    let ev5_case = r#"force = { path = "FLAT.EV5", channel = "P-LC-IMPA-XG" }
acceleration = [{ path = "FLAT.EV5", channel = "1-AC-SIME*-XG" }]"#;
    let path = dir.join("study-ev5.toml");
    std::fs::write(&path, study.replace(flat_case, ev5_case)).unwrap();
    path
}

fn identify_to(study: &Path, dir: &Path) -> (Output, serde_json::Value) {
    let json = dir.join("result.json");
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--starts",
        "4",
        "--json",
        json.to_str().unwrap(),
        "--report",
        dir.join("report").to_str().unwrap(),
        "--quiet",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let result = serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    (run, result)
}

const INVALID_NOTE: &str =
    "case 'flat': '1-AC-SIME*-XG': left out channel 4 (1-AC-SIMEXX-XG): marked invalid";
const ABSENT_NOTE: &str = "case 'flat': '1-AC-SIME*-XG': left out channel 5 (1-AC-SIMEYY-XG) whose file is missing or unusable";

#[test]
fn identify_reports_the_channels_a_wildcard_left_out() {
    let dir = scratch("loader-notes");
    let study = example_with_an_invalid_channel(&dir.join("study"));
    let (run, result) = identify_to(&study, &dir.join("ev5"));
    let stdout = text(&run.stdout);
    assert_contains(
        &stdout,
        &[
            &format!("note: {INVALID_NOTE}"),
            &format!("note: {ABSENT_NOTE}"),
        ],
    );
    assert_eq!(
        result["notes"],
        serde_json::json!([INVALID_NOTE, ABSENT_NOTE])
    );
    let html = std::fs::read_to_string(dir.join("ev5/report/index.html")).unwrap();
    assert_contains(
        &html,
        &[
            "Channel selection",
            "left out channel 4 (1-AC-SIMEXX-XG): marked invalid",
            "whose file is missing or unusable",
        ],
    );
    // the same data as the bundled study: the same model, and no notes there
    let (plain, bundled) = identify_to(&identify_example(), &dir.join("iso-mme"));
    assert!(!text(&plain.stdout).contains("note:"));
    assert_eq!(bundled["notes"], serde_json::json!([]));
    for key in ["objective", "fit_percent"] {
        let (a, b) = (
            result[key].as_f64().unwrap(),
            bundled[key].as_f64().unwrap(),
        );
        approx::assert_relative_eq!(a, b, max_relative = 1e-12);
    }
    // predict reads the cases through the same loader and says the same; the
    // wildcard's channels are the bundled flat test's (the invalid copy of
    // the force, had it been averaged in, would wreck the fit), so one
    // model predicts both to the printed digits
    let model = dir.join("iso-mme/result.json");
    let predict = |study: &Path| {
        let run = bumpsim(&[
            "predict",
            model.to_str().unwrap(),
            study.to_str().unwrap(),
            "--case",
            "flat",
        ]);
        assert!(run.status.success(), "{}", text(&run.stderr));
        text(&run.stdout)
    };
    let (ev5, iso_mme) = (predict(&study), predict(&identify_example()));
    assert_contains(&ev5, &[&format!("note: {INVALID_NOTE}"), "flat: fit"]);
    let fit = |out: &str| {
        out.lines()
            .find(|l| l.starts_with("flat: fit"))
            .map(str::to_string)
    };
    assert_eq!(fit(&ev5), fit(&iso_mme));
    assert!(
        fit(&iso_mme).is_some_and(|l| !l.contains("fit 0")),
        "{iso_mme}"
    );
}

#[test]
fn unknown_parameter_names_in_a_study_are_user_errors() {
    let dir = scratch("loader-names");
    let base = std::fs::read_to_string(identify_example()).unwrap();
    let valid = "m1, m2, m3, c1, c2, k1, k2";
    let cases = [
        (
            "fixed = { M1 = 30.0 }",
            "fixed: no parameter 'M1' in a 3-DOF model",
        ),
        (
            "bounds = { m9 = [1.0, 5.0] }",
            "bounds: no parameter 'm9' in a 3-DOF model",
        ),
    ];
    for (i, (entry, message)) in cases.iter().enumerate() {
        let copy = dir.join(format!("copy-{i}"));
        copy_tree(&root().join("examples/identify"), &copy);
        let path = copy.join("study.toml");
        std::fs::write(
            &path,
            base.replace("method = \"zoh\"", &format!("method = \"zoh\"\n{entry}")),
        )
        .unwrap();
        let run = bumpsim(&[
            "identify",
            path.to_str().unwrap(),
            "--starts",
            "1",
            "--quiet",
        ]);
        assert_user_error(&run, message);
        assert_user_error(&run, valid);
    }
    let copy = dir.join("start");
    copy_tree(&root().join("examples/identify"), &copy);
    let path = copy.join("study.toml");
    let start = "\n[model.start]\nmasses = [30.0, 250.0]\ndampers = [1e4]\nsprings = [1e6]\n";
    let text_with_start = base.replace("method = \"zoh\"\n", &format!("method = \"zoh\"\n{start}"));
    std::fs::write(&path, text_with_start).unwrap();
    let run = bumpsim(&[
        "identify",
        path.to_str().unwrap(),
        "--starts",
        "1",
        "--quiet",
    ]);
    assert_user_error(&run, "start: 2 masses, 1 dampers, 1 springs");
}

#[test]
fn identify_on_nhtsa_10146_names_the_invalid_barrier_cells_it_left_out() {
    let Some(_) = nhtsa_ev5() else { return };
    let study = root().join("examples/nhtsa-10146/study.toml");
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--dof",
        "1",
        "--starts",
        "1",
        "--quiet",
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "note: case 'ncap-57kph': '0-LC-*-XG': left out channel 347",
            "note: case 'ncap-57kph': '0-LC-*-XG': left out channel 500",
            "marked invalid",
        ],
    );
}

/// The bundled example's DOF table reaches every output: the JSON's
/// results, `failed` and `recommended_dof`, the report's table, starts lines
/// and recommendation (before, only the NHTSA run checked them, and it is
/// skipped without ../shared).
#[test]
fn a_dof_table_reaches_the_json_and_the_report() {
    let dir = scratch("dof-table-outputs");
    let (json, report) = (dir.join("table.json"), dir.join("report"));
    let run = bumpsim(&[
        "identify",
        root()
            .join("examples/identify/study.toml")
            .to_str()
            .unwrap(),
        "--dof",
        "1..3",
        "--starts",
        "4",
        "--json",
        json.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let value: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let results = value["results"].as_array().unwrap();
    assert_eq!(results.len(), 3);
    assert_eq!(value["failed"].as_array().map(Vec::len), Some(0));
    let recommended = value["recommended_dof"].as_u64().unwrap();
    // issue 39: the bundled car has 3 masses; in the displacement objective
    // the BIC with the effective sample size could not tell 2 from 3 (and
    // cross-validation decided); in the default velocity objective (issue
    // 44) the residuals carry more effective samples and the BIC decides
    assert_eq!(recommended, 3, "{}", value["model_choice"]);
    assert_eq!(value["model_choice"]["rule"], "bic");
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert_contains(
        &html,
        &[
            "AIC",
            "BIC",
            &format!("recommended: {recommended} DOF ("),
            "with correlated residuals: n_eff",
            "reached the best fit (F within the noise)",
            "3-DOF model",
        ],
    );
    let stdout = text(&run.stdout);
    assert_contains(&stdout, &["recommended:", "starts: 4 run"]);
}

/// Outputs that would lose something are refused: a JSON path inside the
/// report folder that the report's page would replace (and then neither is
/// written), a device (the rename replaced /dev/full by a regular file).
#[test]
fn outputs_that_would_replace_another_output_or_a_device_are_refused() {
    let dir = scratch("output-clash");
    let study = root().join("examples/identify/study.toml");
    let report = dir.join("report");
    let inside = report.join("index.html");
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--starts",
        "2",
        "--json",
        inside.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
        "--quiet",
    ]);
    assert_user_error(&run, "two outputs to one path");
    // issue 34: one command's outputs are all or nothing (the JSON was
    // written, then the report refused)
    assert!(
        !report.exists(),
        "the refused command left {}",
        inside.display()
    );
    let device = bumpsim(&["identify", study.to_str().unwrap(), "--json", "/dev/null"]);
    assert_user_error(&device, "not a regular file");
    use std::os::unix::fs::FileTypeExt;
    assert!(
        std::fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device()
    );
}

/// Issue 34: `--dof 50 --starts 1` ran for 8.5 minutes; a model order
/// beyond MAX_DOF is refused at once, naming `--dof` (or the study's key)
/// and why the limit is there.
#[test]
fn a_dof_beyond_the_limit_is_refused_at_once_with_the_reason() {
    let started = std::time::Instant::now();
    let study = identify_example();
    for dof in ["50", "9", "1..12"] {
        let run = bumpsim(&[
            "identify",
            study.to_str().unwrap(),
            "--dof",
            dof,
            "--starts",
            "1",
        ]);
        assert_user_error(&run, &format!("--dof '{dof}'"));
        assert_contains(
            &text(&run.stderr),
            &["from 1 to 8", "MAX_DOF", "12 masses minutes"],
        );
    }
    let dir = scratch("identify-dof-limit");
    let path = dir.join("study.toml");
    let text_of = std::fs::read_to_string(&study).unwrap();
    std::fs::write(&path, text_of.replace("dof = 3", "dof = 12")).unwrap();
    let run = bumpsim(&["identify", path.to_str().unwrap()]);
    assert_user_error(&run, "[model] dof = 12: expected 1 to 8 masses (MAX_DOF");
    assert!(started.elapsed().as_secs() < 10, "refused at once");
}

/// Issue 34: a reduced model whose objective is lower than the full
/// model's said it "fits within 0 %"; it now says it fits better, and by
/// how much. The bundled example's 8-mass fit from one start is such a
/// case (its 7-mass merge fits 0.8 % better).
#[test]
fn a_reduced_model_that_fits_better_says_so() {
    let dir = scratch("identify-reduction-wording");
    let json = dir.join("result.json");
    // the case was found in the thesis's displacement objective
    let study = displacement_example(&dir);
    let run = bumpsim(&[
        "identify",
        study.to_str().unwrap(),
        "--dof",
        "8",
        "--starts",
        "1",
        "--json",
        json.to_str().unwrap(),
        "--quiet",
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{stdout}{}", text(&run.stderr));
    assert!(!stdout.contains("within 0 %"), "{stdout}");
    let result: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let reduction = &result["reduction"];
    let relative = reduction["relative_objective"].as_f64().unwrap();
    let statement = reduction["statement"].as_str().unwrap();
    assert!(relative < 0.0, "the case this test is about: {statement}");
    assert!(
        statement.contains("fits better than the full model") && statement.contains("% lower"),
        "{statement}"
    );
    assert!(
        stdout.contains("fits better than the full model"),
        "{stdout}"
    );
}

/// Issue 34 (hostile pass 2026-11-26, finding 16): a study `window = [0.0,
/// inf]` and `cfc = 1e-308` (a 1.7e-308 Hz filter) were accepted by
/// `predict` and `identify`; both exit 2 naming the study file, the case
/// and the key.
#[test]
fn a_study_with_an_infinite_window_or_an_impossible_cfc_is_refused_by_key() {
    let dir = scratch("identify-study-window-cfc");
    let example = root().join("examples/identify");
    let absolute = format!("path = \"{}/", example.display());
    let text = std::fs::read_to_string(identify_example())
        .unwrap()
        .replace("path = \"", &absolute);
    let car = example.join("car-truth.toml");
    for (k, (old, new, needle)) in [
        (
            "window = \"contact\"",
            "window = [0.0, inf]",
            "[[case]] 'flat': window = [0, inf]: expected two finite times",
        ),
        (
            "cfc = 180",
            "cfc = 1e-308",
            "[[case]] 'flat': cfc = 1e-308: expected a class from",
        ),
    ]
    .into_iter()
    .enumerate()
    {
        assert!(text.contains(old), "{old}");
        let study = dir.join(format!("study-{k}.toml"));
        std::fs::write(&study, text.replacen(old, new, 1)).unwrap();
        let s = study.to_str().unwrap();
        for run in [
            bumpsim(&["predict", car.to_str().unwrap(), s, "--case", "flat"]),
            bumpsim(&["identify", s, "--quiet", "--starts", "1"]),
        ] {
            assert_user_error(&run, &format!("study-{k}.toml: "));
            assert_user_error(&run, needle);
        }
    }
}
