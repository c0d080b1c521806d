//! Identification with yielding links on an independent generator of
//! another family (issue 46): `tests/peers/crush_bar.py`, an
//! elastic-plastic bar of ten elements with distributed mass between a
//! bumper and the body, into a rigid wall at 10 m/s (numpy only). Its
//! bar is quasi-statically one bilinear link of known stiffness, yield
//! force, hardening and unloading slope; the 2-mass chain identified from
//! the wall force and the noisy body displacement must hold each of them
//! within its 95 % interval.

use bumpsim_estimate::observer::Silent;
use bumpsim_ident::LoadCase;
use bumpsim_ident::links::{LinkSettings, identify, text};
use std::path::{Path, PathBuf};

fn series() -> Option<PathBuf> {
    if !bumpsim_peers::present(
        bumpsim_peers::python_available("numpy"),
        "python3 with numpy",
    ) {
        return None;
    }
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("crush-bar");
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/crush_bar.py");
    bumpsim_peers::generated(&script, &out, &["1"], "truth.json");
    Some(out)
}

#[test]
fn a_crushing_bar_gives_its_yield_force_and_stiffnesses_within_their_intervals() {
    let Some(dir) = series() else { return };
    let truth: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("truth.json")).unwrap()).unwrap();
    let text_csv = std::fs::read_to_string(dir.join("crush.csv")).unwrap();
    let rows: Vec<Vec<f64>> = text_csv
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let step = rows[1][0] - rows[0][0];
    let n = rows.len();
    let case = LoadCase {
        name: "crush-bar".into(),
        start: 0.0,
        step,
        force: rows.iter().map(|r| r[1]).collect(),
        measured: rows.iter().map(|r| r[2]).collect(),
        output_dof: 2,
        initial_velocity: truth["speed"].as_f64().unwrap(),
        window: (0, n - 1),
        compare: Default::default(),
    };
    let total = truth["total_mass"].as_f64().unwrap();
    let peak = case.force.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    // a start that knows nothing of the bar: a tenth of the mass in front,
    // a soft link yielding at a fifth of the peak force
    let start = vec![0.1 * total, 0.9 * total, 100.0, 3e5, 0.2 * peak, 0.3, 3.0];
    let settings = LinkSettings::new(2, 12, start);
    let found = identify(std::slice::from_ref(&case), &settings, &Silent).unwrap();
    println!("{}", text(&found));
    assert!(found.fits[0].1 > 99.0, "fit {} %", found.fits[0].1);
    let u = &found.uncertainty;
    let checks = [
        ("k1", 2, truth["stiffness"].as_f64().unwrap()),
        ("Fy1", 3, truth["yield_force"].as_f64().unwrap()),
    ];
    for (name, i, value) in checks {
        let [lo, hi] = u.ci95[i].unwrap_or_else(|| panic!("{name} has no interval"));
        println!(
            "{name}: truth {value:.4e}, estimate {:.4e}, 95 % [{lo:.4e}, {hi:.4e}]",
            found.theta[i]
        );
        assert!(
            lo <= value && value <= hi,
            "{name}: truth {value} outside [{lo}, {hi}]"
        );
    }
}
