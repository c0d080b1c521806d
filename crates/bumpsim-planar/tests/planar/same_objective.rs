//! Issue 44, item 4's other half: the best the documented study's search
//! reaches is at least as low as the one reached from the true parameters
//! of the independent series of tests/peers/planar_yaw_rate.py, both in
//! the search's own objective.
//!
//! The runs of tests/planar/truth_start.rs start at the truth with the
//! study's priors centred there too (a chain prior's centre is the start
//! car's, and so is `body.mass`'s): another objective. Here the run from
//! the truth keeps every prior centre and spread of the search's (pinned
//! as `[priors]` settings over the study's own), so the two differ only in
//! where they start and in the noise σ each ends at. The joint final
//! stage (`[model] joint`) is left out of both: it polishes each best
//! under a weight of its own start's misfit, so neither would end at a
//! minimum of the objective compared; what is compared is the search.
//! Both are valued at the search's σ, `J = F + σ² Σ zᵢ²` (F the data
//! objective, zᵢ each prior's distance in its standard deviations,
//! [`bumpsim_estimate::prior::Priored`]), and at the truth run's σ too.
//!
//! The search may end above the truth's run by less than one noise
//! variance σ²: that is one unit of χ², a difference that moves a
//! parameter by one standard deviation, below what the data tell apart.

use super::truth_start::yielding_truth_of;
use bumpsim_planar::bumper_fit::identified;
use bumpsim_planar::identify::{PlanarIdentification, PriorSetting};

/// The objective of `run` at the priors' noise `sigma`: F + σ² Σ z².
fn valued(run: &PlanarIdentification, sigma: f64) -> f64 {
    run.objective + sigma * sigma * run.priors.iter().map(|m| m.z * m.z).sum::<f64>()
}

/// The study's `[priors]` settings with the search's priors pinned over
/// them (centres and spreads, whatever the start car; a study's ratio
/// priors and removals stay as the study states them).
fn pinned(study: &[PriorSetting], run: &PlanarIdentification) -> Vec<PriorSetting> {
    let mut out: Vec<PriorSetting> = study.to_vec();
    for m in run.priors.iter().filter(|m| !m.ratio) {
        let setting = PriorSetting {
            name: m.name.clone(),
            removed: false,
            value: Some(m.centre),
            spread: Some(m.spread),
        };
        match out.iter_mut().find(|s| s.name == m.name) {
            Some(s) => *s = setting,
            None => out.push(setting),
        }
    }
    out
}

/// Measured (release, `BUMPSIM_SEEDS=0,…,19`), J at the search's σ: see
/// docs/planar.md, "The search against a run from the truth, in one
/// objective (w19)": the search as low or lower at its σ on all twenty.
#[test]
#[ignore = "a measurement: the documented study and a run from the truth, about 10 s per car in release"]
fn the_search_ends_as_low_as_a_run_from_the_truth_in_its_own_objective() {
    let mut above = Vec::new();
    for seed in super::yaw_rate::seeds("0,6,12") {
        let Some(dir) = super::defaults::series(seed) else {
            return;
        };
        let (_, mut study, truth) = yielding_truth_of(&dir, "study-doc.toml", 0.01);
        study.setup.joint = None;
        let searched = identified(&study.cases, &study.setup, &|| {}).unwrap();
        let mut setup = study.setup.clone();
        setup.template = truth;
        setup.starts = 1;
        setup.staged = false;
        setup.priors = pinned(&study.setup.priors, &searched);
        let from_truth = identified(&study.cases, &setup, &|| {}).unwrap();
        let (sigma, own) = (searched.prior_noise, from_truth.prior_noise);
        let (search, truth) = (valued(&searched, sigma), valued(&from_truth, sigma));
        let at_own = (valued(&searched, own) - valued(&from_truth, own)) / (own * own);
        let (u, u2) = (searched.domain.unit(), searched.domain.squared_unit());
        eprintln!(
            "seed {seed}: at σ {sigma:.4e} {u}: the search {search:.5e} {u2} (F {:.5e} {u2}, {} of {} starts at it), from the truth {truth:.5e} {u2} (F {:.5e} {u2}): {:+.3} σ²; at the truth run's σ {own:.4e} {u}: {at_own:+.3} σ²; I_z {:.0} / {:.0} kg·m², μ {:.3} / {:.3}",
            searched.objective,
            searched.starts.reached_best,
            searched.starts.total,
            from_truth.objective,
            (search - truth) / (sigma * sigma),
            searched.car.body().yaw_inertia,
            from_truth.car.body().yaw_inertia,
            searched.car.tyres().front.mu_lateral,
            from_truth.car.tyres().front.mu_lateral,
        );
        if search > truth + sigma * sigma {
            above.push(seed);
        }
    }
    assert!(
        above.is_empty(),
        "the search above the run from the truth by more than σ² on cars {above:?}"
    );
}
