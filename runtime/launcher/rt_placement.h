/*
 * rt_placement.h -- where and how promptly an architecture's processes run, for contract-launch.
 *
 *   --cpus LIST      CPU affinity of every module (e.g. "1", "2-3", "0,2"): keeps a periodic
 *                    chain's wake-ups on the CPUs given (on a VM a wake-up across vCPUs costs an
 *                    inter-processor interrupt; on a real robot, the CPUs set aside for control).
 *   --pm-qos-us N    holds a PM QoS CPU wake-up latency request of N us (/dev/cpu_dma_latency,
 *                    as cyclictest does) while the architecture runs: idle CPUs stay in shallow
 *                    idle states, so a timer or a message wakes them in microseconds. Needs root;
 *                    otherwise one warning line and the run goes on unchanged.
 * Defaults come from $CONTRACT_CPUS and $CONTRACT_PM_QOS_US; unset = leave the system's choice.
 */
#ifndef CONTRACT_RT_PLACEMENT_H
#define CONTRACT_RT_PLACEMENT_H

#include <sched.h> /* cpu_set_t: the including file defines _GNU_SOURCE */
#include <stddef.h>

/** Parses a CPU list ("0", "1-3", "0,2-3") into `set`, checking each CPU is one this process
 *  may run on. 0, or -1 with a message in err. */
int rt_parse_cpus(const char *list, cpu_set_t *set, char *err, size_t errlen);

/** Parses a PM QoS latency in microseconds (0 .. 2000000000). 0, or -1 with a message in err. */
int rt_parse_pm_qos_us(const char *text, int *us, char *err, size_t errlen);

/** Opens /dev/cpu_dma_latency and requests `us`; the request holds while the returned fd stays
 *  open (close-on-exec, so modules do not inherit it). -1 with a message in err. */
int rt_hold_pm_qos(int us, char *err, size_t errlen);

#endif
