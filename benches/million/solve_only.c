/*
 * The million benchmark's linear solve alone, on any number of MPI ranks
 * (BENCHMARKS.md, "Two ranks: the PETSc solve alone"): load the tangent K
 * (PETSc binary, block size 3; -index k takes the k-th of the matrices a
 * run appended to the file), its right-hand side b and the node
 * coordinates (3 per node, in the mesh's node order), attach the rigid-body
 * near-null space, set the KSP/PC from the options database, time the
 * set-up and -repeat solves, and print per rank the memory PETSc holds
 * after loading, after the set-up and after the solves.
 *
 *   KEEP=1 PETSC_EXTRA="-ksp_view_mat binary:K.bin -ksp_view_rhs binary:b.bin" \
 *       sh benches/million/run.sh 45
 *   gmsh -3 benches/million/block.geo -setnumber n 45 -format msh41 -o n45.msh
 *   python3 benches/million/coords.py n45.msh c.bin
 *   mpicc -O2 benches/million/solve_only.c -o solve_only $(pkg-config --cflags --libs PETSc)
 *   mpirun -np 2 ./solve_only -K K.bin -b b.bin -coords c.bin -index 0 -repeat 2 -malloc \
 *       -ksp_type gmres -ksp_gmres_restart 100 -ksp_rtol 1e-4 -pc_type gamg
 *
 * K.bin grows by one matrix per Newton correction (435 MB each at n = 45):
 * stop the run after the first few.
 */
#include <petscksp.h>
int main(int argc, char **argv) {
  char kf[PETSC_MAX_PATH_LEN], bf[PETSC_MAX_PATH_LEN], cf[PETSC_MAX_PATH_LEN];
  PetscInt repeat = 1;
  PetscCall(PetscInitialize(&argc, &argv, NULL, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-K", kf, sizeof kf, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-b", bf, sizeof bf, NULL));
  PetscCall(PetscOptionsGetString(NULL, NULL, "-coords", cf, sizeof cf, NULL));
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-repeat", &repeat, NULL));
  PetscInt index = 0; /* which of the systems appended to the files */
  PetscCall(PetscOptionsGetInt(NULL, NULL, "-index", &index, NULL));
  Mat A; Vec b, x, c; PetscViewer v; KSP ksp; MatNullSpace ns;
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, kf, FILE_MODE_READ, &v));
  for (PetscInt k = 0; k <= index; k++) {
    if (k) PetscCall(MatDestroy(&A));
    PetscCall(MatCreate(PETSC_COMM_WORLD, &A));
    PetscCall(MatSetBlockSize(A, 3));
    PetscCall(MatSetFromOptions(A));
    PetscCall(MatLoad(A, v));
  }
  PetscCall(PetscViewerDestroy(&v));
  PetscLogDouble m0, m1, m2, r0, r1, r2;
  PetscCall(PetscMallocGetCurrentUsage(&m0)); PetscCall(PetscMemoryGetCurrentUsage(&r0));
  PetscCall(MatCreateVecs(A, &x, &b));
  PetscCall(VecDuplicate(x, &c));
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, bf, FILE_MODE_READ, &v));
  for (PetscInt k = 0; k <= index; k++) PetscCall(VecLoad(b, v));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(PetscViewerBinaryOpen(PETSC_COMM_WORLD, cf, FILE_MODE_READ, &v));
  PetscCall(VecLoad(c, v));
  PetscCall(PetscViewerDestroy(&v));
  PetscCall(VecSetBlockSize(c, 3));
  PetscCall(MatNullSpaceCreateRigidBody(c, &ns));
  PetscCall(MatSetNearNullSpace(A, ns));
  PetscCall(KSPCreate(PETSC_COMM_WORLD, &ksp));
  PetscCall(KSPSetOperators(ksp, A, A));
  PetscCall(KSPSetFromOptions(ksp));
  PetscLogDouble t0, t1, t2;
  PetscCall(PetscTime(&t0));
  PetscCall(KSPSetUp(ksp));
  { PC pc; PetscCall(KSPGetPC(ksp, &pc)); PetscCall(PCSetUp(pc)); }
  PetscCall(PetscTime(&t1));
  PetscCall(PetscMallocGetCurrentUsage(&m1)); PetscCall(PetscMemoryGetCurrentUsage(&r1));
  PetscInt its, total = 0;
  for (PetscInt r = 0; r < repeat; r++) {
    PetscCall(KSPSolve(ksp, b, x));
    PetscCall(KSPGetIterationNumber(ksp, &its));
    total += its;
  }
  PetscCall(PetscTime(&t2));
  PetscCall(PetscMallocGetCurrentUsage(&m2)); PetscCall(PetscMemoryGetCurrentUsage(&r2));
  PetscCall(PetscSynchronizedPrintf(PETSC_COMM_WORLD, "  malloced MB: matrix %.0f, + GAMG %.0f, + GMRES %.0f; resident MB %.0f %.0f %.0f\n", m0 / 1e6, m1 / 1e6, m2 / 1e6, r0 / 1e6, r1 / 1e6, r2 / 1e6));
  PetscCall(PetscSynchronizedFlush(PETSC_COMM_WORLD, PETSC_STDOUT));
  PetscMPIInt size; MPI_Comm_size(PETSC_COMM_WORLD, &size);
  PetscInt n; PetscCall(MatGetSize(A, &n, NULL));
  PetscCall(PetscPrintf(PETSC_COMM_WORLD, "ranks %d rows %d setup %.2f s solve %.2f s (%d solves, %d iterations)\n",
                        size, (int)n, t1 - t0, (t2 - t1) / repeat, (int)repeat, (int)total));
  PetscCall(KSPDestroy(&ksp)); PetscCall(MatDestroy(&A)); PetscCall(VecDestroy(&b));
  PetscCall(VecDestroy(&x)); PetscCall(VecDestroy(&c)); PetscCall(MatNullSpaceDestroy(&ns));
  PetscCall(PetscFinalize());
  return 0;
}
