/** Syntax errors are reported in the user's terms. */
import { describe, expect, it } from 'vitest';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { ALL_WORDS } from '../src/parser/error-messages.js';
import { isModule, isSchema, isSupervisor, type ActivateModule } from '../src/generated/ast.js';
import { build, parse } from './helpers.js';

const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));

/** The tutorial's .contract files, `edits` applied (file -> [written, replacement]). */
function tutorial(edits: Record<string, Array<[string, string]>>): Record<string, string> {
    return Object.fromEntries(readdirSync(TUTORIAL).filter((f) => f.endsWith('.contract')).map((f) => {
        let text = readFileSync(join(TUTORIAL, f), 'utf8');
        for (const [written, replacement] of edits[f] ?? []) {
            expect(text).toContain(written);
            text = text.replace(written, replacement);
        }
        return [f, text];
    }));
}

const first = (text: string) => parse(text).errors[0];

describe('syntax error messages', () => {
    it('names a duration instead of the TIME token', () => {
        expect(first('synchronous module MSA { scheduling { C=5; } }')).toBe("Expected a duration (number + unit ns, us, ms or s, e.g. 500us) but found '5'.");
    });
    it('lists the alternatives once, without keyword noise', () => {
        expect(first('datatype T {int a = };')).toBe(`Expected one of an integer, a real number, a string "...", 'true', 'false', '{', 'ord_schema' or a name but found '}'.`);
    });
    it('explains what may appear at top level', () => {
        expect(first('datatype T {int a = 1}\nmodul MSA {}')).toBe("Unexpected 'modul': expected a datatype, function, module, schema, scheduler configuration or supervisor.");
    });
    it('continues after the shared prefix of the alternatives', () => {
        expect(first('supervisor SUP { f() { rules { R: [elapsed=1ms] activate foo [elapsed=1ms] } } }'))
            .toBe("After 'activate', expected one of 'schema', 'supervisor', 'resttime' or 'critical' but found 'foo'.");
    });
    it('reads two actions without the \';\' between them (the validator reports it: supervisor-action-separator)', () => {
        for (const second of ['subscribe MAA:0 =* :1', 'activate schema S()', 'notify :1', 'compute f()', 'parameterize MSC()', 'activate resttime module MAA']) {
            const r = parse(`supervisor SUP { f() { rules { R: [elapsed=1ms] subscribe MAA:2 =* :2 ${second} [elapsed=1ms] } } }`);
            expect(r.errors, second).toEqual([]);
        }
    });
    it('says that a relational test needs parentheses', () => {
        expect(first('supervisor SUP { f() { rules { R: [MAA:1<x > 3>] [elapsed=1ms] } } }')).toContain('A relational test goes in parentheses');
    });
    it('says that ORD events need no subscribe', () => {
        const rule = (actions: string) => `supervisor SUP { event flows { in :1 int x; } f() { rules { R: [elapsed=1ms] ${actions} [elapsed=1ms] } } }`;
        const message = "ORD events need no subscribe: every supervisor receives them. Remove this subscribe and test 'ORD:n' directly in a rule's condition.";
        expect(parse(rule('subscribe ORD:0 => :1;')).errors).toEqual([message]);
        expect(parse(rule('subscribe MAA:0 => :1; subscribe ORD:1 =* :1;')).errors).toEqual([message]);
        // a name expected elsewhere keeps the generic message
        expect(parse(rule('compute ORD();')).errors).toEqual(["Expected a name but found 'ORD'."]);
    });
    it('names the end of the file', () => {
        expect(first('datatype T {int a')).toBe("Expected '}' but found the end of the file.");
    });
    it('names an unknown time unit instead of the name glued to a duration (20msec)', () => {
        expect(first('periodic schema s() { realtime { PERIOD=20msec; } }')).toBe("Unknown time unit 'msec' in '20msec': the units are ns, us, ms and s (e.g. 20ms).");
        expect(first('periodic schema s() { realtime { PERIOD=1.5sec; } }')).toBe("Unknown time unit 'sec' in '1.5sec': the units are ns, us, ms and s (e.g. 1.5ms).");
        // in a duration clause before 'and' (it said "Expected at least one 'and' but found 'ec'")
        const rule = 'supervisor SAF { event flows { in :0 float d; } g() { rules { STOP: [elapsed=1ms] subscribe LDR:0 =* :0 [(duration(STOP)=1sec{infinite} and SAF:0<(d > 1.0)>)] } } }';
        expect(first(rule)).toBe("Unknown time unit 'sec' in '1sec': the units are ns, us, ms and s (e.g. 1ms).");
    });
    it('offers the keyword a misspelt one was meant to be', () => {
        expect(first('synchronus module ENC {}')).toMatch(/^Unexpected 'synchronus': expected .*\. Did you mean 'synchronous'\?$/);
        expect(first('datatype T {int a = 1}\nsupervisr SUP {}')).toMatch(/Did you mean 'supervisor'\?$/);
        // two adjacent letters swapped are one edit (a word under 7 letters gets a suggestion within 1)
        expect(first('datatype T {int a = 1}\ncosnt int N = 3;')).toMatch(/^Unexpected 'cosnt': .* Did you mean 'const'\?$/);
        expect(first('improt "t.contract";')).toMatch(/Did you mean 'import'\?$/);
        // no guess for a word that is no near miss
        expect(first('datatype T {int a = 1}\nwhatever X {}')).not.toContain('Did you mean');
    });
    it('offers the keyword a misspelt action was meant to be, where the expected tokens do not name it', () => {
        // after a rule's pre-condition come its actions or its post-condition '[': the parser names only '['
        const rule = (actions: string) => `supervisor SUP { f() { rules { R: [elapsed=1ms] ${actions} [elapsed=1ms] } } }`;
        // (not "Expected '[' but found 'parametrize'": the '[' the recovery wanted is not what was meant)
        expect(first(rule('parametrize MSC(1 :0)'))).toBe("Unexpected 'parametrize'. Did you mean 'parameterize'? (the rest of the file is checked as if it were)");
        expect(first(rule('subcribe MAA:0 => :1'))).toMatch(/Did you mean 'subscribe'\?/);
        expect(first(rule('nonsense MSC(1 :0)'))).not.toContain('Did you mean');
        // the misspelt word was read as a name, the error comes at the next token
        expect(first('supervisor SUP { f() { rules { R: [elapsd=1ms] [elapsed=1ms] } } }')).toBe("Unexpected 'elapsd'. Did you mean 'elapsed'? (the rest of the file is checked as if it were)");
    });
    it('knows every keyword of the grammar for those suggestions', () => {
        const grammar = readFileSync(fileURLToPath(new URL('../src/cactal.langium', import.meta.url)), 'utf8');
        const words = [...new Set([...grammar.matchAll(/'([a-z_]{3,})'/g)].map((m) => m[1]!))].sort();
        expect([...ALL_WORDS].sort()).toEqual(words);
    });
    it("says that a comparison is written '=='", () => {
        expect(first('supervisor SUP { f() { rules { R: [MAA:1<x = 3>] [elapsed=1ms] } } }')).toContain("A comparison is written '=='.");
    });
});

describe('follow-on errors', () => {
    it('a line with a syntax error reports that one only: the recovery\'s later errors on the line are dropped', async () => {
        const text = 'supervisor SUP { event flows { in :1 int count; }\n f() { local { int parts; }\n rules {\n R: [elapsed=1ms] [elapsed=2ms]\n'
            + ' S: [MAA:1<count > 3>(parts = count)] [elapsed=1ms]\n } } }';
        const all = parse(text).errors;
        expect(all.length).toBeGreaterThan(1); // the parser does report several on that line
        const built = await build({ 'sup.contract': text });
        // (MAA is unknown here: that error is before the syntax error on the line, and kept)
        const onLine5 = built.diagnostics.filter((d) => d.line === 5 && !d.message.includes("'MAA'"));
        expect(onLine5).toHaveLength(1);
        expect(onLine5[0]!.message).toContain('A relational test goes in parentheses');
    });
    it('a name unknown because the file defining it did not parse says so', async () => {
        const built = await build({
            'enc.contract': 'sync module ENC { }',
            'use.contract': 'import "enc.contract";\nperiodic schema s() { modules { ENC (); } }',
        });
        const unknown = built.diagnostics.find((d) => d.file === 'use.contract' && d.code === 'linking-error');
        expect(unknown?.message).toContain('("enc.contract" has a syntax error: fix it first, it may be where this is defined)');
        const clean = await build({ 'use.contract': 'periodic schema s() { modules { ENC (); } }' });
        expect(clean.diagnostics.find((d) => d.code === 'linking-error')?.message).not.toContain('syntax error');
    });
    it('a misspelt name is not sent to an imported file with a syntax error that does not have it', async () => {
        const files = {
            'plan.contract': 'synchronous module PLN { }',
            'motion.contract': 'synchronous module MOT { scheduling { C=5msec; } }',
            'use.contract': 'import "plan.contract";\nimport "motion.contract";\nperiodic schema s() { modules { PLM (); } }'
        };
        const built = await build(files);
        expect(built.diagnostics.some((d) => d.file === 'motion.contract' && d.code === 'parsing-error')).toBe(true);
        const unknown = built.diagnostics.find((d) => d.file === 'use.contract' && d.code === 'linking-error');
        expect(unknown?.message).toContain("Did you mean 'PLN'?");
        expect(unknown?.message).not.toContain('syntax error');
        // the broken file that has the name is still said, with the near name
        const named = await build({ ...files, 'motion.contract': 'sync module PLM { }' });
        const note = named.diagnostics.find((d) => d.file === 'use.contract' && d.code === 'linking-error');
        expect(note?.message).toContain(`Did you mean 'PLN'? ("motion.contract" has a syntax error: fix it first, it may be where this is defined)`);
    });
});

describe('unused imports and syntax errors', () => {
    it('an import is not said unused while this file or the imported one has a syntax error: the use or the definition may be what was lost', async () => {
        // a stray 'foo bar baz;' among the actions of FIRST: the recovery loses the rule's 'activate schema schemaReceptionMessage()'
        const broken = await build(tutorial({ 'supervisor.contract': [['            activate schema schemaReceptionMessage()', '            foo bar baz;\n            activate schema schemaReceptionMessage()']] }));
        expect(broken.lines.filter((l) => l.startsWith('supervisor.contract:33:'))).toEqual(["supervisor.contract:33:13 error parsing-error Expected '[' but found 'foo'."]);
        expect(broken.diagnostics.filter((d) => d.code === 'import-unused')).toEqual([]);
        const imported = await build({
            'enc.contract': 'sync module ENC { }',
            'use.contract': 'import "enc.contract";\nperiodic schema s() { modules { ENC (); } }'
        });
        expect(imported.diagnostics.filter((d) => d.code === 'import-unused')).toEqual([]);
        // a file that parses, importing one that parses: said
        const clean = await build({ 'enc.contract': 'synchronous module ENC { }', 'use.contract': 'import "enc.contract";\nperiodic schema s() { }' });
        expect(clean.diagnostics.filter((d) => d.code === 'import-unused').map((d) => d.file)).toEqual(['use.contract']);
    });
});

describe('a misspelt keyword', () => {
    // the tutorial with one misspelt keyword: before, the recovery's errors went on (23 errors and 9 hints for the rule)
    const cases: Array<[string, string, string, string, string]> = [
        ['a module declaration', 'smodule1.contract', 'synchronous module MSA', 'synchronus module MSA', "smodule1.contract:3:1 error parsing-error Unexpected 'synchronus': expected a datatype, function, module, schema, scheduler configuration or supervisor. Did you mean 'synchronous'?"],
        ['a schema block', 'sschema1.contract', 'realtime{', 'realtme{', "sschema1.contract:8:5 error parsing-error Unexpected 'realtme'. Did you mean 'realtime'? (the rest of the file is checked as if it were)"],
        ['a supervisor rule', 'supervisor.contract', '            activate schema schemaReceptionMessage()', '            activate restime module MAA;\n            activate schema schemaReceptionMessage()',
            "supervisor.contract:33:22 error parsing-error After 'activate', expected one of 'schema', 'supervisor', 'resttime' or 'critical' but found 'restime'. Did you mean 'resttime'?"],
        // 'module' is as near to 'moduls' as 'modules': the keyword suggested is the one that parses
        ['a scheduler block', 'sched.contract', 'modules{', 'moduls{', "sched.contract:11:5 error parsing-error Unexpected 'moduls'. Did you mean 'modules'? (the rest of the file is checked as if it were)"],
        // two letters swapped are one edit (optimal string alignment): 'rulse' gave 11 errors and no suggestion
        ['a supervision function (two letters swapped)', 'supervisor.contract', '    rules{', '    rulse{', "supervisor.contract:30:5 error parsing-error Unexpected 'rulse'. Did you mean 'rules'? (the rest of the file is checked as if it were)"],
        ['a supervision function (the first two letters swapped)', 'supervisor.contract', '    rules{', '    rlues{', "supervisor.contract:30:5 error parsing-error Unexpected 'rlues'. Did you mean 'rules'? (the rest of the file is checked as if it were)"],
        ['a schema\'s scheduling graph (two letters swapped)', 'sschema1.contract', 'scheduling graph{', 'scheduling grahp{', "sschema1.contract:19:16 error parsing-error Unexpected 'grahp'. Did you mean 'graph'? (the rest of the file is checked as if it were)"]
    ];
    it.each(cases)('in %s is the one diagnostic of the project: the rest is read with the keyword meant', async (_where, file, written, misspelt, error) => {
        const built = await build(tutorial({ [file]: [[written, misspelt]] }));
        expect(built.lines).toEqual([error]);
    });

    it('does not hide the errors that do not follow from it: a second misspelling, an unknown module lines later', async () => {
        const built = await build(tutorial({
            'supervisor.contract': [
                ['            activate schema schemaReceptionMessage()', '            activate restime module MAA;\n            activate schema schemaReceptionMessage()'],
                ['notify :1(failure_message_type=temp_mess_type)', 'notfy :1(failure_message_type=temp_mess_type)'],
                ['activate resttime module MAA', 'activate resttime module MXX']
            ]
        }));
        expect(built.lines.map((l) => l.split(' ').slice(0, 3).join(' '))).toEqual([
            'supervisor.contract:33:22 error parsing-error', // on the misspelt word
            'supervisor.contract:44:17 error parsing-error',
            'supervisor.contract:54:42 error linking-error'
        ]);
        expect(built.lines[0]).toContain("but found 'restime'. Did you mean 'resttime'?");
        expect(built.lines[1]).toContain("Unexpected 'notfy'. Did you mean 'notify'?");
        expect(built.lines[2]).toContain("Unknown module 'MXX'");
    });

    it('is read as the keyword in the model: the checks see the element as it was meant', () => {
        const { model, errors } = parse('periodc schema s() { realtime { PERIOD=1s; CRITICAL_DELAY=1s; } }\nsynchronus module M { }\n'
            + 'supervisor SUP { f() { rules { R: [elapsed=1ms] activate critcal module M [elapsed=1ms] } } }');
        expect(errors).toHaveLength(3);
        const [schema, module, sup] = model.elements;
        expect(isSchema(schema) && schema.kind).toBe('periodic');
        expect(isModule(module) && module.kind).toBe('synchronous');
        expect(isSupervisor(sup) && (sup.functions[0]!.rules[0]!.rules[0]!.actions[0] as ActivateModule).priority).toBe('critical');
    });
});
