import { defineCodes } from './code-table.js';

/** docs/language-reference.md §3: modules (and the naming rules shared with supervisors and all identifiers). */
export const { area: modulesArea, codes: ModuleCodes } = defineCodes('Modules and identifiers', 'language-reference.md §3', {
    'module-name-format': {
        severity: 'error',
        description: 'Module and supervisor names are exactly three upper-case letters (`[A-Z]{3}`). The quick fix upper-cases the name when that makes it valid; the diagnostic data holds `suggestion`.',
        example: 'synchronous module msa { scheduling { C=1ms; } }'
    },
    'module-name-reserved': {
        severity: 'error',
        description: '`ORD` is the scheduler\'s name and cannot name a module or supervisor.',
        example: 'synchronous module ORD { scheduling { C=1ms; } }'
    },
    'module-name-duplicate': {
        severity: 'error',
        description: 'Module and supervisor names are unique across the project (modules and supervisors together).',
        example: '// a.contract\nsynchronous module MSA { scheduling { C=1ms; } }\n// b.contract\nasynchronous module MSA { }'
    },
    'identifier-c-keyword': {
        severity: 'error',
        description: 'The generated C uses Cactal names as they are, so a name cannot be a C keyword (`int`, `double`, `struct`, `switch`, ...), including those of C23 (`typeof`, `nullptr`, `bool`, ...) and GNU C\'s `asm`, which a build with another `-std` would meet.',
        example: 'datatype T {int double};'
    },
    'identifier-generated-clash': {
        severity: 'error',
        description: 'Two datatypes or functions would share a generated `common/` header: the same file name (compared without case, as on case-insensitive file systems: datatype `FunctionStep` and function `Step` both write `SharedFunctionStep.h`) or the same include guard (`Pose` and `POSE` share `SHARED_POSE_H`), so one header would replace or hide the other. The quick fix renames the element to the free name in the diagnostic data (`suggestion`).',
        example: 'datatype Pose {float x};\ndatatype POSE {int y};'
    },
    'identifier-too-long': {
        severity: 'error',
        description: 'A name is at most 200 characters: datatypes, enumerations and functions name files of the generated tree (`common/SharedFunction<name>.h`, written through a temporary `.SharedFunction<name>.h.tmp-<pid>`), and a file name is at most 255 bytes.',
        example: `datatype ${'T'.repeat(201)} {int v};`
    },
    'identifier-reserved-prefix': {
        severity: 'error',
        description: 'Names starting with `_` are reserved for generated code.',
        example: 'datatype T {int _a};'
    },
    'identifier-c-reserved': {
        severity: 'error',
        description: 'The generated C uses Cactal names as they are, so a name cannot be one the generated C or the headers it includes already take: a macro of the C library or runtime headers (`EOF`, `NULL`), and for datatypes, functions and module ports and parameters a C library, POSIX or libmodule name (`time`, `printf`, `exit`, `GetData`), a variable of the generated module.c (`productionTime`, `MODULE_NAME`, `IUSE`, `stateindex`), a function generated for a datatype (`get_Pose`) or a datatype name. A named constant is a macro in every generated module.c, so it may take none of these names, nor a name the request loop reads (`Type`, `Param`), nor a function\'s name; and a field, port, parameter, argument or enumeration member\'s C name may not be a constant\'s; an enumeration member\'s C name (`Mode_AUTO`) may not be a datatype\'s, a function\'s, a module port\'s or parameter\'s, or another member\'s C name. docs/language-reference.md lists the rules. The quick fix renames the element everywhere to the free name in the diagnostic data (`suggestion`).',
        example: 'synchronous module MSA { scheduling { C=1ms; } data flows { out :0 int time; } }'
    },
    'module-block-order': {
        severity: 'error',
        description: 'Module blocks come in the order `parameters`, `scheduling`, `data flows`, `event flows` (each at most once).',
        example: 'synchronous module MSA { data flows { out :0 int x; } scheduling { C=1ms; } }'
    },
    'module-block-duplicate': {
        severity: 'error',
        description: 'A block appears twice in one module.',
        example: 'synchronous module MSA { scheduling { C=1ms; } scheduling { C=2ms; } }'
    },
    'module-scheduling-missing': {
        severity: 'error',
        description: 'A synchronous module needs a `scheduling { C=<time>; }` block giving its nominal execution time.',
        example: 'synchronous module MSA { data flows { out :0 int x; } }'
    },
    'module-scheduling-property': {
        severity: 'error',
        description: 'The scheduling block holds exactly one property, `C` (nominal execution time per cycle).',
        example: 'synchronous module MSA { scheduling { D=1ms; } }'
    },
    'module-async-forbidden-block': {
        severity: 'error',
        description: 'An asynchronous module is not scheduled and exchanges no periodic data: no `scheduling` and no `data flows` block.',
        example: 'asynchronous module MAA { scheduling { C=1ms; } }'
    },
    'module-sync-event-in': {
        severity: 'error',
        description: 'A synchronous module only has `out` event ports (it cannot react to events; use an asynchronous module).',
        example: 'synchronous module MSA { scheduling { C=1ms; } event flows { in :0 int e; } }'
    },
    'port-index-duplicate': {
        severity: 'error',
        description: 'Port indexes are unique per kind and direction: parameters; data in; data out; event in; event out. The quick fix renumbers to the free index in the diagnostic data (`suggestedIndex`).',
        example: 'synchronous module MSA { scheduling { C=1ms; } data flows { out :0 int a; out :0 int b; } }'
    },
    'port-index-negative': {
        severity: 'error',
        description: 'Port indexes are non-negative integers.',
        example: 'synchronous module MSA { scheduling { C=1ms; } data flows { out :-1 int a; } }'
    },
    'parameter-index-too-large': {
        severity: 'error',
        description: 'A parameter port index is at most 1023: the generated module.c gives the runtime a table of each parameter port\'s size indexed by port number (`PARAM_SIZE_IN`, one entry per index up to the largest), so a parameter at :10000000 would make module.c hundreds of megabytes. Data and event port indexes go up to 2147483647.',
        example: 'asynchronous module MSA { parameters { int gain = 1 :5000; } }'
    },
    'member-name-duplicate': {
        severity: 'error',
        description: 'Every name in a module or supervisor interface (parameters and port variables) is unique within it.',
        example: 'synchronous module MSA { scheduling { C=1ms; } data flows { out :0 int a; out :1 float a; } }'
    },
    'time-not-positive': {
        severity: 'error',
        description: 'Durations (`C`, `PERIOD`, `CRITICAL_DELAY`, `elapsed`, `duration`, persistence) are greater than zero: a number and a unit `ns`, `us`, `ms` or `s`; one that rounds to 0ns (`0.4ns`) is zero.',
        example: 'synchronous module MSA { scheduling { C=0ms; } }'
    },
    'time-rounded': {
        severity: 'warning',
        description: 'Durations are whole nanoseconds in the generated C and the runtime: digits below the nanosecond (`1.5ns`, `0.0001us`) are rounded to the nearest nanosecond (half up), and the warning says to what.',
        example: 'synchronous module MSA { scheduling { C=1.5ns; } }'
    }
});
