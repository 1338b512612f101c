//! Status codes of the C ABI: `0` or a count on success, one negative code per
//! [`capdiv::Error`] variant. Shared with the host test (`include`d by path).

use capdiv::Error;

/// A null pointer or a buffer too short for the output.
pub const BAD_BUFFER: i32 = -100;

/// The negative code of an error.
pub fn code(e: &Error) -> i32 {
    match e {
        Error::ValenceTooSmall { .. } => -1,
        Error::ValenceUnsupported { .. } => -2,
        Error::TooFewLinks { .. } => -3,
        Error::LinkLengthMismatch { .. } => -4,
        Error::WrongLength { .. } => -5,
        Error::NonFinite => -6,
        Error::CapacityExceeded { .. } => -7,
        Error::NotEnoughLinks { .. } => -8,
        Error::Degenerate => -9,
        Error::OutOfDomain => -10,
        Error::TableShape => -11,
        Error::TableSymmetry => -12,
        Error::TableRowSum => -13,
        #[allow(unreachable_patterns)]
        _ => -99,
    }
}
