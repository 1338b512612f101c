//! The kernel's error type: every bad input maps to one distinct value.
//!
//! No function of the kernel panics on any input; each returns one of these
//! and leaves the caller's data (and the net it was called on) unchanged.

/// Everything that can go wrong, one variant per cause.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
#[non_exhaustive]
pub enum Error {
    /// A valence below the scheme's minimum (C²PS: 3; EG: 3).
    ValenceTooSmall {
        /// The valence given.
        valence: usize,
    },
    /// A valence the kernel has no rule or table for.
    ValenceUnsupported {
        /// The valence given.
        valence: usize,
    },
    /// A polar configuration needs at least 2 links (the 1- and 2-link).
    TooFewLinks {
        /// Links given.
        links: usize,
    },
    /// Link `link` (1-based) does not have the 1-link's length.
    LinkLengthMismatch {
        /// 1-based link index.
        link: usize,
        /// Its length.
        len: usize,
        /// The 1-link's length (the valence).
        expected: usize,
    },
    /// A slice or array argument has the wrong number of entries.
    WrongLength {
        /// Entries expected.
        expected: usize,
        /// Entries given.
        found: usize,
    },
    /// A coordinate is NaN or infinite.
    NonFinite,
    /// The result would not fit the fixed capacity.
    CapacityExceeded {
        /// Entries needed.
        needed: usize,
        /// Capacity available.
        capacity: usize,
    },
    /// The operation needs more links than the net holds (rings need 5).
    NotEnoughLinks {
        /// Links needed.
        needed: usize,
        /// Links the net has.
        present: usize,
    },
    /// The tangent plane is degenerate (zero normal): no unit normal or curvature.
    Degenerate,
    /// A parameter lies outside its domain (a patch parameter outside `[0, 1]`).
    OutOfDomain,
    /// A user-supplied EG rule table failed the shape check.
    TableShape,
    /// A user-supplied EG rule table violates the §6 symmetries.
    TableSymmetry,
    /// A user-supplied EG rule table has rows whose weights do not sum correctly.
    TableRowSum,
    /// A user-supplied EG rule table's subdominant eigenvalue is not within
    /// 10⁻³ of Catmull-Clark's (docs/math/eg.md §8).
    TableSpectrum,
}

impl core::fmt::Display for Error {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match *self {
            Error::ValenceTooSmall { valence } => write!(f, "valence {valence} is below 3"),
            Error::ValenceUnsupported { valence } => {
                write!(f, "valence {valence} is not supported")
            }
            Error::TooFewLinks { links } => {
                write!(f, "{links} link(s) given, at least 2 are needed")
            }
            Error::LinkLengthMismatch {
                link,
                len,
                expected,
            } => write!(f, "link {link} has {len} points, the 1-link has {expected}"),
            Error::WrongLength { expected, found } => {
                write!(f, "expected {expected} entries, found {found}")
            }
            Error::NonFinite => write!(f, "a coordinate is not finite"),
            Error::CapacityExceeded { needed, capacity } => {
                write!(f, "needs {needed} entries, capacity is {capacity}")
            }
            Error::NotEnoughLinks { needed, present } => {
                write!(f, "needs {needed} links, the net has {present}")
            }
            Error::Degenerate => write!(f, "degenerate tangent plane"),
            Error::OutOfDomain => write!(f, "parameter outside [0, 1]"),
            Error::TableShape => write!(f, "rule table has the wrong shape"),
            Error::TableSymmetry => write!(f, "rule table violates the EG symmetries"),
            Error::TableRowSum => write!(f, "rule table rows do not sum as required"),
            Error::TableSpectrum => {
                write!(
                    f,
                    "rule table's subdominant eigenvalue is not Catmull-Clark's"
                )
            }
        }
    }
}

/// Every variant is a cause of its own: no underlying error.
impl core::error::Error for Error {}
