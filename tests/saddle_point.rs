//! Multiplier unknowns on the sparsity pattern: the symmetric indefinite
//! saddle system that contact will use, solved by faer's LDLᵀ with
//! sign-aware dynamic regularisation, under AMD and under nested dissection
//! with each multiplier ordered after its node.

mod common;

use common::{fix, problem, solve};
use signorini::assembly::pattern::SparsityPattern;
use signorini::material::LinearElastic;
use signorini::mesh::structured::box_mesh;
use signorini::mesh::ElementKind;
use signorini::solve::linear::{Ordering, SparseLdlt};
use std::sync::Arc;

/// Prescribing `u_z = d` on the top face with one Lagrange multiplier per
/// node, `[K Cᵀ; C 0] [u; λ] = [0; d]`, reproduces the displacement of the
/// same problem with those dofs eliminated (to 1e-10), and each multiplier
/// equals minus the reaction force there (to 1e-8 of the largest).
#[test]
fn lagrange_multipliers_reproduce_prescribed_displacements() {
    let d = -0.1;
    let mesh = box_mesh(ElementKind::Hex8, [4, 4, 4], [1.0, 1.0, 1.0]);
    let top = mesh.surface_nodes(mesh.surface("zmax").unwrap());
    let mut reference = problem(mesh, Arc::new(LinearElastic::new(100.0, 0.3, "m").unwrap()));
    fix(&mut reference, "zmin", &[(0, 0.0), (1, 0.0), (2, 0.0)]);
    fix(&mut reference, "zmax", &[(2, d)]);
    let (u_ref, _) = solve(&mut reference);
    let r_ref = reference.residual(1.0, &u_ref, None).unwrap().r;

    // the same with multipliers on the top face
    let model = &reference.model;
    let n_nodes = model.mesh.num_nodes();
    let augmented = SparsityPattern::with_multipliers(
        n_nodes,
        model.mesh.elements.iter().map(|e| e.nodes.as_slice()),
        &top.iter().map(|&s| vec![s]).collect::<Vec<_>>(),
    );
    let mut k = vec![0.0; model.pattern.nnz()];
    let mut f = vec![0.0; model.num_dofs()];
    model
        .assemble_internal(&vec![0.0; model.num_dofs()], &mut f, Some(&mut k))
        .unwrap();
    let (cp, ri) = (
        model.pattern.symbolic().col_ptr(),
        model.pattern.symbolic().row_idx(),
    );
    let mut values = vec![0.0; augmented.nnz()];
    let bottom = model
        .mesh
        .surface_nodes(model.mesh.surface("zmin").unwrap());
    let fixed = |dof: usize| bottom.binary_search(&(dof / 3)).is_ok();
    for j in 0..model.num_dofs() {
        for idx in cp[j]..cp[j + 1] {
            let i = ri[idx];
            let target = augmented.block_entry(i / 3, i % 3, j / 3, j % 3).unwrap();
            values[target] = if fixed(i) || fixed(j) {
                if i == j {
                    1.0
                } else {
                    0.0
                }
            } else {
                k[idx]
            };
        }
    }
    for (m, &s) in top.iter().enumerate() {
        let e = augmented.multiplier_entries(m, s).unwrap();
        values[e.node_rows[2]] = 1.0;
        values[e.multiplier_row[2]] = 1.0;
        values[augmented.multiplier_diagonal(m)] = 0.0;
    }
    let mut rhs = vec![0.0; augmented.dimension()];
    for m in 0..top.len() {
        rhs[3 * n_nodes + m] = d;
    }
    let (xadj, adjncy) = augmented.node_graph();
    let nodes = signorini::solve::ordering::nested_dissection(&xadj, &adjncy).unwrap();
    for ordering in [
        Ordering::Amd,
        Ordering::Custom(augmented.dof_ordering(&nodes)),
    ] {
        let mut solver = SparseLdlt::new(ordering, 1);
        solver
            .factorize(
                augmented.symbolic(),
                &values,
                Some(&augmented.pivot_signs()),
            )
            .unwrap();
        let mut x = rhs.clone();
        let residual = solver
            .solve_refined(augmented.symbolic(), &values, &mut x, 3)
            .unwrap();
        assert!(residual < 1e-12, "linear residual {residual}");
        let scale = u_ref.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        for i in 0..model.num_dofs() {
            assert!(
                (x[i] - u_ref[i]).abs() < 1e-10 * scale,
                "u[{i}] {} vs {}",
                x[i],
                u_ref[i]
            );
        }
        let force = top
            .iter()
            .fold(0.0f64, |m, &s| m.max(r_ref[3 * s + 2].abs()));
        for (m, &s) in top.iter().enumerate() {
            let lambda = x[3 * n_nodes + m];
            assert!(
                (lambda + r_ref[3 * s + 2]).abs() < 1e-8 * force,
                "λ {lambda} vs reaction {}",
                r_ref[3 * s + 2]
            );
        }
    }
}

/// Each multiplier follows the last of its nodes in the dof ordering, and
/// the ordering is a permutation of all dofs.
#[test]
fn multipliers_are_ordered_after_their_nodes() {
    let mesh = box_mesh(ElementKind::Tet4, [2, 2, 2], [1.0, 1.0, 1.0]);
    let couplings = vec![vec![0, 5], vec![26], vec![3, 4, 13]];
    let pattern = SparsityPattern::with_multipliers(
        mesh.num_nodes(),
        mesh.elements.iter().map(|e| e.nodes.as_slice()),
        &couplings,
    );
    let node_order: Vec<usize> = (0..mesh.num_nodes()).rev().collect();
    let forward = pattern.dof_ordering(&node_order);
    let mut sorted = forward.clone();
    sorted.sort_unstable();
    assert!(sorted.iter().enumerate().all(|(i, &v)| i == v));
    let position = |dof: usize| forward.iter().position(|&d| d == dof).unwrap();
    let first = 3 * mesh.num_nodes();
    for (k, nodes) in couplings.iter().enumerate() {
        let p = position(first + k);
        let last_node = nodes.iter().map(|&a| position(3 * a + 2)).max().unwrap();
        // right after its last node, with only multipliers in between
        assert!(p > last_node, "multiplier {k} before its node");
        assert!(forward[last_node + 1..p].iter().all(|&dof| dof >= first));
    }
    assert_eq!(pattern.pivot_signs().iter().filter(|&&s| s < 0).count(), 3);
}
