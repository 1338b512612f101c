//! `capdiv spectrum --valence N [--table FILE]`: the spectrum of the EG
//! subdivision matrix `A_n` (docs/math/eg.md §6, §8) — the way to check a rule
//! table (e.g. one for n = 6..10 from the paper's appendix) against the
//! paper's published λ and μ/λ² (§7, §8).
//!
//! **Assembly.** One EG step is linear in the vector `(d, c0)` of the `12n`
//! d-net nodes and `c0` (every rule is an affine combination, §5, §6). Column
//! `k` of the `(12n+1)²` matrix is the kernel's step ([`DNet::refined`])
//! applied to the unit d-net `e_k` (node `k` = 1 in the `x` coordinate, all
//! else 0; the last column: `c0` = 1, nodes 0); rows in the order sector 0
//! nodes `00 10 20 30 01 11 21 31 02 12 22 32`, sector 1, …, then `c0`. So the
//! spectrum is that of the very step `refine` runs, with the built-in table
//! (n = 3, 5), the regular rules (n = 4: λ = ½, μ = ¼), or the user's checked
//! table ([`crate::table`]).
//!
//! **Eigenvalues.** nalgebra's real Schur decomposition, all `12n+1`
//! eigenvalues `ν`, ordered by modulus, largest first (ties: larger real part,
//! then larger imaginary part). Printed: the 8 largest moduli `|ν|`
//! (`eigenvalues`) and the same 8 as `[re, im]` pairs (`eigenvalues_re_im`),
//! so a complex or negative eigenvalue is visible.
//!
//! **Definitions** (paper §6: "exactly one eigenvalue dominates and is 1 …
//! the double subdominant eigenvalue λ … μ the subsubdominant eigenvalue"):
//! - `ν₀ = 1` (eigenvector: every node = `c0`);
//! - `lambda` = `|ν₁|`; ν₁ = ν₂ is the double subdominant pair (Fourier modes
//!   1 and n−1, the tangent plane);
//! - `mu_over_lambda2` = `|ν₃|/λ², |ν₄|/λ², |ν₅|/λ²`: the three eigenvalues
//!   after the λ pair — for EG one single (Fourier mode 0, the `x² + y²`
//!   part) and one double (modes 2 and n−2, or ±1 for n = 3: the `x² − y²`,
//!   `xy` part), all real and positive. docs/math/eg.md §8's "μ/λ² (single)" and
//!   "(double)" are these; the paper's one published μ/λ² per valence is the
//!   largest of the three (n = 3: 1.000157 single vs 0.998065 double, printed
//!   as 1.00015; n = 5: 1.000160 vs 1.000118, printed as 1.00016).
//! - `lambda_cc`: Catmull-Clark's λ_CC(n) (§8, kernel
//!   [`capdiv::eg::lambda_catmull_clark`]); EG's λ is within 10⁻³ of it.

use super::eg::user_rule;
use super::Outcome;
use crate::args::SpectrumArgs;
use crate::error::CliError;
use crate::json::to_json;
use crate::output::{Sink, SpectrumOutput};
use crate::table::Table;
use capdiv::eg::lambda_catmull_clark;
use capdiv::{DNet, RuleTable};
use nalgebra::linalg::Schur;
use nalgebra::DMatrix;

/// Eigenvalues printed.
pub const PRINTED: usize = 8;

/// Runs the command.
pub fn run(args: &SpectrumArgs) -> Result<Outcome, CliError> {
    let n = args.valence;
    let table = args.table.as_deref().map(Table::read).transpose()?;
    let label = format!("valence {n}");
    let rule = match &table {
        Some(t) => Some(user_rule(t, &label, n)?),
        None => None,
    };
    let source = match &table {
        Some(t) => t.name.clone(),
        None if n == 4 => "regular".to_string(),
        None => "builtin".to_string(),
    };
    let out = spectrum(n, rule.as_ref(), &source)?;
    Ok(Outcome::new(
        to_json(&out, args.pretty),
        Sink::from_option(args.output.clone()),
    ))
}

/// The spectrum of valence `n`'s step: with `rule` when given, else the
/// kernel's built-in rule (kernel errors, e.g. "valence 6 is not supported",
/// named with `valence n`). `source` labels the table in the output.
pub fn spectrum(
    n: usize,
    rule: Option<&RuleTable<'_>>,
    source: &str,
) -> Result<SpectrumOutput, CliError> {
    let label = format!("valence {n}");
    let m = matrix(n, rule).map_err(|e| CliError::kernel(&label, e))?;
    let ev = eigenvalues(m).ok_or_else(|| {
        CliError::Usage(format!(
            "{label}: the eigenvalue iteration did not converge"
        ))
    })?;
    let modulus = |k: usize| ev.get(k).map_or(f64::NAN, |z| z[0].hypot(z[1]));
    let lambda = modulus(1);
    let lambda2 = lambda * lambda;
    let top: Vec<[f64; 2]> = ev.iter().take(PRINTED).copied().collect();
    Ok(SpectrumOutput {
        valence: n,
        table: source.to_string(),
        eigenvalues: top.iter().map(|z| z[0].hypot(z[1])).collect(),
        eigenvalues_re_im: top,
        lambda,
        lambda_cc: lambda_catmull_clark(n),
        mu_over_lambda2: [3, 4, 5].map(|k| modulus(k) / lambda2),
    })
}

/// The `(12n+1)²` matrix of one step (module docs), column by column from
/// the kernel's step of unit d-nets.
pub fn matrix(n: usize, rule: Option<&RuleTable<'_>>) -> Result<DMatrix<f64>, capdiv::Error> {
    let nodes = n.saturating_mul(12);
    let size = nodes + 1;
    // Validates n (3..=10) before anything of size n is built.
    let probe = DNet::<f64>::from_sectors(&vec![[[0.0; 3]; 12]; n], Some([0.0; 3]))?;
    probe.refined(rule)?;
    let mut m = DMatrix::<f64>::zeros(size, size);
    for col in 0..size {
        let mut sectors = vec![[[0.0f64; 3]; 12]; n];
        let mut c0 = [0.0f64; 3];
        match sectors.get_mut(col / 12).and_then(|s| s.get_mut(col % 12)) {
            Some(p) if col < nodes => p[0] = 1.0,
            _ => c0[0] = 1.0,
        }
        let next = DNet::from_sectors(&sectors, Some(c0))?.refined(rule)?;
        for (row, p) in next.sectors().iter().flatten().enumerate() {
            m[(row, col)] = p.0[0];
        }
        m[(nodes, col)] = next.c0().0[0];
    }
    Ok(m)
}

/// Deflation tolerances tried in turn: nalgebra's Schur iteration deflates
/// a sub-diagonal entry below `eps·(|h_ii| + |h_jj|)`, which machine epsilon
/// never reaches next to the zero eigenvalues of the regular n = 4 matrix
/// (measured: no convergence in 10⁴ iterations; 10⁻¹² converges at once).
/// An eigenvalue moves by about `eps·‖A‖` at most, far below the 10⁻⁶
/// that §8 is checked to.
const SCHUR_EPS: [f64; 3] = [f64::EPSILON, 1e-14, 1e-12];

/// All eigenvalues as `[re, im]`, by modulus, largest first; `None` if the
/// Schur iteration converges for none of the thresholds `SCHUR_EPS`.
pub fn eigenvalues(m: DMatrix<f64>) -> Option<Vec<[f64; 2]>> {
    let schur = SCHUR_EPS
        .iter()
        .find_map(|&eps| Schur::try_new(m.clone(), eps, 10_000))?;
    let mut ev: Vec<[f64; 2]> = schur
        .complex_eigenvalues()
        .iter()
        .map(|z| [z.re, z.im])
        .collect();
    ev.sort_by(|a, b| {
        let (ma, mb) = (a[0].hypot(a[1]), b[0].hypot(b[1]));
        mb.total_cmp(&ma)
            .then(b[0].total_cmp(&a[0]))
            .then(b[1].total_cmp(&a[1]))
    });
    Some(ev)
}
