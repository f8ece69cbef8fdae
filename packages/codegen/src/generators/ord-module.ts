import { expandToNode, toString } from 'langium/generate';
import { architecturePath } from '@contract-studio/conventions';

/**
 * `modules/ORD_mod/`: the scheduler. Its algorithm is the runtime's generic engine; module.c only
 * binds the generated tables (vocabulary.c) to it. schedtypes.h, schedmessages.h and tools.h keep the
 * report's file layout and point at the runtime's headers.
 */
export const ORD_DIR = architecturePath('modules/ORD_mod');

/** module.c of ORD or of a supervisor: the libmodule interface tables and the engine call. */
export function engineBindingSource(name: string, priority: number, role: 'scheduler' | 'supervisor', localHeader: string): string {
    const vocabulary = role === 'scheduler' ? 'ContractOrdVocabulary ORD_VOCABULARY' : `ContractSupervisorVocabulary ${name}_VOCABULARY`;
    const call = role === 'scheduler' ? 'contract_ord_main(&ORD_VOCABULARY, argc, argv)' : `contract_supervisor_main(&${name}_VOCABULARY, argc, argv)`;
    const node = expandToNode`
        //          module source file (generated whole: no protected region, regenerated on every Generate All)
        //          MODULE: ${name} (${role})
        // The ${role} algorithm is the runtime's generic engine; this architecture is data in vocabulary.c.
        #include <libmodule/libmodule.h>
        #include <contract/vocabulary.h>
        #include "${localHeader}"

        MODULE_DESCRIPTION("${role === 'scheduler' ? 'ContrACT scheduler (ORD)' : `ContrACT supervisor ${name}`}");
        MODULE_AUTHOR("ContrACT Studio (generated)");

        // module name
        char MODULE_NAME[] = "${name}";
        //module priority
        int MODULE_PRIORITY = ${priority};
        // the engine talks to other modules through requests and raw events: no port table of its own
        ModuleUse IUSE[] = { IUSE_TERM };
        ModuleProduce IPRODUCE[] = { IPRODUCE_TERM };
        ModuleReact IREACT[] = { IREACT_TERM };
        ModuleDetect IDETECT[] = { IDETECT_TERM };
        size_t PARAM_SIZE_IN[] = { PARAM_SIZE_TERM };
        size_t PARAM_SIZE_OUT[] = { PARAM_SIZE_TERM };

        extern const ${vocabulary};

        int ModuleMain(int argc, const char * argv[])
        {
            return ${call};
        }
    `;
    return toString(node) + '\n';
}

export function schedTypesHeader(): string {
    return toString(expandToNode`
        // schedtypes.h: types and constants of the scheduler (generated; the engine's are in contract/vocabulary.h)
        #ifndef SCHEDTYPES_H
        #define SCHEDTYPES_H
        #include <contract/vocabulary.h>
        #include "schedmessages.h"
        #endif
    `) + '\n';
}

export function schedMessagesHeader(): string {
    return toString(expandToNode`
        // schedmessages.h: what ORD tells the supervisors (generated). Every supervisor receives, without
        // subscribing, the events of ORD's out ports; their data is the schema's name (a Cactal string):
        //   ORD:0  a cycle of a periodic schema had not finished at tick + CRITICAL_DELAY
        //   ORD:1  a schema activation was refused (it shares a module with an active schema)
        #ifndef SCHEDMESSAGES_H
        #define SCHEDMESSAGES_H
        #include <contract/vocabulary.h>
        #define ORD_EVENT_DEADLINE_MISS CONTRACT_ORD_EVENT_DEADLINE_MISS
        #define ORD_EVENT_CONFLICT CONTRACT_ORD_EVENT_CONFLICT
        #endif
    `) + '\n';
}

export function toolsHeader(): string {
    return toString(expandToNode`
        // tools.h of ORD_mod: the runtime's helpers (serialisation, parsing), kept here for the report's layout
        #ifndef ORD_MOD_TOOLS_H
        #define ORD_MOD_TOOLS_H
        #include <tools.h>
        #endif
    `) + '\n';
}
