//! Streaming C²PS: the ring patches of levels `0..=M` and the pole jet of a
//! polar configuration in one angular sweep, with state of `O(M)` points —
//! no level is ever stored whole (docs/math/c2ps.md §2, §4, §5).
//!
//! A [`PolarNet`] holds whole levels (`17·CAP` scalars, `CAP = n·2^M`). But a
//! level-`m` column depends only on three columns of level `m−1` (the
//! periodic refinement of §2) and on the pole and 1-link Fourier sums of level
//! `m−1`, and those sums are closed forms of the level-0 eigencoefficients
//! (§4, eq. (30), Lemma 5). So every level keeps a window of its last 4
//! columns (a ring patch of §5 spans 4 columns) and the sweep pulls columns
//! through the levels depth-first: the deepest level advances by one column,
//! which every two columns asks the level below for one more, and so on down
//! to the input. The ring is periodic; the sweep runs each level's columns
//! over the virtual indices `−2 … N+1` (taken mod `N`), recomputing the few
//! wrap-around columns instead of storing them.
//!
//! Memory: [`PolarStream<R, D>`] holds `D + 1` levels of
//! `4·(15 + 2) + 20` scalars (a window of 4 columns of 5 points and a root,
//! the pole, the 1-link sums, a root) and three words each:
//! `size_of = (D + 1)·(88·size_of::<R>() + 3·size_of::<usize>())`
//! (f32, `D = 12`: 4,732 bytes with 32-bit words, 4,888 with 64-bit; f64,
//! `D = 20`: 15,288 bytes with 64-bit words), whatever the
//! valence or the depth reached. The sweep's own stack use is fixed.
//!
//! The results equal [`PolarNet`]'s in-place path to rounding (the 1-link
//! sums of levels ≥ 1 are the exact closed forms instead of sums over
//! `N` points, the roots are rotated per level in `f64`/`R` instead of read
//! from a doubled ring): tested on every patch within `1e-12` (f64) and the
//! docs/kernel.md's f32 bound of the configuration's size, `tests/polar_stream.rs`.

use super::jet::PoleJet;
use super::net::{link_count_after_step, validate, FirstStep, MAX_STORED_LINKS};
use super::stream_level::{next_column, power, Column, Level, Sums};
use crate::bezier::{bspline_to_bezier_cubic, BicubicPatch};
use crate::error::Error;
use crate::point::Point3;
use crate::real::Real;
use crate::trig::primitive_root;

#[cfg(doc)]
use super::net::{PolarNet, PolarNetInner};

/// What a sweep computes and which of its patches it delivers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StreamOptions {
    /// Deepest level `M` (C²PS steps from the input), `≤ D` of
    /// [`PolarStream<R, D>`].
    pub depth: u32,
    /// The first-step variant (§2), as for [`PolarNetInner::step`].
    pub first: FirstStep,
    /// Deliver only levels `≥ from_level` (the levels below are computed, not
    /// turned into patches). Default 0.
    pub from_level: u32,
    /// Deliver only this radial span (0 or 1; `None`: both). Default `None`.
    pub span: Option<u8>,
}

impl StreamOptions {
    /// All patches of levels `0..=depth`, the paper's first-step variant.
    pub const fn depth(depth: u32) -> Self {
        StreamOptions {
            depth,
            first: FirstStep::Uniform,
            from_level: 0,
            span: None,
        }
    }

    /// The same with first-step variant `first`.
    pub const fn first(self, first: FirstStep) -> Self {
        StreamOptions { first, ..self }
    }

    /// Only the ring of level `level`, span `span` (`None`: both) — e.g. to
    /// write patches in [`PolarNetInner::ring_patches`]' order, one sweep per
    /// level and span.
    pub const fn only(self, level: u32, span: Option<u8>) -> Self {
        StreamOptions {
            from_level: level,
            span,
            ..self
        }
    }
}

/// One patch delivered by a sweep: [`PolarNetInner::ring_patch`]`(k)` of
/// level `level`, `k = span·N + column` ([`Self::ring_index`]; its `u` runs outward over `r ∈ [2+span, 3+span]` in
/// level-`level` link units, its `v` counter-clockwise over
/// `τ ∈ [column/N, (column+1)/N]`).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(feature = "defmt", derive(defmt::Format))]
pub struct StreamedPatch<R> {
    /// Level `m` (C²PS steps from the input).
    pub level: u32,
    /// Radial span, 0 or 1.
    pub span: u8,
    /// Column `j < N`.
    pub column: usize,
    /// The level's valence `N = n·2^m`.
    pub valence: usize,
    /// The bicubic Bézier patch.
    pub patch: BicubicPatch<R>,
}

impl<R> StreamedPatch<R> {
    /// Its index `k` in its level's ring ([`PolarNetInner::ring_patch`],
    /// [`PolarNetInner::ring_patches`]): `span·N + column`.
    #[inline]
    pub fn ring_index(&self) -> usize {
        usize::from(self.span) * self.valence + self.column
    }
}

/// The caller-owned state of a streaming sweep to depth at most `D`: one
/// window of 4 columns per level `0..=D` (see the [module docs](self) for
/// the size). `const`-constructible, so it can live in a `static` (`.bss`).
///
/// The sweep delivers the in-place net's ring patches of every level,
/// without storing a level:
///
/// ```
/// use capdiv::{FirstStep, PolarNet, PolarStream, StreamOptions};
/// let links: Vec<Vec<[f64; 3]>> = (1..=5)
///     .map(|i| (0..6).map(|j| {
///         let t = core::f64::consts::TAU * j as f64 / 6.0;
///         let r = i as f64;
///         [r * t.cos(), r * t.sin(), 0.1 * r * r + 0.05 * j as f64]
///     }).collect())
///     .collect();
/// let mut state = PolarStream::<f64, 1>::empty();
/// let sweep = state.sweep([0.0; 3], &links, StreamOptions::depth(1).first(FirstStep::Uniform))?;
/// assert_eq!(sweep.len(), 2 * 6 + 2 * 12); // the rings of levels 0 and 1
/// let streamed: Vec<_> = sweep.collect();
/// // The same patches as a net refined in place, level by level.
/// let mut net: PolarNet<f64, 12> = PolarNet::new([0.0; 3], &links)?;
/// for level in 0..=1 {
///     for p in streamed.iter().filter(|p| p.level == level) {
///         let want = net.ring_patch(p.ring_index())?;
///         for (a, b) in p.patch.points.iter().flatten().zip(want.points.iter().flatten()) {
///             assert!(a.max_abs_diff(*b) < 1e-12);
///         }
///     }
///     if level == 0 {
///         net.step(FirstStep::Uniform)?;
///     }
/// }
/// # Ok::<(), capdiv::Error>(())
/// ```
#[derive(Clone, Debug)]
pub struct PolarStream<R, const D: usize> {
    level0: Level<R>,
    /// Levels `1..=D`.
    levels: [Level<R>; D],
}

impl<R: Real, const D: usize> Default for PolarStream<R, D> {
    fn default() -> Self {
        Self::empty()
    }
}

impl<R: Real, const D: usize> PolarStream<R, D> {
    /// The deepest level this state can stream.
    pub const MAX_DEPTH: u32 = D as u32;

    /// An empty state (all-zero bytes).
    pub const fn empty() -> Self {
        PolarStream {
            level0: Level::EMPTY,
            levels: [Level::EMPTY; D],
        }
    }

    /// Starts a sweep over the level-0 configuration `pole`, `links`
    /// (`links[0]` = 1-link, each a closed ring of `n ≥ 3` points,
    /// counter-clockwise; links beyond the 5th are checked, not used).
    ///
    /// Every check runs here, before any patch: [`Error::TooFewLinks`],
    /// [`Error::ValenceTooSmall`], [`Error::LinkLengthMismatch`],
    /// [`Error::NonFinite`] (as [`PolarNet::new`]); then
    /// [`Error::OutOfDomain`] for a span other than 0 or 1 in the options,
    /// [`Error::CapacityExceeded`] `{ needed: depth, capacity: D }` for a
    /// depth above `D`, [`Error::ValenceUnsupported`] (odd part of `n` above
    /// [`crate::trig::MAX_ODD_PART`]), [`Error::CapacityExceeded`]
    /// `{ needed: usize::MAX, .. }` when `n·2^depth` overflows, and
    /// [`Error::NonFinite`] when a coordinate of the pole or links 1..5 is
    /// above `MAX/(16·max(n, 4))` in magnitude. Below that bound every value of
    /// every level stays finite: the level-0 Fourier sums stay below `2n·m`
    /// (`m` the largest coordinate), every later point below `6m` (the 1-link
    /// by its closed form below `4m`, the 2-link adds at most `m/3·2^{2−k}` at
    /// level `k`, the other links are convex combinations) and every
    /// intermediate below `8·6m`. On error the state is unchanged.
    ///
    /// The returned [`Sweep`] yields the patches; it borrows this state and
    /// the input.
    pub fn sweep<'a, L: AsRef<[[R; 3]]>>(
        &'a mut self,
        pole: [R; 3],
        links: &'a [L],
        options: StreamOptions,
    ) -> Result<Sweep<'a, R, L, D>, Error> {
        let n = validate(&pole, links)?;
        if options.span.is_some_and(|s| s > 1) {
            return Err(Error::OutOfDomain);
        }
        let depth = options.depth;
        if depth as usize > D || depth > 63 {
            return Err(Error::CapacityExceeded {
                needed: depth as usize,
                capacity: D,
            });
        }
        let w0 = primitive_root(n).ok_or(Error::ValenceUnsupported { valence: n })?;
        let overflow = Error::CapacityExceeded {
            needed: usize::MAX,
            capacity: usize::MAX / 8,
        };
        1usize
            .checked_shl(depth)
            .and_then(|p| n.checked_mul(p))
            .filter(|&t| t <= usize::MAX / 8)
            .ok_or(overflow)?;
        let link_count0 = links.len().min(MAX_STORED_LINKS);
        let stored = links.get(..link_count0).unwrap_or(&[]);
        fits(&pole, stored, n)?;

        // Checked: from here on nothing fails.
        let sums = level0_sums(pole, stored.first().map_or(&[][..], |l| l.as_ref()), w0);
        self.level0 = Level {
            count: 0,
            n,
            link_count: link_count0,
            sums,
            w: [R::from_f64(w0.0), R::from_f64(w0.1)],
            ..Level::EMPTY
        };
        let (mut lo_n, mut lo_link_count, mut lo_sums) = (n, link_count0, sums);
        for level in self.levels.iter_mut().take(depth as usize) {
            let n = 2 * lo_n;
            let w = primitive_root(n).unwrap_or((1.0, 0.0));
            let sums = lo_sums.next();
            let link_count = link_count_after_step(lo_link_count);
            *level = Level {
                count: 0,
                n,
                link_count,
                sums,
                w: [R::from_f64(w.0), R::from_f64(w.1)],
                ..Level::EMPTY
            };
            (lo_n, lo_link_count, lo_sums) = (n, link_count, sums);
        }
        let mut total = 0usize;
        for m in options.from_level..=depth {
            let Some(lv) = self.level(m) else { continue };
            if lv.link_count >= 5 {
                let spans = if options.span.is_some() { 1 } else { 2 };
                total = total.saturating_add(spans * lv.n);
            }
        }
        let jet = jet_of(&sums);
        Ok(Sweep {
            state: self,
            links: stored,
            options,
            cursor: 0,
            pending: None,
            left: total,
            done: false,
            jet,
        })
    }

    /// [`Self::sweep`] with a callback: every patch of the sweep goes to
    /// `sink`, in the sweep's order (see [`Sweep`]). Returns the pole jet. On
    /// error nothing has been delivered.
    pub fn run<L: AsRef<[[R; 3]]>>(
        &mut self,
        pole: [R; 3],
        links: &[L],
        options: StreamOptions,
        mut sink: impl FnMut(StreamedPatch<R>),
    ) -> Result<PoleJet<R>, Error> {
        let sweep = self.sweep(pole, links, options)?;
        let jet = sweep.jet();
        for p in sweep {
            sink(p);
        }
        Ok(jet)
    }

    fn level(&self, m: u32) -> Option<&Level<R>> {
        match m {
            0 => Some(&self.level0),
            _ => self.levels.get(m as usize - 1),
        }
    }
}

/// [`Error::NonFinite`] unless every coordinate of `pole` and `links` is at
/// most `MAX/(16·max(n, 4))` in magnitude (see [`PolarStream::sweep`]).
fn fits<R: Real, L: AsRef<[[R; 3]]>>(pole: &[R; 3], links: &[L], n: usize) -> Result<(), Error> {
    let mut m = R::ZERO;
    for c in links
        .iter()
        .flat_map(|l| l.as_ref().iter().flatten())
        .chain(pole)
    {
        let a = c.abs();
        if a > m {
            m = a;
        }
    }
    if (m * (R::from_usize(n.max(4)) * R::from_f64(16.0))).is_finite() {
        Ok(())
    } else {
        Err(Error::NonFinite)
    }
}

/// Terms summed plainly before a compensated addition (as the in-place
/// path's Fourier sums).
const BLOCK: usize = 32;

/// The pole and the Fourier sums of the level-0 1-link (docs/math/c2ps.md §2), roots
/// `ω^h`, `ω^{2h}` by repeated squaring in `f64`: plain sums within blocks of
/// [`BLOCK`] terms, Kahan-compensated across blocks.
fn level0_sums<R: Real>(pole: [R; 3], link: &[[R; 3]], w: (f64, f64)) -> Sums<R> {
    let n = link.len();
    let mut sum = [Point3::ZERO; 5];
    let mut carry = [Point3::ZERO; 5];
    for (b, block) in link.chunks(BLOCK).enumerate() {
        let mut part = [Point3::ZERO; 5];
        for (i, q) in block.iter().enumerate() {
            let h = b * BLOCK + i;
            let q = Point3(*q);
            let (c, s) = power(w, h);
            let (c2, s2) = power(w, (2 * h) % n.max(1));
            let (c, s, c2, s2) = (
                R::from_f64(c),
                R::from_f64(s),
                R::from_f64(c2),
                R::from_f64(s2),
            );
            part[0] += q;
            part[1] += q * c;
            part[2] += q * s;
            part[3] += q * c2;
            part[4] += q * s2;
        }
        for ((s, c), p) in sum.iter_mut().zip(carry.iter_mut()).zip(part) {
            let y = p - *c;
            let t = *s + y;
            *c = (t - *s) - y;
            *s = t;
        }
    }
    let inv = if n == 0 {
        R::ZERO
    } else {
        R::ONE / R::from_usize(n)
    };
    let mut total = [Point3::ZERO; 5];
    for ((t, s), c) in total.iter_mut().zip(sum).zip(carry) {
        *t = (s - c) * inv;
    }
    let [a, c1, s1, c2, s2] = total;
    Sums {
        pole: Point3(pole),
        a,
        c1,
        s1,
        c2,
        s2,
    }
}

/// The eigencoefficients `p0..p5` of level 0 (docs/math/c2ps.md §4, the paper's Table 1
/// normalisation), as [`PoleJet::of`] computes them.
fn jet_of<R: Real>(f: &Sums<R>) -> PoleJet<R> {
    let two = R::from_f64(2.0);
    let three = R::from_f64(3.0);
    PoleJet {
        p: [
            f.pole * R::ratio(2, 3) + f.a * R::ratio(1, 3),
            f.c1 * two,
            f.s1 * two,
            f.a - f.pole,
            f.c2 * three,
            f.s2 * three,
        ],
    }
}

/// A running sweep: an iterator over the ring patches of levels
/// `from_level..=depth` (levels whose configuration holds links 1..5 only:
/// from level 0 with 5 or more input links, level 1 with 3 or 4, level 2
/// with 2 — docs/math/c2ps.md §2, as [`PolarNetInner::ring_patches`]).
///
/// **Order.** The sweep pulls columns through the levels depth-first. Within
/// a level, patches arrive by increasing column `j = 0..N−1`, both spans of a
/// column together (span 0 first); the levels are interleaved in the angular
/// order the sweep reaches them (a level-`m` column `j` is delivered once
/// the deeper levels have consumed what they need of it). Each patch says
/// where it belongs ([`StreamedPatch::level`], `span`, `column`); every
/// `(level, span, column)` is delivered exactly once.
#[derive(Debug)]
pub struct Sweep<'a, R, L, const D: usize> {
    state: &'a mut PolarStream<R, D>,
    links: &'a [L],
    options: StreamOptions,
    /// The level that advances next.
    cursor: u32,
    /// `(level, column number, next span)` of patches ready in a window.
    pending: Option<(u32, usize, u8)>,
    left: usize,
    done: bool,
    jet: PoleJet<R>,
}

impl<R: Real, L: AsRef<[[R; 3]]>, const D: usize> Sweep<'_, R, L, D> {
    /// The pole jet `p0..p5` of the configuration (docs/math/c2ps.md §4, level-0
    /// normalisation: [`PoleJet::of`] of the level-0 net). At level `m` the
    /// coefficients are `λ_k^m p_k` (Lemma 5).
    #[inline]
    pub fn jet(&self) -> PoleJet<R> {
        self.jet
    }

    /// The valence of level `m` (`n·2^m`), `None` beyond the sweep's depth.
    pub fn valence(&self, m: u32) -> Option<usize> {
        if m > self.options.depth {
            return None;
        }
        self.state.level(m).map(|l| l.n)
    }

    /// Produces one column somewhere (or moves the cursor), queueing the
    /// patches it completes.
    fn advance(&mut self) {
        let m = self.cursor;
        let depth = self.options.depth;
        if m == 0 {
            let lv = &mut self.state.level0;
            if lv.finished() {
                self.done = true;
                return;
            }
            let i = lv.count;
            let col = level0_column(self.links, lv, i);
            lv.win[i % 4] = col;
            lv.count += 1;
            self.queue(0, i);
            if depth > 0 {
                self.cursor = 1;
            }
            return;
        }
        let uniform_first = m == 1 && self.options.first == FirstStep::Uniform;
        let st = &mut *self.state;
        let (lo, hi) = match m {
            1 => (&st.level0, st.levels.first_mut()),
            _ => match st.levels.split_at_mut_checked(m as usize - 1) {
                Some((a, b)) => match a.last() {
                    Some(lo) => (lo, b.first_mut()),
                    None => return self.stop(),
                },
                None => return self.stop(),
            },
        };
        let Some(hi) = hi else {
            return self.stop();
        };
        if hi.finished() {
            // Only the deepest level finishes while the cursor is on it.
            return self.stop();
        }
        let i = hi.count;
        if lo.count >= i / 2 + 3 {
            let col = next_column(lo, hi, i, uniform_first);
            hi.win[i % 4] = col;
            hi.count += 1;
            self.queue(m, i);
            if m < depth {
                self.cursor = m + 1;
            }
        } else {
            self.cursor = m - 1;
        }
    }

    fn stop(&mut self) {
        self.done = true;
    }

    /// After column number `i` of level `m`: patches of column `i − 4`, if
    /// that is a column of the ring and the options deliver it.
    fn queue(&mut self, m: u32, i: usize) {
        let Some(lv) = self.state.level(m) else {
            return;
        };
        if lv.link_count < 5 || m < self.options.from_level || i < 4 || i - 4 >= lv.n {
            return;
        }
        self.pending = Some((m, i, self.options.span.unwrap_or(0)));
    }

    /// The next queued patch, if any.
    fn take(&mut self) -> Option<StreamedPatch<R>> {
        let (m, i, span) = self.pending?;
        let last = self.options.span.is_some() || span >= 1;
        self.pending = if last { None } else { Some((m, i, span + 1)) };
        let lv = self.state.level(m)?;
        // B-spline control points: links span+1..span+4 at columns j−1..j+2,
        // i.e. column numbers i−3..i (docs/math/c2ps.md §5).
        let mut d = [[Point3::ZERO; 4]; 4];
        for (k, row) in d.iter_mut().enumerate() {
            for (l, p) in row.iter_mut().enumerate() {
                let col = lv.col(i - 3 + l);
                *p = col
                    .q
                    .get(usize::from(span) + k)
                    .copied()
                    .unwrap_or_default();
            }
        }
        Some(StreamedPatch {
            level: m,
            span,
            column: i - 4,
            valence: lv.n,
            patch: BicubicPatch {
                points: bspline_to_bezier_cubic(&d),
            },
        })
    }
}

/// Column number `i` (virtual index `i − 2`, mod `n`) of the input.
fn level0_column<R: Real, L: AsRef<[[R; 3]]>>(links: &[L], lv: &Level<R>, i: usize) -> Column<R> {
    let n = lv.n;
    let k = (i + n - 2).checked_rem(n).unwrap_or(0);
    let mut q = [Point3::ZERO; 5];
    for (dst, l) in q.iter_mut().zip(links) {
        *dst = Point3(l.as_ref().get(k).copied().unwrap_or_default());
    }
    let w = primitive_root(n).unwrap_or((1.0, 0.0));
    let (c, s) = power(w, k);
    Column {
        q,
        r: [R::from_f64(c), R::from_f64(s)],
    }
}

impl<R: Real, L: AsRef<[[R; 3]]>, const D: usize> Iterator for Sweep<'_, R, L, D> {
    type Item = StreamedPatch<R>;

    fn next(&mut self) -> Option<StreamedPatch<R>> {
        loop {
            if let Some(p) = self.take() {
                self.left = self.left.saturating_sub(1);
                return Some(p);
            }
            if self.done {
                return None;
            }
            self.advance();
        }
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left, Some(self.left))
    }
}

impl<R: Real, L: AsRef<[[R; 3]]>, const D: usize> ExactSizeIterator for Sweep<'_, R, L, D> {}
impl<R: Real, L: AsRef<[[R; 3]]>, const D: usize> core::iter::FusedIterator for Sweep<'_, R, L, D> {}
