/* What feps asks the operating system about files and memory before it reads or writes them
 * (feps_files.f90): the kind of a path (so that only regular files are read: a FIFO blocks at
 * open and /dev/zero never ends), whether a folder takes new files, the removal of a regular
 * file only (never a directory), and the memory a process may use (its address-space limit and
 * the machine's physical memory).
 */
#include <errno.h>
#include <signal.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
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

/* The address space this process has mapped already (libraries, thread stacks, the heap):
 * the first field of /proc/self/statm, in pages; 0 where it cannot be read. */
static int64_t address_space_in_use(void)
{
    long page = sysconf(_SC_PAGESIZE), pages = 0;
    FILE *f = fopen("/proc/self/statm", "r");
    if (f == NULL) return 0;
    if (fscanf(f, "%ld", &pages) != 1) pages = 0;
    fclose(f);
    return page > 0 && pages > 0 ? (int64_t)pages * (int64_t)page : 0;
}

/* Bytes this process may allocate at most: the smaller of what is left of its address-space
 * limit (ulimit -v) and the machine's physical memory; -1 when neither is known. */
int64_t feps_memory_limit(void)
{
    struct rlimit rl;
    int64_t limit = -1;
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0) limit = (int64_t)pages * (int64_t)page;
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) {
        /* what is left of the address-space limit (ulimit -v) */
        int64_t as = (int64_t)rl.rlim_cur - address_space_in_use();
        if (as < 1) as = 1;
        if (limit < 0 || as < limit) limit = as;
    }
    return limit;
}

/* A text file written through C stdio, whose errors are reported: gfortran's formatted WRITE,
 * FLUSH and CLOSE return status 0 when the disk is full (the XDMF file was left empty or cut
 * short with exit status 0). Each call returns 0 or the errno of the failure. */
void *feps_text_open(const char *path, int *status)
{
    FILE *f;
    errno = 0;
    f = fopen(path, "w");
    *status = f == NULL ? (errno != 0 ? errno : EIO) : 0;
    return f;
}

int feps_text_write(void *handle, const char *text, int64_t length)
{
    FILE *f = (FILE *)handle;
    if (f == NULL) return EBADF;
    errno = 0;
    if (length > 0 && fwrite(text, 1, (size_t)length, f) != (size_t)length) return errno != 0 ? errno : EIO;
    if (fputc('\n', f) == EOF) return errno != 0 ? errno : EIO;
    return 0;
}

/* Flush and close (always closes); the data are on the disk's way when it returns 0. */
int feps_text_close(void *handle)
{
    FILE *f = (FILE *)handle;
    int status = 0;
    if (f == NULL) return EBADF;
    errno = 0;
    if (fflush(f) != 0) status = errno != 0 ? errno : EIO;
    if (status == 0 && fsync(fileno(f)) != 0 && errno != EINVAL && errno != EROFS) status = errno;
    errno = 0;
    if (fclose(f) != 0 && status == 0) status = errno != 0 ? errno : EIO;
    return status;
}

/* The text of an errno (strerror) copied into buffer (at most size - 1 characters, padded). */
void feps_error_text(int status, char *buffer, int64_t size)
{
    const char *text = strerror(status);
    int64_t i, n = (int64_t)strlen(text);
    for (i = 0; i < size; i++) buffer[i] = i < n ? text[i] : ' ';
}

/* A write past the file-size limit (ulimit -f) then fails with EFBIG, reported as any other
 * write error, instead of killing the process with SIGXFSZ (no message, a partial file left). */
void feps_ignore_file_size_signal(void)
{
    signal(SIGXFSZ, SIG_IGN);
}

/* The temporary files (`.part`) feps is writing, removed at exit if still there: a run that the
 * Fortran runtime ends (an allocation beyond the memory left: "Error allocating ... bytes")
 * exits without returning to feps, and left a half-written results file behind. The one piece
 * of state in feps outside its arguments, kept here because only an exit handler can act then;
 * a run that ends normally has removed or renamed these files and cleared them. */
#define FEPS_PARTIAL_SLOTS 4
static char feps_partial[FEPS_PARTIAL_SLOTS][4096];
static int feps_partial_registered = 0;

static void feps_remove_partials(void)
{
    int i;
    for (i = 0; i < FEPS_PARTIAL_SLOTS; i++)
        if (feps_partial[i][0] != '\0') (void)feps_remove_regular(feps_partial[i]);
}

/* Remember `path` in slot (0 .. 3) as a file to remove at exit; "" forgets the slot. */
void feps_mark_partial(int slot, const char *path)
{
    if (slot < 0 || slot >= FEPS_PARTIAL_SLOTS) return;
    if (!feps_partial_registered) {
        feps_partial_registered = atexit(feps_remove_partials) == 0;
    }
    if (strlen(path) >= sizeof feps_partial[slot]) return;
    strcpy(feps_partial[slot], path);
}
