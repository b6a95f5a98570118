/*
 * A thin C layer over the PETSc calls that `src/solve/petsc/mod.rs` uses.
 *
 * PETSc's public interface is C macros as much as functions
 * (PETSC_COMM_SELF, PetscCall, the PetscInt width chosen at configure
 * time), so the Rust side does not declare PETSc's own symbols: it calls
 * these few functions, compiled against the installed headers by build.rs
 * (feature `petsc` only). Every function returns 0 or a PETSc error code
 * and writes a message for the user into `err`.
 *
 * One solver holds a sequential AIJ matrix (block size 3 when asked), its
 * right-hand side and solution vectors and a KSP. The matrix is built from
 * CSR arrays the first time and refilled in place while the pattern stays
 * the same, so that PETSc's preconditioner (MUMPS, GAMG, hypre) keeps its
 * symbolic set-up.
 */
#include <petscksp.h>

_Static_assert(sizeof(PetscInt) == sizeof(int), "signorini passes 32-bit PETSc indices");
_Static_assert(sizeof(PetscScalar) == sizeof(double), "signorini needs real double PETSc");
#include <stdio.h>
#include <string.h>

static int initialised = 0;

#define CHECK(call)                                                         \
  do {                                                                      \
    PetscErrorCode ierr_ = (call);                                          \
    if (ierr_) {                                                            \
      const char *text_ = NULL;                                             \
      PetscErrorMessage(ierr_, &text_, NULL);                               \
      snprintf(err, err_len, "PETSc error %d in %s: %s", (int)ierr_, #call, \
               text_ ? text_ : "(no text)");                                \
      return (int)ierr_;                                                    \
    }                                                                       \
  } while (0)

static void finalise(void) {
  if (initialised) {
    PetscFinalize();
    initialised = 0;
  }
}

/* Initialise PETSc once per process (MPI too, as a singleton without
 * mpirun) and return the version text. */
int sg_petsc_initialise(char *version, size_t version_len, char *err,
                        size_t err_len) {
  if (!initialised) {
    CHECK(PetscInitializeNoArguments());
    initialised = 1;
    CHECK(PetscPushErrorHandler(PetscReturnErrorHandler, NULL));
    atexit(finalise);
  }
  CHECK(PetscGetVersion(version, version_len));
  return 0;
}

typedef struct {
  PetscOptions options;
  Mat matrix;
  Vec rhs, solution;
  KSP ksp;
  PetscInt n, nnz;
} Solver;

/* A solver whose KSP and PC read an options database of their own:
 * PETSC_OPTIONS from the environment, then `options` (so the case file
 * wins), so that two solvers in one process do not share options. */
int sg_petsc_solver_new(void **out, const char *options, char *err,
                        size_t err_len) {
  Solver *s = calloc(1, sizeof(Solver));
  if (!s) {
    snprintf(err, err_len, "out of memory for a PETSc solver");
    return 1;
  }
  *out = s;
  CHECK(PetscOptionsCreate(&s->options));
  const char *environment = getenv("PETSC_OPTIONS");
  if (environment && environment[0]) {
    CHECK(PetscOptionsInsertString(s->options, environment));
  }
  if (options && options[0]) {
    CHECK(PetscOptionsInsertString(s->options, options));
  }
  CHECK(KSPCreate(PETSC_COMM_SELF, &s->ksp));
  CHECK(PetscObjectSetOptions((PetscObject)s->ksp, s->options));
  /* the default: a direct solve by MUMPS (LU, so saddle-point systems of the
   * Lagrangian contact methods are fine); the options database overrides */
  PC pc;
  CHECK(KSPSetType(s->ksp, KSPPREONLY));
  CHECK(KSPGetPC(s->ksp, &pc));
  CHECK(PCSetType(pc, PCLU));
  CHECK(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  CHECK(KSPSetFromOptions(s->ksp));
  return 0;
}

void sg_petsc_solver_free(void *handle) {
  Solver *s = handle;
  if (!s) return;
  if (s->ksp) KSPDestroy(&s->ksp);
  if (s->matrix) MatDestroy(&s->matrix);
  if (s->rhs) VecDestroy(&s->rhs);
  if (s->solution) VecDestroy(&s->solution);
  if (s->options) PetscOptionsDestroy(&s->options);
  free(s);
}

/* Describe the KSP and PC (type names) into `text`. */
int sg_petsc_describe(void *handle, char *text, size_t text_len, char *err,
                      size_t err_len) {
  Solver *s = handle;
  KSPType ksp_type;
  PCType pc_type;
  PC pc;
  MatSolverType package = NULL;
  CHECK(KSPGetType(s->ksp, &ksp_type));
  CHECK(KSPGetPC(s->ksp, &pc));
  CHECK(PCGetType(pc, &pc_type));
  if (pc_type && (!strcmp(pc_type, PCLU) || !strcmp(pc_type, PCCHOLESKY))) {
    CHECK(PCFactorGetMatSolverType(pc, &package));
  }
  snprintf(text, text_len, "ksp %s, pc %s%s%s", ksp_type ? ksp_type : "?",
           pc_type ? pc_type : "?", package ? " " : "", package ? package : "");
  return 0;
}

/* One linear system, as `sg_petsc_solve` takes it (the same layout as
 * `SystemArguments` in mod.rs). */
typedef struct {
  int n;
  const int *row_start;
  const int *columns;
  const double *values;
  int same_pattern;
  int block_size;
  const double *coordinates;
  const double *b;
  double *x;
  int *iterations;
} SystemArguments;

/* Solve K x = b with K given by CSR arrays (`row_start` of length n + 1,
 * sorted `columns`, `values`). `same_pattern` says the arrays have the
 * pattern of the previous call. `block_size` 3 when the unknowns are
 * nodal displacements only (then `coordinates`, 3 per node, if not NULL,
 * give GAMG the rigid-body near-null space). Returns the Krylov
 * iterations in `iterations`. */
int sg_petsc_solve(void *handle, const SystemArguments *system, char *err,
                   size_t err_len) {
  Solver *s = handle;
  int n = system->n, same_pattern = system->same_pattern,
      block_size = system->block_size;
  const int *row_start = system->row_start, *columns = system->columns;
  const double *values = system->values, *coordinates = system->coordinates,
               *b = system->b;
  double *x = system->x;
  int *iterations = system->iterations;
  PetscInt nnz = row_start[n];
  if (!(same_pattern && s->matrix && s->n == n && s->nnz == nnz)) {
    if (s->matrix) MatDestroy(&s->matrix);
    if (s->rhs) VecDestroy(&s->rhs);
    if (s->solution) VecDestroy(&s->solution);
    CHECK(MatCreate(PETSC_COMM_SELF, &s->matrix));
    CHECK(PetscObjectSetOptions((PetscObject)s->matrix, s->options));
    CHECK(MatSetSizes(s->matrix, n, n, n, n));
    CHECK(MatSetType(s->matrix, MATSEQAIJ));
    if (block_size > 1) CHECK(MatSetBlockSize(s->matrix, block_size));
    CHECK(MatSeqAIJSetPreallocationCSR(s->matrix, row_start, columns, values));
    CHECK(MatCreateVecs(s->matrix, &s->solution, &s->rhs));
    s->n = n;
    s->nnz = nnz;
    if (coordinates && block_size == 3) {
      Vec coords;
      MatNullSpace rigid;
      CHECK(VecCreateSeq(PETSC_COMM_SELF, n, &coords));
      CHECK(VecSetBlockSize(coords, 3));
      PetscScalar *c;
      CHECK(VecGetArray(coords, &c));
      memcpy(c, coordinates, sizeof(double) * (size_t)n);
      CHECK(VecRestoreArray(coords, &c));
      CHECK(MatNullSpaceCreateRigidBody(coords, &rigid));
      CHECK(MatSetNearNullSpace(s->matrix, rigid));
      CHECK(MatNullSpaceDestroy(&rigid));
      CHECK(VecDestroy(&coords));
    }
  } else {
    for (PetscInt i = 0; i < n; i++) {
      PetscInt count = row_start[i + 1] - row_start[i];
      CHECK(MatSetValues(s->matrix, 1, &i, count, columns + row_start[i],
                         values + row_start[i], INSERT_VALUES));
    }
    CHECK(MatAssemblyBegin(s->matrix, MAT_FINAL_ASSEMBLY));
    CHECK(MatAssemblyEnd(s->matrix, MAT_FINAL_ASSEMBLY));
  }
  CHECK(KSPSetOperators(s->ksp, s->matrix, s->matrix));

  PetscScalar *a;
  CHECK(VecGetArray(s->rhs, &a));
  memcpy(a, b, sizeof(double) * (size_t)n);
  CHECK(VecRestoreArray(s->rhs, &a));
  CHECK(KSPSolve(s->ksp, s->rhs, s->solution));

  KSPConvergedReason reason;
  CHECK(KSPGetConvergedReason(s->ksp, &reason));
  PetscInt its;
  CHECK(KSPGetIterationNumber(s->ksp, &its));
  *iterations = (int)its;
  if (reason < 0) {
    snprintf(err, err_len, "PETSc's KSP did not converge: %s after %d iterations",
             KSPConvergedReasons[reason], (int)its);
    return 1;
  }
  const PetscScalar *y;
  CHECK(VecGetArrayRead(s->solution, &y));
  memcpy(x, y, sizeof(double) * (size_t)n);
  CHECK(VecRestoreArrayRead(s->solution, &y));
  return 0;
}
