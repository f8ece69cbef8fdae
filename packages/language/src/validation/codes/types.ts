import { defineCodes } from './code-table.js';

/** docs/language-reference.md §2: datatypes, values and function prototypes. */
export const { area: typesArea, codes: TypeCodes } = defineCodes('Data types, values and functions', 'language-reference.md §2', {
    'type-duplicate-name': {
        severity: 'error',
        description: 'Two datatypes, enumerations, constants or function prototypes have the same name in the project (they all share the generated `common/` folder).',
        example: 'datatype T {int a};\ndatatype T {float b};'
    },
    'type-duplicate-member': {
        severity: 'error',
        description: 'Two fields of a datatype, two members of an enumeration, or two arguments of a function prototype, have the same name.',
        example: 'datatype T {int a, float a};'
    },
    'type-unknown': {
        severity: 'error',
        description: 'A type that is neither a primitive (`int`, `float`, `string`, `bool`) nor a datatype or enumeration defined in this file or in a file it imports. (A datatype defined in a file that is not imported gives `import-not-imported` instead.)',
        example: 'datatype T {TypeZ z};'
    },
    'type-recursive': {
        severity: 'error',
        description: 'A datatype contains itself, directly or through other datatypes; the message shows the cycle. A C struct cannot contain itself.',
        example: 'datatype A {B b};\ndatatype B {A a};'
    },
    'type-primitive-misuse': {
        severity: 'error',
        description: '`void` is only a function return type; fields, parameters, ports, constants and variables are `int`, `float`, `string`, `bool`, a datatype, an enumeration or an array of these.',
        example: 'datatype T {void nothing};'
    },
    'type-function-return': {
        severity: 'error',
        description: 'A function prototype returns `bool` (a test function, used in event tests) or `void` (a compute function, used by `compute`).',
        example: 'function int f(int a);'
    },
    'type-function-misuse': {
        severity: 'error',
        description: 'A `void` function used as an event test, or a `bool` function used by `compute`.',
        example: 'compute testit("a", x)   // testit returns bool'
    },
    'value-type-mismatch': {
        severity: 'error',
        description: 'A written value does not fit the expected type: a real for an `int`, a number for a `string`, a structured value for a primitive, a variable of another type. An integer literal for a `float` is accepted.',
        example: 'datatype T {int a = 1.5};'
    },
    'number-out-of-range': {
        severity: 'error',
        description: 'A number does not fit where the generated C holds it, which would hold another value: an `int` value is a C `long` (from -9223372036854775808 to 9223372036854775807; gcc truncates a larger one), a `float` value a C `double` (finite, at most about ±1.8e308: `1e400` is infinite; a number that is not 0 must not round to 0, as `1e-400` does). Checked wherever a value is written: defaults, constants, parameter values, arguments, extractions, tests (a number compared with a `float` is a `float`) and scenario values. A port index, a periodicity (`* k`) and an array size are C `int`s (at most 2147483647); a duration is at most 9007199254740991ns (about 104 days: the tools hold durations exactly up to there).',
        example: 'datatype T {int a = 99999999999999999999, float b = 1e400};'
    },
    'value-struct-arity': {
        severity: 'error',
        description: 'A structured value needs exactly one element per field of its datatype, recursively.',
        example: 'datatype A {float i, float j};\ndatatype B {A a = {1.0}};'
    },
    'value-string-too-long': {
        severity: 'error',
        description: 'A string literal longer than 255 bytes (UTF-8) does not fit the generated `char[256]`.',
        example: 'datatype T {string s = "<256 characters or more>"};'
    },
    'value-string-unknown-escape': {
        severity: 'warning',
        description: 'A backslash in a string (a value or an import path) before a character that is none of `n` `t` `r` `b` `f` `0` `\\\\` `"`: the backslash is dropped and the character kept (`"\\u001b"` is `u001b`, `"\\x41"` is `x41`), as the simulator and the runtime read it too; there are no `\\u`, `\\x` or octal escapes. Write `\\\\` for a backslash.',
        example: 'const string ESC = "\\e[0m";'
    },
    'value-array-length': {
        severity: 'error',
        description: 'A value `{...}` for an array (an extension of the report) needs exactly as many elements as the array has, recursively for arrays of arrays.',
        example: 'datatype T {float[3] v = {1.0, 2.0}};'
    },
    'enum-value-without-member': {
        severity: 'error',
        description: 'An enumeration name used as a value: a value of an enumeration is one of its members, written `Mode.AUTO`.',
        example: 'enum Mode {IDLE, AUTO};\ndatatype T {Mode m = Mode};'
    },
    'enum-empty': {
        severity: 'error',
        description: 'An enumeration (an extension of the report) needs at least one member (its first member is the default value).',
        example: 'enum Mode {};'
    },
    'array-size-invalid': {
        severity: 'error',
        description: 'An array size is a positive integer literal or the name of an `int` constant whose value is positive.',
        example: 'datatype T {float[0] v};'
    },
    'array-index-invalid': {
        severity: 'error',
        description: 'An index `[i]` in a path applies to an array and is within its size (from 0 to size - 1); it is an integer literal or an `int` constant.',
        example: 'datatype Scan {float[180] ranges};\n... <(scan.ranges[180] < 0.3)>'
    },
    'type-too-large': {
        severity: 'error',
        description: 'A value too large for the runtime to carry: an event port or a module parameter holds at most 16384 bytes (one request), a data port, a local or a schema/function parameter at most 65536 bytes (sizes of the generated C; large arrays count).',
        example: 'event flows { out :0 float[4096] samples; }   // 32768 bytes'
    },
    'const-cycle': {
        severity: 'error',
        description: 'A constant defined (directly or through other constants) by itself; the message shows the cycle.',
        example: 'const int A = B;\nconst int B = A;'
    },
    'value-not-constant': {
        severity: 'error',
        description: 'Only constants are allowed here (datatype field defaults, module parameters and ports, schema and function parameter defaults, named constants): literals, `{...}`, enumeration members and names of constants.',
        example: 'datatype T {int a = b};'
    }
});
