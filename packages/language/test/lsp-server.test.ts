/**
 * The stdio language server (`contract-language-server`, dist/node/main.js) answers a real LSP
 * session: initialize (capabilities), didOpen of files on disk, outline, hover, definition across
 * files, formatting, then shutdown/exit. Runs the built server: `npm run build` first.
 */
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { pathToFileURL } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { ARCHITECTURE } from './lsp-workspace.js';
import { LSP_TEST_MS, LSP_WAIT_MS, startServer, type Client } from './lsp-stdio-client.js';

describe('contract-language-server (stdio)', () => {
    let dir: string;
    let client: Client;
    const uri = (file: string) => pathToFileURL(join(dir, file)).toString();

    beforeAll(async () => {
        dir = mkdtempSync(join(tmpdir(), 'cactal-lsp-'));
        for (const [file, text] of Object.entries(ARCHITECTURE)) writeFileSync(join(dir, file), text);
        let capabilities: Record<string, unknown>;
        ({ client, capabilities } = await startServer(dir));
        expect(Object.keys(capabilities)).toEqual(expect.arrayContaining([
            'documentSymbolProvider', 'hoverProvider', 'completionProvider', 'definitionProvider', 'referencesProvider',
            'renameProvider', 'documentFormattingProvider', 'codeActionProvider', 'semanticTokensProvider'
        ]));
        for (const file of ['schema.contract', 'msc.contract']) {
            client.notify('textDocument/didOpen', { textDocument: { uri: uri(file), languageId: 'cactal', version: 1, text: readFileSync(join(dir, file), 'utf8') } });
        }
    }, LSP_TEST_MS);

    afterAll(async () => {
        await client?.stop();
        if (dir) rmSync(dir, { recursive: true, force: true });
    }, LSP_TEST_MS);

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
    }, LSP_TEST_MS);

    it('formatting a file with a syntax error changes nothing and says why (window/showMessage)', async () => {
        client.notify('textDocument/didOpen', { textDocument: { uri: uri('broken.contract'), languageId: 'cactal', version: 1, text: 'synchronous module MSZ {\n    scheduling { C=1ms }\n}' } });
        const edits = await client.request<unknown[]>('textDocument/formatting', { textDocument: { uri: uri('broken.contract') }, options: { tabSize: 4, insertSpaces: true } });
        expect(edits).toEqual([]);
        const deadline = Date.now() + LSP_WAIT_MS;
        let shown: Array<{ type: number; message: string }> = [];
        while (Date.now() < deadline && !shown.length) {
            await new Promise((r) => setTimeout(r, 50));
            shown = client.notifications.filter((n) => n.method === 'window/showMessage').map((n) => n.params as { type: number; message: string });
        }
        expect(shown).toHaveLength(1);
        expect(shown[0]!.type).toBe(2); // warning
        expect(shown[0]!.message).toMatch(/^Not formatted: line 2, column \d+: .+Fix the syntax error first/);
    }, LSP_TEST_MS);

    it('publishes diagnostics with codes for an opened file with a problem', async () => {
        client.notify('textDocument/didOpen', { textDocument: { uri: uri('bad.contract'), languageId: 'cactal', version: 1, text: 'synchronous module msa { scheduling { C=1ms; } }' } });
        const deadline = Date.now() + LSP_WAIT_MS;
        let codes: string[] = [];
        while (Date.now() < deadline && !codes.includes('module-name-format')) {
            await new Promise((r) => setTimeout(r, 100));
            codes = client.notifications
                .filter((n) => n.method === 'textDocument/publishDiagnostics' && (n.params as { uri: string }).uri === uri('bad.contract'))
                .flatMap((n) => (n.params as { diagnostics: Array<{ code?: string }> }).diagnostics.map((d) => String(d.code)));
        }
        expect(codes).toContain('module-name-format');
    }, LSP_TEST_MS);

    it('refreshes the diagnostics of a file that does not refer to a newly opened one (scheduler-missing)', async () => {
        const latestCodes = (file: string) => {
            const published = client.notifications.filter((n) => n.method === 'textDocument/publishDiagnostics' && (n.params as { uri: string }).uri === uri(file));
            const last = published[published.length - 1]?.params as { diagnostics: Array<{ code?: string }> } | undefined;
            return last?.diagnostics.map((d) => String(d.code));
        };
        const waitFor = async (condition: () => boolean) => {
            const deadline = Date.now() + LSP_WAIT_MS;
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
    }, LSP_TEST_MS);
});

describe('contract-language-server (stdio) given no workspace folder', () => {
    let dir: string;
    let client: Client;
    const uri = (file: string) => pathToFileURL(join(dir, file)).toString();

    beforeAll(async () => {
        dir = mkdtempSync(join(tmpdir(), 'cactal-lsp-nofolder-'));
        for (const [file, text] of Object.entries(ARCHITECTURE)) writeFileSync(join(dir, file), text);
        ({ client } = await startServer(null));
    }, LSP_TEST_MS);

    afterAll(async () => {
        await client?.stop();
        if (dir) rmSync(dir, { recursive: true, force: true });
    }, LSP_TEST_MS);

    it('reads the files an open file imports from disk, and theirs: no import-missing-file, and definition leads into them', async () => {
        // schema.contract imports types, msa, msc and msd; those import types.contract again
        client.notify('textDocument/didOpen', { textDocument: { uri: uri('schema.contract'), languageId: 'cactal', version: 1, text: ARCHITECTURE['schema.contract'] } });
        const deadline = Date.now() + LSP_WAIT_MS;
        const codes = () => client.latestDiagnostics<{ code?: string }>(uri('schema.contract'))?.map((d) => String(d.code));
        while (Date.now() < deadline && (codes() === undefined || codes()!.includes('import-missing-file') || codes()!.some((c) => c.startsWith('linking')))) {
            await new Promise((r) => setTimeout(r, 100));
        }
        expect(codes()).toBeDefined();
        expect(codes()).not.toContain('import-missing-file');
        const line = ARCHITECTURE['schema.contract']!.split('\n').findIndex((l) => l.includes('MSC:1 -> MSD'));
        const col = ARCHITECTURE['schema.contract']!.split('\n')[line]!.indexOf('MSC:1 -> MSD') + 1;
        const def = await client.request<Array<{ uri?: string; targetUri?: string }>>('textDocument/definition', { textDocument: { uri: uri('schema.contract') }, position: { line, character: col } });
        expect(def.map((d) => d.targetUri ?? d.uri)).toEqual([uri('msc.contract')]);
    }, LSP_TEST_MS);

    it('leaves an import of a missing file reported missing', async () => {
        client.notify('textDocument/didOpen', { textDocument: { uri: uri('lone.contract'), languageId: 'cactal', version: 1, text: 'import "nowhere.contract";\nimport "types.contract";\n' } });
        const deadline = Date.now() + LSP_WAIT_MS;
        const codes = () => client.latestDiagnostics<{ code?: string }>(uri('lone.contract'))?.map((d) => String(d.code));
        while (Date.now() < deadline && codes() === undefined) await new Promise((r) => setTimeout(r, 100));
        expect(codes()).toContain('import-missing-file');
        expect(client.latestDiagnostics<{ message: string }>(uri('lone.contract'))!.filter((d) => /types\.contract/.test(d.message) && /not found|missing|does not exist/i.test(d.message))).toEqual([]);
    }, LSP_TEST_MS);
});
