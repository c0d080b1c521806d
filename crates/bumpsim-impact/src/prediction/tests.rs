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

/// `E[√U]` and `E[U]` of `U` uniform on `[low, high]`.
fn uniform_moments([low, high]: [f64; 2]) -> [f64; 2] {
    let root = 2.0 / 3.0 * (high.powf(1.5) - low.powf(1.5)) / (high - low);
    [root, 0.5 * (low + high)]
}

/// `P(√(a b) ≤ t)` of `a`, `b` uniform on their ranges (the midpoint rule
/// over `a` on 20 000 points of the exact conditional probability).
fn product_cdf([a1, a2]: [f64; 2], [b1, b2]: [f64; 2], t: f64) -> f64 {
    let n = 20_000;
    let conditional = |k: usize| {
        let a = a1 + (a2 - a1) * (k as f64 + 0.5) / n as f64;
        ((t * t / a - b1) / (b2 - b1)).clamp(0.0, 1.0)
    };
    (0..n).map(conditional).sum::<f64>() / n as f64
}

/// The quantile `p` of `√(a b)` by bisection of [`product_cdf`].
fn product_quantile(a: [f64; 2], b: [f64; 2], p: f64) -> f64 {
    let (mut low, mut high) = ((a[0] * b[0]).sqrt(), (a[1] * b[1]).sqrt());
    for _ in 0..60 {
        let mid = 0.5 * (low + high);
        match product_cdf(a, b, mid) < p {
            true => low = mid,
            false => high = mid,
        }
    }
    0.5 * (low + high)
}

/// The rigid car with k (`bumper.force`) uniform on ×0.5 .. ×1.5 and m
/// (`masses[0]`) on ×0.8 .. ×1.2, read from a `[ranges]` table.
fn ranged() -> (ChainUncertainty, [f64; 2], [f64; 2]) {
    let text = "[ranges]\n\"bumper.force\" = [0.5, 1.5]\n\"masses[0]\" = [0.8, 1.2]\n";
    let u = ChainUncertainty::parse(text, "ranges.toml".as_ref()).unwrap();
    (u, [0.5, 1.5], [0.8, 1.2])
}

/// Uniform k and m: the peak force `v √(k m)` over 2000 draws lies within
/// `v √(k_lo m_lo)` .. `v √(k_hi m_hi)`, its mean is `v √(k̂ m̂) E[√a]
/// E[√b]` within 1 % (Monte Carlo error about 0.4 %), and its 5 %, 50 %
/// and 95 % quantiles are the analytic ones of a product of uniforms
/// within 1.5 % (their Monte Carlo error about 0.5 %).
#[test]
fn the_peak_force_over_ranges_has_the_analytic_distribution() {
    let (car, (u, a, b)) = (rigid(), ranged());
    assert_eq!(
        u.laws[1],
        crate::uncertainty::Marginal::Uniform {
            low: 0.8,
            high: 1.2
        }
    );
    let nominal = run(&car).unwrap();
    let lower = u.cholesky().unwrap();
    let peaks: Vec<f64> = (0..2000)
        .map(|i| run(&Chain::scaled(&car, &u.parts(), &u.factors(&lower, 9, i)).unwrap()))
        .map(|r| r.unwrap().peak_force / nominal.peak_force)
        .collect();
    let (least, most) = ((a[0] * b[0]).sqrt(), (a[1] * b[1]).sqrt());
    assert!(
        peaks
            .iter()
            .all(|&f| least * 0.999 <= f && f <= most * 1.001)
    );
    let mean = peaks.iter().sum::<f64>() / peaks.len() as f64;
    let want = uniform_moments(a)[0] * uniform_moments(b)[0];
    assert!((mean / want - 1.0).abs() < 0.01, "{mean} against {want}");
    let sampling = Sampling {
        samples: 2000,
        seed: 9,
        level: 0.9,
    };
    let p = predict(&car, &nominal, &u, &sampling, &run).unwrap();
    let peak = p.outputs[0].spread.unwrap();
    for (got, probability) in [(peak.low, 0.05), (peak.median, 0.5), (peak.high, 0.95)] {
        let want = nominal.peak_force * product_quantile(a, b, probability);
        assert!((got / want - 1.0).abs() < 0.015, "{got} against {want}");
    }
    assert!(lines(&p).contains("uniform ranges bumper.force ×0.5 .. ×1.5, masses[0] ×0.8 .. ×1.2"));
}

/// The Sobol' indices of `v √k √m` with k, m independent uniform factors
/// a, b: `V₁ = Var(√a) E[√b]²`, `V₂ = Var(√b) E[√a]²`, `V = E[a] E[b] −
/// E[√a]² E[√b]²`, `S₁ = V₁/V`, `S_T1 = 1 − V₂/V`; each index within its
/// bootstrap half-width plus 0.02.
#[test]
fn sobol_indices_over_ranges_are_analytic() {
    let (car, (u, a, b)) = (rigid(), ranged());
    let nominal = run(&car).unwrap();
    let settings = bumpsim_estimate::sobol::Settings::new(512, 1);
    let s = sensitivity(&car, &nominal, &u, &settings, &run).unwrap();
    let ([ra, ea], [rb, eb]) = (uniform_moments(a), uniform_moments(b));
    let all = ea * eb - (ra * rb).powi(2);
    let (v1, v2) = ((ea - ra * ra) * rb * rb, (eb - rb * rb) * ra * ra);
    let first = [v1 / all, v2 / all];
    let total = [1.0 - v2 / all, 1.0 - v1 / all];
    let i = &s.outputs[0].indices;
    for j in 0..2 {
        let near = |got: f64, want: f64, half: f64| (got - want).abs() < half + 0.02;
        assert!(
            near(i.first[j], first[j], i.first_conf[j]),
            "{i:?} {first:?}"
        );
        assert!(
            near(i.total[j], total[j], i.total_conf[j]),
            "{i:?} {total:?}"
        );
    }
    assert!(sensitivity_lines(&s).contains("over independent uniform parameters"));
}

/// A `[ranges]` table beside `[uncertainty]`: each parameter its law, the
/// header says both; a range that is not two numbers, reversed, NaN,
/// not positive or beyond the factors' bounds, a parameter in both tables
/// and an unknown name are refused naming the file and the key.
#[test]
fn ranges_are_read_and_bad_ones_refused() {
    let text = "[uncertainty]\n\"masses[0]\" = 0.1\n[ranges]\n\"springs[0]\" = [0.8, 1.2]\n";
    let u = ChainUncertainty::parse(text, "u.toml".as_ref()).unwrap();
    assert_eq!(u.names, ["masses[0]", "springs[0]"]);
    assert_eq!(u.log_sd[0], 0.1);
    // the sd of ln U, U uniform on [0.8, 1.2]: ≈ 0.4/√12/1 (0.1155), a little more
    assert!((u.log_sd[1] - 0.1163).abs() < 0.001, "{}", u.log_sd[1]);
    assert!(
        u.described()
            .starts_with("log-normal spreads and uniform ranges masses[0] 10.0 %")
    );
    for (range, says) in [
        ("[1.2, 0.8]", "low < high"),
        ("[0.8]", "two numbers"),
        ("[0.8, 1.2, 1.4]", "two numbers"),
        ("1.2", "two numbers"),
        ("[\"a\", 1.2]", "two numbers"),
        ("[nan, 1.2]", "low < high"),
        ("[0.8, inf]", "1000"),
        ("[0.0, 1.2]", "0.001 <= low"),
        ("[-1.0, 1.2]", "0.001 <= low"),
        ("[0.5, 2000.0]", "<= 1000"),
    ] {
        let text = format!("[ranges]\n\"springs[0]\" = {range}\n");
        let e = ChainUncertainty::parse(&text, "r.toml".as_ref()).unwrap_err();
        let e = e.to_string();
        assert!(
            e.starts_with("r.toml: ranges.\"springs[0]\"") && e.contains(says),
            "{range}: {e}"
        );
    }
    let both = "[uncertainty]\n\"springs[0]\" = 0.1\n[ranges]\n\"springs[0]\" = [0.8, 1.2]\n";
    let e = ChainUncertainty::parse(both, "b.toml".as_ref())
        .unwrap_err()
        .to_string();
    assert!(e.starts_with("b.toml: 'springs[0]' is in both"), "{e}");
    let unknown = "[ranges]\n\"wheel.size\" = [0.8, 1.2]\n";
    let e = ChainUncertainty::parse(unknown, "w.toml".as_ref())
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with("w.toml: 'wheel.size' is not a parameter"),
        "{e}"
    );
    let neither = ChainUncertainty::parse("[range]\n", "n.toml".as_ref()).unwrap_err();
    assert!(neither.to_string().contains("[ranges] table"), "{neither}");
}

/// An index estimated above 1 prints at the bound with its estimate and
/// half-width, and the table says why (issue 48 item 14: a peak force's
/// first-order index printed as a share of 1.020).
#[test]
fn an_index_above_one_prints_at_the_bound_with_its_estimate() {
    let (car, (u, _, _)) = (rigid(), ranged());
    let nominal = run(&car).unwrap();
    let settings = bumpsim_estimate::sobol::Settings::new(16, 1);
    let mut s = sensitivity(&car, &nominal, &u, &settings, &run).unwrap();
    for o in &mut s.outputs {
        o.indices.first.iter_mut().for_each(|v| *v = 0.5);
        o.indices.total.iter_mut().for_each(|v| *v = 0.5);
    }
    let within = sensitivity_lines(&s);
    assert!(
        !within.contains("est.") && !within.contains(CLIPPED),
        "{within}"
    );
    let i = &mut s.outputs[0].indices;
    (i.first[0], i.first_conf[0]) = (1.0204, 0.0512);
    let lines = sensitivity_lines(&s);
    assert!(lines.contains("1.000 (est. 1.020 ± 0.051)"), "{lines}");
    // the estimate only in its parentheses, never as a share
    let bare = lines.matches("1.020 ± 0.051").count();
    assert_eq!(
        bare,
        lines.matches("(est. 1.020 ± 0.051)").count(),
        "{lines}"
    );
    assert!(lines.contains(CLIPPED), "{lines}");
}

/// The Sobol sequence is balanced only over 2^m points: a base of 100 or
/// 17 is refused naming the powers either side; the range ends pass.
#[test]
fn the_sobol_base_is_a_power_of_two() {
    for (base, powers) in [
        (17, "16 or 32"),
        (100, "64 or 128"),
        (65_535, "32768 or 65536"),
    ] {
        let e = check_base(base, 1).unwrap_err().to_string();
        let head = format!("base = {base} samples: a power of two ({powers})");
        assert!(e.starts_with(&head), "{e}");
    }
    for base in SOBOL_BASE {
        assert!(check_base(base, 1).is_ok());
    }
}
