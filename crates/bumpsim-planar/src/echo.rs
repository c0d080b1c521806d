//! A number as an error message echoes it back to the user: rounded to 12
//! significant digits, so the unit conversion's float noise (a length given
//! in mm, held in m) does not reach the message; `NaN` and infinities as
//! they are.

/// A value as an error echoes it, to 12 significant digits: 3300 mm is
/// `3.3 m`, not the conversion's `3.3000000000000003 m`.
pub(crate) struct Echo(pub(crate) f64);

impl std::fmt::Display for Echo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{:?}",
            format!("{:.11e}", self.0).parse().unwrap_or(self.0)
        )
    }
}
