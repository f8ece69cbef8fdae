/* The crash report: at a crash (core.c on_crash_signal: SIGSEGV, SIGBUS, SIGFPE, SIGILL,
 * SIGABRT) one block on stderr that says where the module crashed, for the build service to map
 * to function, file and line (addr2line on the module's executable, built with -g):
 *
 *   ==contract-crash== module EST signal 11 SIGSEGV addr 0x0
 *   ==contract-crash== build-id 87975f83592c177c758e701ac13508592189f578
 *   ==contract-crash== frame 0 exe 0x1a2b
 *   ==contract-crash== frame 1 exe 0x1c40
 *   ==contract-crash== frame 2 libc.so.6 0x271ca
 *   ==contract-crash== end 3 frames
 *
 * Frame 0 is the instruction that faulted (from the signal's context; when the architecture's is
 * not known here, the handler's caller chain as backtrace() gives it), the others are return
 * addresses, innermost first, at most CRASH_FRAMES. Each is an offset in the object that holds
 * it: `exe` (the executable, the module's code and the runtime linked in: its offset from the
 * executable's load address, what addr2line takes for a PIE and a non-PIE alike), a shared
 * library's file name, or `?` and the address itself (an object loaded after start-up). The
 * build-id line (only when the executable has one: GNU ld's --build-id, gcc's default on Debian)
 * is the executable's NT_GNU_BUILD_ID note, in hex: a reader maps the frames only in an executable
 * of that build-id (the crash file the launcher saves in the run's logs: a rebuilt executable is
 * not the one that crashed).
 *
 * Async-signal-safe: the objects are listed at start-up (rt_crash_report_prepare:
 * dl_iterate_phdr, into static tables, locked with the rest by mlockall), and backtrace() is called
 * once there so that libgcc, which it loads at its first call, is loaded before any crash. The
 * handler only calls backtrace() (no allocation once loaded) and write(2). */
#define _GNU_SOURCE
#include <execinfo.h>
#include <link.h>
#include <signal.h>
#include <stdint.h>
#include <string.h>
#include <ucontext.h>
#include <unistd.h>
#include "internal.h"

#define CRASH_FRAMES 48      /* frames told, at most (a stack overflow has thousands) */
#define CRASH_OBJECTS 32     /* objects (executable and libraries) known at start-up */
#define CRASH_OBJECT_NAME 48 /* bytes of a library's file name kept */
#define CRASH_SEGMENTS 8     /* loaded segments of an object kept */

typedef struct {
    char name[CRASH_OBJECT_NAME]; /* "exe" for the executable, else the library's file name */
    uintptr_t base;                /* its load address (dlpi_addr) */
    int n_segments;
    uintptr_t lo[CRASH_SEGMENTS], hi[CRASH_SEGMENTS];
} CrashObject;

static CrashObject objects[CRASH_OBJECTS];
static int n_objects;
#define CRASH_BUILD_ID_MAX 64                /* bytes of a build-id kept (GNU ld's: 20) */
static char build_id_hex[2 * CRASH_BUILD_ID_MAX + 1]; /* the executable's, "" when it has none */

/* The executable's NT_GNU_BUILD_ID note, as hex into build_id_hex (its PT_NOTE segments, loaded). */
static void find_build_id(const struct dl_phdr_info *info)
{
    build_id_hex[0] = '\0';
    for (int i = 0; i < info->dlpi_phnum; i++) {
        if (info->dlpi_phdr[i].p_type != PT_NOTE) continue;
        const unsigned char *p = (const unsigned char *)(info->dlpi_addr + info->dlpi_phdr[i].p_vaddr);
        const unsigned char *end = p + info->dlpi_phdr[i].p_memsz;
        while (p + sizeof(ElfW(Nhdr)) <= end) {
            const ElfW(Nhdr) *n = (const ElfW(Nhdr) *)(const void *)p;
            size_t name = (n->n_namesz + 3u) & ~(size_t)3u, desc = (n->n_descsz + 3u) & ~(size_t)3u;
            const unsigned char *d = p + sizeof *n + name;
            if (d + desc > end) break;
            if (n->n_type == NT_GNU_BUILD_ID && n->n_namesz == 4 && memcmp(p + sizeof *n, "GNU", 4) == 0 &&
                n->n_descsz > 0 && n->n_descsz <= CRASH_BUILD_ID_MAX) {
                for (size_t k = 0; k < n->n_descsz; k++) {
                    build_id_hex[2 * k] = "0123456789abcdef"[d[k] >> 4];
                    build_id_hex[2 * k + 1] = "0123456789abcdef"[d[k] & 15];
                }
                build_id_hex[2 * n->n_descsz] = '\0';
                return;
            }
            p = d + desc;
        }
    }
}

const char *rt_crash_signal_name(int sig)
{
    switch (sig) {
    case SIGSEGV: return "SIGSEGV";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGABRT: return "SIGABRT";
    default: return "?";
    }
}

static int list_object(struct dl_phdr_info *info, size_t size, void *data)
{
    (void)size; (void)data;
    if (n_objects >= CRASH_OBJECTS) return 1;
    CrashObject *o = &objects[n_objects];
    const char *path = info->dlpi_name;
    if (n_objects == 0) { /* the first one is the executable */
        snprintf(o->name, sizeof o->name, "exe");
        find_build_id(info);
    } else {
        if (!path || !path[0]) return 0; /* the vDSO: no file */
        const char *slash = strrchr(path, '/');
        snprintf(o->name, sizeof o->name, "%s", slash ? slash + 1 : path);
        for (char *c = o->name; *c; c++) /* one word in the block */
            if (*c == ' ' || *c < 0x21 || *c > 0x7e) *c = '_';
    }
    o->base = (uintptr_t)info->dlpi_addr;
    o->n_segments = 0;
    for (int i = 0; i < info->dlpi_phnum && o->n_segments < CRASH_SEGMENTS; i++) {
        if (info->dlpi_phdr[i].p_type != PT_LOAD) continue;
        o->lo[o->n_segments] = o->base + info->dlpi_phdr[i].p_vaddr;
        o->hi[o->n_segments] = o->lo[o->n_segments] + info->dlpi_phdr[i].p_memsz;
        o->n_segments++;
    }
    n_objects++;
    return 0;
}

void rt_crash_report_prepare(void)
{
    void *warm[2];
    (void)backtrace(warm, 2); /* loads libgcc now: not in the handler */
    n_objects = 0;
    dl_iterate_phdr(list_object, NULL);
}

static const CrashObject *object_of(uintptr_t addr)
{
    for (int i = 0; i < n_objects; i++)
        for (int s = 0; s < objects[i].n_segments; s++)
            if (addr >= objects[i].lo[s] && addr < objects[i].hi[s]) return &objects[i];
    return NULL;
}

/* The block's text is put together in a static buffer (the handler runs once: the first crash). */
static char block[CRASH_FRAMES * 96 + 512];

static char *put(char *p, const char *s)
{
    while (*s && p < block + sizeof block - 1) *p++ = *s++;
    return p;
}

static char *put_dec(char *p, unsigned long v)
{
    char digits[24];
    int n = 0;
    do { digits[n++] = (char)('0' + v % 10); v /= 10; } while (v);
    while (n && p < block + sizeof block - 1) *p++ = digits[--n];
    return p;
}

static char *put_hex(char *p, uintptr_t v)
{
    char digits[2 * sizeof v];
    int n = 0;
    do { digits[n++] = "0123456789abcdef"[v & 15]; v >>= 4; } while (v);
    p = put(p, "0x");
    while (n && p < block + sizeof block - 1) *p++ = digits[--n];
    return p;
}

static char *put_frame(char *p, int i, uintptr_t addr)
{
    const CrashObject *o = object_of(addr);
    p = put(p, RT_CRASH_MARK " frame ");
    p = put_dec(p, (unsigned long)i);
    p = put(p, " ");
    p = put(p, o ? o->name : "?");
    p = put(p, " ");
    p = put_hex(p, o ? addr - o->base : addr);
    return put(p, "\n");
}

/* The instruction that faulted, from the signal's context (0: not known on this architecture). */
static uintptr_t fault_pc(const void *context)
{
    const ucontext_t *uc = context;
    if (!uc) return 0;
#if defined(__x86_64__)
    return (uintptr_t)uc->uc_mcontext.gregs[REG_RIP];
#elif defined(__i386__)
    return (uintptr_t)uc->uc_mcontext.gregs[REG_EIP];
#elif defined(__aarch64__)
    return (uintptr_t)uc->uc_mcontext.pc;
#else
    return 0;
#endif
}

void rt_crash_report_write(int sig, const siginfo_t *info, const void *context)
{
    void *frames[CRASH_FRAMES + 8];
    int n = backtrace(frames, (int)(sizeof frames / sizeof frames[0]));
    uintptr_t pc = fault_pc(context);
    /* the frames from the one that faulted on (the handler's own and the signal's trampoline
     * are above it); all of them when it is not found */
    int from = 0;
    if (pc)
        for (int i = 0; i < n; i++)
            if ((uintptr_t)frames[i] == pc) { from = i + 1; break; }
    char *p = block;
    p = put(p, RT_CRASH_MARK " module ");
    p = put(p, g_rt.name[0] ? g_rt.name : "?");
    p = put(p, " signal ");
    p = put_dec(p, (unsigned long)sig);
    p = put(p, " ");
    p = put(p, rt_crash_signal_name(sig));
    p = put(p, " addr ");
    /* si_addr is the fault's address only for a fault (si_code > 0): a signal a process sent
     * (abort(), kill) holds its sender's pid there */
    p = put_hex(p, info && info->si_code > 0 ? (uintptr_t)info->si_addr : 0);
    p = put(p, "\n");
    if (build_id_hex[0]) {
        p = put(p, RT_CRASH_MARK " build-id ");
        p = put(p, build_id_hex);
        p = put(p, "\n");
    }
    int told = 0;
    if (pc) p = put_frame(p, told++, pc);
    for (int i = pc ? from : 0; i < n && told < CRASH_FRAMES; i++) p = put_frame(p, told++, (uintptr_t)frames[i]);
    p = put(p, RT_CRASH_MARK " end ");
    p = put_dec(p, (unsigned long)told);
    p = put(p, " frames\n");
    for (const char *w = block; w < p;) { /* a pipe may take it in parts */
        ssize_t k = write(2, w, (size_t)(p - w));
        if (k <= 0) break;
        w += k;
    }
}
