//! The verdict against the regulation: a bumper that bottoms (issue 45
//! item 1) and what each protocol requires and what of it is judged (item 5).

use super::*;

/// Issue 45 item 1: the bundled car's bumper is crushed through its 80 mm
/// in the RCAR structural test. It used to crush 261.8 mm with the rails
/// at 49.7 kN judged a pass; now its segments block at their depth
/// (`damageability.bumper_stroke`, with the default block stiffness of
/// 5e7 N/m over the 10 segments), the force goes on into the rails and the
/// verdict names the instant.
#[test]
fn a_bumper_crushed_through_its_depth_blocks_and_the_verdict_names_the_instant() {
    let dir = scratch("verdict-bottomed");
    let json = dir.join("verdict.json");
    let run = example("rcar-structural-front", &["--json", json.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    assert_contains(
        &text(&run.stdout),
        &[
            "rcar-structural-front: the bumper bottomed at segment 10 (y = 675 mm) at t = ",
            "on the blocked load path",
        ],
    );
    let document: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let test = &document["verdict"]["tests"][0];
    let bottomed = &test["bottomed"];
    assert_eq!(bottomed["segment"], 9, "{bottomed}");
    let at = bottomed["time"].as_f64().unwrap();
    assert!(at > 0.0 && at < 0.1, "{at}");
    let criterion = |name: &str| {
        test["criteria"]
            .as_array()
            .unwrap()
            .iter()
            .find(|c| c["name"] == name)
            .unwrap()
            .clone()
    };
    let (stroke, rail) = (criterion("bumper stroke"), criterion("rail force"));
    let crush = stroke["value"].as_f64().unwrap();
    let rail_force = rail["value"].as_f64().unwrap();
    // the block's compliance: what it carries past the depth goes into the
    // rails, so its force stays below the largest rail force
    let (depth, k_block) = (0.080, 5e7 / 10.0);
    assert!(crush > depth, "{crush}");
    assert!(
        (crush - depth) * k_block <= rail_force,
        "{crush} {rail_force}"
    );
    // above the whole bumper's 120 kN plateau, all it could pass unblocked
    assert!(rail_force > 120e3, "{rail_force}");
    assert!(
        rail["detail"]
            .as_str()
            .unwrap()
            .contains("after the bumper and the left crash box bottomed: on the blocked load path"),
        "{rail}"
    );
    // its crash boxes block too (damageability.crash_box_stroke = 40 mm,
    // the default 1e8 N/m a box): the left one bottoms after the bumper,
    // and compresses past its 40 mm by no more than the block's compliance
    // at the rail force; the rail takes more than the box's 3e6 N/m could
    // pass at 40 mm (120 kN)
    assert_contains(
        &text(&run.stdout),
        &["rcar-structural-front: the left crash box (y = 500 mm) bottomed at t = "],
    );
    let boxed = &test["box_bottomed"];
    assert_eq!(boxed["side"], "left", "{boxed}");
    let box_at = boxed["time"].as_f64().unwrap();
    assert!(box_at > at && box_at < 0.1, "{box_at}");
    let used = criterion("crash-box stroke")["value"].as_f64().unwrap();
    assert!(used > 0.040, "{used}");
    assert!(used <= 0.040 + rail_force / 1e8, "{used} {rail_force}");
    assert!(rail_force > 3e6 * 0.040, "{rail_force}");
}

/// Issue 45 item 5: what the regulation requires and what of it is judged
/// reaches the table, the JSON, the report and `--list`.
#[test]
fn the_verdict_lists_what_the_regulations_require_and_what_is_judged() {
    let dir = scratch("verdict-requirements");
    let json = dir.join("verdict.json");
    let report = dir.join("report");
    let run = example(
        "part581-barrier-front,rcar-bumper-front",
        &[
            "--json",
            json.to_str().unwrap(),
            "--report",
            report.to_str().unwrap(),
        ],
    );
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    let out = text(&run.stdout);
    assert_contains(
        &out,
        &[
            "what the regulations require: judged by the model / by a proxy / NOT JUDGED",
            "581.5(c)(1) each lamp",
            "proxy (the clearances to the lamps the car file lists)",
            "581.5(c)(4) exhaust system free of leaks and constriction: NOT JUDGED: the engineer must check it",
            "581.5(c)(9)",
            "cmvss215",
            "RCAR barrier spec. §2.2",
            "model (rail force below the rails' yield)",
            "[wording not checked against the text]",
        ],
    );
    assert!(!out.contains("  r42 ("), "r42 was not run:\n{out}");
    let document: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let part581 = document["verdict"]["requirements"]["part581"]
        .as_array()
        .unwrap();
    let clauses: Vec<&str> = part581
        .iter()
        .map(|r| r["clause"].as_str().unwrap())
        .collect();
    let expected: Vec<String> = (1..=9).map(|i| format!("581.5(c)({i})")).collect();
    assert_eq!(clauses, expected);
    assert_eq!(part581[0]["judgement"], "proxy");
    assert_eq!(part581[0]["criterion"], "clearance");
    assert_eq!(part581[0]["verified"], true);
    assert_eq!(part581[3]["judgement"], "not judged");
    assert!(part581[3]["why"].as_str().unwrap().contains("exhaust"));
    let rcar = document["verdict"]["requirements"]["rcar-bumper"]
        .as_array()
        .unwrap();
    assert!(rcar.iter().any(|r| r["judgement"] == "model"
        && r["criterion"] == "crash-box-stroke"
        && r["by"].as_str().unwrap().contains("usable stroke")));
    let html = std::fs::read_to_string(report.join("index.html")).unwrap();
    assert_contains(&html, &["What is judged and what is not", "581.5(c)(7)"]);
    let list = text(&verdict(&["--list"]).stdout);
    assert_contains(
        &list,
        &[
            "requires (UN R42 paragraph 6",
            "judged by a proxy: the clearances to the lamps the car file lists; a lamp nothing reaches",
            "not judged: the exhaust is not modelled",
            "the engineer must check it",
        ],
    );
}

/// Issue 45 item 2: `--sequence` runs 49 CFR 581's front tests on one car;
/// the barrier test inherits the set the pendulum and corners left and says
/// what it changes against the test run alone; without it no test inherits.
#[test]
fn a_sequence_names_what_each_test_inherited_and_changed() {
    let dir = scratch("verdict-sequence");
    let json = dir.join("verdict.json");
    let run = example("part581", &["--sequence", "--json", json.to_str().unwrap()]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    assert_contains(
        &text(&run.stdout),
        &[
            "part581-barrier-front in sequence after part581-pendulum-front, part581-corner-front-left, part581-corner-front-right: inherits a permanent set of up to ",
            "against the test run alone, the inherited damage changes: ",
            "part581-barrier-front: run in sequence on the same car after ",
        ],
    );
    let document: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let tests = document["verdict"]["tests"].as_array().unwrap();
    let barrier = tests
        .iter()
        .find(|t| t["test"]["name"] == "part581-barrier-front")
        .unwrap();
    let inherited = &barrier["inherited"];
    assert_eq!(
        inherited["from"].as_array().unwrap().len(),
        3,
        "{inherited}"
    );
    assert!(inherited["set"].as_f64().unwrap() > 0.01, "{inherited}");
    assert!(!inherited["changes"].as_array().unwrap().is_empty());
    assert!(tests[0]["inherited"].is_null());
    let alone = example("part581-barrier-front", &[]);
    assert!(!text(&alone.stdout).contains("in sequence after"));
}

/// Issue 45 item 8: the target search of the RCAR structural test finds no
/// bumper, and says which criterion rules out every one, the energy budget
/// and what would have to change.
#[test]
fn a_target_that_finds_nothing_says_why_and_what_would_change() {
    let run = example("rcar-structural-front", &["--target"]);
    assert_eq!(run.status.code(), Some(0), "{}", text(&run.stderr));
    assert_contains(
        &text(&run.stdout),
        &[
            "no bumper in the range passes: rail force in rcar-structural-front fails at every stiffness",
            "the crash boxes store 4.80 kJ up to their usable stroke",
            "This is the car's load path, not the bumper",
            "reported, not judged: the structural test crushes the bumper",
        ],
    );
}
