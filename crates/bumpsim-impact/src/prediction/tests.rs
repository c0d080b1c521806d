//! Tests of the chain car's uncertainty and of the predictions over it
//! against analytic answers.

use super::*;
use crate::bumper::Bumper;
use crate::impact::{ImpactResult, Options, Scenario, simulate};
use crate::uncertainty::{Chain, ChainCar, ChainPart, ChainUncertainty, Model};
use bumpsim_core::model::MsdModel;

/// A rigid 1000 kg mass and a linear elastic bumper of 1 MN/m: at v it
/// peaks at `v √(k m)`.
fn rigid() -> ChainCar {
    ChainCar {
        model: MsdModel::new(vec![1000.0], vec![], vec![]).unwrap(),
        bumper: Bumper::three_part(1e6, 1e9, 1e6).unwrap(),
    }
}

fn run(car: &ChainCar) -> Option<ImpactResult> {
    let scenario = Scenario::Barrier { speed: 2.0 };
    simulate(&car.model, &car.bumper, scenario, &Options::default()).ok()
}

/// Standard normal quantile of 0.95.
const Z95: f64 = 1.644_853_626_951_472_2;

/// The peak force of log-normal k and m (correlated, ρ = 0.5) is
/// log-normal with ln-sd `0.5 √(σk² + σm² + 2ρσkσm)` around `v √(k m)`:
/// the 90 % interval's ends and the median match the analytic quantiles
/// within 1.5 % (their Monte Carlo error with 2000 draws is about
/// `2.1 σ/√N` = 0.4 % in ln; the leapfrog's sampled peak adds < 0.1 %).
#[test]
fn the_peak_force_band_is_the_analytic_log_normal() {
    let car = rigid();
    let (sk, sm, rho) = (0.2, 0.1, 0.5);
    let mut u = ChainUncertainty::independent(
        "test",
        vec![("bumper.force".into(), sk), ("masses[0]".into(), sm)],
    )
    .unwrap();
    u.correlation = vec![vec![1.0, rho], vec![rho, 1.0]];
    let nominal = run(&car).unwrap();
    let sampling = Sampling {
        samples: 2000,
        seed: 3,
        level: 0.9,
    };
    let p = predict(&car, &nominal, &u, &sampling, &run).unwrap();
    let peak = p.outputs[0].spread.unwrap();
    let median = 2.0 * (1e6f64 * 1000.0).sqrt();
    let s = 0.5 * (sk * sk + sm * sm + 2.0 * rho * sk * sm).sqrt();
    for (got, want) in [
        (peak.median, median),
        (peak.low, median * (-Z95 * s).exp()),
        (peak.high, median * (Z95 * s).exp()),
    ] {
        assert!((got / want - 1.0).abs() < 0.015, "{got} against {want}");
    }
    assert_eq!(p.failed, 0);
    let force = &p.bands[0];
    let k = (0..force.time.len())
        .max_by(|&a, &b| force.nominal[a].total_cmp(&force.nominal[b]))
        .unwrap();
    assert!(force.band.low[k] < force.nominal[k] && force.nominal[k] < force.band.high[k]);
    // the same seed gives the same prediction
    assert_eq!(p, predict(&car, &nominal, &u, &sampling, &run).unwrap());
}

/// The Sobol' indices of `v √(k m)` with independent log-normal k, m:
/// with `a = ½ ln k`, `b = ½ ln m` (sds `s₁`, `s₂`), `S₁ = (e^{s₁²} − 1)/
/// (e^{s₁²+s₂²} − 1)`, `S_T1 = 1 − S₂`; each index within its bootstrap
/// half-width plus 0.02 (the marginals' 4096 draws).
#[test]
fn sobol_indices_of_the_peak_force_are_analytic() {
    let car = rigid();
    let (sk, sm) = (0.4, 0.2);
    let u = ChainUncertainty::independent(
        "test",
        vec![("bumper.force".into(), sk), ("masses[0]".into(), sm)],
    )
    .unwrap();
    let nominal = run(&car).unwrap();
    let settings = bumpsim_estimate::sobol::Settings::new(512, 1);
    let s = sensitivity(&car, &nominal, &u, &settings, &run).unwrap();
    assert!(!s.correlation_ignored);
    let (a, b) = ((0.5 * sk).powi(2), (0.5 * sm).powi(2));
    let all = (a + b).exp() - 1.0;
    let first = [(a.exp() - 1.0) / all, (b.exp() - 1.0) / all];
    let total = [1.0 - first[1], 1.0 - first[0]];
    let i = &s.outputs[0].indices;
    assert_eq!(s.outputs[0].name, "peak force");
    for j in 0..2 {
        assert!(
            (i.first[j] - first[j]).abs() < i.first_conf[j] + 0.02,
            "{i:?}"
        );
        assert!(
            (i.total[j] - total[j]).abs() < i.total_conf[j] + 0.02,
            "{i:?}"
        );
    }
}

#[test]
fn draws_have_the_correlation_asked_for() {
    let mut u = ChainUncertainty::independent(
        "test",
        vec![("masses[0]".into(), 0.1), ("bumper.force".into(), 0.2)],
    )
    .unwrap();
    u.correlation = vec![vec![1.0, 0.6], vec![0.6, 1.0]];
    let lower = u.cholesky().unwrap();
    let n = 20_000;
    let logs: Vec<Vec<f64>> = (0..n)
        .map(|i| u.factors(&lower, 7, i).iter().map(|f| f.ln()).collect())
        .collect();
    let sd = |k: usize| (logs.iter().map(|l| l[k] * l[k]).sum::<f64>() / n as f64).sqrt();
    let r = logs.iter().map(|l| l[0] * l[1]).sum::<f64>() / n as f64 / (sd(0) * sd(1));
    assert!((sd(0) - 0.1).abs() < 0.003 && (sd(1) - 0.2).abs() < 0.006);
    assert!((r - 0.6).abs() < 0.02, "{r}");
    u.correlation = vec![vec![1.0, 1.2], vec![1.2, 1.0]];
    assert!(u.cholesky().is_err(), "not positive definite");
}

#[test]
fn names_denote_the_chain_parts() {
    assert_eq!(Chain::part("dampers[1]"), Some(ChainPart::Damper(1)));
    assert_eq!(Chain::part("bumper.force"), Some(ChainPart::BumperForce));
    for bad in ["springs", "left.masses[0]", "masses[x]", "body.mass"] {
        assert_eq!(Chain::part(bad), None, "{bad}");
    }
    let car = rigid();
    let u = ChainUncertainty::independent("u", vec![("springs[0]".into(), 0.1)]).unwrap();
    let e = u.check(&car).unwrap_err().to_string();
    assert!(
        e.contains("springs[0]") && e.contains("masses[0], bumper.force"),
        "{e}"
    );
}

/// A chain identification's JSON: SE/value of the kept parameters, their
/// correlation; a fixed one left out; a DOF table's recommended model.
#[test]
fn an_identification_gives_its_spreads_and_correlation() {
    let result = r#"{"dof": 2, "masses": [100.0, 400.0], "dampers": [1000.0], "springs": [2e6],
        "uncertainty": {"names": ["m1", "m2", "c1", "k1"], "standard_errors": [5.0, null, 100.0, 2e5],
        "correlation": [[1.0, null, 0.3, -0.2], [null, null, null, null], [0.3, null, 1.0, 0.1], [-0.2, null, 0.1, 1.0]]}}"#;
    let u = ChainUncertainty::parse(result, "i.json".as_ref()).unwrap();
    assert_eq!(u.names, ["masses[0]", "dampers[0]", "springs[0]"]);
    assert_eq!(u.log_sd, [0.05, 0.1, 0.1]);
    assert_eq!(u.correlation[0], [1.0, 0.3, -0.2]);
    assert!(u.left_out[0].starts_with("m2: no standard error"));
    let table = format!(r#"{{"results": [{{"dof": 1}}, {result}], "recommended_dof": 2}}"#);
    assert_eq!(
        ChainUncertainty::parse(&table, "t.json".as_ref()).unwrap(),
        {
            let mut v = u.clone();
            v.source = "t.json".into();
            v
        }
    );
    let planar = r#"{"result": {"parameters": [{"name": "body.mass", "value": 1.0}]}}"#;
    let e = ChainUncertainty::parse(planar, "p.json".as_ref()).unwrap_err();
    assert!(e.to_string().contains("1-D chain identification"), "{e}");
}
