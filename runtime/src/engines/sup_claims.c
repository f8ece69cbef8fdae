/* sup_claims.c — see sup_claims.h. */
#include "sup_claims.h"
#include "engine_array.h"

#include <stdlib.h>
#include <string.h>

static int grow(void **p, int *cap, int need, size_t elem) { return engine_grow(p, cap, need, elem, 8); }

static void copy_name(char *dst, size_t n, const char *src) {
    size_t l = strlen(src);
    if (l >= n) l = n - 1;
    memcpy(dst, src, l);
    dst[l] = '\0';
}

int sup_claims_push_priority(SupClaims *s, const char *owner, const char *module, uint32_t id,
                             int prio, int before) {
    if (grow((void **)&s->prio, &s->capprio, s->nprio + 1, sizeof *s->prio) != 0) return -1;
    SupPrioClaim *p = &s->prio[s->nprio++];
    copy_name(p->owner, sizeof p->owner, owner);
    copy_name(p->module, sizeof p->module, module);
    p->id = id;
    p->prio = prio;
    p->before = before;
    return 0;
}

int sup_claims_drop_priority(SupClaims *s, const char *owner, const char *module, uint32_t id,
                             int *restore, int *later) {
    int i = -1;
    for (int k = 0; k < s->nprio; k++)
        if (s->prio[k].id == id && strcmp(s->prio[k].module, module) == 0 &&
            strcmp(s->prio[k].owner, owner) == 0)
            i = k;
    if (i < 0) return -1;
    int next = -1; /* the module's next claim, made after this one */
    for (int k = i + 1; k < s->nprio && next < 0; k++)
        if (strcmp(s->prio[k].module, module) == 0) next = k;
    if (next >= 0) s->prio[next].before = s->prio[i].before;
    else *restore = s->prio[i].before;
    memmove(&s->prio[i], &s->prio[i + 1], (size_t)(s->nprio - i - 1) * sizeof *s->prio);
    s->nprio--;
    if (next >= 0 && later) *later = next - 1;
    return next < 0 ? 1 : 0;
}

static int same_flow(const ContractEventFlow *a, const ContractEventFlow *b) {
    return a->src_port == b->src_port && a->dst_port == b->dst_port &&
           strcmp(a->src_module, b->src_module) == 0 && strcmp(a->dst_module, b->dst_module) == 0;
}

int sup_claims_flow_use(SupClaims *s, const ContractEventFlow *flow, int delta) {
    for (int k = 0; k < s->nflows; k++) {
        if (!same_flow(s->flows[k].flow, flow)) continue;
        s->flows[k].users += delta;
        if (s->flows[k].users < 0) s->flows[k].users = 0;
        return s->flows[k].users;
    }
    if (delta <= 0) return 0;
    if (grow((void **)&s->flows, &s->capflows, s->nflows + 1, sizeof *s->flows) != 0)
        return delta; /* out of memory: counted as its only user (disconnected by its undo) */
    s->flows[s->nflows++] = (SupFlowUse){flow, delta};
    return delta;
}

void sup_claims_free(SupClaims *s) {
    free(s->prio);
    free(s->flows);
    memset(s, 0, sizeof *s);
}
