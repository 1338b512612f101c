//! Rule tables supplied by the user (`--table FILE`) for EG (docs/math/eg.md §6,
//! §7): the five arrays of one valence in the spec's format,
//!
//! ```json
//! {"valence": 6,
//!  "A11": [[12 integers], ...], "A22": [...], "A21": [...],
//!  "A31": [...], "A32": [...]}
//! ```
//!
//! one row per sector offset `r` (A11, A22: `r = 0..⌊n/2⌋`; A21: `r = 0..n−1`;
//! A31, A32: `r = 0..⌊(n+1)/2⌋`), columns `00 10 20 30 01 11 21 31 02 12 22 32`,
//! integers ×10⁵. Only the rows the spec lists; the kernel expands the rest by
//! the §6 symmetries.
//!
//! The JSON layer only checks types (integers, rows of 12). Everything else —
//! valence, row counts, entries of magnitude ≥ 10⁵, symmetries, the rows'
//! sums (ρ < 1), λ within 10⁻³ of Catmull-Clark's — is the kernel's
//! [`RuleTable::new`], whose error is reported with the table's file name.
//! An integer beyond the `i32` range is clamped to it, so the kernel refuses it
//! as an entry of magnitude ≥ 10⁵ ("rule table has the wrong shape").

use crate::error::CliError;
use crate::input::{parse_as, Source};
use capdiv::eg::tables::Row;
use capdiv::RuleTable;
use serde::Deserialize;

/// The file format, as parsed.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TableInput {
    /// The valence `n`.
    pub valence: usize,
    /// Rows of d̃₁₁'s array.
    #[serde(rename = "A11")]
    pub a11: Vec<Vec<i64>>,
    /// Rows of d̃₂₂'s array.
    #[serde(rename = "A22")]
    pub a22: Vec<Vec<i64>>,
    /// Rows of d̃₂₁'s array (all `n`).
    #[serde(rename = "A21")]
    pub a21: Vec<Vec<i64>>,
    /// Rows of d̃₃₁'s array.
    #[serde(rename = "A31")]
    pub a31: Vec<Vec<i64>>,
    /// Rows of d̃₃₂'s array.
    #[serde(rename = "A32")]
    pub a32: Vec<Vec<i64>>,
}

/// A table read from a file, its rows in the kernel's row type. Borrow a
/// checked [`RuleTable`] from it with [`Table::rule`].
#[derive(Clone, Debug)]
pub struct Table {
    /// The file's name, for messages.
    pub name: String,
    /// The valence the file states.
    pub valence: usize,
    /// A11, A22, A21, A31, A32.
    rows: [Vec<Row>; 5],
}

/// Array names in the order of [`Table`]'s rows.
const NAMES: [&str; 5] = ["A11", "A22", "A21", "A31", "A32"];

impl Table {
    /// Reads and parses `path` (`-` = stdin). Types only; see the module docs.
    pub fn read(path: &str) -> Result<Self, CliError> {
        let source = Source::read(path)?;
        Self::parse(&source.name, &source.text)
    }

    /// Parses a table text named `name`.
    pub fn parse(name: &str, text: &str) -> Result<Self, CliError> {
        let t: TableInput = parse_as(name, text)?;
        let mut rows: [Vec<Row>; 5] = Default::default();
        let arrays = [&t.a11, &t.a22, &t.a21, &t.a31, &t.a32];
        for ((out, array), label) in rows.iter_mut().zip(arrays).zip(NAMES) {
            for (r, row) in array.iter().enumerate() {
                let row: Row = row
                    .as_slice()
                    .try_into()
                    .map_err(|_| CliError::Schema {
                        source: name.to_string(),
                        message: format!(
                            "{label} row {r} has {} entries, 12 expected \
                         (columns 00 10 20 30 01 11 21 31 02 12 22 32)",
                            row.len()
                        ),
                    })
                    .map(|r: [i64; 12]| {
                        r.map(|a| a.clamp(i64::from(i32::MIN), i64::from(i32::MAX)) as i32)
                    })?;
                out.push(row);
            }
        }
        Ok(Table {
            name: name.to_string(),
            valence: t.valence,
            rows,
        })
    }

    /// The kernel's checked rule table ([`RuleTable::new`]); its error, named
    /// with the file, otherwise.
    pub fn rule(&self) -> Result<RuleTable<'_>, CliError> {
        let [a11, a22, a21, a31, a32] = &self.rows;
        RuleTable::new(self.valence, a11, a22, a21, a31, a32)
            .map_err(|e| CliError::kernel(&self.name, e))
    }
}
