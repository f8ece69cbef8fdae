// The language server's latency on a field-sized project (large-supervisor-architecture.js: 50
// modules, 70 files, a 350-line supervisor), driven over stdio as an editor drives the built
// `contract-language-server`: an edit in a rule of the large supervisor -> its diagnostics
// published, and completion at a rule's condition right after an edit (the request waits for the
// build the edit started, as in an editor while typing). Median of `runs` of each, ms, and the
// server's CPU time per edit (Linux /proc).
// Needs `npm run build -w packages/language`. `node bench/large-supervisor-latency.mjs [runs]`
// prints the figures; run-bench.mjs calls measureLargeSupervisorLatency.
import { spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { LARGE_SUPERVISOR_FILE, writeLargeSupervisorArchitecture } from './large-supervisor-architecture.js';

const SERVER = fileURLToPath(new URL('../dist/node/main.js', import.meta.url));
const WAIT_MS = 120_000;
const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

/** Minimal LSP client over the server's stdio (Content-Length framing). */
function startClient() {
    const child = spawn(process.execPath, [...(process.env.LSP_BENCH_NODE_ARGS?.split(' ').filter(Boolean) ?? []), SERVER, '--stdio'], { stdio: ['pipe', 'pipe', 'inherit'] });
    let buffer = Buffer.alloc(0);
    let nextId = 1;
    const pending = new Map();
    const listeners = new Set();
    child.stdout.on('data', (chunk) => {
        buffer = Buffer.concat([buffer, chunk]);
        for (;;) {
            const headerEnd = buffer.indexOf('\r\n\r\n');
            if (headerEnd < 0) return;
            const length = Number(/Content-Length: (\d+)/i.exec(buffer.subarray(0, headerEnd).toString())?.[1]);
            if (buffer.length < headerEnd + 4 + length) return;
            const msg = JSON.parse(buffer.subarray(headerEnd + 4, headerEnd + 4 + length).toString());
            buffer = buffer.subarray(headerEnd + 4 + length);
            if (msg.id !== undefined && msg.method === undefined) pending.get(msg.id)?.(msg);
            else if (msg.id !== undefined) send({ jsonrpc: '2.0', id: msg.id, result: null });
            else for (const l of listeners) l(msg);
        }
    });
    const send = (msg) => {
        const body = Buffer.from(JSON.stringify(msg));
        child.stdin.write(`Content-Length: ${body.length}\r\n\r\n`);
        child.stdin.write(body);
    };
    const request = (method, params) => new Promise((resolve, reject) => {
        const id = nextId++;
        const timer = setTimeout(() => reject(new Error(`${method}: no answer in ${WAIT_MS / 1000} s`)), WAIT_MS);
        pending.set(id, (msg) => { clearTimeout(timer); pending.delete(id); if (msg.error) reject(new Error(msg.error.message)); else resolve(msg.result); });
        send({ jsonrpc: '2.0', id, method, params });
    });
    const notify = (method, params) => send({ jsonrpc: '2.0', method, params });
    /** The next diagnostics published for `uri` (registered before the message that causes them is sent). */
    const nextDiagnostics = (uri) => new Promise((resolve, reject) => {
        const timer = setTimeout(() => { listeners.delete(l); reject(new Error(`no diagnostics for ${uri} in ${WAIT_MS / 1000} s`)); }, WAIT_MS);
        const l = (msg) => {
            if (msg.method !== 'textDocument/publishDiagnostics' || msg.params.uri !== uri) return;
            clearTimeout(timer);
            listeners.delete(l);
            resolve(msg.params.diagnostics);
        };
        listeners.add(l);
    });
    const stop = async () => {
        await request('shutdown', null).catch(() => undefined);
        notify('exit', null);
        if (child.exitCode !== null) return;
        await new Promise((resolve) => {
            const t = setTimeout(() => { child.kill(); resolve(); }, 3000);
            child.on('exit', () => { clearTimeout(t); resolve(); });
        });
    };
    /** The server's CPU time so far (user + system), ms; Linux /proc, 10 ms ticks. */
    const cpuMs = () => {
        const fields = readFileSync(`/proc/${child.pid}/stat`, 'utf8').split(') ')[1].split(' ');
        return (Number(fields[11]) + Number(fields[12])) * 10;
    };
    return { request, notify, nextDiagnostics, stop, cpuMs };
}

function fail(message) {
    throw new Error(`large supervisor latency: ${message}`);
}

/**
 * @param {number} runs edits (and completions) measured, after two unmeasured ones
 * @returns {Promise<Record<string, number>>}
 */
export async function measureLargeSupervisorLatency(runs = 7) {
    const dir = mkdtempSync(join(tmpdir(), 'cactal-large-sup-'));
    const client = startClient();
    try {
        const files = writeLargeSupervisorArchitecture(dir);
        const path = join(dir, LARGE_SUPERVISOR_FILE);
        const uri = pathToFileURL(path).toString();
        const rootUri = pathToFileURL(dir).toString();
        await client.request('initialize', { processId: process.pid, rootUri, capabilities: {}, workspaceFolders: [{ uri: rootUri, name: 'ws' }] });
        client.notify('initialized', {});
        const original = readFileSync(path, 'utf8');
        const lines = original.split('\n');
        let version = 1;
        let first = client.nextDiagnostics(uri);
        client.notify('textDocument/didOpen', { textDocument: { uri, languageId: 'cactal', version, text: original } });
        const opened = await first;
        if (opened.length) fail(`the large supervisor has ${opened.length} diagnostics, first: ${opened[0].message}`);

        // the edit: a test's constant in a rule of the first function (`== 99` <-> `== 98`): no project fact changes
        const line = lines.findIndex((l) => l.includes('.value == 99>'));
        const character = lines[line].indexOf('99') + 1;
        const edit = (digit) => ({ range: { start: { line, character }, end: { line, character: character + 1 } }, text: digit });
        // completion where a rule's condition starts: just after `WATCH: [` of the second function
        const condLine = lines.findIndex((l, i) => i > line + 20 && l.includes('WATCH: ['));
        const condition = { line: condLine, character: lines[condLine].indexOf('WATCH: [') + 'WATCH: ['.length };

        const diagnosticsTimes = [];
        const cpuTimes = [];
        const completionTimes = [];
        let items = 0;
        for (let i = 0; i < runs + 2; i++) {
            const published = client.nextDiagnostics(uri);
            const c0 = client.cpuMs();
            const t0 = performance.now();
            client.notify('textDocument/didChange', { textDocument: { uri, version: ++version }, contentChanges: [edit(i % 2 === 0 ? '8' : '9')] });
            const diagnostics = await published;
            const t1 = performance.now();
            const c1 = client.cpuMs();
            if (diagnostics.length) fail(`an edit gave ${diagnostics.length} diagnostics, first: ${diagnostics[0].message}`);
            // completion right after the next edit, which it waits for
            const again = client.nextDiagnostics(uri);
            client.notify('textDocument/didChange', { textDocument: { uri, version: ++version }, contentChanges: [edit(i % 2 === 0 ? '9' : '8')] });
            const t2 = performance.now();
            const answer = await client.request('textDocument/completion', { textDocument: { uri }, position: condition });
            const t3 = performance.now();
            await again;
            const list = Array.isArray(answer) ? answer : answer?.items ?? [];
            if (!list.some((c) => /ORD|elapsed|endof/.test(c.label))) fail(`completion at a rule's condition offers no event: ${JSON.stringify(list.slice(0, 5))}`);
            items = list.length;
            if (i >= 2) { diagnosticsTimes.push(t1 - t0); cpuTimes.push(c1 - c0); completionTimes.push(t3 - t2); }
        }
        return {
            'language.large_supervisor_diagnostics_ms': Math.round(median(diagnosticsTimes)),
            // the server's CPU time from the edit to the diagnostics (10 ms ticks): the cost, apart from waiting for a CPU
            'language.large_supervisor_diagnostics_cpu_ms': Math.round(median(cpuTimes)),
            'language.large_supervisor_completion_ms': Math.round(median(completionTimes)),
            'language.large_supervisor_completion_items': items,
            'language.large_supervisor_files': files,
            'language.large_supervisor_lines': lines.length - 1
        };
    } finally {
        await client.stop();
        rmSync(dir, { recursive: true, force: true });
    }
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
    console.log(JSON.stringify(await measureLargeSupervisorLatency(Number(process.argv[2] ?? 7)), null, 2));
}
