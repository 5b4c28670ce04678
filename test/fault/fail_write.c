/* LD_PRELOAD fault injection for test/check_sweep.sh: write(2) to the file named
 * by REGDAE_FAIL_WRITE_PATH fails with ENOSPC (a full disk) after
 * REGDAE_FAIL_WRITE_AFTER successful writes to it. Other files and processes
 * (Open MPI's helpers, stderr) are untouched. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

typedef ssize_t (*write_fn)(int, const void *, size_t);

static int names_target(int fd, const char *target)
{
    char link[64], path[4096];
    snprintf(link, sizeof link, "/proc/self/fd/%d", fd);
    ssize_t n = readlink(link, path, sizeof path - 1);
    if (n < 0) return 0;
    path[n] = '\0';
    return strcmp(path, target) == 0;
}

ssize_t write(int fd, const void *buffer, size_t count)
{
    static write_fn real_write = NULL;
    static long written = 0;
    if (!real_write) real_write = (write_fn)dlsym(RTLD_NEXT, "write");
    const char *target = getenv("REGDAE_FAIL_WRITE_PATH");
    const char *after = getenv("REGDAE_FAIL_WRITE_AFTER");
    if (target && after && fd > 2 && names_target(fd, target)) {
        if (written >= atol(after)) {
            errno = ENOSPC;
            return -1;
        }
        ++written;
    }
    return real_write(fd, buffer, count);
}
