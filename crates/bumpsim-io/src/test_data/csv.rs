//! Crash-test channels from a CSV file with `name [unit]` headers
//! ([`table`](crate::table)): one channel per column after the time column,
//! converted to SI on reading.

use super::{Entry, Format, Store, TestData, Validity};
use crate::signal_error::SignalFileError;
use crate::table::Table;
use bumpsim_core::channel::Channel;
use std::path::Path;

pub(crate) fn open(path: &Path) -> Result<TestData, SignalFileError> {
    let table = Table::read(path)?;
    let entries = table
        .columns
        .iter()
        .enumerate()
        .map(|(i, c)| Entry {
            number: i + 1,
            code: c.name.clone(),
            name: c.name.clone(),
            unit: c.unit.symbol.to_string(),
            validity: Validity::Valid,
            present: true,
            absence: None,
            metadata: Vec::new(),
        })
        .collect();
    let title = path
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default();
    Ok(TestData {
        path: path.to_path_buf(),
        format: Format::Csv,
        title,
        metadata: Vec::new(),
        speed: None,
        mass: None,
        entries,
        store: Store::Csv(table),
    })
}

pub(crate) fn channel(table: &Table, index: usize) -> Result<Channel, SignalFileError> {
    let column = &table.columns[index];
    let mut channel = Channel::new(
        &column.name,
        &column.name,
        column.unit.dimension,
        table.series(column)?,
    );
    channel.source_unit = column.unit.symbol.to_string();
    Ok(channel)
}
