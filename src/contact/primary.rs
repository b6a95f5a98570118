//! A primary surface of a deformable body (formulation note §4, last
//! point): the triangles that the secondary nodes of an interface are
//! projected on, moving with the mesh, and the search that pairs each
//! secondary node with the triangles it may touch.
//!
//! ## Search rule
//! Pairs are found at the start of every increment attempt, from the last
//! converged configuration: the candidates of a secondary node are the
//! primary triangles whose bounding box, grown by a margin `δ_t`, contains
//! the node. `δ_t = 2 h_t + 2 d`, with `h_t = √(2 A_t)` the triangle's size
//! (the side of the square a quadrangle facet was split from)
//! and `d` the largest displacement of a contact node over the previous
//! increment scaled to the new increment's length: the pairs hold while no
//! node slides more than a couple of the local elements within one
//! increment. Before any increment has measured a motion (the run's first),
//! on Newton's path `d` is the largest change of a prescribed displacement
//! over the increment (the condensed path's rounds take `d = 0`: they read
//! every candidate, and wider pairs cost two-spheres' run two rounds):
//! bodies that start apart and close within it are paired at
//! its start (examples/two-spheres with mortar on Newton's path: the first
//! search at `d = 0` missed the contact edge's faces, 0.0117 apart
//! against a margin of 0.0075, and Newton's 17 iterations on those pairs
//! were thrown away; BENCHMARKS.md, "Session 26: mortar Newton, the first
//! search"). Where an increment's answer leaves them (the stepper's
//! check, [`IncrementFailure::PairsMoved`](crate::solve::failure::IncrementFailure::PairsMoved)),
//! the same increment is searched again once, the candidates of a search
//! at that answer with no motion added, and solved again before any cut
//! (bodies closed by a load rather than a prescribed motion). The margin is local so that
//! a graded surface (fine where the bodies touch, coarse elsewhere) does
//! not pair the fine region's nodes with hundreds of triangles (a mean size
//! did: 7.8 M matrix entries for 26 k dofs in the two-spheres example
//! before). The candidates fix the sparsity pattern of
//! the increment (each secondary node is coupled with the nodes of its
//! candidates); within the increment each Newton iteration (or condensed
//! round) projects the node on one of them by the facet choice below. The search is an R*-tree
//! over the grown boxes (the `rstar` crate), `O(log n)` per node.
//!
//! ## Facet choice
//! A node over an edge or a vertex of the primary surface is over several
//! triangles, whose plane gaps and normals differ on a curved surface, so
//! the answer depends on which one it takes. The choice reads the node's
//! position and its [`FacetWalk`](super::facet_walk::FacetWalk) (the
//! triangle at the last converged increment, and whether the node has
//! flipped back to a triangle it had left within the increment):
//! 1. the *kept* triangle while it is among the node's candidates and the
//!    node is over it within [`STICKY_BAND`]: the committed triangle (the
//!    last converged increment's), or once the node has flipped back
//!    (`A → B → A`, or onto its committed triangle after an excursion) the
//!    last iterate's;
//! 2. else the nearest candidate by [`best_triangle`]: the smallest
//!    closest-point distance, ties (within [`TIE_TOLERANCE`] of the
//!    triangle's size) to the triangle whose normal is most aligned with the
//!    direction to the node, then to the smallest index: a function of the
//!    geometry, not of the candidates' order or of round-off.
//!
//! Why committed first: Newton's iterates and the condensed rounds reach an
//! increment's answer along different iterates. Against the last iterate's
//! triangle (the rule before), a node that Newton's first iterates carried
//! off its triangle stayed on another one within the band, and on
//! examples/two-spheres (matching meshes: every secondary node over a
//! primary vertex, within the band of all the triangles around it) the two
//! paths' answers differed by 1.9e-4 of the displacements, both converged.
//! Against the committed triangle, a node whose iterates never flip back
//! ends on a function of the committed state and its position alone,
//! whichever iterates led there (two-spheres: the paths agree to
//! round-off; DESIGN.md, "The condensed contact path").
//!
//! Why the flip back: committed first alone leaves a node sliding over a
//! crease without a fixed point (three sliding tests of tests/deformable.rs
//! did not converge): on its committed triangle `A` its answer lies beyond
//! `A` by more than the band, so it takes `B`, where its answer lies over
//! `A` again. A node that comes back to a triangle it had left keeps its
//! last iterate's triangle from then on within the increment (the band's
//! hysteresis), so it settles on `B`. Only such nodes' answers depend on
//! the path.
//!
//! Quadrangle facets (Hex8 faces) are split into two triangles
//! (`(q0, q1, q2)`, `(q0, q2, q3)`), so the projection is exact and the gap
//! smooth within each triangle.

use crate::contact::closest_point_on_triangle;
use crate::contact::friction::MaterialPoint;
use crate::contact::kinematics::{current_position, SecondaryNode};
use crate::contact::triangle::TriangleProjection;
use crate::contact::triangle_gap::{facet_triangles, is_degenerate, triangle_gap, TriangleGap};
use crate::contact::tributary::tributary_areas;
use crate::mesh::Mesh;
use nalgebra::Vector3;
use rstar::primitives::{GeomWithData, Rectangle};
use rstar::RTree;

/// How far outside its triangle (in barycentric coordinates) a node keeps
/// the triangle it was projected on before. The plane-extended gap jumps
/// where two non-coplanar triangles meet (a warped quadrangle's diagonal,
/// an element edge of a curved surface); a node sitting on such a crease
/// flipped between the two triangles at every Newton iteration and never
/// converged (the stacked-blocks patch test, nodes on the diagonals). The
/// band makes the choice hysteretic: a node changes triangle once it is 5 %
/// of the triangle beyond it. Kept is the committed triangle, or after a
/// flip back the last iterate's (module docs, "Facet choice"), so that
/// only a node that flips back has a converged state that depends on the
/// path.
pub(crate) const STICKY_BAND: f64 = 0.05;

/// A surface of the mesh as primary triangles, with the current candidates.
#[derive(Clone, Debug)]
pub struct PrimarySurface {
    /// Surface-set name.
    pub surface: String,
    /// Mesh node indices of each triangle, ordered so that the right-hand
    /// normal points out of the primary body (the mesh's facet orientation).
    pub triangles: Vec<[usize; 3]>,
    /// The surface's nodes (sorted)…
    pub nodes: Vec<usize>,
    /// …and their tributary reference areas (for the report).
    pub node_areas: Vec<f64>,
    /// Per secondary node, the candidate triangles (indices into
    /// `triangles`), refreshed by [`refresh`](Self::refresh).
    pub candidates: Vec<Vec<usize>>,
    /// Contact element size of the primary surface (square root of the mean
    /// triangle area).
    pub element_size: f64,
    /// The search margin `δ` of the last refresh: the gap reported for a
    /// secondary node without candidates (it is at least that far).
    pub margin: f64,
}

impl PrimarySurface {
    /// The surface set `surface` of `mesh` as triangles; `None` if the mesh
    /// has no such set.
    pub fn from_mesh(mesh: &Mesh, surface: &str) -> Option<Self> {
        let set = mesh.surface(surface)?;
        let triangles = facet_triangles(&set.facets, |n| n);
        let area: f64 = triangles
            .iter()
            .map(|t| {
                let p = |i: usize| Vector3::from(mesh.nodes[t[i]]);
                0.5 * (p(1) - p(0)).cross(&(p(2) - p(0))).norm()
            })
            .sum();
        let element_size = (area / triangles.len().max(1) as f64).sqrt();
        let (nodes, node_areas) = tributary_areas(mesh, set);
        Some(Self {
            surface: surface.to_string(),
            triangles,
            nodes,
            node_areas,
            candidates: Vec::new(),
            element_size,
            margin: 2.0 * element_size,
        })
    }

    /// Current corners of triangle `t`.
    pub fn corners(&self, reference: &[[f64; 3]], x: &[f64], t: usize) -> [Vector3<f64>; 3] {
        self.triangles[t].map(|n| current_position(reference, x, n))
    }

    /// Recompute every secondary node's candidates at configuration `x`,
    /// each triangle's box grown by `δ_t = 2 h_t + 2 motion` (see the
    /// module's search rule); with `reached` (the unknowns of an answer
    /// that left the last candidates) also those a search there with no
    /// motion finds. Returns whether any candidate list changed.
    pub fn refresh(
        &mut self,
        reference: &[[f64; 3]],
        x: &[f64],
        secondary: &[usize],
        motion: f64,
        reached: Option<&[f64]>,
    ) -> bool {
        let (mut candidates, smallest) = self.search(reference, x, secondary, motion);
        if let Some(reached) = reached {
            let there = self.search(reference, reached, secondary, 0.0).0;
            merge_candidates(&mut candidates, there);
        }
        let changed = candidates != self.candidates;
        self.candidates = candidates;
        // the gap reported for a node without candidates (it is at least
        // this far): positive, also with degenerate triangles and no motion
        if smallest.is_finite() {
            self.margin = smallest.max(1e-3 * self.element_size);
        }
        changed
    }

    /// Each secondary node's candidates at configuration `x` with the
    /// margins `2 h_t + 2 motion`, and the smallest margin.
    fn search(
        &self,
        reference: &[[f64; 3]],
        x: &[f64],
        secondary: &[usize],
        motion: f64,
    ) -> (Vec<Vec<usize>>, f64) {
        let mut smallest = f64::INFINITY;
        let boxes: Vec<(Vector3<f64>, Vector3<f64>)> = (0..self.triangles.len())
            .map(|t| {
                let c = self.corners(reference, x, t);
                // √(2 A_t): the side of a square split in two such triangles
                let size = (c[1] - c[0]).cross(&(c[2] - c[0])).norm().sqrt();
                let margin = 2.0 * size + 2.0 * motion;
                if size > 0.0 {
                    smallest = smallest.min(margin);
                }
                let lo = c[0].inf(&c[1]).inf(&c[2]).add_scalar(-margin);
                let hi = c[0].sup(&c[1]).sup(&c[2]).add_scalar(margin);
                (lo, hi)
            })
            .collect();
        let points: Vec<Vector3<f64>> = secondary
            .iter()
            .map(|&s| current_position(reference, x, s))
            .collect();
        (boxes_containing(&boxes, &points), smallest)
    }

    /// Secondary node `node` at `x_s` against its primary triangle: `kept`
    /// (the facet choice's, [`FacetWalk::kept`](super::facet_walk::FacetWalk::kept))
    /// while it is still among the node's candidates and the node stays
    /// over it within [`STICKY_BAND`], else the nearest candidate
    /// ([`nearest_gap`](Self::nearest_gap)).
    /// `None` without a usable candidate, or beyond the primary surface's
    /// edge (the node is open: its extended plane would otherwise push it,
    /// with negative weights on the primary nodes).
    pub fn projection(
        &self,
        node: &SecondaryNode,
        kept: Option<usize>,
    ) -> Option<(usize, TriangleGap)> {
        let kept = kept.and_then(|t| {
            self.candidates
                .get(node.index)?
                .contains(&t)
                .then_some(())?;
            self.gap_within_band(node, t)
        });
        kept.or_else(|| self.nearest_gap(node))
    }

    /// The gap of `node` against triangle `t` where its projection is on the
    /// triangle within [`STICKY_BAND`].
    fn gap_within_band(&self, node: &SecondaryNode, t: usize) -> Option<(usize, TriangleGap)> {
        let c = self.corners(node.reference, node.x, t);
        let gap = triangle_gap(&node.position(), [&c[0], &c[1], &c[2]])?;
        gap.shape
            .iter()
            .all(|&n| n >= -STICKY_BAND)
            .then_some((t, gap))
    }

    /// The nearest of the candidate triangles of secondary node `node`
    /// ([`best_triangle`]: ties broken by its geometric rule) to its
    /// position, with its gap against it; `None` without usable candidates
    /// (degenerate triangles are skipped), or off the triangle by more than
    /// the band of the triangle choice (beyond the surface's edge).
    pub fn nearest_gap(&self, node: &SecondaryNode) -> Option<(usize, TriangleGap)> {
        let mut usable = self.candidate_corners(node)?;
        usable.retain(|(_, c)| !is_degenerate([&c[0], &c[1], &c[2]]));
        let choice = best_triangle(&node.position(), &usable)?;
        self.gap_within_band(node, choice.triangle)
    }

    /// The point of the candidate triangles of secondary node `node`
    /// closest to it, as a material point (triangle and barycentric
    /// weights, each in `[0, 1]`); `None` without candidates. Where a node
    /// over no triangle (beyond the surface's edge) anchors its friction.
    pub fn closest_material_point(&self, node: &SecondaryNode) -> Option<MaterialPoint> {
        let choice = best_triangle(&node.position(), &self.candidate_corners(node)?)?;
        Some(MaterialPoint {
            triangle: choice.triangle,
            shape: choice.projection.barycentric,
            traction: [0.0; 2],
        })
    }

    /// The candidate triangles of secondary node `node` with their current
    /// corners; `None` before a search.
    fn candidate_corners(&self, node: &SecondaryNode) -> Option<Vec<(usize, [Vector3<f64>; 3])>> {
        Some(
            self.candidates
                .get(node.index)?
                .iter()
                .map(|&t| (t, self.corners(node.reference, node.x, t)))
                .collect(),
        )
    }

    /// Every mesh node of the candidates of secondary node `i` (sorted,
    /// without repeats).
    pub fn candidate_nodes(&self, i: usize) -> Vec<usize> {
        let mut nodes: Vec<usize> = self
            .candidates
            .get(i)
            .into_iter()
            .flatten()
            .flat_map(|&t| self.triangles[t])
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }
}

/// Adds `more` to `candidates`, item by item (each sorted, no repeats).
pub(crate) fn merge_candidates(candidates: &mut [Vec<usize>], more: Vec<Vec<usize>>) {
    for (mine, theirs) in candidates.iter_mut().zip(more) {
        mine.extend(theirs);
        mine.sort_unstable();
        mine.dedup();
    }
}

/// For each point, the boxes (`(lo, hi)`) that contain it, in increasing
/// box index, from an R*-tree over the boxes (the `rstar` crate).
pub fn boxes_containing(
    boxes: &[(Vector3<f64>, Vector3<f64>)],
    points: &[Vector3<f64>],
) -> Vec<Vec<usize>> {
    let corner = |v: &Vector3<f64>| [v.x, v.y, v.z];
    let tree = RTree::bulk_load(
        boxes
            .iter()
            .enumerate()
            .map(|(b, (lo, hi))| {
                GeomWithData::new(Rectangle::from_corners(corner(lo), corner(hi)), b)
            })
            .collect(),
    );
    points
        .iter()
        .map(|p| {
            let mut found: Vec<usize> = tree
                .locate_all_at_point(corner(p))
                .map(|b| b.data)
                .collect();
            found.sort_unstable();
            found
        })
        .collect()
}

/// Closest-point distances within `TIE_TOLERANCE · h` of the smallest
/// tie (`h` the longest edge of the nearest triangle), and so do
/// alignments `|n_t · e|` within `TIE_TOLERANCE` of the largest: above the
/// round-off of a position or a distance (1e-16 relative), and small
/// enough that the chosen triangle's distance is the smallest to 1e-14 `h`
/// (a rigid triangulated obstacle's signed distance is exact to 1e-13:
/// tests/contact_geometry.rs; 1e-8 put it 2e-9 off).
pub const TIE_TOLERANCE: f64 = 1e-14;

/// The facet choice of [`best_triangle`]: the chosen triangle, the closest
/// point on it, and every candidate tied with it by distance.
#[derive(Clone, Debug, PartialEq)]
pub struct FacetChoice {
    /// The chosen triangle (an index into the surface's triangles).
    pub triangle: usize,
    /// The closest point of `triangle` to the node.
    pub projection: TriangleProjection,
    /// The candidates whose closest point is as near as the nearest's,
    /// within `TIE_TOLERANCE · h` (`triangle` among them), by increasing index.
    pub tied: Vec<usize>,
}

/// The candidate triangle a secondary node at `x_s` is projected on, a
/// function of the geometry alone (not of the order of the candidates,
/// nor of the path that led there):
///
/// 1. the triangles whose closest point `x̄_t` is nearest, `d_t = |x_s − x̄_t|`
///    within `TIE_TOLERANCE · h` of the smallest `d` (a node over an edge or
///    a vertex ties the triangles that share it);
/// 2. among those, the triangles whose unit normal is most aligned with the
///    direction `e = (x_s − x̄)/d` to the node, `|n_t · e|` within
///    `TIE_TOLERANCE` of the largest: the triangle whose plane projection
///    `x_s − g_t n_t` lies nearest `x̄` (`|x_s − x̄|² = g_t² + |x̄ − (x_s − g_t n_t)|²`),
///    so its plane gap is the nearest to the distance. Where the node is
///    on the surface (`d ≤ TIE_TOLERANCE · h`) `e` is the mean of the tied
///    triangles' normals;
/// 3. among those, the smallest index.
///
/// A node over the interior of a triangle gets that triangle; a node over
/// an edge or a vertex gets one of the triangles sharing it, its plane's
/// gap then used (the usual node-to-surface choice, exact on flat
/// surfaces). `None` without candidates.
pub fn best_triangle(
    x_s: &Vector3<f64>,
    candidates: &[(usize, [Vector3<f64>; 3])],
) -> Option<FacetChoice> {
    let projected: Vec<Projected> = candidates
        .iter()
        .map(|(t, c)| Projected::of(x_s, *t, c))
        .collect();
    let nearest = projected
        .iter()
        .min_by(|a, b| a.distance.total_cmp(&b.distance))?;
    let tie = TIE_TOLERANCE * nearest.size;
    let mut tied: Vec<&Projected> = (projected.iter())
        .filter(|q| q.distance <= nearest.distance + tie)
        .collect();
    tied.sort_by_key(|q| q.triangle);
    let direction = if nearest.distance > tie {
        (x_s - nearest.closest.point) / nearest.distance
    } else {
        let sum: Vector3<f64> = tied.iter().map(|q| q.normal).sum();
        sum.try_normalize(0.0).unwrap_or_else(Vector3::zeros)
    };
    let alignment = |q: &Projected| q.normal.dot(&direction).abs();
    let most = tied.iter().map(|q| alignment(q)).fold(0.0, f64::max);
    let chosen = tied.iter().find(|q| alignment(q) >= most - TIE_TOLERANCE)?;
    Some(FacetChoice {
        triangle: chosen.triangle,
        projection: chosen.closest,
        tied: tied.iter().map(|q| q.triangle).collect(),
    })
}

/// A candidate triangle as [`best_triangle`] weighs it.
struct Projected {
    triangle: usize,
    /// Its closest point `x̄_t` to the node…
    closest: TriangleProjection,
    /// …at `d_t = |x_s − x̄_t|`.
    distance: f64,
    /// Its unit normal (zero for a degenerate triangle).
    normal: Vector3<f64>,
    /// Its longest edge `h`.
    size: f64,
}

impl Projected {
    fn of(x_s: &Vector3<f64>, triangle: usize, c: &[Vector3<f64>; 3]) -> Self {
        let closest = closest_point_on_triangle(x_s, &c[0], &c[1], &c[2]);
        let normal = (c[1] - c[0]).cross(&(c[2] - c[0]));
        Self {
            triangle,
            closest,
            distance: (x_s - closest.point).norm(),
            normal: normal.try_normalize(0.0).unwrap_or_else(Vector3::zeros),
            size: longest_edge(c),
        }
    }
}

/// The longest edge of triangle `c`.
fn longest_edge(c: &[Vector3<f64>; 3]) -> f64 {
    (0..3)
        .map(|i| (c[(i + 1) % 3] - c[i]).norm())
        .fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grid_finds_exactly_the_containing_boxes() {
        // boxes of a 4 × 4 grid of unit squares (thin in z), points anywhere
        let mut boxes = Vec::new();
        for i in 0..4 {
            for j in 0..4 {
                let lo = Vector3::new(i as f64 - 0.1, j as f64 - 0.1, -0.1);
                boxes.push((lo, lo + Vector3::new(1.2, 1.2, 0.2)));
            }
        }
        let points: Vec<Vector3<f64>> = (0..50)
            .map(|k| {
                let f = k as f64;
                Vector3::new(
                    (f * 0.37) % 4.4 - 0.2,
                    (f * 0.71) % 4.4 - 0.2,
                    ((f * 0.13) % 0.3) - 0.15,
                )
            })
            .collect();
        let found = boxes_containing(&boxes, &points);
        for (p, f) in points.iter().zip(&found) {
            let brute: Vec<usize> = (0..boxes.len())
                .filter(|&b| (0..3).all(|d| boxes[b].0[d] <= p[d] && p[d] <= boxes[b].1[d]))
                .collect();
            let mut f = f.clone();
            f.sort_unstable();
            assert_eq!(f, brute, "point {p:?}");
        }
    }

    #[test]
    fn best_triangle_is_the_one_under_the_node() {
        let a = [Vector3::zeros(), Vector3::x(), Vector3::y()];
        let b = [Vector3::x(), Vector3::new(1.0, 1.0, 0.0), Vector3::y()];
        let c = [(4, a), (7, b)];
        assert_eq!(
            best_triangle(&Vector3::new(0.2, 0.2, 0.3), &c).map(|b| b.triangle),
            Some(4)
        );
        assert_eq!(
            best_triangle(&Vector3::new(0.8, 0.7, -0.2), &c).map(|b| b.triangle),
            Some(7)
        );
        assert!(best_triangle(&Vector3::zeros(), &[]).is_none());
    }

    /// A fan of six triangles around the vertex `apex` (right-hand normals
    /// up), its rim at radii `1 ± 0.2` so that the faces tilt by different
    /// angles, numbered 10, 12, …, 20 and listed in `order`.
    fn fan(apex: Vector3<f64>, order: &[usize]) -> Vec<(usize, [Vector3<f64>; 3])> {
        let rim = |k: usize| {
            let angle = std::f64::consts::PI / 3.0 * k as f64;
            let r = 1.0 + 0.2 * ((k * 7 % 5) as f64 - 2.0) / 2.0;
            Vector3::new(r * angle.cos(), r * angle.sin(), 0.0)
        };
        order
            .iter()
            .map(|&k| (10 + 2 * k, [apex, rim(k), rim((k + 1) % 6)]))
            .collect()
    }

    /// A node over the apex of a fan ties all six triangles (their closest
    /// point is the apex); moved by ±1e-15 in x and y, and with the
    /// candidates listed in another order, it gets the same triangle: the
    /// one whose normal is most aligned with the direction from the apex to
    /// the node (found here by brute force); on a flat fan (every normal
    /// the same), the smallest index. The first nearest candidate in list
    /// order (the rule before) changes with the order.
    #[test]
    fn a_tie_at_a_vertex_goes_the_same_way_whatever_the_round_off() {
        let orders: [&[usize]; 3] = [
            &[0, 1, 2, 3, 4, 5],
            &[5, 4, 3, 2, 1, 0],
            &[3, 0, 4, 1, 5, 2],
        ];
        for (apex, above) in [
            (Vector3::new(0.0, 0.0, 0.3), Vector3::new(0.0, 0.0, 0.5)),
            (Vector3::new(0.0, 0.0, 0.3), Vector3::zeros()),
            (Vector3::zeros(), Vector3::new(0.0, 0.0, 0.5)),
        ] {
            let node = apex + above;
            let reference = fan(apex, orders[0]);
            // brute force: the most aligned normal with the direction to
            // the node (or, on the surface, with the mean normal), then
            // the smallest index
            let direction = if above.norm() > 0.0 {
                above.normalize()
            } else {
                let sum: Vector3<f64> = (reference.iter())
                    .map(|(_, c)| (c[1] - c[0]).cross(&(c[2] - c[0])).normalize())
                    .sum();
                sum.normalize()
            };
            let alignment = |c: &[Vector3<f64>; 3]| {
                (c[1] - c[0])
                    .cross(&(c[2] - c[0]))
                    .normalize()
                    .dot(&direction)
                    .abs()
            };
            let most = reference
                .iter()
                .map(|(_, c)| alignment(c))
                .fold(0.0, f64::max);
            let expected = (reference.iter())
                .filter(|(_, c)| alignment(c) >= most - TIE_TOLERANCE)
                .map(|(t, _)| *t)
                .min()
                .unwrap();
            let mut first_nearest = std::collections::BTreeSet::new();
            for order in orders {
                let candidates = fan(apex, order);
                for dx in [-1e-15, 0.0, 1e-15] {
                    for dy in [-1e-15, 0.0, 1e-15] {
                        let x = node + Vector3::new(dx, dy, 0.0);
                        let choice = best_triangle(&x, &candidates).unwrap();
                        assert_eq!(choice.triangle, expected, "apex {apex:?}, node {x:?}");
                        assert_eq!(choice.tied, vec![10, 12, 14, 16, 18, 20]);
                    }
                }
                let d = |c: &[Vector3<f64>; 3]| {
                    (node - closest_point_on_triangle(&node, &c[0], &c[1], &c[2]).point).norm()
                };
                let least = candidates
                    .iter()
                    .map(|(_, c)| d(c))
                    .fold(f64::MAX, f64::min);
                first_nearest.insert(candidates.iter().find(|(_, c)| d(c) == least).unwrap().0);
            }
            if apex.z > 0.0 && above.z > 0.0 {
                // the rim's radii make one face the most aligned
                assert_ne!(expected, 10);
            } else if apex.z == 0.0 {
                assert_eq!(expected, 10);
            }
            assert!(first_nearest.len() > 1, "the list order decided before");
        }
    }
}
