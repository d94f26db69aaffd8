#!/usr/bin/env bash
# The floor of a solve pair (issue 28 item 4): a supernodal solve with one right-hand side reads
# the whole factor twice (forward and back), so one solve cannot take less than 2 x the factor's
# bytes over the rate one core reads memory. This measures, on one core and one BLAS thread:
# the read rate of arrays of 1 MiB, 4 MiB (cache) and of the factor's size and twice it, and
# dgemv N and T over the factor's bytes as a matrix 32 columns wide (a supernode's width), the
# rate the BLAS reaches on the solve's own operation; then the factor's size read by two cores at
# once, each its half (the threaded solves, issue 28). Each figure: the median of 7 timings.
#
#   bash scripts/bench_solve_bound.sh [FACTOR_BYTES]
#
# FACTOR_BYTES: the factor's values and row indices (CHOLMOD's xsize x 8 + ssize x 8); the
# default, 49 723 408, is FE1's (input/modelB/FE1.dat: xsize 6 122 570, ssize 92 856).
# Prints one line per measurement, then the bound: 2 x FACTOR_BYTES / the read rate at that size,
# on one core and on two.
set -euo pipefail
bytes=${1:-49723408}
[[ "$bytes" =~ ^[1-9][0-9]*$ ]] || { echo "usage: bash scripts/bench_solve_bound.sh [FACTOR_BYTES]" >&2; exit 2; }
tmp=$(mktemp -d); trap 'rm -rf "$tmp"' EXIT
cat >"$tmp/bound.c" <<'EOF'
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include <omp.h>
extern void dgemv_(const char *, const int *, const int *, const double *, const double *,
                   const int *, const double *, const int *, const double *, double *, const int *);
extern void openblas_set_num_threads(int) __attribute__((weak));

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median over 7 timings of reading n doubles (8 independent sums, so the adds keep up). */
static double read_seconds(const double *a, size_t n)
{
    double t[7];
    volatile double sink = 0.0;
    int reps = (int)(4e8 / n) + 1;
    for (int r = 0; r < 7; r++) {
        double s[8] = {0}, t0 = now();
        for (int k = 0; k < reps; k++)
            for (size_t i = 0; i + 8 <= n; i += 8)
                for (int j = 0; j < 8; j++) s[j] += a[i + j];
        t[r] = (now() - t0) / reps;
        for (int j = 0; j < 8; j++) sink += s[j];
    }
    qsort(t, 7, sizeof(double), by_value);
    return t[3];
}

/* The same with two threads, each reading its half at the same time. */
static double read2_seconds(const double *a, size_t n)
{
    double t[7];
    volatile double sink = 0.0;
    int reps = (int)(4e8 / n) + 1;
    for (int r = 0; r < 7; r++) {
        double t0 = now(), total = 0.0;
#pragma omp parallel num_threads(2) reduction(+ : total)
        {
            size_t half = n / 2, first = omp_get_thread_num() * half;
            double s[8] = {0};
            for (int k = 0; k < reps; k++)
                for (size_t i = first; i + 8 <= first + half; i += 8)
                    for (int j = 0; j < 8; j++) s[j] += a[i + j];
            for (int j = 0; j < 8; j++) total += s[j];
        }
        t[r] = (now() - t0) / reps;
        sink += total;
    }
    qsort(t, 7, sizeof(double), by_value);
    return t[3];
}

static double gemv_seconds(const char *trans, const double *a, int m, int k, double *x, double *y)
{
    double t[7], one = 1.0;
    int inc = 1, reps = (int)(4e8 / ((double)m * k)) + 1;
    for (int r = 0; r < 7; r++) {
        double t0 = now();
        for (int q = 0; q < reps; q++) dgemv_(trans, &m, &k, &one, a, &m, x, &inc, &one, y, &inc);
        t[r] = (now() - t0) / reps;
    }
    qsort(t, 7, sizeof(double), by_value);
    return t[3];
}

int main(int argc, char **argv)
{
    if (openblas_set_num_threads) openblas_set_num_threads(1);
    size_t factor = (size_t)atoll(argv[1]) / 8;
    size_t sizes[4] = {(size_t)1 << 17, (size_t)1 << 19, factor, 2 * factor};
    double factor_rate = 0.0, factor_rate2 = 0.0;
    for (int s = 0; s < 4; s++) {
        size_t n = sizes[s];
        double *a = malloc(n * sizeof(double));
        if (a == NULL) return 1;
        for (size_t i = 0; i < n; i++) a[i] = 1.0 / (double)(i + 1);
        double t = read_seconds(a, n);
        printf("read   %10.2f MB  %8.3f ms  %6.1f GB/s\n", n * 8 / 1e6, t * 1e3, n * 8 / t / 1e9);
        if (s == 2) {
            factor_rate = n * 8 / t;
            int k = 32, m = (int)(n / 32);
            double *x = calloc((size_t)m, sizeof(double)), *y = calloc((size_t)m, sizeof(double));
            if (x == NULL || y == NULL) return 1;
            for (int i = 0; i < m; i++) x[i] = 1.0;
            for (int p = 0; p < 2; p++) {
                double tg = gemv_seconds(p ? "T" : "N", a, m, k, x, y);
                printf("dgemv_%s %d x %d  %8.3f ms  %6.1f GB/s\n", p ? "T" : "N", m, k, tg * 1e3,
                       (double)m * k * 8 / tg / 1e9);
            }
            free(x);
            free(y);
            double t2 = read2_seconds(a, n);
            factor_rate2 = n * 8 / t2;
            printf("read   %10.2f MB  %8.3f ms  %6.1f GB/s  on two cores, a half each\n", n * 8 / 1e6, t2 * 1e3,
                   n * 8 / t2 / 1e9);
        }
        free(a);
    }
    printf("bound: 2 x %.2f MB / %.1f GB/s = %.3f ms per solve\n", factor * 8 / 1e6, factor_rate / 1e9,
           2.0 * factor * 8 / factor_rate * 1e3);
    printf("bound on two cores: 2 x %.2f MB / %.1f GB/s = %.3f ms per solve\n", factor * 8 / 1e6,
           factor_rate2 / 1e9, 2.0 * factor * 8 / factor_rate2 * 1e3);
    return 0;
}
EOF
cc -O3 -march=native -fopenmp -o "$tmp/bound" "$tmp/bound.c" -lblas
"$tmp/bound" "$bytes"
