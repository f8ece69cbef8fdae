/* prio_claims.c — see prio_claims.h. */
#define _GNU_SOURCE
#include "prio_claims.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "libmodule/libmodule.h"
#include "sup_claims.h"

/* one claim file as read back */
typedef struct ClaimFile {
    long long t; /* its order across supervisors */
    char owner[CONTRACT_NAME_MAX];
    uint32_t id;
    int prio, before;
} ClaimFile;

static int claim_path(char *buf, size_t size, const char *owner, const char *module, uint32_t id) {
    int n = snprintf(buf, size, "%s/%s.prio-%s-%u.hold", ContractRunDir(), owner, module, id);
    return n > 0 && (size_t)n < size ? 0 : -1;
}

static int write_claim(const char *path, long long t, int prio, int before) {
    FILE *f = fopen(path, "w");
    if (!f) return -1;
    int ok = fprintf(f, "%lld %d %d\n", t, prio, before) > 0;
    return fclose(f) == 0 && ok ? 0 : -1;
}

int prio_claims_record(const char *module, uint32_t id, int prio, int before) {
    char path[4200];
    if (claim_path(path, sizeof path, ContractSelfName(), module, id) != 0 ||
        write_claim(path, (long long)GetTime(), prio, before) != 0) {
        ContractLog("module_priority", module, -1, 0, "cannot record the change in the run directory");
        return -1;
    }
    return 0;
}

static int by_time(const void *a, const void *b) {
    const ClaimFile *x = a, *y = b;
    return (x->t > y->t) - (x->t < y->t);
}

/* every claim on `module`, in time order, into s; their times into *times (same order) */
static int load_claims(const char *module, SupClaims *s, long long **times) {
    char infix[CONTRACT_NAME_MAX + 8];
    snprintf(infix, sizeof infix, ".prio-%s-", module);
    DIR *d = opendir(ContractRunDir());
    if (!d) return -1;
    int n = 0, cap = 0;
    ClaimFile *fs = NULL;
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        const char *at = strstr(e->d_name, infix);
        unsigned id;
        int used = 0;
        if (!at || (size_t)(at - e->d_name) >= CONTRACT_NAME_MAX ||
            sscanf(at + strlen(infix), "%u%n", &id, &used) != 1 || strcmp(at + strlen(infix) + used, ".hold") != 0)
            continue;
        if (n == cap) {
            ClaimFile *nf = realloc(fs, (size_t)(cap = cap ? cap * 2 : 8) * sizeof *fs);
            if (!nf) break;
            fs = nf;
        }
        char path[4200];
        snprintf(path, sizeof path, "%s/%s", ContractRunDir(), e->d_name);
        FILE *f = fopen(path, "r");
        ClaimFile *c = &fs[n];
        int ok = f && fscanf(f, "%lld %d %d", &c->t, &c->prio, &c->before) == 3;
        if (f) fclose(f);
        if (!ok) continue;
        snprintf(c->owner, sizeof c->owner, "%.*s", (int)(at - e->d_name), e->d_name);
        c->id = id;
        n++;
    }
    closedir(d);
    if (n) qsort(fs, (size_t)n, sizeof *fs, by_time);
    *times = malloc((size_t)(n ? n : 1) * sizeof **times);
    for (int i = 0; i < n; i++) {
        sup_claims_push_priority(s, fs[i].owner, module, fs[i].id, fs[i].prio, fs[i].before);
        if (*times) (*times)[i] = fs[i].t;
    }
    free(fs);
    return *times ? n : -1;
}

int prio_claims_release(const char *module, uint32_t id, int *restore, char *later_owner,
                        size_t later_size) {
    SupClaims s;
    memset(&s, 0, sizeof s);
    long long *times = NULL;
    if (load_claims(module, &s, &times) < 0) {
        free(times);
        sup_claims_free(&s);
        return -1;
    }
    int later = -1, mine_at = -1;
    for (int i = 0; i < s.nprio; i++)
        if (s.prio[i].id == id && strcmp(s.prio[i].owner, ContractSelfName()) == 0) mine_at = i;
    int r = sup_claims_drop_priority(&s, ContractSelfName(), module, id, restore, &later);
    char path[4200];
    if (claim_path(path, sizeof path, ContractSelfName(), module, id) == 0) unlink(path);
    if (r == 0 && later >= 0) { /* the later claim now restores what this one found */
        const SupPrioClaim *p = &s.prio[later];
        long long t = times[later >= mine_at ? later + 1 : later]; /* times still hold mine */
        if (claim_path(path, sizeof path, p->owner, module, p->id) == 0)
            write_claim(path, t, p->prio, p->before);
        if (later_owner) snprintf(later_owner, later_size, "%s", p->owner);
    }
    free(times);
    sup_claims_free(&s);
    return r;
}
