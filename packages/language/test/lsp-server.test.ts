/**
 * The stdio language server (`contract-language-server`, dist/node/main.js) answers a real LSP
 * session: initialize (capabilities), didOpen of files on disk, outline, hover, definition across
 * files, formatting, then shutdown/exit. Runs the built server: `npm run build` first.
 */
import { spawn, type ChildProcessWithoutNullStreams } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { ARCHITECTURE } from './lsp-workspace.js';

const SERVER = fileURLToPath(new URL('../dist/node/main.js', import.meta.url));

/** Minimal LSP client over the server's stdio (Content-Length framing). */
class Client {
    private buffer = Buffer.alloc(0);
    private nextId = 1;
    private readonly pending = new Map<number, (msg: { result?: unknown; error?: { message: string } }) => void>();
    readonly notifications: Array<{ method: string; params: unknown }> = [];

    constructor(private readonly child: ChildProcessWithoutNullStreams) {
        child.stdout.on('data', (chunk: Buffer) => this.receive(chunk));
    }

    private receive(chunk: Buffer): void {
        this.buffer = Buffer.concat([this.buffer, chunk]);
        for (;;) {
            const headerEnd = this.buffer.indexOf('\r\n\r\n');
            if (headerEnd < 0) return;
            const length = Number(/Content-Length: (\d+)/i.exec(this.buffer.subarray(0, headerEnd).toString())?.[1]);
            if (this.buffer.length < headerEnd + 4 + length) return;
            const msg = JSON.parse(this.buffer.subarray(headerEnd + 4, headerEnd + 4 + length).toString());
            this.buffer = this.buffer.subarray(headerEnd + 4 + length);
            if (msg.id !== undefined && msg.method === undefined) this.pending.get(msg.id)?.(msg);
            else if (msg.id !== undefined) this.send({ jsonrpc: '2.0', id: msg.id, result: null }); // server -> client requests
            else this.notifications.push(msg);
        }
    }

    private send(msg: unknown): void {
        const body = Buffer.from(JSON.stringify(msg));
        this.child.stdin.write(`Content-Length: ${body.length}\r\n\r\n`);
        this.child.stdin.write(body);
    }

    request<T>(method: string, params: unknown): Promise<T> {
        const id = this.nextId++;
        return new Promise((resolve, reject) => {
            const timer = setTimeout(() => reject(new Error(`${method}: no answer in 20 s`)), 20_000);
            this.pending.set(id, (msg) => {
                clearTimeout(timer);
                if (msg.error) reject(new Error(msg.error.message)); else resolve(msg.result as T);
            });
            this.send({ jsonrpc: '2.0', id, method, params });
        });
    }

    notify(method: string, params: unknown): void {
        this.send({ jsonrpc: '2.0', method, params });
    }
}

describe('contract-language-server (stdio)', () => {
    let dir: string;
    let child: ChildProcessWithoutNullStreams;
    let client: Client;
    const uri = (file: string) => pathToFileURL(join(dir, file)).toString();

    beforeAll(async () => {
        if (!existsSync(SERVER)) throw new Error(`${SERVER} is missing: run \`npm run build -w packages/language\` first`);
        dir = mkdtempSync(join(tmpdir(), 'cactal-lsp-'));
        for (const [file, text] of Object.entries(ARCHITECTURE)) writeFileSync(join(dir, file), text);
        child = spawn(process.execPath, [SERVER, '--stdio'], { stdio: 'pipe' });
        client = new Client(child);
        const init = await client.request<{ capabilities: Record<string, unknown> }>('initialize', {
            processId: process.pid, rootUri: pathToFileURL(dir).toString(), capabilities: {},
            workspaceFolders: [{ uri: pathToFileURL(dir).toString(), name: 'ws' }]
        });
        expect(Object.keys(init.capabilities)).toEqual(expect.arrayContaining([
            'documentSymbolProvider', 'hoverProvider', 'completionProvider', 'definitionProvider', 'referencesProvider',
            'renameProvider', 'documentFormattingProvider', 'codeActionProvider', 'semanticTokensProvider'
        ]));
        client.notify('initialized', {});
        for (const file of ['schema.contract', 'msc.contract']) {
            client.notify('textDocument/didOpen', { textDocument: { uri: uri(file), languageId: 'cactal', version: 1, text: readFileSync(join(dir, file), 'utf8') } });
        }
    }, 30_000);

    afterAll(async () => {
        if (client) {
            await client.request('shutdown', null).catch(() => undefined);
            client.notify('exit', null);
        }
        if (child && child.exitCode === null) {
            await new Promise((resolve) => { const t = setTimeout(() => { child.kill(); resolve(undefined); }, 3000); child.on('exit', () => { clearTimeout(t); resolve(undefined); }); });
        }
        if (dir) rmSync(dir, { recursive: true, force: true });
    });

    it('serves outline, hover, cross-file definition and formatting for files read from disk', async () => {
        const symbols = await client.request<Array<{ name: string; children?: Array<{ name: string }> }>>('textDocument/documentSymbol', { textDocument: { uri: uri('msc.contract') } });
        expect(symbols.map((s) => s.name)).toEqual(['MSC']);
        expect(symbols[0]!.children!.map((c) => c.name)).toEqual(['consigne', 'in_coordinates', 'command', 'failing']);

        // `MSC:1 -> MSD:2 * 2;` is line 9 (0-based 8) of schema.contract
        const line = ARCHITECTURE['schema.contract']!.split('\n').findIndex((l) => l.includes('MSC:1 -> MSD'));
        const col = ARCHITECTURE['schema.contract']!.split('\n')[line]!.indexOf('MSC:1 -> MSD') + 4;
        const hover = await client.request<{ contents: { value: string } }>('textDocument/hover', { textDocument: { uri: uri('schema.contract') }, position: { line, character: col } });
        expect(hover.contents.value).toContain('out data port :1 of `MSC`, type `TypeB`');

        const links = await client.request<Array<{ targetUri: string }>>('textDocument/definition', { textDocument: { uri: uri('schema.contract') }, position: { line, character: col - 3 } });
        expect(links.map((l) => l.targetUri)).toEqual([uri('msc.contract')]);

        const edits = await client.request<Array<{ newText: string }>>('textDocument/formatting', { textDocument: { uri: uri('msc.contract') }, options: { tabSize: 4, insertSpaces: true } });
        expect(edits.length).toBe(1);
        expect(edits[0]!.newText).toContain('scheduling {\n        C = 1ms;\n    }');
    }, 30_000);

    it('publishes diagnostics with codes for an opened file with a problem', async () => {
        client.notify('textDocument/didOpen', { textDocument: { uri: uri('bad.contract'), languageId: 'cactal', version: 1, text: 'synchronous module msa { scheduling { C=1ms; } }' } });
        const deadline = Date.now() + 20_000;
        let codes: string[] = [];
        while (Date.now() < deadline && !codes.includes('module-name-format')) {
            await new Promise((r) => setTimeout(r, 100));
            codes = client.notifications
                .filter((n) => n.method === 'textDocument/publishDiagnostics' && (n.params as { uri: string }).uri === uri('bad.contract'))
                .flatMap((n) => (n.params as { diagnostics: Array<{ code?: string }> }).diagnostics.map((d) => String(d.code)));
        }
        expect(codes).toContain('module-name-format');
    }, 30_000);

    it('refreshes the diagnostics of a file that does not refer to a newly opened one (scheduler-missing)', async () => {
        const latestCodes = (file: string) => {
            const published = client.notifications.filter((n) => n.method === 'textDocument/publishDiagnostics' && (n.params as { uri: string }).uri === uri(file));
            const last = published[published.length - 1]?.params as { diagnostics: Array<{ code?: string }> } | undefined;
            return last?.diagnostics.map((d) => String(d.code));
        };
        const waitFor = async (condition: () => boolean) => {
            const deadline = Date.now() + 20_000;
            while (Date.now() < deadline && !condition()) await new Promise((r) => setTimeout(r, 100));
        };
        await waitFor(() => latestCodes('schema.contract')?.includes('scheduler-missing') ?? false);
        expect(latestCodes('schema.contract')).toContain('scheduler-missing');
        const sched = 'import "msa.contract";\nimport "msc.contract";\nimport "msd.contract";\nimport "schema.contract";\n' +
            'scheduler configuration { modules { MSA; MSC; MSD; } schemas { cmd; } }\n';
        client.notify('textDocument/didOpen', { textDocument: { uri: uri('sched.contract'), languageId: 'cactal', version: 1, text: sched } });
        await waitFor(() => latestCodes('sched.contract') !== undefined && !(latestCodes('schema.contract') ?? []).includes('scheduler-missing'));
        expect(latestCodes('sched.contract')).toEqual([]);
        expect(latestCodes('schema.contract')).not.toContain('scheduler-missing');
    }, 45_000);
});
