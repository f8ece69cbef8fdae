/*
 * test_hold_lock.c — the cross-process lock of module holds (src/engines/hold_lock.c) with
 * real processes: exclusive between processes, per module, freed when its holder is killed.
 */
#define _GNU_SOURCE
#include <errno.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "harness.h"
#include "hold_lock.h"

/* runs hold_lock_try(dir, module) in a child process: 1 it got the lock, 0 it was held, -1 error */
static int try_in_child(const char *dir, const char *module) {
    pid_t pid = fork();
    if (pid == 0) {
        int fd = hold_lock_try(dir, module);
        _exit(fd >= 0 ? 1 : errno == EWOULDBLOCK ? 0 : 2);
    }
    int st = 0;
    if (pid < 0 || waitpid(pid, &st, 0) != pid || !WIFEXITED(st)) return -1;
    return WEXITSTATUS(st) == 2 ? -1 : WEXITSTATUS(st);
}

static void remove_dir(const char *dir) {
    char path[300];
    const char *files[] = {"holds-AMX.hold", "holds-MAB.hold", NULL};
    for (int i = 0; files[i]; i++) {
        snprintf(path, sizeof path, "%s/%s", dir, files[i]);
        unlink(path);
    }
    rmdir(dir);
}

void test_hold_lock_excludes_other_processes_per_module(void) {
    char dir[] = "/tmp/contract-hold-lock-XXXXXX";
    if (!mkdtemp(dir)) { CHECK(0); return; }
    int fd = hold_lock_acquire(dir, "AMX");
    CHECK(fd >= 0);
    CHECK(try_in_child(dir, "AMX") == 0); /* held here: another process cannot take it */
    CHECK(try_in_child(dir, "MAB") == 1); /* another module's lock is independent */
    struct stat st;
    char path[300];
    snprintf(path, sizeof path, "%s/holds-AMX.hold", dir);
    CHECK(stat(path, &st) == 0); /* one dot: never read as a <SUP>.<M>.hold */
    hold_lock_release(fd);
    CHECK(try_in_child(dir, "AMX") == 1); /* released: the other process gets it */
    remove_dir(dir);
}

void test_hold_lock_freed_when_its_holder_is_killed(void) {
    char dir[] = "/tmp/contract-hold-lock-XXXXXX";
    if (!mkdtemp(dir)) { CHECK(0); return; }
    int ready[2];
    if (pipe(ready) != 0) { CHECK(0); remove_dir(dir); return; }
    pid_t pid = fork();
    if (pid == 0) { /* takes the lock, says so, and waits to be killed without releasing it */
        close(ready[0]);
        char ok = hold_lock_acquire(dir, "AMX") >= 0 ? 'y' : 'n';
        if (write(ready[1], &ok, 1) != 1) _exit(2);
        for (;;) pause();
    }
    close(ready[1]);
    char got = 0;
    CHECK(pid > 0 && read(ready[0], &got, 1) == 1 && got == 'y');
    close(ready[0]);
    CHECK(hold_lock_try(dir, "AMX") == -1 && errno == EWOULDBLOCK);
    if (pid > 0) {
        kill(pid, SIGKILL);
        waitpid(pid, NULL, 0);
    }
    int fd = hold_lock_try(dir, "AMX"); /* the kernel released it with the dead holder */
    CHECK(fd >= 0);
    hold_lock_release(fd);
    remove_dir(dir);
}
