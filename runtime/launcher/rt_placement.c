/* rt_placement.c -- see rt_placement.h. */
#define _GNU_SOURCE
#include "rt_placement.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static int parse_cpu(const char **p, long *cpu)
{
    char *end;
    errno = 0;
    long v = strtol(*p, &end, 10);
    if (end == *p || errno || v < 0 || v >= CPU_SETSIZE) return -1;
    *cpu = v;
    *p = end;
    return 0;
}

/* A CPU outside the affinity mask this process inherited is still usable when the kernel lets a
 * process run there: the mask may only be a `taskset` of the parent (a build service kept off the
 * modules' CPUs, docs/watching-a-run.md), not a cpuset. Tried on this process, its mask then restored. */
static int cpu_usable(int cpu, const cpu_set_t *allowed)
{
    if (CPU_COUNT(allowed) == 0) return 0;
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(cpu, &one);
    int ok = sched_setaffinity(0, sizeof one, &one) == 0;
    if (ok) sched_setaffinity(0, sizeof *allowed, allowed);
    return ok;
}

int rt_parse_cpus(const char *list, cpu_set_t *set, char *err, size_t errlen)
{
    cpu_set_t allowed;
    CPU_ZERO(set);
    if (sched_getaffinity(0, sizeof allowed, &allowed) != 0) CPU_ZERO(&allowed);
    const char *p = list;
    if (!p || !*p) { snprintf(err, errlen, "--cpus: empty CPU list"); return -1; }
    for (;;) {
        long lo, hi;
        if (parse_cpu(&p, &lo) != 0) goto bad;
        hi = lo;
        if (*p == '-') {
            p++;
            if (parse_cpu(&p, &hi) != 0 || hi < lo) goto bad;
        }
        for (long c = lo; c <= hi; c++) {
            if (!CPU_ISSET((int)c, &allowed) && !cpu_usable((int)c, &allowed)) {
                snprintf(err, errlen, "--cpus '%s': CPU %ld is not available here (%ld CPUs online)", list, c,
                         sysconf(_SC_NPROCESSORS_ONLN));
                return -1;
            }
            CPU_SET((int)c, set);
        }
        if (*p == '\0') return 0;
        if (*p != ',') goto bad;
        p++;
    }
bad:
    snprintf(err, errlen, "--cpus '%s': expected a CPU list such as 1, 0-1 or 0,2", list);
    return -1;
}

int rt_parse_pm_qos_us(const char *text, int *us, char *err, size_t errlen)
{
    char *end;
    errno = 0;
    long v = text ? strtol(text, &end, 10) : -1;
    if (!text || end == text || *end || errno || v < 0 || v > 2000000000L) {
        snprintf(err, errlen, "--pm-qos-us '%s': expected a wake-up latency in microseconds (0 = lowest)",
                 text ? text : "");
        return -1;
    }
    *us = (int)v;
    return 0;
}

int rt_hold_pm_qos(int us, char *err, size_t errlen)
{
    int fd = open("/dev/cpu_dma_latency", O_WRONLY | O_CLOEXEC);
    if (fd < 0) {
        snprintf(err, errlen, "cannot open /dev/cpu_dma_latency (%s): CPU wake-up latency not lowered%s",
                 strerror(errno), errno == EACCES || errno == EPERM ? "; it needs root" : "");
        return -1;
    }
    int32_t v = us;
    if (write(fd, &v, sizeof v) != (ssize_t)sizeof v) {
        snprintf(err, errlen, "cannot write /dev/cpu_dma_latency (%s): CPU wake-up latency not lowered",
                 strerror(errno));
        close(fd);
        return -1;
    }
    return fd;
}
