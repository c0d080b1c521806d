//! Issue 44 (h3, item 3): the result of a 1-D identification does not
//! depend on the scale of a given `noise`: the residuals are divided by
//! it, so every objective is multiplied by 1/σ², and the search must end
//! at the same parameters whatever σ is (a given 1e-8 m/s, inside the
//! accepted range, stopped the search at its start). With
//! [`bumpsim_ident::Settings::solver_for`] (LM's λ starting dimensionless)
//! it does not; that is not yet the default (docs/identify.md).

use bumpsim_estimate::observer::Silent;
use bumpsim_ident::{Study, identify};
use std::path::Path;

fn example(noise: f64) -> Study {
    let mut study = Study::read(
        &Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/identify/study.toml"),
    )
    .unwrap();
    for case in &mut study.case {
        case.noise = Some(noise);
    }
    study
}

#[test]
fn the_parameters_do_not_depend_on_the_noise_scale() {
    let fit = |noise: f64| {
        let study = example(noise);
        let cases = study.cases(3).unwrap();
        let mut settings = study.settings(3).unwrap();
        settings.starts = 4;
        // the scaled start is not yet the identification's default (see
        // docs/identify.md "Iterations"): asked for here
        settings.solver = settings.solver_for(&cases);
        let result = identify(&cases, &settings, &Silent).unwrap();
        eprintln!(
            "noise {noise:e}: {:?} objective {:e} fit {} % stop {:?} iterations {} warnings {:?}",
            result.model.parameters(),
            result.objective,
            result.fit_percent,
            result.stop,
            result.iterations,
            result.warnings
        );
        result.model.parameters()
    };
    let (coarse, fine) = (fit(1e-3), fit(1e-8));
    for (a, b) in coarse.iter().zip(&fine) {
        assert!((a / b - 1.0).abs() < 1e-6, "{coarse:?} against {fine:?}");
    }
}
