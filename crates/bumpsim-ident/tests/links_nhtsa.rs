//! Acceptance of issue 46 on NHTSA test 10146 (2018 Camry, 57 km/h into
//! the load-cell barrier): the chain with yielding links fits the
//! crossmember's displacement ≥ 99 % (the linear chain stops at 96.52 %),
//! and the identified car alone, run into a rigid barrier at the test's
//! speed, predicts the summed barrier force ≥ 90 % and the crossmember's
//! ΔV within 3 %; the plastic sets print with their intervals.
//!
//! The data are read from `../shared` beside the repository or from
//! `$BUMPSIM_SHARED`; the test skips with a message when they are absent.

use bumpsim_core::chain::Drive;
use bumpsim_estimate::observer::Silent;
use bumpsim_ident::links::{Layout, LinkSettings, identify, text};
use bumpsim_ident::{Settings, Study, identify as identify_linear};
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// The example study with its data paths pointing at the shared folder.
fn study() -> Option<Study> {
    let shared = std::env::var_os("BUMPSIM_SHARED").map_or(root().join("../shared"), PathBuf::from);
    let ev5 = shared.join("data/nhtsa-10146/v10146.EV5");
    if !ev5.exists() {
        eprintln!(
            "SKIPPED: {} is absent (NHTSA test 10146 is read from ../shared or $BUMPSIM_SHARED)",
            ev5.display()
        );
        return None;
    }
    let text = std::fs::read_to_string(root().join("examples/nhtsa-10146/study.toml")).unwrap();
    let text = text.replace("../../../shared", shared.to_str().unwrap());
    let dir = std::env::temp_dir().join(format!("bumpsim-links-nhtsa-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("study.toml");
    std::fs::write(&path, text).unwrap();
    Some(Study::read(&path).unwrap())
}

#[test]
fn nhtsa_10146_with_yielding_links_fits_and_predicts_the_barrier() {
    let Some(study) = study() else { return };
    let dof: usize = std::env::var("LINKS_DOF")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(2);
    let cases = study.cases(dof).unwrap();
    let case = &cases[0];
    let linear = identify_linear(
        &cases,
        &Settings {
            starts: 8,
            ..study.settings(dof).unwrap()
        },
        &|| {},
    )
    .unwrap();
    let peak = case.force.iter().fold(0.0_f64, |m, f| m.max(f.abs()));
    let layout = Layout { dof };
    let start = layout.start_from(&linear.model, 0.5 * peak);
    let starts = std::env::var("LINKS_STARTS")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(16);
    let settings = LinkSettings::new(dof, starts, start);
    let found = identify(&cases, &settings, &Silent).unwrap();
    println!(
        "linear fit {:.2} %\n{}",
        linear.cases[0].fit_percent,
        text(&found)
    );
    let fit = found.fits[0].1;
    let verdict = bumpsim_ident::links::verdict::compare(&linear, &found);
    println!("{}", verdict.reasons.join("\n"));
    // forward: the identified car alone into a rigid wall at the test's speed
    let samples = case.force.len();
    let drive = Drive::Barrier {
        speed: case.initial_velocity,
        step: case.step,
        samples,
    };
    let _ = drive;
    let run = found
        .forward(case.initial_velocity, case.step, samples)
        .unwrap();
    let (a, b) = case.window;
    let force_fit = bumpsim_estimate::fit::percent(&run.force[a..=b], &case.force[a..=b]);
    let last = dof - 1;
    let h = case.step;
    let measured_dv = (case.measured[b] - case.measured[b - 1]) / h - case.initial_velocity;
    let predicted_dv = run.velocity[last][b] - case.initial_velocity;
    let dv_error = (predicted_dv - measured_dv).abs() / measured_dv.abs();
    println!(
        "forward into a rigid wall at {:.2} m/s: force fit {force_fit:.2} %, crossmember ΔV {predicted_dv:.3} m/s (measured {measured_dv:.3} m/s, {:.2} % off)",
        case.initial_velocity,
        100.0 * dv_error
    );
    assert!(fit >= 99.0, "fit {fit} %");
    assert!(force_fit >= 90.0, "forward force fit {force_fit} %");
    assert!(dv_error <= 0.03, "ΔV error {dv_error}");
    assert!(found.plastic_sets.iter().all(|s| s.ci95.is_some()));
}
