//! Issue 44, item 5: the held-out predictions' 90 % predictive bands on
//! the independent series of tests/peers/planar_yaw_rate.py (a third model
//! family; two sill accelerometers and a yaw-rate sensor; trained on a
//! flat pendulum, a narrow centred face and a 10° wall, held out a 40 %
//! offset 10° wall and the narrow face 0.4 m off centre). The bands are
//! linearised from the identification's covariance plus the training
//! residuals' RMS ([`bumpsim_planar::bands`]); the share of measured
//! samples inside each is printed, and the held-out yaw's is asserted.

use bumpsim_estimate::band::TOO_WIDE;
use bumpsim_planar::bands::{Bands, attach};
use bumpsim_planar::forward::forward;
use bumpsim_planar::identify::{PlanarIdentification, Prediction, identify, predict};
use bumpsim_planar::study::PlanarStudy;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;

/// The series in a folder of its own (the yaw-rate test writes the same
/// series concurrently into another).
fn series() -> Option<PathBuf> {
    if !bumpsim_peers::python_available("numpy") {
        return None;
    }
    let out = Path::new(env!("CARGO_TARGET_TMPDIR")).join("planar-yaw-rate-bands");
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/planar_yaw_rate.py");
    bumpsim_peers::generated(&script, &out, &[], "study.toml");
    Some(out)
}

#[test]
fn the_held_out_yaw_lies_inside_its_predictive_band() {
    let Some(dir) = series() else { return };
    let study = PlanarStudy::read(&dir.join("study.toml")).unwrap();
    let result = identify(&study.cases, &study.setup, &|| {}).unwrap();
    let mut held: Vec<_> = study
        .validation
        .iter()
        .map(|c| predict(&result.car, c).unwrap())
        .collect();
    let mut ahead: Vec<_> = study
        .validation
        .iter()
        .filter(|c| c.striker.is_some())
        .map(|c| forward(&result.car, c).unwrap())
        .collect();
    let bands = attach(
        &result,
        &study.cases,
        (&study.validation, &mut held),
        &mut ahead,
    )
    .unwrap();
    eprint!("{}", bands.lines());
    for p in &held {
        eprintln!(
            "{}: x {:.2} %, yaw {:.2} %",
            p.fit.name, p.fit.fit_x, p.fit.fit_yaw
        );
    }
    let judged = |case: &str, channel: &str| {
        bands
            .judged
            .iter()
            .find(|j| j.case == case && j.channel == channel && j.prediction == "replay")
            .unwrap()
            .clone()
    };
    // every held-out replay and forward channel carries its band
    assert!(
        held.iter()
            .all(|p| p.x_band.is_some() && p.yaw_band.is_some())
    );
    assert!(
        ahead
            .iter()
            .flat_map(|f| &f.channels)
            .all(|c| c.band.is_some())
    );
    // measured (2026-11-29, release): before the priors and with one AR(1)
    // inflation the held-out yaw lay inside its band at 17 % (OFFSET40) and
    // 20 % (NARROW-OFFSET) of the samples; with the priors, σ² τ intervals
    // and the training replays' relative model error in the band's noise,
    // on the generator before its crash-box couple was fixed, at 79.7 % and
    // 31.8 %; on the fixed generator, with this default study (linear side
    // members, the start's tyres), at 100 % and 40.4 % (the face's yaw fit
    // 12.6 %: a model error of the start's relaxed tyres,
    // tests/planar/truth_start.rs). The 80 % holds with the
    // yaw-rate acceptance's set-up (the test below); here a band the
    // measurement leaves (below the level less `MISSED`) must be said in
    // words
    let statements = bands.statements();
    for case in ["OFFSET40", "NARROW-OFFSET"] {
        let yaw = judged(case, "yaw");
        assert!(
            yaw.inside_percent >= 80.0
                || !yaw.missed()
                || statements
                    .iter()
                    .any(|s| s
                        .starts_with(&format!("{case}'s measured yaw lies inside its 90 % band"))),
            "{yaw:?} {statements:?}"
        );
    }
    // the yaw inertia is propagated, or named as left out
    assert!(
        bands
            .parameters
            .iter()
            .chain(&bands.left_out)
            .any(|n| n == "body.yaw_inertia"),
        "{bands:?}"
    );
}

/// The series' folder, its documented study, the identification and the
/// seconds it took.
pub(super) type Run = (PathBuf, PlanarStudy, PlanarIdentification, f64);

/// The series' documented study (`study-doc.toml`: 16 starts, the sheet's
/// mass, yielding side members, the bumper fitted, the tyres' law estimated
/// by default since the training carries a yaw-rate sensor) and its
/// identification, made once per test binary: the acceptance of
/// tests/planar/yaw_rate.rs scores the same run (a debug build takes
/// 3.5 min for one identification on a loaded machine). `None` without
/// numpy.
pub(super) fn acceptance_run() -> Option<&'static Run> {
    static RUN: OnceLock<Option<Run>> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = series()?;
        let study = PlanarStudy::read(&dir.join("study-doc.toml")).unwrap();
        let clock = std::time::Instant::now();
        let result = study.identified(&|| {}).unwrap();
        Some((dir, study, result, clock.elapsed().as_secs_f64()))
    })
    .as_ref()
}

/// The held-out replays of `result` with their bands, judged.
fn held_out_bands(study: &PlanarStudy, result: &PlanarIdentification) -> (Bands, Vec<Prediction>) {
    let mut held: Vec<_> = study
        .validation
        .iter()
        .map(|c| predict(&result.car, c).unwrap())
        .collect();
    let bands = attach(
        result,
        &study.cases,
        (&study.validation, &mut held),
        &mut [],
    )
    .unwrap();
    eprint!("{}", bands.lines());
    for p in &held {
        eprintln!(
            "{}: x {:.2} %, yaw {:.2} % (window {:?} s)",
            p.fit.name, p.fit.fit_x, p.fit.fit_yaw, p.fit.window
        );
        dump(p);
    }
    (bands, held)
}

/// With `BUMPSIM_BANDS_DUMP=<folder>`, writes the held-out yaw, its model
/// and band as `<case>.csv` there (for a plot).
fn dump(p: &Prediction) {
    let (Ok(folder), Some(band)) = (std::env::var("BUMPSIM_BANDS_DUMP"), &p.yaw_band) else {
        return;
    };
    let mut text = String::from("time_s,measured_rad,model_rad,low_rad,high_rad\n");
    for k in 0..p.time.len() {
        text += &format!(
            "{},{},{},{},{}\n",
            p.time[k], p.yaw[1][k], p.yaw[0][k], band.low[k], band.high[k]
        );
    }
    std::fs::create_dir_all(&folder).unwrap();
    std::fs::write(Path::new(&folder).join(format!("{}.csv", p.fit.name)), text).unwrap();
}

/// Issue 44's acceptance: the measured held-out yaw inside its 90 % band
/// at ≥ 80 % of the samples, with the yaw-rate acceptance's set-up
/// ([`acceptance`]), every held-out replay carrying its band and no band
/// uselessly wide (the whole band's mean half-width within a quarter of the
/// yaw's range).
///
/// Measured (2026-11-29, release, the documented study with the sills in
/// velocity, their biases as nuisances and the joint final stage, w13-h4):
/// OFFSET40's yaw inside at 100 % of the samples, the parameters' band's
/// half-width 0.7 % of the yaw's range (1.1 % in all); NARROW-OFFSET's at
/// 87.3 %, 3.8 % (4.1 %). Before (displacement, the bumper fitted after the
/// car): OFFSET40 100 %, 1.9 % (1.3 % from the parameters);
/// NARROW-OFFSET 100 %, 6.7 % (6.3 %). The relaxation length, at its 1 cm floor (1 mm since w27), has no standard
/// error and is named as left out. Before the bands made their cars through
/// the identification's own unknowns, a linked chain's perturbed spring
/// was no valid car and no band was made at all (the yielding side
/// members'). With the default study (linear side members, C_α and σ
/// fixed): OFFSET40 100 %, NARROW-OFFSET 40.4 % (its yaw fit 12.6 %: a
/// model error, said as a missed band by the test above).
#[test]
fn the_held_out_yaw_lies_inside_its_band_at_80_percent_of_the_samples() {
    let Some((_, study, result, _)) = acceptance_run() else {
        return;
    };
    let (bands, held) = held_out_bands(study, result);
    eprintln!("propagated: {:?}", bands.parameters);
    assert!(
        held.iter()
            .all(|p| p.x_band.is_some() && p.yaw_band.is_some()),
        "{bands:?}"
    );
    for case in ["OFFSET40", "NARROW-OFFSET"] {
        let yaw = bands
            .judged
            .iter()
            .find(|j| j.case == case && j.channel == "yaw")
            .unwrap();
        eprintln!("{yaw:?}");
        assert!(yaw.inside_percent >= 80.0, "{yaw:?}");
        assert!(
            yaw.trusted && yaw.total_width_percent <= 100.0 * TOO_WIDE,
            "{yaw:?}"
        );
    }
    // the side members' yield is propagated with the rest of the car
    for name in ["body.yaw_inertia", "left.yield_force[0]"] {
        assert!(bands.parameters.iter().any(|n| n == name), "{bands:?}");
    }
}

/// The held-out yaw's 90 % band of `result` judged on each held-out case
/// of `study` (OFFSET40 and the off-centre case): issue 44's "the measured held-out
/// yaw inside its 90 % band at ≥ 80 % of samples", for the varied cars.
pub(super) fn held_out_yaw(
    study: &PlanarStudy,
    result: &PlanarIdentification,
) -> [bumpsim_planar::bands::Judged; 2] {
    let (bands, _) = held_out_bands(study, result);
    let off_centre = super::defaults::off_centre(study);
    ["OFFSET40", off_centre.as_str()].map(|case| {
        bands
            .judged
            .iter()
            .find(|j| j.case == case && j.channel == "yaw" && j.prediction == "replay")
            .unwrap()
            .clone()
    })
}
