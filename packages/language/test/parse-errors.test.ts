/** Syntax errors are reported in the user's terms. */
import { describe, expect, it } from 'vitest';
import { parse } from './helpers.js';

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
});
