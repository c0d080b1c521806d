//! The n-DOF chain mass-spring-damper (MSD) car model (thesis ch. 3.3, paper B;
//! spec §2).
//!
//! Masses m1..mn sit in a line; between mass j and j+1 a linear spring k_j and
//! a viscous damper c_j act in parallel. The external force f(t) acts on m1;
//! the chain is free (no ground):
//!
//! ```text
//! M x'' + C x' + K x = e1 f(t),   M = diag(m)
//! K11 = k1,  Kjj = k(j-1) + kj,  Knn = k(n-1),  K(j,j+1) = K(j+1,j) = -kj
//! ```
//!
//! and C likewise with c. Sign conventions: x is positive in the direction of
//! the force on m1 (for a pendulum test, rearwards into the car); a spring or
//! damper force is positive in compression, i.e. when mass j moves towards
//! mass j+1.
//!
//! The parameter vector uses the thesis order
//! `theta = [m1..mn, c1..c(n-1), k1..k(n-1)]` (kg, N·s/m, N/m).
//!
//! Validation: masses and springs must be positive and finite. Dampers must be
//! finite and non-negative: zero is allowed because a link without a damper is
//! physical (paper A's 2-DOF car has a spring only, and the undamped
//! oscillator is the textbook check); identification bounds keep them ≥ 1.
//!
//! With the `serde` feature a model serialises as
//! `{"masses": [..], "dampers": [..], "springs": [..]}` (SI) and deserialises
//! only through [`MsdModel::new`], so a file can never hold an invalid model
//! (`dampers` and `springs` may be absent for one mass).
//!
//! ```
//! use bumpsim_core::model::MsdModel;
//! let car = MsdModel::new(vec![1.8, 74.8, 1670.0], vec![6.46e6, 1.97e5], vec![4.75e5, 5.0e5]).unwrap();
//! assert_eq!(car.dof(), 3);
//! assert_eq!(car.parameters().len(), 7);
//! assert!(MsdModel::new(vec![-1.0], vec![], vec![]).is_err());
//! ```

use crate::units::{Dimension, format_quantity};
use nalgebra::DMatrix;

/// A validated chain MSD model; parameters in SI.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize),
    serde(into = "ModelFields")
)]
pub struct MsdModel {
    masses: Vec<f64>,
    dampers: Vec<f64>,
    springs: Vec<f64>,
}

/// Why a model cannot be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// No masses given.
    #[error("a model needs at least one mass")]
    NoMass,
    /// More masses than [`MAX_DOF`].
    #[error(
        "{dof} masses: at most {MAX_DOF} (limit MAX_DOF; the state matrices grow with the square of the DOF)"
    )]
    TooManyMasses {
        /// The number given.
        dof: usize,
    },
    /// The number of dampers or springs does not fit the number of masses.
    #[error("{count} {kind} given for {dof} masses: a chain of n masses needs n - 1 = {expected}")]
    Count {
        /// `"dampers"` or `"springs"`.
        kind: &'static str,
        /// Number of masses.
        dof: usize,
        /// Number required.
        expected: usize,
        /// Number given.
        count: usize,
    },
    /// A parameter value is out of its physical range.
    #[error("{parameter} = {value} {unit}: {requirement}")]
    Value {
        /// Parameter name in thesis notation (`m2`, `c1`, `k1`).
        parameter: String,
        /// The value given (SI).
        value: f64,
        /// Its SI unit.
        unit: &'static str,
        /// What was expected.
        requirement: &'static str,
    },
    /// A parameter vector of the wrong length.
    #[error("a {dof}-DOF model has {expected} parameters [m1..m{dof}, c.., k..], got {count}")]
    ParameterCount {
        /// Number of masses.
        dof: usize,
        /// Number required (3n − 2).
        expected: usize,
        /// Number given.
        count: usize,
    },
}

/// The kind of a model parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParameterKind {
    /// A mass, kg.
    Mass,
    /// A viscous damper, N·s/m.
    Damper,
    /// A linear spring, N/m.
    Spring,
}

impl ParameterKind {
    /// Thesis letter: `m`, `c` or `k`.
    pub fn letter(self) -> char {
        match self {
            ParameterKind::Mass => 'm',
            ParameterKind::Damper => 'c',
            ParameterKind::Spring => 'k',
        }
    }

    /// The physical dimension: mass, damping or stiffness.
    pub fn dimension(self) -> Dimension {
        match self {
            ParameterKind::Mass => Dimension::Mass,
            ParameterKind::Damper => Dimension::Damping,
            ParameterKind::Spring => Dimension::Stiffness,
        }
    }

    /// The SI unit symbol.
    pub fn unit(self) -> &'static str {
        match self {
            ParameterKind::Mass => "kg",
            ParameterKind::Damper => "Ns/m",
            ParameterKind::Spring => "N/m",
        }
    }
}

/// Most masses of a model (a 1000-mass model already needs ~100 MB of
/// state matrices per discretisation).
pub const MAX_DOF: usize = 1000;

impl MsdModel {
    /// Builds a model from masses (kg), dampers (N·s/m) and springs (N/m).
    pub fn new(masses: Vec<f64>, dampers: Vec<f64>, springs: Vec<f64>) -> Result<Self, ModelError> {
        let dof = masses.len();
        if dof == 0 {
            return Err(ModelError::NoMass);
        }
        if dof > MAX_DOF {
            return Err(ModelError::TooManyMasses { dof });
        }
        check_count("dampers", dof, dampers.len())?;
        check_count("springs", dof, springs.len())?;
        let model = Self {
            masses,
            dampers,
            springs,
        };
        for (index, value) in model.parameters().into_iter().enumerate() {
            check_value(dof, index, value)?;
        }
        Ok(model)
    }

    /// Builds a `dof`-mass model from `theta = [m1..mn, c1..c(n-1), k1..k(n-1)]`.
    pub fn from_parameters(dof: usize, theta: &[f64]) -> Result<Self, ModelError> {
        if dof == 0 {
            return Err(ModelError::NoMass);
        }
        let expected = parameter_count(dof);
        if theta.len() != expected {
            return Err(ModelError::ParameterCount {
                dof,
                expected,
                count: theta.len(),
            });
        }
        let (masses, rest) = theta.split_at(dof);
        let (dampers, springs) = rest.split_at(dof - 1);
        Self::new(masses.to_vec(), dampers.to_vec(), springs.to_vec())
    }

    /// Number of masses n.
    pub fn dof(&self) -> usize {
        self.masses.len()
    }

    /// Masses m1..mn, kg.
    pub fn masses(&self) -> &[f64] {
        &self.masses
    }

    /// Dampers c1..c(n-1), N·s/m.
    pub fn dampers(&self) -> &[f64] {
        &self.dampers
    }

    /// Springs k1..k(n-1), N/m.
    pub fn springs(&self) -> &[f64] {
        &self.springs
    }

    /// Sum of the masses, kg.
    pub fn total_mass(&self) -> f64 {
        self.masses.iter().sum()
    }

    /// The parameter vector in thesis order `[m.., c.., k..]`, SI.
    pub fn parameters(&self) -> Vec<f64> {
        [&self.masses[..], &self.dampers, &self.springs].concat()
    }

    /// The stiffness matrix K (n × n, N/m).
    pub fn stiffness_matrix(&self) -> DMatrix<f64> {
        chain_matrix(self.dof(), &self.springs)
    }

    /// The damping matrix C (n × n, N·s/m).
    pub fn damping_matrix(&self) -> DMatrix<f64> {
        chain_matrix(self.dof(), &self.dampers)
    }
}

/// Number of parameters of a `dof`-mass chain: n masses, n − 1 dampers, n − 1 springs.
pub fn parameter_count(dof: usize) -> usize {
    3 * dof - 2
}

/// Kind and 1-based number of parameter `index` of a `dof`-mass model.
pub fn parameter_kind(dof: usize, index: usize) -> (ParameterKind, usize) {
    if index < dof {
        (ParameterKind::Mass, index + 1)
    } else if index < 2 * dof - 1 {
        (ParameterKind::Damper, index - dof + 1)
    } else {
        (ParameterKind::Spring, index + 2 - 2 * dof)
    }
}

/// Thesis name of parameter `index` (`m1`, `c2`, `k1`, ...).
pub fn parameter_name(dof: usize, index: usize) -> String {
    let (kind, number) = parameter_kind(dof, index);
    format!("{}{number}", kind.letter())
}

/// Parameter `index` of a `dof`-mass model, SI value, with its display
/// unit (kg, Ns/mm, N/mm).
///
/// ```
/// use bumpsim_core::model::format_parameter;
/// assert!(format_parameter(3, 0, 1.8).ends_with("kg"));
/// ```
pub fn format_parameter(dof: usize, index: usize, value: f64) -> String {
    format_quantity(value, parameter_kind(dof, index).0.dimension())
}

fn check_count(kind: &'static str, dof: usize, count: usize) -> Result<(), ModelError> {
    if count == dof - 1 {
        return Ok(());
    }
    Err(ModelError::Count {
        kind,
        dof,
        expected: dof - 1,
        count,
    })
}

fn check_value(dof: usize, index: usize, value: f64) -> Result<(), ModelError> {
    let (kind, _) = parameter_kind(dof, index);
    let (ok, requirement) = match kind {
        ParameterKind::Damper => (
            value >= 0.0,
            "a damper must be finite and non-negative (0 = no damper)",
        ),
        ParameterKind::Mass => (value > 0.0, "a mass must be positive and finite"),
        ParameterKind::Spring => (value > 0.0, "a spring must be positive and finite"),
    };
    if ok && value.is_finite() {
        return Ok(());
    }
    Err(ModelError::Value {
        parameter: parameter_name(dof, index),
        value,
        unit: kind.unit(),
        requirement,
    })
}

/// The tridiagonal chain (Laplacian) matrix of link coefficients.
fn chain_matrix(dof: usize, links: &[f64]) -> DMatrix<f64> {
    let mut matrix = DMatrix::zeros(dof, dof);
    for (j, &value) in links.iter().enumerate() {
        matrix[(j, j)] += value;
        matrix[(j + 1, j + 1)] += value;
        matrix[(j, j + 1)] -= value;
        matrix[(j + 1, j)] -= value;
    }
    matrix
}

/// The model's fields as a file holds them (SI), before validation: the
/// one layout of a model in JSON and TOML (`masses`, `dampers`, `springs`,
/// the last two absent for one mass), and of a car file, which adds the
/// car's `name`. Unknown keys are refused, so a typo such as `spring` is
/// never silently ignored.
#[cfg(feature = "serde")]
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ModelFields {
    /// The car's name (car files; a model alone has none).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Masses m1..mn, kg.
    pub masses: Vec<f64>,
    /// Dampers c1..c(n-1), N·s/m.
    #[serde(default)]
    pub dampers: Vec<f64>,
    /// Springs k1..k(n-1), N/m.
    #[serde(default)]
    pub springs: Vec<f64>,
}

#[cfg(feature = "serde")]
impl ModelFields {
    /// The model these fields give, validated by [`MsdModel::new`] (the
    /// name is not part of it).
    pub fn into_model(self) -> Result<MsdModel, ModelError> {
        MsdModel::new(self.masses, self.dampers, self.springs)
    }
}

#[cfg(feature = "serde")]
impl From<MsdModel> for ModelFields {
    fn from(model: MsdModel) -> ModelFields {
        ModelFields {
            name: None,
            masses: model.masses,
            dampers: model.dampers,
            springs: model.springs,
        }
    }
}

#[cfg(feature = "serde")]
impl<'de> serde::Deserialize<'de> for MsdModel {
    /// Deserialises and validates like [`MsdModel::new`]; the error names
    /// the parameter. A `name` is refused: a model is not a car file.
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let fields = ModelFields::deserialize(deserializer)?;
        if fields.name.is_some() {
            const FIELDS: &[&str] = &["masses", "dampers", "springs"];
            return Err(serde::de::Error::unknown_field("name", FIELDS));
        }
        fields.into_model().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_the_offending_parameter() {
        let err = MsdModel::new(vec![1.0, 0.0], vec![1.0], vec![1.0]).unwrap_err();
        assert!(err.to_string().starts_with("m2 = 0 kg"), "{err}");
        let err = MsdModel::new(vec![1.0, 2.0], vec![1.0], vec![f64::NAN]).unwrap_err();
        assert!(err.to_string().starts_with("k1 = NaN N/m"), "{err}");
        let err = MsdModel::new(vec![1.0, 2.0], vec![-1.0], vec![1.0]).unwrap_err();
        assert!(err.to_string().starts_with("c1 = -1 Ns/m"), "{err}");
    }

    #[test]
    fn counts_must_fit_a_chain() {
        let err = MsdModel::new(vec![1.0, 2.0, 3.0], vec![1.0], vec![1.0, 1.0]).unwrap_err();
        assert!(matches!(
            err,
            ModelError::Count {
                kind: "dampers",
                expected: 2,
                count: 1,
                ..
            }
        ));
        assert_eq!(
            MsdModel::new(vec![], vec![], vec![]),
            Err(ModelError::NoMass)
        );
    }

    #[test]
    fn parameters_round_trip_in_thesis_order() {
        let theta = [1.8, 74.8, 1670.0, 6.46e6, 1.97e5, 4.75e5, 5.0e5];
        let model = MsdModel::from_parameters(3, &theta).unwrap();
        assert_eq!(model.parameters(), theta.to_vec());
        assert_eq!(parameter_name(3, 3), "c1");
        assert_eq!(parameter_name(3, 6), "k2");
        assert!(MsdModel::from_parameters(3, &theta[..6]).is_err());
    }

    #[test]
    fn stiffness_matrix_is_the_chain_laplacian() {
        let model = MsdModel::new(vec![1.0; 3], vec![0.0, 0.0], vec![2.0, 3.0]).unwrap();
        let k = model.stiffness_matrix();
        let expected =
            DMatrix::from_row_slice(3, 3, &[2.0, -2.0, 0.0, -2.0, 5.0, -3.0, 0.0, -3.0, 3.0]);
        assert_eq!(k, expected);
        assert_eq!(k.row_sum().norm(), 0.0);
    }

    #[cfg(feature = "serde")]
    #[test]
    fn serde_round_trips_and_validates() {
        let car = MsdModel::new(vec![1.8, 74.8], vec![6.46e6], vec![4.75e5]).unwrap();
        let json = serde_json::to_string(&car).unwrap();
        assert_eq!(
            json,
            r#"{"masses":[1.8,74.8],"dampers":[6460000.0],"springs":[475000.0]}"#
        );
        assert_eq!(serde_json::from_str::<MsdModel>(&json).unwrap(), car);
        let rigid: MsdModel = serde_json::from_str(r#"{"masses": [1000.0]}"#).unwrap();
        assert_eq!(rigid.dof(), 1);
        let err = serde_json::from_str::<MsdModel>(
            r#"{"masses": [1.0, -2.0], "dampers": [0.0], "springs": [1.0]}"#,
        )
        .unwrap_err();
        assert!(err.to_string().contains("m2 = -2 kg"), "{err}");
        let err = serde_json::from_str::<MsdModel>(r#"{"masses": [1.0], "mass": 2}"#).unwrap_err();
        assert!(err.to_string().contains("unknown field `mass`"), "{err}");
        let err =
            serde_json::from_str::<MsdModel>(r#"{"masses": [1.0], "name": "a"}"#).unwrap_err();
        assert!(err.to_string().contains("unknown field `name`"), "{err}");
    }
}
