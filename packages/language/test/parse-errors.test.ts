/** Syntax errors are reported in the user's terms. */
import { describe, expect, it } from 'vitest';
import { readFileSync } from 'node:fs';
import { fileURLToPath } from 'node:url';
import { ALL_WORDS } from '../src/parser/error-messages.js';
import { build, parse } from './helpers.js';

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
        // no guess for a word that is no near miss
        expect(first('datatype T {int a = 1}\nwhatever X {}')).not.toContain('Did you mean');
    });
    it('offers the keyword a misspelt action was meant to be, where the expected tokens do not name it', () => {
        // after a rule's pre-condition come its actions or its post-condition '[': the parser names only '['
        const rule = (actions: string) => `supervisor SUP { f() { rules { R: [elapsed=1ms] ${actions} [elapsed=1ms] } } }`;
        expect(first(rule('parametrize MSC(1 :0)'))).toMatch(/but found 'parametrize'\. Did you mean 'parameterize'\?$/);
        expect(first(rule('subcribe MAA:0 => :1'))).toMatch(/Did you mean 'subscribe'\?$/);
        expect(first(rule('nonsense MSC(1 :0)'))).not.toContain('Did you mean');
        // the misspelt word was read as a name, the error comes at the next token
        expect(first('supervisor SUP { f() { rules { R: [elapsd=1ms] [elapsed=1ms] } } }')).toBe("Expected ':' but found '='. Did you mean 'elapsed' (not 'elapsd')?");
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
            'enc.contract': 'synchronus module ENC { }',
            'use.contract': 'import "enc.contract";\nperiodic schema s() { modules { ENC (); } }',
        });
        const unknown = built.diagnostics.find((d) => d.file === 'use.contract' && d.code === 'linking-error');
        expect(unknown?.message).toContain('("enc.contract" has a syntax error: fix it first, it may be where this is defined)');
        const clean = await build({ 'use.contract': 'periodic schema s() { modules { ENC (); } }' });
        expect(clean.diagnostics.find((d) => d.code === 'linking-error')?.message).not.toContain('syntax error');
    });
});
