//! Issue 34, the writers' property: whatever bumpsim writes, bumpsim reads
//! back equal. Drawn ISO-MME tests (codes, names, dimensions, time bases and
//! values from 1e-300 to 1e300 of either sign) and drawn response tables go
//! through their writer and reader; a few dozen cases each (well under a
//! second).

use bumpsim_core::channel::Channel;
use bumpsim_core::series::UniformSeries;
use bumpsim_core::units::Dimension;
use bumpsim_io::test_data::TestData;
use proptest::prelude::*;

/// Finite values across the whole range a test may hold.
fn value() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(0.0),
        -1e6..1e6f64,
        (-1.0..1.0f64, -300..300i32).prop_map(|(m, e)| m * 10f64.powi(e)),
    ]
}

/// Channel codes as the standard spells them (test object, location,
/// dimension, direction, filter class), the ones a test holds distinct.
fn code() -> impl Strategy<Value = (String, Dimension)> {
    let dimension = prop_oneof![
        Just(("FO", Dimension::Force)),
        Just(("AC", Dimension::Acceleration)),
        Just(("VE", Dimension::Velocity)),
        Just(("DS", Dimension::Length)),
    ];
    (
        prop::sample::select(vec!['1', '2', 'P', 'B']),
        prop::sample::select(vec!["SIME", "IMPA", "BARR", "HEAD"]),
        0..100u32,
        dimension,
        prop::sample::select(vec!['X', 'Y', 'Z']),
        prop::sample::select(vec!['0', 'A', 'D', 'P']),
    )
        .prop_map(
            |(object, location, fine, (dim, dimension), direction, class)| {
                let code = format!("{object}0{location}{fine:02}0000{dim}{direction}{class}");
                (code, dimension)
            },
        )
}

/// A drawn channel: code, name, time base and values.
fn channel() -> impl Strategy<Value = Channel> {
    (
        code(),
        "[A-Za-z0-9][A-Za-z0-9 ._-]{0,30}[A-Za-z0-9]",
        -1.0..1.0f64,
        prop::sample::select(vec![1e-5, 1e-4, 2.5e-4, 1e-3]),
        prop::collection::vec(value(), 2..40),
    )
        .prop_map(|((code, dimension), name, start, step, values)| {
            let series = UniformSeries::new(start, step, values).unwrap();
            Channel::new(&code, &name, dimension, series)
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]

    /// An ISO-MME test bumpsim writes reads back with the same codes,
    /// names, dimensions and bit-identical values on the same time base.
    #[test]
    fn an_isomme_test_reads_back_what_was_written(
        channels in prop::collection::vec(channel(), 1..5),
        title in "[A-Za-z0-9][A-Za-z0-9 ,._-]{0,40}",
    ) {
        let mut channels = channels;
        let mut seen = std::collections::HashSet::new();
        channels.retain(|c| seen.insert(c.code.clone()));
        let dir = tempdir("isomme");
        let metadata = vec![("Title".to_string(), title.clone())];
        bumpsim_io::isomme::write(&dir.join("T"), "T", &metadata, &channels).unwrap();
        let test = TestData::open(&dir.join("T")).unwrap();
        prop_assert_eq!(test.title.trim(), title.trim());
        prop_assert_eq!(test.entries.len(), channels.len());
        for (k, written) in channels.iter().enumerate() {
            let read = test.load(k).unwrap();
            prop_assert_eq!(&read.code, &written.code);
            prop_assert_eq!(&read.name, &written.name);
            prop_assert_eq!(read.dimension, written.dimension);
            prop_assert_eq!(read.series.values(), written.series.values());
            let (a, b) = (read.series.start(), written.series.start());
            prop_assert!((a - b).abs() <= 1e-12 * b.abs().max(written.series.step()));
            let (a, b) = (read.series.step(), written.series.step());
            prop_assert!((a - b).abs() <= 1e-12 * b);
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// A fresh scratch folder for one drawn case.
fn tempdir(name: &str) -> std::path::PathBuf {
    use std::sync::atomic::{AtomicUsize, Ordering};
    static NEXT: AtomicUsize = AtomicUsize::new(0);
    let k = NEXT.fetch_add(1, Ordering::Relaxed);
    let dir =
        std::env::temp_dir().join(format!("bumpsim-io-prop-{}-{name}-{k}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}
