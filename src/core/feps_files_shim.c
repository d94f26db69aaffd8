/* What feps asks the operating system about files and memory before it reads or writes them
 * (feps_files.f90): the kind of a path (so that only regular files are read: a FIFO blocks at
 * open and /dev/zero never ends), whether a folder takes new files, the removal of a regular
 * file only (never a directory), and the memory a process may use (its address-space limit and
 * the machine's physical memory).
 */
#include <errno.h>
#include <stdint.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <unistd.h>

/* Must match the parameters in feps_files.f90. */
enum {
    FEPS_FILE_MISSING = 0,
    FEPS_FILE_REGULAR = 1,
    FEPS_FILE_DIRECTORY = 2,
    FEPS_FILE_SPECIAL = 3,   /* FIFO, device, socket */
    FEPS_FILE_UNKNOWN = 4    /* stat failed for another reason (permission on a folder, ...) */
};

int feps_file_kind(const char *path)
{
    struct stat st;
    if (stat(path, &st) != 0)   /* a missing name (no entry at all) or one that cannot be looked at */
        return lstat(path, &st) != 0 && errno == ENOENT ? FEPS_FILE_MISSING : FEPS_FILE_UNKNOWN;
    if (S_ISREG(st.st_mode)) return FEPS_FILE_REGULAR;
    if (S_ISDIR(st.st_mode)) return FEPS_FILE_DIRECTORY;
    return FEPS_FILE_SPECIAL;
}

/* 1 when a new file can be created in the folder `dir` (write and search permission). */
int feps_folder_writable(const char *dir)
{
    return access(dir, W_OK | X_OK) == 0;
}

/* Remove `path` if it is a regular file (or a symbolic link to one: the link goes); 0 on
 * success, -1 when it is not one or cannot be removed. Never removes a directory. */
int feps_remove_regular(const char *path)
{
    struct stat st;
    if (lstat(path, &st) != 0) return -1;
    if (S_ISLNK(st.st_mode)) {
        if (stat(path, &st) != 0 || !S_ISREG(st.st_mode)) return -1;
    } else if (!S_ISREG(st.st_mode)) {
        return -1;
    }
    return unlink(path) == 0 ? 0 : -1;
}

/* Bytes this process may allocate at most: the smaller of its address-space limit
 * (ulimit -v) and the machine's physical memory; -1 when neither is known. */
int64_t feps_memory_limit(void)
{
    struct rlimit rl;
    int64_t limit = -1;
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0) limit = (int64_t)pages * (int64_t)page;
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) {
        int64_t as = (int64_t)rl.rlim_cur;
        if (limit < 0 || as < limit) limit = as;
    }
    return limit;
}
