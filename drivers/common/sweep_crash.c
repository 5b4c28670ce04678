/* The crash log of drivers/sweep: a row that kills its process is recorded, so that a
 * resume can tell it from a row that was only interrupted. Each process of a sweep (every
 * MPI rank) opens the log (RESULT_FILE.crashes, O_APPEND) once; while a row runs, a
 * synchronous fatal signal (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT) or an exit from inside
 * it (the Fortran runtime's "Error allocating ...", a STOP in a library) appends one line
 *     crash id=<row> signal=<number>      or      crash id=<row> exit
 * by one write(2) (async-signal-safe), then the process dies as it would have. A kill from
 * outside (SIGKILL, SIGTERM: a user, the OOM killer, a killed mpirun) writes nothing: that
 * row is only interrupted and runs again. This state is per process by nature (signal
 * dispositions are), and belongs to the driver, not to the library.
 * Called from sweep_schedule.f90. */
#define _DEFAULT_SOURCE
#include <fcntl.h>
#include <signal.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int log_fd = -1;
static volatile sig_atomic_t current_row = 0;
static char alt_stack[65536];
static const int fatal_signals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};

/* "crash id=<id> <what>=<n>\n" (n >= 0) or "crash id=<id> <what>\n" into buf without stdio (a
 * signal handler calls it). */
static size_t format_line(char *buf, long id, const char *what, long n)
{
    char digits[24];
    size_t len = 0, k;
    const char *head = "crash id=";
    for (k = 0; head[k]; ++k) buf[len++] = head[k];
    long parts[2] = {id, n};
    for (int p = 0; p < 2; ++p) {
        long v = parts[p];
        int d = 0;
        if (p == 1) {
            buf[len++] = ' ';
            for (k = 0; what[k]; ++k) buf[len++] = what[k];
            if (v < 0) break;
            buf[len++] = '=';
        }
        do { digits[d++] = (char)('0' + v % 10); v /= 10; } while (v > 0);
        while (d > 0) buf[len++] = digits[--d];
    }
    buf[len++] = '\n';
    return len;
}

static void record(const char *what, long n)
{
    char buf[96];
    long id = current_row;
    if (log_fd < 0 || id <= 0) return;
    current_row = 0;
    size_t len = format_line(buf, id, what, n);
    ssize_t w = write(log_fd, buf, len);
    (void)w;
    fsync(log_fd);
}

static void on_signal(int sig)
{
    record("signal", sig);
    /* SA_RESETHAND restored the default action: die of the same signal */
    raise(sig);
}

static void on_exit_call(void) { record("exit", -1); }

/* Open the crash log `path` and install the handlers (once per process). Returns 0, or -1
 * when the log cannot be opened (the sweep then runs without it). */
int regdae_sweep_crash_log(const char *path)
{
    static int installed = 0;
    if (log_fd >= 0) close(log_fd);
    log_fd = open(path, O_WRONLY | O_APPEND | O_CREAT | O_CLOEXEC, 0666);
    if (log_fd < 0) return -1;
    if (!installed) {
        stack_t ss;
        struct sigaction sa;
        memset(&ss, 0, sizeof ss);
        ss.ss_sp = alt_stack;
        ss.ss_size = sizeof alt_stack;
        sigaltstack(&ss, NULL);   /* a stack overflow's SIGSEGV needs a stack of its own */
        memset(&sa, 0, sizeof sa);
        sa.sa_handler = on_signal;
        sa.sa_flags = SA_RESETHAND | SA_ONSTACK;
        sigemptyset(&sa.sa_mask);
        for (size_t k = 0; k < sizeof fatal_signals / sizeof fatal_signals[0]; ++k)
            sigaction(fatal_signals[k], &sa, NULL);
        atexit(on_exit_call);
        installed = 1;
    }
    return 0;
}

/* The row now running in this process (0: none, e.g. between rows or while rank 0 serves
 * the other ranks from a row's hook). */
void regdae_sweep_crash_row(int id) { current_row = id; }

/* Testing: kill this process by signal `sig` as a crashing row would (raise), or, with
 * sig = 0, exit(1) as the Fortran runtime does on a refused allocation. */
void regdae_sweep_crash_now(int sig)
{
    if (sig == 0) exit(1);
    raise(sig);
}
