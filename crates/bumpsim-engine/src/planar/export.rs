//! `export planar` of the planar car: its LS-DYNA include or CalculiX deck
//! ([`bumpsim_planar::export`]), with a force history on the bumper line
//! when one is given. No equations here.

use crate::EngineError;
use crate::model::{Deck, ExportRequest, Solver};
use bumpsim_planar::PlanarCar;
use bumpsim_planar::drive::Load;
use bumpsim_planar::export::{
    Forces, PlanarExport, PlanarExportError, calculix_deck, lsdyna_include,
};

/// The deck of the planar car of `request.car`.
pub(super) fn export(request: &ExportRequest<'_>) -> Result<Deck, EngineError> {
    let car = PlanarCar::read(request.car)?;
    let options = options(request, &car);
    let calculix =
        || calculix_deck(&car, &options).map_err(|e| name_output_every(e, options.output_every));
    let (text, what) = match request.solver {
        Solver::Lsdyna => (
            lsdyna_include(&car, &options).map_err(EngineError::PlanarExport)?,
            "LS-DYNA include",
        ),
        Solver::Calculix if options.forces.is_some() => {
            (calculix()?, "CalculiX transient analysis (run: ccx JOB)")
        }
        Solver::Calculix => (calculix()?, "CalculiX model"),
    };
    let masses = car.left().masses.len() + car.right().masses.len();
    let what = format!(
        "{what} of the planar car, {masses} chain masses, ids from {}",
        request.id_offset + 1
    );
    Ok(Deck { text, what })
}

/// Names `--output-every` in the refusal of a zero output interval (the
/// library names the interval, not the option).
fn name_output_every(error: PlanarExportError, every: usize) -> EngineError {
    use bumpsim_export::ExportError::OutputInterval;
    match error {
        PlanarExportError::Export(OutputInterval) => EngineError::OutputEvery {
            every,
            source: error,
        },
        error => EngineError::PlanarExport(error),
    }
}

/// The export options of the request for `car`.
fn options(request: &ExportRequest<'_>, car: &PlanarCar) -> PlanarExport {
    let title = format!(
        "{} (from {})",
        car.name().unwrap_or("planar car"),
        request.car.display()
    );
    let forces = request.force.as_ref().map(|f| Forces {
        step: f.step,
        loads: vec![Load {
            lateral: f.lateral,
            anchor: None,
            cell: None,
            direction: f.direction,
            force: f.values.to_vec(),
        }],
    });
    PlanarExport {
        units: request.units,
        origin: request.origin,
        spacing: request.spacing,
        id_offset: request.id_offset,
        attach: request.attach.clone(),
        speed: request.speed,
        forces,
        output_interval: request.output_interval,
        increment: request.increment,
        output_every: request.output_every,
        prefix: request.prefix.clone(),
        title,
    }
}
