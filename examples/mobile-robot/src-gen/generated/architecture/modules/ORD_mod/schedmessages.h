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
