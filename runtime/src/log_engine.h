/* Which engine a process runs, for its CSV log (csvlog.c): only ORD logs ORD's record kinds
 * (scheduler, ord_*), only a supervisor the supervisors' (supervisor, sup_rule, module_hold,
 * flow_hold, module_priority, priority_kept); ContractLog refuses them in any other process, an
 * error record saying so (docs/runtime-api.md "Whose records, and their times"). Library-internal:
 * contract_ord_main and contract_supervisor_main call it first. */
#ifndef CONTRACT_LOG_ENGINE_H
#define CONTRACT_LOG_ENGINE_H

#define RT_ENGINE_NONE 0
#define RT_ENGINE_ORD 1
#define RT_ENGINE_SUPERVISOR 2

void rt_log_engine(int engine);

#endif
