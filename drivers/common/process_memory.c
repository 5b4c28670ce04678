/* The peak resident memory of the running process, for the drivers' summaries
 * (drivers/chain: peak_rss_kb): getrusage's ru_maxrss, in kilobytes on Linux.
 * Called from chain.f90; -1 where getrusage fails. */
#include <sys/resource.h>

long regdae_peak_rss_kb(void)
{
    struct rusage usage;
    if (getrusage(RUSAGE_SELF, &usage) != 0) return -1;
    return usage.ru_maxrss;
}
