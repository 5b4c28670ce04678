/* The POSIX calls drivers/sweep's result file needs and Fortran 2008 cannot make:
 * a descriptor of the file, an exclusive lock on it (flock: released when the
 * process ends, however it ends), writes whose errors are seen (gfortran 12's
 * WRITE and FLUSH return iostat 0 on a full disk: measured on /dev/full), and
 * fsync. Called from sweep_table.f90. */
#define _DEFAULT_SOURCE
#include <errno.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

/* Open `path` for appending (created if missing, never truncated) and lock it,
 * trying every 0.1 s up to `tries` times. Returns the descriptor (>= 0), -1 if
 * the file cannot be opened for writing, -2 if the lock is held by another
 * process (or refused). */
int regdae_sweep_lock(const char *path, int tries)
{
    int fd = open(path, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0666);
    if (fd < 0) return -1;
    for (int k = 0; k < tries; ++k) {
        if (flock(fd, LOCK_EX | LOCK_NB) == 0) return fd;
        if (errno != EWOULDBLOCK && errno != EINTR) break;
        if (k + 1 < tries) usleep(100000);
    }
    close(fd);
    return -2;
}

/* fsync the file open on `fd`: 0 done (or not a regular file, which has
 * nothing to sync: /dev/null, a pipe), else errno. */
int regdae_sweep_sync(int fd)
{
    struct stat st;
    if (fstat(fd, &st) != 0) return errno;
    if (!S_ISREG(st.st_mode)) return 0;
    return fsync(fd) == 0 ? 0 : errno;
}

/* Write n bytes to fd (all of them: partial writes and EINTR retried).
 * Returns 0, or the errno of the failure (ENOSPC: the disk is full). */
int regdae_sweep_write(int fd, const char *text, int n)
{
    while (n > 0) {
        ssize_t done = write(fd, text, (size_t)n);
        if (done < 0) {
            if (errno == EINTR) continue;
            return errno;
        }
        text += done;
        n -= (int)done;
    }
    return 0;
}

/* Create (or truncate) `path` for writing: the descriptor, or -1. */
int regdae_sweep_create(const char *path)
{
    int fd = open(path, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    return fd < 0 ? -1 : fd;
}

/* Close fd (and with it a lock taken on it): 0, or errno. */
int regdae_sweep_close(int fd)
{
    if (fd < 0) return 0;
    return close(fd) == 0 ? 0 : errno;
}
