/** Hover (docs/ide.md "Editor services"): types, ports by index, resolved values with defaults, module C, schema timing. */
import { describe, expect, it } from 'vitest';
import type { MarkupContent } from 'vscode-languageserver-protocol';
import { build, type Built } from './helpers.js';
import { ARCHITECTURE, offsetOf, positionParams } from './lsp-workspace.js';

async function hover(ws: Built, file: string, needle: string, delta = 0, n = 1): Promise<string | undefined> {
    const doc = ws.docs.get(file)!;
    const result = await ws.services.lsp.HoverProvider!.getHoverContent(doc, positionParams(doc, offsetOf(doc, needle, delta, n)));
    return (result?.contents as MarkupContent | undefined)?.value;
}

describe('hover', () => {
    it('on a port reference by index: direction, kind, index, owner, type and initial value', async () => {
        const ws = await build(ARCHITECTURE);
        const text = await hover(ws, 'schema.contract', 'MSC:1 ->', 4);
        expect(text).toContain('out data port :1 of `MSC`, type `TypeB`');
        expect(text).toContain('value: `{{1.0,1.0,1.0},1}` (default)');
        // the same index in a supervisor's subscription is MSC's *event* port 1
        expect(await hover(ws, 'sup.contract', 'MSC:1 =*', 4)).toContain('out event port :1 of `MSC`, type `TypeD`');
    });

    it('on a parameter setting: the parameter port with its written value', async () => {
        const ws = await build(ARCHITECTURE);
        const text = await hover(ws, 'schema.contract', 'consigne :0', 10);
        expect(text).toContain('parameter port :0 of `MSC`, type `TypeA`');
        expect(text).toContain('value: `{2.1,6.98,5.34}`');
        expect(text).not.toContain('(default)');
    });

    it('on a module reference: kind, C and ports', async () => {
        const ws = await build(ARCHITECTURE);
        const text = await hover(ws, 'schema.contract', 'MSD()', 0);
        expect(text).toContain('synchronous module MSD');
        expect(text).toContain('C = 2ms');
        expect(text).toContain('- in data :2 `TypeB order`');
    });

    it('on a schema: utilisation (sum C / PERIOD) and critical path through the precedences', async () => {
        const ws = await build(ARCHITECTURE);
        const text = await hover(ws, 'schema.contract', 'cmd(', 0);
        // C: MSA 500us + MSC 1ms + MSD 2ms = 3.5ms over 10ms
        expect(text).toContain('utilisation: 35% (sum C = 3500us)');
        // MSA -> MSC is 1.5ms, MSD alone is 2ms: the critical path is MSD
        expect(text).toContain('critical path: 2ms (MSD)');
        expect(text).toContain('PERIOD = 10ms, CRITICAL_DELAY = 8ms');
        // the same figures from a reference (activate schema in the supervisor)
        expect(await hover(ws, 'sup.contract', 'schema cmd', 7)).toContain('utilisation: 35%');
    });

    it('on variables: type, owner and resolved value (written, or the default of the type)', async () => {
        const ws = await build(ARCHITECTURE);
        expect(await hover(ws, 'sup.contract', 'target.k', 0)).toContain('local of supervision function `go`');
        const count = await hover(ws, 'sup.contract', 'count', 0);
        expect(count).toContain('int count');
        expect(count).toContain('value: `3`');
        const field = await hover(ws, 'sup.contract', 'target.k', 7);
        expect(field).toContain('field of `TypeA`');
        expect(field).toContain('value: `0.0`');
        const type = await hover(ws, 'msc.contract', 'TypeB', 0);
        expect(type).toContain('datatype TypeB {TypeA coord, int frfrrrf}');
        expect(type).toContain('default: `{{1.0,1.0,1.0},1}`');
    });

    it('on a rule label reference and on a supervisor port used by name', async () => {
        const ws = await build(ARCHITECTURE);
        expect(await hover(ws, 'sup.contract', 'endof(FIRST)', 6)).toContain('rule of supervision function `go` (2 actions)');
        expect(await hover(ws, 'sup.contract', '= failure)', 3)).toContain('in event port :3 of `SUP`, type `TypeD`');
    });

    it('on the scheduler events ORD:0 and ORD:1: their meaning', async () => {
        const ws = await build({ ...ARCHITECTURE, 'o.contract': 'supervisor SUO { go() { rules { R: [ORD:0] [ORD:1] } } }' });
        expect(await hover(ws, 'o.contract', 'ORD:0', 1)).toContain('critical lateness');
        expect(await hover(ws, 'o.contract', 'ORD:1', 1)).toContain('activation was refused');
    });
});

describe('hover on timing properties', () => {
    it('`C=500us` in a module: the value in µs and its meaning', async () => {
        const ws = await build(ARCHITECTURE);
        const text = await hover(ws, 'msa.contract', 'C=500us', 0);
        expect(text).toContain('= 500 µs');
        expect(text).toContain('computation time');
        expect(await hover(ws, 'msa.contract', 'C=500us', 4)).toContain('= 500 µs'); // on the value too
    });

    it('`PERIOD=` and `CRITICAL_DELAY=` in a schema: µs, utilisation and critical path', async () => {
        const ws = await build(ARCHITECTURE);
        const period = await hover(ws, 'schema.contract', 'PERIOD=', 0);
        expect(period).toContain('= 10,000 µs');
        // C: MSA 500us + MSC 1ms + MSD 2ms = 3.5ms over 10ms; MSD alone (2ms) is the critical path
        expect(period).toContain('utilisation of `cmd`: 35% (sum C = 3,500 µs)');
        expect(period).toContain('critical path: 2,000 µs (MSD)');
        const delay = await hover(ws, 'schema.contract', 'CRITICAL_DELAY=', 2);
        expect(delay).toContain('= 8,000 µs');
        expect(delay).toContain('ORD:0');
        expect(delay).toContain('utilisation of `cmd`: 35%');
    });
});
