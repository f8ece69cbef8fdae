import { expandToNode, joinToNode, NL, toString, type Generated } from 'langium/generate';
import type { Module, PortDecl } from '../model/architecture.js';
import { namedTypeOf, type ArchitectureIndex } from '../model/lookup.js';
import { cDeclaration, cInitializer, cSizeof, cType } from './c/c-syntax.js';
import { blockRegion, inlineRegion } from './c/regions.js';
import { CONSTANTS_HEADER } from './constants-header.js';
import { architecturePath } from '@contract-studio/conventions';

/** `modules/<M>_mod/module.c` of a synchronous or asynchronous module, in the shape of report §8.2. */
export function moduleSourcePath(name: string): string {
    return architecturePath(`modules/${name}_mod/module.c`);
}

const byIndex = (ports: PortDecl[]) => [...ports].sort((a, b) => a.index - b.index);

function includedTypes(m: Module): string[] {
    const all = [...m.dataIn, ...m.dataOut, ...m.eventIn, ...m.eventOut, ...m.parameters];
    return [...new Set(all.flatMap((p) => namedTypeOf(p.type) ?? []))];
}

/**
 * The parameters of `_react_to_event` and `_react_to_parameterizing`, cast to void in the skeleton
 * before their region: any body (the default, yours, an older generator's or the ContrACT Eclipse
 * tool's, which had no casts) compiles with -Wall -Wextra without an unused-parameter warning.
 */
const EVENT_PARAMS_USED = '(void)receiverport; (void)senderport; (void)sendermodule; (void)eventProductionTime; (void)eventReceptionTime;';
const PARAM_PARAMS_USED = '(void)parameterport; (void)productionTime; (void)receptionTime;';

const EVENT_DEFAULT = `//TODO : implement the code for reaction to event notifications
/* example pattern for implementing this function
if (strlen(sendermodule) != 0){//event incoming in a port of the module
    switch(receiverport){
        case 0:
            ...
            break;
        case 1:
            ...
            break;
    }
}
else{//event coming from the specified port of the sender module
    ...
}
*/
`;

const PARAM_DEFAULT = `//TODO : implement the code for reaction to parameterizing requests
/* example pattern for implementing this function
switch(parameterport){
    case 0: ...
        break;
    case 1: ...
        break;
}
*/
`;

function execDefault(m: Module): string {
    return `//TODO : implement the ${m.kind === 'synchronous' ? 'activity of one period' : 'behaviour of the module'}, one state per call
switch(*stateindex){
    case 0:
        *stateindex = -1; //the run is finished
        break;
    default:
        *stateindex = -1;
        break;
}
`;
}

/** The static parts of the report's request loop (ModuleMain), rendered once: the skeleton is the same for every module. */
const LOOP_HEAD = toString(expandToNode`
    int ModuleMain(int argc, const char * argv[])
    {
        RequestMessage receivedMessage, registered;
        int subscription = 0;
        int end=0;
        int state=0;
        int interact,cycleRunning=0;
        (void)argc; (void)argv;
        memset(&receivedMessage, 0, sizeof(receivedMessage));
        memset(&registered, 0, sizeof(registered));

        if( _init_module() == 0 ){
            /* the init region refused to start (it returned 0): said, not left to read as a crash */
            fprintf(stderr, "%s: its init region returned 0 (false): the module does not start\\n", MODULE_NAME);
            return(-1);
        }
        receivedMessage.Type=REQ_UNKNOWN;
        while(!end)
        {
            switch(receivedMessage.Type)
            {
                case REQ_UNKNOWN :
                    if (cycleRunning && state != -1 && PendingRequests() > 0 && WaitForRequestUntil(&receivedMessage, 0) == 1)
                        break; //a request read with the one just handled (a STOP behind an UNSUB_EVENT) is handled before the run's next state
                    if (cycleRunning){
                        if (state != -1){ //the execution has not been interrupted
                            //filling the received message with old START request information
                            receivedMessage.Type=REQ_START;
                            if ((registered.Param.Start.WantedAck&ACK_NOTHING) == 0)//do not try to copy module names if an ACK is not required
                                strcpy( receivedMessage.Param.Start.ModAck, registered.Param.Start.ModAck);
                            receivedMessage.Param.Start.WantedAck= registered.Param.Start.WantedAck;
                            receivedMessage.Param.Start.AckID = registered.Param.Start.AckID;
                        }
                        else { //the execution has been interrupted, waiting again
                            state = 0;
                            cycleRunning = 0;
                            //sending an acknowledge to the module that has started this module
                            if ((registered.Param.Start.WantedAck &ACK_STOPPED) != 0){
                                SendAck( registered.Param.Start.ModAck, registered.Param.Start.WantedAck, ACK_STOPPED, registered.Param.Start.AckID);
                            }
                            //reinitializing registered
                            registered.Type=REQ_UNKNOWN;
                            registered.Param.Start.WantedAck = ACK_NOTHING;
                            registered.Param.Start.AckID = -1;
                            //waiting a new request
                            if (WaitForRequest(&receivedMessage) == NULL) end = 1;
                            break;
                        }
                    }
                    else {
                        if (WaitForRequest(&receivedMessage) == NULL) end = 1;
                        break;
                    }
                    __attribute__((fallthrough)); //a START is resumed after a request was handled

                case REQ_START:
                    if (cycleRunning == 0){//if execution cycle does not run
                        if ((receivedMessage.Param.Start.WantedAck&ACK_START) != 0) //if an ACK is required by the caller
                            SendAck( receivedMessage.Param.Start.ModAck, receivedMessage.Param.Start.WantedAck, ACK_START, receivedMessage.Param.Start.AckID);
                    }
                    if (subscription == 0){
                        SubscribeVariables();
                        SubscribeEvent();
                        subscription = 1;
                    }
                    interact = 0;
                    cycleRunning = 1;
                    while(!interact){
                        _exec_module_state(&state);
                        if(state==-1){//termination of the run
                            state = 0;
                            cycleRunning = 0;
                            interact = 1;
                            receivedMessage.Type=REQ_UNKNOWN;
                            if((receivedMessage.Param.Start.WantedAck&ACK_FINISHED) != 0) //if an ACK is required by the caller
                                SendAck( receivedMessage.Param.Start.ModAck, receivedMessage.Param.Start.WantedAck, ACK_FINISHED, receivedMessage.Param.Start.AckID);
                        }
                        if(cycleRunning){
                            //registering the previous request
                            registered.Type=receivedMessage.Type;
                            registered.Param.Start.WantedAck= receivedMessage.Param.Start.WantedAck;
                            registered.Param.Start.AckID = receivedMessage.Param.Start.AckID;
                            if ((registered.Param.Start.WantedAck&ACK_NOTHING) == 0)//do not try to copy module names if an ACK is not required
                                strcpy(registered.Param.Start.ModAck, receivedMessage.Param.Start.ModAck);

                            // polling on message to be reactive
                            if (LookForRequest(&receivedMessage) != NULL)
                                interact=1;
                        }
                    }
                    break;

                case REQ_STOP:
                    if (cycleRunning) {
                        state = -1;
                        //sending an acknowledge
                        if ((receivedMessage.Param.Stop.WantedAck&ACK_STOPPED) != 0)//if an ACK is required
                            SendAck( receivedMessage.Param.Stop.ModAck, receivedMessage.Param.Stop.WantedAck, ACK_STOPPED, receivedMessage.Param.Stop.AckID);
                        registered.Param.Start.WantedAck = ACK_NOTHING; //the STOP request has been acknowledged
                    }
                    else {
                        state = 0;
                        if ((receivedMessage.Param.Stop.WantedAck&ACK_STOPPED) != 0){//if an ACK is required
                            SendAck( receivedMessage.Param.Stop.ModAck, receivedMessage.Param.Stop.WantedAck, ACK_NOTDONE, receivedMessage.Param.Stop.AckID);
                        }
                    }
                    receivedMessage.Type=REQ_UNKNOWN;
                    break;

                case REQ_KILL:
                    end = 1;
                    if ((receivedMessage.Param.Kil.WantedAck&ACK_KILLED) != 0){//if an ACK is required
                        SendAck( receivedMessage.Param.Kil.ModAck, receivedMessage.Param.Kil.WantedAck, ACK_KILLED, receivedMessage.Param.Kil.AckID);
                    }
                    receivedMessage.Type=REQ_UNKNOWN;
                    break;

                case REQ_EVENT:
`);
const LOOP_MID = [
    '',
    '            case REQ_SETPARAM:',
    '                switch(receivedMessage.Param.SetParam.Port) {',
].join('\n');
const LOOP_TAIL = toString(expandToNode`
                        default:
                            printf("Unknown param port:%d\\n", receivedMessage.Param.SetParam.Port);
                            break;
                    }
                    receivedMessage.Type=REQ_UNKNOWN;
                    break;

                case REQ_SUBSCRIBE:
                    SubscribeUser(receivedMessage.Param.Subscribe.SourcePort, receivedMessage.Param.Subscribe.TargetModule, receivedMessage.Param.Subscribe.TargetPort, receivedMessage.Param.Subscribe.Periodicity, receivedMessage.Param.Subscribe.isContextual);
                    receivedMessage.Type=REQ_UNKNOWN;
                    break;

                case REQ_UNSUBSCRIBE:
                    UnsubscribeUser(receivedMessage.Param.Unsubscribe.SourcePort, receivedMessage.Param.Unsubscribe.TargetModule, receivedMessage.Param.Unsubscribe.TargetPort);
                    receivedMessage.Type=REQ_UNKNOWN;
                    break;

                case REQ_SUB_EVENT:
                    SubscribeUserToEvent(receivedMessage.Param.SubscribeEvent.targetModule, receivedMessage.Param.SubscribeEvent.targetPort, receivedMessage.Param.SubscribeEvent.sourcePort, receivedMessage.Param.SubscribeEvent.mode);
                    receivedMessage.Type=REQ_UNKNOWN;
                    break;

                case REQ_UNSUB_EVENT:
                    UnsubscribeUserToEvent(receivedMessage.Param.UnsubscribeEvent.targetModule, receivedMessage.Param.UnsubscribeEvent.targetPort, receivedMessage.Param.UnsubscribeEvent.sourcePort);
                    receivedMessage.Type=REQ_UNKNOWN;
                    break;

                case REQ_PURGE_MBX:
                    PurgeData(NULL);
                    receivedMessage.Type=REQ_UNKNOWN;
                    break;

                default:
                    receivedMessage.Type=REQ_UNKNOWN;
                    break;
            }
        }
        UnsubscribeVariables();
        UnsubscribeEvent();
        _exit_module();
        return 0;
    }
`);

/** ModuleMain: the static skeleton around the module's REQ_EVENT and REQ_SETPARAM handling. */
function requestLoop(eventCase: Generated, setParamCases: Generated): Generated {
    const parts = [trimNewlines(LOOP_HEAD), indentBy(16, eventCase), LOOP_MID, indentBy(20, setParamCases), trimNewlines(LOOP_TAIL)];
    return joinToNode(parts.filter((part) => part !== ''), (part) => part, { separator: NL });
}

function trimNewlines(text: string): string {
    return text.replace(/^\n+|\n+$/g, '');
}

/** A generator node rendered and shifted right by `columns` spaces (every non-empty line). */
function indentBy(columns: number, node: Generated): string {
    if (node === undefined) return '';
    const pad = ' '.repeat(columns);
    return trimNewlines(toString(node)).split('\n').map((l) => (l ? pad + l : l)).join('\n');
}

export function generateModuleSource(m: Module, priority: number, index: ArchitectureIndex): string {
    const M = m.name;
    const async = m.kind === 'asynchronous';
    const reactsToEvents = async && m.eventIn.length > 0;
    const reactsToParams = async && m.parameters.length > 0;
    const variables = [...m.dataIn, ...m.dataOut, ...m.eventIn, ...m.eventOut, ...m.parameters];
    const decl = (p: PortDecl) => `${cDeclaration(p.type, p.name)} = ${cInitializer(index, p.type, p.initial)};`;
    const iuse = byIndex(m.dataIn).map((p) => `{ &${p.name}, ${p.index}, ${cSizeof(p.type)}, "---", 0, 0}, `).join('');
    const iproduce = byIndex(m.dataOut).map((p) => `{ &${p.name}, ${p.index}, ${cSizeof(p.type)}}, `).join('');
    const ireact = byIndex(m.eventIn).map((p) => `{ &${p.name}, ${p.index}, ${cSizeof(p.type)}, "---", 0, 0}, `).join('');
    const idetect = byIndex(m.eventOut).map((p) => `{ &${p.name}, ${p.index}, ${cSizeof(p.type)}}, `).join('');
    // PARAM_SIZE_IN is indexed by port number: a gap gets a placeholder size (never 0, the terminator)
    const lastParam = Math.max(-1, ...m.parameters.map((p) => p.index));
    const paramSizes = Array.from({ length: lastParam + 1 }, (_, i) => {
        const p = m.parameters.find((q) => q.index === i);
        return p ? `${cSizeof(p.type)}, ` : `sizeof(char) /* no parameter port ${i} */, `;
    }).join('');
    const setParamCases: Generated = joinToNode(byIndex(m.parameters), (p) => expandToNode`
        case ${p.index} :
            GetDataFromSetParamRequest(&receivedMessage, &${p.name}, ${cSizeof(p.type)}, &productionTime, &receptionTime);
            ${reactsToParams ? `_react_to_parameterizing(${p.index}, &productionTime, &receptionTime);` : undefined}
            break;
    `, { appendNewLineIfNotEmpty: true });
    const eventCase = reactsToEvents
        ? expandToNode`
            _react_to_event(GetEventId(&productionTime, &receptionTime), receivedMessage.Param.Event.sourcePort, &receivedMessage.Param.Event.sourceModule[0], &productionTime, &receptionTime);
            receivedMessage.Type=REQ_UNKNOWN;
            break;`
        : expandToNode`
            receivedMessage.Type=REQ_UNKNOWN;
            break;`;

    const node = expandToNode`
        //          module source file
        //          MODULE: ${M} (${m.kind})
        //          Libraries includes
        #include <libmodule/libmodule.h>
        #include <stdio.h>
        #include <time.h>
        #include <string.h>
        ${[...m.dataIn, ...m.dataOut, ...m.eventIn, ...m.eventOut, ...m.parameters].some((p) => cType(p.type) === 'bool') ? '#include <stdbool.h>' : undefined}
        #include "tools.h"
        ${joinToNode(includedTypes(m), (t) => `#include "Shared${t}.h"`, { appendNewLineIfNotEmpty: true })}
        ${(index.architecture.constants ?? []).length > 0 ? `#include "${CONSTANTS_HEADER}"` : undefined}

        //from here you can make new imports or definitions
        ${blockRegion(`protect_additional_import_${M}`, '//TODO')}

        MODULE_DESCRIPTION(${inlineRegion(`protect_description_${M}`, `"${m.kind} module ${M}"`)});
        MODULE_AUTHOR(${inlineRegion(`protect_author_${M}`, '"TODO"')});

        //Exchanges Management Variables
        ${joinToNode(variables, decl, { appendNewLineIfNotEmpty: true })}

        // module name
        char MODULE_NAME[] = "${M}";
        //module priority
        int MODULE_PRIORITY = ${priority};
        // input data flows : example = { &Variable, PortReception, Size, "Name of emitter module"(can be unused by setting value to "---"), PortModuleEmetteur, Periodicity}
        ModuleUse IUSE[] = { ${iuse}IUSE_TERM };

        // output data flows : example = { &Variable, PortEmission, Size}
        ModuleProduce IPRODUCE[] = { ${iproduce}IPRODUCE_TERM };

        //input event flows : example = { &Variable, PortReception, size, "module name" (can be unused by setting value to "---"), PortEmission, oneshot}
        ModuleReact IREACT[] = { ${ireact}IREACT_TERM };

        //output event flows : example = { &variable, PortEmission, size }
        ModuleDetect IDETECT[] = { ${idetect}IDETECT_TERM };

        // size of parameters that can be received in the request mailbox:
        size_t PARAM_SIZE_IN[] = { ${paramSizes}PARAM_SIZE_TERM };

        // size of parameters or events that can be sent in request mailboxes of other modules (user has to add sizes of sent param requests, if any):
        size_t PARAM_SIZE_OUT[] = { ${inlineRegion(`protect_param_out_${M}`, ' ')}PARAM_SIZE_TERM };

        //global variables (the CSV log <MODULE>_<date>.csv is written by libmodule: add records with ContractLog())
        RTIME productionTime, receptionTime;

        //from here you can define new internal variables
        ${blockRegion(`protect_internal_vars_${M}`, '//TODO')}

        // Generic Prototypes (to be implemented by the user)
        int _init_module(void);//==0 false, != 0 true
        void _exit_module(void);
        void _exec_module_state(int * stateindex);//state from 0 to x with x > 0, if stateindex is -1 at end of execution then run is finished
        ${reactsToEvents ? 'void _react_to_event(int receiverport, int senderport, char * sendermodule, RTIME * eventProductionTime, RTIME * eventReceptionTime);//to implement to react to some events' : undefined}
        ${reactsToParams ? 'void _react_to_parameterizing(int parameterport, RTIME * productionTime, RTIME * receptionTime);//to implement to code reaction on parameterizing actions' : undefined}
        //Specific prototypes (from here you can declare new internal functions)
        ${blockRegion(`protect_internal_functions_decl_${M}`, '//TODO')}

        ${requestLoop(eventCase, setParamCases)}

        int _init_module(void){//==0 false, != 0 true
            ${blockRegion(`protect_init_${M}`, '//TODO\nreturn 1;')}
        }

        void _exit_module(void){
            ${blockRegion(`protect_exit_${M}`, '//TODO')}
        }

        void _exec_module_state(int * stateindex){//state from 0 to x with x > 0, if stateindex is -1 at end of execution then run is finished
            ${blockRegion(`protect_exec_${M}`, execDefault(m))}
        }
        ${reactsToEvents ? expandToNode`

            void _react_to_event(int receiverport, int senderport, char * sendermodule, RTIME * eventProductionTime, RTIME * eventReceptionTime){
                ${EVENT_PARAMS_USED}
                ${blockRegion(`protect_event_${M}`, EVENT_DEFAULT)}
            }
        ` : undefined}
        ${reactsToParams ? expandToNode`

            void _react_to_parameterizing(int parameterport, RTIME * productionTime, RTIME * receptionTime){
                ${PARAM_PARAMS_USED}
                ${blockRegion(`protect_param_${M}`, PARAM_DEFAULT)}
            }
        ` : undefined}

        //Specific functions (from here you have to implement new internal functions declared before main)
        ${blockRegion(`protect_internal_functions_impl_${M}`, '//TODO')}
    `;
    return toString(node) + '\n';
}
