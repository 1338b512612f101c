//! Feature-adaptive Catmull-Clark with OpenSubdiv's semantics (Nießner, Loop,
//! Meyer & DeRose 2012; OpenSubdiv's `RefineAdaptive`): every face that no
//! cap and no level-0 patch covers is refined on its own, as deep as it
//! needs, with the `Sdc` rules for creases, corners, boundaries, holes and
//! non-manifold features ([`mod@subdivide`]). A face that is regular at some level
//! ([`regular`]) is a uniform B-spline patch there; around an irregular
//! vertex the faces refine into rings converging to it until `depth`, and
//! the last ring's hole is closed to the vertex's limit point; semi-sharp
//! features refine until their sharpness has decayed. Where the refinement
//! has separated an extraordinary vertex from every other feature (its
//! c-net is there, [`cnet`]), the faces around it become a cap (EG, or
//! Catmull-Clark where EG has no rule) instead of rings.
//!
//! The refinement goes level by level, as OpenSubdiv's sparse refinement
//! does: the faces of a level that need refining are refined together,
//! inside one child level made of the faces around their corners (the
//! faces around the vertices of those faces are all the refinement rules
//! reach), each such face once. Points are named by what they are the
//! child of ([`points`]), so a patch edge can ask whether the patch across
//! it is finer.

pub mod base;
pub mod cnet;
pub mod crease;
pub mod level;
pub mod points;
pub mod regular;
pub mod subdivide;

use crate::chart::{Affine, FaceChart};
use crate::mem::{self, OutOfMemory};
use alloc::vec;
use alloc::vec::Vec;
use cnet::level_cnet;
use hashbrown::{HashMap, HashSet};
use level::Level;
use points::{Key, Points};
use regular::{corner_is_regular, regular_grid};
use subdivide::{limit_point, subdivide, Rules};

/// "No point".
pub const NONE: u32 = u32::MAX;

/// The shallowest level a last hole may have: at level 1 every child of a
/// face with irregular corners can be a hole (a single quad's four corners),
/// leaving no ring at all.
const MIN_HOLE_LEVEL: u32 = 2;

/// Levels a semi-sharp feature may need beyond `depth` (sharpness below 10
/// decays in 10 levels).
const EXTRA_LEVELS: u32 = 11;

/// A B-spline patch of the adaptive refinement.
#[derive(Clone, Debug, PartialEq)]
pub struct AdaptivePatch {
    /// Its 16 control points (working-point indices), `[4·i + j]`.
    pub gather: [u32; 16],
    /// Where it lies in the input.
    pub chart: FaceChart,
    /// Refinement level below the analysed level (0: the face itself).
    pub level: u32,
    /// Its four corners (working points), for matching neighbours' edges.
    pub corners: [u32; 4],
    /// Bit `k`: edge `k` (corner k → k+1) borders the last hole of a vertex's
    /// rings, closed to `hole_point`.
    pub hole: u8,
    /// The limit point of that vertex ([`NONE`] without hole edges).
    pub hole_point: u32,
    /// Bit `k`: across edge `k` lie two patches of half the size.
    pub finer: u8,
}

/// A face of the refinement left as the last hole around an irregular
/// vertex, closed by a fan to the vertex's limit point.
#[derive(Clone, Debug, PartialEq)]
pub struct LastHole {
    /// Where it lies in the input.
    pub chart: FaceChart,
    /// Its corners (working points).
    pub corners: [u32; 4],
    /// The vertex (its working point at the hole's level).
    pub vertex: u32,
    /// The hole's level.
    pub level: u32,
    /// The vertex's limit point (working point).
    pub point: u32,
}

/// A cap around an extraordinary vertex that the refinement has separated
/// from every other feature ([`cnet`]): the faces around the vertex at that
/// level are its sectors.
#[derive(Clone, Debug, PartialEq)]
pub struct AdaptiveCap {
    /// Its centre (working point).
    pub center: u32,
    /// The level of its sectors' faces.
    pub level: u32,
    /// `6n` c-net nodes (working points), docs/math/eg.md §1 order.
    pub nodes: Vec<u32>,
    /// Per sector: its face's corners (working points) from the centre:
    /// (0,0) (1,0) (1,1) (0,1).
    pub faces: Vec<[u32; 4]>,
    /// Per sector: from sector coordinates to the input face, once the
    /// sector's face has been reached (every one is, see [`cover`]).
    pub sectors: Vec<Option<FaceChart>>,
}

impl AdaptiveCap {
    /// Whether every sector's face was reached.
    pub fn is_complete(&self) -> bool {
        self.sectors.iter().all(Option::is_some)
    }
}

/// The adaptive refinement of some faces.
#[derive(Clone, Debug)]
pub struct Adaptive {
    /// The patches.
    pub patches: Vec<AdaptivePatch>,
    /// Caps (complete ones; see [`AdaptiveCap`]).
    pub caps: Vec<AdaptiveCap>,
    /// Per centre point looked at: its cap in `caps`, or `None` when it has
    /// no c-net.
    cap_at: HashMap<u32, Option<usize>>,
    /// The points they need beyond the level's own vertices.
    pub points: Points,
    /// The last holes around irregular vertices, one face of the
    /// refinement each.
    pub holes: Vec<LastHole>,
    /// Patches next to the last holes of two different vertices (only one
    /// hole point per patch; none seen for depth ≥ 2).
    pub hole_conflicts: usize,
    /// Input faces with a part that reached the deepest level allowed
    /// without becoming regular or a hole (that part is missing; none seen).
    pub unresolved_faces: Vec<u32>,
    /// Patch edges met by patches two or more levels finer (the
    /// tessellation welds only one level of difference; none seen).
    pub level_jumps: usize,
    /// The edges of the patches and of the caps' faces, by their end points
    /// (smaller first), for [`finer_across`].
    pub edges: HashSet<(u32, u32)>,
}

/// Options of the adaptive refinement.
#[derive(Clone, Copy, Debug)]
pub struct AdaptiveOptions {
    /// Rings around an irregular vertex (its last hole is `2^-depth` of its faces).
    pub depth: u32,
    /// The rules that are options.
    pub rules: Rules,
    /// An extraordinary vertex gets a cap where its c-net appears (else
    /// rings of this refinement converge to it).
    pub caps: bool,
}

/// Covers `roots` (faces of `base` with where they lie in the input).
/// Points are numbered from `first_point` on. Every buffer whose size
/// depends on the mesh (levels, points and their rows, patches, holes,
/// caps, the edge sets) is reserved fallibly ([`crate::mem`]); what is
/// allocated as it is (a vertex's fan, a cap's c-net, a row being built)
/// is of the size of one vertex's neighbourhood.
pub fn cover(
    base: &Level,
    roots: &[(u32, FaceChart)],
    options: AdaptiveOptions,
    first_point: u32,
) -> Result<Adaptive, OutOfMemory> {
    let mut out = Adaptive {
        patches: Vec::new(),
        caps: Vec::new(),
        cap_at: HashMap::new(),
        points: Points::new(first_point),
        holes: Vec::new(),
        hole_conflicts: 0,
        unresolved_faces: Vec::new(),
        level_jumps: 0,
        edges: HashSet::new(),
    };
    // Level by level: the faces of a level that need refinement are refined
    // together, inside one child level of the faces around their corners
    // (each face once however many of them it borders).
    let mut active: Vec<Active> = mem::collect(roots.iter().map(|&(f, chart)| Active {
        face: f,
        chart,
        may_close: false,
    }))?;
    let mut child_level: Level;
    let mut m = base;
    let mut level = 0;
    while !active.is_empty() {
        // The faces to refine, with their irregular corners.
        let mut refined: Vec<(Active, u32)> = Vec::new();
        for a in active {
            if let Some(bits) = visit(m, &a, level, options, &mut out)? {
                mem::push(&mut refined, (a, bits))?;
            }
        }
        if refined.is_empty() {
            break;
        }
        // The faces around the refined faces' corners, each once, and each
        // one's place in that list.
        let mut ring: Vec<u32> = Vec::new();
        let mut place = mem::filled(m.num_faces(), NONE)?;
        for (a, _) in &refined {
            for c in m.face_corners(a.face as usize) {
                let v = m.corner_vertex[c as usize] as usize;
                for &k in m.vertex_corners(v) {
                    let g = m.corner_face[k as usize];
                    if place[g as usize] == NONE {
                        place[g as usize] = ring.len() as u32;
                        mem::push(&mut ring, g)?;
                    }
                }
            }
        }
        let child = subdivide(m, &ring, options.rules, &mut out.points)?;
        active = mem::with_capacity(4 * refined.len())?;
        for (a, irregular) in &refined {
            let f = a.face as usize;
            let at = place[f] as usize;
            // A child may be a last hole only if this face has one
            // irregular corner: otherwise a sibling would border the holes
            // of two vertices (a triangle's sub-quad, whose corner and
            // centre are both irregular).
            let may_close = irregular.count_ones() <= 1;
            let n = m.face(f).len();
            let first = child.first[at];
            mem::reserve(&mut active, n)?;
            active.extend((0..n).map(|k| Active {
                face: first + k as u32,
                chart: a.chart.child(k, n),
                may_close,
            }));
        }
        child_level = child.level;
        m = &child_level;
        level += 1;
    }
    // Every face around a cap's centre is reached at the cap's level (their
    // parents all have the centre's parent as an irregular corner, and no
    // parent is a last hole above the caps' deepest level); a cap that
    // missed one would leave its faces bare, so they are reported.
    // (In place: the partial caps' faces are listed, then the caps go.)
    for cap in out.caps.iter().filter(|c| !c.is_complete()) {
        for s in cap.sectors.iter().flatten() {
            mem::push(&mut out.unresolved_faces, s.face)?;
        }
    }
    out.caps.retain(AdaptiveCap::is_complete);
    mark_neighbours(&mut out)?;
    Ok(out)
}

/// If face `f` at `level` is a sector of a cap: records its chart there
/// (making the cap at its first face) and returns true.
fn cap_sector(
    m: &Level,
    f: usize,
    level: u32,
    chart: FaceChart,
    (bits, semi): (u32, bool),
    options: AdaptiveOptions,
    out: &mut Adaptive,
) -> Result<bool, OutOfMemory> {
    // Above the first level whose faces may be last holes, so that every
    // face around the centre is reached (see `cover`); level 0 is the fast
    // path's.
    if !options.caps
        || level == 0
        || level > options.depth.max(MIN_HOLE_LEVEL)
        || m.face(f).len() != 4
    {
        return Ok(false);
    }
    if semi || bits.count_ones() != 1 {
        return Ok(false);
    }
    let k = bits.trailing_zeros() as usize;
    let c = m.face_start[f] + k as u32;
    let centre = m.point[m.corner_vertex[c as usize] as usize];
    let at = match out.cap_at.get(&centre) {
        Some(&at) => at,
        None => {
            let at = match level_cnet(m, c) {
                Some(net) => {
                    mem::push(
                        &mut out.caps,
                        AdaptiveCap {
                            center: centre,
                            level,
                            sectors: vec![None; net.valence],
                            nodes: net.nodes,
                            faces: net.faces,
                        },
                    )?;
                    Some(out.caps.len() - 1)
                }
                None => None,
            };
            mem::reserve_map(&mut out.cap_at, 1)?;
            out.cap_at.insert(centre, at);
            at
        }
    };
    let Some(cap) = at.map(|i| &mut out.caps[i]) else {
        return Ok(false);
    };
    let diagonal = m.point[m.corner_vertex[m.next(m.next(c)) as usize] as usize];
    let Some(j) = cap.faces.iter().position(|q| q[2] == diagonal) else {
        return Ok(false);
    };
    cap.sectors[j] = Some(FaceChart {
        face: chart.face,
        corner: chart.corner,
        map: chart.map.compose(&Affine::rotation(k)),
    });
    Ok(true)
}

/// Irregular corners of face `f` (bit per corner) and whether a semi-sharp
/// feature reaches a corner.
fn irregular_corners(m: &Level, f: usize) -> (u32, bool) {
    let mut fan = Vec::with_capacity(8);
    let mut bits = 0u32;
    let mut semi = false;
    for (k, c) in m.face_corners(f).enumerate() {
        let v = m.corner_vertex[c as usize] as usize;
        semi |= m.has_semi_sharp(v);
        if !corner_is_regular(m, c, &mut fan) {
            bits |= 1 << k.min(31);
        }
    }
    (bits, semi)
}

/// If face `f` at `level` is the last hole around one irregular vertex: that
/// vertex.
fn final_hole(
    m: &Level,
    f: usize,
    level: u32,
    (bits, semi): (u32, bool),
    options: AdaptiveOptions,
) -> Option<usize> {
    if level < options.depth.max(MIN_HOLE_LEVEL) || m.face(f).len() != 4 || m.hole[f] {
        return None;
    }
    if semi || bits.count_ones() != 1 {
        return None;
    }
    let k = bits.trailing_zeros();
    Some(m.corner_vertex[(m.face_start[f] + k) as usize] as usize)
}

/// A face of a level that the refinement has reached.
struct Active {
    /// The face (of its level).
    face: u32,
    /// Where it lies in the input.
    chart: FaceChart,
    /// Whether it may be a last hole (see [`cover`]).
    may_close: bool,
}

/// Covers face `a.face` of `m` at `level` by a patch, a cap's sector or a
/// last hole, or records it as unresolved; when it needs refining instead,
/// its irregular corners (bit per corner).
fn visit(
    m: &Level,
    a: &Active,
    level: u32,
    options: AdaptiveOptions,
    out: &mut Adaptive,
) -> Result<Option<u32>, OutOfMemory> {
    let (f, chart) = (a.face as usize, a.chart);
    if m.hole[f] {
        return Ok(None);
    }
    if let Some(gather) = regular_grid(m, f, &mut out.points)? {
        let first = m.face_start[f] as usize;
        let corners = core::array::from_fn(|k| m.point[m.corner_vertex[first + k] as usize]);
        let patch = AdaptivePatch {
            gather,
            chart,
            level,
            corners,
            hole: 0,
            hole_point: NONE,
            finer: 0,
        };
        mem::push(&mut out.patches, patch)?;
        return Ok(None);
    }
    let irregular = irregular_corners(m, f);
    if cap_sector(m, f, level, chart, irregular, options, out)? {
        return Ok(None);
    }
    if let Some(v) = final_hole(m, f, level, irregular, options).filter(|_| a.may_close) {
        if let Some(point) = limit_point(m, v, &mut out.points)? {
            let first = m.face_start[f] as usize;
            let hole = LastHole {
                chart,
                corners: core::array::from_fn(|k| m.point[m.corner_vertex[first + k] as usize]),
                vertex: m.point[v],
                level,
                point,
            };
            mem::push(&mut out.holes, hole)?;
            return Ok(None);
        }
    }
    if level >= options.depth.max(MIN_HOLE_LEVEL) + EXTRA_LEVELS {
        mem::push(&mut out.unresolved_faces, chart.face)?;
        return Ok(None);
    }
    Ok(Some(irregular.0))
}

/// Sets [`AdaptivePatch::finer`] and [`AdaptivePatch::hole`] from the
/// patches' and holes' edges, named by their end points: an edge `(a, b)`
/// whose neighbour across is refined once more meets the edges `(a', m)`
/// and `(m, b')` of the child points `a'`, `b'` of `a`, `b` and `m` of the
/// edge; an edge of a last hole, or a piece of one at a finer level (where
/// the faces around an irregular vertex stop at different levels, as
/// semi-sharp features and crowded corners make them), borders that hole.
fn mark_neighbours(out: &mut Adaptive) -> Result<(), OutOfMemory> {
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    // Edge → (vertex at the coarsest level its holes have, limit point).
    let mut hole_edges: HashMap<(u32, u32), usize> = HashMap::new();
    for (i, h) in out.holes.iter().enumerate() {
        for k in 0..4 {
            // The edge and its pieces at every finer level made.
            let mut stack = vec![(h.corners[k], h.corners[(k + 1) % 4])];
            while let Some((a, b)) = stack.pop() {
                mem::reserve_map(&mut hole_edges, 1)?;
                hole_edges.insert(key(a, b), i);
                if let Some((x, y)) = halves(&out.points, a, b) {
                    stack.push(x);
                    stack.push(y);
                }
            }
        }
    }
    // The holes around one vertex may stop at different levels. The limit
    // masks of levels differ where the rule is not exact (a dart uses the
    // smooth mask, as OpenSubdiv's does): every hole of a vertex takes the
    // point of its coarsest hole, so their fans meet.
    let mut order: Vec<usize> = mem::collect(0..out.holes.len())?;
    order.sort_by_key(|&i| out.holes[i].level);
    let mut point_of: HashMap<u32, (u32, u32)> = HashMap::new();
    for &i in &order {
        let (vertex, point) = (out.holes[i].vertex, out.holes[i].point);
        mem::reserve_map(&mut point_of, 1)?;
        let root = *point_of.entry(vertex).or_insert((vertex, point));
        let mut v = vertex;
        for _ in 0..=EXTRA_LEVELS + 2 {
            match out.points.get(&Key::Vertex(v)) {
                Some(c) => {
                    mem::reserve_map(&mut point_of, 1)?;
                    point_of.entry(c).or_insert(root);
                    v = c;
                }
                None => break,
            }
        }
    }
    for h in &mut out.holes {
        (h.vertex, h.point) = point_of[&h.vertex];
    }
    let mut conflicts = 0;
    for p in &mut out.patches {
        let mut vertex = NONE;
        for k in 0..4 {
            let (a, b) = (p.corners[k], p.corners[(k + 1) % 4]);
            if let Some(&i) = hole_edges.get(&key(a, b)) {
                let h = &out.holes[i];
                if p.hole != 0 && vertex != h.vertex {
                    conflicts += 1;
                    continue;
                }
                p.hole |= 1 << k;
                p.hole_point = h.point;
                vertex = h.vertex;
            }
        }
    }
    out.hole_conflicts = conflicts;
    let edges = out.collect_edges()?;
    let mut cap_edges: HashSet<(u32, u32)> = HashSet::new();
    for q in out.caps.iter().flat_map(|c| &c.faces) {
        for k in 0..4 {
            mem::reserve_set(&mut cap_edges, 1)?;
            cap_edges.insert(key(q[k], q[(k + 1) % 4]));
        }
    }
    let mut jumps = 0;
    for p in &mut out.patches {
        for k in 0..4 {
            let (a, b) = (p.corners[k], p.corners[(k + 1) % 4]);
            // Across a cap's face: its first ring is finer.
            if cap_edges.contains(&key(a, b)) || finer_across(&out.points, &edges, a, b) {
                p.finer |= 1 << k;
            } else if let Some(((a1, m), (m2, b1))) = halves(&out.points, a, b) {
                // Not met by halves: is it met by quarters?
                if finer_across(&out.points, &edges, a1, m)
                    || finer_across(&out.points, &edges, m2, b1)
                {
                    jumps += 1;
                }
            }
        }
    }
    out.level_jumps = jumps;
    out.edges = edges;
    Ok(())
}

impl Adaptive {
    /// The edges of the patches and of the caps' faces, by their end points
    /// (smaller first).
    fn collect_edges(&self) -> Result<HashSet<(u32, u32)>, OutOfMemory> {
        let key = |a: u32, b: u32| (a.min(b), a.max(b));
        let quads = self.patches.len() + self.caps.iter().map(|c| c.faces.len()).sum::<usize>();
        // Most edges are two quads' (reserved for those; a collect would
        // grow the set step by step), the rest reserved as they come.
        let mut edges = HashSet::new();
        mem::reserve_set(&mut edges, 2 * quads)?;
        let faces = self.patches.iter().map(|p| p.corners);
        for q in faces.chain(self.caps.iter().flat_map(|c| c.faces.iter().copied())) {
            for k in 0..4 {
                mem::reserve_set(&mut edges, 1)?;
                edges.insert(key(q[k], q[(k + 1) % 4]));
            }
        }
        Ok(edges)
    }
}

/// The child edges of edge `(a, b)`, if its points were made.
fn halves(points: &Points, a: u32, b: u32) -> Option<((u32, u32), (u32, u32))> {
    let m = points.get(&Key::Edge(a.min(b), a.max(b)))?;
    Some((
        (points.get(&Key::Vertex(a))?, m),
        (m, points.get(&Key::Vertex(b))?),
    ))
}

/// Whether the edge `(a, b)` is met by two half-size patch edges.
#[inline]
pub fn finer_across(points: &Points, edges: &HashSet<(u32, u32)>, a: u32, b: u32) -> bool {
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    // The edge's child first: most patch edges were never refined.
    let Some(mid) = points.get(&Key::Edge(a.min(b), a.max(b))) else {
        return false;
    };
    let Some(ca) = points.get(&Key::Vertex(a)) else {
        return false;
    };
    edges.contains(&key(ca, mid))
}
