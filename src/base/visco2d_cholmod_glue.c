/* The thin C layer between module visco2d_cholmod (Fortran, bind(c)) and
 * CHOLMOD (SuiteSparse): one opaque handle holding CHOLMOD's workspace, the
 * lower triangle of the matrix (compressed columns), its factor and the
 * solve's work arrays, so that a factorization with an unchanged pattern
 * reuses the ordering (cholmod_analyze once) and the solves allocate
 * nothing (cholmod_solve2). Every function returns 0 on success. */
#include <stdlib.h>
#include <string.h>
#include <suitesparse/cholmod.h>

typedef struct {
    cholmod_common common;
    cholmod_sparse *matrix; /* lower triangle, stype -1 */
    cholmod_factor *factor;
    cholmod_dense *x, *y, *e; /* cholmod_solve2's solution and work arrays */
} visco2d_cholmod_t;

void *visco2d_cholmod_create(void) {
    visco2d_cholmod_t *h = calloc(1, sizeof(visco2d_cholmod_t));
    if (h == NULL) return NULL;
    cholmod_start(&h->common);
    h->common.print = 0;
    h->common.error_handler = NULL;
    h->common.supernodal = CHOLMOD_SUPERNODAL;
    h->common.final_ll = 1; /* an L L^T factor, as the band and profile solvers */
    return h;
}

void visco2d_cholmod_destroy(void *handle) {
    visco2d_cholmod_t *h = handle;
    if (h == NULL) return;
    cholmod_free_dense(&h->x, &h->common);
    cholmod_free_dense(&h->y, &h->common);
    cholmod_free_dense(&h->e, &h->common);
    cholmod_free_factor(&h->factor, &h->common);
    cholmod_free_sparse(&h->matrix, &h->common);
    cholmod_finish(&h->common);
    free(h);
}

/* The pattern: n columns, column j's rows (0-based, j first, increasing)
 * in rows[start[j] .. start[j+1]-1]. Orders and analyzes it (CHOLMOD's
 * default: AMD, and METIS when AMD's fill is large). */
int visco2d_cholmod_analyze(void *handle, int n, const int *start, const int *rows) {
    visco2d_cholmod_t *h = handle;
    int nonzeros = start[n];
    cholmod_free_factor(&h->factor, &h->common);
    cholmod_free_sparse(&h->matrix, &h->common);
    h->matrix = cholmod_allocate_sparse(n, n, nonzeros, 1, 1, -1, CHOLMOD_REAL, &h->common);
    if (h->matrix == NULL) return 1;
    memcpy(h->matrix->p, start, (size_t)(n + 1) * sizeof(int));
    memcpy(h->matrix->i, rows, (size_t)nonzeros * sizeof(int));
    memset(h->matrix->x, 0, (size_t)nonzeros * sizeof(double));
    h->factor = cholmod_analyze(h->matrix, &h->common);
    return h->factor == NULL ? 2 : 0;
}

/* The smallest pivot ratio L(j,j)^2 / A(j,j) over the columns of the
 * supernodal factor (the band solver's test, in CHOLMOD's order). */
static double smallest_pivot_ratio(visco2d_cholmod_t *h) {
    cholmod_factor *L = h->factor;
    const int *super = L->super, *pi = L->pi, *px = L->px, *perm = L->Perm;
    const int *start = h->matrix->p;
    const double *x = L->x, *a = h->matrix->x;
    double smallest = 1.0;
    for (size_t s = 0; s < L->nsuper; s++) {
        int nsrow = pi[s + 1] - pi[s];
        for (int j = super[s]; j < super[s + 1]; j++) {
            double l = x[px[s] + (size_t)(j - super[s]) * nsrow + (j - super[s])];
            double diagonal = a[start[perm[j]]]; /* the diagonal is each column's first entry */
            double ratio = l * l / diagonal;
            if (ratio < smallest) smallest = ratio;
        }
    }
    return smallest;
}

/* Factor the analyzed pattern with these values (in the pattern's order).
 * 0: factored; -1: not positive definite, or a pivot L(j,j)^2 below
 * `pivot_floor` times its diagonal A(j,j); > 0: CHOLMOD failed otherwise. */
int visco2d_cholmod_factor(void *handle, const double *values, double pivot_floor) {
    visco2d_cholmod_t *h = handle;
    if (h->factor == NULL) return 3;
    memcpy(h->matrix->x, values, (size_t)h->matrix->nzmax * sizeof(double));
    if (!cholmod_factorize(h->matrix, h->factor, &h->common)) return 4;
    if (h->common.status == CHOLMOD_NOT_POSDEF) return -1;
    if (h->common.status != CHOLMOD_OK) return 5;
    if (!h->factor->is_super || !h->factor->is_ll) return 7;
    if (smallest_pivot_ratio(h) < pivot_floor) return -1;
    return 0;
}

/* Solve A X = B in place, B of n rows and nrhs columns (leading dimension n). */
int visco2d_cholmod_solve(void *handle, int nrhs, double *b) {
    visco2d_cholmod_t *h = handle;
    cholmod_dense rhs;
    size_t n;
    if (h->factor == NULL) return 3;
    n = h->factor->n;
    memset(&rhs, 0, sizeof(rhs));
    rhs.nrow = n;
    rhs.ncol = (size_t)nrhs;
    rhs.nzmax = n * (size_t)nrhs;
    rhs.d = n;
    rhs.x = b;
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;
    if (!cholmod_solve2(CHOLMOD_A, h->factor, &rhs, NULL, &h->x, NULL, &h->y, &h->e, &h->common)) return 6;
    memcpy(b, h->x->x, n * (size_t)nrhs * sizeof(double));
    return 0;
}

/* The number of reals in the factor L. */
double visco2d_cholmod_entries(void *handle) {
    visco2d_cholmod_t *h = handle;
    if (h->factor == NULL) return 0.0;
    return h->common.lnz;
}
