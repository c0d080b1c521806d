//! A chain car file in either form ([`ChainCar`]: linear springs or
//! nonlinear links) as the model the export crate's decks take
//! ([`CarModel`]), so that `export lsdyna` and `export calculix` pick the
//! chain's form here and not in a front end. No equations.

use bumpsim_export::car_deck::CarModel;
use bumpsim_io::link_car::ChainCar;

/// The model of `car` for [`bumpsim_export::car_deck`].
pub fn model(car: &ChainCar) -> CarModel<'_> {
    match car {
        ChainCar::Linear(car) => CarModel::Linear(&car.model),
        ChainCar::Links(car) => CarModel::Chain(&car.chain),
    }
}
