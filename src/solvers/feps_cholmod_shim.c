/* Thin handle-based shim over CHOLMOD (64-bit cholmod_l_* API) for feps.
 *
 * The C side owns cholmod_common, the kept matrix and the factor; Fortran only holds an
 * opaque pointer (see feps_cholmod_bindings.f90).  Fortran passes the lower triangle in
 * 1-based compressed rows; read as compressed columns this is the upper triangle, which
 * CHOLMOD takes as a symmetric matrix with stype = +1.
 *
 * Return codes of analyze/factorize/solve: see FEPS_CHOL_* below (0 = success).
 * Column numbers handed back to Fortran are original (unpermuted) and 1-based.
 */
#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <suitesparse/cholmod.h>

/* The shim passes int64_t arrays straight to CHOLMOD's SuiteSparse_long arrays. */
_Static_assert(sizeof(SuiteSparse_long) == sizeof(int64_t), "SuiteSparse_long must be 64-bit");

enum {
    FEPS_CHOL_OK = 0,
    FEPS_CHOL_BAD_INPUT = 1,    /* pattern not a valid lower-triangle CSR, or sizes disagree */
    FEPS_CHOL_NOT_POSDEF = 2,   /* a pivot <= 0: see feps_chol_failed_column */
    FEPS_CHOL_CHOLMOD_ERROR = 3,/* CHOLMOD failed (out of memory, ...): see feps_chol_status */
    FEPS_CHOL_NOT_READY = 4     /* called out of order (no analysis / no factor) */
};

typedef struct {
    cholmod_common common;
    cholmod_sparse *a;          /* kept upper-triangle matrix: pattern from analyze */
    cholmod_factor *l;          /* symbolic after analyze, numeric after factorize */
    int64_t n;
    int64_t nnz;
    int factorized;             /* 1 after a successful factorization */
    int64_t failed_column;      /* 1-based original column of a failed pivot, 0 if none */
    double min_ratio;           /* min over columns of L_jj^2 / A_jj */
    int64_t min_ratio_column;   /* 1-based original column of min_ratio */
    double max_ratio;
    double flops;               /* Common->fl of the last analysis */
    int64_t lnz;                /* Common->lnz of the last analysis */
} feps_chol_handle;

void *feps_chol_create(void)
{
    feps_chol_handle *h = calloc(1, sizeof(*h));
    if (h == NULL) return NULL;
    cholmod_common *c = &h->common;
    if (!cholmod_l_start(c)) {
        free(h);
        return NULL;
    }
    c->print = 0;               /* silent: the caller reads status instead */
    c->error_handler = NULL;
    c->supernodal = CHOLMOD_SUPERNODAL;
    c->nmethods = 1;
    c->method[0].ordering = CHOLMOD_METIS;
    c->postorder = 1;
    c->final_ll = 1;            /* supernodal factors are LL' anyway; keep simplicial ones LL' too */
    return h;
}

static void release_matrices(feps_chol_handle *h)
{
    if (h->l != NULL) cholmod_l_free_factor(&h->l, &h->common);
    if (h->a != NULL) cholmod_l_free_sparse(&h->a, &h->common);
    h->n = 0;
    h->nnz = 0;
    h->factorized = 0;
}

void feps_chol_free(void *handle)
{
    feps_chol_handle *h = handle;
    if (h == NULL) return;
    release_matrices(h);
    cholmod_l_finish(&h->common);
    free(h);
}

static void reset_results(feps_chol_handle *h)
{
    h->factorized = 0;
    h->failed_column = 0;
    h->min_ratio = 0.0;
    h->min_ratio_column = 0;
    h->max_ratio = 0.0;
}

int feps_chol_analyze(void *handle, int64_t n, const int64_t *row_ptr, const int32_t *col)
{
    feps_chol_handle *h = handle;
    if (h == NULL) return FEPS_CHOL_NOT_READY;
    release_matrices(h);
    reset_results(h);
    if (n <= 0 || row_ptr == NULL || col == NULL || row_ptr[0] != 1) return FEPS_CHOL_BAD_INPUT;

    /* Validate before allocating: each row sorted strictly ascending, within the lower
     * triangle, with the diagonal as its last entry. */
    for (int64_t r = 0; r < n; r++) {
        int64_t first = row_ptr[r] - 1, last = row_ptr[r + 1] - 2;
        if (last < first) return FEPS_CHOL_BAD_INPUT;
        if ((int64_t)col[last] != r + 1) return FEPS_CHOL_BAD_INPUT;
        for (int64_t k = first; k <= last; k++) {
            if (col[k] < 1) return FEPS_CHOL_BAD_INPUT;
            if (k > first && col[k] <= col[k - 1]) return FEPS_CHOL_BAD_INPUT;
        }
    }
    int64_t nnz = row_ptr[n] - 1;

    cholmod_common *c = &h->common;
    h->a = cholmod_l_allocate_sparse((size_t)n, (size_t)n, (size_t)nnz,
                                     1 /* sorted */, 1 /* packed */, 1 /* stype: upper */,
                                     CHOLMOD_REAL, c);
    if (h->a == NULL) return FEPS_CHOL_CHOLMOD_ERROR;
    SuiteSparse_long *ap = h->a->p, *ai = h->a->i;
    double *ax = h->a->x;
    for (int64_t j = 0; j <= n; j++) ap[j] = row_ptr[j] - 1;
    for (int64_t k = 0; k < nnz; k++) {
        ai[k] = col[k] - 1;
        ax[k] = 0.0;
    }
    h->n = n;
    h->nnz = nnz;

    h->l = cholmod_l_analyze(h->a, c);
    if (h->l == NULL || c->status < CHOLMOD_OK) {
        release_matrices(h);
        return FEPS_CHOL_CHOLMOD_ERROR;
    }
    h->flops = c->fl;
    h->lnz = (int64_t)c->lnz;
    return FEPS_CHOL_OK;
}

/* Diagonal entry of L in permuted column k (LL' factors), or D_kk for simplicial LDL'. */
static double factor_diagonal(const cholmod_factor *l, int64_t k, const int64_t *column_to_super)
{
    const double *x = l->x;
    if (l->is_super) {
        const SuiteSparse_long *super = l->super, *pi = l->pi, *px = l->px;
        int64_t s = column_to_super[k];
        int64_t nrows = pi[s + 1] - pi[s];   /* leading dimension of the supernode block */
        int64_t j = k - super[s];
        return x[px[s] + j * nrows + j];
    }
    const SuiteSparse_long *p = l->p;
    return x[p[k]];                          /* the first entry of each column is the diagonal */
}

/* Pivot ratios L_jj^2 / A_jj over permuted columns 0..ncols-1. */
static int compute_ratios(feps_chol_handle *h, int64_t ncols)
{
    const cholmod_factor *l = h->l;
    const SuiteSparse_long *perm = l->Perm;
    const SuiteSparse_long *ap = h->a->p;
    const double *ax = h->a->x;
    int64_t *column_to_super = NULL;

    if (l->is_super) {
        column_to_super = malloc((size_t)h->n * sizeof(*column_to_super));
        if (column_to_super == NULL) return FEPS_CHOL_CHOLMOD_ERROR;
        const SuiteSparse_long *super = l->super;
        for (int64_t s = 0; s < (int64_t)l->nsuper; s++)
            for (int64_t k = super[s]; k < super[s + 1]; k++) column_to_super[k] = s;
    }
    double min_ratio = DBL_MAX, max_ratio = -DBL_MAX;
    int64_t min_column = 0;
    for (int64_t k = 0; k < ncols; k++) {
        int64_t j = perm[k];
        double a_jj = ax[ap[j + 1] - 1];     /* the diagonal is the last entry of column j */
        double d = factor_diagonal(l, k, column_to_super);
        double pivot = l->is_ll ? d * d : d;
        double ratio = a_jj > 0.0 ? pivot / a_jj : -1.0;
        if (ratio < min_ratio) {
            min_ratio = ratio;
            min_column = j + 1;
        }
        if (ratio > max_ratio) max_ratio = ratio;
    }
    free(column_to_super);
    if (ncols > 0) {
        h->min_ratio = min_ratio;
        h->min_ratio_column = min_column;
        h->max_ratio = max_ratio;
    }
    return FEPS_CHOL_OK;
}

int feps_chol_factorize(void *handle, const double *val)
{
    feps_chol_handle *h = handle;
    if (h == NULL || h->a == NULL || h->l == NULL) return FEPS_CHOL_NOT_READY;
    reset_results(h);
    memcpy(h->a->x, val, (size_t)h->nnz * sizeof(double));

    cholmod_common *c = &h->common;
    int ok = cholmod_l_factorize(h->a, h->l, c);
    if (!ok || c->status < CHOLMOD_OK) return FEPS_CHOL_CHOLMOD_ERROR;

    cholmod_factor *l = h->l;
    if (c->status == CHOLMOD_NOT_POSDEF || l->minor < l->n) {
        const SuiteSparse_long *perm = l->Perm;
        h->failed_column = perm[l->minor] + 1;
        /* Ratios of the columns completed before the failure; the failing pivot is <= 0. */
        int rc = compute_ratios(h, (int64_t)l->minor);
        if (rc != FEPS_CHOL_OK) return rc;
        h->min_ratio = 0.0;
        h->min_ratio_column = h->failed_column;
        return FEPS_CHOL_NOT_POSDEF;
    }
    int rc = compute_ratios(h, h->n);
    if (rc != FEPS_CHOL_OK) return rc;
    h->factorized = 1;
    return FEPS_CHOL_OK;
}

int feps_chol_solve(void *handle, int64_t n, int64_t nrhs, double *b)
{
    feps_chol_handle *h = handle;
    if (h == NULL || !h->factorized) return FEPS_CHOL_NOT_READY;
    if (n != h->n || nrhs < 1 || b == NULL) return FEPS_CHOL_BAD_INPUT;

    /* Wrap the caller's array without copying; CHOLMOD returns the solution in a new X. */
    cholmod_dense rhs;
    memset(&rhs, 0, sizeof(rhs));
    rhs.nrow = (size_t)n;
    rhs.ncol = (size_t)nrhs;
    rhs.nzmax = (size_t)(n * nrhs);
    rhs.d = (size_t)n;
    rhs.x = b;
    rhs.z = NULL;
    rhs.xtype = CHOLMOD_REAL;
    rhs.dtype = CHOLMOD_DOUBLE;

    cholmod_common *c = &h->common;
    cholmod_dense *x = cholmod_l_solve(CHOLMOD_A, h->l, &rhs, c);
    if (x == NULL || c->status < CHOLMOD_OK) {
        if (x != NULL) cholmod_l_free_dense(&x, c);
        return FEPS_CHOL_CHOLMOD_ERROR;
    }
    memcpy(b, x->x, (size_t)(n * nrhs) * sizeof(double));
    cholmod_l_free_dense(&x, c);
    return FEPS_CHOL_OK;
}

double feps_chol_flops(void *handle)
{
    const feps_chol_handle *h = handle;
    return h == NULL ? 0.0 : h->flops;
}

int64_t feps_chol_lnz(void *handle)
{
    const feps_chol_handle *h = handle;
    return h == NULL ? 0 : h->lnz;
}

int feps_chol_status(void *handle)
{
    const feps_chol_handle *h = handle;
    return h == NULL ? CHOLMOD_INVALID : h->common.status;
}

int64_t feps_chol_failed_column(void *handle)
{
    const feps_chol_handle *h = handle;
    return h == NULL ? 0 : h->failed_column;
}

double feps_chol_min_ratio(void *handle)
{
    const feps_chol_handle *h = handle;
    return h == NULL ? 0.0 : h->min_ratio;
}

double feps_chol_max_ratio(void *handle)
{
    const feps_chol_handle *h = handle;
    return h == NULL ? 0.0 : h->max_ratio;
}

int64_t feps_chol_min_ratio_column(void *handle)
{
    const feps_chol_handle *h = handle;
    return h == NULL ? 0 : h->min_ratio_column;
}
