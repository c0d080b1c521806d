//! The hostile pass of round 5 over issue 44's inputs: what still ran with
//! exit 0. A test sheet's `[model] mass = 1e300` (1-D or planar) was taken
//! and its prior dropped without a word (the centre beyond the search's
//! range), a planar study's `spread = 1e300` drew starts that failed, and
//! a prior's spread of 1e-6 printed as "± 0.000", a bias window's end of
//! 1e300 s was quoted with its 301 digits. Each now exits 2 naming the key
//! and its limit, or prints its digits.

use super::inputs::refused;
use super::{examples, run_in, stderr};

#[test]
fn a_sheet_mass_beyond_any_car_is_refused_in_both_studies() {
    let dir = examples("ranges-mass");
    let study = std::fs::read_to_string(dir.join("ex/identify/study.toml")).unwrap();
    let sheet = "mass = \"1450 kg\"";
    assert!(study.contains(sheet));
    for (mass, quoted) in [
        ("1e300", "1e300"),
        ("\"1e300 kg\"", "\"1e300 kg\""),
        ("1e7", "10000000"),
        ("\"0.1 g\"", "\"0.1 g\""),
    ] {
        std::fs::write(
            dir.join("ex/identify/h.toml"),
            study.replacen(sheet, &format!("mass = {mass}"), 1),
        )
        .unwrap();
        let needle = format!("h.toml: [model] mass = {quoted}: expected a positive mass");
        refused(
            &dir,
            &["identify", "ex/identify/h.toml", "--quiet"],
            &needle,
        );
        refused(
            &dir,
            &["identify", "ex/identify/h.toml"],
            "from 0.001 to 1e6 kg",
        );
    }
    // a bias window of 1e300 s was quoted with its 301 digits
    std::fs::write(
        dir.join("ex/identify/h.toml"),
        study.replacen("cfc = 180\n", "cfc = 180\nbias = [0, 1e300]\n", 1),
    )
    .unwrap();
    refused(
        &dir,
        &["identify", "ex/identify/h.toml", "--quiet"],
        "step 'bias': the bias window [0, 1e300] s reaches beyond the record",
    );
    let (out, _) = run_in(
        &dir,
        &["synth", "ex/planar/identify/series.toml", "-o", "ps"],
    );
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let planar = std::fs::read_to_string(dir.join("ps/study.toml")).unwrap();
    let sheet = "mass = 1265.0";
    assert!(planar.contains(sheet));
    std::fs::write(
        dir.join("ps/h.toml"),
        planar.replacen(sheet, "mass = 1e300", 1),
    )
    .unwrap();
    refused(
        &dir,
        &["identify", "ps/h.toml", "--quiet"],
        "h.toml: [model] mass = 1e300: expected a positive mass in kg or text such as \"1350 kg\", from 0.001 to 1e6 kg",
    );
    // the random starts' factor: 1e300 drew starts of 0 and ∞ (exit 0)
    for spread in ["1e300", "1e7", "inf", "1.0"] {
        std::fs::write(
            dir.join("ps/h.toml"),
            planar.replacen("starts = 8", &format!("starts = 8\nspread = {spread}"), 1),
        )
        .unwrap();
        refused(&dir, &["identify", "ps/h.toml", "--quiet"], "spread = ");
        refused(
            &dir,
            &["identify", "ps/h.toml", "--quiet"],
            "a factor above 1, at most 1e6 (MAX_SPREAD)",
        );
    }
}

#[test]
fn a_prior_s_spread_is_refused_beyond_its_range_and_printed_with_its_digits() {
    let dir = examples("ranges-spread");
    let study = std::fs::read_to_string(dir.join("ex/identify/study.toml")).unwrap();
    let with = |prior: &str| {
        std::fs::write(
            dir.join("ex/identify/h.toml"),
            format!("{study}\n[priors]\n{prior}\n"),
        )
        .unwrap();
    };
    for (spread, shown) in [("1e300", "1e300"), ("1e-7", "1e-7"), ("inf", "inf")] {
        with(&format!("k1 = {{ spread = {spread} }}"));
        let needle = match spread {
            "inf" => "[priors] k1: spread = inf: must be finite and positive".to_string(),
            _ => format!("[priors] k1: spread = {shown}: must be from 1e-6 to 1e2"),
        };
        refused(
            &dir,
            &["identify", "ex/identify/h.toml", "--quiet"],
            &needle,
        );
    }
    // the tightest spread taken prints its digits, not "± 0.000"
    with("total_mass = { spread = 1e-6 }");
    let (out, _) = run_in(
        &dir,
        &["identify", "ex/identify/h.toml", "--quiet", "--starts", "2"],
    );
    let printed = String::from_utf8_lossy(&out.stdout).into_owned();
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    assert!(
        printed.contains("prior total_mass: 1450 kg ± 1.00e-6 (ln) (the study's [priors])"),
        "{printed}"
    );
    assert!(!printed.contains("± 0.000"), "{printed}");
}

/// A links car (docs/formats.md): a negative progressive limit was refused
/// as a `limit_force` below a negative product (the wrong key), and a
/// hardening of 1e300 was quoted with its 301 digits.
#[test]
fn a_links_car_s_limit_and_hardening_are_named() {
    let dir = examples("ranges-links");
    let car = std::fs::read_to_string(dir.join("ex/links/car.toml")).unwrap();
    for (old, new, needle) in [
        (
            "limit = \"300 mm\"",
            "limit = \"-300 mm\"",
            "h.toml: link 1: limit: -0.3 m: must be positive",
        ),
        (
            "hardening = 0.05",
            "hardening = 1e300",
            "h.toml: front link: hardening = 1e300 : the hardening ratio must lie in 0..=1",
        ),
    ] {
        assert!(car.contains(old), "{old}");
        std::fs::write(dir.join("h.toml"), car.replacen(old, new, 1)).unwrap();
        let args = [
            "impact",
            "--car",
            "h.toml",
            "--barrier",
            "--speed",
            "15 km/h",
        ];
        refused(&dir, &args, needle);
    }
}
