/*
 * test_ks_nomem.c - a simulated K-S test whose buffers do not fit fails at
 * once with MCSTAT_ENOMEM, before simulating.  A forked child runs the test
 * with its address space limited (RLIMIT_AS) to 1 GiB beyond its current
 * size: the 400 MB of simulated keys fit, the 800 MB sort buffer does not.
 * The child also gets a 20 s CPU limit: simulating 5e7 arrangements of 10000
 * labels takes hours, so a library that simulates before allocating dies of
 * SIGXCPU instead of returning ENOMEM within milliseconds.
 */
#include "harness.h"
#include "mcstat.h"

#include <stdio.h>
#include <string.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define UNDER_SANITIZER 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define UNDER_SANITIZER 1
#endif
#endif

/* The process's current address space in bytes (/proc/self/statm), or 0. */
static unsigned long long vm_size(void)
{
    FILE *f = fopen("/proc/self/statm", "r");
    unsigned long long pages = 0;
    if (!f)
        return 0;
    if (fscanf(f, "%llu", &pages) != 1)
        pages = 0;
    fclose(f);
    return pages * (unsigned long long)sysconf(_SC_PAGESIZE);
}

static int child(void)
{
    enum { NX = 5000, NY = 5000 };
    static double x[NX], y[NY];
    for (int i = 0; i < NX; i++)
        x[i] = i * 0.5;
    for (int i = 0; i < NY; i++)
        y[i] = i * 0.5 + 0.25;
    mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
    o.method = MCSTAT_METHOD_SIMULATE;
    o.n_sim = 50000000; /* keys 400 MB, sort buffer 800 MB */
    o.threads = 2;
    o.critical = 0;
    unsigned long long vm = vm_size();
    if (vm == 0)
        return 77;
    struct rlimit as = {(rlim_t)(vm + (1ull << 30)), (rlim_t)(vm + (1ull << 30))};
    struct rlimit cpu = {20, 25};
    if (setrlimit(RLIMIT_AS, &as) != 0 || setrlimit(RLIMIT_CPU, &cpu) != 0)
        return 77;
    mcstat_result r;
    int st = mcstat_ks_test_2(x, NX, y, NY, MCSTAT_TWO_SIDED, 0.05, &o, &r);
    return st == MCSTAT_ENOMEM ? 0 : 10 + st;
}

int main(void)
{
#ifdef UNDER_SANITIZER
    puts("test_ks_nomem: skipped under a sanitizer (it reserves the address space)");
    return 0;
#else
    fflush(NULL);
    pid_t pid = fork();
    if (pid == 0)
        _exit(child());
    CHECK(pid > 0);
    int ws = 0;
    CHECK(waitpid(pid, &ws, 0) == pid);
    CHECK_MSG(WIFEXITED(ws), "child killed by signal %d (the CPU limit: it simulated before allocating)",
              WIFSIGNALED(ws) ? WTERMSIG(ws) : 0);
    if (WIFEXITED(ws)) {
        if (WEXITSTATUS(ws) == 77) { /* no /proc or no rlimits: nothing to test here */
            puts("test_ks_nomem: skipped (cannot limit the child's resources)");
            return 0;
        }
        CHECK_MSG(WEXITSTATUS(ws) == 0, "status %d, want MCSTAT_ENOMEM", WEXITSTATUS(ws) - 10);
    }
    return h_report("test_ks_nomem");
#endif
}
