//! `bumpsim doe`: design, fit, predict, stiffness, reach and collect.

use std::path::PathBuf;

use crate::util::*;

fn doe_data(name: &str) -> PathBuf {
    root().join("tests/data/doe").join(name)
}

#[test]
fn doe_predict_reproduces_paper_c_table_4_and_flags_extrapolation() {
    let model = doe_data("paper-c-stage2.json");
    let run = bumpsim(&[
        "doe",
        "predict",
        model.to_str().unwrap(),
        "--at",
        "Kax=21747,Kbnd=20630,M=1681",
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "m1 = 1.000 kg",
            "m2 = 2230 kg",
            "c1 = 200.2 Ns/mm",
            "k1 = 3.920 N/mm",
        ],
    );
    let outside = bumpsim(&[
        "doe",
        "predict",
        model.to_str().unwrap(),
        "--at",
        "Kax=27000,Kbnd=20630,M=1681",
    ]);
    assert!(text(&outside.stdout).contains("warning: Kax = 27000 is outside the design region"));
    let missing = bumpsim(&[
        "doe",
        "predict",
        model.to_str().unwrap(),
        "--at",
        "Kax=23000",
    ]);
    assert_user_error(&missing, "no value for factor 'Kbnd'");
}

#[test]
fn doe_design_fit_report_and_saturated_model() {
    let dir = scratch("doe-fit");
    let design = dir.join("design.csv");
    let run = bumpsim(&[
        "doe",
        "design",
        "full",
        "--factors",
        "Kax:21210:25684,Kbnd:20217:23643,M:1375:1681",
        "--centre",
        "3",
        "-o",
        design.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    // responses from paper C's stage-2 coefficients plus a small deterministic disturbance
    let rows: Vec<Vec<f64>> = std::fs::read_to_string(&design)
        .unwrap()
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    let mut data = String::from("Kax [N/mm],Kbnd [N/mm],M [kg],m2 [kg],c1 [Ns/mm]\n");
    for (i, r) in rows.iter().enumerate() {
        let (z1, z2, z3) = (r[5], r[6], r[7]);
        let wobble = ((i * 7) as f64).sin();
        let m2 = 1987.0 - 52.38 * z1 + 16.63 * z2 + 215.63 * z3 + 3.0 * wobble;
        let c1 = 206.4 + 27.39 * z1 - 10.63 * z2 + 6.53 * z3 + 0.5 * wobble;
        data += &format!("{},{},{},{m2},{c1}\n", r[2], r[3], r[4]);
    }
    let csv = dir.join("data.csv");
    std::fs::write(&csv, data).unwrap();
    let json = dir.join("model.json");
    let report = dir.join("report");
    let fit = bumpsim(&[
        "doe",
        "fit",
        csv.to_str().unwrap(),
        "--factors",
        "Kax,Kbnd,M",
        "--responses",
        "m2,c1",
        "--json",
        json.to_str().unwrap(),
        "--report",
        report.to_str().unwrap(),
    ]);
    let stdout = text(&fit.stdout);
    assert!(fit.status.success(), "{stdout}{}", text(&fit.stderr));
    assert!(
        stdout.contains("m2 [kg]: R²") && stdout.contains("lack of fit"),
        "{stdout}"
    );
    let model: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let m2 = &model["responses"][0];
    for key in [
        "coefficients",
        "std_errors",
        "ci95",
        "r2",
        "r2_adjusted",
        "q2",
        "press",
    ] {
        assert!(!m2[key].is_null(), "{key} in {m2}");
    }
    let coefficient = m2["coefficients"]["M"].as_f64().unwrap();
    assert!((coefficient - 215.63).abs() < 5.0, "{coefficient}");
    assert!(
        std::fs::read_to_string(report.join("index.html"))
            .unwrap()
            .matches("<svg")
            .count()
            >= 6
    );
    let predicted = bumpsim(&[
        "doe",
        "predict",
        json.to_str().unwrap(),
        "--at",
        "Kax=23447,Kbnd=21930,M=1528",
    ]);
    assert!(
        text(&predicted.stdout).contains("95 % PI"),
        "{}",
        text(&predicted.stdout)
    );
    // a saturated model: 2^2 runs for intercept, two mains and the interaction
    let small = dir.join("small.csv");
    std::fs::write(&small, "A,B,y\n-1,-1,1\n1,-1,2\n-1,1,4\n1,1,7\n").unwrap();
    let saturated = bumpsim(&[
        "doe",
        "fit",
        small.to_str().unwrap(),
        "--factors",
        "A,B",
        "--responses",
        "y",
        "--interactions",
    ]);
    assert!(saturated.status.success(), "{}", text(&saturated.stderr));
    assert!(
        text(&saturated.stdout).contains("Q² undefined: the model is saturated"),
        "{}",
        text(&saturated.stdout)
    );
}

#[test]
fn doe_reach_stiffness_and_fraction_resolution() {
    let dir = scratch("doe-reach");
    let run = bumpsim(&[
        "doe",
        "reach",
        doe_data("paper-c-stage1.json").to_str().unwrap(),
        "--x",
        "Kax",
        "--y",
        "Kbnd",
        "--cell",
        "21210,25684,20217,23643",
        "--plot",
        dir.to_str().unwrap(),
    ]);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_eq!(
        stdout.matches(": reachable with coded").count(),
        4,
        "{stdout}"
    );
    // every vertex names its responses with their units (issue 35)
    let vertices: Vec<&str> = stdout
        .lines()
        .filter(|l| l.trim_start().starts_with("vertex"))
        .collect();
    assert!(
        !vertices.is_empty()
            && vertices
                .iter()
                .all(|l| l.contains("Kax = ") && l.matches(" N/mm").count() == 2),
        "{stdout}"
    );
    assert!(dir.join("reachable.svg").exists());
    let curve = dir.join("curve.csv");
    let mut csv = String::from("displacement [mm],force [kN]\n");
    for i in 0..=40 {
        let d = i as f64 * 0.5;
        csv += &format!("{d},{}\n", 2.5 * d + 0.01 * (i as f64).sin());
    }
    std::fs::write(&curve, csv).unwrap();
    let stiff = bumpsim(&["doe", "stiffness", curve.to_str().unwrap()]);
    assert!(
        text(&stiff.stdout).starts_with("stiffness 2500 N/mm")
            || text(&stiff.stdout).starts_with("stiffness 2499")
            || text(&stiff.stdout).starts_with("stiffness 2501"),
        "{}",
        text(&stiff.stdout)
    );
    let fraction = bumpsim(&[
        "doe",
        "design",
        "fractional",
        "--factors",
        "A:-1:1,B:-1:1,C:-1:1,D:-1:1,E:-1:1,F:-1:1,G:-1:1",
        "--generators",
        "D=AB,E=AC,F=BC,G=ABC",
        "-o",
        dir.join("f.csv").to_str().unwrap(),
    ]);
    let out = text(&fraction.stdout);
    assert!(
        out.contains("resolution 3") && out.contains("8 runs of 7 factors"),
        "{out}{}",
        text(&fraction.stderr)
    );
}

#[test]
fn doe_collect_appends_identified_parameters_to_the_design() {
    let dir = scratch("doe-collect");
    let design = dir.join("design.csv");
    std::fs::write(&design, "Kax [N/mm],M [kg]\n21210,1375\n25684,1681\n").unwrap();
    let mut results = Vec::new();
    for (i, m2) in [1800.0, 2100.0].iter().enumerate() {
        let path = dir.join(format!("r{i}.json"));
        std::fs::write(&path, format!("{{\"dof\": 2, \"masses\": [1.0, {m2}], \"dampers\": [2.0e5], \"springs\": [4.0e6], \"objective\": 1e-4}}")).unwrap();
        results.push(path.to_str().unwrap().to_string());
    }
    let out = dir.join("data.csv");
    let run = bumpsim(&[
        "doe",
        "collect",
        design.to_str().unwrap(),
        "--results",
        &results.join(","),
        "-o",
        out.to_str().unwrap(),
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    let csv = std::fs::read_to_string(&out).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "Kax [N/mm],M [kg],m1 [kg],m2 [kg],c1 [Ns/m],k1 [N/m]"
    );
    assert_eq!(
        csv.lines().nth(2).unwrap(),
        "25684,1681,1,2100,200000,4000000"
    );
    let short = bumpsim(&[
        "doe",
        "collect",
        design.to_str().unwrap(),
        "--results",
        &results[0],
        "-o",
        out.to_str().unwrap(),
    ]);
    assert_user_error(&short, "1 results for 2 design runs");
}

/// Writes a 2² design's data with replicates (`y` from A and B) as
/// `name` in `dir`; with `extreme`, the responses are ±`extreme` instead.
fn replicated_data(dir: &std::path::Path, name: &str, extreme: Option<f64>) -> PathBuf {
    let mut data = String::from("A [mm],B [mm],y [N]\n");
    for (i, (a, b)) in [(0, 0), (1, 0), (0, 1), (1, 1)].into_iter().enumerate() {
        for r in 0..2 {
            let sign = if (i + r) % 2 == 0 { 1.0 } else { -1.0 };
            let y = extreme.map_or(
                1.0 + 2.0 * f64::from(a) - f64::from(b) + 0.1 * r as f64,
                |e| sign * e,
            );
            data += &format!("{a},{b},{y:e}\n");
        }
    }
    let path = dir.join(name);
    std::fs::write(&path, data).unwrap();
    path
}

/// Issue 34: DOE values that were ignored or mixed up (duplicate or empty
/// names, infinite levels, generators and runs a design does not use), and
/// numbers beyond the largest float (a statrs panic, an allocation abort,
/// an `inf` prediction) are refused with exit 2, and nothing is written.
#[test]
fn doe_refuses_what_it_would_ignore_mix_up_or_overflow() {
    let dir = scratch("doe-hostile");
    let out = dir.join("d.csv");
    let o = out.to_str().unwrap();
    let two = "A:0:1,B:0:1";
    for (args, needle) in [
        (
            &["full", "--factors", "A:0:1,A:0:1"][..],
            "'A' is given twice",
        ),
        (&["full", "--factors", ":0:1,B:0:1"], "an empty name"),
        (&["full", "--factors", "A:0:inf,B:0:1"], "finite LOW < HIGH"),
        (
            &["full", "--factors", "A:-inf:1,B:0:1"],
            "finite LOW < HIGH",
        ),
        (
            &["full", "--factors", "A:-1.7e308:1.7e308"],
            "HIGH - LOW finite",
        ),
        (
            &[
                "fractional",
                "--factors",
                "A:0:1,B:0:1,C:0:1",
                "--generators",
                "=AB",
            ],
            "generator '=AB'",
        ),
        (
            &["fractional", "--factors", "A:0:1,B:0:1,C:0:1"],
            "needs generators",
        ),
        (
            &["full", "--factors", two, "--generators", "C=AB"],
            "fractional design only",
        ),
        (&["full", "--factors", two, "--runs", "5"], "--runs"),
        (&["lhs", "--factors", two, "--centre", "2"], "centre points"),
        (
            &["full", "--factors", two, "--centre", "1000000000"],
            "MAX_CENTRE",
        ),
    ] {
        let mut all = vec!["doe", "design"];
        all.extend_from_slice(args);
        all.extend(["-o", o]);
        assert_user_error(&bumpsim(&all), needle);
        assert!(!out.exists(), "{args:?}");
    }
    let data = replicated_data(&dir, "data.csv", None);
    let huge = replicated_data(&dir, "huge.csv", Some(1e308));
    let twice = dir.join("twice.csv");
    std::fs::write(&twice, "A [mm],A [mm],y [N]\n0,0,1\n1,1,2\n2,2,3\n").unwrap();
    let json = dir.join("model.json");
    let (d, j) = (data.to_str().unwrap(), json.to_str().unwrap());
    for (file, factors, extra, needle) in [
        (
            d,
            "A,B",
            &["--responses", "y,y"][..],
            "response 'y' is given twice",
        ),
        (d, "A,A", &["--responses", "y"], "factor 'A' is given twice"),
        (
            d,
            "A,B",
            &["--responses", "A"],
            "as a factor and as a response",
        ),
        (
            d,
            "A,B",
            &["--responses", "y", "--low", "0"],
            "1 low levels for 2 factors",
        ),
        (
            huge.to_str().unwrap(),
            "A,B",
            &["--responses", "y"],
            "rescale it",
        ),
        (
            twice.to_str().unwrap(),
            "A",
            &["--responses", "y"],
            "named twice",
        ),
    ] {
        let mut all = vec!["doe", "fit", file, "--factors", factors, "--json", j];
        all.extend_from_slice(extra);
        assert_user_error(&bumpsim(&all), needle);
        assert!(!json.exists(), "{extra:?}");
    }
    // one command's outputs are all or nothing: the JSON is not left behind
    let report = dir.join("rep");
    let inside = report.join("index.html");
    let fit = ["doe", "fit", d, "--factors", "A,B", "--responses", "y"];
    let both = [&fit[..], &["--json", inside.to_str().unwrap()]].concat();
    let both = [&both[..], &["--report", report.to_str().unwrap()]].concat();
    assert_user_error(&bumpsim(&both), "two outputs to one path");
    assert!(
        !report.exists(),
        "the refused command left {}",
        report.display()
    );
    let run = bumpsim(&[&fit[..], &["--json", j]].concat());
    assert!(run.status.success(), "{}", text(&run.stderr));
    for (at, needle) in [
        ("A=1e308,B=0", "beyond the largest number"),
        ("A=0.5,A=0.5,B=0", "'A' is given twice"),
    ] {
        assert_user_error(&bumpsim(&["doe", "predict", j, "--at", at]), needle);
    }
    let stage1 = doe_data("paper-c-stage1.json");
    let cell = ["--cell", "nan,1,0,1", "--samples", "10"];
    let reach = [
        &[
            "doe",
            "reach",
            stage1.to_str().unwrap(),
            "--x",
            "Kax",
            "--y",
            "Kbnd",
        ][..],
        &cell,
    ]
    .concat();
    assert_user_error(&bumpsim(&reach), "expected finite bounds");
}

/// Issue 39 item 4: `doe fit --se` fits identified parameters with the
/// identification's standard errors (τ² by REML, weights 1/(τ² + s²)); the
/// model file carries the weighting and `doe predict` reads it.
#[test]
fn doe_fit_with_standard_errors_includes_the_identification() {
    let dir = scratch("doe-se");
    let data = root().join("examples/doe/identified.csv");
    let (weighted, plain) = (dir.join("weighted.json"), dir.join("plain.json"));
    let fit = |extra: &[&str], json: &std::path::Path| {
        let mut all = vec!["doe", "fit", data.to_str().unwrap(), "--factors", "Kax,M"];
        all.extend(["--responses", "k1,c1", "--json", json.to_str().unwrap()]);
        all.extend_from_slice(extra);
        bumpsim(&all)
    };
    let run = fit(&["--se", "k1,c1=c1.se"], &weighted);
    let stdout = text(&run.stdout);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_contains(
        &stdout,
        &[
            "k1 [N/m]: weighted by its standard errors (k1.se, 24992 .. 78447 N/m): τ (REML)",
            "c1 [Ns/m]: weighted by its standard errors (c1.se",
            "OLS std. error",
            "residual heterogeneity Q_E",
            "note: τ² = 0",
        ],
    );
    assert!(fit(&[], &plain).status.success());
    let read = |p: &std::path::Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
    };
    let (w, o) = (read(&weighted), read(&plain));
    let c1 = &w["responses"][1];
    assert_eq!(c1["weighted"]["method"], "REML");
    assert_eq!(c1["weighted"]["tau2"], 0.0);
    // c1's runs scatter within their SEs: its intervals widen beyond OLS's
    let span = |r: &serde_json::Value, t: &str| {
        r["ci95"][t][1].as_f64().unwrap() - r["ci95"][t][0].as_f64().unwrap()
    };
    for term in ["intercept", "Kax", "M"] {
        assert!(span(c1, term) > span(&o["responses"][1], term), "{term}");
    }
    let run = bumpsim(&[
        "doe",
        "predict",
        weighted.to_str().unwrap(),
        "--at",
        "Kax=23447,M=1528",
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert_contains(
        &text(&run.stdout),
        &["c1 = 206684 Ns/m; 95 % CI 202732 .. 210636"],
    );
}

/// Hostile standard errors: NaN, negative, beyond a finite square, zero
/// beside positive ones, a missing column, a column for a response that is
/// not fitted or does not exist, a factor as SE column, and the model file
/// over the data: exit 2 naming what is wrong, nothing written.
#[test]
fn doe_fit_refuses_bad_standard_errors() {
    let dir = scratch("doe-se-hostile");
    let table = |name: &str, cell: &str| {
        let mut text = String::from("A [mm],y [N],y.se [N]\n");
        for (i, a) in [0, 1, 2, 0, 1, 2].iter().enumerate() {
            let se = if i == 1 {
                cell.to_string()
            } else {
                "0.5".into()
            };
            text += &format!("{a},{},{se}\n", 1.0 + f64::from(*a) + 0.1 * i as f64);
        }
        let path = dir.join(name);
        std::fs::write(&path, text).unwrap();
        path
    };
    let json = dir.join("model.json");
    let j = json.to_str().unwrap();
    let cases: [(std::path::PathBuf, &[&str], &str); 9] = [
        (
            table("nan.csv", "nan"),
            &["--se", "y"],
            "nan.csv:3: column 'y.se' holds 'nan'",
        ),
        (
            table("negative.csv", "-0.5"),
            &["--se", "y"],
            "response 'y' with standard errors 'y.se': standard error -0.5 in data row 2",
        ),
        (
            table("huge.csv", "1e200"),
            &["--se", "y"],
            "whose square (a variance)",
        ),
        (
            table("zero.csv", "0"),
            &["--se", "y"],
            "standard error 0 in data row 2",
        ),
        (
            table("ok.csv", "0.5"),
            &["--se", "y=y_se"],
            "no column 'y_se'",
        ),
        (
            table("ok.csv", "0.5"),
            &["--se", "k1"],
            "'k1' is not a fitted response (y)",
        ),
        (
            table("ok.csv", "0.5"),
            &["--responses", "y.se", "--se", "y"],
            "'y' is not a fitted response (y.se)",
        ),
        (
            table("ok.csv", "0.5"),
            &["--se", "y=A"],
            "'A' is a factor or a response",
        ),
        (
            table("ok.csv", "0.5"),
            &["--se", "=y.se"],
            "expected RESPONSE=COLUMN",
        ),
    ];
    for (file, extra, needle) in cases {
        let mut all = vec!["doe", "fit", file.to_str().unwrap(), "--factors", "A"];
        if !extra.contains(&"--responses") {
            all.extend(["--responses", "y"]);
        }
        all.extend(["--json", j]);
        all.extend_from_slice(extra);
        assert_user_error(&bumpsim(&all), needle);
        assert!(!json.exists(), "{extra:?}");
    }
    // the model file over the data it reads
    let data = table("ok.csv", "0.5");
    let d = data.to_str().unwrap();
    let run = bumpsim(&[
        "doe",
        "fit",
        d,
        "--factors",
        "A",
        "--responses",
        "y",
        "--se",
        "y",
        "--json",
        d,
    ]);
    assert_user_error(&run, "would overwrite the input");
    assert!(
        std::fs::read_to_string(&data)
            .unwrap()
            .starts_with("A [mm],y [N],y.se [N]")
    );
}

/// `doe collect` appends `NAME.se` for each parameter whose standard error
/// every result carries (a fixed m1 has none), and `doe fit --se` reads it.
#[test]
fn doe_collect_appends_standard_errors_that_doe_fit_reads() {
    let dir = scratch("doe-collect-se");
    let design = dir.join("design.csv");
    let runs = [(21210, 1375), (25684, 1375), (21210, 1681), (25684, 1681)];
    let mut table = String::from("Kax [N/mm],M [kg]\n");
    let mut results = Vec::new();
    for (i, (kax, m)) in runs.iter().enumerate() {
        table += &format!("{kax},{m}\n");
        let k1 = 3.9e6 + 20.0 * f64::from(*kax - 23447) - 300.0 * f64::from(*m - 1528);
        let k1 = k1 + [1.0e4, -2.0e4, -1.5e4, 2.5e4][i];
        let path = dir.join(format!("r{i}.json"));
        let json = format!(
            r#"{{"dof": 2, "masses": [1.0, {m}], "dampers": [2.0e5], "springs": [{k1}],
            "uncertainty": {{"names": ["m1", "m2", "c1", "k1"],
            "standard_errors": [null, 15.0, 900.0, {}]}}}}"#,
            2.0e4 + 5.0e3 * i as f64
        );
        std::fs::write(&path, json).unwrap();
        results.push(path.to_str().unwrap().to_string());
    }
    std::fs::write(&design, table).unwrap();
    let out = dir.join("data.csv");
    let (d, o) = (design.to_str().unwrap(), out.to_str().unwrap());
    let run = bumpsim(&[
        "doe",
        "collect",
        d,
        "--results",
        &results.join(","),
        "-o",
        o,
    ]);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(text(&run.stdout).contains("standard errors of m2, c1, k1 (columns NAME.se"));
    let csv = std::fs::read_to_string(&out).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "Kax [N/mm],M [kg],m1 [kg],m2 [kg],c1 [Ns/m],k1 [N/m],m2.se [kg],c1.se [Ns/m],k1.se [N/m]"
    );
    assert!(csv.lines().nth(4).unwrap().ends_with(",15,900,35000"));
    let fit = [
        "doe",
        "fit",
        o,
        "--factors",
        "Kax,M",
        "--responses",
        "k1",
        "--se",
        "k1",
    ];
    let run = bumpsim(&fit);
    assert!(run.status.success(), "{}", text(&run.stderr));
    assert!(
        text(&run.stdout)
            .contains("k1 [N/m]: weighted by its standard errors (k1.se, 20000 .. 35000 N/m)")
    );
}

/// Issue 34 (hostile pass 2026-11-26, findings 6 and 16): `doe reach` with
/// a coefficient of 1e308 printed `vertex Y = inf N` / `NaN N` with exit 0,
/// and `--x Y --y Y` (a response against itself) was accepted; both are
/// refused with exit 2, naming the model file and the coefficient or flags.
#[test]
fn doe_reach_refuses_overflowing_coefficients_and_one_response_twice() {
    let dir = scratch("doe-reach-hostile");
    let stage1 = doe_data("paper-c-stage1.json");
    let source = std::fs::read_to_string(&stage1).unwrap();
    let huge = dir.join("huge.json");
    let edited = source.replacen("\"t1\": 3290.69", "\"t1\": 1e308", 1);
    assert_ne!(edited, source);
    std::fs::write(&huge, edited).unwrap();
    let s = stage1.to_str().unwrap();
    for (model, x, y, needle) in [
        (
            huge.to_str().unwrap(),
            "Kax",
            "Kbnd",
            "coefficient of 't1' = 1e308",
        ),
        (huge.to_str().unwrap(), "Kbnd", "Kax", "huge.json"),
        (s, "Kax", "Kax", "--x and --y both name 'Kax'"),
    ] {
        let run = bumpsim(&["doe", "reach", model, "--x", x, "--y", y, "--samples", "10"]);
        assert_user_error(&run, needle);
        assert!(!text(&run.stdout).contains("inf"), "{}", text(&run.stdout));
    }
}

/// Issue 34 (hostile pass 2026-11-26, finding 26): `doe fit`'s coefficient
/// columns, `doe predict`'s intervals and `doe reach --cell`'s corners and
/// distances printed numbers without units; each now carries the
/// response's unit.
#[test]
fn doe_tables_intervals_and_corners_carry_their_units() {
    let dir = scratch("doe-units");
    let json = dir.join("identified.json");
    let data = root().join("examples/doe/identified.csv");
    let fit = bumpsim(&[
        "doe",
        "fit",
        data.to_str().unwrap(),
        "--factors",
        "Kax,M",
        "--responses",
        "k1",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(fit.status.success(), "{}", text(&fit.stderr));
    assert_contains(
        &text(&fit.stdout),
        &[
            "coefficient [N/m]",
            "std. error [N/m]",
            "95 % interval [N/m]",
        ],
    );
    let at = [
        "doe",
        "predict",
        json.to_str().unwrap(),
        "--at",
        "Kax=25000,M=1400",
    ];
    let predict = text(&bumpsim(&at).stdout);
    let ci = predict
        .lines()
        .find(|l| l.contains("95 % CI"))
        .unwrap_or("");
    assert!(
        ci.contains(" N/m; 95 % PI") && ci.ends_with(" N/m"),
        "{predict}"
    );
    let stage1 = doe_data("paper-c-stage1.json");
    let reach = bumpsim(&[
        "doe",
        "reach",
        stage1.to_str().unwrap(),
        "--x",
        "Kax",
        "--y",
        "Kbnd",
        "--cell",
        "20000,25684,20217,23643",
        "--samples",
        "10",
    ]);
    let out = text(&reach.stdout);
    assert!(reach.status.success(), "{}", text(&reach.stderr));
    let missed = out
        .lines()
        .find(|l| l.contains("UNREACHABLE"))
        .unwrap_or("");
    assert!(
        missed.starts_with("corner (20000 N/mm, 23643 N/mm)") && missed.ends_with(" N/mm"),
        "{out}"
    );
}
