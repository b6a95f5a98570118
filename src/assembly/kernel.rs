//! Pure element kernels of the total-Lagrangian formulation.
//!
//! For an element with nodes `a`, reference gradients `G_a = ∂N_a/∂X`,
//! `F = I + Σ_a u_a ⊗ G_a`, the internal force and tangent are
//!
//! ```text
//! f_a   = ∫ P G_a dV₀,                         P = F S
//! K_ab  = ∫ B_aᵀ 𝔻 B_b dV₀  +  ∫ (G_aᵀ S G_b) I dV₀
//! ```
//!
//! with `B_a` the 6×3 strain–displacement operator of `δE` (Voigt, order
//! 11, 22, 33, 12, 23, 13; engineering shear). For a small-strain material
//! `F = I` in `B_a`, the stress is `σ = ℂ:ε` and the geometric term is absent.

use crate::fem::volume_reference;
use crate::material::{Kinematics, Mat3, Mat6, Material};
use crate::mesh::ElementKind;
use nalgebra::{Matrix3, Vector3};

/// Why an element kernel could not be evaluated.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum KernelFailure {
    /// `det J ≤ 0` in the reference configuration (bad mesh).
    ReferenceInverted { quadrature_point: usize, det_j: f64 },
    /// `det F ≤ 0` (or not finite): the deformed element is inverted.
    Inverted { quadrature_point: usize, det_f: f64 },
}

/// Reference gradients `∂N_a/∂X` at one quadrature point and `det(∂X/∂ξ)·w`.
#[derive(Clone)]
pub struct PointGeometry {
    pub gradients: Vec<Vector3<f64>>,
    pub dv: f64,
}

/// Reference geometry of every quadrature point of an element: `∂N_a/∂X`
/// and the reference volume weight `det J₀ · w_q`.
pub fn reference_geometry(
    kind: ElementKind,
    reference_coords: &[[f64; 3]],
) -> Result<Vec<PointGeometry>, KernelFailure> {
    let r = volume_reference(kind);
    (0..r.num_points())
        .map(|q| {
            // J₀ = ∂X/∂ξ = Σ_a X_a ⊗ ∂N_a/∂ξ
            let mut j0 = Matrix3::zeros();
            for (x, g) in reference_coords.iter().zip(&r.gradients[q]) {
                j0 += Vector3::from(*x) * Vector3::from(*g).transpose();
            }
            let det = j0.determinant();
            if !(det > 0.0) {
                return Err(KernelFailure::ReferenceInverted {
                    quadrature_point: q,
                    det_j: det,
                });
            }
            let inv_t = j0.try_inverse().unwrap_or_else(Matrix3::zeros).transpose();
            Ok(PointGeometry {
                gradients: r.gradients[q]
                    .iter()
                    .map(|g| inv_t * Vector3::from(*g))
                    .collect(),
                dv: det * r.weights[q],
            })
        })
        .collect()
}

/// Deformation gradient `F = I + Σ_a u_a ⊗ G_a`.
pub fn deformation_gradient(gradients: &[Vector3<f64>], displacements: &[[f64; 3]]) -> Mat3 {
    let mut f = Mat3::identity();
    for (g, u) in gradients.iter().zip(displacements) {
        f += Vector3::from(*u) * g.transpose();
    }
    f
}

/// What an element evaluation returns: internal force `f` (length `3n`,
/// node-major) and, if asked, the tangent `K` (`3n × 3n`, row-major).
#[derive(Clone, Debug, Default)]
pub struct ElementOutput {
    pub force: Vec<f64>,
    pub stiffness: Vec<f64>,
}

/// Most nodes of an element (Hex20).
pub const MAX_NODES: usize = 20;

/// Most nodes of a linear element (Hex8): the kernel's scratch for an
/// element of at most this many nodes is sized for it, so a Tet4 or a
/// Hex8 never fills a 20-node buffer.
pub const LINEAR_MAX_NODES: usize = 8;

/// Internal force and (if `with_tangent`) tangent stiffness of one element.
/// `geometry` comes from [`reference_geometry`]. Allocates the two output
/// vectors; [`internal_force_and_tangent_into`] writes into the caller's.
pub fn internal_force_and_tangent(
    geometry: &[PointGeometry],
    displacements: &[[f64; 3]],
    material: &dyn Material,
    with_tangent: bool,
) -> Result<ElementOutput, KernelFailure> {
    let dofs = 3 * displacements.len();
    let mut out = ElementOutput {
        force: vec![0.0; dofs],
        stiffness: if with_tangent {
            vec![0.0; dofs * dofs]
        } else {
            Vec::new()
        },
    };
    let stiffness = with_tangent.then_some(&mut out.stiffness[..]);
    internal_force_and_tangent_into(geometry, displacements, material, &mut out.force, stiffness)?;
    Ok(out)
}

/// The tangent's blocks `K_ab` for `b ≥ a` of an element of at most `M`
/// nodes (`B = M (M + 1) / 2`), `3 × 3` each (row: a-dof `i`, column:
/// b-dof `k`, row-major), in the order `(0,0), (0,1), …, (0,n−1), (1,1), …`.
type UpperBlocks<const B: usize> = [[f64; 9]; B];

/// Blocks of an element of at most [`LINEAR_MAX_NODES`] nodes.
const LINEAR_BLOCKS: usize = LINEAR_MAX_NODES * (LINEAR_MAX_NODES + 1) / 2;
/// Blocks of an element of at most [`MAX_NODES`] nodes.
const MAX_BLOCKS: usize = MAX_NODES * (MAX_NODES + 1) / 2;

/// The first elasticity tensor of one quadrature point times its volume
/// weight, `𝔸_iJkL dV₀ = (F_iI F_kK ℂ_IJKL + δ_ik S_JL) dV₀` (without
/// `S` for a small-strain material, `F = I`), stored `a[J][L][3i + k]`:
/// the tangent of the point is `K_ab,ik = Σ_JL G_aJ 𝔸_iJkL G_bL dV₀`
/// (`ℂ_IJKL = 𝔻_αβ` with `α = (IJ)`, `β = (KL)` Voigt; the `(I, J)` ↔
/// `(K, L)` symmetry of `𝔻` makes `a[L][J][3k + i] = a[J][L][3i + k]`,
/// computed for `J ≤ L` and copied).
fn first_elasticity(f: &Mat3, s: Option<&Mat3>, d: &Mat6, dv: f64) -> [[[f64; 9]; 3]; 3] {
    // Voigt index of (I, J)
    const V: [[usize; 3]; 3] = [[0, 3, 5], [3, 1, 4], [5, 4, 2]];
    let mut a = [[[0.0; 9]; 3]; 3];
    for jj in 0..3 {
        for ll in jj..3 {
            // t[I][k] = Σ_K ℂ_IJKL F_kK
            let mut t = [[0.0; 3]; 3];
            for (ii, t_i) in t.iter_mut().enumerate() {
                let alpha = V[ii][jj];
                for (k, t_ik) in t_i.iter_mut().enumerate() {
                    *t_ik = (0..3).map(|kk| d[(alpha, V[kk][ll])] * f[(k, kk)]).sum();
                }
            }
            let mut block = [0.0; 9];
            for i in 0..3 {
                for k in 0..3 {
                    let material: f64 = (0..3).map(|ii| f[(i, ii)] * t[ii][k]).sum();
                    let geometric = match s {
                        Some(s) if i == k => s[(jj, ll)],
                        _ => 0.0,
                    };
                    block[3 * i + k] = (material + geometric) * dv;
                }
            }
            a[jj][ll] = block;
            a[ll][jj] = std::array::from_fn(|m| block[3 * (m % 3) + m / 3]);
        }
    }
    a
}

/// [`internal_force_and_tangent`] into `force` (length `3n`) and, if
/// given, `stiffness` (`3n × 3n`, row-major, exactly symmetric), both
/// overwritten, without a heap allocation: the blocks `K_ab`, `b ≥ a`,
/// are summed over the points on the stack and mirrored once at the end.
///
/// At each point `𝔸 dV₀` is formed once ([`first_elasticity`]), then for
/// each node `a` the `3 × 9` contraction `h_a[L][3i + k] = Σ_J G_aJ 𝔸_iJkL`
/// and for each `b ≥ a` `K_ab,ik += Σ_L h_a[L][3i + k] G_bL`: the same
/// tangent as `Σ B_aᵀ 𝔻 B_b + (G_aᵀ S G_b) I` in about two thirds of the
/// operations, with `𝔻` symmetric (every material here is hyperelastic
/// or linear).
pub fn internal_force_and_tangent_into(
    geometry: &[PointGeometry],
    displacements: &[[f64; 3]],
    material: &dyn Material,
    force: &mut [f64],
    stiffness: Option<&mut [f64]>,
) -> Result<(), KernelFailure> {
    let n = displacements.len();
    assert!(n <= MAX_NODES, "an element of {n} nodes");
    if n <= LINEAR_MAX_NODES {
        let mut upper: UpperBlocks<LINEAR_BLOCKS> = [[0.0; 9]; LINEAR_BLOCKS];
        accumulate(
            geometry,
            displacements,
            material,
            force,
            stiffness,
            &mut upper,
        )
    } else {
        quadratic(geometry, displacements, material, force, stiffness)
    }
}

/// [`accumulate`] with the scratch of a 20-node element, in a frame of its
/// own (the linear elements' frame does not grow).
#[inline(never)]
fn quadratic(
    geometry: &[PointGeometry],
    displacements: &[[f64; 3]],
    material: &dyn Material,
    force: &mut [f64],
    stiffness: Option<&mut [f64]>,
) -> Result<(), KernelFailure> {
    let mut upper: UpperBlocks<MAX_BLOCKS> = [[0.0; 9]; MAX_BLOCKS];
    accumulate(
        geometry,
        displacements,
        material,
        force,
        stiffness,
        &mut upper,
    )
}

/// The body of [`internal_force_and_tangent_into`] with the scratch
/// `upper` (zeroed, at least `n (n + 1) / 2` blocks).
#[inline(always)]
fn accumulate(
    geometry: &[PointGeometry],
    displacements: &[[f64; 3]],
    material: &dyn Material,
    force: &mut [f64],
    stiffness: Option<&mut [f64]>,
    upper: &mut [[f64; 9]],
) -> Result<(), KernelFailure> {
    let n = displacements.len();
    let dofs = 3 * n;
    force.iter_mut().for_each(|v| *v = 0.0);
    let small = material.kinematics() == Kinematics::SmallStrain;
    for (q, p) in geometry.iter().enumerate() {
        let f = deformation_gradient(&p.gradients, displacements);
        let det_f = f.determinant();
        let admissible = det_f > 0.0 && det_f.is_finite();
        if !small && !admissible {
            return Err(KernelFailure::Inverted {
                quadrature_point: q,
                det_f,
            });
        }
        // the stress alone where no tangent is asked (line search, convergence
        // checks): a material may compute it for much less (Ogden: no 𝔻)
        let (s, d): (Mat3, Option<Mat6>) = if stiffness.is_some() {
            let (s, d) = material.stress_and_tangent(&f);
            (s, Some(d))
        } else {
            (material.second_piola_kirchhoff(&f), None)
        };
        let kin = if small { Mat3::identity() } else { f };
        // f_a = ∫ (F S) G_a dV₀
        let pk1 = kin * s;
        for a in 0..n {
            let fa = pk1 * p.gradients[a] * p.dv;
            for i in 0..3 {
                force[3 * a + i] += fa[i];
            }
        }
        let Some(d) = d else {
            continue;
        };
        let tangent = first_elasticity(&kin, (!small).then_some(&s), &d, p.dv);
        let mut block = 0;
        for (a, g_a) in p.gradients.iter().enumerate() {
            // h[L][m] = Σ_J G_aJ 𝔸[J][L][m]
            let h: [[f64; 9]; 3] = std::array::from_fn(|l| {
                std::array::from_fn(|m| {
                    g_a[0] * tangent[0][l][m]
                        + g_a[1] * tangent[1][l][m]
                        + g_a[2] * tangent[2][l][m]
                })
            });
            for g_b in &p.gradients[a..] {
                let k_ab = &mut upper[block];
                for m in 0..9 {
                    k_ab[m] += h[0][m] * g_b[0] + h[1][m] * g_b[1] + h[2][m] * g_b[2];
                }
                block += 1;
            }
        }
    }
    if let Some(k) = stiffness {
        // K_ba = K_abᵀ; a diagonal block's upper half mirrored onto its lower
        let mut block = 0;
        for a in 0..n {
            for b in a..n {
                let k_ab = &upper[block];
                for i in 0..3 {
                    for j in 0..3 {
                        let v = if a == b && j < i {
                            k_ab[3 * j + i]
                        } else {
                            k_ab[3 * i + j]
                        };
                        k[(3 * a + i) * dofs + 3 * b + j] = v;
                        k[(3 * b + j) * dofs + 3 * a + i] = v;
                    }
                }
                block += 1;
            }
        }
    }
    Ok(())
}

/// Cauchy stress `σ = J⁻¹ F S Fᵀ` averaged over the element's quadrature
/// points (volume-weighted), for output. Small-strain materials return `σ`.
pub fn element_cauchy_stress(
    geometry: &[PointGeometry],
    displacements: &[[f64; 3]],
    material: &dyn Material,
) -> Mat3 {
    let small = material.kinematics() == Kinematics::SmallStrain;
    let mut sum = Mat3::zeros();
    let mut vol = 0.0;
    for p in geometry {
        let f = deformation_gradient(&p.gradients, displacements);
        let s = material.second_piola_kirchhoff(&f);
        let sigma = if small {
            s
        } else {
            f * s * f.transpose() / f.determinant()
        };
        sum += sigma * p.dv;
        vol += p.dv;
    }
    sum / vol
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::{LinearElastic, NeoHookean, Ogden, SaintVenantKirchhoff};

    /// The 6×3 block `B_a` of `δE = Σ_a B_a δu_a` for deformation gradient `F`.
    fn strain_operator(f: &Mat3, g: &Vector3<f64>) -> nalgebra::Matrix6x3<f64> {
        let mut b = nalgebra::Matrix6x3::zeros();
        for i in 0..3 {
            b[(0, i)] = f[(i, 0)] * g[0];
            b[(1, i)] = f[(i, 1)] * g[1];
            b[(2, i)] = f[(i, 2)] * g[2];
            b[(3, i)] = f[(i, 0)] * g[1] + f[(i, 1)] * g[0];
            b[(4, i)] = f[(i, 1)] * g[2] + f[(i, 2)] * g[1];
            b[(5, i)] = f[(i, 0)] * g[2] + f[(i, 2)] * g[0];
        }
        b
    }

    /// A distorted element of `kind` (the reference nodes through
    /// `X = A ξ + 0.03 (ξ₂², ξ₀ ξ₁, ξ₁²)`: curved for a quadratic kind) and
    /// a displacement of a few percent.
    fn element(kind: ElementKind) -> (Vec<PointGeometry>, Vec<[f64; 3]>) {
        let corners: Vec<[f64; 3]> = crate::fem::shape::reference_nodes(kind)
            .iter()
            .map(|x| {
                [
                    x[0] + 0.1 * x[1] + 0.03 * x[2] * x[2],
                    0.05 * x[0] + 0.9 * x[1] + 0.03 * x[0] * x[1],
                    0.02 * x[0] + 0.1 * x[1] + 1.1 * x[2] + 0.03 * x[1] * x[1],
                ]
            })
            .collect();
        let u = (0..corners.len())
            .map(|a| {
                [
                    0.03 * (a as f64).sin(),
                    -0.02 * (a as f64 * 0.7).cos(),
                    0.04 * (a as f64 * 1.3).sin(),
                ]
            })
            .collect();
        (reference_geometry(kind, &corners).unwrap(), u)
    }

    const KINDS: [ElementKind; 7] = [
        ElementKind::Tet4,
        ElementKind::Hex8,
        ElementKind::Tet10,
        ElementKind::Hex20,
        ElementKind::Hex20R,
        ElementKind::Wedge6,
        ElementKind::Wedge15,
    ];

    /// The fixed-size kernel (no heap allocation) against the formula
    /// evaluated densely: `f = Σ_q P Gₐ dV`, `K = Σ_q (Bᵀ 𝔻 B + (Gₐ·S G_b) I) dV`
    /// with the full `6 × 3n` operator `B` (nalgebra's dynamic matrices, no
    /// symmetric half, no first elasticity tensor), to 1e-13 relative, for
    /// every element kind, the small-strain and the three finite-strain
    /// materials; `K` exactly symmetric; and the allocating wrapper gives
    /// the same numbers.
    #[test]
    fn fixed_size_kernel_equals_the_dense_formula() {
        let materials: [Box<dyn Material>; 4] = [
            Box::new(LinearElastic::new(1000.0, 0.3, "m").unwrap()),
            Box::new(NeoHookean::new(100.0, 0.45, "m").unwrap()),
            Box::new(SaintVenantKirchhoff::new(100.0, 0.3, "m").unwrap()),
            Box::new(
                Ogden::new(vec![0.4095, 0.003, 0.01], vec![1.3, 5.0, -2.0], 4.0, "m").unwrap(),
            ),
        ];
        for kind in KINDS {
            let (geometry, u) = element(kind);
            let n = u.len();
            for material in &materials {
                let small = material.kinematics() == Kinematics::SmallStrain;
                let mut force = vec![1.0; 3 * n];
                let mut k = vec![1.0; 9 * n * n];
                internal_force_and_tangent_into(
                    &geometry,
                    &u,
                    material.as_ref(),
                    &mut force,
                    Some(&mut k),
                )
                .unwrap();
                let mut f_ref = nalgebra::DVector::<f64>::zeros(3 * n);
                let mut k_ref = nalgebra::DMatrix::<f64>::zeros(3 * n, 3 * n);
                for p in &geometry {
                    let f = deformation_gradient(&p.gradients, &u);
                    let (s, d) = material.stress_and_tangent(&f);
                    let kin = if small { Mat3::identity() } else { f };
                    let mut b = nalgebra::DMatrix::<f64>::zeros(6, 3 * n);
                    for (a, g) in p.gradients.iter().enumerate() {
                        b.view_mut((0, 3 * a), (6, 3))
                            .copy_from(&strain_operator(&kin, g));
                        let fa = kin * s * g * p.dv;
                        for i in 0..3 {
                            f_ref[3 * a + i] += fa[i];
                        }
                    }
                    let d = nalgebra::DMatrix::from_iterator(6, 6, d.iter().copied());
                    k_ref += b.transpose() * d * &b * p.dv;
                    if !small {
                        for (a, ga) in p.gradients.iter().enumerate() {
                            for (c, gc) in p.gradients.iter().enumerate() {
                                let geo = ga.dot(&(s * gc)) * p.dv;
                                for i in 0..3 {
                                    k_ref[(3 * a + i, 3 * c + i)] += geo;
                                }
                            }
                        }
                    }
                }
                let f_scale = f_ref.amax();
                let k_scale = k_ref.amax();
                assert!(f_scale > 0.0 && k_scale > 0.0);
                for r in 0..3 * n {
                    assert!(
                        (force[r] - f_ref[r]).abs() <= 1e-13 * f_scale,
                        "{kind:?} f[{r}]"
                    );
                    for c in 0..3 * n {
                        let v = k[r * 3 * n + c];
                        assert!(
                            (v - k_ref[(r, c)]).abs() <= 1e-13 * k_scale,
                            "{kind:?} K[{r},{c}]"
                        );
                    }
                }
                for r in 0..3 * n {
                    for c in 0..r {
                        assert_eq!(k[r * 3 * n + c], k[c * 3 * n + r], "{kind:?} K symmetric");
                    }
                }
                let wrapped =
                    internal_force_and_tangent(&geometry, &u, material.as_ref(), true).unwrap();
                assert_eq!((wrapped.force, wrapped.stiffness), (force, k));
            }
        }
    }

    /// A force-only evaluation (the material's stress alone) gives the
    /// force of the evaluation with the tangent bit for bit, for materials
    /// with and without their own stress-only path (Ogden, neo-Hookean).
    #[test]
    fn force_alone_equals_the_force_with_the_tangent() {
        let materials: [Box<dyn Material>; 2] = [
            Box::new(
                Ogden::new(vec![0.4095, 0.003, 0.01], vec![1.3, 5.0, -2.0], 4.0, "m").unwrap(),
            ),
            Box::new(NeoHookean::new(100.0, 0.45, "m").unwrap()),
        ];
        for kind in KINDS {
            let (geometry, u) = element(kind);
            for material in &materials {
                let full =
                    internal_force_and_tangent(&geometry, &u, material.as_ref(), true).unwrap();
                let alone =
                    internal_force_and_tangent(&geometry, &u, material.as_ref(), false).unwrap();
                assert_eq!(alone.force, full.force, "{kind:?} {}", material.name());
                assert!(alone.stiffness.is_empty());
            }
        }
    }
}
