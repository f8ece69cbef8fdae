/* hold_lock.c — see hold_lock.h. */
#define _GNU_SOURCE
#include "hold_lock.h"

#include <errno.h>
#include <fcntl.h>
#include <stdio.h>
#include <sys/file.h>
#include <unistd.h>

static int lock(const char *dir, const char *module, int how) {
    char path[4200];
    int n = snprintf(path, sizeof path, "%s/holds-%s.hold", dir, module);
    if (n < 0 || (size_t)n >= sizeof path) {
        errno = ENAMETOOLONG;
        return -1;
    }
    int fd = open(path, O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) return -1;
    int rc;
    while ((rc = flock(fd, how)) != 0 && errno == EINTR) {
    }
    if (rc != 0) {
        int e = errno;
        close(fd);
        errno = e;
        return -1;
    }
    return fd;
}

int hold_lock_acquire(const char *dir, const char *module) { return lock(dir, module, LOCK_EX); }

int hold_lock_try(const char *dir, const char *module) { return lock(dir, module, LOCK_EX | LOCK_NB); }

void hold_lock_release(int fd) {
    if (fd < 0) return;
    flock(fd, LOCK_UN);
    close(fd);
}
