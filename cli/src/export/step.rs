//! STEP (ISO 10303-21 clear text, schema `AUTOMOTIVE_DESIGN`, AP214) of a
//! whole surface as a boundary representation.
//!
//! - Every Bézier patch is one `ADVANCED_FACE` on a
//!   `B_SPLINE_SURFACE_WITH_KNOTS` of its own degree (3 or 4 in both
//!   directions): knots `(0, 1)` of multiplicity `degree + 1`
//!   (`.PIECEWISE_BEZIER_KNOTS.`), control points row by row along `u`, so
//!   the surface's `(u, v)` is the patch's. Regular grid regions are **not**
//!   merged into larger B-spline surfaces: one face per patch keeps every
//!   face exactly one of capdiv's patches.
//! - Faces share their `EDGE_CURVE`s and `VERTEX_POINT`s: patch corners are
//!   welded by position ([`weld::representatives`], the tessellator's weld),
//!   and an edge is shared by the faces whose boundary pieces have the same
//!   two vertices and the same midpoint. A patch edge met by two patches of
//!   half its size ([`PatchRecord::finer`]) is split at its midpoint: the
//!   face's loop then has more than four edges, each piece's curve being the
//!   half of the Bézier boundary curve (de Casteljau at ½).
//! - Each edge's curve is a `SURFACE_CURVE`: its 3D curve a
//!   `B_SPLINE_CURVE_WITH_KNOTS`, the boundary curve (or half of it) of the
//!   first face that uses it in Bézier form, and one `PCURVE` per face using
//!   it: the straight segment of that face's `(u, v)` square (a degree-1
//!   B-spline) that the face's surface maps onto the curve with the same
//!   parameter. A reader then has each face's exact parameter domain and
//!   need not project curves onto surfaces.
//!   Boundary pieces whose control points all weld into one point (a polar
//!   patch's pole side, the limit-point side of a hole fill) are collapsed
//!   edges and are left out of the loop (a reader adds its degenerate edge).
//! - Each cap's last hole ([`PatchRecord::hole`]) is closed by one *hole
//!   fill* face per hole edge: the ruled patch between that edge and the
//!   cap's limit point, `F(u, v) = (1 − v)·e(1 − u) + v·L`, degree-elevated
//!   to the edge's degree, its side `v = 1` collapsed to `L`. The fills meet
//!   their ring patch and each other with position continuity only (C0), and
//!   meet at `L`; the hole shrinks with `--depth` (its size halves a ring).
//! - Faces are oriented by `∂u × ∂v` (`same_sense = .T.`, loops
//!   counter-clockwise in `(u, v)`). When every edge has exactly two faces
//!   the faces form a `CLOSED_SHELL` in a `MANIFOLD_SOLID_BREP`
//!   (`ADVANCED_BREP_SHAPE_REPRESENTATION`); otherwise an `OPEN_SHELL` in a
//!   `SHELL_BASED_SURFACE_MODEL` (`MANIFOLD_SURFACE_SHAPE_REPRESENTATION`).
//! - Units: one model unit is one millimetre (`SI_UNIT(.MILLI.,.METRE.)`);
//!   the distance uncertainty is [`UNCERTAINTY`] × the model size. Numbers
//!   are written exactly (shortest round-trip, [`write_number`]).
//! - Memory: the export's lists (faces, boundary pieces, vertices, edges,
//!   loops, instance numbers) and its text are reserved fallibly
//!   ([`capdiv_mesh::mem`], `String::try_reserve`), and a refusal is an
//!   [`OutOfMemory`] error, not an abort.

use capdiv::{Point3, Real};
use capdiv_mesh::tessellate::{weld, write_number, PatchGeometry};
use capdiv_mesh::{mem, OutOfMemory, PatchRecord};
use std::collections::HashMap;
use std::fmt;

/// Distance uncertainty written to the file, relative to the model size.
pub const UNCERTAINTY: f64 = 1e-7;

/// A tensor-product Bézier patch of degree `degree` in `u` and in `v`, in
/// `f64`.
#[derive(Clone, Debug, PartialEq)]
pub struct Bezier {
    /// 3 or 4 (any degree ≥ 1 works).
    pub degree: usize,
    /// `(degree + 1)²` control points, `net[(degree + 1)·i + j] = b_ij`,
    /// `i` along `u`.
    pub net: Vec<[f64; 3]>,
}

/// Where a face comes from.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum FaceKind {
    /// One of capdiv's patches (index into the evaluator's patches).
    Patch(usize),
    /// A hole fill: patch `patch`'s hole edge `edge` ruled to the limit point.
    HoleFill {
        /// The ring patch.
        patch: usize,
        /// Its edge, in `capdiv_mesh::tessellate`'s edge numbering.
        edge: u8,
    },
}

/// One face to write.
#[derive(Clone, Debug, PartialEq)]
pub struct StepFace {
    /// Its surface.
    pub surface: Bezier,
    /// Edges split at their midpoint (bit `e`: edge `e`).
    pub finer: u8,
    /// Its origin.
    pub kind: FaceKind,
}

impl Bezier {
    fn n(&self) -> usize {
        self.degree + 1
    }

    /// `b_ij`.
    pub fn at(&self, i: usize, j: usize) -> [f64; 3] {
        self.net[self.n() * i + j]
    }

    /// From a patch's geometry.
    pub fn of<R: Real>(g: &PatchGeometry<R>) -> Result<Self, OutOfMemory> {
        fn net<R: Real, const K: usize>(
            p: &[[capdiv::Point3<R>; K]; K],
        ) -> Result<Vec<[f64; 3]>, OutOfMemory> {
            let mut net = mem::with_capacity(K * K)?;
            net.extend(p.iter().flatten().map(|q| q.0.map(|x| x.to_f64())));
            Ok(net)
        }
        Ok(match g {
            PatchGeometry::Cubic(t) => Bezier {
                degree: 3,
                net: net(&t.points)?,
            },
            PatchGeometry::Quartic(t) => Bezier {
                degree: 4,
                net: net(&t.points)?,
            },
        })
    }

    /// Control points of boundary edge `e`, in the loop's direction
    /// (counter-clockwise in `(u, v)`: `v = 0` with `u` rising, `u = 1` with
    /// `v` rising, `v = 1` with `u` falling, `u = 0` with `v` falling).
    pub fn edge(&self, e: u8) -> Result<Vec<[f64; 3]>, OutOfMemory> {
        let d = self.degree;
        mem::collect((0..=d).map(|k| match e & 3 {
            0 => self.at(k, 0),
            1 => self.at(d, k),
            2 => self.at(d - k, d),
            _ => self.at(0, d - k),
        }))
    }

    /// The point and the partial derivatives at `(u, v)`.
    pub fn eval(&self, u: f64, v: f64) -> [[f64; 3]; 3] {
        let n = self.n();
        // Each u-row (fixed i, the net's `n` points from `n·i`) evaluated in
        // v, with its v-derivative.
        let (mut stack, mut heap);
        let (col, col_v) = if n <= STACK {
            stack = [[0.0; 3]; 2 * STACK];
            stack.split_at_mut(STACK)
        } else {
            heap = vec![[0.0; 3]; 2 * n];
            heap.split_at_mut(n)
        };
        for (i, row) in self.net.chunks_exact(n).take(n).enumerate() {
            let (p, dp) = curve_eval(row, v);
            col[i] = p;
            col_v[i] = dp;
        }
        let (p, pu) = curve_eval(&col[..n], u);
        let (pv, _) = curve_eval(&col_v[..n], u);
        [p, pu, pv]
    }
}

/// The most control points a curve's de Casteljau copy holds on the stack
/// (degree 7; capdiv's patches have degree 3 or 4). Longer curves copy to
/// the heap (infallibly, as they are never made here).
const STACK: usize = 8;

/// `f` on a working copy of `c` (on the stack when `c` has at most
/// [`STACK`] points).
fn on_copy<T>(c: &[[f64; 3]], f: impl FnOnce(&mut [[f64; 3]]) -> T) -> T {
    if c.len() <= STACK {
        let mut b = [[0.0; 3]; STACK];
        b[..c.len()].copy_from_slice(c);
        f(&mut b[..c.len()])
    } else {
        f(&mut c.to_vec())
    }
}

/// A Bézier curve's point and derivative at `t` (de Casteljau).
pub fn curve_eval(c: &[[f64; 3]], t: f64) -> ([f64; 3], [f64; 3]) {
    let d = c.len() - 1;
    if d == 0 {
        return (c[0], [0.0; 3]);
    }
    on_copy(c, |b| {
        for r in (1..d).rev() {
            for k in 0..=r {
                b[k] = lerp(b[k], b[k + 1], t);
            }
        }
        let p = lerp(b[0], b[1], t);
        let dp = (Point3(b[1]) - Point3(b[0])).0.map(|x| x * d as f64);
        (p, dp)
    })
}

/// The two halves of a Bézier curve split at `t = ½` (de Casteljau).
#[allow(clippy::type_complexity)]
pub fn split_half(c: &[[f64; 3]]) -> Result<(Vec<[f64; 3]>, Vec<[f64; 3]>), OutOfMemory> {
    let d = c.len() - 1;
    let mut left = mem::with_capacity(d + 1)?;
    let mut right = mem::with_capacity(d + 1)?;
    on_copy(c, |b| {
        left.push(b[0]);
        right.push(b[d]);
        for r in (0..d).rev() {
            for k in 0..=r {
                b[k] = lerp(b[k], b[k + 1], 0.5);
            }
            left.push(b[0]);
            right.push(b[r]);
        }
    });
    right.reverse();
    Ok((left, right))
}

fn lerp(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    [0, 1, 2].map(|k| a[k] + (b[k] - a[k]) * t)
}

fn dist(a: [f64; 3], b: [f64; 3]) -> f64 {
    (Point3(a) - Point3(b)).norm()
}

/// The faces of a surface: every patch in order, then one hole fill per
/// hole edge (patch by patch, edge by edge).
pub fn faces<R: Real>(patches: &[PatchRecord<R>]) -> Result<Vec<StepFace>, OutOfMemory> {
    let fills: usize = patches
        .iter()
        .map(|p| (p.hole & 15).count_ones() as usize)
        .sum();
    let mut out = mem::with_capacity(patches.len().saturating_add(fills))?;
    for (k, p) in patches.iter().enumerate() {
        out.push(StepFace {
            surface: Bezier::of(&p.geometry)?,
            finer: p.finer & 15,
            kind: FaceKind::Patch(k),
        });
    }
    for (k, p) in patches.iter().enumerate() {
        for e in 0..4u8 {
            if p.hole & (1 << e) != 0 {
                // The ring is face `k`.
                let edge = out[k].surface.edge(e)?;
                let limit = p.hole_point.0.map(|x| x.to_f64());
                out.push(StepFace {
                    surface: hole_fill(&edge, limit)?,
                    finer: 0,
                    kind: FaceKind::HoleFill { patch: k, edge: e },
                });
            }
        }
    }
    Ok(out)
}

/// The ruled patch from a hole edge (control points in its ring patch's loop
/// direction) to the limit point: row `v = 0` is the edge reversed (the
/// fill runs along the shared edge the other way, so it is oriented like
/// the ring), row `v = j/d` is `(1 − j/d)·edge + (j/d)·limit` (the linear
/// ruling degree-elevated), row `v = 1` is the limit point.
pub fn hole_fill(edge: &[[f64; 3]], limit: [f64; 3]) -> Result<Bezier, OutOfMemory> {
    let d = edge.len() - 1;
    let mut net = mem::with_capacity((d + 1) * (d + 1))?;
    for i in 0..=d {
        let e = edge[d - i];
        for j in 0..=d {
            net.push(if j == d {
                limit
            } else {
                lerp(e, limit, j as f64 / d as f64)
            });
        }
    }
    Ok(Bezier { degree: d, net })
}

/// An edge of the B-rep: its curve runs from `start` to `end`.
#[derive(Clone, Debug, PartialEq)]
pub struct Edge {
    /// First vertex.
    pub start: usize,
    /// Last vertex.
    pub end: usize,
    /// Bézier control points of its curve.
    pub curve: Vec<[f64; 3]>,
    /// Faces using it.
    pub uses: usize,
    /// The boundary piece its curve is (numbered face by face, edge by
    /// edge, the halves of a split edge in order).
    pub piece: usize,
    /// Per face using it: the face and the points of its `(u, v)` square
    /// where the curve starts and ends (the curve is that straight segment
    /// of the square mapped by the face's surface, with the same parameter).
    pub pcurves: Vec<(usize, [[f64; 2]; 2])>,
}

/// The B-rep's topology: welded vertices, shared edges, one loop per face.
#[derive(Clone, Debug, PartialEq)]
pub struct Brep {
    /// The faces.
    pub faces: Vec<StepFace>,
    /// Vertex positions.
    pub vertices: Vec<[f64; 3]>,
    /// Per vertex: the piece end it was taken from (`2k`: start of piece
    /// `k`, `2k + 1`: its end).
    pub vertex_end: Vec<usize>,
    /// Edges.
    pub edges: Vec<Edge>,
    /// Per face: its loop, `(edge, same direction as the edge's curve)`.
    pub loops: Vec<Vec<(usize, bool)>>,
    /// Boundary pieces left out as collapsed.
    pub collapsed: usize,
}

impl Brep {
    /// Every edge has exactly two faces, running it in opposite directions
    /// (or the error when the per-edge count cannot be allocated).
    pub fn is_closed(&self) -> Result<bool, OutOfMemory> {
        let mut sense = mem::filled(self.edges.len(), (0usize, 0usize))?;
        for l in &self.loops {
            for &(e, same) in l {
                if same {
                    sense[e].0 += 1;
                } else {
                    sense[e].1 += 1;
                }
            }
        }
        Ok(!self.edges.is_empty() && sense.iter().all(|&s| s == (1, 1)))
    }

    /// Edges with one face.
    pub fn free_edges(&self) -> usize {
        self.edges.iter().filter(|e| e.uses == 1).count()
    }
}

/// A boundary piece of a face: a whole edge, or half of a `finer` one.
#[derive(Clone, Debug)]
struct Piece {
    /// The face.
    face: usize,
    /// Its edge, in `capdiv_mesh::tessellate`'s edge numbering.
    edge: u8,
    /// The part of the edge, as the edge's own parameter in the loop's
    /// direction: `[0, 1]`, `[0, ½]` or `[½, 1]`.
    span: [f64; 2],
    /// Control points in the loop's direction.
    curve: Vec<[f64; 3]>,
}

impl Piece {
    /// End `end` of the piece: 0 its start, 1 its end.
    fn end(&self, end: usize) -> [f64; 3] {
        if end == 0 {
            self.curve[0]
        } else {
            self.curve[self.curve.len() - 1]
        }
    }
}

/// The point `(u, v)` of a face's square at parameter `s` of its edge `e`,
/// `s` running in the loop's direction.
fn edge_uv(e: u8, s: f64) -> [f64; 2] {
    match e & 3 {
        0 => [s, 0.0],
        1 => [1.0, s],
        2 => [1.0 - s, 1.0],
        _ => [0.0, 1.0 - s],
    }
}

/// The number of boundary pieces of a face: 4, and one more per `finer`
/// edge.
fn piece_count(face: &StepFace) -> usize {
    4 + (face.finer & 15).count_ones() as usize
}

/// The boundary pieces of `faces`, face by face, edge by edge (halves of a
/// `finer` edge in order).
fn pieces(faces: &[StepFace]) -> Result<Vec<Piece>, OutOfMemory> {
    let mut out = mem::with_capacity(faces.iter().map(piece_count).sum())?;
    for (f, face) in faces.iter().enumerate() {
        for e in 0..4u8 {
            let c = face.surface.edge(e)?;
            let piece = |span, curve| Piece {
                face: f,
                edge: e,
                span,
                curve,
            };
            if face.finer & (1 << e) != 0 {
                let (a, b) = split_half(&c)?;
                out.push(piece([0.0, 0.5], a));
                out.push(piece([0.5, 1.0], b));
            } else {
                out.push(piece([0.0, 1.0], c));
            }
        }
    }
    Ok(out)
}

/// The end points of `pieces`: `2k` the start and `2k + 1` the end of piece `k`.
fn piece_ends(pieces: &[Piece]) -> Result<Vec<capdiv::Point3<f64>>, OutOfMemory> {
    let mut out = mem::with_capacity(pieces.len().saturating_mul(2))?;
    out.extend(
        pieces
            .iter()
            .flat_map(|p| [p.end(0), p.end(1)].map(capdiv::Point3)),
    );
    Ok(out)
}

/// Builds the topology of `faces`: boundary pieces (whole edges, or halves
/// of the `finer` ones) whose end points weld within `tol` share vertices;
/// pieces with the same two vertices and midpoints within `mid_tol` share an
/// edge (each edge at most two faces); pieces whose control points all lie
/// within `tol` of their start are collapsed. The error when a list of the
/// B-rep cannot be allocated.
pub fn brep(faces: Vec<StepFace>, tol: f64, mid_tol: f64) -> Result<Brep, OutOfMemory> {
    let mut b = topology(&faces, tol, mid_tol)?;
    b.faces = faces;
    Ok(b)
}

/// [`brep`] of `faces` but for its face list (left empty).
fn topology(faces: &[StepFace], tol: f64, mid_tol: f64) -> Result<Brep, OutOfMemory> {
    let pieces = pieces(faces)?;
    let ends = piece_ends(&pieces)?;
    let rep = weld::representatives(&ends, tol)?;
    // A class's representative is its first point: one vertex each.
    let classes = (rep.iter().enumerate())
        .filter(|&(k, &r)| r as usize == k)
        .count();
    let mut vertex_of = mem::filled(ends.len(), usize::MAX)?;
    let mut vertices = mem::with_capacity(classes)?;
    let mut vertex_end = mem::with_capacity(classes)?;
    for k in 0..ends.len() {
        let r = rep[k] as usize;
        if vertex_of[r] == usize::MAX {
            vertex_of[r] = vertices.len();
            mem::push(&mut vertices, ends[r].0)?;
            mem::push(&mut vertex_end, r)?;
        }
        vertex_of[k] = vertex_of[r];
    }
    drop(ends);
    let mut edges: Vec<Edge> = Vec::new();
    // The edges with the same two vertices, in the order made: the first
    // and the last per vertex pair, and per edge the next one (`usize::MAX`
    // after the last). At most one pair per piece.
    let mut by_ends: HashMap<(usize, usize), (usize, usize)> = HashMap::new();
    by_ends
        .try_reserve(pieces.len())
        .map_err(|_| OutOfMemory::of::<((usize, usize), (usize, usize))>(pieces.len()))?;
    let mut next: Vec<usize> = Vec::new();
    let mut loops = mem::with_capacity(faces.len())?;
    for face in faces {
        loops.push(mem::with_capacity(piece_count(face))?);
    }
    let mut collapsed = 0;
    for (k, piece) in pieces.into_iter().enumerate() {
        let Piece {
            face: f,
            edge,
            span,
            curve: c,
        } = piece;
        let (a, b) = (vertex_of[2 * k], vertex_of[2 * k + 1]);
        // The piece's ends in its face's square, in the loop's direction.
        let ends = span.map(|s| edge_uv(edge, s));
        if a == b && c.iter().all(|&p| dist(p, c[0]) <= tol) {
            collapsed += 1;
            continue;
        }
        let mid = curve_eval(&c, 0.5).0;
        let key = (a.min(b), a.max(b));
        let mut found = None;
        if let Some(&(first, _)) = by_ends.get(&key) {
            let mut e = first;
            while e != usize::MAX {
                let edge = &edges[e];
                if edge.uses < 2 && dist(curve_eval(&edge.curve, 0.5).0, mid) <= mid_tol {
                    found = Some(e);
                    break;
                }
                e = next[e];
            }
        }
        match found {
            Some(e) => {
                edges[e].uses += 1;
                // A closed edge (a == b) runs the way its quarter point says.
                let same = if a != b {
                    edges[e].start == a
                } else {
                    dist(curve_eval(&edges[e].curve, 0.25).0, curve_eval(&c, 0.25).0) <= mid_tol
                };
                mem::push(&mut loops[f], (e, same))?;
                let [p, q] = ends;
                mem::push(
                    &mut edges[e].pcurves,
                    (f, if same { [p, q] } else { [q, p] }),
                )?;
            }
            None => {
                let e = edges.len();
                // An edge has at most two faces.
                let mut pcurves = mem::with_capacity(2)?;
                pcurves.push((f, ends));
                mem::push(
                    &mut edges,
                    Edge {
                        start: a,
                        end: b,
                        curve: c,
                        uses: 1,
                        piece: k,
                        pcurves,
                    },
                )?;
                mem::push(&mut next, usize::MAX)?;
                mem::push(&mut loops[f], (e, true))?;
                // Within the reservation: no allocation.
                match by_ends.get_mut(&key) {
                    Some((_, last)) => {
                        next[*last] = e;
                        *last = e;
                    }
                    None => {
                        by_ends.insert(key, (e, e));
                    }
                }
            }
        }
    }
    Ok(Brep {
        faces: Vec::new(),
        vertices,
        vertex_end,
        edges,
        loops,
        collapsed,
    })
}

/// [`brep`] with the topology of `guide` (the same patches in a higher
/// precision: where `f32` patches of a deep cap lie closer together than
/// `f32` rounding lets a tolerance tell apart, the `f64` ones weld exactly)
/// and the geometry of `faces`: each vertex and edge curve is taken from the
/// same corner and boundary piece of `faces`. Without a matching guide (not
/// the same faces, degrees and split edges) it is `brep(faces, …)`.
pub fn brep_guided(
    faces: Vec<StepFace>,
    guide: &[StepFace],
    tol: f64,
    mid_tol: f64,
) -> Result<Brep, OutOfMemory> {
    let matches = guide.len() == faces.len()
        && guide.iter().zip(&faces).all(|(g, f)| {
            g.finer == f.finer && g.kind == f.kind && g.surface.degree == f.surface.degree
        });
    if !matches {
        return brep(faces, tol, mid_tol);
    }
    let mut b = topology(guide, tol, mid_tol)?;
    let mut pieces = pieces(&faces)?;
    for (v, &k) in b.vertices.iter_mut().zip(&b.vertex_end) {
        *v = pieces[k / 2].end(k % 2);
    }
    // Each edge is its own piece's.
    for e in &mut b.edges {
        e.curve = std::mem::take(&mut pieces[e.piece].curve);
    }
    b.faces = faces;
    Ok(b)
}

/// The enclosed volume `⅓ ∬ P · (P_u × P_v) du dv` summed over the faces
/// (divergence theorem; exact for a closed, outward-oriented surface), by
/// 6-point Gauss–Legendre quadrature in `u` and `v`: the integrand of a
/// degree-`d` patch has degree `3d − 1 ≤ 11` in each parameter, which 6
/// points integrate exactly.
pub fn volume(faces: &[StepFace]) -> f64 {
    const X: [f64; 3] = [
        0.238_619_186_083_196_9,
        0.661_209_386_466_264_5,
        0.932_469_514_203_152,
    ];
    const W: [f64; 3] = [
        0.467_913_934_572_691,
        0.360_761_573_048_138_6,
        0.171_324_492_379_170_3,
    ];
    let nodes = [0, 1, 2].map(|k| {
        [
            ((1.0 - X[k]) / 2.0, W[k] / 2.0),
            ((1.0 + X[k]) / 2.0, W[k] / 2.0),
        ]
    });
    let nodes = nodes.as_flattened();
    let mut total = 0.0;
    for f in faces {
        for &(u, wu) in nodes {
            for &(v, wv) in nodes {
                let [p, pu, pv] = f.surface.eval(u, v);
                total += wu * wv * Point3(p).dot(Point3(pu).cross(Point3(pv)));
            }
        }
    }
    total / 3.0
}

/// The largest side of the bounding box of every control point (0 for none).
pub fn model_size(faces: &[StepFace]) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for p in faces.iter().flat_map(|f| &f.surface.net) {
        for k in 0..3 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    let s = (0..3).map(|k| hi[k] - lo[k]).fold(0.0f64, f64::max);
    if s.is_finite() {
        s
    } else {
        0.0
    }
}

/// A real in ISO 10303-21's form (§6.3.3: a decimal point always, `E` for
/// the exponent): `1.`, `0.25`, `-4.6053215007904947E-14`; the digits of
/// [`write_number`] (shortest round-trip), so the value reads back exactly.
/// Written in place: `text` grows by the number's length and at most one
/// byte more.
pub fn real(text: &mut String, x: f64) {
    let start = text.len();
    write_number(text, x);
    match text[start..].find('e') {
        Some(k) => {
            let e = start + k;
            text.replace_range(e..e + 1, "E");
            if !text[start..e].contains('.') {
                text.insert(e, '.');
            }
        }
        None => {
            if !text[start..].contains('.') {
                text.push('.');
            }
        }
    }
}

/// The most bytes [`real`] writes (an `f64`'s shortest round-trip digits,
/// sign, point and exponent take at most 25).
const REAL_BYTES: usize = 32;

/// A STEP string literal (§6.3.4): `'` doubled, only printable ASCII kept
/// (others become `?`).
pub fn string(text: &mut String, s: &str) {
    text.push('\'');
    for c in s.chars() {
        match c {
            '\'' => text.push_str("''"),
            '\\' => text.push_str("\\\\"),
            ' '..='~' => text.push(c),
            _ => text.push('?'),
        }
    }
    text.push('\'');
}

/// Text whose growth is fallible: room is reserved
/// (`String::try_reserve_exact`) before anything is written, and a refusal
/// is an [`OutOfMemory`] error (through [`fmt::Write`], the first refusal
/// is kept and the write fails).
#[derive(Debug, Default)]
struct Text {
    text: String,
    refused: Option<OutOfMemory>,
}

impl Text {
    /// The least the text grows by.
    const STEP: usize = 1 << 16;

    /// Room for `additional` more bytes. The text grows by an eighth of its
    /// size (at least [`Text::STEP`]), not by doubling: what it holds past
    /// the file's end stays under an eighth of the file.
    fn reserve(&mut self, additional: usize) -> Result<(), OutOfMemory> {
        let (len, capacity) = (self.text.len(), self.text.capacity());
        if capacity - len >= additional {
            return Ok(());
        }
        let grown = capacity.saturating_add((capacity / 8).max(Self::STEP));
        let bytes = len.saturating_add(additional).max(grown);
        self.text
            .try_reserve_exact(bytes - len)
            .map_err(|_| OutOfMemory { bytes })
    }

    /// Appends `s`.
    fn push(&mut self, s: &str) -> Result<(), OutOfMemory> {
        self.reserve(s.len())?;
        self.text.push_str(s);
        Ok(())
    }

    /// Appends the formatted `args`.
    fn format(&mut self, args: fmt::Arguments) -> Result<(), OutOfMemory> {
        match fmt::Write::write_fmt(self, args) {
            Ok(()) => Ok(()),
            // Formatting fails only when this text refuses to grow.
            Err(fmt::Error) => Err(self.refused.unwrap_or(OutOfMemory { bytes: usize::MAX })),
        }
    }

    /// Appends `x` as a STEP real ([`real`]).
    fn real(&mut self, x: f64) -> Result<(), OutOfMemory> {
        self.reserve(REAL_BYTES)?;
        real(&mut self.text, x);
        Ok(())
    }

    /// Appends `s` as a STEP string literal ([`string`]).
    fn string(&mut self, s: &str) -> Result<(), OutOfMemory> {
        // Each character takes at most two bytes, and two quotes.
        self.reserve(s.len().saturating_mul(2).saturating_add(2))?;
        string(&mut self.text, s);
        Ok(())
    }
}

impl fmt::Write for Text {
    fn write_str(&mut self, s: &str) -> fmt::Result {
        match self.push(s) {
            Ok(()) => Ok(()),
            Err(e) => {
                self.refused.get_or_insert(e);
                Err(fmt::Error)
            }
        }
    }
}

/// Instance references `#a,#b,…` (a STEP list's items).
struct Refs<'a>(&'a [usize]);

impl fmt::Display for Refs<'_> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        for (k, id) in self.0.iter().enumerate() {
            if k > 0 {
                f.write_str(",")?;
            }
            write!(f, "#{id}")?;
        }
        Ok(())
    }
}

/// A list of lists of references: `ids` in rows of `n`, `(#a,#b),(#c,#d)`.
struct Rows<'a>(&'a [usize], usize);

impl fmt::Display for Rows<'_> {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        for (k, row) in self.0.chunks(self.1).enumerate() {
            if k > 0 {
                f.write_str(",")?;
            }
            write!(f, "({})", Refs(row))?;
        }
        Ok(())
    }
}

/// A face's name: `patch k` or `hole fill k.e`.
struct Label(FaceKind);

impl fmt::Display for Label {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        match self.0 {
            FaceKind::Patch(k) => write!(f, "patch {k}"),
            FaceKind::HoleFill { patch, edge } => write!(f, "hole fill {patch}.{edge}"),
        }
    }
}

/// Entity instances numbered `#1, #2, …` in the order written, straight
/// into the file's text.
struct Data {
    text: Text,
    next: usize,
}

impl Data {
    /// Starts instance `#k=` and returns `k`.
    fn begin(&mut self) -> Result<usize, OutOfMemory> {
        let k = self.next;
        self.next += 1;
        self.text.format(format_args!("#{k}="))?;
        Ok(k)
    }

    /// Ends an instance: `;` and the line's end.
    fn end(&mut self) -> Result<(), OutOfMemory> {
        self.text.push(";\n")
    }

    /// Writes `#k=body;` and returns `k`.
    fn add(&mut self, body: fmt::Arguments) -> Result<usize, OutOfMemory> {
        let k = self.begin()?;
        self.text.format(body)?;
        self.end()?;
        Ok(k)
    }

    /// `CARTESIAN_POINT('',(x,y,z))`: a point in model units (or `(u,v)`,
    /// a point of a parameter square).
    fn point(&mut self, p: &[f64]) -> Result<usize, OutOfMemory> {
        let k = self.begin()?;
        self.text.push("CARTESIAN_POINT('',(")?;
        for (i, x) in p.iter().enumerate() {
            if i > 0 {
                self.text.push(",")?;
            }
            self.text.real(*x)?;
        }
        self.text.push("))")?;
        self.end()?;
        Ok(k)
    }

    /// `B_SPLINE_CURVE_WITH_KNOTS`: a Bézier curve of degree `d` as a
    /// B-spline with knots 0 and 1 of multiplicity `d + 1`.
    fn curve(&mut self, c: &[[f64; 3]]) -> Result<usize, OutOfMemory> {
        let d = c.len() - 1;
        let mut ids = mem::with_capacity(c.len())?;
        for p in c {
            ids.push(self.point(p)?);
        }
        self.add(format_args!(
            "B_SPLINE_CURVE_WITH_KNOTS('',{d},({}),.UNSPECIFIED.,.F.,.F.,({m},{m}),(0.,1.),\
             .PIECEWISE_BEZIER_KNOTS.)",
            Refs(&ids),
            m = d + 1
        ))
    }

    /// `PCURVE`: the straight segment `uv[0] → uv[1]` (parameter 0 to 1)
    /// of a surface's parameter square, as a `DEFINITIONAL_REPRESENTATION`
    /// of a degree-1 `B_SPLINE_CURVE_WITH_KNOTS` in the context `ctx`.
    fn pcurve(
        &mut self,
        surface: usize,
        uv: [[f64; 2]; 2],
        ctx: usize,
    ) -> Result<usize, OutOfMemory> {
        let ids = [self.point(&uv[0])?, self.point(&uv[1])?];
        let line = self.add(format_args!(
            "B_SPLINE_CURVE_WITH_KNOTS('',1,({}),.POLYLINE_FORM.,.F.,.F.,(2,2),(0.,1.),\
             .UNSPECIFIED.)",
            Refs(&ids)
        ))?;
        let rep = self.add(format_args!(
            "DEFINITIONAL_REPRESENTATION('',(#{line}),#{ctx})"
        ))?;
        self.add(format_args!("PCURVE('',#{surface},#{rep})"))
    }

    /// `B_SPLINE_SURFACE_WITH_KNOTS`: a tensor Bézier patch as a B-spline
    /// surface, `control_points_list[i][j] = b_ij` (`i` along `u`).
    fn surface(&mut self, s: &Bezier) -> Result<usize, OutOfMemory> {
        let d = s.degree;
        let n = s.n();
        let mut ids = mem::with_capacity(n * n)?;
        for i in 0..n {
            for j in 0..n {
                ids.push(self.point(&s.at(i, j))?);
            }
        }
        self.add(format_args!(
            "B_SPLINE_SURFACE_WITH_KNOTS('',{d},{d},({}),.UNSPECIFIED.,.F.,.F.,.F.,\
             ({m},{m}),({m},{m}),(0.,1.),(0.,1.),.PIECEWISE_BEZIER_KNOTS.)",
            Rows(&ids, n),
            m = d + 1
        ))
    }
}

/// What goes in the header and the product structure.
#[derive(Clone, Debug)]
pub struct Header {
    /// `FILE_NAME` name (the output file's name).
    pub file_name: String,
    /// The product's name (the input's name).
    pub product: String,
    /// `FILE_NAME` time stamp (ISO 8601).
    pub time_stamp: String,
    /// A line for `FILE_DESCRIPTION` (how the surface was made).
    pub description: String,
}

/// `t` as ISO 8601 UTC, `YYYY-MM-DDThh:mm:ss` (the `FILE_NAME` time stamp);
/// times before 1970 are written as 1970-01-01T00:00:00.
pub fn time_stamp(t: std::time::SystemTime) -> String {
    let secs = t
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_secs())
        .unwrap_or(0);
    let (days, rest) = ((secs / 86_400) as i64, secs % 86_400);
    // Civil date from days since 1970-01-01 (proleptic Gregorian).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let day = doy - (153 * mp + 2) / 5 + 1;
    let month = if mp < 10 { mp + 3 } else { mp - 9 };
    let year = yoe + era * 400 + i64::from(month <= 2);
    format!(
        "{year:04}-{month:02}-{day:02}T{:02}:{:02}:{:02}",
        rest / 3600,
        rest / 60 % 60,
        rest % 60
    )
}

/// The STEP file of `b`: header, product structure, units, and the shell;
/// or the error when its text (or a list of instance numbers) cannot be
/// allocated.
pub fn write(b: &Brep, h: &Header) -> Result<String, OutOfMemory> {
    let size = model_size(&b.faces);
    let uncertainty = if size > 0.0 { UNCERTAINTY * size } else { 1e-7 };
    let closed = b.is_closed()?;
    // One text, header and data: it grows as it is written.
    let mut d = Data {
        text: Text::default(),
        next: 1,
    };
    let t = &mut d.text;
    t.push("ISO-10303-21;\nHEADER;\nFILE_DESCRIPTION((")?;
    t.string(&h.description)?;
    t.push(",")?;
    let mut units = String::from("units: millimetre; distance uncertainty: ");
    real(&mut units, uncertainty);
    t.string(&units)?;
    t.push("),'2;1');\nFILE_NAME(")?;
    t.string(&h.file_name)?;
    t.push(",")?;
    t.string(&h.time_stamp)?;
    t.push(",(''),(''),'capdiv','capdiv surface','');\n")?;
    t.push("FILE_SCHEMA(('AUTOMOTIVE_DESIGN { 1 0 10303 214 1 1 1 1 }'));\nENDSEC;\nDATA;\n")?;
    // Product structure (AP214 part 1: a part with one shape).
    let app = d.add(format_args!(
        "APPLICATION_CONTEXT('core data for automotive mechanical design processes')"
    ))?;
    d.add(format_args!(
        "APPLICATION_PROTOCOL_DEFINITION('international standard','automotive_design',2000,#{app})"
    ))?;
    let pc = d.add(format_args!("PRODUCT_CONTEXT('',#{app},'mechanical')"))?;
    let mut name = String::new();
    string(&mut name, &h.product);
    let product = d.add(format_args!("PRODUCT({name},{name},'',(#{pc}))"))?;
    let pdf = d.add(format_args!(
        "PRODUCT_DEFINITION_FORMATION('','',#{product})"
    ))?;
    let pdc = d.add(format_args!(
        "PRODUCT_DEFINITION_CONTEXT('part definition',#{app},'design')"
    ))?;
    let pd = d.add(format_args!(
        "PRODUCT_DEFINITION('design','',#{pdf},#{pdc})"
    ))?;
    let pds = d.add(format_args!("PRODUCT_DEFINITION_SHAPE('','',#{pd})"))?;
    // Units and uncertainty: the geometric context of the representation.
    let length = d.add(format_args!(
        "(LENGTH_UNIT()NAMED_UNIT(*)SI_UNIT(.MILLI.,.METRE.))"
    ))?;
    let angle = d.add(format_args!(
        "(NAMED_UNIT(*)PLANE_ANGLE_UNIT()SI_UNIT($,.RADIAN.))"
    ))?;
    let solid_angle = d.add(format_args!(
        "(NAMED_UNIT(*)SI_UNIT($,.STERADIAN.)SOLID_ANGLE_UNIT())"
    ))?;
    let mut u = String::new();
    real(&mut u, uncertainty);
    let unc = d.add(format_args!(
        "UNCERTAINTY_MEASURE_WITH_UNIT(LENGTH_MEASURE({u}),#{length},'distance_accuracy_value',\
         'maximum distance between points taken as equal')"
    ))?;
    let ctx = d.add(format_args!(
        "(GEOMETRIC_REPRESENTATION_CONTEXT(3)GLOBAL_UNCERTAINTY_ASSIGNED_CONTEXT((#{unc}))\
         GLOBAL_UNIT_ASSIGNED_CONTEXT((#{length},#{angle},#{solid_angle}))\
         REPRESENTATION_CONTEXT('',''))"
    ))?;
    // The faces' parameter squares (for the edges' PCURVEs).
    let uv_ctx = d.add(format_args!(
        "(GEOMETRIC_REPRESENTATION_CONTEXT(2)PARAMETRIC_REPRESENTATION_CONTEXT()\
         REPRESENTATION_CONTEXT('2D SPACE',''))"
    ))?;
    // Geometry, then topology.
    let mut surface = mem::with_capacity(b.faces.len())?;
    for f in &b.faces {
        surface.push(d.surface(&f.surface)?);
    }
    let mut vertex = mem::with_capacity(b.vertices.len())?;
    for p in &b.vertices {
        let cp = d.point(p)?;
        vertex.push(d.add(format_args!("VERTEX_POINT('',#{cp})"))?);
    }
    let mut edge = mem::with_capacity(b.edges.len())?;
    for e in &b.edges {
        let c = d.curve(&e.curve)?;
        let mut pcurves = mem::with_capacity(e.pcurves.len())?;
        for &(f, uv) in &e.pcurves {
            pcurves.push(d.pcurve(surface[f], uv, uv_ctx)?);
        }
        let sc = d.add(format_args!(
            "SURFACE_CURVE('',#{c},({}),.CURVE_3D.)",
            Refs(&pcurves)
        ))?;
        edge.push(d.add(format_args!(
            "EDGE_CURVE('',#{},#{},#{sc},.T.)",
            vertex[e.start], vertex[e.end]
        ))?);
    }
    let mut face_ids = mem::with_capacity(b.faces.len())?;
    let mut oriented = Vec::new();
    for (f, face) in b.faces.iter().enumerate() {
        oriented.clear();
        mem::reserve(&mut oriented, b.loops[f].len())?;
        for &(e, same) in &b.loops[f] {
            let s = if same { ".T." } else { ".F." };
            oriented.push(d.add(format_args!("ORIENTED_EDGE('',*,*,#{},{s})", edge[e]))?);
        }
        let lp = d.add(format_args!("EDGE_LOOP('',({}))", Refs(&oriented)))?;
        let bound = d.add(format_args!("FACE_OUTER_BOUND('',#{lp},.T.)"))?;
        let surface = surface[f];
        face_ids.push(d.add(format_args!(
            "ADVANCED_FACE('{}',(#{bound}),#{surface},.T.)",
            Label(face.kind)
        ))?);
    }
    let list = Refs(&face_ids);
    let origin = d.point(&[0.0; 3])?;
    let z = d.add(format_args!("DIRECTION('',(0.,0.,1.))"))?;
    let x = d.add(format_args!("DIRECTION('',(1.,0.,0.))"))?;
    let axis = d.add(format_args!("AXIS2_PLACEMENT_3D('',#{origin},#{z},#{x})"))?;
    let rep = if closed {
        let shell = d.add(format_args!("CLOSED_SHELL('',({list}))"))?;
        let solid = d.add(format_args!("MANIFOLD_SOLID_BREP({name},#{shell})"))?;
        d.add(format_args!(
            "ADVANCED_BREP_SHAPE_REPRESENTATION({name},(#{axis},#{solid}),#{ctx})"
        ))?
    } else {
        let shell = d.add(format_args!("OPEN_SHELL('',({list}))"))?;
        let model = d.add(format_args!("SHELL_BASED_SURFACE_MODEL({name},(#{shell}))"))?;
        d.add(format_args!(
            "MANIFOLD_SURFACE_SHAPE_REPRESENTATION({name},(#{axis},#{model}),#{ctx})"
        ))?
    };
    d.add(format_args!(
        "SHAPE_DEFINITION_REPRESENTATION(#{pds},#{rep})"
    ))?;
    d.text.push("ENDSEC;\nEND-ISO-10303-21;\n")?;
    Ok(d.text.text)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The flat bicubic patch over the square `origin + u·a + v·b`.
    fn flat(origin: [f64; 3], a: [f64; 3], b: [f64; 3], finer: u8) -> StepFace {
        let mut net = Vec::new();
        for i in 0..4 {
            for j in 0..4 {
                let (s, t) = (i as f64 / 3.0, j as f64 / 3.0);
                net.push([0, 1, 2].map(|k| origin[k] + s * a[k] + t * b[k]));
            }
        }
        StepFace {
            surface: Bezier { degree: 3, net },
            finer,
            kind: FaceKind::Patch(0),
        }
    }

    /// The unit cube's six faces, `∂u × ∂v` outward.
    fn cube() -> Vec<StepFace> {
        let (o, x, y, z) = ([0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]);
        vec![
            flat(o, y, x, 0),               // z = 0, normal -z
            flat(z, x, y, 0),               // z = 1, normal +z
            flat(o, x, z, 0),               // y = 0, normal -y
            flat([0.0, 1.0, 0.0], z, x, 0), // y = 1, normal +y
            flat(o, z, y, 0),               // x = 0, normal -x
            flat([1.0, 0.0, 0.0], y, z, 0), // x = 1, normal +x
        ]
    }

    fn text(x: f64) -> String {
        let mut s = String::new();
        real(&mut s, x);
        s
    }

    #[test]
    fn reals_have_a_decimal_point_and_read_back_exactly() {
        assert_eq!(text(1.0), "1.");
        assert_eq!(text(0.0), "0.");
        assert_eq!(text(-0.25), "-0.25");
        assert_eq!(text(1e-20), "1.E-20");
        assert_eq!(text(1e300), "1.E300");
        for x in [0.1, 1.0 / 3.0, -4.6053215007904947e-14, 123456789.125] {
            let t = text(x).replace("E", "e");
            assert_eq!(t.parse::<f64>().unwrap(), x, "{t}");
        }
    }

    #[test]
    fn reals_are_appended_in_place() {
        let mut s = String::from("(1e5,");
        for x in [1e-20, 2.5, 3.0, -7e22] {
            real(&mut s, x);
            s.push(',');
        }
        assert_eq!(s, "(1e5,1.E-20,2.5,3.,-7.E22,");
    }

    #[test]
    fn text_grows_by_an_eighth() {
        let mut t = Text::default();
        let line = "#123=CARTESIAN_POINT('',(1.,2.,3.));\n";
        while t.text.len() < 4 << 20 {
            t.push(line).unwrap();
            let (len, capacity) = (t.text.len(), t.text.capacity());
            assert!(
                capacity - len <= (len / 8).max(Text::STEP),
                "{len} {capacity}"
            );
        }
        let mut d = Data { text: t, next: 7 };
        assert_eq!(d.point(&[0.5, -1.0]).unwrap(), 7);
        assert!(d
            .text
            .text
            .ends_with(";\n#7=CARTESIAN_POINT('',(0.5,-1.));\n"));
    }

    #[test]
    fn strings_escape_quotes_and_non_ascii() {
        let mut s = String::new();
        string(&mut s, "it's ü\\");
        assert_eq!(s, "'it''s ?\\\\'");
    }

    #[test]
    fn halves_of_a_curve_join_at_its_midpoint() {
        let c = [
            [0.0, 0.0, 0.0],
            [1.0, 2.0, 0.0],
            [3.0, 2.0, 1.0],
            [4.0, 0.0, 0.0],
        ];
        let (a, b) = split_half(&c).unwrap();
        let mid = curve_eval(&c, 0.5).0;
        assert_eq!(a[0], c[0]);
        assert_eq!(b[3], c[3]);
        assert_eq!(a[3], mid);
        assert_eq!(b[0], mid);
        for t in [0.1, 0.3, 0.77] {
            let whole = curve_eval(&c, t / 2.0).0;
            assert!(dist(curve_eval(&a, t).0, whole) < 1e-15);
            let whole = curve_eval(&c, 0.5 + t / 2.0).0;
            assert!(dist(curve_eval(&b, t).0, whole) < 1e-15);
        }
    }

    #[test]
    fn a_cube_of_patches_is_a_closed_shell_of_unit_volume() {
        let b = brep(cube(), 1e-12, 1e-9).unwrap();
        assert_eq!((b.vertices.len(), b.edges.len()), (8, 12));
        assert!(b.is_closed().unwrap());
        assert_eq!(b.free_edges(), 0);
        assert!(b.loops.iter().all(|l| l.len() == 4));
        assert!((volume(&b.faces) - 1.0).abs() < 1e-14);
        let step = write(
            &b,
            &Header {
                file_name: "cube.step".into(),
                product: "cube".into(),
                time_stamp: "2026-01-01T00:00:00".into(),
                description: "test".into(),
            },
        )
        .unwrap();
        assert!(step.starts_with("ISO-10303-21;\nHEADER;\n"));
        assert!(step.ends_with("ENDSEC;\nEND-ISO-10303-21;\n"));
        assert_eq!(step.matches("=ADVANCED_FACE(").count(), 6);
        assert_eq!(step.matches("=EDGE_CURVE(").count(), 12);
        assert_eq!(step.matches("=VERTEX_POINT(").count(), 8);
        assert_eq!(step.matches("=ORIENTED_EDGE(").count(), 24);
        assert_eq!(
            step.matches("=B_SPLINE_SURFACE_WITH_KNOTS('',3,3,").count(),
            6
        );
        assert_eq!(step.matches("=CLOSED_SHELL(").count(), 1);
        assert_eq!(step.matches("=SURFACE_CURVE(").count(), 12);
        assert_eq!(step.matches("=PCURVE(").count(), 24);
        assert_eq!(step.matches("=MANIFOLD_SOLID_BREP(").count(), 1);
        // Every reference points at an instance written.
        let defined = step.matches("\n#").count();
        for r in step.split('#').skip(1) {
            let n: usize = r[..r.find(|c: char| !c.is_ascii_digit()).unwrap()]
                .parse()
                .unwrap();
            assert!((1..=defined).contains(&n));
        }
    }

    #[test]
    fn rounded_patches_are_joined_where_their_guide_joins() {
        // Each face moved by its own 1e-9: no weld within 1e-12.
        let mut faces = cube();
        for (k, f) in faces.iter_mut().enumerate() {
            for p in &mut f.surface.net {
                p[0] += k as f64 * 1e-9;
            }
        }
        assert!(!brep(faces.clone(), 1e-12, 1e-9)
            .unwrap()
            .is_closed()
            .unwrap());
        let b = brep_guided(faces.clone(), &cube(), 1e-12, 1e-9).unwrap();
        assert!(b.is_closed().unwrap());
        assert_eq!((b.vertices.len(), b.edges.len()), (8, 12));
        // The geometry is the rounded faces'.
        assert_eq!(b.faces, faces);
        for e in &b.edges {
            let piece = &pieces(&faces).unwrap()[e.piece];
            assert_eq!(e.curve, piece.curve);
            assert!(faces[piece.face].surface.net.contains(&e.curve[0]));
        }
    }

    /// Each edge's curve at `t` is each of its faces' surface at the
    /// pcurve's point `(1 − t)·uv0 + t·uv1`.
    fn assert_pcurves_on_curves(b: &Brep) {
        for e in &b.edges {
            assert_eq!(e.pcurves.len(), e.uses);
            for &(f, [p, q]) in &e.pcurves {
                for t in [0.0, 0.3, 0.5, 1.0] {
                    let uv = [0, 1].map(|k| p[k] + (q[k] - p[k]) * t);
                    let on_face = b.faces[f].surface.eval(uv[0], uv[1])[0];
                    assert!(dist(on_face, curve_eval(&e.curve, t).0) < 1e-15);
                }
            }
        }
    }

    #[test]
    fn pcurves_map_onto_the_edge_curves() {
        assert_pcurves_on_curves(&brep(cube(), 1e-12, 1e-9).unwrap());
        let (x, y) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let half = |o: [f64; 3]| flat(o, [0.5, 0.0, 0.0], [0.0, 0.5, 0.0], 0);
        let t_junction = vec![
            flat([0.0; 3], x, y, 1 << 1),
            half([1.0, 0.0, 0.0]),
            half([1.0, 0.5, 0.0]),
        ];
        assert_pcurves_on_curves(&brep(t_junction, 1e-12, 1e-9).unwrap());
    }

    #[test]
    fn a_face_without_its_top_is_an_open_shell() {
        let mut faces = cube();
        faces.remove(1);
        let b = brep(faces, 1e-12, 1e-9).unwrap();
        assert!(!b.is_closed().unwrap());
        assert_eq!(b.free_edges(), 4);
        assert_eq!(b.edges.len(), 12);
    }

    #[test]
    fn a_coarse_edge_beside_two_finer_patches_is_split_at_its_midpoint() {
        // A unit square (its edge u = 1 finer) beside two half squares.
        let (x, y) = ([1.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
        let half = |o: [f64; 3]| flat(o, [0.5, 0.0, 0.0], [0.0, 0.5, 0.0], 0);
        let faces = vec![
            flat([0.0; 3], x, y, 1 << 1),
            half([1.0, 0.0, 0.0]),
            half([1.0, 0.5, 0.0]),
        ];
        let b = brep(faces, 1e-12, 1e-9).unwrap();
        assert_eq!(b.loops[0].len(), 5);
        // The two pieces of the coarse edge are the finer patches' edges u = 0.
        let shared: Vec<usize> = b.loops[0]
            .iter()
            .filter(|(e, _)| b.edges[*e].uses == 2)
            .map(|(e, _)| *e)
            .collect();
        assert_eq!(shared.len(), 2);
        for (f, e) in [(1, shared[0]), (2, shared[1])] {
            assert!(b.loops[f].contains(&(e, false)));
        }
        assert_eq!(b.vertices.len(), 8);
    }

    #[test]
    fn a_hole_is_closed_by_ruled_patches_meeting_at_the_limit_point() {
        // Four unit squares around a square hole, closed to a point above.
        let limit = [0.5, 0.5, 0.3];
        let edges = [
            [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
            [[1.0, 0.0, 0.0], [1.0, 1.0, 0.0]],
            [[1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
            [[0.0, 1.0, 0.0], [0.0, 0.0, 0.0]],
        ];
        let fills: Vec<StepFace> = edges
            .iter()
            .map(|[a, b]| {
                // The ring's edge runs b → a around the hole.
                let c: Vec<[f64; 3]> = (0..4).map(|k| lerp(*b, *a, k as f64 / 3.0)).collect();
                StepFace {
                    surface: hole_fill(&c, limit).unwrap(),
                    finer: 0,
                    kind: FaceKind::HoleFill { patch: 0, edge: 0 },
                }
            })
            .collect();
        for f in &fills {
            for u in [0.0, 0.4, 1.0] {
                assert_eq!(f.surface.eval(u, 1.0)[0], limit);
            }
        }
        let b = brep(fills, 1e-12, 1e-9).unwrap();
        assert_eq!(b.collapsed, 4);
        assert_eq!(b.vertices.len(), 5);
        // The square hole's four edges (free) and four shared rulings.
        assert_eq!((b.edges.len(), b.free_edges()), (8, 4));
        assert!(b.loops.iter().all(|l| l.len() == 3));
        // A pyramid's flux: ⅓ · base · height, the base's outward side down.
        assert!((volume(&b.faces) - 0.1).abs() < 1e-15);
    }

    #[test]
    fn time_stamps_are_utc_dates() {
        use std::time::{Duration, UNIX_EPOCH};
        assert_eq!(time_stamp(UNIX_EPOCH), "1970-01-01T00:00:00");
        let t = UNIX_EPOCH + Duration::from_secs(951_782_400 + 3_723);
        assert_eq!(time_stamp(t), "2000-02-29T01:02:03");
    }
}
