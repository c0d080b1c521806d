//! A fixed count of numbers in an input file: a curve point `[d, F]`, a pair
//! of biases, a position `[ξ, η]`. Serde reads a Rust array `[f64; 2]` from a
//! TOML text by taking its first two values and dropping the rest, so a
//! point given with three values lost its third without a word (issue 34).
//! [`Numbers`] reads the whole array and refuses any other count; the TOML
//! reader then names the line and column of the array.
//!
//! ```
//! use bumpsim_io::numbers::Numbers;
//! #[derive(serde::Deserialize)]
//! struct File { curve: Vec<Numbers<2>> }
//! let file: File = toml::from_str("curve = [[0, 0], [0.01, 1e4]]").unwrap();
//! assert_eq!(file.curve[1].0, [0.01, 1e4]);
//! let text = "curve = [[0, 0],\n  [0.01, 1e4, 5]]";
//! let error = toml::from_str::<File>(text).err().unwrap();
//! let message = bumpsim_io::toml_message(text, &error);
//! assert!(message.contains("line 2") && message.contains("exactly 2 numbers"), "{message}");
//! ```

use serde::de::{Deserialize, Deserializer, Error, SeqAccess, Visitor};

/// Exactly `N` numbers, read from an array of `N` (no more, no fewer).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Numbers<const N: usize>(pub [f64; N]);

struct Expect<const N: usize>;

impl<'de, const N: usize> Visitor<'de> for Expect<N> {
    type Value = Numbers<N>;

    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "an array of exactly {N} numbers")
    }

    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Self::Value, A::Error> {
        let mut values = [0.0; N];
        let mut count = 0;
        while let Some(value) = seq.next_element::<f64>()? {
            if let Some(slot) = values.get_mut(count) {
                *slot = value;
            }
            count += 1;
        }
        match count == N {
            true => Ok(Numbers(values)),
            false => Err(A::Error::invalid_length(count, &self)),
        }
    }
}

impl<'de, const N: usize> Deserialize<'de> for Numbers<N> {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_seq(Expect::<N>)
    }
}

impl<const N: usize> From<Numbers<N>> for [f64; N] {
    fn from(numbers: Numbers<N>) -> Self {
        numbers.0
    }
}

/// `#[serde(deserialize_with = "bumpsim_io::numbers::list")]` on a
/// `Vec<[f64; N]>` field: every element exactly `N` numbers.
pub fn list<'de, D: Deserializer<'de>, const N: usize>(
    deserializer: D,
) -> Result<Vec<[f64; N]>, D::Error> {
    let numbers = Vec::<Numbers<N>>::deserialize(deserializer)?;
    Ok(numbers.into_iter().map(|n| n.0).collect())
}

/// [`list`] for an `Option<Vec<[f64; N]>>` field (with `#[serde(default)]`).
pub fn optional_list<'de, D: Deserializer<'de>, const N: usize>(
    deserializer: D,
) -> Result<Option<Vec<[f64; N]>>, D::Error> {
    list(deserializer).map(Some)
}

/// A `[f64; N]` field or newtype variant: exactly `N` numbers (serde's own
/// array reader leaves extra values of a TOML array unread).
pub fn exact<'de, D: Deserializer<'de>, const N: usize>(
    deserializer: D,
) -> Result<[f64; N], D::Error> {
    Numbers::<N>::deserialize(deserializer).map(|n| n.0)
}

/// An `Option<[f64; N]>` field (with `#[serde(default)]`): exactly `N` numbers.
pub fn optional<'de, D: Deserializer<'de>, const N: usize>(
    deserializer: D,
) -> Result<Option<[f64; N]>, D::Error> {
    Numbers::<N>::deserialize(deserializer).map(|n| Some(n.0))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, serde::Deserialize)]
    struct Pair {
        p: Numbers<2>,
    }

    #[test]
    fn any_other_count_is_refused_from_text_and_from_a_value() {
        for text in ["p = [1]", "p = [1, 2, 3]", "p = []", "p = 1"] {
            let message = toml::from_str::<Pair>(text).unwrap_err().to_string();
            assert!(message.contains("exactly 2 numbers"), "{text}: {message}");
            let value: toml::Table = toml::from_str(text).unwrap();
            assert!(value.try_into::<Pair>().is_err(), "{text}");
        }
        assert_eq!(
            toml::from_str::<Pair>("p = [1, -2.5]").unwrap().p.0,
            [1.0, -2.5]
        );
        assert!(serde_json::from_str::<Pair>(r#"{"p": [1, 2, 3]}"#).is_err());
    }

    #[derive(Debug, serde::Deserialize)]
    struct Fields {
        #[serde(default, deserialize_with = "optional_list")]
        curve: Option<Vec<[f64; 2]>>,
        #[serde(default, deserialize_with = "optional")]
        at: Option<[f64; 2]>,
        #[serde(default, deserialize_with = "list")]
        points: Vec<[f64; 3]>,
    }

    #[test]
    fn field_helpers_read_absent_and_exact_values_and_refuse_others() {
        let none: Fields = toml::from_str("").unwrap();
        assert!(none.curve.is_none() && none.at.is_none() && none.points.is_empty());
        let all: Fields =
            toml::from_str("curve = [[0, 1]]\nat = [2, 3]\npoints = [[1, 2, 3]]").unwrap();
        assert_eq!(all.curve, Some(vec![[0.0, 1.0]]));
        assert_eq!(
            (all.at, all.points),
            (Some([2.0, 3.0]), vec![[1.0, 2.0, 3.0]])
        );
        for text in ["curve = [[0, 1, 2]]", "at = [2, 3, 4]", "points = [[1, 2]]"] {
            assert!(toml::from_str::<Fields>(text).is_err(), "{text}");
        }
    }
}
