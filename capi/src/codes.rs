//! Status codes of the C ABI: `≥ 0` on success (the number of values
//! written), one negative code per [`capdiv::Error`] variant. Shared with the
//! host tests (`include`d there by path) and exported to `capdiv.h` as
//! `#define`s.

use capdiv::Error;

/// `Error::ValenceTooSmall`: a polar configuration of valence < 3, a c-net of fewer than 3 sectors.
pub const CAPDIV_ERR_VALENCE_TOO_SMALL: i32 = -1;
/// `Error::ValenceUnsupported`: no angle table (odd part of the valence > 127) or no EG rule (n > 5 without a table).
pub const CAPDIV_ERR_VALENCE_UNSUPPORTED: i32 = -2;
/// `Error::TooFewLinks`: a polar configuration needs at least 2 links.
pub const CAPDIV_ERR_TOO_FEW_LINKS: i32 = -3;
/// `Error::LinkLengthMismatch`: links of unequal length.
pub const CAPDIV_ERR_LINK_LENGTH_MISMATCH: i32 = -4;
/// `Error::WrongLength`: a coordinate list that is not whole links / whole sectors of points.
pub const CAPDIV_ERR_WRONG_LENGTH: i32 = -5;
/// `Error::NonFinite`: a NaN or infinite input, or a value that would overflow.
pub const CAPDIV_ERR_NON_FINITE: i32 = -6;
/// `Error::CapacityExceeded`: `valence·2^steps` above the capacity (the work buffer is too short).
pub const CAPDIV_ERR_CAPACITY_EXCEEDED: i32 = -7;
/// `Error::NotEnoughLinks`: an operation needs more links than the net holds.
pub const CAPDIV_ERR_NOT_ENOUGH_LINKS: i32 = -8;
/// `Error::Degenerate`: no tangent plane (normals, curvatures).
pub const CAPDIV_ERR_DEGENERATE: i32 = -9;
/// `Error::OutOfDomain`: an index or parameter outside its range.
pub const CAPDIV_ERR_OUT_OF_DOMAIN: i32 = -10;
/// `Error::TableShape`: an EG rule table of the wrong shape.
pub const CAPDIV_ERR_TABLE_SHAPE: i32 = -11;
/// `Error::TableSymmetry`: an EG rule table without the §6 symmetries.
pub const CAPDIV_ERR_TABLE_SYMMETRY: i32 = -12;
/// `Error::TableRowSum`: an EG rule table whose rows do not sum to 1.
pub const CAPDIV_ERR_TABLE_ROW_SUM: i32 = -13;
/// `Error::TableSpectrum`: an EG rule table whose subdominant eigenvalue is off.
pub const CAPDIV_ERR_TABLE_SPECTRUM: i32 = -14;
/// An error variant added to the kernel after this ABI.
pub const CAPDIV_ERR_OTHER: i32 = -99;
/// A null or misaligned pointer, or a buffer too short for the output.
pub const CAPDIV_BAD_BUFFER: i32 = -100;

/// [`CAPDIV_BAD_BUFFER`] under its older name (the WASM module's).
pub const BAD_BUFFER: i32 = CAPDIV_BAD_BUFFER;

/// The negative code of an error.
pub fn code(e: &Error) -> i32 {
    match e {
        Error::ValenceTooSmall { .. } => CAPDIV_ERR_VALENCE_TOO_SMALL,
        Error::ValenceUnsupported { .. } => CAPDIV_ERR_VALENCE_UNSUPPORTED,
        Error::TooFewLinks { .. } => CAPDIV_ERR_TOO_FEW_LINKS,
        Error::LinkLengthMismatch { .. } => CAPDIV_ERR_LINK_LENGTH_MISMATCH,
        Error::WrongLength { .. } => CAPDIV_ERR_WRONG_LENGTH,
        Error::NonFinite => CAPDIV_ERR_NON_FINITE,
        Error::CapacityExceeded { .. } => CAPDIV_ERR_CAPACITY_EXCEEDED,
        Error::NotEnoughLinks { .. } => CAPDIV_ERR_NOT_ENOUGH_LINKS,
        Error::Degenerate => CAPDIV_ERR_DEGENERATE,
        Error::OutOfDomain => CAPDIV_ERR_OUT_OF_DOMAIN,
        Error::TableShape => CAPDIV_ERR_TABLE_SHAPE,
        Error::TableSymmetry => CAPDIV_ERR_TABLE_SYMMETRY,
        Error::TableRowSum => CAPDIV_ERR_TABLE_ROW_SUM,
        Error::TableSpectrum => CAPDIV_ERR_TABLE_SPECTRUM,
        // `Error` is non-exhaustive: a variant added later gets the catch-all code.
        _ => CAPDIV_ERR_OTHER,
    }
}
