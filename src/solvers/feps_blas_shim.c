/* Which BLAS feps runs on, for --version, the run summary and the results file (issue 28).
 *
 * OpenBLAS says which kernels it chose for this CPU (a wrong guess, such as Debian's 0.3.21
 * taking a new Xeon for a Prescott, costs a factor of 5 in dgemm) and how many threads it
 * uses. Its functions are looked up at run time, so that feps links and runs with any BLAS;
 * another BLAS is named as unknown. */
#define _GNU_SOURCE             /* RTLD_DEFAULT */
#include <cpuid.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

/* Set in the environment of the process feps started again with better kernels: OpenBLAS's own
 * choice, for the description. */
#define CHOSEN_VARIABLE "FEPS_BLAS_KERNELS_REPLACED"

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
/* Whether the operating system saves the vector registers a kernel family uses (XCR0): the
 * CPU flags alone do not say that AVX or AVX-512 may be used. */
static int os_saves(unsigned int mask)
{
    unsigned int a, b, c, d, lo, hi;
    if (!__get_cpuid(1, &a, &b, &c, &d) || !(c & bit_OSXSAVE)) return 0;
    __asm__ volatile("xgetbv" : "=a"(lo), "=d"(hi) : "c"(0));
    (void)hi;
    return (lo & mask) == mask;
}

static const char *better_kernels(const char *core)
{
    int tier = kernel_tier(core);
    __builtin_cpu_init();
    if (tier < 3 && os_saves(0xe6u) && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
        __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq") &&
        __builtin_cpu_supports("avx512cd"))
        return "SkylakeX";
    if (tier < 2 && os_saves(0x06u) && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma"))
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
    const char *replaced = getenv(CHOSEN_VARIABLE);
    int n;
    if (replaced != NULL && core != NULL && strcmp(replaced, core) != 0)
        n = snprintf(buf, (size_t)len, "%s, %s kernels (chosen by feps; OpenBLAS chose %s), %d thread%s "
                     "(solves on 1)", version, core, replaced, t, t == 1 ? "" : "s");
    else
        n = snprintf(buf, (size_t)len, "%s, %s kernels, %d thread%s (solves on 1)", version,
                     core != NULL ? core : "unknown", t, t == 1 ? "" : "s");
    const char *better = better_kernels(core);
    if (better != NULL && n > 0 && n < len)
        snprintf(buf + n, (size_t)(len - n), "; this CPU runs %s kernels: OPENBLAS_CORETYPE=%s is up to "
                 "5x faster in dgemm", better, better);
}

/* Start feps again with the kernels this CPU runs when OpenBLAS chose older ones (issue 28: an
 * old OpenBLAS takes a CPU it does not know for a Prescott, 5x slower in dgemm). OpenBLAS reads
 * OPENBLAS_CORETYPE only when it is loaded, hence the new start, made before feps has read or
 * written anything. Never when the user set OPENBLAS_CORETYPE (their choice stands), never twice,
 * never for kernels whose instructions the CPU or the operating system lacks. Returns only when
 * it does not start again (0), or when the new start failed (-1: feps goes on as it was). */
int feps_blas_choose_kernels(void)
{
    char *(*corename)(void) = NULL;
    if (getenv("OPENBLAS_CORETYPE") != NULL || getenv(CHOSEN_VARIABLE) != NULL) return 0;
    *(void **)&corename = dlsym(RTLD_DEFAULT, "openblas_get_corename");
    if (corename == NULL) return 0;
    const char *core = corename();
    const char *better = better_kernels(core);
    if (better == NULL || core == NULL) return 0;

    /* the arguments as given, from /proc/self/cmdline (NUL-separated) */
    static char text[1 << 16];
    static char *args[1024];
    FILE *f = fopen("/proc/self/cmdline", "rb");
    if (f == NULL) return -1;
    size_t n = fread(text, 1, sizeof text - 1, f);
    int complete = feof(f);
    fclose(f);
    if (n == 0 || !complete) return -1;
    text[n] = '\0';
    size_t i = 0;
    int count = 0;
    while (i < n && count < (int)(sizeof args / sizeof *args) - 1) {
        args[count++] = text + i;
        i += strlen(text + i) + 1;
    }
    if (i < n) return -1;
    args[count] = NULL;
    if (setenv("OPENBLAS_CORETYPE", better, 1) != 0 || setenv(CHOSEN_VARIABLE, core, 1) != 0) return -1;
    fflush(NULL);
    execv("/proc/self/exe", args);
    unsetenv("OPENBLAS_CORETYPE");         /* the new start failed: go on with OpenBLAS's choice */
    unsetenv(CHOSEN_VARIABLE);
    return -1;
}

/* OpenBLAS's thread controls, looked up once (NULL with another BLAS): the factorization gets
 * its threads through them, and every solve sets one thread and back (feps_cholmod_shim.c,
 * feps_supernodal_solve.f90), so the lookup is not repeated per call. */
static void thread_controls(void (**set)(int), int (**get)(void))
{
    static int looked_up = 0;
    static void (*set_fn)(int) = NULL;
    static int (*get_fn)(void) = NULL;
    if (!looked_up) {
        *(void **)&set_fn = dlsym(RTLD_DEFAULT, "openblas_set_num_threads");
        *(void **)&get_fn = dlsym(RTLD_DEFAULT, "openblas_get_num_threads");
        looked_up = 1;
    }
    *set = set_fn;
    *get = get_fn;
}

/* Set OpenBLAS's thread count. Nothing with another BLAS. */
void feps_blas_set_threads(int n)
{
    void (*set)(int);
    int (*get)(void);
    thread_controls(&set, &get);
    if (set != NULL && n >= 1) set(n);
}

/* OpenBLAS's thread count; 1 with another BLAS (which feps does not thread). */
int feps_blas_get_threads(void)
{
    void (*set)(int);
    int (*get)(void);
    thread_controls(&set, &get);
    return get != NULL ? get() : 1;
}
