//          module source file (generated whole: no protected region, regenerated on every Generate All)
//          MODULE: ORD (scheduler)
// The scheduler algorithm is the runtime's generic engine; this architecture is data in vocabulary.c.
#include <libmodule/libmodule.h>
#include <contract/vocabulary.h>
#include "schedtypes.h"

MODULE_DESCRIPTION("ContrACT scheduler (ORD)");
MODULE_AUTHOR("ContrACT Studio (generated)");

// module name
char MODULE_NAME[] = "ORD";
//module priority
int MODULE_PRIORITY = 90;
// the engine talks to other modules through requests and raw events: no port table of its own
ModuleUse IUSE[] = { IUSE_TERM };
ModuleProduce IPRODUCE[] = { IPRODUCE_TERM };
ModuleReact IREACT[] = { IREACT_TERM };
ModuleDetect IDETECT[] = { IDETECT_TERM };
size_t PARAM_SIZE_IN[] = { PARAM_SIZE_TERM };
size_t PARAM_SIZE_OUT[] = { PARAM_SIZE_TERM };

extern const ContractOrdVocabulary ORD_VOCABULARY;

int ModuleMain(int argc, const char * argv[])
{
    return contract_ord_main(&ORD_VOCABULARY, argc, argv);
}
