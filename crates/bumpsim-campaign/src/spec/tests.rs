//! The campaign file's checks, each refusal naming the file and key.

use super::*;

const BASE: &str = r#"
name = "t"
[design]
kind = "full"
factors = [{ name = "a", low = 1, high = 2 }, { name = "b", low = 3, high = 4 }]
[template]
file = "deck.inp"
[solver]
command = ["true"]
"#;

fn parse(extra: &str) -> Result<Spec> {
    Spec::parse(&format!("{BASE}{extra}"), Path::new("c.toml"))
}

#[test]
fn derived_are_ordered_and_unknown_names_refused() {
    let spec = parse("[derived]\nz = \"y * 2 [kg]\"\ny = \"a + b\"\n").unwrap();
    assert_eq!(
        (spec.unit_of("z").as_deref(), spec.unit_of("y")),
        (Some("kg"), None)
    );
    let order: Vec<String> = spec
        .derived_order(Path::new("c"))
        .unwrap()
        .into_iter()
        .map(|(n, _)| n)
        .collect();
    assert_eq!(order, ["y", "z"]);
    let err = parse("[derived]\ny = \"a + t_rail\"\n")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("derived.y: unknown name 't_rail' (factors: a, b)"),
        "{err}"
    );
    let err = parse("[derived]\ny = \"z\"\nz = \"y\"\n")
        .unwrap_err()
        .to_string();
    assert!(err.contains("depend on each other"), "{err}");
}

#[test]
fn bad_keys_and_values_are_named() {
    let err = parse("colour = 1\n").unwrap_err().to_string();
    assert!(err.contains("colour"), "{err}");
    // the identification's own limit, not a looser one of the campaign's
    let err = parse("[identify]\nstudy = \"s.toml\"\ndof = 9\n")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("identify.dof") && err.contains("1 to 8"),
        "{err}"
    );
    assert!(parse("[identify]\nstudy = \"s.toml\"\ndof = 8\n").is_ok());
    let relative = BASE.replace("[\"true\"]", "[\"./solver.sh\"]");
    let err = Spec::parse(&relative, Path::new("c.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("solver.command: './solver.sh': give an absolute path"),
        "{err}"
    );
    let err = parse("[executor]\ntime = \"2h\"\n")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("executor.time: '2h': expected a Slurm time"),
        "{err}"
    );
    let spec =
        parse("[executor]\ntime = \"0:02\"\n[executor.slurm]\ntime = \"1:00:00\"\n").unwrap();
    assert_eq!(spec.executor.local_time().map(|t| t.1.as_secs()), Some(2));
    assert_eq!(
        spec.executor.slurm_time().map(String::as_str),
        Some("1:00:00")
    );
    let err = parse("[executor]\nkind = \"pbs\"\n")
        .unwrap_err()
        .to_string();
    assert!(err.contains("executor.kind"), "{err}");
    let err =
        Spec::parse(&BASE.replace("\"full\"", "\"fuller\""), Path::new("c.toml")).unwrap_err();
    assert!(err.to_string().contains("design.kind"), "{err}");
}

/// A deck named `../../../evil.txt` reached the staging, which named
/// neither the campaign file nor the key.
#[test]
fn a_deck_name_that_is_a_path_is_refused_naming_the_key() {
    let deck = BASE.replace(
        "file = \"deck.inp\"",
        "file = \"deck.inp\"\ndeck = \"../../../evil.txt\"",
    );
    let err = Spec::parse(&deck, Path::new("c.toml"))
        .unwrap_err()
        .to_string();
    assert!(err.contains("c.toml: template.deck: "), "{err}");
    assert!(err.contains("not a plain name"), "{err}");
}

/// A file listed twice, or a deck named like a copied file, was
/// written twice into each point folder: "cannot write: File exists"
/// from the staging folder (issue 48, item 13).
#[test]
fn two_point_files_of_one_name_are_refused_naming_both_keys() {
    let spec = parse("").unwrap();
    assert_eq!(spec.point_files()[0].0, "deck.inp");
    let twice = BASE.replace(
        "file = \"deck.inp\"",
        "file = \"deck.inp\"\nfiles = [\"a/force.inc\", \"b/force.inc\"]",
    );
    let err = Spec::parse(&twice, Path::new("c.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains(
            "c.toml: template.files[2]: 'force.inc' is also the file of template.files[1]"
        ),
        "{err}"
    );
    let deck = BASE.replace(
        "file = \"deck.inp\"",
        "file = \"deck.tmpl\"\ndeck = \"force.inc\"\nfiles = [\"force.inc\"]",
    );
    let err = Spec::parse(&deck, Path::new("c.toml"))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("template.files[1]: 'force.inc' is also the file of template.deck"),
        "{err}"
    );
}
