//! The coupled bumper–car run in CalculiX against `bumpsim impact` and its
//! own energy balance (issue 16). Needs `ccx` (Debian calculix-ccx); skipped
//! with a message without it unless BUMPSIM_REQUIRE_PEERS is set.

use bumpsim_core::model::MsdModel;
use bumpsim_fe::bumper::BumperMesh;
use bumpsim_fe::run::{FeRun, run};
use bumpsim_impact::impact::Scenario;
use std::path::PathBuf;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn ccx() -> bool {
    bumpsim_peers::peer_available("ccx (calculix-ccx)", "sh", &["-c", "command -v ccx"])
}

/// The bundled example's synthetic 3-DOF car.
fn car() -> MsdModel {
    MsdModel::new(
        vec![30.0, 250.0, 1170.0],
        vec![8e3, 2.5e4],
        vec![1.5e6, 6e5],
    )
    .unwrap()
}

fn settings(bumper: &str, scenario: Scenario, work: &str) -> FeRun {
    let mesh = BumperMesh::read(&root().join("examples/fe").join(bumper)).unwrap();
    let work = std::env::temp_dir().join(format!("bumpsim-fe-{}-{work}", std::process::id()));
    let _ = std::fs::remove_dir_all(&work);
    FeRun::new(mesh, car(), scenario, work)
}

/// An elastic bumper stiff enough to act as a spring: peak force and
/// largest compression within 2 % of `impact` with the equivalent linear
/// characteristic (the FE force CFC 60-filtered, as a barrier load cell),
/// energy closed within 2 %.
#[test]
fn an_elastic_bumper_reproduces_impact_with_its_equivalent_spring() {
    if !ccx() {
        return;
    }
    let s = settings(
        "bumper-elastic.toml",
        Scenario::Barrier { speed: 2.2 },
        "elastic",
    );
    let fe = run(&s).unwrap();
    let (r, e) = (&fe.impact, fe.equivalent.as_ref().unwrap());
    let close = |a: f64, b: f64| (a - b).abs() <= 0.02 * b.abs();
    assert!(
        close(r.peak_force, e.peak_force),
        "peak {} N vs impact {} N",
        r.peak_force,
        e.peak_force
    );
    assert!(
        close(r.max_compression, e.max_compression),
        "compression {} m vs impact {} m",
        r.max_compression,
        e.max_compression
    );
    assert!(
        close(r.contact_time, e.contact_time),
        "contact {} s vs {} s",
        r.contact_time,
        e.contact_time
    );
    assert!(r.energy.relative_error < 0.02, "{:?}", r.energy);
    // elastic: nothing stays in the bumper; the car rebounds
    assert!(
        fe.bumper_internal_energy < 1e-2 * r.energy.initial,
        "{}",
        fe.bumper_internal_energy
    );
    assert!(
        r.remaining_compression.abs() < 1e-3,
        "{}",
        r.remaining_compression
    );
    let _ = std::fs::remove_dir_all(&s.work);
}

/// Crash boxes that yield: the energy balance closes within 2 %, the
/// bumper keeps a permanent crush and its internal energy is the plastic
/// work (most of the energy it took).
#[test]
fn a_plastic_bumper_closes_its_energy_balance_and_keeps_a_crush() {
    if !ccx() {
        return;
    }
    let s = settings(
        "bumper-plastic.toml",
        Scenario::Barrier { speed: 2.2 },
        "plastic",
    );
    let fe = run(&s).unwrap();
    let r = &fe.impact;
    assert!(r.energy.relative_error < 0.02, "{:?}", r.energy);
    let kinetic = 0.5 * (30.0 + 250.0 + 1170.0) * 2.2 * 2.2;
    assert!(
        fe.bumper_internal_energy > 0.1 * kinetic,
        "{}",
        fe.bumper_internal_energy
    );
    assert!(
        r.remaining_compression > 0.01,
        "{}",
        r.remaining_compression
    );
    // the plateau bounds the force: 2 σ_y A at most 10 % above the initial yield
    let area = 0.08 * 0.08 - 0.077 * 0.077;
    assert!(r.peak_force < 1.1 * 2.0 * 44e6 * area, "{}", r.peak_force);
    let _ = std::fs::remove_dir_all(&s.work);
}

/// Bad settings are refused before CalculiX starts.
#[test]
fn bad_runs_are_refused_with_the_parameter_named() {
    let mut s = settings(
        "bumper-elastic.toml",
        Scenario::Barrier { speed: 2.2 },
        "bad",
    );
    s.increment = Some(1e-300);
    let e = run(&s).unwrap_err().to_string();
    assert!(e.contains("increments (duration / increment)"), "{e}");
    s.increment = Some(f64::NAN);
    assert!(run(&s).unwrap_err().to_string().contains("increment (s)"));
    s.increment = None;
    s.solver = "no-such-ccx-here".into();
    let e = run(&s).unwrap_err().to_string();
    assert!(e.contains("no-such-ccx-here: cannot start"), "{e}");
    let _ = std::fs::remove_dir_all(&s.work);
}

/// Issue 48 item 20: the examples' crash-box material is an equivalent one,
/// and what docs/fe.md says it stands for follows from the files: E = k L / A
/// gives 1.0 MN/m a box, σy = F / A the 18.84 kN crush force, which is
/// Abramowicz and Jones's mean folding force `13.06 σ0 t^(5/3) C^(1/3)` of the
/// 80 × 80 × 1.5 mm steel box at σ0 = 170 MPa; the density gives its mass.
#[test]
fn the_crash_boxes_equivalent_material_is_what_the_docs_say() {
    let docs = std::fs::read_to_string(root().join("docs/fe.md")).unwrap();
    assert!(docs.contains("### The crash boxes' material"), "docs/fe.md");
    for file in ["bumper-elastic.toml", "bumper-plastic.toml"] {
        let mesh = BumperMesh::read(&root().join("examples/fe").join(file)).unwrap();
        let boxes = &mesh.crash_boxes;
        let area = boxes.section.area();
        let stiffness = boxes.material.youngs_modulus * area / boxes.length;
        assert!(
            (stiffness / 1.0e6 - 1.0).abs() < 0.01,
            "{file}: k = {stiffness} N/m"
        );
        let mass = area * boxes.length * boxes.material.density;
        assert!((mass - 0.555).abs() < 0.005, "{file}: box mass {mass} kg");
        assert!(docs.contains("320 MPa") && docs.contains("0.555 kg"));
        if let Some([yield_stress, _]) = boxes.material.yield_curve.first() {
            let crush = yield_stress * area;
            let (t, c) = (boxes.section.wall, boxes.section.depth);
            let folding = 13.06 * 170e6 * t.powf(5.0 / 3.0) * c.powf(1.0 / 3.0);
            assert!(
                (crush / 18.84e3 - 1.0).abs() < 0.01,
                "{file}: F = {crush} N"
            );
            assert!((folding / crush - 1.0).abs() < 0.01, "{file}: {folding} N");
            assert!(docs.contains("18.84 kN") && docs.contains("40 MPa"));
        }
    }
}
