/* Thin handle-based shim over CHOLMOD (64-bit cholmod_l_* API) for feps.
 *
 * The C side owns cholmod_common, the kept matrix and the factor; Fortran only holds an
 * opaque pointer (see feps_cholmod_bindings.f90).  Fortran passes the lower triangle in
 * 1-based compressed rows; read as compressed columns this is the upper triangle, which
 * CHOLMOD takes as a symmetric matrix with stype = +1.
 *
 * Ordering: METIS on the graph of supervariables (equations with identical pattern, such as
 * the DOFs of one node), given to CHOLMOD through cholmod_l_analyze_p; CHOLMOD's own METIS
 * ordering of the full graph is the fallback (see analyze_node_graph).
 *
 * Return codes of analyze/factorize/solve: see FEPS_CHOL_* below (0 = success).
 * Column numbers handed back to Fortran are original (unpermuted) and 1-based.
 */
#include <float.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <metis.h>
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
    int64_t supervariables;     /* vertices of the graph METIS ordered (0: CHOLMOD's own METIS) */
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
    /* Merge more small supernodes than CHOLMOD's 4/16/48 (zrelax kept at 0.8/0.1/0.05): at 200k
     * DOFs the factor grows by 1.4% but BLAS works on bigger blocks, and the one-thread
     * factorization took 0.82-1.03x the CPU time in 10 alternating pairs (median 0.9x). */
    c->nrelax[0] = 8;
    c->nrelax[1] = 32;
    c->nrelax[2] = 64;
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

/* Each row sorted strictly ascending, within the lower triangle, with the diagonal as its last
 * entry (1-based compressed rows). */
static int valid_lower_csr(int64_t n, const int64_t *row_ptr, const int32_t *col)
{
    if (n <= 0 || row_ptr == NULL || col == NULL || row_ptr[0] != 1) return 0;
    for (int64_t r = 0; r < n; r++) {
        int64_t first = row_ptr[r] - 1, last = row_ptr[r + 1] - 2;
        if (last < first) return 0;
        if ((int64_t)col[last] != r + 1) return 0;
        for (int64_t k = first; k <= last; k++) {
            if (col[k] < 1) return 0;
            if (k > first && col[k] <= col[k - 1]) return 0;
        }
    }
    return 1;
}

/* ---------------------------------------------------------------------------------------
 * Ordering on the graph of supervariables.
 *
 * A finite-element matrix has up to 3 equations per node (fewer where a DOF is held), and
 * the equations of one node have the same pattern.  Equations whose closed adjacency (row and
 * column pattern with the diagonal) is identical form a supervariable; eliminating them
 * together never costs fill, so METIS can order the graph of supervariables (weighted by their
 * sizes) instead of the full graph.  CHOLMOD's own METIS path builds the full graph A + A' and
 * lets METIS compress it again on every call, which is most of its analysis time.
 * ------------------------------------------------------------------------------------- */

typedef struct {
    int64_t n;
    int64_t *ptr;   /* n + 1: equation v's neighbours are idx[ptr[v] .. ptr[v+1]-1] */
    int32_t *idx;   /* 0-based, ascending, v itself included */
} closed_adjacency;

static void free_adjacency(closed_adjacency *adj)
{
    free(adj->ptr);
    free(adj->idx);
    adj->ptr = NULL;
    adj->idx = NULL;
}

/* Both triangles of a valid lower CSR pattern; returns 0 if out of memory. */
static int build_closed_adjacency(int64_t n, const int64_t *row_ptr, const int32_t *col,
                                  closed_adjacency *adj)
{
    int64_t nnz = row_ptr[n] - 1;
    adj->n = n;
    adj->ptr = calloc((size_t)n + 1, sizeof(*adj->ptr));
    adj->idx = malloc((size_t)(2 * nnz - n) * sizeof(*adj->idx));
    int64_t *next = malloc((size_t)n * sizeof(*next));
    if (adj->ptr == NULL || adj->idx == NULL || next == NULL) {
        free(next);
        free_adjacency(adj);
        return 0;
    }
    /* Degree of v: its own row (diagonal included) plus the later rows that reference it. */
    for (int64_t r = 0; r < n; r++) {
        adj->ptr[r + 1] += row_ptr[r + 1] - row_ptr[r];
        for (int64_t k = row_ptr[r] - 1; k < row_ptr[r + 1] - 2; k++) adj->ptr[col[k]]++;
    }
    for (int64_t v = 0; v < n; v++) adj->ptr[v + 1] += adj->ptr[v];
    /* Own row first (columns <= v, ascending), then the rows r > v in ascending r: sorted. */
    for (int64_t v = 0; v < n; v++) {
        next[v] = adj->ptr[v];
        for (int64_t k = row_ptr[v] - 1; k < row_ptr[v + 1] - 1; k++) adj->idx[next[v]++] = col[k] - 1;
    }
    for (int64_t r = 0; r < n; r++)
        for (int64_t k = row_ptr[r] - 1; k < row_ptr[r + 1] - 2; k++)
            adj->idx[next[col[k] - 1]++] = (int32_t)r;
    free(next);
    return 1;
}

/* A well-mixed 64-bit hash of one equation number (splitmix64 finaliser). */
static uint64_t mix64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

typedef struct {
    uint64_t hash;      /* sum of mix64 over the closed adjacency: independent of its order */
    int64_t degree;
    int64_t equation;
} pattern_key;

static int compare_keys(const void *pa, const void *pb)
{
    const pattern_key *a = pa, *b = pb;
    if (a->hash != b->hash) return a->hash < b->hash ? -1 : 1;
    if (a->degree != b->degree) return a->degree < b->degree ? -1 : 1;
    return (a->equation > b->equation) - (a->equation < b->equation);
}

static int same_pattern(const closed_adjacency *adj, int64_t u, int64_t v)
{
    int64_t du = adj->ptr[u + 1] - adj->ptr[u];
    return du == adj->ptr[v + 1] - adj->ptr[v] &&
           memcmp(adj->idx + adj->ptr[u], adj->idx + adj->ptr[v], (size_t)du * sizeof(*adj->idx)) == 0;
}

/* Supervariable of each equation, numbered 0.. in the order of their smallest equations.
 * Returns their count, or -1 if out of memory. */
static int64_t find_supervariables(const closed_adjacency *adj, int64_t *sv_of)
{
    int64_t n = adj->n;
    pattern_key *keys = malloc((size_t)n * sizeof(*keys));
    if (keys == NULL) return -1;
    for (int64_t v = 0; v < n; v++) {
        uint64_t hash = 0;
        for (int64_t k = adj->ptr[v]; k < adj->ptr[v + 1]; k++) hash += mix64((uint64_t)adj->idx[k]);
        keys[v].hash = hash;
        keys[v].degree = adj->ptr[v + 1] - adj->ptr[v];
        keys[v].equation = v;
    }
    qsort(keys, (size_t)n, sizeof(*keys), compare_keys);

    /* Within a run of equal keys (ascending equations), each equation joins the first earlier
     * leader with the same pattern or leads a new group; sv_of holds the leader for now. */
    for (int64_t start = 0, end; start < n; start = end) {
        for (end = start + 1; end < n && keys[end].hash == keys[start].hash &&
                              keys[end].degree == keys[start].degree; end++) {}
        for (int64_t k = start; k < end; k++) {
            int64_t v = keys[k].equation;
            sv_of[v] = v;
            for (int64_t m = start; m < k; m++) {
                int64_t u = keys[m].equation;
                if (sv_of[u] == u && same_pattern(adj, u, v)) {
                    sv_of[v] = u;
                    break;
                }
            }
        }
    }
    free(keys);
    /* Leaders are the smallest equations of their groups, so one ascending pass numbers them. */
    int64_t count = 0;
    for (int64_t v = 0; v < n; v++) sv_of[v] = sv_of[v] == v ? count++ : sv_of[sv_of[v]];
    return count;
}

/* Work arrays of the node-graph ordering; every pointer is owned (NULL when not allocated). */
typedef struct {
    closed_adjacency adj;
    int64_t *sv_of;         /* n: supervariable of each equation */
    int64_t ns;             /* supervariables */
    int64_t *member_ptr;    /* ns + 1 */
    int64_t *members;       /* n: equations of each supervariable, ascending */
    idx_t *xadj, *adjncy;   /* quotient graph for METIS, without self-loops */
    idx_t *vwgt;            /* ns: equations per supervariable */
    idx_t *order;           /* ns: supervariable eliminated k-th */
} node_graph;

static void free_node_graph(node_graph *g)
{
    free_adjacency(&g->adj);
    free(g->sv_of);
    free(g->member_ptr);
    free(g->members);
    free(g->xadj);
    free(g->adjncy);
    free(g->vwgt);
    free(g->order);
    memset(g, 0, sizeof(*g));
}

static int group_equations(node_graph *g)
{
    int64_t n = g->adj.n;
    g->sv_of = malloc((size_t)n * sizeof(*g->sv_of));
    if (g->sv_of == NULL) return 0;
    g->ns = find_supervariables(&g->adj, g->sv_of);
    if (g->ns < 1 || g->ns >= IDX_MAX) return 0;
    g->member_ptr = calloc((size_t)g->ns + 1, sizeof(*g->member_ptr));
    g->members = malloc((size_t)n * sizeof(*g->members));
    if (g->member_ptr == NULL || g->members == NULL) return 0;
    /* Counting sort; after the fill pass member_ptr[s] is the end of s, so shift it back. */
    for (int64_t v = 0; v < n; v++) g->member_ptr[g->sv_of[v] + 1]++;
    for (int64_t s = 0; s < g->ns; s++) g->member_ptr[s + 1] += g->member_ptr[s];
    for (int64_t v = 0; v < n; v++) g->members[g->member_ptr[g->sv_of[v]]++] = v;
    for (int64_t s = g->ns; s > 0; s--) g->member_ptr[s] = g->member_ptr[s - 1];
    g->member_ptr[0] = 0;
    return 1;
}

/* The neighbours of a supervariable are those of any one of its members. */
static int build_quotient_graph(node_graph *g)
{
    int64_t ns = g->ns, capacity = 0, edges = 0;
    for (int64_t s = 0; s < ns; s++) {
        int64_t leader = g->members[g->member_ptr[s]];
        capacity += g->adj.ptr[leader + 1] - g->adj.ptr[leader];
    }
    int64_t *marker = malloc((size_t)ns * sizeof(*marker));
    g->xadj = malloc(((size_t)ns + 1) * sizeof(*g->xadj));
    g->adjncy = malloc((size_t)capacity * sizeof(*g->adjncy));
    g->vwgt = malloc((size_t)ns * sizeof(*g->vwgt));
    if (marker == NULL || g->xadj == NULL || g->adjncy == NULL || g->vwgt == NULL) {
        free(marker);
        return 0;
    }
    for (int64_t s = 0; s < ns; s++) marker[s] = -1;
    for (int64_t s = 0; s < ns; s++) {
        int64_t leader = g->members[g->member_ptr[s]];
        g->xadj[s] = (idx_t)edges;
        g->vwgt[s] = (idx_t)(g->member_ptr[s + 1] - g->member_ptr[s]);
        marker[s] = s;
        for (int64_t k = g->adj.ptr[leader]; k < g->adj.ptr[leader + 1]; k++) {
            int64_t t = g->sv_of[g->adj.idx[k]];
            if (marker[t] != s) {
                marker[t] = s;
                g->adjncy[edges++] = (idx_t)t;
            }
        }
    }
    g->xadj[ns] = (idx_t)edges;
    free(marker);
    return edges <= IDX_MAX;
}

static int order_quotient_graph(node_graph *g)
{
    idx_t nvtxs = (idx_t)g->ns;
    g->order = malloc((size_t)g->ns * sizeof(*g->order));
    idx_t *position = malloc((size_t)g->ns * sizeof(*position));
    int ok = g->order != NULL && position != NULL;
    if (ok && g->xadj[g->ns] == 0) {
        for (idx_t s = 0; s < nvtxs; s++) g->order[s] = s;   /* no coupling: any order is exact */
    } else if (ok) {
        idx_t options[METIS_NOPTIONS];
        METIS_SetDefaultOptions(options);
        options[METIS_OPTION_NUMBERING] = 0;
        /* METIS's perm is the new-to-old map: row k of the permuted matrix is row perm[k]. */
        ok = METIS_NodeND(&nvtxs, g->xadj, g->adjncy, g->vwgt, options, g->order, position) == METIS_OK;
    }
    free(position);
    return ok;
}

/* Fill-reducing order of the equations from METIS on the supervariable graph: perm[k] is the
 * equation eliminated k-th (0-based).  Returns the number of supervariables, or -1 if out of
 * memory or METIS failed. */
static int64_t node_graph_ordering(int64_t n, const int64_t *row_ptr, const int32_t *col,
                                   SuiteSparse_long *perm)
{
    node_graph g;
    memset(&g, 0, sizeof(g));
    int ok = build_closed_adjacency(n, row_ptr, col, &g.adj) && group_equations(&g) &&
             build_quotient_graph(&g);
    if (ok) {
        free_adjacency(&g.adj);   /* METIS needs the memory more */
        ok = order_quotient_graph(&g);
    }
    if (ok) {
        int64_t pos = 0;
        for (int64_t k = 0; k < g.ns; k++) {
            int64_t s = g.order[k];
            for (int64_t m = g.member_ptr[s]; m < g.member_ptr[s + 1]; m++) perm[pos++] = g.members[m];
        }
    }
    int64_t ns = ok ? g.ns : -1;
    free_node_graph(&g);
    return ns;
}

/* Symbolic analysis with the node-graph ordering; 0 (and nothing kept) if any step failed. */
static int analyze_node_graph(feps_chol_handle *h, const int64_t *row_ptr, const int32_t *col)
{
    cholmod_common *c = &h->common;
    SuiteSparse_long *perm = malloc((size_t)h->n * sizeof(*perm));
    if (perm == NULL) return 0;
    int64_t ns = node_graph_ordering(h->n, row_ptr, col, perm);
    if (ns > 0) {
        /* CHOLMOD still postorders the elimination tree, which keeps supernodes contiguous. */
        c->method[0].ordering = CHOLMOD_GIVEN;
        h->l = cholmod_l_analyze_p(h->a, perm, NULL, 0, c);
        c->method[0].ordering = CHOLMOD_METIS;
        if (h->l != NULL && c->status < CHOLMOD_OK) cholmod_l_free_factor(&h->l, c);
    }
    free(perm);
    if (h->l == NULL) {
        c->status = CHOLMOD_OK;
        return 0;
    }
    h->supervariables = ns;
    return 1;
}

int64_t feps_chol_count_supervariables(int64_t n, const int64_t *row_ptr, const int32_t *col)
{
    if (!valid_lower_csr(n, row_ptr, col)) return -1;
    closed_adjacency adj = {0};
    if (!build_closed_adjacency(n, row_ptr, col, &adj)) return -2;
    int64_t *sv_of = malloc((size_t)n * sizeof(*sv_of));
    int64_t count = sv_of == NULL ? -2 : find_supervariables(&adj, sv_of);
    if (count == -1) count = -2;
    free(sv_of);
    free_adjacency(&adj);
    return count;
}

int feps_chol_analyze(void *handle, int64_t n, const int64_t *row_ptr, const int32_t *col)
{
    feps_chol_handle *h = handle;
    if (h == NULL) return FEPS_CHOL_NOT_READY;
    release_matrices(h);
    reset_results(h);
    h->supervariables = 0;
    /* Validate before allocating. */
    if (!valid_lower_csr(n, row_ptr, col)) return FEPS_CHOL_BAD_INPUT;
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

    /* CHOLMOD's own METIS ordering remains the fallback if the node-graph ordering fails. */
    if (!analyze_node_graph(h, row_ptr, col)) h->l = cholmod_l_analyze(h->a, c);
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

/* A solve with one right-hand side is a sequence of small triangular solves and matrix-vector
 * products, one per supernode: more BLAS threads there only spin between calls (FE1, 1 316
 * solves, ran 1.2-1.5x faster with one BLAS thread than with two, issue 28), while the
 * factorization's dense updates gain from them. So solves run on one BLAS thread, set through
 * feps_blas_shim.c (nothing with a BLAS other than OpenBLAS). */
void feps_blas_set_threads(int n);
int feps_blas_get_threads(void);

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
    int threads = feps_blas_get_threads();
    if (threads > 1) feps_blas_set_threads(1);
    cholmod_dense *x = cholmod_l_solve(CHOLMOD_A, h->l, &rhs, c);
    if (threads > 1) feps_blas_set_threads(threads);
    if (x == NULL || c->status < CHOLMOD_OK) {
        if (x != NULL) cholmod_l_free_dense(&x, c);
        return FEPS_CHOL_CHOLMOD_ERROR;
    }
    memcpy(b, x->x, (size_t)(n * nrhs) * sizeof(double));
    cholmod_l_free_dense(&x, c);
    return FEPS_CHOL_OK;
}

/* The numeric supernodal LL' factor's arrays (0-based, as CHOLMOD keeps them), for feps's own
 * triangular solves (feps_supernodal_solve.f90): returns 1 and sets the pointers, or 0 when there
 * is no such factor (none yet, or a simplicial one), in which case the caller solves with
 * feps_chol_solve. The pointers stay valid until the next analyze, factorize or free. */
int feps_chol_supernodes(void *handle, int64_t *nsuper, int64_t **super, int64_t **pi, int64_t **px,
                         int64_t **rows, double **x, int64_t **perm)
{
    const feps_chol_handle *h = handle;
    *nsuper = 0;
    if (h == NULL || !h->factorized || h->l == NULL) return 0;
    const cholmod_factor *l = h->l;
    if (!l->is_super || !l->is_ll || l->xtype != CHOLMOD_REAL || l->x == NULL || l->nsuper < 1) return 0;
    *nsuper = (int64_t)l->nsuper;
    *super = l->super;
    *pi = l->pi;
    *px = l->px;
    *rows = l->s;
    *x = l->x;
    *perm = l->Perm;
    return 1;
}

/* y = A x with the matrix last factorized (CHOLMOD's copy of it, both triangles by its
 * symmetry): the product of mixed precision's test solve.  Returns FEPS_CHOL_OK. */
int feps_chol_multiply(void *handle, int64_t n, const double *x, double *y)
{
    feps_chol_handle *h = handle;
    if (h == NULL || !h->factorized || h->a == NULL) return FEPS_CHOL_NOT_READY;
    if (n != h->n || x == NULL || y == NULL) return FEPS_CHOL_BAD_INPUT;
    cholmod_dense xd, yd;
    memset(&xd, 0, sizeof(xd));
    xd.nrow = xd.d = xd.nzmax = (size_t)n;
    xd.ncol = 1;
    xd.x = (double *)x;
    xd.xtype = CHOLMOD_REAL;
    xd.dtype = CHOLMOD_DOUBLE;
    yd = xd;
    yd.x = y;
    double one[2] = {1.0, 0.0}, zero[2] = {0.0, 0.0};
    if (!cholmod_l_sdmult(h->a, 0, one, zero, &xd, &yd, &h->common)) return FEPS_CHOL_CHOLMOD_ERROR;
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

int64_t feps_chol_supervariables(void *handle)
{
    const feps_chol_handle *h = handle;
    return h == NULL ? 0 : h->supervariables;
}

int64_t feps_chol_min_ratio_column(void *handle)
{
    const feps_chol_handle *h = handle;
    return h == NULL ? 0 : h->min_ratio_column;
}
