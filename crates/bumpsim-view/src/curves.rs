//! Model against test: an identification result JSON given together with
//! its study (`bumpsim view study.toml result.json`) is simulated on each
//! of the study's cases by bumpsim-ident's own [`predict`] (the zoh
//! simulation of `identify` and `predict`), and each case shows the
//! measured and the model's displacement over time with the fitted window,
//! the fit % and the ISO/TS 18571 rating in `identify`'s words. A
//! prediction JSON (`predict --json`) names its model file: given with the
//! study, that file is simulated the same way on the cases it predicted
//! (the session calls [`model_against_test`] with it).

use crate::error::ViewError;
use bumpsim_core::units::format_number;
use bumpsim_ident::Study;
use bumpsim_ident::explore::predict;
use bumpsim_io::Car;
use serde::Serialize;
use std::path::Path;

/// One case: measured and model displacement.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CaseCurves {
    /// Case name.
    pub name: String,
    /// `fit 99.69 %`.
    pub fit: String,
    /// `ISO/TS 18571 rating …`.
    pub rating: String,
    /// Times, s.
    pub time: Vec<f64>,
    /// Measured displacement, mm.
    pub measured: Vec<f64>,
    /// Model displacement, mm.
    pub model: Vec<f64>,
    /// The fitted window, s.
    pub window: [f64; 2],
}

fn input(path: &Path, error: impl std::fmt::Display) -> ViewError {
    ViewError::Input {
        path: path.to_path_buf(),
        reason: error.to_string(),
    }
}

/// The model of `result` (an `identify --json` file) on every case of `study`.
pub fn model_against_test(study: &Path, result: &Path) -> Result<Vec<CaseCurves>, ViewError> {
    let car = Car::read_model_file(result).map_err(|e| input(result, e))?;
    let study_file = Study::read(study).map_err(|e| input(study, e))?;
    let loaded = study_file
        .load_named(car.model.dof(), &[])
        .map_err(|e| input(study, e))?;
    let predictions = predict(&loaded.cases, &car.model).map_err(|e| input(study, e))?;
    Ok(predictions
        .into_iter()
        .map(|p| CaseCurves {
            fit: format!("fit {} %", format_number(p.fit.fit_percent, 4)),
            rating: bumpsim_ident::text::rating_line(p.fit.rating.as_ref()),
            name: p.fit.name,
            time: p.time,
            measured: p.measured.iter().map(|x| x * 1e3).collect(),
            model: p.simulated.iter().map(|x| x * 1e3).collect(),
            window: p.window,
        })
        .collect())
}
