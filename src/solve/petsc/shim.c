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
 * right-hand side and solution vectors and a KSP. The matrix is
 * preallocated for the pattern the first time and refilled in place,
 * column by column from the caller's compressed columns, while the pattern
 * stays the same, so that PETSc's preconditioner (MUMPS, GAMG, hypre)
 * keeps its symbolic set-up.
 */
#include <petscksp.h>

_Static_assert(sizeof(PetscInt) == sizeof(int), "signorini passes 32-bit PETSc indices");
_Static_assert(sizeof(PetscScalar) == sizeof(double), "signorini needs real double PETSc");
#include <stdio.h>
#include <stdint.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

static int initialised = 0;

/* "PETSc error <code> in <what>: <the code's text>" into `err`, and the
 * message PETSc's own check gave (PetscErrorMessage's specific one: an
 * unknown option value, a wrong size) when it gave one. */
static void describe_error(PetscErrorCode code, const char *what, char *err,
                           size_t err_len) {
  const char *text = NULL;
  char *specific = NULL;
  PetscErrorMessage(code, &text, &specific);
  if (specific && specific[0]) {
    snprintf(err, err_len, "PETSc error %d in %s: %s%s%s", (int)code, what,
             text ? text : "", text ? ": " : "", specific);
  } else {
    snprintf(err, err_len, "PETSc error %d in %s: %s", (int)code, what,
             text ? text : "(no text)");
  }
}

#define CHECK(call)                             \
  do {                                          \
    PetscErrorCode ierr_ = (call);              \
    if (ierr_) {                                \
      describe_error(ierr_, #call, err, err_len); \
      return (int)ierr_;                        \
    }                                           \
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

/* The options prefix of one solver: "sg<k>_". */
#define PREFIX_LEN 32

/* An option PETSc reads without a prefix (a matrix product's, which
 * GAMG and fieldsplit make with no prefix of their own): put into the
 * global database around each set-up and solve of its solver only
 * (push_globals), the value it had there before (`saved`, `was_set`)
 * restored after. `value` NULL: an option without a value. */
typedef struct {
  char *name, *value, *saved;
  PetscBool was_set;
} GlobalOption;

/* What both solvers hold first: the options prefix (make_ksp), the KSP,
 * the displacement unknowns fieldsplit's fields were given for (0: none
 * given) and the solver's global options. */
typedef struct {
  char prefix[PREFIX_LEN];
  KSP ksp;
  PetscInt split;
  GlobalOption *globals;
  int global_count;
} Common;

typedef struct {
  Common c;
  Mat matrix;
  Vec rhs, solution;
  PetscInt n, nnz;
} Solver;

/* Insert PETSC_OPTIONS from the environment, then `text` (so the case
 * file wins), into PETSc's global options database under `prefix`
 * ("-pc_type gamg" becomes "-<prefix>pc_type gamg"). */
static int insert_options(const char *prefix, const char *text, char *err,
                          size_t err_len) {
  CHECK(PetscOptionsPrefixPush(NULL, prefix));
  PetscErrorCode failed = 0;
  const char *environment = getenv("PETSC_OPTIONS");
  if (environment && environment[0]) {
    failed = PetscOptionsInsertString(NULL, environment);
  }
  if (!failed && text && text[0]) failed = PetscOptionsInsertString(NULL, text);
  CHECK(PetscOptionsPrefixPop(NULL));
  if (failed) {
    char what[256];
    snprintf(what, sizeof what, "the options \"%s\"", text ? text : "");
    describe_error(failed, what, err, err_len);
    return (int)failed;
  }
  return 0;
}

/* A KSP on `comm` with the options prefix `prefix`, set from PETSc's
 * global options database. The default is a direct solve by MUMPS (LU, so
 * saddle-point systems of the Lagrangian contact methods are fine); the
 * options database overrides. */
static int new_ksp(MPI_Comm comm, const char *prefix, KSP *ksp, char *err,
                   size_t err_len) {
  CHECK(KSPCreate(comm, ksp));
  CHECK(KSPSetOptionsPrefix(*ksp, prefix));
  PC pc;
  CHECK(KSPSetType(*ksp, KSPPREONLY));
  CHECK(KSPGetPC(*ksp, &pc));
  CHECK(PCSetType(pc, PCLU));
  CHECK(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  CHECK(KSPSetFromOptions(*ksp));
  return 0;
}

/* A KSP on `comm` whose options are its own: they go into PETSc's global
 * database under a prefix of this solver's, "sg<k>_" (k counts the
 * solvers made in this process, in the same order on every process of a
 * run), written into `prefix` (PREFIX_LEN), and the KSP reads them under
 * it. So two solvers in one process do not share options, and every
 * solver PETSc makes inside this one (fieldsplit's sub-solvers, the
 * multigrid levels' smoothers), whose prefixes extend their parent's,
 * reads the case's options too. The options stay in the database until
 * the process ends (a few strings per solver). */
static int make_ksp(MPI_Comm comm, const char *text, char *prefix, KSP *ksp,
                    char *err, size_t err_len) {
  static int solvers = 0;
  snprintf(prefix, PREFIX_LEN, "sg%d_", ++solvers);
  int failed = insert_options(prefix, text, err, err_len);
  if (failed) return failed;
  return new_ksp(comm, prefix, ksp, err, err_len);
}

/* A solver whose KSP and PC read options of their own (make_ksp) on one
 * process. */
int sg_petsc_solver_new(void **out, const char *options, char *err,
                        size_t err_len) {
  Solver *s = calloc(1, sizeof(Solver));
  if (!s) {
    snprintf(err, err_len, "out of memory for a PETSc solver");
    return 1;
  }
  *out = s;
  return make_ksp(PETSC_COMM_SELF, options, s->c.prefix, &s->c.ksp, err, err_len);
}

/* The KSP and the global options of a solver (`Common`). */
static void free_common(Common *c) {
  if (c->ksp) KSPDestroy(&c->ksp);
  for (int k = 0; k < c->global_count; k++) {
    free(c->globals[k].name);
    free(c->globals[k].value);
    free(c->globals[k].saved);
  }
  free(c->globals);
}

/* Add the option `name` (with its leading dash) and its `value` (NULL:
 * none) to the options the solver at `handle` (either kind: both begin
 * with `Common`) puts into PETSc's global database around each set-up
 * and solve (push_globals). */
int sg_petsc_global_option(void *handle, const char *name, const char *value,
                           char *err, size_t err_len) {
  Common *c = handle;
  GlobalOption *grown =
      realloc(c->globals, sizeof(GlobalOption) * (size_t)(c->global_count + 1));
  if (!grown) {
    snprintf(err, err_len, "out of memory for the PETSc option %s", name);
    return 1;
  }
  c->globals = grown;
  GlobalOption *o = &c->globals[c->global_count++];
  o->name = strdup(name);
  o->value = value ? strdup(value) : NULL;
  o->saved = NULL;
  o->was_set = PETSC_FALSE;
  if (!o->name || (value && !o->value)) {
    snprintf(err, err_len, "out of memory for the PETSc option %s", name);
    return 1;
  }
  return 0;
}

/* Put the solver's global options into PETSc's global database, each
 * one's earlier value saved; `*pushed` counts those put (pop_globals
 * restores them, also after a failure here). */
static int push_globals(Common *c, int *pushed, char *err, size_t err_len) {
  for (*pushed = 0; *pushed < c->global_count; (*pushed)++) {
    GlobalOption *o = &c->globals[*pushed];
    const char *before = NULL;
    CHECK(PetscOptionsFindPair(NULL, NULL, o->name, &before, &o->was_set));
    free(o->saved);
    o->saved = o->was_set && before ? strdup(before) : NULL;
    CHECK(PetscOptionsSetValue(NULL, o->name, o->value));
  }
  return 0;
}

/* Restore the `pushed` first global options' earlier values (or their
 * absence), last first. */
static void pop_globals(Common *c, int pushed) {
  for (int k = pushed; k > 0; k--) {
    GlobalOption *o = &c->globals[k - 1];
    if (o->was_set) {
      PetscOptionsSetValue(NULL, o->name, o->saved);
    } else {
      PetscOptionsClearValue(NULL, o->name);
    }
  }
}

void sg_petsc_solver_free(void *handle) {
  Solver *s = handle;
  if (!s) return;
  free_common(&s->c);
  if (s->matrix) MatDestroy(&s->matrix);
  if (s->rhs) VecDestroy(&s->rhs);
  if (s->solution) VecDestroy(&s->solution);
  free(s);
}

/* Describe a KSP and its PC (type names) into `text`. */
static int describe_ksp(KSP ksp, char *text, size_t text_len, char *err,
                        size_t err_len) {
  KSPType ksp_type;
  PCType pc_type;
  PC pc;
  MatSolverType package = NULL;
  CHECK(KSPGetType(ksp, &ksp_type));
  CHECK(KSPGetPC(ksp, &pc));
  CHECK(PCGetType(pc, &pc_type));
  if (pc_type && (!strcmp(pc_type, PCLU) || !strcmp(pc_type, PCCHOLESKY))) {
    CHECK(PCFactorGetMatSolverType(pc, &package));
  }
  snprintf(text, text_len, "ksp %s, pc %s%s%s", ksp_type ? ksp_type : "?",
           pc_type ? pc_type : "?", package ? " " : "", package ? package : "");
  return 0;
}

/* Describe the solver's KSP and PC into `text`. */
int sg_petsc_describe(void *handle, char *text, size_t text_len, char *err,
                      size_t err_len) {
  return describe_ksp(((Common *)handle)->ksp, text, text_len, err, err_len);
}

/* KSPSetUp and KSPSetUpOnBlocks: the preconditioner's set-up (PCSetUp),
 * its blocks' (block Jacobi, ASM) and, for fieldsplit, its sub-solvers'
 * (PCFieldSplitGetSubKSP: the displacement block's GAMG, the Schur
 * complement's preconditioner), which PETSc would otherwise set up at
 * their first use inside KSPSolve. */
static int set_up_ksp(KSP ksp, char *err, size_t err_len) {
  CHECK(KSPSetUp(ksp));
  CHECK(KSPSetUpOnBlocks(ksp));
  PC pc;
  PetscBool fieldsplit;
  CHECK(KSPGetPC(ksp, &pc));
  CHECK(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fieldsplit));
  if (!fieldsplit) return 0;
  PetscInt count;
  KSP *sub;
  CHECK(PCFieldSplitGetSubKSP(pc, &count, &sub));
  int failed = 0;
  for (PetscInt k = 0; k < count && !failed; k++) {
    failed = set_up_ksp(sub[k], err, err_len);
  }
  CHECK(PetscFree(sub));
  return failed;
}

/* The KSP's set-up (set_up_ksp), then KSPSolve, their wall times
 * (PetscTime) into seconds[0] and seconds[1]; the iterations into
 * `iterations`, and an error when it did not converge. */
static int solve_ksp(KSP ksp, Vec b, Vec x, int *iterations, double *seconds,
                     char *err, size_t err_len) {
  PetscLogDouble start, set_up, end;
  CHECK(PetscTime(&start));
  int failed = set_up_ksp(ksp, err, err_len);
  if (failed) return failed;
  CHECK(PetscTime(&set_up));
  seconds[0] = set_up - start;
  CHECK(KSPSolve(ksp, b, x));
  CHECK(PetscTime(&end));
  seconds[1] = end - set_up;
  KSPConvergedReason reason;
  CHECK(KSPGetConvergedReason(ksp, &reason));
  PetscInt its;
  CHECK(KSPGetIterationNumber(ksp, &its));
  *iterations = (int)its;
  if (reason < 0) {
    snprintf(err, err_len, "PETSc's KSP did not converge: %s after %d iterations",
             KSPConvergedReasons[reason], (int)its);
    return 1;
  }
  return 0;
}

/* solve_ksp on the solver's KSP with its global options in PETSc's
 * database (push_globals), restored whatever the outcome. */
static int solve_with_globals(Common *c, Vec b, Vec x, int *iterations,
                              double *seconds, char *err, size_t err_len) {
  int pushed = 0;
  int failed = push_globals(c, &pushed, err, err_len);
  if (!failed) failed = solve_ksp(c->ksp, b, x, iterations, seconds, err, err_len);
  pop_globals(c, pushed);
  return failed;
}

/* The rigid-body modes of the nodes at `coordinates` (3 per node,
 * `local` of `global` values on this process) into `rigid`. */
static int rigid_body_modes(MPI_Comm comm, PetscInt local, PetscInt global,
                            const double *coordinates, MatNullSpace *rigid,
                            char *err, size_t err_len) {
  Vec coords;
  CHECK(VecCreateMPI(comm, local, global, &coords));
  CHECK(VecSetBlockSize(coords, 3));
  PetscScalar *c;
  CHECK(VecGetArray(coords, &c));
  memcpy(c, coordinates, sizeof(double) * (size_t)local);
  CHECK(VecRestoreArray(coords, &c));
  CHECK(MatNullSpaceCreateRigidBody(coords, rigid));
  CHECK(VecDestroy(&coords));
  return 0;
}

/* Attach the rigid-body modes of the nodes at `coordinates` (3 per
 * node, `local` of `global` values on this process) to `matrix` as its
 * near-null space (GAMG's). */
static int attach_rigid_body_modes(Mat matrix, MPI_Comm comm, PetscInt local,
                                   PetscInt global, const double *coordinates,
                                   char *err, size_t err_len) {
  MatNullSpace rigid;
  int failed = rigid_body_modes(comm, local, global, coordinates, &rigid, err, err_len);
  if (failed) return failed;
  CHECK(MatSetNearNullSpace(matrix, rigid));
  CHECK(MatNullSpaceDestroy(&rigid));
  return 0;
}

/* The rows of a Lagrangian contact tangent one process owns, [first,
 * first + local) of `global`: the nodal displacements are the rows [0,
 * displacements), the contact multipliers the rest. */
typedef struct {
  PetscInt first, local, global, displacements;
} Rows;

/* Give a fieldsplit PC (`-pc_type fieldsplit`) the two fields of a
 * Lagrangian contact tangent on `comm`, the rows `rows` of it on this
 * process: its own displacement rows and its own multiplier rows, as
 * fields "0" and "1" (the names -pc_fieldsplit_detect_saddle_point
 * gives, so that the options -fieldsplit_0_... and -fieldsplit_1_...
 * address them). The displacements' index set has block size 3 and
 * carries the rigid-body modes of `coordinates` (3 per own node) as its
 * "nearnullspace", which fieldsplit attaches to the displacement block's
 * matrix: GAMG on that block is then elasticity's (6 modes per
 * aggregate), not a scalar AMG. Fields given for an earlier pattern are
 * dropped with the KSP (a fresh one from the same options, on every
 * process of `comm`). Nothing for another PC. */
static int split_fields(Common *c, MPI_Comm comm, Rows rows,
                        const double *coordinates, char *err, size_t err_len) {
  PC pc;
  PetscBool fieldsplit;
  CHECK(KSPGetPC(c->ksp, &pc));
  CHECK(PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &fieldsplit));
  if (!fieldsplit) return 0;
  if (c->split) {
    CHECK(KSPDestroy(&c->ksp));
    int failed = new_ksp(comm, c->prefix, &c->ksp, err, err_len);
    if (failed) return failed;
    CHECK(KSPGetPC(c->ksp, &pc));
  }
  PetscInt end = rows.first + rows.local;
  PetscInt u_end = PetscMin(end, rows.displacements);
  PetscInt u_local = PetscMax(u_end - rows.first, 0);
  PetscInt lambda_first = PetscMax(rows.first, rows.displacements);
  PetscInt lambda_local = PetscMax(end - lambda_first, 0);
  IS u, lambda;
  MatNullSpace rigid;
  CHECK(ISCreateStride(comm, u_local, rows.first, 1, &u));
  CHECK(ISSetBlockSize(u, 3));
  CHECK(ISCreateStride(comm, lambda_local, lambda_first, 1, &lambda));
  int failed = rigid_body_modes(comm, u_local, rows.displacements, coordinates,
                                &rigid, err, err_len);
  if (failed) return failed;
  CHECK(PetscObjectCompose((PetscObject)u, "nearnullspace", (PetscObject)rigid));
  CHECK(PCFieldSplitSetIS(pc, "0", u));
  CHECK(PCFieldSplitSetIS(pc, "1", lambda));
  CHECK(MatNullSpaceDestroy(&rigid));
  CHECK(ISDestroy(&u));
  CHECK(ISDestroy(&lambda));
  c->split = rows.displacements;
  return 0;
}

/* The tangent's compressed columns as the caller holds them (faer's CSC,
 * `Columns` in mod.rs): column j's rows are row_idx[col_ptr[j] ..
 * col_ptr[j + 1]) and its values the same positions of a values array.
 * PETSc's row of row i is row_map[i] (negative: an entry PETSc is to
 * ignore) and its column of column j column_map[j]; a NULL map is the
 * identity. The pattern is structurally symmetric. */
typedef struct {
  size_t columns;
  const size_t *col_ptr;
  const size_t *row_idx;
  const int *row_map;
  const int *column_map;
} Columns;

/* Put `values` (NULL: zeros) into `matrix` one column at a time, an m x 1
 * block per MatSetValues (the same in PETSc's row or column orientation),
 * with `mode`: PETSc finds each entry's place in its compressed rows, so
 * no map from the caller's positions to PETSc's is kept. Rows another
 * process owns go through PETSc's stash at the next assembly. `mirrored`:
 * the columns hold a symmetric matrix's lower triangle, and each entry
 * (i, j) off the diagonal goes in as (j, i) too, a 1 x m block of row j
 * (PETSc's row of j, its columns those of the rows i). */
static int put_columns(Mat matrix, const Columns *c, const double *values,
                       InsertMode mode, int mirrored, char *err,
                       size_t err_len) {
  size_t longest = 1;
  for (size_t j = 0; j < c->columns; j++) {
    size_t len = c->col_ptr[j + 1] - c->col_ptr[j];
    if (len > longest) longest = len;
  }
  PetscInt *rows, *columns;
  PetscScalar *zeros;
  CHECK(PetscMalloc1(longest, &rows));
  CHECK(PetscMalloc1(longest, &columns));
  CHECK(PetscCalloc1(longest, &zeros));
  for (size_t j = 0; j < c->columns; j++) {
    size_t first = c->col_ptr[j], len = c->col_ptr[j + 1] - first;
    for (size_t k = 0; k < len; k++) {
      size_t i = c->row_idx[first + k];
      rows[k] = c->row_map ? c->row_map[i] : (PetscInt)i;
      /* the diagonal goes in once, as the column's */
      columns[k] = i == j ? -1 : c->column_map ? c->column_map[i] : (PetscInt)i;
    }
    PetscInt column = c->column_map ? c->column_map[j] : (PetscInt)j;
    const PetscScalar *v = values ? values + first : zeros;
    CHECK(MatSetValues(matrix, (PetscInt)len, rows, 1, &column, v, mode));
    PetscInt row = c->row_map ? c->row_map[j] : (PetscInt)j;
    if (mirrored && row >= 0) {
      CHECK(MatSetValues(matrix, 1, &row, (PetscInt)len, columns, v, mode));
    }
  }
  CHECK(PetscFree(rows));
  CHECK(PetscFree(columns));
  CHECK(PetscFree(zeros));
  return 0;
}

/* put_columns, not mirrored. */
static int set_columns(Mat matrix, const Columns *c, const double *values,
                       InsertMode mode, char *err, size_t err_len) {
  return put_columns(matrix, c, values, mode, 0, err, err_len);
}

/* Preallocate `matrix` (its type, sizes and block size set) for exactly
 * the entries of `c`, its own and those other processes give in its rows:
 * PETSc's MATPREALLOCATOR counts each row's distinct (block) columns in a
 * hash set, freed before this returns, and MatXAIJSetPreallocation
 * reserves them. A later entry outside them is an error. */
static int preallocate(Mat matrix, const Columns *c, char *err, size_t err_len) {
  Mat counter;
  PetscInt local_rows, local_columns, rows, columns, block_size;
  CHECK(MatGetLocalSize(matrix, &local_rows, &local_columns));
  CHECK(MatGetSize(matrix, &rows, &columns));
  CHECK(MatGetBlockSize(matrix, &block_size));
  CHECK(MatCreate(PetscObjectComm((PetscObject)matrix), &counter));
  CHECK(MatSetType(counter, MATPREALLOCATOR));
  CHECK(MatSetSizes(counter, local_rows, local_columns, rows, columns));
  CHECK(MatSetBlockSize(counter, block_size));
  CHECK(MatSetUp(counter));
  int failed = set_columns(counter, c, NULL, INSERT_VALUES, err, err_len);
  if (failed) return failed;
  CHECK(MatAssemblyBegin(counter, MAT_FINAL_ASSEMBLY));
  CHECK(MatAssemblyEnd(counter, MAT_FINAL_ASSEMBLY));
  CHECK(MatPreallocatorPreallocate(counter, PETSC_FALSE, matrix));
  CHECK(MatDestroy(&counter));
  return 0;
}

/* One linear system, as `sg_petsc_solve` takes it (the same layout as
 * `SystemArguments` in mod.rs): the tangent's columns and their
 * `values`. */
typedef struct {
  int n;
  Columns columns;
  const double *values;
  int same_pattern;
  int block_size;
  const double *coordinates;
  int displacements;
  const double *b;
  double *x;
  int *iterations;
  double *seconds;
} SystemArguments;

/* Solve K x = b with K given by compressed columns. A new pattern
 * (`same_pattern` 0, or none yet) makes the matrix, preallocated for its
 * entries (`preallocate`); every call puts the values in (`set_columns`,
 * straight from the caller's array: PETSc holds the one compressed-row
 * copy of the tangent and no map to it). `block_size` 3 when the
 * unknowns are nodal displacements only (then `coordinates`, 3 per node,
 * if not NULL, give GAMG the rigid-body near-null space); with contact
 * multipliers after the displacements, `displacements` (> 0) of them
 * with `coordinates`, fieldsplit gets the two fields (split_fields).
 * Returns the Krylov iterations in `iterations`, and the seconds of the
 * preconditioner's set-up and of the solve in `seconds` (solve_ksp). */
int sg_petsc_solve(void *handle, const SystemArguments *system, char *err,
                   size_t err_len) {
  Solver *s = handle;
  int n = system->n, block_size = system->block_size;
  PetscInt nnz = (PetscInt)system->columns.col_ptr[system->columns.columns];
  if (!(system->same_pattern && s->matrix && s->n == n && s->nnz == nnz)) {
    if (s->matrix) MatDestroy(&s->matrix);
    if (s->rhs) VecDestroy(&s->rhs);
    if (s->solution) VecDestroy(&s->solution);
    CHECK(MatCreate(PETSC_COMM_SELF, &s->matrix));
    CHECK(MatSetOptionsPrefix(s->matrix, s->c.prefix));
    CHECK(MatSetSizes(s->matrix, n, n, n, n));
    CHECK(MatSetType(s->matrix, MATSEQAIJ));
    if (block_size > 1) CHECK(MatSetBlockSize(s->matrix, block_size));
    int failed = preallocate(s->matrix, &system->columns, err, err_len);
    if (failed) return failed;
    CHECK(MatCreateVecs(s->matrix, &s->solution, &s->rhs));
    s->n = n;
    s->nnz = nnz;
    if (system->coordinates && block_size == 3) {
      failed = attach_rigid_body_modes(s->matrix, PETSC_COMM_SELF, n, n,
                                       system->coordinates, err, err_len);
      if (failed) return failed;
    }
    int d = system->displacements;
    if (system->coordinates && d > 0 && d < n && d % 3 == 0) {
      Rows rows = {0, n, n, d};
      failed = split_fields(&s->c, PETSC_COMM_SELF, rows, system->coordinates, err,
                            err_len);
      if (failed) return failed;
    }
  }
  int failed = set_columns(s->matrix, &system->columns, system->values,
                           INSERT_VALUES, err, err_len);
  if (failed) return failed;
  CHECK(MatAssemblyBegin(s->matrix, MAT_FINAL_ASSEMBLY));
  CHECK(MatAssemblyEnd(s->matrix, MAT_FINAL_ASSEMBLY));
  CHECK(KSPSetOperators(s->c.ksp, s->matrix, s->matrix));

  PetscScalar *a;
  CHECK(VecGetArray(s->rhs, &a));
  memcpy(a, system->b, sizeof(double) * (size_t)n);
  CHECK(VecRestoreArray(s->rhs, &a));
  failed = solve_with_globals(&s->c, s->rhs, s->solution, system->iterations,
                              system->seconds, err, err_len);
  if (failed) return failed;
  const PetscScalar *y;
  CHECK(VecGetArrayRead(s->solution, &y));
  memcpy(system->x, y, sizeof(double) * (size_t)n);
  CHECK(VecRestoreArrayRead(s->solution, &y));
  return 0;
}

/* ---- distributed runs (mpirun -np N): src/solve/petsc/distributed.rs ---- */

/* This process's rank and the number of processes of PETSc's world
 * (PETSc initialised first). */
int sg_mpi_world(int *rank, int *size, char *err, size_t err_len) {
  CHECK(MPI_Comm_rank(PETSC_COMM_WORLD, rank));
  CHECK(MPI_Comm_size(PETSC_COMM_WORLD, size));
  return 0;
}

/* v <- the sum of every process's v, the same bits on every process: a
 * reduction to rank 0, then a broadcast (an MPI_Allreduce may round
 * differently on different processes). */
/* Give the pages of freed memory back to the system (glibc's
 * malloc_trim, which releases free pages anywhere in the heap, not only at
 * its top): after a distributed run's set-up the whole-mesh structures made
 * at reading the case (the other processes' element geometry, the whole
 * element graph) are freed in small pieces that would otherwise stay in
 * the process's resident memory. Nothing elsewhere. */
#ifdef __GLIBC__
#include <malloc.h>
#endif
void sg_release_freed_memory(void) {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

int sg_mpi_sum(double *v, size_t n, char *err, size_t err_len) {
  int rank;
  CHECK(MPI_Comm_rank(PETSC_COMM_WORLD, &rank));
  const size_t chunk = 1 << 26;
  for (size_t start = 0; start < n; start += chunk) {
    int count = (int)(n - start < chunk ? n - start : chunk);
    if (rank == 0) {
      CHECK(MPI_Reduce(MPI_IN_PLACE, v + start, count, MPI_DOUBLE, MPI_SUM, 0,
                       PETSC_COMM_WORLD));
    } else {
      CHECK(MPI_Reduce(v + start, NULL, count, MPI_DOUBLE, MPI_SUM, 0,
                       PETSC_COMM_WORLD));
    }
    CHECK(MPI_Bcast(v + start, count, MPI_DOUBLE, 0, PETSC_COMM_WORLD));
  }
  return 0;
}

typedef struct {
  Common c;
  Mat matrix;
  Vec rhs, solution, everywhere;
  VecScatter to_all;
  /* a fill of the matrix begun and not finished (sg_petsc_mpi_begin) */
  int filling;
} DistributedSolver;

/* A KSP on PETSc's world (make_ksp). */
int sg_petsc_mpi_solver_new(void **out, const char *options, char *err,
                            size_t err_len) {
  DistributedSolver *s = calloc(1, sizeof(DistributedSolver));
  if (!s) {
    snprintf(err, err_len, "out of memory for a PETSc solver");
    return 1;
  }
  *out = s;
  return make_ksp(PETSC_COMM_WORLD, options, s->c.prefix, &s->c.ksp, err, err_len);
}

static void distributed_free_system(DistributedSolver *s) {
  if (s->matrix) MatDestroy(&s->matrix);
  if (s->rhs) VecDestroy(&s->rhs);
  if (s->solution) VecDestroy(&s->solution);
  if (s->everywhere) VecDestroy(&s->everywhere);
  if (s->to_all) VecScatterDestroy(&s->to_all);
}

void sg_petsc_mpi_solver_free(void *handle) {
  DistributedSolver *s = handle;
  if (!s) return;
  distributed_free_system(s);
  free_common(&s->c);
  free(s);
}

/* The distributed matrix's layout (`DistributedLayout` in
 * distributed.rs): this process owns the global rows [first, first +
 * local) of `global`; `columns` are its part of the tangent's columns,
 * their rows mapped to PETSc's (negative: a row this process leaves to
 * the others), every entry of its own rows and of the other processes'
 * rows its part of K touches (PETSc sends those to their owners at each
 * assembly); `coordinates` (3 per owned node, or NULL) the rigid-body
 * near-null space: the matrix's when block_size is 3, else, with
 * contact multipliers after the `displacements` nodal displacements
 * (the last process owns them), the displacement field's of fieldsplit
 * (split_fields: each process's own displacement rows and own multiplier
 * rows). */
typedef struct {
  int global;
  int first;
  int local;
  int block_size;
  Columns columns;
  const double *coordinates;
  int displacements;
} DistributedLayout;

/* Make the matrix (MPIAIJ, preallocated for the entries every process
 * gives: `preallocate`), its vectors, the scatter of the solution to
 * every process, and the near-null space or fieldsplit's fields. */
int sg_petsc_mpi_layout(void *handle, const DistributedLayout *layout,
                        char *err, size_t err_len) {
  DistributedSolver *s = handle;
  distributed_free_system(s);
  CHECK(MatCreate(PETSC_COMM_WORLD, &s->matrix));
  CHECK(MatSetOptionsPrefix(s->matrix, s->c.prefix));
  CHECK(MatSetSizes(s->matrix, layout->local, layout->local, layout->global,
                    layout->global));
  CHECK(MatSetType(s->matrix, MATMPIAIJ));
  if (layout->block_size > 1) CHECK(MatSetBlockSize(s->matrix, layout->block_size));
  int failed = preallocate(s->matrix, &layout->columns, err, err_len);
  if (failed) return failed;
  /* the prescribed rows and columns zeroed (sg_petsc_mpi_identity_rows)
   * keep their entries: the next fill adds to them, and the
   * preconditioner sees the same nonzero pattern */
  CHECK(MatSetOption(s->matrix, MAT_KEEP_NONZERO_PATTERN, PETSC_TRUE));
  s->filling = 0;
  CHECK(MatCreateVecs(s->matrix, &s->solution, &s->rhs));
  CHECK(VecScatterCreateToAll(s->solution, &s->to_all, &s->everywhere));
  if (layout->coordinates && layout->block_size == 3) {
    CHECK(attach_rigid_body_modes(s->matrix, PETSC_COMM_WORLD, layout->local,
                                  layout->global, layout->coordinates, err,
                                  err_len));
  }
  int d = layout->displacements;
  if (layout->coordinates && layout->block_size == 1 && d > 0 &&
      d < layout->global && d % 3 == 0) {
    Rows rows = {layout->first, layout->local, layout->global, d};
    failed = split_fields(&s->c, PETSC_COMM_WORLD, rows, layout->coordinates,
                          err, err_len);
    if (failed) return failed;
  }
  return 0;
}

/* The matrix's fill (collective, every process): a new one begins with
 * every entry zero; one left unfinished (an evaluation that failed on
 * every process after adding some entries) is assembled first, so that
 * the entries it left in PETSc's stash for other processes' rows are not
 * added to the next. */
int sg_petsc_mpi_begin(void *handle, char *err, size_t err_len) {
  DistributedSolver *s = handle;
  if (s->filling) {
    CHECK(MatAssemblyBegin(s->matrix, MAT_FINAL_ASSEMBLY));
    CHECK(MatAssemblyEnd(s->matrix, MAT_FINAL_ASSEMBLY));
  }
  PetscBool assembled;
  CHECK(MatAssembled(s->matrix, &assembled));
  if (assembled) CHECK(MatZeroEntries(s->matrix));
  s->filling = 1;
  return 0;
}

/* Add a dense `n` x `n` block (row-major) at PETSc's `rows` and
 * `columns` (a negative row: left out). */
int sg_petsc_mpi_add_block(void *handle, int n, const int *rows,
                           const int *columns, const double *values,
                           char *err, size_t err_len) {
  DistributedSolver *s = handle;
  CHECK(MatSetValues(s->matrix, n, rows, n, columns, values, ADD_VALUES));
  return 0;
}

/* Add `values` on `columns` (their rows and columns mapped to PETSc's,
 * negative: left out); `mirrored`: a symmetric matrix's lower triangle
 * (put_columns). */
int sg_petsc_mpi_add_columns(void *handle, const Columns *columns,
                             const double *values, int mirrored, char *err,
                             size_t err_len) {
  DistributedSolver *s = handle;
  return put_columns(s->matrix, columns, values, ADD_VALUES, mirrored, err,
                     err_len);
}

/* End the fill (collective): PETSc adds the processes' parts, sending
 * the entries of other processes' rows to their owners. */
int sg_petsc_mpi_finish(void *handle, char *err, size_t err_len) {
  DistributedSolver *s = handle;
  CHECK(MatAssemblyBegin(s->matrix, MAT_FINAL_ASSEMBLY));
  CHECK(MatAssemblyEnd(s->matrix, MAT_FINAL_ASSEMBLY));
  s->filling = 0;
  return 0;
}

/* The whole of the distributed vector `v` into `whole` (PETSc's global
 * numbering), on every process. */
static int gather_whole(DistributedSolver *s, Vec v, double *whole, char *err,
                        size_t err_len) {
  CHECK(VecScatterBegin(s->to_all, v, s->everywhere, INSERT_VALUES,
                        SCATTER_FORWARD));
  CHECK(VecScatterEnd(s->to_all, v, s->everywhere, INSERT_VALUES,
                      SCATTER_FORWARD));
  PetscInt global;
  CHECK(VecGetSize(s->everywhere, &global));
  const PetscScalar *y;
  CHECK(VecGetArrayRead(s->everywhere, &y));
  memcpy(whole, y, sizeof(double) * (size_t)global);
  CHECK(VecRestoreArrayRead(s->everywhere, &y));
  return 0;
}

/* `x` (this process's rows) into the vector `v`. */
static int set_own(Vec v, const double *x, char *err, size_t err_len) {
  PetscInt local;
  CHECK(VecGetLocalSize(v, &local));
  PetscScalar *a;
  CHECK(VecGetArray(v, &a));
  memcpy(a, x, sizeof(double) * (size_t)local);
  CHECK(VecRestoreArray(v, &a));
  return 0;
}

/* y = K x (collective) with the filled matrix: `x` this process's rows,
 * `y` the whole product (global numbering) on every process. */
int sg_petsc_mpi_multiply(void *handle, const double *x, double *y, char *err,
                          size_t err_len) {
  DistributedSolver *s = handle;
  int failed = set_own(s->rhs, x, err, err_len);
  if (failed) return failed;
  CHECK(MatMult(s->matrix, s->rhs, s->solution));
  return gather_whole(s, s->solution, y, err, err_len);
}

/* Make the rows and columns `rows` (PETSc's, `n` of them, this process's
 * own) of the filled matrix a scaled identity (collective): `*scale` the
 * mean |K_dd| over the rows whose `free_rows` flag (one per own row) is
 * set, summed over the processes (a reduction to process 0 and a
 * broadcast: the same bits on every process), 1 if there is none. */
int sg_petsc_mpi_identity_rows(void *handle, int n, const int *rows,
                               const char *free_rows, double *scale,
                               char *err, size_t err_len) {
  DistributedSolver *s = handle;
  CHECK(MatGetDiagonal(s->matrix, s->solution));
  PetscInt local;
  CHECK(VecGetLocalSize(s->solution, &local));
  const PetscScalar *d;
  CHECK(VecGetArrayRead(s->solution, &d));
  double sums[2] = {0.0, 0.0};
  for (PetscInt k = 0; k < local; k++) {
    if (free_rows[k]) {
      sums[0] += PetscAbsScalar(d[k]);
      sums[1] += 1.0;
    }
  }
  CHECK(VecRestoreArrayRead(s->solution, &d));
  int failed = sg_mpi_sum(sums, 2, err, err_len);
  if (failed) return failed;
  *scale = sums[1] > 0.0 && sums[0] > 0.0 ? sums[0] / sums[1] : 1.0;
  CHECK(MatZeroRowsColumns(s->matrix, n, rows, *scale, NULL, NULL));
  return 0;
}

/* Solve K x = b with the filled matrix (sg_petsc_mpi_begin, the
 * additions, sg_petsc_mpi_finish, sg_petsc_mpi_identity_rows): `b` the
 * right-hand side of this process's rows, `x` the whole solution (global
 * numbering) on every process on return; the Krylov iterations into
 * `iterations` and the seconds of the set-up and the solve into
 * `seconds` (solve_ksp). */
int sg_petsc_mpi_solve(void *handle, const double *b, double *x,
                       int *iterations, double *seconds, char *err,
                       size_t err_len) {
  DistributedSolver *s = handle;
  if (s->filling) {
    snprintf(err, err_len, "the distributed matrix was not filled before the solve");
    return 1;
  }
  CHECK(KSPSetOperators(s->c.ksp, s->matrix, s->matrix));
  int failed = set_own(s->rhs, b, err, err_len);
  if (failed) return failed;
  failed = solve_with_globals(&s->c, s->rhs, s->solution, iterations, seconds,
                              err, err_len);
  if (failed) return failed;
  return gather_whole(s, s->solution, x, err, err_len);
}

/* ---- the parallel partition: src/solve/petsc/partitioning.rs ---- */

/* The partitioner PETSc was built with, ParMETIS first, then PT-Scotch;
 * NULL when it has neither. */
static MatPartitioningType parallel_partitioner(void) {
#if defined(PETSC_HAVE_PARMETIS)
  return MATPARTITIONINGPARMETIS;
#elif defined(PETSC_HAVE_PTSCOTCH)
  return MATPARTITIONINGPTSCOTCH;
#else
  return NULL;
#endif
}

/* The name of PETSc's parallel partitioner into `name` (empty when it
 * has none). */
void sg_petsc_partitioner(char *name, size_t name_len) {
  MatPartitioningType type = parallel_partitioner();
  snprintf(name, name_len, "%s", type ? type : "");
}

/* Cut a graph distributed by rows into `parts` parts with PETSc's
 * MatPartitioning (ParMETIS or PT-Scotch, `sg_petsc_partitioner`): this
 * process gives the rows [first, first + local) of `global` (`offsets`,
 * local + 1 of them, and the sorted `neighbours` of each row, global, no
 * diagonal); `part` (global entries) receives every row's part, gathered
 * on every process. */
int sg_petsc_mpi_partition(int local, int global, const int *offsets,
                           const int *neighbours, int parts, int *part,
                           char *err, size_t err_len) {
  MatPartitioningType type = parallel_partitioner();
  if (!type) {
    snprintf(err, err_len, "PETSc was built without ParMETIS and PT-Scotch");
    return 1;
  }
  PetscInt *ia, *ja;
  CHECK(PetscMalloc1(local + 1, &ia));
  CHECK(PetscMalloc1(offsets[local] > 0 ? offsets[local] : 1, &ja));
  for (int r = 0; r <= local; r++) ia[r] = offsets[r];
  for (int k = 0; k < offsets[local]; k++) ja[k] = neighbours[k];
  Mat adjacency;
  /* PETSc owns ia and ja from here (freed with the matrix) */
  CHECK(MatCreateMPIAdj(PETSC_COMM_WORLD, local, global, ia, ja, NULL, &adjacency));
  MatPartitioning partitioning;
  CHECK(MatPartitioningCreate(PETSC_COMM_WORLD, &partitioning));
  CHECK(MatPartitioningSetAdjacency(partitioning, adjacency));
  CHECK(MatPartitioningSetNParts(partitioning, parts));
  CHECK(MatPartitioningSetType(partitioning, type));
  IS is;
  CHECK(MatPartitioningApply(partitioning, &is));
  const PetscInt *mine;
  CHECK(ISGetIndices(is, &mine));
  int size;
  CHECK(MPI_Comm_size(PETSC_COMM_WORLD, &size));
  int *counts = malloc(sizeof(int) * (size_t)size * 2);
  int *own = malloc(sizeof(int) * (size_t)(local > 0 ? local : 1));
  if (!counts || !own) {
    free(counts);
    free(own);
    snprintf(err, err_len, "out of memory for the partition");
    return 1;
  }
  for (int r = 0; r < local; r++) own[r] = (int)mine[r];
  CHECK(ISRestoreIndices(is, &mine));
  int *displacements = counts + size;
  CHECK(MPI_Allgather(&local, 1, MPI_INT, counts, 1, MPI_INT, PETSC_COMM_WORLD));
  displacements[0] = 0;
  for (int p = 1; p < size; p++) displacements[p] = displacements[p - 1] + counts[p - 1];
  CHECK(MPI_Allgatherv(own, local, MPI_INT, part, counts, displacements, MPI_INT,
                       PETSC_COMM_WORLD));
  free(counts);
  free(own);
  CHECK(ISDestroy(&is));
  CHECK(MatPartitioningDestroy(&partitioning));
  CHECK(MatDestroy(&adjacency));
  return 0;
}

/* ---- faults of a distributed run: src/solve/petsc/distributed.rs ---- */

/* A communicator of its own for the agreement on outcomes, so that a
 * process waiting there never matches the collectives of a process still
 * inside a solve or a sum on PETSC_COMM_WORLD. */
static MPI_Comm fault_comm = MPI_COMM_NULL;

int sg_mpi_fault_init(char *err, size_t err_len) {
  if (fault_comm == MPI_COMM_NULL) {
    CHECK(MPI_Comm_dup(PETSC_COMM_WORLD, &fault_comm));
  }
  return 0;
}

/* Every process's record of `record` bytes (a flag byte, 0 when it
 * succeeded, else its failure's `severity` (fault.rs: 1 a cut may mend
 * it, 2 it ends the run), then its message) gathered into `records` (size × record)
 * with a non-blocking gather on the fault communicator, polled. A process
 * gives up after `timeout` seconds (none when `timeout` <= 0): `*done` 0
 * then, and the gather stays pending (the caller ends the run). */
int sg_mpi_agree(int severity, const char *message, char *records,
                 size_t record, double timeout, int *done, char *err,
                 size_t err_len) {
  /* kept alive while the gather may still read it (one per call site's
   * lifetime; a pending gather only precedes MPI_Abort) */
  char *mine = calloc(record, 1);
  if (!mine) {
    snprintf(err, err_len, "out of memory for the agreement of the processes");
    return 1;
  }
  if (message) {
    mine[0] = (char)(severity > 0 ? severity : 1);
    strncpy(mine + 1, message, record - 2);
  }
  MPI_Request request;
  CHECK(MPI_Iallgather(mine, (int)record, MPI_CHAR, records, (int)record,
                       MPI_CHAR, fault_comm, &request));
  double start = MPI_Wtime();
  int flag = 0;
  for (long polls = 0;; polls++) {
    CHECK(MPI_Test(&request, &flag, MPI_STATUS_IGNORE));
    if (flag) break;
    if (timeout > 0 && MPI_Wtime() - start > timeout) break;
    if (polls > 1000) {
      struct timespec pause = {0, 1000000};
      nanosleep(&pause, NULL);
    }
  }
  *done = flag;
  if (flag) free(mine);
  return 0;
}

/* End every process of the run (mpirun kills the others). */
void sg_mpi_abort(int code) { MPI_Abort(PETSC_COMM_WORLD, code); }

/* End this process now, without PETSc's and MPI's finalisation (which
 * would wait for processes that are gone). */
void sg_exit_now(int code) { _exit(code); }
