//! The mortar coupling of a secondary and a primary surface (Popp, Gee &
//! Wall 2009, §3; Popp et al. 2010, §3):
//!
//! ```text
//! D_j  = Σ_pairs Σ_cells ∫ Φ_j dA,            M_jl = Σ_pairs Σ_cells ∫ Φ_j N_l dA,
//! n_j  = Σ_e n_e(ξ_j) / |Σ_e n_e(ξ_j)|        (averaged outward nodal normal),
//! g̃_j = n_jᵀ (Σ_l M_jl x_l − D_j x̃_j)        (weighted gap, > 0 open),
//! ```
//!
//! with `x̃_j` the transformed nodal coordinates of [`super::quadratic`]
//! (`x̃_j = x_j` on linear faces). For multipliers `λ_j ≥ 0` (pressures),
//! the contact forces exerted on the nodes are
//!
//! ```text
//! secondary node k:  f_k = −Σ_j D_j λ_j n_j R_jk      (R_jk = ∂x̃_j/∂x_k),
//! primary node l:    f_l = +Σ_j M_jl λ_j n_j,
//! ```
//!
//! which sum to zero since `Σ_l M_jl = D_j` and `Σ_k R_jk = 1`. For a
//! uniform `λ` on a fully covered secondary surface they are the consistent
//! loads `∓λ ∫ N_k n dA`: the contact patch test.

use std::collections::BTreeMap;

use nalgebra::Vector3;

use super::dual_basis::faces_and_duals;
use super::face::SurfaceFace;
use super::normals::nodal_normals;
use super::quadratic;
use super::segment::integrate_pair;
use super::MortarError;

/// Every (secondary, primary) face index pair: the candidate list when no
/// search has narrowed it.
pub fn all_pairs(secondary_count: usize, primary_count: usize) -> Vec<(usize, usize)> {
    (0..secondary_count)
        .flat_map(|s| (0..primary_count).map(move |p| (s, p)))
        .collect()
}

/// The assembled mortar coupling of two surfaces (global node numbers).
#[derive(Clone, Debug, PartialEq, Default)]
pub struct MortarCoupling {
    /// `D_j` per secondary node touched by a segment.
    pub d: BTreeMap<usize, f64>,
    /// `M_jl` per (secondary node, primary node).
    pub m: BTreeMap<(usize, usize), f64>,
    /// `n_j` per secondary node.
    pub normals: BTreeMap<usize, Vector3<f64>>,
    /// `x̃_j = Σ_k R_jk x_k` per secondary node, as `(k, R_jk)`.
    pub transformation: BTreeMap<usize, Vec<(usize, f64)>>,
}

/// Integrates `D` and `M` over the candidate face `pairs`
/// (secondary index, primary index) and gathers the nodal normals.
pub fn mortar_coupling(
    secondary: &[SurfaceFace],
    primary: &[SurfaceFace],
    pairs: &[(usize, usize)],
    coordinates: &[Vector3<f64>],
) -> Result<MortarCoupling, MortarError> {
    let mut out = MortarCoupling {
        normals: nodal_normals(secondary, coordinates)?,
        ..MortarCoupling::default()
    };
    let (faces, duals) = faces_and_duals(secondary, coordinates)?;
    for &(s, p) in pairs {
        let primary_face = primary[p].with_coordinates(coordinates)?;
        let Some(seg) = integrate_pair(&faces[s], &duals[s], &primary_face)? else {
            continue;
        };
        for (j, &node_j) in secondary[s].nodes.iter().enumerate() {
            *out.d.entry(node_j).or_insert(0.0) += seg.d[j];
            for (l, &node_l) in primary[p].nodes.iter().enumerate() {
                *out.m.entry((node_j, node_l)).or_insert(0.0) += seg.m[(j, l)];
            }
        }
    }
    for face in secondary {
        for (j, row) in quadratic::nodal_transformation(face.shape)
            .into_iter()
            .enumerate()
        {
            let global = row.into_iter().map(|(k, r)| (face.nodes[k], r)).collect();
            out.transformation.insert(face.nodes[j], global);
        }
    }
    Ok(out)
}

impl MortarCoupling {
    /// `x̃_j = Σ_k R_jk x_k`.
    fn transformed(&self, j: usize, coordinates: &[Vector3<f64>]) -> Vector3<f64> {
        self.transformation[&j]
            .iter()
            .map(|(k, r)| coordinates[*k] * *r)
            .sum()
    }

    /// The weighted gaps `g̃_j = n_jᵀ (Σ_l M_jl x_l − D_j x̃_j)`.
    pub fn weighted_gaps(&self, coordinates: &[Vector3<f64>]) -> BTreeMap<usize, f64> {
        let mut gaps: BTreeMap<usize, Vector3<f64>> = self
            .d
            .iter()
            .map(|(&j, &d)| (j, -self.transformed(j, coordinates) * d))
            .collect();
        for (&(j, l), &m) in &self.m {
            *gaps.entry(j).or_insert_with(Vector3::zeros) += coordinates[l] * m;
        }
        gaps.into_iter()
            .map(|(j, v)| (j, self.normals[&j].dot(&v)))
            .collect()
    }

    /// The contact forces exerted on the nodes by the pressures `λ_j`
    /// (secondary `−Σ_j D_j λ_j n_j R_jk`, primary `+Σ_j M_jl λ_j n_j`).
    pub fn contact_forces(&self, pressure: &BTreeMap<usize, f64>) -> BTreeMap<usize, Vector3<f64>> {
        let mut forces: BTreeMap<usize, Vector3<f64>> = BTreeMap::new();
        let lambda = |j: &usize| pressure.get(j).copied().unwrap_or(0.0);
        for (j, d) in &self.d {
            let t = self.normals[j] * (d * lambda(j));
            for (k, r) in &self.transformation[j] {
                *forces.entry(*k).or_insert_with(Vector3::zeros) -= t * *r;
            }
        }
        for ((j, l), m) in &self.m {
            *forces.entry(*l).or_insert_with(Vector3::zeros) += self.normals[j] * (m * lambda(j));
        }
        forces
    }
}
