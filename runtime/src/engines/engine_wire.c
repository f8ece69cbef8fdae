/* engine_wire.c — see engine_wire.h. */
#define _POSIX_C_SOURCE 200809L
#include "engine_wire.h"

#include <stdlib.h>
#include <string.h>

int engine_send_start(const char *module, const char *function, const void *block, size_t size,
                      int ackId, int wantedAck) {
    if (size + CONTRACT_BINARY_ARGS_MAGIC_LEN > CONTRACT_REQUEST_DATA_MAX) return CONTRACT_ETOOBIG;
    RequestMessage *m = calloc(1, sizeof *m);
    if (!m) return CONTRACT_ESYS;
    m->Type = REQ_START;
    strncpy(m->Param.Start.ModAck, ContractSelfName(), CONTRACT_NAME_MAX - 1);
    m->Param.Start.WantedAck = wantedAck;
    m->Param.Start.AckID = ackId;
    strncpy(m->Param.Start.Function, function, CONTRACT_FUNCTION_MAX - 1);
    memcpy(m->Data, CONTRACT_BINARY_ARGS_MAGIC, CONTRACT_BINARY_ARGS_MAGIC_LEN);
    if (size) memcpy(m->Data + CONTRACT_BINARY_ARGS_MAGIC_LEN, block, size);
    m->DataSize = CONTRACT_BINARY_ARGS_MAGIC_LEN + size;
    int rc = SendRequest(module, m);
    free(m);
    return rc;
}

int engine_send_stop(const char *module, const char *function, int ackId) {
    RequestMessage *m = calloc(1, sizeof *m);
    if (!m) return CONTRACT_ESYS;
    m->Type = REQ_STOP;
    strncpy(m->Param.Stop.ModAck, ContractSelfName(), CONTRACT_NAME_MAX - 1);
    m->Param.Stop.WantedAck = ACK_NOTHING;
    m->Param.Stop.AckID = ackId;
    size_t n = strlen(function) + 1;
    if (n > CONTRACT_REQUEST_DATA_MAX) n = CONTRACT_REQUEST_DATA_MAX;
    memcpy(m->Data, function, n);
    m->Data[n - 1] = '\0';
    m->DataSize = n;
    int rc = SendRequest(module, m);
    free(m);
    return rc;
}

int engine_binary_args(const RequestMessage *m, const unsigned char **block, size_t *size) {
    if (m->DataSize < CONTRACT_BINARY_ARGS_MAGIC_LEN ||
        memcmp(m->Data, CONTRACT_BINARY_ARGS_MAGIC, CONTRACT_BINARY_ARGS_MAGIC_LEN) != 0)
        return 0;
    *block = m->Data + CONTRACT_BINARY_ARGS_MAGIC_LEN;
    *size = m->DataSize - CONTRACT_BINARY_ARGS_MAGIC_LEN;
    return 1;
}

void engine_data_string(const RequestMessage *m, char *out, size_t n) {
    size_t k = m->DataSize < n - 1 ? m->DataSize : n - 1;
    memcpy(out, m->Data, k);
    out[k] = '\0';
}

void engine_terminate_names(RequestMessage *m) {
    m->Sender[CONTRACT_NAME_MAX - 1] = '\0';
    switch (m->Type) {
    case REQ_START:
        m->Param.Start.ModAck[CONTRACT_NAME_MAX - 1] = '\0';
        m->Param.Start.Function[CONTRACT_FUNCTION_MAX - 1] = '\0';
        break;
    case REQ_STOP: m->Param.Stop.ModAck[CONTRACT_NAME_MAX - 1] = '\0'; break;
    case REQ_KILL: m->Param.Kil.ModAck[CONTRACT_NAME_MAX - 1] = '\0'; break;
    case REQ_EVENT: m->Param.Event.sourceModule[CONTRACT_NAME_MAX - 1] = '\0'; break;
    case REQ_ACK: m->Param.Ack.Module[CONTRACT_NAME_MAX - 1] = '\0'; break;
    case REQ_SUB_EVENT: m->Param.SubscribeEvent.targetModule[CONTRACT_NAME_MAX - 1] = '\0'; break;
    case REQ_UNSUB_EVENT: m->Param.UnsubscribeEvent.targetModule[CONTRACT_NAME_MAX - 1] = '\0'; break;
    default: break;
    }
}
