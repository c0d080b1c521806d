//! A damaged, truncated or lost state: refused by every command (never read
//! as fewer points), and rebuilt by `campaign repair` from the point
//! folders without running a finished point again.

use super::{Fake, Faults, NO_FAULTS, path, point, run};
use crate::util::{assert_contains, assert_user_error, bumpsim, text};

/// Every command refuses the state, naming the damage and `repair`.
fn refused(fake: &Fake, damage: &str) {
    let campaign = fake.campaign();
    let c = path(&campaign);
    for command in ["status", "run", "collect", "abort"] {
        assert_user_error(&bumpsim(&["campaign", command, c]), damage);
    }
    // and init over it does not drop it silently
    let campaign = fake.dir.join("campaign.toml");
    let out = bumpsim(&["campaign", "init", path(&campaign), "-o", c]);
    assert_user_error(&out, "`bumpsim campaign repair");
}

/// A finished campaign (5 done, run 4 failed for good) whose journal is
/// altered, then truncated mid-record after 3 of its 6 points: refused
/// each time; `repair` keeps every done point from its exit marker and
/// outputs, and the next run runs none of them again.
#[test]
fn a_corrupt_or_truncated_state_is_refused_and_repaired_without_rerunning() {
    let faults = Faults {
        fail_always: &["0004"],
        ..NO_FAULTS
    };
    let fake = Fake::new("campaign-repair", 2, &faults, "local");
    let c = fake.campaign();
    run(&["campaign", "run", path(&c)]);
    let journal = c.join("state.journal");
    let whole = std::fs::read_to_string(&journal).unwrap();
    // run 1's record (line 2) altered by hand or by the disk
    std::fs::write(&journal, whole.replacen("\"done\"", "\"pending\"", 1)).unwrap();
    refused(&fake, "line 2: checksum mismatch");
    let out = run(&["campaign", "repair", path(&c)]);
    assert_contains(
        &text(&out.stdout),
        &[
            "5 done kept, 0 in flight adopted, 0 re-queued, 1 failed",
            "(5 records read from the old state)",
        ],
    );
    let out = run(&["campaign", "run", path(&c)]);
    assert_contains(
        &text(&out.stdout),
        &["5 points done, 1 failed (0 tasks submitted by this run)"],
    );
    // cut in the middle of run 4's record
    let text_now = std::fs::read_to_string(&journal).unwrap();
    let cut: usize = text_now.lines().take(4).map(|l| l.len() + 1).sum::<usize>() + 20;
    std::fs::write(&journal, &text_now[..cut]).unwrap();
    refused(
        &fake,
        "records of 3 of its 6 points (truncated?): none of run 4",
    );
    let out = run(&["campaign", "repair", path(&c)]);
    assert_contains(
        &text(&out.stdout),
        &[
            "5 done kept, 0 in flight adopted, 1 re-queued",
            "run 4: re-queued: solver exit code 3 before the repair",
        ],
    );
    // the failed point runs its remaining attempts; no other point runs again
    let out = run(&["campaign", "run", path(&c)]);
    assert_contains(
        &text(&out.stdout),
        &["5 points done, 1 failed (2 tasks submitted by this run)"],
    );
    let counts: Vec<usize> = (1..=6)
        .map(|r| fake.invocations(&format!("{r:04}")))
        .collect();
    assert_eq!(counts, [1, 1, 1, 5, 1, 1], "{}", fake.state());
    assert_contains(
        &point(&fake.state(), 4),
        &["status = \"failed\"", "attempts = 3"],
    );
    // the damaged journals are kept for a look
    let kept = std::fs::read_dir(&c)
        .unwrap()
        .filter(|e| {
            let name = e.as_ref().unwrap().file_name();
            name.to_string_lossy().starts_with("state.journal.damaged-")
        })
        .count();
    assert!(kept >= 1, "the damaged journal is kept");
    fake.collect();
    assert_eq!(fake.table().lines().count(), 1 + 5);
}

/// The controller killed mid-campaign and its state lost (cut to the
/// header): `repair` keeps the done points, adopts the tasks still
/// running and leaves the rest pending; the next run finishes the
/// campaign with every point run exactly once, in one attempt.
#[test]
fn a_state_lost_mid_campaign_is_repaired_adopting_the_running_tasks() {
    let faults = Faults {
        sleep: 1.5,
        ..NO_FAULTS
    };
    let fake = Fake::new("campaign-repair-running", 4, &faults, "local");
    let c = fake.campaign();
    let mut controller = fake.spawn_run(&[]);
    fake.wait_done(2);
    // runs 3 and 4 started with the second round (1.5 s to go)
    std::thread::sleep(std::time::Duration::from_millis(200));
    controller.kill().unwrap(); // SIGKILL
    controller.wait().unwrap();
    let journal = c.join("state.journal");
    let header = std::fs::read_to_string(&journal)
        .unwrap()
        .lines()
        .next()
        .unwrap()
        .to_string();
    std::fs::write(&journal, header + "\n").unwrap();
    assert_user_error(
        &bumpsim(&["campaign", "status", path(&c)]),
        "records of 0 of its 8 points",
    );
    let out = run(&["campaign", "repair", path(&c)]);
    let report = text(&out.stdout);
    assert_contains(&report, &["done kept, 2 in flight adopted, 0 re-queued"]);
    let out = run(&["campaign", "run", path(&c)]);
    assert_contains(&text(&out.stdout), &["8 points done, 0 failed"]);
    let state = fake.state();
    for run in 1..=8 {
        assert_eq!(
            fake.invocations(&format!("{run:04}")),
            1,
            "run {run}: {state}"
        );
        assert_contains(&point(&state, run), &["attempts = 1"]);
    }
}
