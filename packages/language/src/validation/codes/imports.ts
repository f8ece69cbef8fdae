import { defineCodes } from './code-table.js';

/** docs/language-reference.md §1: files and imports. */
export const { area: importsArea, codes: ImportCodes } = defineCodes('Files and imports', 'language-reference.md §1', {
    'import-missing-file': {
        severity: 'error',
        description: 'The imported file does not exist in the project. Paths resolve relative to the importing file. When a project file has that name elsewhere, the message suggests its relative path (diagnostic data `suggestion`).',
        example: 'import "nosuchfile.contract";'
    },
    'import-cycle': {
        severity: 'warning',
        description: 'An import of a file nothing of which is used closes an import cycle (the imported file imports this one back, directly or through other files): the warning is on that import, the one to remove, and its message shows the cycle from this file (imports are not transitive: a file imports only the files whose names it uses). The other files of the cycle get nothing: their imports are used. Files that use each other\'s names (a supervisor activating another that subscribes to its port) import each other: a cycle whose imports are all used is not reported.',
        example: '// a.contract\nimport "b.contract";\ndatatype A {B b};\n// b.contract (uses nothing of a.contract)\nimport "a.contract";\ndatatype B {int x};'
    },
    'import-unused': {
        severity: 'hint',
        description: 'Nothing the file refers to comes from the imported file, nor from what those elements rely on (a schema\'s modules, a module\'s types), nor (for a file that activates a periodic schema) is it the scheduler configuration. Not said while this file or the imported one has a syntax error (the use or the definition may be what did not parse). Hints are not counted by `contract check` as warnings.',
        example: 'import "datatype.contract";\nsynchronous module MSA { scheduling { C=1ms; } }'
    },
    'import-not-imported': {
        severity: 'error',
        description: 'The name is defined in another file of the project that this file does not import (imports are not transitive). The quick fix "add import" inserts the import; the diagnostic data holds `importPath`.',
        example: '// smodule.contract (no import of datatype.contract)\nsynchronous module MSA { scheduling { C=1ms; } data flows { out :0 TypeA x; } }'
    },
    'import-duplicate': {
        severity: 'warning',
        description: 'The same file is imported twice.',
        example: 'import "datatype.contract";\nimport "datatype.contract";'
    },
    'import-self': {
        severity: 'warning',
        description: 'A file imports itself.',
        example: '// a.contract\nimport "a.contract";'
    },
    'import-not-at-top': {
        severity: 'warning',
        description: 'Imports belong at the top of the file, before any definition.',
        example: 'datatype T {int a};\nimport "other.contract";'
    },
    'file-mixed-content': {
        severity: 'warning',
        description: 'A file holds either type definitions (datatypes and function prototypes, any number) or exactly one module, schema, scheduler configuration or supervisor.',
        example: 'datatype T {int a};\nsynchronous module MSA { scheduling { C=1ms; } }'
    }
});
