//! Refusals that name the flag and the value as the user gave it (the
//! hostile pass's panic and unclear items): exit 2, the flag, its value.

use super::{examples, run_in, stderr, user_error};

#[test]
fn centre_points_beyond_the_limit_name_centre() {
    let dir = examples("flags-centre");
    for kind in ["ccc", "ccf", "full"] {
        user_error(
            &dir,
            &[
                "doe",
                "design",
                kind,
                "--factors",
                "A:0:1",
                "--centre",
                "99999999999",
                "-o",
                "d.csv",
            ],
            "--centre 99999999999: 99999999999 centre points: at most 1000000",
        );
    }
    assert!(!dir.join("d.csv").exists());
}

/// `planar` and `impact` (a planar car) with one face or set-up option.
fn planar_refused(dir: &std::path::Path, option: &[&str], needle: &str) {
    let car = "ex/verdict/car.toml";
    for command in ["planar", "impact"] {
        let mut args = vec![command, "--car", car, "--speed", "2"];
        if command == "impact"
            && !option
                .iter()
                .any(|o| o.starts_with("--gap") || o.starts_with("--duration"))
        {
            args.push("--barrier");
        } else if command == "impact" {
            continue; // the set-up options are planar's
        }
        args.extend_from_slice(option);
        user_error(dir, &args, needle);
    }
}

#[test]
fn face_options_are_named_in_their_own_units() {
    let dir = examples("flags-face");
    let percent = "in percent of the bumper width, must lie in 0 < overlap ≤ 100";
    for overlap in ["250", "101", "-10"] {
        planar_refused(
            &dir,
            &["--overlap", overlap],
            &format!("--overlap {overlap}: the overlap, {percent}"),
        );
    }
    for angle in ["nan", "1e308", "95"] {
        let shown = if angle == "nan" { "NaN" } else { angle };
        planar_refused(
            &dir,
            &["--angle", angle],
            &format!("--angle {shown}: the face angle, in degrees, must lie within ±80"),
        );
    }
    planar_refused(
        &dir,
        &["--pole", "-0.1"],
        "--pole '-0.1' (the pole's diameter",
    );
    planar_refused(
        &dir,
        &["--pole", "0.2", "--pole-offset", "1e9"],
        "--pole-offset '1e9'",
    );
}

#[test]
fn set_up_options_are_named() {
    let dir = examples("flags-set-up");
    planar_refused(&dir, &["--gap", "-50 mm"], "--gap '-50 mm'");
    planar_refused(&dir, &["--gap", "1e9"], "--gap '1e9'");
    planar_refused(&dir, &["--duration", "1e9"], "--duration '1e9'");
}

#[test]
fn mass_reduction_names_the_input_that_overflows() {
    let dir = examples("flags-reduction");
    let bumper = "ex/impact/bumper-a.toml";
    let base = ["mass-reduction", "--bumper", bumper];
    let with = |extra: &[&'static str]| {
        let mut args = base.to_vec();
        args.extend_from_slice(extra);
        args
    };
    // a mass beyond MASS_RANGE is refused before the impact runs
    user_error(&dir, &with(&["--m2", "1e308"]), "--m2: m2 = 1e308 kg");
    user_error(&dir, &with(&["--k", "1e308"]), "--k 1e308 ");
    std::fs::write(
        dir.join("b-huge.toml"),
        "ramp = 1e308\nplateau = 1e308\nunloading = 1e308\n",
    )
    .unwrap();
    user_error(
        &dir,
        &["mass-reduction", "--bumper", "b-huge.toml"],
        "with --bumper b-huge.toml",
    );
}

#[test]
fn stiffness_names_the_range_and_the_file() {
    let dir = examples("flags-stiffness");
    let rows: String = (0..20).map(|i| format!("{i},{}\n", 3 * i)).collect();
    std::fs::write(dir.join("curve.csv"), format!("d [mm],f [kN]\n{rows}")).unwrap();
    std::fs::write(dir.join("one.csv"), "d [mm],f [kN]\n1,3\n").unwrap();
    let fit = |extra: &[&'static str]| {
        let mut args = vec!["doe", "stiffness", "curve.csv"];
        args.extend_from_slice(extra);
        args
    };
    for range in ["5,1", "nan,1", "1,1"] {
        user_error(&dir, &fit(&["--range", range]), "curve.csv --range ");
        user_error(&dir, &fit(&["--range", range]), "expected finite D0 < D1");
    }
    user_error(
        &dir,
        &fit(&["--range", "100,200"]),
        "curve.csv --range 100,200: stiffness: 0 points in the fit range",
    );
    user_error(
        &dir,
        &["doe", "stiffness", "one.csv"],
        "one.csv (fit range: 10–90 % of the peak force): stiffness: 0 points",
    );
}

#[test]
fn a_trim_that_keeps_one_sample_names_trim() {
    let dir = examples("flags-trim");
    let export = |trim: &'static str| {
        [
            "signal",
            "export",
            "ex/identify/FLAT",
            "-c",
            "P0IMPA000000FOXP",
            "-o",
            "o.csv",
            "--trim",
            trim,
        ]
    };
    user_error(&dir, &export("0.01,0.01"), "--trim 0.01,0.01: ");
    user_error(&dir, &export("0.01,0.01"), "keeps one sample");
    user_error(&dir, &export("0.02,0.01"), "--trim 0.02,0.01: ");
    assert!(!dir.join("o.csv").exists());
}

#[test]
fn a_zero_output_interval_names_output_every() {
    let dir = examples("flags-output-every");
    let force = "ex/simulate/pendulum-force.csv";
    let car = "ex/simulate/car-3dof.toml";
    let needle = "--output-every 0: the output interval must be at least 1 increment";
    let calculix = ["export", "calculix", car, "-o", "d.inp", "--force", force];
    user_error(
        &dir,
        &[&calculix[..], &["--output-every", "0"]].concat(),
        needle,
    );
    let planar = ["export", "planar", "ex/planar/saloon.toml", "-o", "p.inp"];
    let zero = ["--solver", "calculix", "--output-every", "0"];
    user_error(&dir, &[&planar[..], &zero].concat(), needle);
    user_error(
        &dir,
        &[&planar[..], &zero, &["--force", force]].concat(),
        needle,
    );
    assert!(!dir.join("d.inp").exists() && !dir.join("p.inp").exists());
}

#[test]
fn a_force_beyond_the_model_names_the_force_file() {
    let dir = examples("flags-force");
    let rows: String = (0..6)
        .map(|i| format!("{},1e300\n", i as f64 * 1e-4))
        .collect();
    std::fs::write(
        dir.join("f-huge.csv"),
        format!("time [s],force [kN]\n{rows}"),
    )
    .unwrap();
    user_error(
        &dir,
        &[
            "simulate",
            "--car",
            "ex/simulate/car-3dof.toml",
            "--force",
            "f-huge.csv",
        ],
        "with the force of f-huge.csv (peak 1e303 N)",
    );
}

#[test]
fn an_overflowing_prediction_names_the_factor_and_its_value() {
    let dir = examples("flags-predict");
    let factors = r#"{ "name": "Kax", "low": 20000, "high": 26000 }, { "name": "M", "low": 1300, "high": 1700 }"#;
    let response =
        r#"{ "name": "y", "coefficients": { "intercept": 1.0, "Kax^2": 2.0, "Kax*M": 1.0 } }"#;
    let json = format!(r#"{{ "factors": [{factors}], "responses": [{response}] }}"#);
    std::fs::write(dir.join("m.json"), json).unwrap();
    let model = "m.json";
    let at = "Kax=1e308,M=1400";
    user_error(
        &dir,
        &["doe", "predict", model, "--at", at],
        &format!("--at {at}: "),
    );
    user_error(
        &dir,
        &["doe", "predict", model, "--at", at],
        "Kax = 1e308 lies too far outside the design region",
    );
}

#[test]
fn a_deck_name_that_is_a_path_names_the_campaign_file_and_key() {
    let dir = examples("flags-campaign");
    let spec = dir.join("ex/campaign/campaign.toml");
    let text = std::fs::read_to_string(&spec).unwrap();
    let text = text.replacen("deck = \"deck.inp\"", "deck = \"../../../evil.txt\"", 1);
    assert!(text.contains("evil.txt"));
    std::fs::write(
        &spec,
        text.replacen("\"ccx\", \"-i\", \"deck\"", "\"true\"", 1),
    )
    .unwrap();
    user_error(
        &dir,
        &["campaign", "init", "ex/campaign/campaign.toml", "-o", "c"],
        "ex/campaign/campaign.toml: template.deck: ",
    );
    assert!(!dir.join("c").exists() && !dir.join("evil.txt").exists());
}

#[test]
fn a_hyphen_quantity_reaches_the_check_of_its_option() {
    let dir = examples("flags-hyphen");
    let car = "ex/simulate/car-3dof.toml";
    let bumper = "ex/impact/bumper-a.toml";
    let args = ["impact", "--car", car, "--bumper", bumper, "--barrier"];
    user_error(
        &dir,
        &[&args[..], &["--speed", "-3 m/s"]].concat(),
        "--speed '-3 m/s'",
    );
    let planar = ["planar", "--car", "ex/verdict/car.toml", "--speed", "2"];
    user_error(
        &dir,
        &[&planar[..], &["--pole", "-10 cm"]].concat(),
        "--pole '-10 cm'",
    );
}

/// A path option does not take the next flag as its value: with hyphen
/// values allowed everywhere, `--json --quiet` wrote a file named `--quiet`.
#[test]
fn a_path_option_never_takes_a_flag_as_its_file() {
    let dir = examples("path-hyphen");
    let (out, _) = run_in(
        &dir,
        &[
            "impact",
            "--car",
            "ex/identify/car-truth.toml",
            "--bumper",
            "ex/impact/bumper-a.toml",
            "--barrier",
            "--speed",
            "2",
            "--json",
            "--report",
        ],
    );
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(!dir.join("--report").exists(), "a file named --report");
}
