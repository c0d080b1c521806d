//! Unit systems, the model axis and node placement shared by all decks.
//!
//! FE codes have no units; a deck is consistent in one system. Factors
//! convert SI to the deck's system (value in deck = SI value × factor):
//!
//! | system | mass | length | time | force | stiffness | damping | velocity |
//! |---|---|---|---|---|---|---|---|
//! | `si` | kg | m | s | N | N/m | N·s/m | m/s |
//! | `mm-s-t` | t | mm | s | N | N/mm | N·s/mm | mm/s |
//! | `mm-ms-kg` | kg | mm | ms | kN | kN/mm | kN·ms/mm | mm/ms |
//!
//! The lumped masses sit on a line: m_i at `origin + (i − 1) · spacing · axis`,
//! where the axis is the model's +x, the direction of the bumper force on m1
//! (rearwards into the car). Axes are global ±x, ±y, ±z so that "translation
//! along the axis only" is a plain constraint on the two other directions.

use std::fmt;
use std::str::FromStr;

/// A consistent unit system of an FE deck.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum UnitSystem {
    /// kg, m, s, N.
    #[default]
    Si,
    /// tonne, mm, s, N.
    MmSTonne,
    /// kg, mm, ms, kN.
    MmMsKg,
}

impl UnitSystem {
    /// Command-line name.
    pub fn name(self) -> &'static str {
        match self {
            UnitSystem::Si => "si",
            UnitSystem::MmSTonne => "mm-s-t",
            UnitSystem::MmMsKg => "mm-ms-kg",
        }
    }

    /// Unit symbols (mass, length, time, force) for deck comments.
    pub fn symbols(self) -> [&'static str; 4] {
        match self {
            UnitSystem::Si => ["kg", "m", "s", "N"],
            UnitSystem::MmSTonne => ["t", "mm", "s", "N"],
            UnitSystem::MmMsKg => ["kg", "mm", "ms", "kN"],
        }
    }

    /// (mass, length, time, force) factors from SI.
    fn base(self) -> [f64; 4] {
        match self {
            UnitSystem::Si => [1.0, 1.0, 1.0, 1.0],
            UnitSystem::MmSTonne => [1e-3, 1e3, 1.0, 1.0],
            UnitSystem::MmMsKg => [1.0, 1e3, 1e3, 1e-3],
        }
    }

    /// Mass factor (kg → deck).
    pub fn mass(self) -> f64 {
        self.base()[0]
    }

    /// Length factor (m → deck).
    pub fn length(self) -> f64 {
        self.base()[1]
    }

    /// Time factor (s → deck).
    pub fn time(self) -> f64 {
        self.base()[2]
    }

    /// Force factor (N → deck).
    pub fn force(self) -> f64 {
        self.base()[3]
    }

    /// Stiffness factor (N/m → deck force / length).
    pub fn stiffness(self) -> f64 {
        self.force() / self.length()
    }

    /// Damping factor (N·s/m → deck force · time / length).
    pub fn damping(self) -> f64 {
        self.force() * self.time() / self.length()
    }

    /// Velocity factor (m/s → deck length / time).
    pub fn velocity(self) -> f64 {
        self.length() / self.time()
    }
}

impl fmt::Display for UnitSystem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A unit-system or axis name that is not one of the choices.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown {what} '{given}': expected {expected}")]
pub struct UnknownName {
    /// `unit system` or `axis`.
    pub what: &'static str,
    /// The text given.
    pub given: String,
    /// The choices.
    pub expected: &'static str,
}

impl FromStr for UnitSystem {
    type Err = UnknownName;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "si" => Ok(UnitSystem::Si),
            "mm-s-t" => Ok(UnitSystem::MmSTonne),
            "mm-ms-kg" => Ok(UnitSystem::MmMsKg),
            other => Err(UnknownName {
                what: "unit system",
                given: other.into(),
                expected: "si, mm-s-t or mm-ms-kg",
            }),
        }
    }
}

/// A global axis with a sign: the model's +x direction in the deck.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Axis {
    /// 0 = x, 1 = y, 2 = z.
    pub component: usize,
    /// +1.0 or −1.0.
    pub sign: f64,
}

impl Default for Axis {
    fn default() -> Self {
        Axis {
            component: 0,
            sign: 1.0,
        }
    }
}

impl Axis {
    /// The unit vector.
    pub fn vector(self) -> [f64; 3] {
        let mut v = [0.0; 3];
        v[self.component] = self.sign;
        v
    }

    /// The 1-based degree of freedom (1 = x, 2 = y, 3 = z).
    pub fn dof(self) -> usize {
        self.component + 1
    }

    /// The two other 1-based translational degrees of freedom.
    pub fn other_dofs(self) -> [usize; 2] {
        match self.component {
            0 => [2, 3],
            1 => [1, 3],
            _ => [1, 2],
        }
    }
}

impl fmt::Display for Axis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let sign = if self.sign > 0.0 { '+' } else { '-' };
        write!(f, "{sign}{}", ['x', 'y', 'z'][self.component])
    }
}

impl FromStr for Axis {
    type Err = UnknownName;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let (sign, name) = match s.as_bytes().first() {
            Some(b'-') => (-1.0, &s[1..]),
            Some(b'+') => (1.0, &s[1..]),
            _ => (1.0, s),
        };
        let component = ["x", "y", "z"]
            .iter()
            .position(|&c| c.eq_ignore_ascii_case(name))
            .ok_or_else(|| UnknownName {
                what: "axis",
                given: s.into(),
                expected: "+x, -x, +y, -y, +z or -z",
            })?;
        Ok(Axis { component, sign })
    }
}

/// Where the masses go and in which units the deck is written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layout {
    /// Deck units.
    pub units: UnitSystem,
    /// The model's +x in the deck.
    pub axis: Axis,
    /// Position of m1, m (SI; converted when written).
    pub origin: [f64; 3],
    /// Distance between neighbouring masses, m (SI). Discrete elements need
    /// distinct nodes; the distance has no effect on the linear physics.
    pub spacing: f64,
}

impl Default for Layout {
    fn default() -> Self {
        Layout {
            units: UnitSystem::Si,
            axis: Axis::default(),
            origin: [0.0; 3],
            spacing: 0.1,
        }
    }
}

impl Layout {
    /// Position of mass `index` (0-based) in deck length units.
    pub fn node_position(&self, index: usize) -> [f64; 3] {
        let along = index as f64 * self.spacing;
        let axis = self.axis.vector();
        std::array::from_fn(|c| (self.origin[c] + along * axis[c]) * self.units.length())
    }
}

/// Formats a number into at most `width − 1` characters (one blank column
/// stays free between fields) with the smallest rounding error among plain,
/// fixed-decimal and scientific forms. Real fields always carry a `.` or an
/// exponent, so every real field reads as a real.
pub fn real_field(value: f64, width: usize) -> String {
    let room = width - 1;
    let value = value + 0.0; // no "-0.0"
    let plain = if value.fract() == 0.0 && value.abs() < 1e15 {
        format!("{value:.1}")
    } else {
        format!("{value}")
    };
    let fixed = (0..room)
        .map(|d| format!("{value:.d$}"))
        .filter(|t| t.contains('.'));
    let scientific = (0..room).map(|p| format!("{value:.p$e}"));
    let best = std::iter::once(plain)
        .chain(fixed)
        .chain(scientific)
        .filter(|t| t.len() <= room)
        .min_by(|a, b| rounding_error(a, value).total_cmp(&rounding_error(b, value)))
        .unwrap_or_else(|| format!("{value:e}"));
    format!("{best:>width$}")
}

fn rounding_error(text: &str, value: f64) -> f64 {
    text.parse::<f64>()
        .map_or(f64::INFINITY, |v| (v - value).abs())
}

/// Formats an integer right-aligned in `width` columns.
pub fn int_field(value: u64, width: usize) -> String {
    format!("{value:>width$}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn real_fields_keep_precision_within_their_width() {
        let cases = [
            (4.75e5, 10, 1e-15),
            (197.1234567, 10, 1e-6),
            (6.46e6, 10, 1e-15),
            (1.0 / 3.0, 10, 1e-6),
            (-1.234567e-7, 10, 5e-4),
            (0.1, 16, 1e-15),
        ];
        for (value, width, tolerance) in cases {
            let text = real_field(value, width);
            assert_eq!(text.len(), width, "{text:?}");
            assert!(text.starts_with(' '), "{text:?}");
            let back: f64 = text.trim().parse().unwrap();
            assert_relative_eq!(back, value, max_relative = tolerance);
        }
        assert_eq!(real_field(1670.0, 10), "    1670.0");
    }

    #[test]
    fn unit_factors_are_consistent() {
        for units in [UnitSystem::Si, UnitSystem::MmSTonne, UnitSystem::MmMsKg] {
            // F = m a in every system: force factor = mass × length / time²
            assert_relative_eq!(
                units.force(),
                units.mass() * units.length() / units.time().powi(2),
                max_relative = 1e-12
            );
        }
    }

    #[test]
    fn axes_parse_and_place_nodes() {
        let axis: Axis = "-y".parse().unwrap();
        assert_eq!(axis.other_dofs(), [1, 3]);
        let layout = Layout {
            units: UnitSystem::MmSTonne,
            axis,
            origin: [1.0, 2.0, 0.5],
            spacing: 0.1,
        };
        assert_eq!(layout.node_position(2), [1000.0, 1800.0, 500.0]);
        assert!("w".parse::<Axis>().is_err());
        assert!("imperial".parse::<UnitSystem>().is_err());
    }
}
