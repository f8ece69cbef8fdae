/* itest_support.c — see itest_support.h. */
#define _GNU_SOURCE
#include "itest_support.h"

#include <dirent.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

static int passed, failed;

int check(int ok, const char *what) {
    printf("%s %s\n", ok ? "ok  " : "FAIL", what);
    if (ok) passed++;
    else failed++;
    return ok;
}

int itest_failed(void) { return failed; }
int itest_passed(void) { return passed; }

static int make_dir(const char *path) {
    if (mkdir(path, 0700) == 0) return 0;
    perror(path);
    return -1;
}

int scenario_begin(Scenario *s, const char *root, const char *name) {
    char base[400];
    snprintf(base, sizeof base, "%s/%s", root, name);
    snprintf(s->run, sizeof s->run, "%s/run", base);
    snprintf(s->logs, sizeof s->logs, "%s/logs", base);
    snprintf(s->out, sizeof s->out, "%s/out", base);
    snprintf(s->launch, sizeof s->launch, "%s/launch.txt", base);
    snprintf(s->stats, sizeof s->stats, "%s/ord.json", s->out);
    s->failed_before = failed;
    s->stop_first = NULL;
    if (make_dir(base) != 0 || make_dir(s->logs) != 0 || make_dir(s->out) != 0) {
        char what[500];
        snprintf(what, sizeof what, "scenario %s set up in %s", name, base);
        return check(0, what);
    }
    setenv("ITEST_OUT", s->out, 1);
    setenv("CONTRACT_ORD_STATS", s->stats, 1);
    return 1;
}

int scenario_failed(const Scenario *s) { return failed > s->failed_before; }

pid_t scenario_spawn(const Scenario *s, const char *bin_dir, const char *launcher, const char *start,
                     const char *duration, const char *const *names) {
    enum { MAX_EXE = 16 };
    static char exe[MAX_EXE][512];
    const char *argv[MAX_EXE + 14];
    int n = 0;
    argv[n++] = launcher;
    argv[n++] = "--run-dir";
    argv[n++] = s->run;
    argv[n++] = "--log-dir";
    argv[n++] = s->logs;
    argv[n++] = "--start";
    argv[n++] = start;
    if (duration) {
        argv[n++] = "--duration";
        argv[n++] = duration;
    }
    if (s->stop_first) {
        argv[n++] = "--stop-first";
        argv[n++] = s->stop_first;
    }
    for (int i = 0; names[i] && i < MAX_EXE; i++) {
        snprintf(exe[i], sizeof exe[i], "%s/%s", bin_dir, names[i]);
        argv[n++] = exe[i];
    }
    argv[n] = NULL;
    pid_t pid = fork();
    if (pid < 0) perror("fork");
    if (pid == 0) {
        FILE *o = freopen(s->launch, "w", stdout);
        if (!o || dup2(fileno(stdout), 2) < 0) _exit(127);
        execv(launcher, (char *const *)argv);
        _exit(127);
    }
    return pid;
}

int scenario_launch(const Scenario *s, const char *bin_dir, const char *launcher, const char *start,
                    const char *duration, const char *const *names) {
    pid_t pid = scenario_spawn(s, bin_dir, launcher, start, duration, names);
    if (pid < 0) return 0;
    int st = 0;
    if (waitpid(pid, &st, 0) != pid) return 0;
    return WIFEXITED(st) && WEXITSTATUS(st) == 0;
}

void say_output_tail(const char *scenario, const char *txt, size_t max) {
    size_t n = txt ? strlen(txt) : 0;
    fprintf(stderr, "launcher output (%s scenario, last %zu bytes):\n%s\n", scenario, max, txt ? txt + (n > max ? n - max : 0) : "(none)");
}

char *slurp(const char *path) {
    FILE *f = fopen(path, "r");
    if (!f) return NULL;
    enum { LIMIT = 1 << 20 };
    char *buf = malloc(LIMIT);
    if (!buf) {
        fclose(f);
        return NULL;
    }
    size_t n = fread(buf, 1, LIMIT - 1, f);
    buf[n] = '\0';
    fclose(f);
    return buf;
}

char *read_csv_log(const Scenario *s, const char *module) {
    DIR *d = opendir(s->logs);
    if (!d) return NULL;
    size_t n = strlen(module);
    char path[1024] = "";
    struct dirent *e;
    while ((e = readdir(d)) != NULL) {
        size_t l = strlen(e->d_name);
        if (strncmp(e->d_name, module, n) == 0 && e->d_name[n] == '_' && l > 4 &&
            strcmp(e->d_name + l - 4, ".csv") == 0) {
            snprintf(path, sizeof path, "%s/%s", s->logs, e->d_name);
            break;
        }
    }
    closedir(d);
    return path[0] ? slurp(path) : NULL;
}

long json_number(const char *json, const char *key) {
    char pat[64];
    snprintf(pat, sizeof pat, "\"%s\": ", key);
    const char *p = json ? strstr(json, pat) : NULL;
    return p ? strtol(p + strlen(pat), NULL, 10) : -1;
}

int count_of(const char *s, const char *text) {
    int n = 0;
    for (const char *p = s ? strstr(s, text) : NULL; p; p = strstr(p + 1, text)) n++;
    return n;
}

int lines_with(const char *s, const char *a, const char *b) {
    int n = 0;
    for (const char *line = s; line && *line;) {
        const char *end = strchr(line, '\n');
        size_t len = end ? (size_t)(end - line) : strlen(line);
        const char *pa = strstr(line, a), *pb = strstr(line, b);
        if (pa && pb && pa < line + len && pb < line + len) n++;
        line = end ? end + 1 : NULL;
    }
    return n;
}

long long sum_of_key(const char *s, const char *text, const char *key) {
    long long sum = 0;
    size_t klen = strlen(key);
    for (const char *p = s ? strstr(s, text) : NULL; p; p = strstr(p + 1, text)) {
        const char *end = strchr(p, '\n');
        for (const char *k = strstr(p, key); k && (!end || k < end); k = strstr(k + 1, key))
            if (k[klen] == '=' && (k[-1] == ' ' || k[-1] == ',')) { sum += atoll(k + klen + 1); break; }
    }
    return sum;
}

long long csv_time_of(const char *csv, const char *from, const char *text, const char **at) {
    if (!csv) return -1;
    const char *p = from ? from : csv;
    const char *hit = strstr(p, text);
    if (!hit) return -1;
    const char *line = hit;
    while (line > csv && line[-1] != '\n') line--;
    long long t = -1;
    if (sscanf(line, "%lld,", &t) != 1) return -1;
    if (at) {
        const char *nl = strchr(hit, '\n');
        *at = nl ? nl + 1 : hit + strlen(hit);
    }
    return t;
}

int read_trace(const char *dir, const char *name, Trace *t) {
    memset(t, 0, sizeof *t);
    t->param = -1;
    t->slow = -1;
    char path[600], line[128];
    snprintf(path, sizeof path, "%s/%s.trace", dir, name);
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    while (fgets(line, sizeof line, f)) {
        long long v, id;
        int k = sscanf(line, "start %lld %lld", &v, &id);
        if (k >= 1 && t->nstart < TRACE_MAX) {
            t->id[t->nstart] = k == 2 ? (long)id : 0;
            t->start[t->nstart++] = v;
        } else if (sscanf(line, "end %lld", &v) == 1 && t->nend < TRACE_MAX) {
            t->end[t->nend++] = v;
        } else if (sscanf(line, "got %lld", &v) == 1 && t->ngot < TRACE_MAX) {
            t->got[t->ngot++] = (long)v;
        } else if (sscanf(line, "param %lld", &v) == 1) {
            t->param = (long)v;
        } else if (strncmp(line, "slow", 4) == 0) {
            t->slow = t->nstart - 1;
        }
    }
    fclose(f);
    return 0;
}
