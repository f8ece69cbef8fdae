/* module_holds.c — see module_holds.h. */
#define _GNU_SOURCE
#include "module_holds.h"

#include <dirent.h>
#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "engine_values.h"
#include "hold_lock.h"
#include "libmodule/libmodule.h"

/* the locks this process holds: module, descriptor, nesting depth */
#define MAX_LOCKED 16
static struct {
    char module[CONTRACT_NAME_MAX];
    int fd, depth;
} locked[MAX_LOCKED];

/* the slot holding `module`'s lock (module NULL: a free slot), or -1 */
static int locked_slot(const char *module) {
    for (int i = 0; i < MAX_LOCKED; i++)
        if (module ? locked[i].depth > 0 && strcmp(locked[i].module, module) == 0 : locked[i].depth == 0) return i;
    return -1;
}

static void (*before_block)(void);

void holds_before_block(void (*fn)(void)) { before_block = fn; }

/* The lock file of `module`, taken at once if free; else, after before_block, waited for. */
static int acquire(const char *module) {
    int fd = hold_lock_try(ContractRunDir(), module);
    if (fd >= 0 || errno != EWOULDBLOCK) return fd;
    static int in_hook;
    if (before_block && !in_hook) {
        in_hook = 1;
        before_block();
        in_hook = 0;
    }
    return hold_lock_acquire(ContractRunDir(), module);
}

int holds_lock(const char *module) {
    int i = locked_slot(module);
    if (i >= 0) {
        locked[i].depth++;
        return 0;
    }
    i = locked_slot(NULL);
    int fd = i >= 0 ? acquire(module) : -1;
    if (fd >= 0 && (i = locked_slot(NULL)) < 0) { /* the hook may have taken and released locks */
        hold_lock_release(fd);
        fd = -1;
    }
    if (fd < 0) {
        char detail[160];
        snprintf(detail, sizeof detail, "cannot lock its holds: %s", i >= 0 ? strerror(errno) : "too many locks");
        ContractLog("module_hold", module, -1, 0, detail);
        fprintf(stderr, "%s: %s: %s (deciding on it without the lock)\n", ContractSelfName(), module, detail);
        return -1;
    }
    snprintf(locked[i].module, sizeof locked[i].module, "%s", module);
    locked[i].fd = fd;
    locked[i].depth = 1;
    return 0;
}

void holds_unlock(const char *module) {
    int i = locked_slot(module);
    if (i < 0 || --locked[i].depth > 0) return;
    hold_lock_release(locked[i].fd);
    locked[i].fd = -1;
}

/* <M>.engine-stopped.hold: not an identifier, so never read as a supervisor's hold of a module */
#define STOPPED_MARK "engine-stopped"

_Static_assert(ENGINE_HOLD_NAME_MAX == CONTRACT_NAME_MAX, "a flow's hold name has a module name's room");

static int path_of(char *buf, size_t size, const char *holder, const char *module) {
    int n = snprintf(buf, size, "%s/%s.%s.hold", ContractRunDir(), holder, module);
    return n > 0 && (size_t)n < size ? 0 : -1;
}

static int touch(const char *path) {
    int fd = open(path, O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) return -1;
    close(fd);
    return 0;
}

int holds_take(const char *module, int started) {
    char path[4200];
    if (path_of(path, sizeof path, ContractSelfName(), module) != 0 || touch(path) != 0) {
        ContractLog("module_hold", module, -1, 0, "cannot record the hold in the run directory");
        return -1;
    }
    if (started && (path_of(path, sizeof path, module, "started") != 0 || touch(path) != 0)) {
        ContractLog("module_hold", module, -1, 0, "cannot record the start in the run directory");
        return -1;
    }
    if (started && path_of(path, sizeof path, module, STOPPED_MARK) == 0) unlink(path);
    ContractLog("module_hold", module, -1, 0, started ? "hold taken (started it)" : "hold taken (it was running)");
    return 0;
}

int holds_drop(const char *module) {
    char path[4200];
    if (path_of(path, sizeof path, ContractSelfName(), module) == 0) unlink(path);
    char suffix[CONTRACT_NAME_MAX + 8];
    snprintf(suffix, sizeof suffix, ".%s.hold", module);
    size_t sl = strlen(suffix);
    DIR *d = opendir(ContractRunDir());
    if (!d) return 0;
    int others = 0;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        size_t l = strlen(e->d_name);
        if (l > sl && strcmp(e->d_name + l - sl, suffix) == 0) others++;
    }
    closedir(d);
    return others;
}

void holds_mark_stopped(const char *module) {
    char path[4200];
    if (path_of(path, sizeof path, module, STOPPED_MARK) == 0) touch(path);
}

int holds_stopped(const char *module, int clear) {
    char path[4200];
    if (path_of(path, sizeof path, module, STOPPED_MARK) != 0) return 0;
    int marked = access(path, F_OK) == 0;
    if (marked && clear) unlink(path);
    return marked;
}

int holds_started(const char *module, int clear) {
    char path[4200];
    if (path_of(path, sizeof path, module, "started") != 0) return 0;
    int marked = access(path, F_OK) == 0;
    if (marked && clear) unlink(path);
    return marked;
}

int holds_take_flow(const char *name) {
    char path[4200];
    if (path_of(path, sizeof path, ContractSelfName(), name) != 0 || touch(path) != 0) {
        ContractLog("flow_hold", name, -1, 0, "cannot record the hold in the run directory");
        return -1;
    }
    ContractLog("flow_hold", name, -1, 0, "hold taken");
    return 0;
}
