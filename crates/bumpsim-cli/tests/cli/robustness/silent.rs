//! Silent acceptances of the hostile pass: input that ran with exit 0
//! (a junk EV5 file, a Sobol base that is not a power of two, ...) is
//! refused with exit 2 naming the file, line, key or flag and the value,
//! or the output says what it cannot compute.

use super::{examples, user_error};

/// Random bytes or an empty file named `.EV5` listed "0 channels".
#[test]
fn a_junk_or_empty_ev5_file_is_no_test() {
    let dir = examples("silent-ev5");
    let junk: Vec<u8> = (0..1000u32).map(|i| (i * 7919 % 251) as u8).collect();
    std::fs::write(dir.join("j.EV5"), junk).unwrap();
    std::fs::write(dir.join("e.EV5"), b"").unwrap();
    for file in ["j.EV5", "e.EV5"] {
        let needle = format!("{file}: not an NHTSA EV5 test");
        user_error(&dir, &["signal", "info", file], &needle);
    }
}
