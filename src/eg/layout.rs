//! Compile-time index tables: where every stencil of docs/math/eg.md §3, §5 and §9
//! reads, in the frame of one sector.
//!
//! Positions are integer lattice coordinates of one sector's frame (§1, §2):
//! c-net points at `(x, y)` in c-units, d-net (and refined-net) nodes at
//! half-units `(X, Y) = (2x, 2y)`, so d-node `d_ij` sits at `(3−i, 3−j)`.
//! A position outside the owned region is re-expressed in a neighbor's frame
//! by the §1/§2 change of frame, repeatedly; the result is a sector offset `ds`
//! (relative to the sector being computed) and a node index. Everything here is
//! evaluated by the compiler; at run time the kernel only reads these tables.

/// Marks the center: `e` of a c-net, or the (absent) d-lattice node at `(0, 0)`.
pub(crate) const CENTER: u8 = 12;

/// One stencil term: weight `w` on node `node` of sector `s + ds`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Term {
    /// Sector offset.
    pub ds: i8,
    /// Node index (`i + 4j` in a d-net, `(x−1) + 2y` in a c-net) or [`CENTER`].
    pub node: u8,
    /// Integer weight (denominator given by the table).
    pub w: i16,
}

const NO_TERM: Term = Term {
    ds: 0,
    node: 0,
    w: 0,
};

/// Change of frame on the d-lattice (§2): `y ≤ 0 → (−y, x)_{s−1}`, else
/// `x < 0 → (y, −x)_{s+1}`, until owned. Returns `(ds, X, Y)`; the center
/// `(0, 0)` stays `(0, 0, 0)`.
pub(crate) const fn resolve_d(x: i32, y: i32) -> (i8, i32, i32) {
    let (mut x, mut y, mut ds) = (x, y, 0i8);
    let mut k = 0;
    while k < 8 {
        if x == 0 && y == 0 {
            return (0, 0, 0);
        }
        if y <= 0 {
            let t = x;
            x = -y;
            y = t;
            ds -= 1;
        } else if x < 0 {
            let t = x;
            x = y;
            y = -t;
            ds += 1;
        } else {
            break;
        }
        k += 1;
    }
    (ds, x, y)
}

/// A d-node position to `(ds, node)`: node `(3−X) + 4(3−Y)` or [`CENTER`].
const fn d_node(x: i32, y: i32) -> (i8, u8) {
    let (ds, x, y) = resolve_d(x, y);
    if x == 0 && y == 0 {
        return (0, CENTER);
    }
    assert!(x >= 0 && x <= 3 && y >= 1 && y <= 3);
    (ds, ((3 - x) + 4 * (3 - y)) as u8)
}

/// Change of frame on the c-net (§1): `y < 0 → (−y, x)_{s−1}`, else
/// `x ≤ 0 → (y, −x)_{s+1}`. Returns `(ds, node)` with node `(x−1) + 2y`.
const fn c_node(x: i32, y: i32) -> (i8, u8) {
    let (mut x, mut y, mut ds) = (x, y, 0i8);
    let mut k = 0;
    while k < 8 {
        if x == 0 && y == 0 {
            return (0, CENTER);
        }
        if y < 0 {
            let t = x;
            x = -y;
            y = t;
            ds -= 1;
        } else if x <= 0 {
            let t = x;
            x = y;
            y = -t;
            ds += 1;
        } else {
            break;
        }
        k += 1;
    }
    assert!(x >= 1 && x <= 2 && y >= 0 && y <= 2);
    (ds, ((x - 1) + 2 * y) as u8)
}

/// §5 univariate rule of new regular index `I` (0..=5), ×16, and the first old
/// index it reads: `I=0: (9,6,1)`, `I=1: (3,10,3)`, `I=2: (1,6,9)` on old 0..2,
/// `I=3: (1,6,1)/8 = (2,12,2)/16` on old 1..3, `I+4`: same as `I`, old +2.
const fn univariate(i: usize) -> ([i32; 3], i32) {
    let base = match i % 4 {
        0 => ([9, 6, 1], 0),
        1 => ([3, 10, 3], 0),
        2 => ([1, 6, 9], 0),
        _ => ([2, 12, 2], 1),
    };
    (base.0, base.1 + 2 * (i / 4) as i32)
}

/// Regular bi-4 refinement (§5), new regular index `(I, J)`, `I, J ∈ 0..=5`:
/// 9 terms over the old d-net, weights ×256.
const fn regular_terms(ii: usize, jj: usize) -> [Term; 9] {
    let (wi, pi) = univariate(ii);
    let (wj, pj) = univariate(jj);
    let mut out = [NO_TERM; 9];
    let mut a = 0;
    while a < 3 {
        let mut b = 0;
        while b < 3 {
            let (p, q) = (pi + a as i32, pj + b as i32);
            let (ds, node) = d_node(3 - p, 3 - q);
            out[a * 3 + b] = Term {
                ds,
                node,
                w: (wi[a] * wj[b]) as i16,
            };
            b += 1;
        }
        a += 1;
    }
    out
}

const fn build_regular() -> [[[Term; 9]; 6]; 6] {
    let mut t = [[[NO_TERM; 9]; 6]; 6];
    let mut i = 0;
    while i < 6 {
        let mut j = 0;
        while j < 6 {
            t[i][j] = regular_terms(i, j);
            j += 1;
        }
        i += 1;
    }
    t
}

/// `REGULAR[I][J]`: the §5 stencil of the refined regular node with regular
/// index `(I, J)` (new d-node `d̃_{i'j'}` is `I = i'+2`, `J = j'+2`), ÷256.
pub(crate) const REGULAR: [[[Term; 9]; 6]; 6] = build_regular();

/// §3 per direction, ×12: d-node at half-unit `u2 = 2u`.
const fn raise(u2: i32) -> ([i32; 3], i32, usize) {
    if u2 % 2 == 1 {
        ([6, 6, 0], (u2 - 1) / 2, 2)
    } else {
        ([1, 10, 1], u2 / 2 - 1, 3)
    }
}

const fn build_raise() -> [[Term; 9]; 12] {
    let mut t = [[NO_TERM; 9]; 12];
    let mut node = 0;
    while node < 12 {
        let (i, j) = ((node % 4) as i32, (node / 4) as i32);
        let (wx, x0, nx) = raise(3 - i);
        let (wy, y0, ny) = raise(3 - j);
        let mut k = 0;
        let mut a = 0;
        while a < nx {
            let mut b = 0;
            while b < ny {
                let (ds, c) = c_node(x0 + a as i32, y0 + b as i32);
                t[node][k] = Term {
                    ds,
                    node: c,
                    w: (wx[a] * wy[b]) as i16,
                };
                k += 1;
                b += 1;
            }
            a += 1;
        }
        node += 1;
    }
    t
}

/// `RAISE[i + 4j]`: the §3 degree-raising stencil of `d_ij` over the c-net, ÷144.
pub(crate) const RAISE: [[Term; 9]; 12] = build_raise();

/// The 8 lattice neighbors of the center with their weights in the corner
/// BB-coefficient `b00 = [1 2 1]⊗[1 2 1]/16` (§9 tensored), center weight 4.
const fn build_center_ring() -> [Term; 8] {
    let offs: [(i32, i32, i16); 8] = [
        (1, 0, 2),
        (0, 1, 2),
        (-1, 0, 2),
        (0, -1, 2),
        (1, 1, 1),
        (-1, 1, 1),
        (-1, -1, 1),
        (1, -1, 1),
    ];
    let mut t = [NO_TERM; 8];
    let mut k = 0;
    while k < 8 {
        let (ds, node) = d_node(offs[k].0, offs[k].1);
        t[k] = Term {
            ds,
            node,
            w: offs[k].2,
        };
        k += 1;
    }
    t
}

/// Valence 4 only: the neighbors of the absent center node (see
/// [`crate::eg::DNet`] and the step's n = 4 rule).
pub(crate) const CENTER_RING: [Term; 8] = build_center_ring();

/// Where one node of a ring patch's 5×5 node block comes from (§9).
#[derive(Clone, Copy, Debug)]
pub(crate) struct Fine {
    /// Sector offset.
    pub ds: i8,
    /// A node of the new d-net (`i' + 4j'`), or 255.
    pub new_node: u8,
    /// Otherwise the regular refinement `REGULAR[I][J]` of the old d-net.
    pub reg: (u8, u8),
    /// For a regular node in the patch's own sector frame (`ds = 0`): its
    /// slot in [`OWN_REG`], else 255.
    pub slot: u8,
}

const NO_FINE: Fine = Fine {
    ds: 0,
    new_node: 255,
    reg: (0, 0),
    slot: 255,
};

/// Regular nodes of the ring in one sector's own frame: positions (new
/// half-units) `x ∈ {4,5}, y ∈ 1..=5` (slots 0..10) and `x ∈ 0..=3,
/// y ∈ {4,5}` (slots 10..18). The 3 patches of a sector read all of them.
pub(crate) const OWN: usize = 18;

/// The slot of own-frame position `(x, y)`, or 255.
const fn own_slot(x: i32, y: i32) -> u8 {
    if x >= 4 && x <= 5 && y >= 1 && y <= 5 {
        ((x - 4) * 5 + (y - 1)) as u8
    } else if x >= 0 && x <= 3 && y >= 4 && y <= 5 {
        (10 + x * 2 + (y - 4)) as u8
    } else {
        255
    }
}

const fn build_own() -> [(u8, u8); OWN] {
    let mut t = [(0u8, 0u8); OWN];
    let mut x = 0;
    while x <= 5 {
        let mut y = 1;
        while y <= 5 {
            let slot = own_slot(x, y);
            if slot != 255 {
                t[slot as usize] = ((5 - x) as u8, (5 - y) as u8);
            }
            y += 1;
        }
        x += 1;
    }
    t
}

/// `OWN_REG[slot]`: the regular index `(I, J)` of each own-frame slot.
pub(crate) const OWN_REG: [(u8, u8); OWN] = build_own();

/// Lower-left corner `(X₀, Y₀)` (new half-units) of the node block of ring
/// patch `p`: 0 = `[½,1]×[0,½]`, 1 = `[0,½]×[½,1]`, 2 = `[½,1]²` (old units).
pub(crate) const PATCH_ORIGIN: [(i32, i32); 3] = [(1, -1), (-1, 1), (1, 1)];

const fn build_ring() -> [[[Fine; 5]; 5]; 3] {
    let mut t = [[[NO_FINE; 5]; 5]; 3];
    let mut p = 0;
    while p < 3 {
        let mut a = 0;
        while a < 5 {
            let mut b = 0;
            while b < 5 {
                let (ds, x, y) =
                    resolve_d(PATCH_ORIGIN[p].0 + a as i32, PATCH_ORIGIN[p].1 + b as i32);
                assert!(x >= 0 && x <= 5 && y >= 1 && y <= 5);
                t[p][a][b] = if x <= 3 && y <= 3 {
                    Fine {
                        ds,
                        new_node: ((3 - x) + 4 * (3 - y)) as u8,
                        reg: (0, 0),
                        slot: 255,
                    }
                } else {
                    Fine {
                        ds,
                        new_node: 255,
                        reg: ((5 - x) as u8, (5 - y) as u8),
                        slot: if ds == 0 { own_slot(x, y) } else { 255 },
                    }
                };
                b += 1;
            }
            a += 1;
        }
        p += 1;
    }
    t
}

/// `RING[p][a][b]`: node `(a, b)` of ring patch `p`'s node block, `a` along
/// `x` (patch `u`), `b` along `y` (patch `v`), increasing.
pub(crate) const RING: [[[Fine; 5]; 5]; 3] = build_ring();

const fn build_cap4() -> [[(i8, u8); 4]; 4] {
    let mut t = [[(0i8, 0u8); 4]; 4];
    let mut a = 0;
    while a < 4 {
        let mut b = 0;
        while b < 4 {
            t[a][b] = c_node(a as i32 - 1, b as i32 - 1);
            b += 1;
        }
        a += 1;
    }
    t
}

/// Valence 4: the 4×4 c-net control points `(x, y) ∈ {−1..2}²` of the
/// bicubic patch over `[0,1]²` of a sector.
pub(crate) const CAP4: [[(i8, u8); 4]; 4] = build_cap4();

/// `true` when a table reads the center (only the n = 4 step may).
pub(crate) const fn reads_center(terms: &[Term]) -> bool {
    let mut k = 0;
    while k < terms.len() {
        if terms[k].node == CENTER && terms[k].w != 0 {
            return true;
        }
        k += 1;
    }
    false
}

// The outer new nodes (§5) and the ring's regular nodes never read the center;
// the ring's sector offsets stay within its windows (`ring::window`):
const _: () = {
    let outer = [(0, 0), (1, 0), (2, 0), (3, 0), (0, 1), (0, 2)];
    let mut k = 0;
    while k < 6 {
        assert!(!reads_center(&REGULAR[outer[k].0 + 2][outer[k].1 + 2]));
        k += 1;
    }
    let mut used = [false; OWN];
    let mut p = 0;
    while p < 3 {
        let mut a = 0;
        while a < 5 {
            let mut b = 0;
            while b < 5 {
                let f = RING[p][a][b];
                if f.new_node == 255 {
                    let terms = &REGULAR[f.reg.0 as usize][f.reg.1 as usize];
                    assert!(!reads_center(terms));
                    // The ring reads old sectors s−2..=s+2 only (its window).
                    let mut t = 0;
                    while t < 9 {
                        let ds = f.ds + terms[t].ds;
                        assert!(ds >= -2 && ds <= 2);
                        t += 1;
                    }
                    // Own-frame regular nodes have their cache slot.
                    assert!((f.ds == 0) == (f.slot != 255));
                    if f.slot != 255 {
                        let (i, j) = OWN_REG[f.slot as usize];
                        assert!(i == f.reg.0 && j == f.reg.1);
                        used[f.slot as usize] = true;
                    }
                } else {
                    // ... and new sectors s−1..=s+1.
                    assert!(f.ds >= -1 && f.ds <= 1);
                }
                b += 1;
            }
            a += 1;
        }
        p += 1;
    }
    // The 3 patches of a sector read every own-frame slot.
    let mut k = 0;
    while k < OWN {
        assert!(used[k]);
        k += 1;
    }
    // Degree raising reads e only through stencil weights that sum to 144.
    let mut node = 0;
    while node < 12 {
        let mut s = 0;
        let mut k = 0;
        while k < 9 {
            s += RAISE[node][k].w as i32;
            k += 1;
        }
        assert!(s == 144);
        node += 1;
    }
};
