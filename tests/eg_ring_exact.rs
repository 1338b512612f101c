//! The kernel's ring patches (docs/math/eg.md §9) are bit for bit those of a
//! straightforward construction written here from the spec: every node of a
//! patch's 5×5 block looked up by position (§2 change of frame), the regular
//! ones refined from the old d-net one by one (§5, tensor product of the
//! univariate rules, summed as `c0 + Σ w (d − c0)` in stencil order), then
//! the tensored (5) applied with every weight of its matrix (zeros too), on
//! differences from the mid-mid node. The kernel may organise the work
//! however it likes (shared lookups, reuse between patches), but its patches
//! must not change by a single bit; this pins them down for `f32` and `f64`,
//! n = 3, 4, 5, several levels and random nets.

mod eg_support;

use capdiv::bezier::BiquarticPatch;
use capdiv::eg::{CNet, DNet, EgSubdivision};
use capdiv::{Point3, Real};
use eg_support::{ExtNet, Rng};

/// §2 change of frame: `y ≤ 0 → (−y, x)` in sector `s−1`, else
/// `x < 0 → (y, −x)` in sector `s+1`, until owned (`x ≥ 0, y ≥ 1`).
fn resolve(s: isize, x: i32, y: i32) -> (isize, i32, i32) {
    let (mut s, mut x, mut y) = (s, x, y);
    for _ in 0..8 {
        if y <= 0 {
            (x, y, s) = (-y, x, s - 1);
        } else if x < 0 {
            (x, y, s) = (y, -x, s + 1);
        } else {
            break;
        }
    }
    (s, x, y)
}

/// Node at half-unit position `(x, y)` of sector `s` of a d-net: `d_ij`
/// sits at `(3 − i, 3 − j)` (§2).
fn d_at<R: Real>(d: &DNet<R>, s: isize, x: i32, y: i32) -> Point3<R> {
    let (s, x, y) = resolve(s, x, y);
    assert!((0..=3).contains(&x) && (1..=3).contains(&y), "({x},{y})");
    let n = d.valence() as isize;
    d.node(s.rem_euclid(n) as usize, (3 - x) as usize, (3 - y) as usize)
        .unwrap()
}

/// §5 univariate rule of new index `I`: weights ×16 and the old indices.
fn univariate(i: i32) -> ([i32; 3], [i32; 3]) {
    let shift = 2 * (i / 4);
    let (w, first) = match i % 4 {
        0 => ([9, 6, 1], 0),
        1 => ([3, 10, 3], 0),
        2 => ([1, 6, 9], 0),
        _ => ([2, 12, 2], 1), // (1,6,1)/8 = (2,12,2)/16
    };
    (w, [first + shift, first + shift + 1, first + shift + 2])
}

/// The regular refinement (§5) of `old` at new half-unit position `(x, y)`
/// of sector `s`: new index `I = 5 − x` (so `d̃_{i'j'}`, at `3 − i'`, is
/// `I = i' + 2`), old index `p` at old position `3 − p`.
fn regular<R: Real>(old: &DNet<R>, s: isize, x: i32, y: i32) -> Point3<R> {
    let (wi, pi) = univariate(5 - x);
    let (wj, pj) = univariate(5 - y);
    let c0 = old.c0();
    let mut acc = Point3::ZERO;
    for a in 0..3 {
        for b in 0..3 {
            let p = d_at(old, s, 3 - pi[a], 3 - pj[b]);
            acc += (p - c0) * R::ratio(wi[a] * wj[b], 256);
        }
    }
    c0 + acc
}

/// (5) as a matrix ×4: `b0..b4` from the nodes `d_{2s−2} … d_{2s+2}`.
const B_FROM_D: [[i32; 5]; 5] = [
    [1, 2, 1, 0, 0],
    [0, 2, 2, 0, 0],
    [0, 0, 4, 0, 0],
    [0, 0, 2, 2, 0],
    [0, 0, 1, 2, 1],
];

fn convert<R: Real>(v: [Point3<R>; 5]) -> [Point3<R>; 5] {
    let mut out = [Point3::ZERO; 5];
    for (o, row) in out.iter_mut().zip(B_FROM_D.iter()) {
        let mut acc = Point3::ZERO;
        for (p, w) in v.iter().zip(row.iter()) {
            acc += *p * R::ratio(*w, 4);
        }
        *o = acc;
    }
    out
}

/// Patch `k` of the ring from `old` to `new`, literally (§9).
fn reference<R: Real>(old: &DNet<R>, new: &DNet<R>, k: usize) -> BiquarticPatch<R> {
    let (s, piece) = ((k / 3) as isize, k % 3);
    // Lower-left node of the block, new half-units: the patch square is
    // [½,1]×[0,½], [0,½]×[½,1] or [½,1]² (old units) = [2,4]×[0,2], ...
    // (new half-units), and its nodes run from 1 below to 1 above.
    let (x0, y0) = [(1, -1), (-1, 1), (1, 1)][piece];
    let mut d = [[Point3::ZERO; 5]; 5];
    for (a, row) in d.iter_mut().enumerate() {
        for (b, p) in row.iter_mut().enumerate() {
            let (x, y) = (x0 + a as i32, y0 + b as i32);
            let (s2, rx, ry) = resolve(s, x, y);
            *p = if rx <= 3 && ry <= 3 {
                d_at(new, s2, rx, ry)
            } else {
                regular(old, s2, rx, ry)
            };
        }
    }
    let o = d[2][2];
    let rel = d.map(|row| row.map(|p| p - o));
    // Along v (within a row), then along u (within a column).
    let along_v = rel.map(convert);
    let mut both = [[Point3::ZERO; 5]; 5];
    for j in 0..5 {
        let col = convert([0, 1, 2, 3, 4].map(|i| along_v[i][j]));
        for i in 0..5 {
            both[i][j] = o + col[i];
        }
    }
    BiquarticPatch { points: both }
}

fn same_bits<R: Real>(a: &BiquarticPatch<R>, b: &BiquarticPatch<R>) -> bool {
    a.points
        .iter()
        .flatten()
        .zip(b.points.iter().flatten())
        .all(|(p, q)| (0..3).all(|c| p.0[c].to_f64().to_bits() == q.0[c].to_f64().to_bits()))
}

fn check<R: Real>(n: usize, seed: u64, levels: u32) -> usize {
    let mut rng = Rng(seed);
    let ext = ExtNet::random(n, &mut rng, 0.4);
    let nodes: Vec<[R; 3]> = ext
        .cnet_nodes()
        .iter()
        .map(|p| p.map(R::from_f64))
        .collect();
    let c = CNet::new(ext.center.map(R::from_f64), &nodes).unwrap();
    let mut sub = EgSubdivision::new(&c, None).unwrap();
    let mut compared = 0;
    for _ in 0..levels {
        sub.step().unwrap();
        let (old, new) = (sub.previous().unwrap(), sub.net());
        assert_eq!(sub.ring_len(), 3 * n);
        for (k, patch) in sub.ring_patches().enumerate() {
            let want = reference(old, new, k);
            assert!(
                same_bits(&patch, &want),
                "n {n} level {} patch {k}",
                sub.level()
            );
            assert!(same_bits(&sub.ring_patch(k).unwrap(), &want));
            compared += 1;
        }
    }
    compared
}

#[test]
fn ring_patches_are_bit_identical_to_the_literal_construction() {
    let mut compared = 0;
    // Under Miri (an EG step and ring take seconds there) valence 3, one
    // level.
    let (nets, levels): (&[(usize, u64)], u32) = if cfg!(miri) {
        (&[(3, 71)], 1)
    } else {
        (&[(3, 71), (4, 72), (5, 73), (3, 74), (5, 75)], 4)
    };
    for &(n, seed) in nets {
        compared += check::<f64>(n, seed, levels);
        compared += check::<f32>(n, seed + 100, levels);
    }
    let valences: usize = nets.iter().map(|&(n, _)| n).sum();
    assert_eq!(compared, 2 * levels as usize * 3 * valences);
}
