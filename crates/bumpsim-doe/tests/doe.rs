//! Integration tests of the DOE crate: paper C table 4 from the published
//! coefficients, regression against statsmodels, designs against pyDOE3,
//! and the reachable cell of paper C stage 1.

use bumpsim_doe::design::{fractional_factorial, full_factorial, resolution};
use bumpsim_doe::model::ModelFile;
use bumpsim_doe::reachable::{LinearMap, cell};
use bumpsim_doe::regression::{fit, terms};
use rand_chacha::ChaCha8Rng;
use rand_core::{Rng, SeedableRng};
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/doe")
        .join(name)
}

fn model(name: &str) -> ModelFile {
    serde_json::from_str(&std::fs::read_to_string(data(name)).unwrap()).unwrap()
}

#[test]
fn paper_c_table_4_from_the_published_coefficients() {
    let m = model("paper-c-stage2.json");
    let points = [
        (23447.0, 21930.0, 1528.0),
        (25147.0, 23230.0, 1375.0),
        (21747.0, 20630.0, 1681.0),
    ];
    let expected = [
        ("m1", [1.0, 1.0, 1.0], 0),
        ("m2", [1987.0, 1744.0, 2230.0], 0),
        ("c1", [206.4, 212.6, 200.2], 1),
        ("k1", [3.971, 4.022, 3.920], 3),
    ];
    for (p, &(kax, kbnd, mass)) in points.iter().enumerate() {
        let at = [
            ("Kax".to_string(), kax),
            ("Kbnd".to_string(), kbnd),
            ("M".to_string(), mass),
        ];
        let prediction = m.predict(&at).unwrap();
        assert!(prediction.warnings.is_empty(), "{:?}", prediction.warnings);
        for (name, values, digits) in expected {
            let got = prediction
                .values
                .iter()
                .find(|v| v.name == name)
                .unwrap()
                .value;
            let printed = format!("{got:.digits$}");
            assert_eq!(
                printed,
                format!("{:.digits$}", values[p]),
                "{name} at point {p}: {got}"
            );
        }
    }
    let outside = m
        .predict(&[
            ("Kax".into(), 27000.0),
            ("Kbnd".into(), 21930.0),
            ("M".into(), 1528.0),
        ])
        .unwrap();
    assert_eq!(outside.warnings.len(), 1);
    assert!(outside.warnings[0].contains("Kax = 27000 is outside the design region 21210..25684"));
}

use bumpsim_peers::python_available;

fn close(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-8 * b.abs().max(1e-12)
}

#[test]
fn regression_equals_statsmodels_on_random_designs() {
    if !python_available("statsmodels") {
        return;
    }
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/statsmodels_ols.py");
    let mut rng = ChaCha8Rng::seed_from_u64(11);
    let mut u = || (rng.next_u64() >> 11) as f64 / (1u64 << 53) as f64;
    for (case, (k, n, interactions, squares)) in [
        (2, 9, true, true),
        (3, 12, true, false),
        (4, 20, false, true),
    ]
    .into_iter()
    .enumerate()
    {
        let names: Vec<String> = (0..k).map(|i| format!("x{i}")).collect();
        let z: Vec<Vec<f64>> = (0..n)
            .map(|_| (0..k).map(|_| 2.0 * u() - 1.0).collect())
            .collect();
        let y: Vec<f64> = z
            .iter()
            .map(|r| {
                3.0 + r
                    .iter()
                    .enumerate()
                    .map(|(i, v)| (i + 1) as f64 * v)
                    .sum::<f64>()
                    + r[0] * r[0]
                    + 0.3 * (u() - 0.5)
            })
            .collect();
        let model_terms = terms(k, interactions, squares);
        let ours = fit(&z, &y, &model_terms, &names).unwrap();
        let file =
            std::env::temp_dir().join(format!("bumpsim-ols-{}-{case}.csv", std::process::id()));
        let mut text = String::from("y");
        model_terms.iter().for_each(|_| text += ",x");
        text.push('\n');
        for (row, yi) in z.iter().zip(&y) {
            text += &format!("{yi:e}");
            model_terms
                .iter()
                .for_each(|t| text += &format!(",{:e}", t.value(row)));
            text.push('\n');
        }
        std::fs::write(&file, text).unwrap();
        let out = bumpsim_peers::python(&script, &[&file]);
        let theirs: serde_json::Value = serde_json::from_slice(&out).unwrap();
        for j in 0..model_terms.len() {
            assert!(
                close(ours.coefficients[j], theirs["params"][j].as_f64().unwrap()),
                "coefficient {j}"
            );
            assert!(
                close(
                    ours.std_errors[j].unwrap(),
                    theirs["bse"][j].as_f64().unwrap()
                ),
                "standard error {j}"
            );
            let [lo, hi] = ours.ci95[j].unwrap();
            assert!(
                close(lo, theirs["conf_int"][j][0].as_f64().unwrap())
                    && close(hi, theirs["conf_int"][j][1].as_f64().unwrap()),
                "interval {j}"
            );
        }
        assert!(close(ours.r2, theirs["rsquared"].as_f64().unwrap()));
        assert!(close(
            ours.r2_adjusted.unwrap(),
            theirs["rsquared_adj"].as_f64().unwrap()
        ));
        assert!(
            close(ours.press.unwrap(), theirs["press"].as_f64().unwrap()),
            "PRESS"
        );
    }
}

fn sorted(mut rows: Vec<Vec<f64>>) -> Vec<Vec<f64>> {
    rows.sort_by(|a, b| {
        a.iter()
            .zip(b)
            .map(|(x, y)| x.total_cmp(y))
            .find(|o| o.is_ne())
            .unwrap_or(std::cmp::Ordering::Equal)
    });
    rows
}

fn pydoe(kind: &str, arg: &str) -> Vec<Vec<f64>> {
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/peers/pydoe3_designs.py");
    serde_json::from_slice(&bumpsim_peers::python(&script, &[kind, arg])).unwrap()
}

#[test]
fn designs_equal_pydoe3_up_to_row_order() {
    if !python_available("pyDOE3") {
        return;
    }
    for k in 1..=5 {
        let names: Vec<String> = (0..k)
            .map(|i| ((b'A' + i as u8) as char).to_string())
            .collect();
        let refs: Vec<&str> = names.iter().map(String::as_str).collect();
        assert_eq!(
            sorted(full_factorial(&refs, 0).unwrap().runs),
            sorted(pydoe("ff2n", &k.to_string()))
        );
    }
    for (ours, theirs) in [
        (
            vec!["A", "B", "C", "D=AB", "E=AC", "F=BC", "G=ABC"],
            "a b c ab ac bc abc",
        ),
        (
            vec!["A", "B", "C", "D", "E=ABC", "F=-BCD"],
            "a b c d abc -bcd",
        ),
    ] {
        assert_eq!(
            sorted(fractional_factorial(&ours).unwrap().runs),
            sorted(pydoe("fracfact", theirs))
        );
    }
    let d = fractional_factorial(&["A", "B", "C", "D=AB", "E=AC", "F=BC", "G=ABC"]).unwrap();
    assert_eq!(
        (
            d.runs.len(),
            resolution(&["D=AB", "E=AC", "F=BC", "G=ABC"]).unwrap()
        ),
        (8, 3)
    );
}

#[test]
fn paper_c_stage_1_cell_is_reachable_with_thicknesses_within_bounds() {
    let map = LinearMap::from_model(&model("paper-c-stage1.json"), "Kax", "Kbnd").unwrap();
    let corners = cell(&map, [21210.0, 25684.0], [20217.0, 23643.0]).unwrap();
    for c in &corners {
        assert!(c.reachable, "{c:?}");
        assert!(c.factors.iter().all(|t| t.abs() <= 1.0 + 1e-12), "{c:?}");
        assert!(c.residual < 1e-6, "{c:?}");
    }
    let samples = map.samples(50_000, 1);
    let polygon = map.boundary();
    assert_eq!(polygon.len(), 8);
    assert!(
        samples
            .iter()
            .all(|p| bumpsim_doe::reachable::contains(&polygon, *p)),
        "every sample lies in the exact region"
    );
    let far = cell(&map, [10000.0, 12000.0], [20000.0, 21000.0]).unwrap();
    assert!(
        far.iter().all(|c| !c.reachable && c.residual > 1.0),
        "a far cell is unreachable"
    );
}
