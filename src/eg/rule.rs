//! EG rule tables (docs/math/eg.md §6, §7): the five listed arrays, their expansion
//! by the §6 symmetries, and the checks a caller's table must pass.

use super::net::check_valence;
use super::spectrum;
use super::tables::{self, Row};
use crate::error::Error;

/// Scale of the tabulated weights: an entry `a` means `a / 10⁵` (§6).
pub const WEIGHT_SCALE: i32 = 100_000;

/// The six inner new nodes `d̃_hk` of a sector that the EG rule computes (§6).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub enum InnerNode {
    /// `d̃₁₁` (array A11).
    D11,
    /// `d̃₂₁` (array A21).
    D21,
    /// `d̃₃₁` (array A31), on the sector-separating spoke.
    D31,
    /// `d̃₁₂` (from A21 by the diagonal symmetry).
    D12,
    /// `d̃₂₂` (array A22).
    D22,
    /// `d̃₃₂` (array A32), on the sector-separating spoke.
    D32,
}

impl InnerNode {
    /// All six, in the order 11 21 31 12 22 32.
    pub const ALL: [InnerNode; 6] = [
        InnerNode::D11,
        InnerNode::D21,
        InnerNode::D31,
        InnerNode::D12,
        InnerNode::D22,
        InnerNode::D32,
    ];
    /// `(h, k)`.
    pub const fn hk(self) -> (usize, usize) {
        match self {
            InnerNode::D11 => (1, 1),
            InnerNode::D21 => (2, 1),
            InnerNode::D31 => (3, 1),
            InnerNode::D12 => (1, 2),
            InnerNode::D22 => (2, 2),
            InnerNode::D32 => (3, 2),
        }
    }
    /// Index `h + 4k` in a d-net sector.
    pub const fn index(self) -> usize {
        let (h, k) = self.hk();
        h + 4 * k
    }
}

/// Which §6 symmetry relates the rows of a node's rule.
#[derive(Clone, Copy)]
enum Symmetry {
    /// A21: all rows listed.
    None,
    /// d̃₁₂ from A21: `a_ij^{r,12} = a_ji^{−r,21}` (i ≤ 2), `a_3j^{r,12} = a_3j^{−r−1,21}`.
    FromTwentyOne,
    /// A11, A22: `a_ij^r = a_ji^{−r}` (i ≤ 2), `a_3j^r = a_3j^{−r−1}`.
    Diagonal,
    /// A31, A32: `a_ij^r = a_ji^{1−r}` (i ≤ 2), `a_3j^r = a_3j^{−r}`.
    Spoke,
}

/// Column `(i, j)` (index `i + 4j`, `i ≤ 2`) transposed: `(j, i)`.
#[inline]
fn transpose(col: usize) -> usize {
    col / 4 + 4 * (col % 4)
}

/// The source rows `(r_a, r_b)` of row `r < n`'s symmetric image: its
/// columns `i ≤ 2` are row `r_a`'s transposed ([`transpose`]), its columns
/// `i = 3` row `r_b`'s. No division (`v mod n` for `−n ≤ v ≤ 1`).
fn image_rows(sym: Symmetry, n: usize, r: usize) -> (usize, usize) {
    // −k mod n for 0 ≤ k ≤ n.
    let neg = |k: usize| match n.saturating_sub(k) {
        m if m == n => 0,
        m => m,
    };
    match sym {
        Symmetry::None => (r, r),
        // a^r from a^{−r} (i ≤ 2) and a^{−r−1} (i = 3).
        Symmetry::FromTwentyOne | Symmetry::Diagonal => (neg(r), neg(r.saturating_add(1))),
        // a^r from a^{1−r} (i ≤ 2) and a^{−r} (i = 3).
        Symmetry::Spoke => (
            1usize.checked_sub(r).unwrap_or(neg(r.saturating_sub(1))),
            neg(r),
        ),
    }
}

/// The symmetric image `(r', column')` of entry `(r, column)`, `r < n`.
fn image(sym: Symmetry, n: usize, r: usize, col: usize) -> (usize, usize) {
    let (ra, rb) = image_rows(sym, n, r);
    match sym {
        Symmetry::None => (r, col),
        _ if col % 4 <= 2 => (ra, transpose(col)),
        _ => (rb, col),
    }
}

/// An EG rule table for one valence: the five arrays of §7 in the spec's
/// format (rows of 12 integers ×10⁵, only the listed rows), borrowed.
///
/// Built-in tables (n = 3, 5) come from [`RuleTable::builtin`]; any other
/// table goes through [`RuleTable::new`], which checks it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct RuleTable<'a> {
    valence: usize,
    a11: &'a [Row],
    a22: &'a [Row],
    a21: &'a [Row],
    a31: &'a [Row],
    a32: &'a [Row],
}

impl RuleTable<'static> {
    /// The published table of valence `n` (§7): `Some` for n = 3 and 5.
    /// n = 4 needs none (regular); n = 6..10 are not published in usable form.
    pub fn builtin(n: usize) -> Option<Self> {
        match n {
            3 => Some(RuleTable {
                valence: 3,
                a11: &tables::A11_3,
                a22: &tables::A22_3,
                a21: &tables::A21_3,
                a31: &tables::A31_3,
                a32: &tables::A32_3,
            }),
            5 => Some(RuleTable {
                valence: 5,
                a11: &tables::A11_5,
                a22: &tables::A22_5,
                a21: &tables::A21_5,
                a31: &tables::A31_5,
                a32: &tables::A32_5,
            }),
            _ => None,
        }
    }
}

impl<'a> RuleTable<'a> {
    /// A caller's table for valence `n`, in the §7 format: A11 and A22 with
    /// `⌊n/2⌋+1` rows, A21 with `n`, A31 and A32 with `⌊(n+1)/2⌋+1`.
    ///
    /// Checks, in this order:
    /// - [`Error::ValenceTooSmall`] / [`Error::ValenceUnsupported`]: `n ∉ 3..=10`;
    /// - [`Error::TableShape`]: `n = 4` (regular, no EG rule), a wrong row
    ///   count, or an entry with `|a| ≥ 10⁵` (the weights are 5-digit
    ///   fractions of absolute value below 1, paper appendix);
    /// - [`Error::TableSymmetry`]: two listed entries that the §6 symmetries
    ///   identify differ;
    /// - [`Error::TableRowSum`]: with `a0 = 1 − Σa` every row of `A_n` sums to 1,
    ///   so `(c0, all nodes equal)` is an eigenvector of eigenvalue 1. That is
    ///   only the limit if it is dominant (§8): rejected when the d-net does
    ///   not contract to `c0`, i.e. the spectral radius `ρ` of `A_n` on nets
    ///   with `c0 = 0` is `≥ 1`;
    /// - [`Error::TableSpectrum`]: `|ρ − λ_CC(n)| > 10⁻³`, λ_CC the Catmull-Clark
    ///   subdominant eigenvalue (§8: EG's λ is within 10⁻³ of it).
    ///
    /// ρ is measured by power iteration with this table's own step (96 steps
    /// of an `f32` d-net; two d-nets on the stack).
    ///
    /// ```
    /// use capdiv::eg::tables::{A11_5, A21_5, A22_5, A31_5, A32_5};
    /// use capdiv::eg::RuleTable;
    /// use capdiv::Error;
    /// // A11 with a row missing: the wrong shape, caught first.
    /// assert_eq!(
    ///     RuleTable::new(5, &A11_5[..2], &A22_5, &A21_5, &A31_5, &A32_5),
    ///     Err(Error::TableShape)
    /// );
    /// # // The spectrum check's 96 steps take minutes under Miri.
    /// # if cfg!(miri) { return Ok(()); }
    /// // The published valence-5 arrays pass every check.
    /// let table = RuleTable::new(5, &A11_5, &A22_5, &A21_5, &A31_5, &A32_5)?;
    /// assert_eq!(Some(table), RuleTable::builtin(5));
    /// # Ok::<(), capdiv::Error>(())
    /// ```
    pub fn new(
        n: usize,
        a11: &'a [Row],
        a22: &'a [Row],
        a21: &'a [Row],
        a31: &'a [Row],
        a32: &'a [Row],
    ) -> Result<Self, Error> {
        check_valence(n)?;
        let t = RuleTable {
            valence: n,
            a11,
            a22,
            a21,
            a31,
            a32,
        };
        t.check_shape()?;
        t.check_symmetry()?;
        spectrum::check(&t)?;
        Ok(t)
    }

    /// The valence.
    #[inline]
    pub fn valence(&self) -> usize {
        self.valence
    }

    /// The listed rows of a node's array (for [`InnerNode::D12`]: A21's).
    pub fn listed(&self, node: InnerNode) -> &'a [Row] {
        self.source(node).0
    }

    /// Rows the spec lists for a node's array at this valence.
    pub fn listed_rows(&self, node: InnerNode) -> usize {
        let n = self.valence;
        match node {
            InnerNode::D21 | InnerNode::D12 => n,
            InnerNode::D11 | InnerNode::D22 => (n / 2).saturating_add(1),
            InnerNode::D31 | InnerNode::D32 => n.div_ceil(2).saturating_add(1),
        }
    }

    fn source(&self, node: InnerNode) -> (&'a [Row], Symmetry) {
        match node {
            InnerNode::D11 => (self.a11, Symmetry::Diagonal),
            InnerNode::D22 => (self.a22, Symmetry::Diagonal),
            InnerNode::D21 => (self.a21, Symmetry::None),
            InnerNode::D12 => (self.a21, Symmetry::FromTwentyOne),
            InnerNode::D31 => (self.a31, Symmetry::Spoke),
            InnerNode::D32 => (self.a32, Symmetry::Spoke),
        }
    }

    /// Row `r` (`r < n`) of node's rule, expanded by the §6 symmetries:
    /// the weights `a_ij^{r,hk}·10⁵` on sector `s + r`'s nodes. `None` for
    /// `r ≥ n` (or a table that failed [`RuleTable::new`]'s shape check).
    pub fn row(&self, node: InnerNode, r: usize) -> Option<Row> {
        if r >= self.valence {
            return None;
        }
        let (rows, sym) = self.source(node);
        let listed = match sym {
            Symmetry::FromTwentyOne => None,
            _ => rows.get(r),
        };
        if let Some(row) = listed {
            return Some(*row);
        }
        let (ra, rb) = image_rows(sym, self.valence, r);
        let (a, b) = (rows.get(ra)?, rows.get(rb)?);
        let mut out = *b;
        for (col, w) in out.iter_mut().enumerate() {
            if col % 4 <= 2 {
                *w = *a.get(transpose(col))?;
            }
        }
        Some(out)
    }

    /// The weight of `c0` in node's rule, ×10⁵: `a0 = 1 − Σ_r Σ_ij a_ij^{r,hk}`.
    pub fn c0_weight(&self, node: InnerNode) -> Option<i32> {
        let mut sum: i32 = 0;
        for r in 0..self.valence {
            for a in self.row(node, r)? {
                sum = sum.checked_add(a)?;
            }
        }
        WEIGHT_SCALE.checked_sub(sum)
    }

    fn check_shape(&self) -> Result<(), Error> {
        if self.valence == 4 {
            return Err(Error::TableShape);
        }
        for node in [
            InnerNode::D11,
            InnerNode::D22,
            InnerNode::D21,
            InnerNode::D31,
            InnerNode::D32,
        ] {
            let rows = self.listed(node);
            if rows.len() != self.listed_rows(node) {
                return Err(Error::TableShape);
            }
            if rows
                .iter()
                .flatten()
                .any(|a| a.unsigned_abs() >= WEIGHT_SCALE as u32)
            {
                return Err(Error::TableShape);
            }
        }
        Ok(())
    }

    fn check_symmetry(&self) -> Result<(), Error> {
        for node in [
            InnerNode::D11,
            InnerNode::D22,
            InnerNode::D31,
            InnerNode::D32,
        ] {
            let (rows, sym) = self.source(node);
            for (r, row) in rows.iter().enumerate() {
                for (col, a) in row.iter().enumerate() {
                    let (r2, c2) = image(sym, self.valence, r, col);
                    if let Some(b) = rows.get(r2).and_then(|x| x.get(c2)) {
                        if a != b {
                            return Err(Error::TableSymmetry);
                        }
                    }
                }
            }
        }
        Ok(())
    }
}
