//! The small things a careful user trips over (issues 44 and 46, round 5),
//! beside `inputs.rs`: what last round's hostile pass found and left. A fit
//! `window = [0, 1e300]` was cut to the end of the record while a bias
//! window past it was refused; `objective = "Displacement"` and
//! `"displacement "` were taken for `"displacement"`; a yaw-rate sensor's
//! `body` was dropped without a word; a `[priors]` entry that names no
//! parameter was refused after the search, without the study file; a
//! `synth` series of 2000 tests ran past 120 s. Each now exits 2 naming the
//! file, the key and what is expected.

use super::inputs::{chain, planar_series, refused};
use super::{examples, run_in, stderr};

/// A fit window reaching past the record is refused as a bias window is,
/// with the record's span; one within it still fits. A planar study has no
/// fit window (its replay runs over the force's contact): `window` is an
/// unknown key there.
#[test]
fn a_fit_window_past_the_record_is_refused_with_the_record_s_span() {
    let dir = examples("careful-window");
    let quick = ["--starts", "1", "--quiet"];
    for (window, given) in [
        ("[0, 1e300]", "[0, 1e300]"),
        ("[0.0, 0.3]", "[0, 0.3]"),
        ("[-1.0, 0.1]", "[-1, 0.1]"),
    ] {
        let study = chain(&dir, |t| {
            t.replacen("window = \"contact\"", &format!("window = {window}"), 1)
        });
        // the bundled tests: 50 ms of pre-trigger, 160 ms after contact at 10 kHz
        let needle = format!(
            "h.toml: [[case]] 'flat': window = {given}: expected times within the record of the case's channels, -0.05000 s to 0.1599 s (0.2099 s long"
        );
        refused(&dir, &[&["identify", study][..], &quick].concat(), &needle);
    }
    let study = chain(&dir, |t| {
        t.replacen("window = \"contact\"", "window = [0.0, 0.1599]", 1)
    });
    let (out, _) = run_in(&dir, &[&["identify", study][..], &quick].concat());
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let text = planar_series(&dir);
    let with_window = text.replacen("cfc = 180\n", "cfc = 180\nwindow = [0.0, 1e300]\n", 1);
    std::fs::write(dir.join("ps/w.toml"), with_window).unwrap();
    refused(
        &dir,
        &["identify", "ps/w.toml", "--quiet"],
        "unknown field `window`",
    );
}

/// The objective's names are exact, in chain and planar studies alike.
#[test]
fn an_objective_is_one_of_its_names_exactly() {
    let dir = examples("careful-objective");
    let planar = planar_series(&dir);
    for name in ["Displacement", "displacement ", " velocity", "ACCELERATION"] {
        let table = format!("\n[identification]\nobjective = {name:?}\n");
        let study = chain(&dir, |t| format!("{t}{table}"));
        let needle = format!(
            "h.toml: [identification] objective {name:?}: expected \"displacement\", \"velocity\" or \"acceleration\", written exactly (lower case, no spaces)"
        );
        refused(&dir, &["identify", study, "--starts", "1"], &needle);
        std::fs::write(dir.join("ps/o.toml"), format!("{planar}{table}")).unwrap();
        let needle = needle.replace("h.toml", "ps/o.toml");
        refused(&dir, &["identify", "ps/o.toml", "--quiet"], &needle);
    }
}

/// A place given to a yaw-rate sensor is refused, not dropped.
#[test]
fn a_yaw_rate_channel_takes_no_place() {
    let dir = examples("careful-yaw");
    let study = planar_series(&dir);
    let yaw = "{ path = \"FLAT/FLAT.mme\", channel = \"10VEHC0000CGAVZP\" }";
    assert!(study.contains(yaw));
    let placed = yaw.replace(" }", ", body = [0.6, 0.7] }");
    std::fs::write(dir.join("ps/y.toml"), study.replacen(yaw, &placed, 1)).unwrap();
    refused(
        &dir,
        &["identify", "ps/y.toml", "--quiet"],
        "a yaw-rate channel takes no `body`: a yaw-rate sensor reads the body's rotation, the same everywhere",
    );
}

/// A `[priors]` entry that names no estimated parameter is refused naming
/// the study file and the section, before the search.
#[test]
fn an_unknown_prior_names_the_study_file() {
    let dir = examples("careful-priors");
    let quick = ["--starts", "1", "--quiet"];
    for (prior, why) in [
        ("m5", "no such estimated parameter"),
        ("foo", "no such estimated parameter"),
        (
            "k2",
            "fixed ([model] fixed): a fixed parameter is not estimated and takes no prior",
        ),
    ] {
        let study = chain(&dir, |t| {
            let t = t.replacen(
                "method = \"zoh\"",
                "method = \"zoh\"\nfixed = { k2 = 6e5 }",
                1,
            );
            format!("{t}\n[priors]\n{prior} = {{ value = 100.0, spread = 0.3 }}\n")
        });
        let needle = format!(
            "h.toml: [priors] {prior}: {why}; known for the 3-DOF model: total_mass, m1, m2, m3, c1, c2, k1"
        );
        refused(&dir, &[&["identify", study][..], &quick].concat(), &needle);
    }
    let planar = planar_series(&dir);
    let study = format!("{planar}\n[priors]\nbody.foo = {{ value = 100.0, spread = 0.3 }}\n");
    std::fs::write(dir.join("ps/p.toml"), study).unwrap();
    refused(
        &dir,
        &["identify", "ps/p.toml", "--starts", "1", "--quiet"],
        "planar identification of ps/p.toml: [priors] body.foo: no such estimated car parameter",
    );
}

/// A series of more than `MAX_TESTS` tests is refused before any is made,
/// for each model's series, as a campaign beyond its `MAX_POINTS` is.
#[test]
fn a_series_of_too_many_tests_is_refused_before_it_runs() {
    let dir = examples("careful-synth");
    let chain_series = std::fs::read_to_string(dir.join("ex/identify/series.toml")).unwrap();
    let head = "[[head]]\nname = \"T{k}\"\nbumper = \"bumper-flat.toml\"\nmass = 1450.0\nspeed = \"6 km/h\"\n";
    let planar = std::fs::read_to_string(dir.join("ex/planar/identify/series.toml")).unwrap();
    let links = std::fs::read_to_string(dir.join("ex/links/series.toml")).unwrap();
    let test = |text: &str| {
        let at = text.find("[[test]]").unwrap();
        let end = text[at + 1..]
            .find("[[test]]")
            .map_or(text.len(), |e| e + at + 1);
        text[at..end].to_string()
    };
    for (series, table, one, name) in [
        (
            &chain_series,
            "[[head]]",
            head.to_string(),
            "ex/identify/many.toml",
        ),
        (
            &planar,
            "[[test]]",
            test(&planar),
            "ex/planar/identify/many.toml",
        ),
        (&links, "[[test]]", test(&links), "ex/links/many.toml"),
    ] {
        let kept = &series[..series.find(table).unwrap()];
        let name_line = one
            .lines()
            .find(|l| l.starts_with("name"))
            .unwrap()
            .to_string();
        let many: String = (0..1001)
            .map(|k| one.replacen(&name_line, &format!("name = \"T{k}\""), 1) + "\n")
            .collect();
        std::fs::write(dir.join(name), format!("{kept}{many}")).unwrap();
        let needle =
            format!("{name}: {table}: 1001 tests: a series holds at most 1000 (limit MAX_TESTS");
        refused(&dir, &["synth", name, "-o", "out"], &needle);
        assert!(!dir.join("out").exists());
    }
}
