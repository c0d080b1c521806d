//! Numbers in the fixed-width text that solvers print (CalculiX `.dat` and
//! `.frd`, LS-DYNA's ASCII time histories): the one rule that splits a line
//! into its words when numbers touch.
//!
//! A solver writing `E` numbers in fixed-width fields leaves no blank before
//! a negative one: `1.0E-03-2.0E-04` is two numbers, `x-1.2E+01` a label and
//! a number. A line is therefore split before every sign that is not an
//! exponent's. A sign is an exponent's only when it follows an exponent
//! letter (`E`, `e`, or FORTRAN's `D`, `d`) that itself follows a digit or a
//! decimal point: the sign in `1.5E-03` or `2.D+01` stays, the one in
//! `time-1.0` or `node-5` (a letter before a letter) splits.
//!
//! ```
//! use bumpsim_core::fixed_width::words;
//! assert_eq!(words(" 1 1.0E-03-2.0E-04"), ["1", "1.0E-03", "-2.0E-04"]);
//! assert_eq!(words("x-1.2E+01 time-1.0"), ["x", "-1.2E+01", "time", "-1.0"]);
//! ```

/// The words of `line` (split at blanks), with touching numbers separated:
/// a blank goes before every `+` or `-` that is not an exponent's.
pub fn words(line: &str) -> Vec<String> {
    let mut spaced = String::with_capacity(line.len() + 8);
    let (mut before, mut previous) = (' ', ' ');
    for c in line.chars() {
        if matches!(c, '-' | '+') && !is_exponent(before, previous) {
            spaced.push(' ');
        }
        spaced.push(c);
        (before, previous) = (previous, c);
    }
    spaced.split_whitespace().map(str::to_string).collect()
}

/// Whether a sign after `previous` (itself after `before`) is an
/// exponent's: `previous` an exponent letter after a digit or a point.
fn is_exponent(before: char, previous: char) -> bool {
    matches!(previous, 'E' | 'e' | 'D' | 'd') && (before.is_ascii_digit() || before == '.')
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cases of the two splitters this one replaces: the CalculiX
    /// `.dat` rows (any exponent letter, `D` included) and the LS-DYNA
    /// lines (labels touching numbers, a letter-`e` word before a sign).
    #[test]
    fn touching_numbers_split_and_exponents_stay() {
        let cases: [(&str, &[&str]); 10] = [
            (
                "  1 1.0E-03-2.0E-04 0.0",
                &["1", "1.0E-03", "-2.0E-04", "0.0"],
            ),
            (
                "   1001 0.0000E+00-1.2340E-03",
                &["1001", "0.0000E+00", "-1.2340E-03"],
            ),
            ("1.0e-3+2.0e+4", &["1.0e-3", "+2.0e+4"]),
            ("1.0D-03-2.0d+01", &["1.0D-03", "-2.0d+01"]),
            ("1.E-03-2.E+00", &["1.E-03", "-2.E+00"]),
            ("x-1.2E+01 y 2.0E-03", &["x", "-1.2E+01", "y", "2.0E-03"]),
            ("time-1.0 node-5", &["time", "-1.0", "node", "-5"]),
            (" -1.5E+02", &["-1.5E+02"]),
            (
                "  2  1.500000E+03  0.000000E+00",
                &["2", "1.500000E+03", "0.000000E+00"],
            ),
            ("", &[]),
        ];
        for (line, expected) in cases {
            assert_eq!(words(line), expected, "{line:?}");
        }
    }
}
