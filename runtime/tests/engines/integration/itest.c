/*
 * itest.c — integration test of the engines with real processes through libmodule: runs
 * contract-launch with ORD (iord.c), the supervisor ISU (isup.c) and three synchronous
 * modules IMA/IMB/IMC (imod.c), starts ISU.go, and checks what the modules recorded:
 * parameterisation from the supervisor's local, precedence in every cycle, absolute-time
 * releases, `* 1` / `* 2` deliveries, deactivation, ORD:1 reaching the supervisor.
 * Second scenario (inest.c, amod.c): GLT activates SLV.work, which runs an event schema with
 * the asynchronous AMX, ends on its third event, notifies GLT, which stops SLV.work.
 * Third scenario (ishare.c, amod.c): two supervisors SHA and SHB use AMX through event schemas:
 * AMX is started once, survives the end of SHA's schema and is stopped at the end of SHB's.
 * Usage: itest <dir with ORD ISU IMA IMB IMC GLT SLV AMX SHA SHB> <contract-launch>. Prints "N passed, N failed".
 */
#define _GNU_SOURCE
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static int passed, failed;

static void check(int ok, const char *what) {
    printf("%s %s\n", ok ? "ok  " : "FAIL", what);
    if (ok) passed++;
    else failed++;
}

typedef struct Trace {
    long long start[64], end[64];
    long got[64], param;
    int nstart, nend, ngot;
} Trace;

static int read_trace(const char *dir, const char *name, Trace *t) {
    memset(t, 0, sizeof *t);
    t->param = -1;
    char path[600], line[128];
    snprintf(path, sizeof path, "%s/%s.trace", dir, name);
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    while (fgets(line, sizeof line, f)) {
        long long v;
        if (sscanf(line, "start %lld", &v) == 1 && t->nstart < 64) t->start[t->nstart++] = v;
        else if (sscanf(line, "end %lld", &v) == 1 && t->nend < 64) t->end[t->nend++] = v;
        else if (sscanf(line, "got %lld", &v) == 1 && t->ngot < 64) t->got[t->ngot++] = (long)v;
        else if (sscanf(line, "param %lld", &v) == 1) t->param = (long)v;
    }
    fclose(f);
    return 0;
}

static char *slurp(const char *path) {
    FILE *f = fopen(path, "r");
    if (!f) return NULL;
    char *buf = malloc(1 << 16);
    if (!buf) {
        fclose(f);
        return NULL;
    }
    size_t n = fread(buf, 1, (1 << 16) - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

int main(int argc, char **argv) {
    if (argc < 3) {
        fprintf(stderr, "usage: itest <bin dir> <contract-launch>\n");
        return 2;
    }
    char tmpl[] = "/tmp/contract-engines-itest-XXXXXX";
    char *root = mkdtemp(tmpl);
    if (!root) { perror("mkdtemp"); return 2; }
    char out[128], run[128], logs[128], launch_out[128], stats[160];
    snprintf(out, sizeof out, "%s/out", root);
    snprintf(run, sizeof run, "%s/run", root);
    snprintf(logs, sizeof logs, "%s/logs", root);
    snprintf(launch_out, sizeof launch_out, "%s/launch.txt", root);
    snprintf(stats, sizeof stats, "%s/ord.json", out);
    if (mkdir(out, 0700) != 0) { perror(out); return 2; }
    setenv("ITEST_OUT", out, 1);
    setenv("CONTRACT_ORD_STATS", stats, 1);
    char exe[5][512];
    const char *names[5] = {"ORD", "ISU", "IMA", "IMB", "IMC"};
    for (int i = 0; i < 5; i++) snprintf(exe[i], sizeof exe[i], "%s/%s", argv[1], names[i]);
    pid_t pid = fork();
    if (pid == 0) {
        FILE *o = freopen(launch_out, "w", stdout);
        if (!o || dup2(fileno(stdout), 2) < 0) _exit(127);
        execl(argv[2], argv[2], "--run-dir", run, "--log-dir", logs, "--start", "ISU.go()",
              "--duration", "0.6", exe[0], exe[1], exe[2], exe[3], exe[4], (char *)NULL);
        _exit(127);
    }
    int st = 0;
    waitpid(pid, &st, 0);
    check(WIFEXITED(st) && WEXITSTATUS(st) == 0, "contract-launch ran the architecture and stopped it cleanly");

    Trace a, b, c;
    int ra = read_trace(out, "IMA", &a), rb = read_trace(out, "IMB", &b), rc = read_trace(out, "IMC", &c);
    check(ra == 0 && rb == 0 && rc == 0, "the three modules wrote their traces");
    check(a.param == 7, "IMA parameterised with gain = 7 (the supervisor's local through ORD)");
    /* R1 active from 10 ms to 310 ms, period 20 ms: 15 cycles (14..16 with start-up slack) */
    check(a.nstart >= 14 && a.nstart <= 16, "IMA released once per period while ISC was active, none after");
    check(b.nstart == a.nstart && c.nstart == a.nstart, "IMB and IMC released in every cycle");
    int prec = a.nstart > 0 && a.nend == a.nstart;
    for (int k = 0; k < a.nstart && k < b.nstart && k < c.nstart; k++)
        if (b.start[k] < a.end[k] || c.start[k] < a.end[k]) prec = 0;
    check(prec, "precedence IMA -> IMB, IMA -> IMC respected in every cycle");
    int periodic = a.nstart > 1;
    for (int k = 1; k < a.nstart; k++) {
        long long ideal = a.start[0] + (long long)k * 20000000LL, dev = a.start[k] - ideal;
        if (dev < -2000000 || dev > 2000000) periodic = 0;
    }
    check(periodic, "releases at absolute ticks start + k * 20 ms (within 2 ms, no drift)");
    int ones = b.ngot == a.nstart;
    for (int k = 0; k < b.ngot; k++) if (b.got[k] != k + 1) ones = 0;
    check(ones, "IMA:0 -> IMB:0 * 1 delivers every activation's value");
    int twos = c.ngot == a.nstart / 2;
    for (int k = 0; k < c.ngot; k++) if (c.got[k] != 2 * (k + 1)) twos = 0;
    check(twos, "IMA:0 -> IMC:0 * 2 delivers every second activation's value");
    char *txt = slurp(launch_out);
    check(txt && strstr(txt, "[ORD] conflict: ICF shares a module with active ISC (ORD:1)"),
          "ORD refuses ICF (shares IMB with ISC)");
    check(txt && strstr(txt, "[ISU] rule go.R3 active"), "ORD:1 with ord_schema == \"ICF\" reached the supervisor");
    check(txt && strstr(txt, "[ORD] deactivate ISC"), "R1's postcondition deactivates ISC");
    char *js = slurp(stats);
    check(js && strstr(js, "\"deadline_misses\": 0") && strstr(js, "\"overruns\": 0"),
          "no deadline miss, no overrun");
    if (failed) fprintf(stderr, "launcher output (scheduler scenario):\n%s\n", txt ? txt : "(none)");

    /* scenario 2: nested supervisors, event schema, asynchronous module, notify */
    char run2[160], out2[160];
    snprintf(run2, sizeof run2, "%s/run2", root);
    snprintf(out2, sizeof out2, "%s/launch2.txt", root);
    char exe2[3][512];
    const char *names2[3] = {"GLT", "SLV", "AMX"};
    for (int i = 0; i < 3; i++) snprintf(exe2[i], sizeof exe2[i], "%s/%s", argv[1], names2[i]);
    pid = fork();
    if (pid == 0) {
        FILE *o = freopen(out2, "w", stdout);
        if (!o || dup2(fileno(stdout), 2) < 0) _exit(127);
        execl(argv[2], argv[2], "--run-dir", run2, "--log-dir", logs, "--start", "GLT.top()",
              "--duration", "0.5", exe2[0], exe2[1], exe2[2], (char *)NULL);
        _exit(127);
    }
    waitpid(pid, &st, 0);
    check(WIFEXITED(st) && WEXITSTATUS(st) == 0, "nested supervisors: architecture ran and stopped cleanly");
    char amx_path[200];
    snprintf(amx_path, sizeof amx_path, "%s/AMX.trace", out);
    char *amx = slurp(amx_path);
    check(amx && strcmp(amx, "param 2\nstart\npost 2\npost 4\npost 6\nstop\n") == 0,
          "event schema: AMX parameterised (GLT's value through SLV's local), started, stopped after W1");
    char *txt2 = slurp(out2);
    const char *order[] = {"[GLT] rule top.T1 active", "[SLV] function work started", "[SLV] rule work.W1 active",
                           "[SLV] rule work.W1 inactive", "[SLV] rule work.W2 active",
                           "[SLV] function work stopped", NULL};
    int in_order = txt2 != NULL;
    const char *at = txt2;
    for (int i = 0; order[i] && in_order; i++) {
        const char *p = strstr(at, order[i]);
        if (!p) in_order = 0;
        else at = p;
    }
    check(in_order, "SLV.work started by GLT, W1 -> W2 on endof, stopped by GLT");
    check(txt2 && strstr(txt2, "[GLT] rule top.T1 inactive"), "SLV's notify reached GLT (T1 ended)");
    if (failed) fprintf(stderr, "launcher output (nested scenario):\n%s\n", txt2 ? txt2 : "(none)");

    /* scenario 3: a module shared by two supervisors' event schemas */
    char run3[160], out3[160], trace3[160];
    snprintf(run3, sizeof run3, "%s/run3", root);
    snprintf(out3, sizeof out3, "%s/launch3.txt", root);
    snprintf(trace3, sizeof trace3, "%s/out3", root);
    if (mkdir(trace3, 0700) != 0) { perror(trace3); return 2; }
    setenv("ITEST_OUT", trace3, 1);
    char exe3[3][512];
    const char *names3[3] = {"SHA", "SHB", "AMX"};
    for (int i = 0; i < 3; i++) snprintf(exe3[i], sizeof exe3[i], "%s/%s", argv[1], names3[i]);
    pid = fork();
    if (pid == 0) {
        FILE *o = freopen(out3, "w", stdout);
        if (!o || dup2(fileno(stdout), 2) < 0) _exit(127);
        execl(argv[2], argv[2], "--run-dir", run3, "--log-dir", logs, "--start", "SHA.top()",
              "--duration", "0.5", exe3[0], exe3[1], exe3[2], (char *)NULL);
        _exit(127);
    }
    waitpid(pid, &st, 0);
    check(WIFEXITED(st) && WEXITSTATUS(st) == 0, "shared module: architecture ran and stopped cleanly");
    snprintf(amx_path, sizeof amx_path, "%s/AMX.trace", trace3);
    char *amx3 = slurp(amx_path);
    int starts = 0, stops = 0, posts = 0;
    for (const char *p = amx3; p && *p; p = strchr(p, '\n') ? strchr(p, '\n') + 1 : "") {
        if (strncmp(p, "start\n", 6) == 0) starts++;
        else if (strncmp(p, "stop\n", 5) == 0) stops++;
        else if (strncmp(p, "post ", 5) == 0) posts++;
    }
    check(starts == 1, "AMX started once: SHB found it running (started by SHA) and did not start it again");
    /* SHA's schema ends at 150 ms (~14 posts), SHB's at ~320 ms (~31 posts) */
    check(stops == 1 && posts >= 22 && posts <= 45,
          "AMX kept running after SHA's schema ended, stopped once when SHB's (its last user) ended");
    char *txt3 = slurp(out3);
    check(txt3 && strstr(txt3, "[SHA] rule top.A1 inactive") && strstr(txt3, "[SHB] rule use.B1 inactive"),
          "both schemas were activated and deactivated");
    struct stat rst;
    check(stat(run3, &rst) != 0, "no hold file (or other runtime file) left in the run directory");
    if (failed) fprintf(stderr, "launcher output (shared module scenario):\n%s\nAMX trace:\n%s\n", txt3 ? txt3 : "(none)",
                        amx3 ? amx3 : "(none)");
    if (failed) {
        fprintf(stderr, "kept %s for inspection\n", root);
    } else {
        char cmd[300];
        snprintf(cmd, sizeof cmd, "rm -rf '%s'", root);
        if (system(cmd) != 0) fprintf(stderr, "could not remove %s\n", root);
    }
    printf("%d passed, %d failed\n", passed, failed);
    return failed ? 1 : 0;
}
