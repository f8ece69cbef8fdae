/**
 * The stdio language server (`contract-language-server`) as a desktop editor drives it, through a
 * real LSP client library (vscode-languageserver-protocol's node connection over vscode-jsonrpc):
 * initialize with a workspace folder whose files are on disk, then diagnostics pushed for an
 * opened file, hover, definition into another file, and a rename that edits every file that
 * refers to the entity (docs/editors.md). Runs the built server: `npm run build` first.
 */
import { spawn, type ChildProcessWithoutNullStreams } from 'node:child_process';
import { existsSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import {
    createProtocolConnection, DefinitionRequest, DidOpenTextDocumentNotification, ExitNotification, HoverRequest,
    InitializedNotification, InitializeRequest, PublishDiagnosticsNotification, RenameRequest, ShutdownRequest,
    StreamMessageReader, StreamMessageWriter, type Location, type LocationLink, type MarkupContent,
    type ProtocolConnection, type PublishDiagnosticsParams,
} from 'vscode-languageserver-protocol/node.js';
import { ARCHITECTURE } from './lsp-workspace.js';
import { LSP_TEST_MS, SERVER } from './lsp-stdio-client.js';


describe('contract-language-server driven by vscode-jsonrpc', () => {
    let dir: string;
    let child: ChildProcessWithoutNullStreams;
    let connection: ProtocolConnection;
    const published = new Map<string, PublishDiagnosticsParams>();
    const waiters: Array<() => void> = [];
    const uri = (file: string) => pathToFileURL(join(dir, file)).toString();
    const text = (file: string) => ARCHITECTURE[file] ?? '';
    /** The 0-based position of `needle` (+ delta characters) in a fixture file. */
    const at = (file: string, needle: string, delta = 0) => {
        const lines = text(file).split('\n');
        const line = lines.findIndex((l) => l.includes(needle));
        if (line < 0) throw new Error(`'${needle}' not in ${file}`);
        return { line, character: lines[line]!.indexOf(needle) + delta };
    };
    const diagnosticsOf = (file: string) => new Promise<PublishDiagnosticsParams>((resolve) => {
        const check = () => {
            const p = published.get(uri(file));
            if (p) resolve(p); else waiters.push(check);
        };
        check();
    });

    beforeAll(async () => {
        if (!existsSync(SERVER)) throw new Error(`${SERVER} is missing: run \`npm run build -w packages/language\` first`);
        dir = mkdtempSync(join(tmpdir(), 'cactal-jsonrpc-'));
        for (const [file, content] of Object.entries(ARCHITECTURE)) writeFileSync(join(dir, file), content);
        child = spawn(process.execPath, [SERVER, '--stdio'], { stdio: 'pipe' });
        connection = createProtocolConnection(new StreamMessageReader(child.stdout), new StreamMessageWriter(child.stdin));
        connection.onNotification(PublishDiagnosticsNotification.type, (p) => {
            published.set(p.uri, p);
            for (const w of waiters.splice(0)) w();
        });
        // what the server may ask a client
        connection.onRequest('workspace/configuration', (p: { items: unknown[] }) => p.items.map(() => null));
        for (const method of ['client/registerCapability', 'window/workDoneProgress/create', 'workspace/semanticTokens/refresh']) connection.onRequest(method, () => null);
        connection.listen();
        const init = await connection.sendRequest(InitializeRequest.type, {
            processId: process.pid, rootUri: pathToFileURL(dir).toString(), capabilities: {},
            workspaceFolders: [{ uri: pathToFileURL(dir).toString(), name: 'robot' }],
        });
        expect(init.capabilities.renameProvider).toBeTruthy();
        await connection.sendNotification(InitializedNotification.type, {});
    }, LSP_TEST_MS);

    afterAll(async () => {
        await connection?.sendRequest(ShutdownRequest.type).catch(() => undefined);
        await connection?.sendNotification(ExitNotification.type).catch(() => undefined);
        connection?.dispose();
        if (child && child.exitCode === null) child.kill();
        if (dir) rmSync(dir, { recursive: true, force: true });
    }, LSP_TEST_MS);

    it('pushes diagnostics for an opened file, with the code and the place of the problem', async () => {
        const bad = 'synchronous module msa { scheduling { C=1ms; } }';
        await connection.sendNotification(DidOpenTextDocumentNotification.type, { textDocument: { uri: uri('bad.contract'), languageId: 'cactal', version: 1, text: bad } });
        const { diagnostics } = await diagnosticsOf('bad.contract');
        expect(diagnostics.length).toBeGreaterThan(0);
        expect(diagnostics.every((d) => d.range.start.line === 0 && typeof d.code === 'string' && d.message.length > 0)).toBe(true);
    }, LSP_TEST_MS);

    it('a file nested thousands of brackets deep gets the nesting error and the server goes on (it crashed: the guard was not on the server\'s way in)', async () => {
        const deep = `const D K = ${'{'.repeat(5000)}1${'}'.repeat(5000)};`;
        await connection.sendNotification(DidOpenTextDocumentNotification.type, { textDocument: { uri: uri('deep.contract'), languageId: 'cactal', version: 1, text: deep } });
        const { diagnostics } = await diagnosticsOf('deep.contract');
        expect(diagnostics.map((d) => d.message)).toEqual([expect.stringContaining('Brackets are nested 65 levels deep here; Cactal accepts at most 64')]);
        expect(child.exitCode).toBeNull();
    }, LSP_TEST_MS);

    it('answers hover and a definition in another file', async () => {
        await connection.sendNotification(DidOpenTextDocumentNotification.type, { textDocument: { uri: uri('schema.contract'), languageId: 'cactal', version: 1, text: text('schema.contract') } });
        const position = at('schema.contract', 'MSC:1 -> MSD', 1);
        const hover = await connection.sendRequest(HoverRequest.type, { textDocument: { uri: uri('schema.contract') }, position });
        expect((hover?.contents as MarkupContent).value).toMatch(/MSC/);
        const found = await connection.sendRequest(DefinitionRequest.type, { textDocument: { uri: uri('schema.contract') }, position });
        const targets = (Array.isArray(found) ? found : found ? [found] : []) as Array<Location | LocationLink>;
        expect(targets.map((t) => ('targetUri' in t ? t.targetUri : t.uri))).toContain(uri('msc.contract'));
    }, LSP_TEST_MS);

    it('renames a module in every file that refers to it, files not opened included', async () => {
        const position = at('schema.contract', 'MSC(consigne', 1);
        const edit = await connection.sendRequest(RenameRequest.type, { textDocument: { uri: uri('schema.contract') }, position, newName: 'MSX' });
        const changes = edit?.changes ?? {};
        expect(Object.keys(changes).sort()).toEqual([uri('msc.contract'), uri('schema.contract'), uri('sup.contract')].sort());
        for (const edits of Object.values(changes)) expect(edits.every((e) => e.newText === 'MSX')).toBe(true);
        const declaration = at('msc.contract', 'MSC {');
        expect(changes[uri('msc.contract')]!.map((e) => e.range.start)).toContainEqual(declaration);
        expect(changes[uri('schema.contract')]!.length).toBe(4); // modules {...}, the graph, two communications
    }, LSP_TEST_MS);
});
