/* Which BLAS feps runs on, for --version, the run summary and the results file (issue 28).
 *
 * OpenBLAS says which kernels it chose for this CPU (a wrong guess, such as Debian's 0.3.21
 * taking a new Xeon for a Prescott, costs a factor of 5 in dgemm) and how many threads it
 * uses. Its functions are looked up at run time, so that feps links and runs with any BLAS;
 * another BLAS is named as unknown. */
#define _GNU_SOURCE             /* RTLD_DEFAULT */
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

/* Write a one-line description into buf (at most len bytes with the terminating NUL). */
void feps_blas_describe(char *buf, int len)
{
    char *(*config)(void) = NULL;
    char *(*corename)(void) = NULL;
    int (*threads)(void) = NULL;
    if (buf == NULL || len < 1) return;
    *(void **)&config = dlsym(RTLD_DEFAULT, "openblas_get_config");
    *(void **)&corename = dlsym(RTLD_DEFAULT, "openblas_get_corename");
    *(void **)&threads = dlsym(RTLD_DEFAULT, "openblas_get_num_threads");
    if (config == NULL || corename == NULL || threads == NULL) {
        snprintf(buf, (size_t)len, "not OpenBLAS (its kernels and threads unknown)");
        return;
    }
    /* the configuration starts with "OpenBLAS <version>"; the rest is build options */
    char version[64] = "OpenBLAS";
    const char *text = config();
    if (text != NULL) {
        int n = 0;
        int words = 0;
        while (text[n] != '\0' && n < (int)sizeof(version) - 1) {
            if (text[n] == ' ' && ++words == 2) break;
            version[n] = text[n];
            n++;
        }
        version[n] = '\0';
    }
    const char *core = corename();
    int t = threads();
    snprintf(buf, (size_t)len, "%s, %s kernels, %d thread%s (solves on 1)", version,
             core != NULL ? core : "unknown", t, t == 1 ? "" : "s");
}
