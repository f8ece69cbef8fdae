/**
 * `.scenario` files in the stdio language server (`contract-language-server`, docs/simulation.md
 * "Editing scenarios"): a real LSP session over a workspace holding both examples (tutorial and
 * mobile-robot, copied from examples/ with their scenarios). The example scenarios get no
 * diagnostic; broken variants get each problem with its exact range, code, severity and message;
 * a `.contract` change re-checks an open scenario; completion and hover answer from the project
 * the scenario belongs to. Runs the built server: `npm run build` first.
 */
import { cpSync, mkdtempSync, readFileSync, readdirSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { LSP_TEST_MS, startServer, waitFor, type Client } from './lsp-stdio-client.js';

const EXAMPLES = fileURLToPath(new URL('../../../examples/', import.meta.url));

interface Diag { range: { start: { line: number; character: number }; end: { line: number; character: number } }; severity: number; code: string; source: string; message: string }
interface Item { label: string; detail?: string; textEdit?: { newText: string } }
type Hover = { contents: { kind: string; value: string } } | null;

describe('contract-language-server: .scenario files', () => {
    let dir: string;
    let client: Client;
    const uri = (file: string) => pathToFileURL(join(dir, file)).toString();
    const versions = new Map<string, number>();
    const open = (file: string, text: string, languageId = 'cactal-scenario') => {
        versions.set(file, 1);
        client.notify('textDocument/didOpen', { textDocument: { uri: uri(file), languageId, version: 1, text } });
    };
    const change = (file: string, text: string) => {
        const version = (versions.get(file) ?? 1) + 1;
        versions.set(file, version);
        client.notify('textDocument/didChange', { textDocument: { uri: uri(file), version }, contentChanges: [{ text }] });
    };
    /** Waits for a diagnostics notification after the `count` already seen, returns the latest. */
    const nextDiagnostics = async (file: string, count: number): Promise<Diag[]> => {
        await waitFor(() => client.publishedCount(uri(file)) > count);
        expect(client.publishedCount(uri(file)), `diagnostics for ${file}`).toBeGreaterThan(count);
        return client.latestDiagnostics<Diag>(uri(file))!;
    };
    const completion = async (file: string, line: number, character: number) =>
        (await client.request<{ items: Item[] }>('textDocument/completion', { textDocument: { uri: uri(file) }, position: { line, character } })).items;
    const hover = (file: string, line: number, character: number) =>
        client.request<Hover>('textDocument/hover', { textDocument: { uri: uri(file) }, position: { line, character } });

    beforeAll(async () => {
        dir = mkdtempSync(join(tmpdir(), 'cactal-lsp-scenario-'));
        for (const example of ['tutorial', 'mobile-robot']) {
            for (const f of readdirSync(join(EXAMPLES, example)).filter((x) => x.endsWith('.contract'))) cpSync(join(EXAMPLES, example, f), join(dir, example, f));
            cpSync(join(EXAMPLES, example, 'scenarios'), join(dir, example, 'scenarios'), { recursive: true });
        }
        ({ client } = await startServer(dir));
    }, LSP_TEST_MS);

    afterAll(async () => {
        await client?.stop();
        if (dir) rmSync(dir, { recursive: true, force: true });
    }, LSP_TEST_MS);

    it('publishes no diagnostic for the example scenarios, each checked against its own project', async () => {
        const files = ['tutorial/scenarios/commutation.scenario', 'tutorial/scenarios/mission.scenario', 'mobile-robot/scenarios/modes.scenario'];
        for (const f of files) open(f, readFileSync(join(dir, f), 'utf8'));
        for (const f of files) expect(await nextDiagnostics(f, 0), f).toEqual([]);
    }, LSP_TEST_MS);

    it('a scenario opened with the Cactal language id (a client that maps every file to cactal) is still checked as a scenario, against its project', async () => {
        const f = 'tutorial/scenarios/as-cactal.scenario';
        const text = readFileSync(join(dir, 'tutorial/scenarios/mission.scenario'), 'utf8');
        open(f, text, 'cactal');
        expect(await nextDiagnostics(f, 0)).toEqual([]);
        // and its problems are the scenario checker's, against the tutorial's modules
        change(f, `${text}\nt=999s NOM:0 1\n`);
        const after = await nextDiagnostics(f, 1);
        const unknown = after.filter((d) => d.code === 'scenario-unknown-module');
        expect(unknown).toHaveLength(1);
        expect(unknown[0]!.message).toBe("no module or supervisor 'NOM' emits events in the project (those that do: MAA, MSC, SUP)");
    }, LSP_TEST_MS);

    it('reports each problem of a broken scenario with its range, code, severity and message', async () => {
        const text = [
            'scenario broken on purpose',                   // 0
            'start SUP.action(consigne = {1.0, 2.0, 3.0})', // 1
            't=100ms MAA:7 "x"',                            // 2: no out event port 7
            'expect rule SUP.action.SECNOD active',         // 3: misspelt rule
            't=200ms MAA:2 connection_status = 3',          // 4: a string port given an integer
            't=150ms MSC:1 {"overheat", 3}',                // 5: time goes backwards
            'expect module MAB runing',                     // 6: syntax
            'expect schema schemaCommande3 active',         // 7: unknown schema, close to two
            't=1s MZA:0 1',                                 // 8: unknown module, MAA is close
        ].join('\n');
        open('tutorial/scenarios/broken.scenario', text);
        const d = await nextDiagnostics('tutorial/scenarios/broken.scenario', 0);
        const at = (line: number) => d.filter((x) => x.range.start.line === line);
        const lines = text.split('\n');
        const col = (line: number, s: string) => lines[line]!.indexOf(s);

        expect(at(2)).toEqual([expect.objectContaining({
            code: 'scenario-unknown-port', severity: 1, source: 'cactal-scenario',
            range: { start: { line: 2, character: col(2, '7') }, end: { line: 2, character: col(2, '7') + 1 } },
            message: 'MAA has no out event port 7 (out event ports: :0 message_type_notification, :1 received_message, :2 connection_status)',
        })]);
        expect(at(3)).toEqual([expect.objectContaining({
            code: 'scenario-unknown-rule', severity: 1,
            range: { start: { line: 3, character: col(3, 'SECNOD') }, end: { line: 3, character: col(3, 'SECNOD') + 6 } },
            message: "SUP.action has no rule 'SECNOD' (rules: FIRST, SECOND, THIRD, FOURTH, RECEPTION). Did you mean 'SECOND'?",
        })]);
        expect(at(4)).toEqual([expect.objectContaining({
            code: 'scenario-value-type', severity: 1,
            range: { start: { line: 4, character: col(4, '3') }, end: { line: 4, character: col(4, '3') + 1 } },
            message: 'Expected a string ("...") for MAA:2 (string connection_status), found the integer 3.',
        })]);
        expect(at(5)).toEqual([expect.objectContaining({
            code: 'scenario-time-order', severity: 1,
            range: { start: { line: 5, character: 2 }, end: { line: 5, character: 7 } },
            message: "steps go forward in time: 150ms is before the previous step's 200ms",
        })]);
        expect(at(6)).toEqual([expect.objectContaining({ code: 'scenario-syntax', severity: 1, message: "expected 'running' or 'stopped', found 'runing'. Did you mean 'running'?" })]);
        expect(at(6)[0]!.range.start.character).toBe(col(6, 'runing'));
        expect(at(7)).toEqual([expect.objectContaining({ code: 'scenario-unknown-schema', message: expect.stringMatching(/^no schema 'schemaCommande3' in the project \(schemas: .*\)\. Did you mean 'schemaCommande[12]'\?$/) })]);
        expect(at(8)).toEqual([expect.objectContaining({ code: 'scenario-unknown-module', message: expect.stringContaining("Did you mean 'MAA'?") })]);
        expect(d).toHaveLength(7);

        // Fixed: the diagnostics go away.
        const count = client.publishedCount(uri('tutorial/scenarios/broken.scenario'));
        change('tutorial/scenarios/broken.scenario', lines.slice(0, 2).join('\n') + '\nexpect rule SUP.action.SECOND inactive\n');
        expect(await nextDiagnostics('tutorial/scenarios/broken.scenario', count)).toEqual([]);
    }, LSP_TEST_MS);

    it('reports a misspelt rule and an ill-typed value in a broken variant of the mobile robot\'s scenario', async () => {
        const file = 'mobile-robot/scenarios/broken.scenario';
        const text = readFileSync(join(dir, 'mobile-robot/scenarios/modes.scenario'), 'utf8')
            .replace('expect rule MIS.mission.TELEOP active', 'expect rule MIS.mission.TELEOPP active')
            .replace('t=500ms OBS:0 distance = 0.3', 't=500ms OBS:0 distance = "near"');
        open(file, text);
        const d = await nextDiagnostics(file, 0);
        const lines = text.split('\n');
        const rule = lines.findIndex((l) => l.includes('TELEOPP'));
        const obs = lines.findIndex((l) => l.includes('"near"'));
        expect(d.map((x) => [x.range.start.line, x.range.start.character, x.range.end.character, x.code])).toEqual([
            [rule, lines[rule]!.indexOf('TELEOPP'), lines[rule]!.indexOf('TELEOPP') + 7, 'scenario-unknown-rule'],
            [obs, lines[obs]!.indexOf('"near"'), lines[obs]!.indexOf('"near"') + 6, 'scenario-value-type'],
        ]);
        expect(d[0]!.message).toMatch(/^MIS\.mission has no rule 'TELEOPP' \(rules: .*\)\. Did you mean 'TELEOP'\?$/);
        expect(d[1]!.message).toContain('float');
    }, LSP_TEST_MS);

    it('re-checks an open scenario when a .contract file of its project changes', async () => {
        const file = 'tutorial/scenarios/commutation.scenario';
        const supervisor = readFileSync(join(dir, 'tutorial/supervisor.contract'), 'utf8');
        const before = client.publishedCount(uri(file));
        open('tutorial/supervisor.contract', supervisor, 'cactal');
        change('tutorial/supervisor.contract', supervisor.replace(/\bFOURTH\b/g, 'FOURTH_B'));
        await waitFor(() => (client.latestDiagnostics<Diag>(uri(file)) ?? []).some((x) => x.code === 'scenario-unknown-rule'));
        const d = client.latestDiagnostics<Diag>(uri(file))!;
        expect(client.publishedCount(uri(file))).toBeGreaterThan(before);
        expect(d.map((x) => x.message)).toEqual([
            "SUP.action has no rule 'FOURTH' (rules: FIRST, SECOND, THIRD, FOURTH_B, RECEPTION). Did you mean 'FOURTH_B'?",
        ]);
        // The other project's scenario is not about this supervisor: still clean.
        expect(client.latestDiagnostics(uri('mobile-robot/scenarios/modes.scenario'))).toEqual([]);
        change('tutorial/supervisor.contract', supervisor);
        await waitFor(() => client.latestDiagnostics<Diag>(uri(file))?.length === 0);
        expect(client.latestDiagnostics(uri(file))).toEqual([]);
    }, LSP_TEST_MS);

    it('completes keywords, module names, event ports, rules, schemas, locals and the values the rules test', async () => {
        const file = 'tutorial/scenarios/typing.scenario';
        const lines = ['', 't=1ms MAA:', 'expect rule SUP.action.', 't=2ms MAA:2 ', 'expect schema ', 'expect local SUP.action.', 'start SUP.action(', 'expect ', 't=3ms ORD:0 ', 'exec ', 'start SUP.action(consigne = ', 'expect local SUP.action.failure_data == ', 't=4ms MAA:0 message_type_notification = ', 'finish ', 'finish MAB ', 'expect deadline misses ', 'expect deadline ', 'expect overruns s'];
        open(file, lines.join('\n'));
        const labels = async (line: number) => (await completion(file, line, lines[line]!.length)).map((i) => i.label);

        expect(await labels(0)).toEqual(expect.arrayContaining(['t=', 'start', 'stop', 'expect', 'crash', 'finish', 'exec', 'scenario', 'until', 'MAA:', 'MSC:', 'SUP:', 'ORD:']));
        const ports = await completion(file, 1, lines[1]!.length);
        expect(ports.map((i) => `${i.label} ${i.detail}`)).toEqual([
            '0 out event :0 TypeC message_type_notification of MAA',
            '1 out event :1 TypeE received_message of MAA',
            '2 out event :2 string connection_status of MAA',
        ]);
        expect(await labels(2)).toEqual(['FIRST', 'SECOND', 'THIRD', 'FOURTH', 'RECEPTION']);
        expect(await labels(3)).toEqual(['connection_status =', '"disconnected"', '""']);
        expect(await labels(4)).toEqual(expect.arrayContaining(['schemaReceptionMessage', 'schemaCommande1', 'schemaCommande2']));
        expect(await labels(5)).toEqual(['temp_message', 'temp_mess_type', 'failure_data', 'temp_consigne']);
        expect(await labels(6)).toEqual(['consigne']);
        expect(await labels(7)).toEqual(['rule', 'schema', 'function', 'module', 'local', 'deadline misses', 'overruns', 'at']);
        // deadline misses and overruns: the periodic schemas only (an event schema has no period)
        expect(await labels(15)).toEqual(['schemaCommande1', 'schemaCommande2']);
        expect(await labels(16)).toEqual(['misses']);
        expect(await labels(17)).toEqual(['schemaCommande1', 'schemaCommande2']);
        expect(await labels(8)).toEqual(expect.arrayContaining(['"schemaCommande1"']));
        expect(await labels(9)).toEqual(['MAA', 'MAB', 'MSA', 'MSB', 'MSC', 'MSD']);
        expect(await labels(13)).toEqual(['MAA', 'MAB']); // finish: the asynchronous modules only
        expect(await labels(14)).toEqual(['after']); // finish MAB after TIME: each of its runs
        // Value templates: the type's default, one element per field.
        expect(await labels(10)).toEqual(['{0.0, 0.0, 0.0}']);
        expect(await labels(11)).toEqual(['{"", 0}']);
        const message = await completion(file, 12, lines[12]!.length);
        expect(message.map((i) => [i.label, i.detail])).toEqual([['{"", 0, {0.0, 0.0, 0.0}}', "TypeC message_type_notification: the type's default value, to edit"]]);

        // The mobile robot's scenario sees the mobile robot, not the tutorial.
        const robot = 'mobile-robot/scenarios/typing.scenario';
        open(robot, 't=1ms TEL:1 ');
        const values = (await completion(robot, 0, '"t=1ms TEL:1 '.length - 1)).map((i) => i.label);
        expect(values).toContain('"auto"');
        expect((await completion(robot, 0, 0)).map((i) => i.label)).not.toContain('MAA:');
    }, LSP_TEST_MS);

    it('hovers a port with its type and declaration, a rule with its conditions, a schema with its period, a time in µs', async () => {
        const file = 'tutorial/scenarios/commutation.scenario';
        const lines = readFileSync(join(dir, file), 'utf8').split('\n');
        const find = (s: string) => {
            const line = lines.findIndex((l) => l.includes(s));
            return { line, character: lines[line]!.indexOf(s) };
        };
        const value = async (s: string, offset = 0) => {
            const p = find(s);
            const h = await hover(file, p.line, p.character + offset);
            return h?.contents.value ?? '';
        };
        const port = await value('MAA:2 connection_status', 4);
        expect(port).toContain('**MAA:2**: out event port of `MAA`, type `string`');
        expect(port).toMatch(/out :2 string connection_status;?\n```\ndeclared at amodule1\.contract:\d+/);
        const rule = await value('SUP.action.SECOND active', 'SUP.action.'.length + 1);
        expect(rule).toContain('**rule SUP.action.SECOND** (supervisor.contract:');
        expect(rule).toContain('precondition: `(MAA:2<(connection_status == "disconnected" & testit ("dedede", temp_consigne))> and started(FIRST){infinite})`');
        expect(rule).toContain('postcondition: `MSC:1(failure_data = failure, temp_mess_type = "commutation")`');
        const schema = await value('schema schemaCommande1 active', 'schema '.length + 2);
        expect(schema).toMatch(/^\*\*periodic schema schemaCommande1\*\* \(sschema1\.contract:\d+\)\n\nPERIOD = [0-9,.]+ µs, CRITICAL_DELAY = [0-9,.]+ µs$/);
        expect(await value('t=300ms', 4)).toBe('**300ms** = 300,000 µs (300,000,000 ns) of virtual time');
        expect(await value('t=1.2s', 3)).toBe('**1.2s** = 1,200,000 µs (1,200,000,000 ns) of virtual time');
        expect(await value('expect local temp_mess_type', 'expect local '.length + 1)).toContain('**string temp_mess_type**: local of SUP.action');
        expect(await hover(file, 0, 3)).toBeNull(); // a comment
        // The mobile robot's scenario: its own ports and rules.
        const robot = 'mobile-robot/scenarios/modes.scenario';
        const robotLines = readFileSync(join(dir, robot), 'utf8').split('\n');
        const teleop = robotLines.findIndex((l) => l.startsWith('t=200ms TEL:1'));
        expect((await hover(robot, teleop, 't=200ms TEL:'.length))?.contents.value).toMatch(/^\*\*TEL:1\*\*: out event port of `TEL`, type `string`[\s\S]*out :1 string request;[\s\S]*declared at teleop\.contract:7$/);
        const distance = robotLines.findIndex((l) => l.startsWith('t=500ms OBS:0'));
        expect((await hover(robot, distance, 't=500ms OBS:0 dis'.length))?.contents.value).toContain('type `float`');
        // Requests that mean nothing for a scenario answer empty, not with an error.
        expect(await client.request('textDocument/documentSymbol', { textDocument: { uri: uri(file) } })).toBeNull();
    }, LSP_TEST_MS);
});
