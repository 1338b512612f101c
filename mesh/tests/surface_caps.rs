//! Every cap equals the kernel (or the literal
//! reference) run on the configuration the TEST extracts from the mesh by
//! construction of the sample (pole and links of `pole_disk`/`globe`, the
//! c-net of `extraordinary_disk`), compared level by level as sets of Bézier
//! control grids up to orientation (the plan may start its columns or sectors
//! anywhere, and patches are re-oriented to their input face).
mod common;

use capdiv::eg::{CNet, EgSubdivision};
use capdiv::{FirstStep, PolarNet};
use capdiv_mesh::{samples, MeshInput, PatchKind, Scheme};
use capdiv_reference::{bezier, catmull_clark as cc};
use common::*;

type Grid = Vec<Vec<[f64; 3]>>;

/// Emitted patches of cap `index` at `level`, as control grids.
fn emitted(out: &Collect<f64>, index: u32, level: u32, kind: PatchKind) -> Vec<Grid> {
    out.patches
        .iter()
        .filter(|p| p.cap == Some(index) && p.level == level)
        .inspect(|p| assert_eq!(p.kind, kind))
        .map(|p| control_grid(&p.geometry))
        .collect()
}

fn cap_of(out: &Collect<f64>, vertex: u32) -> u32 {
    out.caps
        .iter()
        .find(|c| c.vertex == Some(vertex))
        .unwrap_or_else(|| panic!("no cap at vertex {vertex}"))
        .index
}

/// The C²PS cap at `pole` (links 1..3 given by the test) equals `PolarNet`'s
/// rings level by level. Returns the worst control-point distance.
fn polar_case(m: &MeshInput, pole: usize, links: &[Vec<usize>; 3], depth: u32) -> f64 {
    let (plan, out) = surface(m, depth);
    assert!(plan.steps.is_empty());
    let index = cap_of(&out, pole as u32);
    let cap = out.caps.iter().find(|c| c.index == index).unwrap();
    assert_eq!(cap.scheme, Scheme::C2ps);
    assert_eq!(cap.valence, links[0].len());
    let pts: Vec<Vec<[f64; 3]>> = links
        .iter()
        .map(|l| l.iter().map(|&v| m.vertices[v]).collect())
        .collect();
    let mut net: Box<PolarNet<f64, 1024>> = Box::new(PolarNet::empty());
    net.reset(m.vertices[pole], &pts).unwrap();
    let mut worst = 0.0f64;
    for level in 1..=depth {
        net.step(if level == 1 {
            FirstStep::Uniform
        } else {
            FirstStep::Plain
        })
        .unwrap();
        let want: Vec<Grid> = net
            .ring_patches()
            .map(|p| {
                p.points
                    .iter()
                    .map(|r| r.iter().map(|q| q.0).collect())
                    .collect()
            })
            .collect();
        assert_eq!(want.len(), (2 * links[0].len()) << level);
        let got = emitted(&out, index, level, PatchKind::C2ps);
        worst = worst.max(match_patch_sets(&want, &got));
    }
    worst
}

/// `pole_disk(n, 4)`: pole 0, link `i` column `j` is vertex `1 + (i−1)n + j`
/// (samples::pole_disk builds them in that order, all used).
#[test]
fn c2ps_caps_equal_polar_net_rings_on_pole_disks() {
    for (n, depth) in [(3, 5), (5, 5), (8, 4), (16, 3)] {
        let m = samples::pole_disk(n, 4);
        let links = [1, 2, 3].map(|i| (0..n).map(|j| 1 + (i - 1) * n + j).collect());
        let worst = polar_case(&m, 0, &links, depth);
        println!("pole_disk n={n} depth {depth}: worst {worst:.2e}");
        assert!(worst < 1e-13, "n={n}: {worst}");
    }
}

/// `globe(n, R)`: north pole 0 with link `i` = ring `i−1` (vertex
/// `1 + (i−1)n + j`); south pole `1 + Rn` with link `i` = ring `R−i` run the
/// other way (counter-clockwise about the outward normal, −z).
#[test]
fn c2ps_caps_equal_polar_net_rings_on_globes() {
    for (n, rings, depth) in [(5, 9, 4), (8, 9, 4)] {
        let m = samples::globe(n, rings);
        let north = [1, 2, 3].map(|i| (0..n).map(|j| 1 + (i - 1) * n + j).collect());
        let south = [1, 2, 3].map(|i| (0..n).map(|j| 1 + (rings - i) * n + (n - j) % n).collect());
        let a = polar_case(&m, 0, &north, depth);
        let b = polar_case(&m, 1 + rings * n, &south, depth);
        println!("globe n={n}: north {a:.2e} south {b:.2e}");
        assert!(a < 1e-13 && b < 1e-13, "n={n}: {a} {b}");
    }
}

/// The c-net of `extraordinary_disk(n, r)` by construction: centre 0, spoke
/// `s` point `a` is `1 + s·r + a − 1`, sector `s` inner point `(a, c)` is
/// `1 + n·r + s·r² + (a−1)·r + c − 1`; sector `s` node `(x, y)` is point
/// `(x, y)` of sector `s` (x along spoke s, y along spoke s+1), §1 order.
fn disk_cnet(m: &MeshInput, n: usize, r: usize) -> ([f64; 3], Vec<[f64; 3]>) {
    let at = |s: usize, a: usize, c: usize| -> usize {
        match (a, c) {
            (0, 0) => 0,
            (a, 0) => 1 + s * r + a - 1,
            (0, c) => 1 + ((s + 1) % n) * r + c - 1,
            (a, c) => 1 + n * r + s * r * r + (a - 1) * r + c - 1,
        }
    };
    let mut nodes = Vec::new();
    for s in 0..n {
        for (x, y) in [(1, 0), (2, 0), (1, 1), (2, 1), (1, 2), (2, 2)] {
            nodes.push(m.vertices[at(s, x, y)]);
        }
    }
    (m.vertices[0], nodes)
}

#[test]
fn eg_caps_equal_eg_subdivision_rings() {
    let depth = 4;
    for n in [3, 5] {
        let m = samples::extraordinary_disk(n, 3);
        let (plan, out) = surface(&m, depth);
        assert!(plan.steps.is_empty());
        let index = cap_of(&out, 0);
        let cap = out.caps.iter().find(|c| c.index == index).unwrap();
        assert_eq!((cap.scheme, cap.valence), (Scheme::Eg, n));
        let (centre, nodes) = disk_cnet(&m, n, 3);
        let net = CNet::new(centre, &nodes).unwrap();
        let mut eg: Box<EgSubdivision<'static, f64>> =
            Box::new(EgSubdivision::new(&net, None).unwrap());
        assert!(dist(cap.limit.0, eg.limit().0) < 1e-15);
        let mut worst = 0.0f64;
        for level in 1..=depth {
            eg.step().unwrap();
            let want: Vec<Grid> = eg
                .ring_patches()
                .map(|p| {
                    p.points
                        .iter()
                        .map(|r| r.iter().map(|q| q.0).collect())
                        .collect()
                })
                .collect();
            assert_eq!(want.len(), 3 * n);
            let got = emitted(&out, index, level, PatchKind::Eg);
            worst = worst.max(match_patch_sets(&want, &got));
        }
        println!("EG n={n}: worst {worst:.2e}");
        assert!(worst < 1e-14, "n={n}: {worst}");
    }
}

/// Catmull-Clark caps (valences EG has no rule for, no tables given) equal
/// the reference's literal CC step on the c-net: the limit point is the
/// reference's limit weights (left eigenvector of the dense matrix) applied
/// to the c-net, and the rings of levels 1..3 are the uniform bicubic
/// B-splines of the refined grids (`ring_grid` of each extended ring,
/// converted to Bézier by the reference).
#[test]
fn catmull_clark_caps_equal_the_literal_reference() {
    let depth = 3;
    for n in [6, 7, 11, 12] {
        let m = samples::extraordinary_disk(n, 3);
        let (plan, out) = surface(&m, depth);
        assert!(plan.steps.is_empty());
        let index = cap_of(&out, 0);
        let cap = out.caps.iter().find(|c| c.index == index).unwrap();
        assert_eq!((cap.scheme, cap.valence), (Scheme::CatmullClark, n));
        let (centre, nodes) = disk_cnet(&m, n, 3);
        let mut cnet = nodes.clone();
        cnet.push(centre);
        let w = cc::limit_weights(n);
        let mut limit = [0.0; 3];
        for (k, p) in cnet.iter().enumerate() {
            for c in 0..3 {
                limit[c] += w[k] * p[c];
            }
        }
        let limit_err = dist(limit, cap.limit.0);
        let mut worst = 0.0f64;
        for level in 1..=depth {
            let ext = cc::refine_extended(n, &cnet);
            let mut want: Vec<Grid> = Vec::new();
            for s in 0..n {
                for piece in 0..3 {
                    let b = bezier::bspline_to_bezier(&cc::ring_grid(n, &ext, s, piece));
                    want.push(b.iter().map(|r| r.to_vec()).collect());
                }
            }
            let got = emitted(&out, index, level, PatchKind::CatmullClark);
            worst = worst.max(match_patch_sets(&want, &got));
            cnet = cc::ext_to_cnet(n, &ext);
        }
        println!("CC n={n}: limit {limit_err:.2e}, rings 1..{depth} worst {worst:.2e}");
        assert!(limit_err < 1e-14, "n={n}: {limit_err}");
        assert!(worst < 1e-14, "n={n}: {worst}");
    }
}
