//! The campaign cases of issues 34 and 48: a response named like a
//! factor, an attempt count at the end of its type, a damaged point
//! folder, two point files of one name; each refused with an error naming
//! the key or the state record it is about. A journal of a smaller design
//! refused by `run`, and a header written without its padding that
//! survives a killed controller. (A journal cut at a record's end:
//! `state::tests` in the campaign crate.)

use super::{Fake, Faults, NO_FAULTS, path, run};
use crate::util::{assert_contains, assert_user_error, bumpsim, text};
use bumpsim_campaign::journal::frame;

/// A response named like a factor or derived quantity would give the
/// table two columns of one name (`doe fit` refused it only at collect).
#[test]
fn a_response_named_like_a_factor_is_refused_naming_both() {
    let fake = Fake::new("campaign-case-names", 0, &NO_FAULTS, "local");
    let campaign = std::fs::read_to_string(fake.dir.join("campaign.toml")).unwrap();
    for (name, other) in [("a", "factor"), ("y", "derived quantity")] {
        let file = fake.dir.join(format!("{name}.toml"));
        let named = format!("name = \"{name}\"");
        std::fs::write(&file, campaign.replace("name = \"y_max\"", &named)).unwrap();
        let folder = fake.dir.join(name);
        let out = bumpsim(&["campaign", "init", path(&file), "-o", path(&folder)]);
        assert_user_error(
            &out,
            &format!(
                "response[1] '{name}': named like the {other} '{name}' ({}): the table would have two columns '{name}'",
                if name == "a" {
                    "design.factors"
                } else {
                    "derived"
                }
            ),
        );
        assert!(!folder.exists(), "{name}: nothing written");
    }
}

/// `attempts = 4294967295` in a state record (the end of its type: one
/// more wrapped to 0, or panicked) is refused naming the line, the key and
/// the limit; so is `retries = 4294967295` in the campaign file.
#[test]
fn an_attempt_count_beyond_its_limit_is_refused_naming_key_and_limit() {
    let fake = Fake::new("campaign-case-attempts", 0, &NO_FAULTS, "local");
    let c = fake.campaign();
    let journal = c.join("state.journal");
    let text = std::fs::read_to_string(&journal).unwrap();
    let edited: String = text
        .lines()
        .map(|line| match line.split_once(' ') {
            Some((_, json)) if json.contains("\"run\":2,") => {
                frame(&json.replace("\"attempts\":0", "\"attempts\":4294967295"))
            }
            _ => format!("{line}\n"),
        })
        .collect();
    std::fs::write(&journal, edited).unwrap();
    for command in ["status", "run"] {
        assert_user_error(
            &bumpsim(&["campaign", command, path(&c)]),
            "state.journal: the campaign's state is damaged: line 3: run 2: attempts 4294967295: at most 1000000",
        );
    }
    assert_eq!(fake.invocations("0001"), 0, "nothing ran");
    let campaign = std::fs::read_to_string(fake.dir.join("campaign.toml")).unwrap();
    let file = fake.dir.join("retries.toml");
    std::fs::write(
        &file,
        campaign.replace("retries = 2", "retries = 4294967295"),
    )
    .unwrap();
    let out = bumpsim(&[
        "campaign",
        "init",
        path(&file),
        "-o",
        path(&fake.dir.join("r")),
    ]);
    assert_user_error(&out, "executor.retries: 4294967295: at most 100");
}

/// A point folder that lost its deck is named by the state record that
/// points to it (the journal's line), not only by the deck's path.
#[test]
fn a_damaged_point_folder_is_named_by_its_state_record() {
    let fake = Fake::new("campaign-case-folder", 0, &NO_FAULTS, "local");
    let c = fake.campaign();
    std::fs::remove_file(c.join("points/0002/in.csv")).unwrap();
    let out = bumpsim(&["campaign", "run", path(&c)]);
    assert_user_error(&out, "state.journal:3: run 2: its point folder");
    assert_user_error(&out, "points/0002 is damaged (in.csv: No such file");
    assert_user_error(&out, "`bumpsim campaign init CAMPAIGN.toml -o");
    assert_eq!(fake.invocations("0001"), 0, "nothing ran");
}

/// `campaign init` with a standard output that cannot be printed to (`>
/// /dev/full`) is refused before the campaign folder is created: it said
/// "no output was written" with the whole folder in place (hostile pass of
/// issue 34).
#[test]
fn an_unprintable_standard_output_leaves_no_campaign_folder() {
    let fake = Fake::new("campaign-case-dev-full", 0, &NO_FAULTS, "local");
    let folder = fake.dir.join("full");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_bumpsim"))
        .args(["campaign", "init"])
        .arg(fake.dir.join("campaign.toml"))
        .arg("-o")
        .arg(&folder)
        .stdout(std::fs::File::create("/dev/full").unwrap())
        .output()
        .unwrap();
    assert_user_error(&out, "cannot print the results");
    assert!(!folder.exists(), "a refused init left its folder");
}

/// `[regress] responses = ["y_max", "y_max"]` was accepted (hostile pass of
/// 2026-11-26, finding 16): the regression would fit one response twice;
/// refused naming the key and the response, with no campaign folder.
#[test]
fn a_response_listed_twice_for_the_regression_is_refused_naming_the_key() {
    let fake = Fake::new("campaign-case-regress-twice", 0, &NO_FAULTS, "local");
    let campaign = std::fs::read_to_string(fake.dir.join("campaign.toml")).unwrap();
    let file = fake.dir.join("twice.toml");
    let regress = "\n[regress]\nresponses = [\"y_max\", \"y_max\"]\n";
    std::fs::write(&file, format!("{campaign}{regress}")).unwrap();
    let folder = fake.dir.join("twice");
    let out = bumpsim(&["campaign", "init", path(&file), "-o", path(&folder)]);
    assert_user_error(&out, "regress.responses");
    assert_user_error(&out, "'y_max' is listed twice");
    assert!(!folder.exists(), "nothing written");
}

/// A file listed twice in `template.files`, or a copied file named like
/// the deck, was written twice into each point folder: init failed with
/// "cannot write: File exists (os error 17)" from its hidden staging
/// folder (issue 48, item 13); refused naming the campaign file, both
/// keys and the name, with no campaign folder.
#[test]
fn two_point_files_of_one_name_are_refused_naming_the_campaign_file_and_both_keys() {
    let fake = Fake::new("campaign-case-files-twice", 0, &NO_FAULTS, "local");
    let campaign = std::fs::read_to_string(fake.dir.join("campaign.toml")).unwrap();
    std::fs::write(fake.dir.join("extra.csv"), "x\n").unwrap();
    std::fs::write(fake.dir.join("in.csv"), "x\n").unwrap();
    let cases = [
        (
            "twice",
            "files = [\"extra.csv\", \"./extra.csv\"]",
            "twice.toml: template.files[2]: 'extra.csv' is also the file of template.files[1]",
        ),
        (
            "deck",
            "files = [\"in.csv\"]",
            "deck.toml: template.files[1]: 'in.csv' is also the file of template.deck",
        ),
    ];
    for (name, files, needle) in cases {
        let file = fake.dir.join(format!("{name}.toml"));
        let deck = format!("deck = \"in.csv\"\n{files}");
        std::fs::write(&file, campaign.replace("deck = \"in.csv\"", &deck)).unwrap();
        let folder = fake.dir.join(name);
        let out = bumpsim(&["campaign", "init", path(&file), "-o", path(&folder)]);
        assert_user_error(&out, needle);
        assert_user_error(&out, "each file of a point folder needs a name of its own");
        assert!(!folder.exists(), "{name}: nothing written");
    }
}

/// A journal holding the 4 points of a smaller design (its header and
/// records valid) in a campaign of 5: `run` ended "4 points done, 0
/// failed" and never ran point 5 (issue 48, item 7). Refused, naming both
/// counts and `repair`, which rebuilds the state of the 5 points.
#[test]
fn a_journal_of_a_smaller_design_is_refused_by_run() {
    let fake = Fake::new("campaign-case-smaller", 1, &NO_FAULTS, "local");
    let c = fake.campaign();
    let journal = c.join("state.journal");
    let text_now = std::fs::read_to_string(&journal).unwrap();
    let lines: Vec<&str> = text_now.lines().collect();
    assert_eq!(lines.len(), 1 + 5);
    let head = lines[0].split_once(' ').unwrap().1;
    let smaller = head.replace("\"points\":5,\"records\":5", "\"points\":4,\"records\":4");
    assert_ne!(smaller, head);
    let kept: String = lines[1..5].iter().map(|l| format!("{l}\n")).collect();
    std::fs::write(&journal, frame(&smaller) + &kept).unwrap();
    let out = bumpsim(&["campaign", "run", path(&c)]);
    assert_user_error(
        &out,
        "state.journal: the campaign's state is damaged: it holds 4 points (header, line 1) where the design of campaign.toml has 5",
    );
    assert_user_error(&out, "`bumpsim campaign repair");
    assert_eq!(fake.invocations("0001"), 0, "nothing ran");
    run(&["campaign", "repair", path(&c)]);
    let out = run(&["campaign", "run", path(&c)]);
    assert_contains(&text(&out.stdout), &["5 points done, 0 failed"]);
    assert_eq!(fake.invocations("0005"), 1);
}

/// A valid header written without its space padding (checksum right) was
/// rewritten in place at its padded length over the first point's
/// record: after a kill -9 of the controller, `status` said "line 2: not
/// a journal record" until a `repair` (issue 48, item 6). The journal is
/// compacted into a padded one instead; the killed campaign resumes.
#[test]
fn a_header_without_its_padding_survives_a_killed_controller() {
    let faults = Faults {
        sleep: 0.4,
        ..NO_FAULTS
    };
    let fake = Fake::new("campaign-case-unpadded", 4, &faults, "local");
    let c = fake.campaign();
    let journal = c.join("state.journal");
    let text_now = std::fs::read_to_string(&journal).unwrap();
    let (head, rest) = text_now.split_once('\n').unwrap();
    let json = head.split_once(' ').unwrap().1.replace(' ', "");
    std::fs::write(&journal, frame(&json) + rest).unwrap();
    run(&["campaign", "status", path(&c)]);
    let mut controller = fake.spawn_run(&[]);
    fake.wait_done(2);
    controller.kill().unwrap(); // SIGKILL
    controller.wait().unwrap();
    let out = run(&["campaign", "status", path(&c)]);
    assert_contains(&text(&out.stdout), &["done"]);
    let out = run(&["campaign", "run", path(&c)]);
    assert_contains(&text(&out.stdout), &["8 points done, 0 failed"]);
    for r in 1..=8 {
        assert_eq!(fake.invocations(&format!("{r:04}")), 1, "run {r}");
    }
}
