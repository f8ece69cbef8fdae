import { defineCodes } from './code-table.js';

/** docs/language-reference.md §5: the scheduler configuration (ORD). */
export const { area: schedulerArea, codes: SchedulerCodes } = defineCodes('Scheduler configuration', 'language-reference.md §5', {
    'scheduler-duplicate': {
        severity: 'error',
        description: 'A project has one scheduler configuration (it configures the one ORD module); the message names the other files.',
        example: '// a.contract\nscheduler configuration { }\n// b.contract\nscheduler configuration { }'
    },
    'scheduler-missing': {
        severity: 'warning',
        description: 'The project has periodic schemas but no `scheduler configuration`: ORD would schedule nothing. Reported on each periodic schema.',
        example: 'periodic schema s() { realtime { PERIOD=1s; CRITICAL_DELAY=1s; } modules { MSA (); } }   // no scheduler configuration anywhere'
    },
    'scheduler-module-kind': {
        severity: 'error',
        description: 'The scheduler configuration lists synchronous modules only (asynchronous modules are not scheduled).',
        example: 'scheduler configuration { modules { MAA; } }   // MAA is asynchronous'
    },
    'scheduler-schema-kind': {
        severity: 'error',
        description: 'The scheduler configuration lists periodic schemas only (supervisors run event schemas themselves).',
        example: 'scheduler configuration { schemas { schemaReceptionMessage; } }   // an event schema'
    },
    'scheduler-module-unlisted': {
        severity: 'error',
        description: 'Every module used by a listed schema must be listed in the `modules` block of the configuration; the message names the missing modules and the diagnostic data holds them (`modules`, for a quick fix).',
        example: 'scheduler configuration { modules { MSA; } schemas { schemaCommande1; } }   // uses MSA, MSC, MSD'
    },
    'scheduler-schema-unlisted': {
        severity: 'error',
        description: 'A periodic schema that a supervisor activates must be listed in the scheduler configuration (ORD only knows the listed schemas). Reported on the `activate schema` action; the diagnostic data holds `schema` (for a quick fix).',
        example: 'activate schema schemaCommande2(consigne = c)   // schemaCommande2 missing from the scheduler configuration'
    },
    'scheduler-entry-duplicate': {
        severity: 'warning',
        description: 'A module or schema is listed twice in the scheduler configuration.',
        example: 'scheduler configuration { modules { MSA; MSA; } }'
    },
    'scheduler-utilisation': {
        severity: 'warning',
        description: 'The utilisation of all listed schemas together (the sum over schemas of sum of C / PERIOD) exceeds 1: if they are active at once, the processor cannot run them all in time.',
        example: 'scheduler configuration { modules { MSA; MSB; } schemas { s1; s2; } }   // s1: C=0.6ms per 1ms, s2: C=0.6ms per 1ms'
    }
});
