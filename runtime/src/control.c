/* The generic control tool behind every generated control<M> (see libmodule/control.h). */
#define _GNU_SOURCE
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>
#include "contract/vocabulary.h"
#include "libmodule/control.h"
#include "tools.h"

#define ACK_WAIT_NS 2000000000LL

static void control_usage(const char *prog, const char *module)
{
    fprintf(stderr,
            "usage: %s [--run-dir DIR] COMMAND   (controls module %s)\n"
            "  start [FUNCTION ['p=v,...']]   start the module (a supervisor: one of its functions)\n"
            "  stop | kill | status\n"
            "  setparam PORT VALUE            e.g. setparam 0 '{1.0,2.0,3.0}'\n"
            "The run directory is --run-dir DIR or $CONTRACT_RUN_DIR.\n",
            prog, module);
}

static void list_ports(const ControlParam params[])
{
    fprintf(stderr, "  parameter ports:");
    int any = 0;
    for (int i = 0; params && params[i].Parse; i++, any = 1) fprintf(stderr, " %d (%s)", params[i].Port, params[i].TypeName);
    fprintf(stderr, "%s\n", any ? "" : " none");
}

static int wait_ack(const char *module, int id, int mask, RequestMessage *ack)
{
    return WaitForAck(module, id, mask, GetTime() + ACK_WAIT_NS, ack);
}

/* ControlMainTyped: the descriptors of the parameter ports (NULL for ControlMain). */
static const ControlTypedParam *typed_params;

static const ContractType *typed_param(long port)
{
    for (int i = 0; typed_params && typed_params[i].Type; i++)
        if (typed_params[i].Port == port) return typed_params[i].Type;
    return NULL;
}

/* the Parse of a typed port in the ControlParam list (do_setparam parses through the descriptor) */
static int typed_placeholder(void *dst, char *text)
{
    (void)dst;
    (void)text;
    return -1;
}

static int do_setparam(const char *module, const ControlParam params[], const char *port_text, const char *value)
{
    char *end;
    errno = 0;
    long port = strtol(port_text, &end, 10);
    if (errno || *end || end == port_text || port < 0 || port > 255) {
        fprintf(stderr, "control %s: bad parameter port '%s': expected a number\n", module, port_text);
        list_ports(params);
        return CONTROL_EXIT_BADVALUE;
    }
    const ControlParam *p = NULL;
    for (int i = 0; params && params[i].Parse; i++) if (params[i].Port == port) p = &params[i];
    if (!p) {
        fprintf(stderr, "control %s: %s has no parameter port %ld\n", module, module, port);
        list_ports(params);
        return CONTROL_EXIT_BADVALUE;
    }
    unsigned char *buf = calloc(1, p->Size + 1);
    char *text = strdup(value);
    if (!buf || !text) { free(buf); free(text); return CONTROL_EXIT_ERROR; }
    const ContractType *type = typed_param(port);
    int n = type ? contract_value_get(type, buf, text) : p->Parse(buf, text);
    int ok = n >= 0 && only_blanks_remain(text + n);
    if (!ok) {
        fprintf(stderr, "control %s: bad value '%s' for parameter port %ld of type %s\n", module, value, port, p->TypeName);
        free(buf);
        free(text);
        return CONTROL_EXIT_BADVALUE;
    }
    char shown[1024];
    if (type) contract_value_format(shown, sizeof shown, type, buf); /* the value as it was read */
    int rc = SendSetParam(module, (int)port, buf, p->Size, ACK_NOTHING, -1);
    free(buf);
    free(text);
    if (rc != CONTRACT_OK) return rc == CONTRACT_ETOOBIG ? CONTROL_EXIT_BADVALUE : CONTROL_EXIT_ERROR;
    printf("%s: parameter %ld set to %s\n", module, port, type ? shown : value);
    return CONTROL_EXIT_OK;
}

int ControlMain(const char *module, const ControlParam params[], int argc, char *argv[])
{
    const char *prog = argc > 0 ? argv[0] : "control";
    int i = 1;
    while (i < argc && strncmp(argv[i], "--", 2) == 0) {
        if (strcmp(argv[i], "--run-dir") == 0 && i + 1 < argc) { setenv("CONTRACT_RUN_DIR", argv[i + 1], 1); i += 2; }
        else if (strcmp(argv[i], "--help") == 0) { control_usage(prog, module); return CONTROL_EXIT_OK; }
        else { fprintf(stderr, "control %s: unknown option %s\n", module, argv[i]); control_usage(prog, module); return CONTROL_EXIT_USAGE; }
    }
    if (i >= argc) { control_usage(prog, module); return CONTROL_EXIT_USAGE; }
    const char *cmd = argv[i++];
    int nargs = argc - i;
    const char *dir = getenv("CONTRACT_RUN_DIR");
    struct stat st;
    if (!dir || !*dir) {
        fprintf(stderr, "control %s: no run directory: pass --run-dir DIR or set CONTRACT_RUN_DIR\n", module);
        return CONTROL_EXIT_UNKNOWN;
    }
    if (stat(dir, &st) != 0 || !S_ISDIR(st.st_mode)) {
        fprintf(stderr, "control %s: run directory %s does not exist (is the architecture running?)\n", module, dir);
        return CONTROL_EXIT_UNKNOWN;
    }
    int known = !strcmp(cmd, "start") || !strcmp(cmd, "stop") || !strcmp(cmd, "kill") || !strcmp(cmd, "status") ||
                !strcmp(cmd, "setparam");
    if (!known) { fprintf(stderr, "control %s: unknown command '%s'\n", module, cmd); control_usage(prog, module); return CONTROL_EXIT_USAGE; }
    if ((!strcmp(cmd, "setparam") && nargs != 2) || (!strcmp(cmd, "start") && nargs > 2) ||
        ((!strcmp(cmd, "stop") || !strcmp(cmd, "kill") || !strcmp(cmd, "status")) && nargs != 0)) {
        fprintf(stderr, "control %s: wrong number of arguments for '%s'\n", module, cmd);
        control_usage(prog, module);
        return CONTROL_EXIT_USAGE;
    }
    int state = ModuleState(module);
    if (state == CONTRACT_EUNKNOWN || state == CONTRACT_EINVAL) {
        fprintf(stderr, "control %s: unknown module %s: it is not running in %s\n", module, module, dir);
        return CONTROL_EXIT_UNKNOWN;
    }
    if (state == CONTRACT_ENOTRUNNING) {
        fprintf(stderr, "control %s: module %s is not running (its mailbox in %s is stale: it crashed)\n", module, module, dir);
        return CONTROL_EXIT_NOTRUNNING;
    }
    char self[CONTRACT_NAME_MAX];
    snprintf(self, sizeof self, "control%.40s-%ld", module, (long)getpid());
    if (ContractClientInit(self) != 0) return CONTROL_EXIT_ERROR;
    if (!strcmp(cmd, "setparam")) return do_setparam(module, params, argv[i], argv[i + 1]);
    RequestMessage *ack = malloc(sizeof *ack);
    if (!ack) return CONTROL_EXIT_ERROR;
    int code = CONTROL_EXIT_OK, rc, r;
    if (!strcmp(cmd, "status")) {
        char text[1024];
        rc = QueryStatus(module, text, sizeof text, GetTime() + ACK_WAIT_NS);
        if (rc == CONTRACT_OK) printf("%s\n", text);
        else { fprintf(stderr, "control %s: no status answer within 2 s (%s)\n", module, ContractStrError(rc)); code = CONTROL_EXIT_NOACK; }
    } else if (!strcmp(cmd, "start")) {
        const char *fn = nargs > 0 ? argv[i] : NULL, *args = nargs > 1 ? argv[i + 1] : NULL;
        rc = SendStartFunction(module, fn, args, ACK_START | ACK_NOTDONE, 1);
        if (rc != CONTRACT_OK) code = CONTROL_EXIT_ERROR;
        else if ((r = wait_ack(module, 1, ACK_START | ACK_NOTDONE, ack)) == 1 && ack->Param.Ack.Ack == ACK_START)
            printf("%s: started%s%s\n", module, fn ? " " : "", fn ? fn : "");
        else if (r == 1) { fprintf(stderr, "control %s: %s refused the start request\n", module, module); code = CONTROL_EXIT_NOACK; }
        else { fprintf(stderr, "control %s: start sent, but no acknowledgement within 2 s (already running?)\n", module); code = CONTROL_EXIT_NOACK; }
    } else if (!strcmp(cmd, "stop")) {
        rc = SendStop(module, ACK_STOPPED, 2);
        if (rc != CONTRACT_OK) code = CONTROL_EXIT_ERROR;
        else if ((r = wait_ack(module, 2, ACK_STOPPED | ACK_NOTDONE, ack)) == 1 && ack->Param.Ack.Ack == ACK_STOPPED)
            printf("%s: stopped\n", module);
        else if (r == 1) { fprintf(stderr, "control %s: %s had no run to stop\n", module, module); code = CONTROL_EXIT_NOACK; }
        else { fprintf(stderr, "control %s: stop sent, but no acknowledgement within 2 s\n", module); code = CONTROL_EXIT_NOACK; }
    } else { /* kill */
        rc = SendKill(module, ACK_KILLED, 3);
        if (rc != CONTRACT_OK) code = CONTROL_EXIT_ERROR;
        else if (wait_ack(module, 3, ACK_KILLED, ack) != 1) {
            fprintf(stderr, "control %s: kill sent, but no acknowledgement within 2 s\n", module);
            code = CONTROL_EXIT_NOACK;
        } else {
            for (int t = 0; t < 200 && ModuleState(module) == CONTRACT_OK; t++) usleep(10000);
            printf("%s: killed\n", module);
        }
    }
    free(ack);
    return code;
}

int ControlMainTyped(const char *module, const ControlTypedParam params[], int argc, char *argv[])
{
    int n = 0;
    while (params && params[n].Type) n++;
    ControlParam *list = calloc((size_t)n + 1, sizeof *list);
    if (!list) return CONTROL_EXIT_ERROR;
    for (int i = 0; i < n; i++)
        list[i] = (ControlParam){ params[i].Port, params[i].Type->size, typed_placeholder, params[i].Type->name };
    list[n] = (ControlParam)CONTROL_PARAM_TERM;
    typed_params = params;
    int rc = ControlMain(module, list, argc, argv);
    typed_params = NULL;
    free(list);
    return rc;
}
