//! Sharpness and vertex rules of OpenSubdiv's `Sdc::Crease` (DeRose, Kass &
//! Truong 1998, as OpenSubdiv implements them): sharpness is `f32`, `≥ 10`
//! is infinitely sharp, each level takes one from a semi-sharp value (to 0
//! below 1); Chaikin's method blends in the other semi-sharp edges at the end
//! vertex; a vertex's rule follows from its sharpness and how many of its
//! edges are sharp; a rule that changes between levels is blended by the mean
//! parent sharpness of the features that became smooth.

/// Infinitely sharp (`Sdc::Crease::SHARPNESS_INFINITE`).
pub const INFINITE: f32 = 10.0;

/// `s ≥ 10`.
pub fn is_infinite(s: f32) -> bool {
    s >= INFINITE
}

/// `s > 0`.
pub fn is_sharp(s: f32) -> bool {
    s > 0.0
}

/// `0 < s < 10`.
pub fn is_semi_sharp(s: f32) -> bool {
    s > 0.0 && s < INFINITE
}

/// A vertex's subdivision rule (`Sdc::Crease::Rule`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Rule {
    /// No sharp edge, no vertex sharpness.
    Smooth,
    /// One sharp edge (the smooth rule applies to the vertex).
    Dart,
    /// Two sharp edges.
    Crease,
    /// Three or more sharp edges, or a sharp vertex.
    Corner,
}

/// `Crease::DetermineVertexVertexRule`.
pub fn vertex_rule(vertex_sharpness: f32, sharp_edges: usize) -> Rule {
    if is_sharp(vertex_sharpness) {
        return Rule::Corner;
    }
    match sharp_edges {
        0 => Rule::Smooth,
        1 => Rule::Dart,
        2 => Rule::Crease,
        _ => Rule::Corner,
    }
}

/// `Crease::SubdivideUniformSharpness` (vertex sharpness, and edges under the
/// uniform method).
pub fn decay(s: f32) -> f32 {
    if is_infinite(s) {
        s
    } else if s > 1.0 {
        s - 1.0
    } else {
        0.0
    }
}

/// `Crease::SubdivideEdgeSharpnessAtVertex`: the sharpness of the child of an
/// edge of sharpness `s` at an end vertex whose edges have `around` (the edge
/// itself included).
pub fn child_edge_sharpness(s: f32, chaikin: bool, around: impl Iterator<Item = f32>) -> f32 {
    if !chaikin || !is_sharp(s) || is_infinite(s) {
        return decay(s);
    }
    let (mut sum, mut count) = (0.0f32, 0usize);
    for x in around {
        if is_semi_sharp(x) {
            sum += x;
            count += 1;
        }
    }
    let mut s = s;
    if count > 1 {
        let mean_others = (sum - s) / (count - 1) as f32;
        s = 0.75 * s + 0.25 * mean_others;
    }
    s -= 1.0;
    if is_sharp(s) {
        s
    } else {
        0.0
    }
}

/// `Crease::ComputeFractionalWeightAtVertex`: the weight of the parent rule
/// when a vertex's rule changes, the mean parent sharpness of the features
/// (vertex and edges) that go from sharp to smooth, at most 1.
pub fn fractional_weight(
    parent_vertex: f32,
    child_vertex: f32,
    edges: impl Iterator<Item = (f32, f32)>,
) -> f64 {
    let (mut sum, mut count) = (0.0f32, 0usize);
    if is_sharp(parent_vertex) && !is_sharp(child_vertex) {
        sum += parent_vertex;
        count += 1;
    }
    for (p, c) in edges {
        if is_sharp(p) && !is_sharp(c) {
            sum += p;
            count += 1;
        }
    }
    if count == 0 {
        return 0.0;
    }
    let w = sum / count as f32;
    f64::from(if w > 1.0 { 1.0 } else { w })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn uniform_sharpness_loses_one_per_level_and_infinite_stays() {
        assert_eq!(decay(2.5), 1.5);
        assert_eq!(decay(1.0), 0.0);
        assert_eq!(decay(0.5), 0.0);
        assert_eq!(decay(10.0), 10.0);
        assert_eq!(decay(12.0), 12.0);
    }

    #[test]
    fn chaikin_blends_the_other_semi_sharp_edges_at_the_vertex() {
        // Edges 2 and 4 at the vertex: 0.75·2 + 0.25·4 − 1 = 1.5.
        let s = child_edge_sharpness(2.0, true, [2.0, 4.0, 0.0, 10.0].into_iter());
        assert_eq!(s, 1.5);
        // Alone among semi-sharp edges: as uniform.
        assert_eq!(child_edge_sharpness(2.0, true, [2.0, 0.0].into_iter()), 1.0);
        // Clamped at 0.
        assert_eq!(child_edge_sharpness(1.0, true, [1.0, 0.2].into_iter()), 0.0);
    }

    #[test]
    fn rules_follow_the_sharp_edge_count_and_vertex_sharpness() {
        assert_eq!(vertex_rule(0.0, 0), Rule::Smooth);
        assert_eq!(vertex_rule(0.0, 1), Rule::Dart);
        assert_eq!(vertex_rule(0.0, 2), Rule::Crease);
        assert_eq!(vertex_rule(0.0, 3), Rule::Corner);
        assert_eq!(vertex_rule(0.3, 0), Rule::Corner);
    }

    #[test]
    fn fractional_weight_is_the_mean_of_the_decaying_features() {
        let w = fractional_weight(0.0, 0.0, [(0.5, 0.0), (0.25, 0.0), (3.0, 2.0)].into_iter());
        assert_eq!(w, 0.375);
        assert_eq!(fractional_weight(0.0, 0.0, [(3.0, 2.0)].into_iter()), 0.0);
        assert_eq!(fractional_weight(1.5, 0.0, core::iter::empty()), 1.0);
    }
}
