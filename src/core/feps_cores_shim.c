/* How busy this machine is (feps_cores.f90): the other processes running or ready to run. */
#define _POSIX_C_SOURCE 200809L
#include <dirent.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

/* procs_running in /proc/stat: the threads of every process running or ready to run now,
 * this one's included; -1 where it cannot be read. */
static int running_now(void)
{
    char line[4096];
    int n = -1;
    FILE *f = fopen("/proc/stat", "r");
    if (f == NULL) return -1;
    while (fgets(line, sizeof line, f) != NULL)
        if (sscanf(line, "procs_running %d", &n) == 1) break;
    fclose(f);
    return n;
}

/* This process's threads running or ready to run now (state R in /proc/self/task/N/stat): the
 * reader itself, and the BLAS's threads, which spin for a while after they start. */
static int own_running(void)
{
    char path[64], text[512];
    int n = 0;
    DIR *tasks = opendir("/proc/self/task");
    if (tasks == NULL) return 1;
    for (struct dirent *e = readdir(tasks); e != NULL; e = readdir(tasks)) {
        if (e->d_name[0] == '.') continue;
        snprintf(path, sizeof path, "/proc/self/task/%.20s/stat", e->d_name);
        FILE *f = fopen(path, "r");
        if (f == NULL) continue;
        size_t len = fread(text, 1, sizeof text - 1, f);
        fclose(f);
        text[len] = '\0';
        const char *end = strrchr(text, ')');   /* the name may hold blanks and parentheses */
        if (end != NULL && end[1] == ' ' && end[2] == 'R') ++n;
    }
    closedir(tasks);
    return n > 0 ? n : 1;
}

/* The threads of other processes running or ready to run on this machine: the least of
 * `readings` readings 10 ms apart, so that one that only happened to run at one instant is
 * not counted; -1 where /proc/stat cannot be read. */
int feps_other_running(int readings)
{
    int least = -1;
    for (int i = 0; i < readings; ++i) {
        if (i > 0) {
            struct timespec pause = {0, 10000000L};
            nanosleep(&pause, NULL);
        }
        int all = running_now();
        if (all < 1) return -1;
        int others = all - own_running();
        if (others < 0) others = 0;
        if (least < 0 || others < least) least = others;
    }
    return least;
}
