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

/* How new a kernel family is: 0 SSE only (Prescott, Core2, Nehalem, ...), 1 AVX (Sandybridge),
 * 2 AVX2 and FMA (Haswell, Zen), 3 AVX-512 (SkylakeX, Cooperlake, SapphireRapids). */
static int kernel_tier(const char *core)
{
    static const char *avx512[] = {"SkylakeX", "Cooperlake", "SapphireRapids"};
    static const char *avx2[] = {"Haswell", "Zen", "Excavator", "Steamroller"};
    size_t i;
    if (core == NULL) return 3;                       /* unknown: advise nothing */
    for (i = 0; i < sizeof avx512 / sizeof *avx512; i++) if (strcmp(core, avx512[i]) == 0) return 3;
    for (i = 0; i < sizeof avx2 / sizeof *avx2; i++) if (strcmp(core, avx2[i]) == 0) return 2;
    if (strcmp(core, "Sandybridge") == 0 || strcmp(core, "Bulldozer") == 0 || strcmp(core, "Piledriver") == 0)
        return 1;
    return 0;
}

/* The kernels to ask for when OpenBLAS chose older ones than this CPU runs (an old OpenBLAS
 * takes a CPU it does not know for a Prescott): SkylakeX where the CPU has the AVX-512
 * subsets those kernels use, Haswell where it has AVX2 and FMA; NULL when its choice fits.
 * Only advice: OpenBLAS reads OPENBLAS_CORETYPE when it starts, and feps never picks kernels
 * whose instructions the CPU lacks. */
static const char *better_kernels(const char *core)
{
    int tier = kernel_tier(core);
    __builtin_cpu_init();
    if (tier < 3 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
        __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq") &&
        __builtin_cpu_supports("avx512cd"))
        return "SkylakeX";
    if (tier < 2 && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
        return "Haswell";
    return NULL;
}

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
    int n = snprintf(buf, (size_t)len, "%s, %s kernels, %d thread%s (solves on 1)", version,
                     core != NULL ? core : "unknown", t, t == 1 ? "" : "s");
    const char *better = better_kernels(core);
    if (better != NULL && n > 0 && n < len)
        snprintf(buf + n, (size_t)(len - n), "; this CPU runs %s kernels: OPENBLAS_CORETYPE=%s is up to "
                 "5x faster in dgemm", better, better);
}
