/**
 * model/event-in-port.ts on a large rule set: a module event's subscribes are found through an
 * index made once per supervision function (not a scan of every rule per event), and what the
 * checks and code generation read from them is the same as the rules say: each event's delivered
 * and bound input port, and the warnings of the events (supervisor-event-variable,
 * supervisor-event-not-subscribed). Also when another file changes what the references resolve to
 * while the function's syntax tree is kept.
 */
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { AstUtils, URI } from 'langium';
import { afterEach, describe, expect, it } from 'vitest';
import { architecture, supervisor } from './architecture-fixture.js';
import { build } from './helpers.js';
import { isModuleEvent, isRule, type Model, type ModuleEvent } from '../src/generated/ast.js';
import { eventInPort } from '../src/model/event-in-port.js';
import { loadWorkspace } from '../src/node/load-workspace.js';

const PORTS = 'in :1 TypeC message_received; in :2 string connection_status; in :3 TypeD failure; in :4 string status2; out :1 string failure_message_type;';

/**
 * `n` rules in one endof chain, four kinds in turn (the last rule is of the fourth):
 * 0: subscribes MAA:2 to :2, ends on an MAA:2 event reading :2, or on MAB:1 (never subscribed);
 * 1: subscribes MAA:2 to :4, ends on an MAA:2 event reading and extracting :4;
 * 2: ends on an MAA:2 event reading both :2 and :4 (ambiguous: an occurrence writes one);
 * 3: ends on an MSC:1 event, which only the last rule subscribes to :3, reading :2 (not written by it).
 */
function chainRules(n: number): string[] {
    return Array.from({ length: n }, (_, i) => {
        const pre = i === 0 ? 'elapsed=1ms' : `endof(R${i - 1})`;
        switch (i % 4) {
            case 0: return `R${i}: [${pre}] subscribe MAA:2 =* :2 [MAA:2<connection_status == "a"> or MAB:1]`;
            case 1: return `R${i}: [${pre}] subscribe MAA:2 =* :4 [MAA:2<status2 == "b">(temp_mess_type = status2)]`;
            case 2: return `R${i}: [${pre}] compute doit("x", 1.0) [MAA:2<status2 == "x" | connection_status == "y">]`;
            default: return `R${i}: [${pre}] ${i === n - 1 ? 'subscribe MSC:1 => :3' : 'compute doit("x", 1.0)'} [MSC:1<connection_status == "z">]`;
        }
    });
}

/** What the rules say of each kind: the warnings of its rule, and per event (source) the input port it is bound to. */
const EXPECTED: Array<{ warnings: string[]; bound: Record<string, number | undefined> }> = [
    { warnings: ['supervisor-event-not-subscribed'], bound: { 'MAA:2': 2, 'MAB:1': undefined } },
    { warnings: [], bound: { 'MAA:2': 4 } },
    { warnings: ['supervisor-event-variable'], bound: { 'MAA:2': undefined } },
    { warnings: ['supervisor-event-variable'], bound: { 'MSC:1': 3 } }
];

/** `R<i> code` for each warning of sup.contract, by the label of the rule on its line. */
function warningsByRule(text: string, diagnostics: Array<{ line: number; severity: string; code: string }>): string[] {
    const lines = text.split('\n');
    return diagnostics.filter((d) => d.severity === 'warning').map((d) => `${/^\s*(R\d+):/.exec(lines[d.line - 1] ?? '')?.[1] ?? `line ${d.line}`} ${d.code}`).sort();
}

const expectedWarnings = (n: number) =>
    Array.from({ length: n }, (_, i) => EXPECTED[i % 4]!.warnings.map((code) => `R${i} ${code}`)).flat().sort();

const eventText = (e: ModuleEvent) => `${e.source?.$refText}:${e.port?.$refText}`;

describe('event input ports of a large rule set', () => {
    it('1,000 rules: every event bound to the port its subscribes and tests say, and the events\' warnings where the rules put them', async () => {
        const n = 1000;
        const files = architecture({ 'sup.contract': supervisor(chainRules(n).join('\n'), { ports: PORTS }) });
        const built = await build(files);
        expect(built.diagnostics.filter((d) => d.severity === 'error')).toEqual([]);
        expect(warningsByRule(files['sup.contract']!, built.diagnostics.filter((d) => d.file === 'sup.contract'))).toEqual(expectedWarnings(n));
        const model = built.docs.get('sup.contract')!.parseResult.value as Model;
        const bound: string[] = [];
        const wanted: string[] = [];
        for (const event of AstUtils.streamAllContents(model).filter(isModuleEvent)) {
            const rule = AstUtils.getContainerOfType(event, isRule)!;
            const i = Number(rule.name.slice(1));
            bound.push(`${rule.name} ${eventText(event)} :${eventInPort(event).port?.index ?? 'any'}`);
            wanted.push(`${rule.name} ${eventText(event)} :${EXPECTED[i % 4]!.bound[eventText(event)] ?? 'any'}`);
        }
        expect(bound).toHaveLength(n + n / 4);
        expect(bound).toEqual(wanted);
        // the messages name the ports delivered in the order the subscribes are written
        const messages = built.diagnostics.filter((d) => d.file === 'sup.contract' && d.code === 'supervisor-event-variable').map((d) => d.message);
        expect(messages).toContain('MAA:2 is delivered to :2 connection_status, :4 status2 (one subscribe each), and this event reads the variables of :4 status2, :2 connection_status: an occurrence comes in on one of them and writes that one only, so what it reads of the others is older. Read one input port per event; to wait for either, write one event per port: MAA:2<status2 ...> or MAA:2<connection_status ...>.');
        expect(messages).toContain("MSC:1 is delivered to :3 failure; 'connection_status' is the variable of input port :2, which this event does not write: the test would read an older value.");
    }, 240_000); // the whole workspace built and checked: the suite runs at the lowest CPU priority beside others

    describe('when a module file changes and the supervisor is linked again (its syntax tree kept)', () => {
        const dirs: string[] = [];
        afterEach(() => {
            for (const dir of dirs.splice(0)) rmSync(dir, { recursive: true, force: true });
        });

        it('the subscribes are found by what they resolve to now', async () => {
            const n = 40;
            const files = architecture({ 'sup.contract': supervisor(chainRules(n).join('\n'), { ports: PORTS }) });
            const dir = mkdtempSync(join(tmpdir(), 'cactal-event-in-port-'));
            dirs.push(dir);
            for (const [file, text] of Object.entries(files)) writeFileSync(join(dir, file), text);
            const ws = await loadWorkspace(dir);
            const workspace = ws.services.shared.workspace;
            const supUri = URI.file(join(dir, 'sup.contract'));
            const supDoc = workspace.LangiumDocuments.getDocument(supUri)!;
            const tree = supDoc.parseResult.value;
            const supWarnings = () => warningsByRule(files['sup.contract']!, (workspace.LangiumDocuments.getDocument(supUri)!.diagnostics ?? [])
                .map((d) => ({ line: d.range.start.line + 1, severity: d.severity === 2 ? 'warning' : d.severity === 1 ? 'error' : 'other', code: String(d.code) })));
            const writeMaa = async (text: string) => {
                writeFileSync(join(dir, 'maa.contract'), text);
                await workspace.DocumentBuilder.update([URI.file(join(dir, 'maa.contract'))], []);
            };
            expect(supWarnings()).toEqual(expectedWarnings(n));
            // MAA parsed again: new port nodes, the supervisor's references resolved anew
            await writeMaa(`${files['maa.contract']}\n// edited\n`);
            expect(workspace.LangiumDocuments.getDocument(supUri)!.parseResult.value).toBe(tree);
            expect(supWarnings()).toEqual(expectedWarnings(n));
            // MAA's port 2 gone: the subscribes and events of MAA:2 resolve to nothing
            await writeMaa(files['maa.contract']!.replace('out :2 string connection_status;', ''));
            expect(supWarnings()).not.toContain('R2 supervisor-event-variable');
            await writeMaa(files['maa.contract']!);
            expect(workspace.LangiumDocuments.getDocument(supUri)!.parseResult.value).toBe(tree);
            expect(supWarnings()).toEqual(expectedWarnings(n));
        }, 120_000);
    });
});
