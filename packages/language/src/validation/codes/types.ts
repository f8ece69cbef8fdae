import { defineCodes } from './code-table.js';

/** docs/language-reference.md §2: datatypes, values and function prototypes. */
export const { area: typesArea, codes: TypeCodes } = defineCodes('Data types, values and functions', 'language-reference.md §2', {
    'type-duplicate-name': {
        severity: 'error',
        description: 'Two datatypes, or two function prototypes, have the same name in the project (they all share the generated `common/` folder).',
        example: 'datatype T {int a};\ndatatype T {float b};'
    },
    'type-duplicate-member': {
        severity: 'error',
        description: 'Two fields of a datatype, or two arguments of a function prototype, have the same name.',
        example: 'datatype T {int a, float a};'
    },
    'type-unknown': {
        severity: 'error',
        description: 'A type that is neither a primitive (`int`, `float`, `string`) nor a datatype defined in this file or in a file it imports. (A datatype defined in a file that is not imported gives `import-not-imported` instead.)',
        example: 'datatype T {TypeZ z};'
    },
    'type-recursive': {
        severity: 'error',
        description: 'A datatype contains itself, directly or through other datatypes; the message shows the cycle. A C struct cannot contain itself.',
        example: 'datatype A {B b};\ndatatype B {A a};'
    },
    'type-primitive-misuse': {
        severity: 'error',
        description: '`bool` and `void` are only function return types; fields, parameters, ports and variables are `int`, `float`, `string` or a datatype.',
        example: 'datatype T {bool flag};'
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
    'value-not-constant': {
        severity: 'error',
        description: 'Only constants are allowed here (datatype field defaults, module parameters and ports, schema and function parameter defaults).',
        example: 'datatype T {int a = b};'
    }
});
