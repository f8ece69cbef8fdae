import { defineCodes } from './code-table.js';

/** Codes Langium gives to syntax and linking problems (kept as Langium names them). */
export const { area: syntaxArea, codes: SyntaxCodes } = defineCodes('Syntax and references', 'language-reference.md', {
    'lexing-error': {
        severity: 'error',
        description: 'A character sequence that is not a Cactal token (for example a stray `$` or an unterminated string).',
        example: 'datatype T {int a = $};'
    },
    'parsing-error': {
        severity: 'error',
        description: 'The text does not follow the Cactal grammar; the message says which token was expected, and what was probably meant where it can tell (a misspelt keyword, two adjacent letters swapped as much as one missing, extra or wrong: "Did you mean \'synchronous\'?", `rulse {` for `rules {`, also where the parser expected something else: `parametrize MSC(...)` after a rule\'s condition gives "Unexpected \'parametrize\'. Did you mean \'parameterize\'? (the rest of the file is checked as if it were)", on the word; `20msec`: an unknown time unit; `<x > 3>`: parentheses; `<x = 3>`: `==`; two actions with no `;` between them are not a syntax error but one `supervisor-action-separator` error). Parsing recovers and the rest of the file is still checked, but the other diagnostics of the same line after the error are dropped (they come from the recovery), and an unknown name defined in an imported file that has a syntax error says so. A misspelt keyword is read as the keyword suggested when the text then parses on (the suggestion is the keyword that does: `moduls {` in a scheduler configuration gives \'modules\', not \'module\'): the rest of the file is checked as it was meant, without the follow-on errors of the recovery (`activate restime module MAA` in a rule is that one error).',
        example: 'datatype T {int a = };'
    },
    'merge-conflict-marker': {
        severity: 'error',
        description: 'A line of an unresolved git merge conflict: `<<<<<<< HEAD` (your side begins), `|||||||` (the common ancestor\'s lines, with diff3), `=======` (their side begins), `>>>>>>> eng-b` (their side ends), at the start of a line. One error on each marker line, and nothing else in the file is checked until the conflict is resolved (the parser would report every marker, and the two sides read as one text, as tens of follow-on errors): keep the lines you want, delete the marker lines, save. A lone `=======` line is no conflict. Generation refuses such a file too, as it refuses a generated file holding markers (docs/getting-started.md "Keeping a project in git").',
        example: '<<<<<<< HEAD\nsynchronous module GTG { ... }\n=======\nsynchronous module PLN { ... }\n>>>>>>> eng-b'
    },
    'linking-error': {
        severity: 'error',
        description: 'A name or port index that does not resolve in its context: unknown type, module, schema, rule label, variable or field, or a port index that the module does not have with that kind and direction. The message lists what would be valid, and the closest name when one is near: a letter missing, extra or wrong, or two adjacent letters swapped, is one edit (`Unknown module or supervisor \'LNI\': ... Did you mean \'LIN\'?`, `Function run has no parameter \'sped\'; its parameters: speed, mode. Did you mean \'speed\'?`). An unknown variable is matched against the names valid where it is: in a rule, the function\'s locals, its supervisor\'s event-port variables, the constants and enumerations, and in the tests and extracted values of an `ORD:0`/`ORD:1` event the implicit `ord_schema` (`ORD:0(late = ord_shema)`: "... in this ORD event, also \'ord_schema\' (the name of the schema it is about). Did you mean \'ord_schema\'?"); an extraction\'s target, among the locals; a supervisor named where a module must be (a schema\'s modules and flows, `parameterize`) is said to be one: its events reach only the supervisors that subscribe to them.',
        example: 'periodic schema s() { modules { MZZ (); } }   // no module MZZ'
    }
});
