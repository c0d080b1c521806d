//! Refusals that name the flag and the value as the user gave it (the
//! hostile pass's panic and unclear items): exit 2, the flag, its value.

use super::{examples, user_error};

#[test]
fn centre_points_beyond_the_limit_name_centre() {
    let dir = examples("flags-centre");
    for kind in ["ccc", "ccf", "full"] {
        user_error(
            &dir,
            &[
                "doe",
                "design",
                kind,
                "--factors",
                "A:0:1",
                "--centre",
                "99999999999",
                "-o",
                "d.csv",
            ],
            "--centre 99999999999: 99999999999 centre points: at most 1000000",
        );
    }
    assert!(!dir.join("d.csv").exists());
}
