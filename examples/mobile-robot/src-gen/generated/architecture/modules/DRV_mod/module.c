//          module source file (generated whole: no protected region, regenerated on every Generate All)
//          MODULE: DRV (supervisor)
// The supervisor algorithm is the runtime's generic engine; this architecture is data in vocabulary.c.
#include <libmodule/libmodule.h>
#include <contract/vocabulary.h>
#include "suptypes.h"

MODULE_DESCRIPTION("ContrACT supervisor DRV");
MODULE_AUTHOR("ContrACT Studio (generated)");

// module name
char MODULE_NAME[] = "DRV";
//module priority
int MODULE_PRIORITY = 98;
// the engine talks to other modules through requests and raw events: no port table of its own
ModuleUse IUSE[] = { IUSE_TERM };
ModuleProduce IPRODUCE[] = { IPRODUCE_TERM };
ModuleReact IREACT[] = { IREACT_TERM };
ModuleDetect IDETECT[] = { IDETECT_TERM };
size_t PARAM_SIZE_IN[] = { PARAM_SIZE_TERM };
size_t PARAM_SIZE_OUT[] = { PARAM_SIZE_TERM };

extern const ContractSupervisorVocabulary DRV_VOCABULARY;

int ModuleMain(int argc, const char * argv[])
{
    return contract_supervisor_main(&DRV_VOCABULARY, argc, argv);
}
