//! The links series' `synth` request on the example series: its tests and
//! the study that names their channels, read by the study reader.

use super::*;

fn example() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/links/series.toml")
}

#[test]
fn the_example_series_makes_its_tests_and_a_links_study_of_them() {
    let made = make(&example()).unwrap();
    let names: Vec<&str> = made.tests.iter().map(|t| t.0.as_str()).collect();
    assert_eq!(names, ["B15", "B32", "B56"]);
    for (_, header, channels) in &made.tests {
        let codes: Vec<&str> = channels.iter().map(|c| c.code.as_str()).collect();
        assert_eq!(
            codes,
            ["B0LOMASU0000FOXP", "10SECMLE0000ACXP", "10SECMRI0000ACXP"]
        );
        let mass = header.iter().find(|(k, _)| k == "Mass test object 1");
        let mass: Option<f64> = mass.and_then(|(_, v)| v.parse().ok());
        assert_eq!(mass, Some(1436.0));
    }
    assert!(made.provenance.contains("# car file "));
    let [(name, study)] = made.files.as_slice() else {
        panic!("one further file: {:?}", made.files);
    };
    assert_eq!(*name, "study.toml");
    // the study reader reads it (its [links] table left out)
    let dir = std::env::temp_dir().join(format!("bumpsim-links-study-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("study.toml"), study).unwrap();
    let read = bumpsim_ident::Study::read(&dir.join("study.toml"));
    std::fs::remove_dir_all(&dir).unwrap();
    let read = read.unwrap();
    assert_eq!(read.kind.as_deref(), Some("links"));
    assert_eq!(read.case.len(), 3);
    let b56 = &read.case[2];
    assert_eq!(b56.force.path, std::path::Path::new("B56/B56.mme"));
    assert_eq!(b56.force.channel, "B0LOMASU0000FOXP");
    assert_eq!(b56.acceleration[1].channel, "10SECMRI0000ACXP");
    assert!((b56.initial_velocity - 56.0 / 3.6).abs() < 1e-12);
}
