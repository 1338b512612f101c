//! Shared steps of the commands on EG inputs (docs/math/eg.md): the d-net of a
//! `cnet` or `dnet` input in the working precision, and the subdivision with
//! the built-in rule or a user table.
//!
//! - `cnet` (§1): the kernel's [`CNet`], degree-raised by R (§3) to its d-net,
//!   `c0` by formula (3);
//! - `dnet` (§2): the kernel's [`DNet`] as given, `c0` as given or fitted by
//!   formula (4).
//!
//! Rules: n = 3, 5 built in (§7); n = 4 needs none (the kernel refines it with
//! the regular bi-4 rules everywhere, the absent lattice node at the center
//! set so that the spline's value there is `c0`: for a d-net raised from a
//! c-net this is exact refinement of the c-net's bicubic surface); n = 6..10
//! need `--table` (the kernel's "valence n is not supported" otherwise).

use crate::error::CliError;
use crate::input::{CnetInput, DnetInput, EgInput};
use crate::table::Table;
use crate::Scalar;
use capdiv::{CNet, DNet, EgSubdivision, RuleTable};

fn points<R: Scalar, const N: usize>(sectors: &[[[f64; 3]; N]]) -> Vec<[[R; 3]; N]> {
    sectors
        .iter()
        .map(|s| s.map(|p| p.map(R::from_f64)))
        .collect()
}

/// The kernel's c-net of a `cnet` input, rounded to `R` (values beyond the
/// `f32` range become infinite and are refused as non-finite).
pub fn cnet<R: Scalar>(name: &str, input: &CnetInput) -> Result<CNet<R>, CliError> {
    CNet::from_sectors(input.center.map(R::from_f64), &points(&input.sectors))
        .map_err(|e| CliError::kernel(name, e))
}

/// The kernel's d-net of a `dnet` input (`c0` given, or by formula (4)).
pub fn dnet_of<R: Scalar>(name: &str, input: &DnetInput) -> Result<DNet<R>, CliError> {
    DNet::from_sectors(
        &points(&input.sectors),
        input.c0.map(|p| p.map(R::from_f64)),
    )
    .map_err(|e| CliError::kernel(name, e))
}

/// The d-net an EG input stands for: a c-net's degree raising (§3, `c0` by
/// (3)) or the d-net itself.
pub fn dnet<R: Scalar>(name: &str, input: &EgInput) -> Result<DNet<R>, CliError> {
    match input {
        EgInput::Cnet(c) => Ok(cnet::<R>(name, c)?.to_dnet()),
        EgInput::Dnet(d) => dnet_of(name, d),
    }
}

/// Reads `--table FILE` when given.
pub fn read_table(path: Option<&str>) -> Result<Option<Table>, CliError> {
    path.map(Table::read).transpose()
}

/// The kernel's checked rule of a user table, after checking that it is for
/// the input's valence.
pub fn user_rule<'t>(
    table: &'t Table,
    name: &str,
    valence: usize,
) -> Result<RuleTable<'t>, CliError> {
    if table.valence != valence {
        return Err(CliError::Usage(format!(
            "{}: the rule table is for valence {}, {name} has valence {valence}",
            table.name, table.valence
        )));
    }
    table.rule()
}

/// An EG subdivision of `input` at level 0: with the user's table when given,
/// the built-in rule otherwise (kernel errors named with `name`).
pub fn subdivision<'t, R: Scalar>(
    name: &str,
    input: &EgInput,
    table: Option<&'t Table>,
) -> Result<EgSubdivision<'t, R>, CliError> {
    let net = dnet::<R>(name, input)?;
    let kernel = |e| CliError::kernel(name, e);
    match table {
        Some(t) => {
            EgSubdivision::new(&net, Some(user_rule(t, name, input.valence())?)).map_err(kernel)
        }
        None => EgSubdivision::new(&net, None).map_err(kernel),
    }
}
