//! LS-DYNA include checked card by card against the manual's field layout,
//! against golden files, and across unit systems; CalculiX deck structure.
//! Golden files: `BUMPSIM_BLESS=1 cargo test -p bumpsim-export` rewrites them.

use approx::assert_relative_eq;
use bumpsim_core::model::MsdModel;
use bumpsim_core::state_space::elastic_modes;
use bumpsim_export::ExportError;
use bumpsim_export::calculix::{CalculixOptions, calculix_deck};
use bumpsim_export::layout::{Axis, Layout, UnitSystem};
use bumpsim_export::lsdyna::{LsDynaOptions, lsdyna_include};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

fn thesis_model() -> MsdModel {
    MsdModel::new(
        vec![1.8, 74.8, 1670.0],
        vec![6.46e6, 1.97e5],
        vec![4.75e5, 5.0e5],
    )
    .unwrap()
}

fn options(units: UnitSystem) -> LsDynaOptions {
    LsDynaOptions {
        layout: Layout {
            units,
            axis: Axis::default(),
            origin: [3.2, 0.0, 0.45],
            spacing: 0.1,
        },
        id_offset: 9_000_000,
        attach: vec![1001, 1002, 2001, 2002],
        initial_velocity: Some(-4.0),
        title: "thesis 3-DOF model (Isaksson 2006, paper B, table 2)".into(),
        ..Default::default()
    }
}

#[derive(Clone, Copy, PartialEq)]
enum Field {
    Int,
    Real,
}

use Field::{Int, Real};

/// Field layouts per card of each keyword (the manual's fixed format); the
/// last layout repeats for further cards. `None` is a free title line.
fn layout(keyword: &str) -> Vec<Option<Vec<(usize, Field)>>> {
    let w = |fields: &[(usize, Field)]| Some(fields.to_vec());
    match keyword {
        "*NODE" => vec![w(&[
            (8, Int),
            (16, Real),
            (16, Real),
            (16, Real),
            (8, Int),
            (8, Int),
        ])],
        "*ELEMENT_MASS" => vec![w(&[(8, Int), (8, Int), (16, Real)])],
        "*SECTION_DISCRETE" => vec![w(&[(10, Int), (10, Int)])],
        "*MAT_SPRING_ELASTIC" | "*MAT_DAMPER_VISCOUS" => vec![w(&[(10, Int), (10, Real)])],
        "*PART" => vec![None, w(&[(10, Int), (10, Int), (10, Int)])],
        "*ELEMENT_DISCRETE" => vec![w(&[
            (8, Int),
            (8, Int),
            (8, Int),
            (8, Int),
            (8, Int),
            (16, Real),
        ])],
        "*DEFINE_SD_ORIENTATION" => {
            vec![w(&[
                (10, Int),
                (10, Int),
                (10, Real),
                (10, Real),
                (10, Real),
            ])]
        }
        "*SET_NODE_LIST" => vec![w(&[(10, Int)]), w(&[(10, Int); 8])],
        "*CONSTRAINED_NODAL_RIGID_BODY_SPC" => vec![
            w(&[(10, Int), (10, Int), (10, Int)]),
            w(&[(10, Real), (10, Real), (10, Real)]),
        ],
        "*INITIAL_VELOCITY_NODE" => vec![w(&[(10, Int), (10, Real), (10, Real), (10, Real)])],
        "*KEYWORD" | "*END" => vec![],
        other => panic!("keyword {other} has no layout in the checker"),
    }
}

/// Cards of a deck: keyword and, per card, its numeric fields.
type Cards = Vec<(String, Vec<Vec<f64>>)>;

/// Checks every card's fields sit in the right columns and parse as their type.
fn check_cards(deck: &str) -> Cards {
    let mut cards: Cards = Vec::new();
    for (number, line) in deck.lines().enumerate() {
        let at = format!("line {}: {line:?}", number + 1);
        assert!(line.len() <= 80, "{at}: longer than 80 columns");
        if line.starts_with('$') {
            continue;
        }
        if line.starts_with('*') {
            layout(line.trim());
            cards.push((line.trim().to_string(), Vec::new()));
            continue;
        }
        let (keyword, rows) = cards
            .last_mut()
            .unwrap_or_else(|| panic!("{at}: card before any keyword"));
        let layouts = layout(keyword);
        let index = rows.len().min(layouts.len() - 1);
        let Some(fields) = &layouts[index] else {
            rows.push(Vec::new()); // title line
            continue;
        };
        let mut values = Vec::new();
        let mut column = 0;
        for &(width, kind) in fields {
            if column >= line.len() {
                break;
            }
            let cell = line
                .get(column..(column + width).min(line.len()))
                .unwrap()
                .trim();
            column += width;
            let value = match kind {
                Int => cell.parse::<i64>().map(|v| v as f64).ok(),
                Real => cell
                    .parse::<f64>()
                    .ok()
                    .filter(|_| cell.contains('.') || cell.contains('e')),
            };
            values.push(value.unwrap_or_else(|| {
                panic!(
                    "{at}: field '{cell}' is not a {}",
                    if kind == Int { "integer" } else { "real" }
                )
            }));
        }
        assert!(line.len() <= column, "{at}: text beyond the last field");
        rows.push(values);
    }
    cards
}

fn rows<'a>(cards: &'a Cards, keyword: &str) -> Vec<&'a Vec<f64>> {
    cards
        .iter()
        .filter(|(k, _)| k == keyword)
        .flat_map(|(_, r)| r.iter().filter(|v| !v.is_empty()))
        .collect()
}

/// Ids unique per kind and every referenced id defined (attachment nodes are the user's).
fn check_ids(cards: &Cards, external_nodes: &[u64]) {
    let mut defined: BTreeMap<&str, BTreeSet<u64>> = BTreeMap::new();
    let mut define = |kind: &'static str, id: f64| {
        assert!(
            defined.entry(kind).or_default().insert(id as u64),
            "{kind} id {id} defined twice"
        )
    };
    rows(cards, "*NODE")
        .iter()
        .for_each(|r| define("node", r[0]));
    rows(cards, "*ELEMENT_MASS")
        .iter()
        .chain(&rows(cards, "*ELEMENT_DISCRETE"))
        .for_each(|r| define("element", r[0]));
    rows(cards, "*PART")
        .iter()
        .chain(
            &rows(cards, "*CONSTRAINED_NODAL_RIGID_BODY_SPC")
                [..1.min(rows(cards, "*CONSTRAINED_NODAL_RIGID_BODY_SPC").len())],
        )
        .for_each(|r| define("part", r[0]));
    rows(cards, "*MAT_SPRING_ELASTIC")
        .iter()
        .chain(&rows(cards, "*MAT_DAMPER_VISCOUS"))
        .for_each(|r| define("material", r[0]));
    rows(cards, "*SECTION_DISCRETE")
        .iter()
        .for_each(|r| define("section", r[0]));
    rows(cards, "*DEFINE_SD_ORIENTATION")
        .iter()
        .for_each(|r| define("orientation", r[0]));
    let is = |kind: &str, id: f64| defined.get(kind).is_some_and(|s| s.contains(&(id as u64)));
    let node = |id: f64| is("node", id) || external_nodes.contains(&(id as u64));
    for r in rows(cards, "*ELEMENT_MASS") {
        assert!(node(r[1]), "mass on undefined node {}", r[1]);
    }
    for r in rows(cards, "*ELEMENT_DISCRETE") {
        assert!(
            is("part", r[1]) && node(r[2]) && node(r[3]) && is("orientation", r[4]),
            "discrete element {} references undefined ids (or acts along the nodes' line)",
            r[0]
        );
    }
    for r in rows(cards, "*PART") {
        assert!(
            is("section", r[1]) && is("material", r[2]),
            "part {} references undefined ids",
            r[0]
        );
    }
    let set = rows(cards, "*SET_NODE_LIST");
    for id in set.iter().skip(1).flat_map(|r| r.iter()) {
        assert!(node(*id), "set member {id} is not a node");
    }
    if let Some(rigid) = rows(cards, "*CONSTRAINED_NODAL_RIGID_BODY_SPC").first() {
        assert_eq!(
            rigid[2], set[0][0],
            "rigid body references an undefined set"
        );
    }
}

#[test]
fn every_card_is_in_its_columns_and_every_id_resolves() {
    for units in [UnitSystem::Si, UnitSystem::MmSTonne, UnitSystem::MmMsKg] {
        let deck = lsdyna_include(&thesis_model(), &options(units)).unwrap();
        let cards = check_cards(&deck);
        check_ids(&cards, &options(units).attach);
        assert_eq!(
            rows(&cards, "*ELEMENT_DISCRETE").len(),
            4,
            "two springs and two dampers"
        );
    }
}

/// Reads the model, node coordinates and initial velocity back from a deck, in SI.
fn physics(deck: &str, units: UnitSystem) -> (MsdModel, Vec<Vec<f64>>, Vec<f64>) {
    let cards = check_cards(deck);
    let values = |keyword: &str, column: usize, factor: f64| -> Vec<f64> {
        rows(&cards, keyword)
            .iter()
            .map(|r| r[column] / factor)
            .collect()
    };
    let model = MsdModel::new(
        values("*ELEMENT_MASS", 2, units.mass()),
        values("*MAT_DAMPER_VISCOUS", 1, units.damping()),
        values("*MAT_SPRING_ELASTIC", 1, units.stiffness()),
    )
    .unwrap();
    let nodes = rows(&cards, "*NODE")
        .iter()
        .map(|r| r[1..4].iter().map(|x| x / units.length()).collect())
        .collect();
    (
        model,
        nodes,
        values("*INITIAL_VELOCITY_NODE", 1, units.velocity()),
    )
}

#[test]
fn unit_systems_describe_the_same_physics() {
    let reference = thesis_model();
    let modes = elastic_modes(&reference).unwrap();
    let (si_model, si_nodes, si_velocity) = physics(
        &lsdyna_include(&reference, &options(UnitSystem::Si)).unwrap(),
        UnitSystem::Si,
    );
    for units in [UnitSystem::MmSTonne, UnitSystem::MmMsKg] {
        let (model, nodes, velocity) =
            physics(&lsdyna_include(&reference, &options(units)).unwrap(), units);
        // 10-column fields keep at least 6 significant digits for these values
        for (a, b) in model.parameters().iter().zip(si_model.parameters()) {
            assert_relative_eq!(*a, b, max_relative = 1e-6);
        }
        for (a, b) in nodes.iter().flatten().zip(si_nodes.iter().flatten()) {
            assert_relative_eq!(*a, *b, max_relative = 1e-9, epsilon = 1e-12);
        }
        assert_relative_eq!(velocity[0], si_velocity[0], max_relative = 1e-9);
        for (a, b) in elastic_modes(&model).unwrap().iter().zip(&modes) {
            assert_relative_eq!(
                a.natural_frequency(),
                b.natural_frequency(),
                max_relative = 1e-5
            );
        }
    }
    assert_relative_eq!(si_velocity[0], -4.0);
}

fn golden(name: &str, text: &str) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../tests/data/export")
        .join(name);
    if std::env::var_os("BUMPSIM_BLESS").is_some() {
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        std::fs::write(&path, text).unwrap();
    }
    let expected = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("{}: {e} (BUMPSIM_BLESS=1 writes it)", path.display()));
    assert_eq!(
        text,
        expected,
        "{} differs; if the change is intended, rerun with BUMPSIM_BLESS=1",
        path.display()
    );
}

#[test]
fn golden_includes_in_si_and_mm_s_tonne() {
    golden(
        "car-3dof-si.k",
        &lsdyna_include(&thesis_model(), &options(UnitSystem::Si)).unwrap(),
    );
    golden(
        "car-3dof-mm-s-t.k",
        &lsdyna_include(&thesis_model(), &options(UnitSystem::MmSTonne)).unwrap(),
    );
}

#[test]
fn clashing_and_oversized_ids_are_refused() {
    let mut clash = options(UnitSystem::Si);
    clash.attach = vec![9_000_002];
    let err = lsdyna_include(&thesis_model(), &clash).unwrap_err();
    assert!(
        matches!(
            &err,
            ExportError::IdClash {
                node: 9_000_002,
                ..
            }
        ),
        "{err}"
    );
    let mut big = options(UnitSystem::Si);
    big.id_offset = 99_999_990;
    assert!(
        lsdyna_include(&thesis_model(), &big)
            .unwrap_err()
            .to_string()
            .contains("8-column limit")
    );
    assert!(
        "imperial"
            .parse::<UnitSystem>()
            .unwrap_err()
            .to_string()
            .contains("expected si, mm-s-t or mm-ms-kg")
    );
}

#[test]
fn undamped_links_get_no_damper_and_axis_sets_constraints() {
    let spring_only = MsdModel::new(vec![650.0, 400.0], vec![0.0], vec![4e6]).unwrap();
    let mut opts = options(UnitSystem::Si);
    opts.layout.axis = "-y".parse().unwrap();
    opts.attach.clear();
    let deck = lsdyna_include(&spring_only, &opts).unwrap();
    let cards = check_cards(&deck);
    check_ids(&cards, &[]);
    assert!(rows(&cards, "*MAT_DAMPER_VISCOUS").is_empty());
    // y axis: TC 6 fixes z and x; nodes step along -y
    let nodes = rows(&cards, "*NODE");
    assert!(nodes.iter().all(|r| r[4] == 6.0 && r[5] == 7.0));
    assert_relative_eq!(nodes[1][2] - nodes[0][2], -0.1);
    // the links act along the axis whatever the nodes' current line: a crush
    // beyond the 0.1 m spacing must not turn a spring over
    let orientation = rows(&cards, "*DEFINE_SD_ORIENTATION");
    assert_eq!(orientation.len(), 1);
    assert_eq!(orientation[0][1..], [0.0, 0.0, -1.0, 0.0]);
    assert!(
        rows(&cards, "*ELEMENT_DISCRETE")
            .iter()
            .all(|r| r[4] == orientation[0][0])
    );
}

#[test]
fn calculix_model_deck_fixes_the_cross_directions() {
    let deck = calculix_deck(&thesis_model(), &CalculixOptions::default()).unwrap();
    for expected in [
        "*ELEMENT, TYPE=MASS",
        // a fixed-direction spring on x (DOF 1) of both nodes: a SPRINGA
        // turned over once a crush beyond the spacing crossed its nodes
        "*ELEMENT, TYPE=SPRING2",
        "*SPRING, ELSET=BUMPSIM_EK1\n1, 1\n",
        "*ELEMENT, TYPE=DASHPOTA",
        "*BOUNDARY\nBUMPSIM_NALL, 2, 2\nBUMPSIM_NALL, 3, 3",
    ] {
        assert!(deck.contains(expected), "missing {expected:?}");
    }
    assert!(!deck.contains("*STEP"), "no analysis without a force");
}

/// Values finite in SI that overflow in the deck's units were written as
/// `inf` (exit 0): a force history reaching 1e307 s is inf ms, an origin of
/// 1e308 m is inf mm, a spacing of 1e308 m puts mass 3 at inf m.
#[test]
fn values_that_overflow_in_the_decks_units_are_refused() {
    use bumpsim_core::series::UniformSeries;
    use bumpsim_export::calculix::Analysis;
    let force = UniformSeries::new(0.0, 1e307, vec![1.0, 2.0]).unwrap();
    let mut run = options(UnitSystem::MmMsKg);
    run.force = Some(force.clone());
    run.standalone = true;
    let mut far = options(UnitSystem::MmSTonne);
    far.layout.origin = [1e308, 0.0, 0.0];
    let mut spaced = options(UnitSystem::Si);
    spaced.layout.spacing = 1e308;
    let mut huge_dt = options(UnitSystem::MmMsKg);
    huge_dt.output_interval = Some(1e308);
    for (o, what) in [
        (run, "force sample 2"),
        (far, "position of mass 1"),
        (spaced, "position of mass 3"),
        (huge_dt, "output interval"),
    ] {
        let err = lsdyna_include(&thesis_model(), &o).unwrap_err();
        assert!(
            matches!(err, ExportError::Overflow { .. }) && err.to_string().contains(what),
            "{err}"
        );
    }
    let ccx = CalculixOptions {
        layout: Layout {
            units: UnitSystem::MmMsKg,
            ..Layout::default()
        },
        analysis: Some(Analysis {
            force,
            increment: None,
            output_every: 1,
        }),
        ..CalculixOptions::default()
    };
    let err = calculix_deck(&thesis_model(), &ccx).unwrap_err();
    assert!(err.to_string().contains("force sample 2"), "{err}");
    // the SI deck of the same force is fine
    let mut si = options(UnitSystem::Si);
    si.force = Some(UniformSeries::new(0.0, 1e307, vec![1.0, 2.0]).unwrap());
    assert!(
        !lsdyna_include(&thesis_model(), &si)
            .unwrap()
            .contains("inf")
    );
}
