/**
 * The VS Code extension as users install it: `npm run package` builds dist/cactal-vscode.vsix with
 * vsce; the .vsix carries the language contribution, the language package's TextMate grammar and a
 * language server that runs on its own (no node_modules): extracted alone into a temp folder, it
 * answers an LSP session over stdio driven by vscode-jsonrpc (initialize, diagnostics).
 */
import { execFileSync, spawn } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import {
    createProtocolConnection, DidOpenTextDocumentNotification, InitializedNotification, InitializeRequest,
    PublishDiagnosticsNotification, ShutdownRequest, StreamMessageReader, StreamMessageWriter, type PublishDiagnosticsParams,
} from 'vscode-languageserver-protocol/node.js';

const PACKAGE = fileURLToPath(new URL('..', import.meta.url));
const VSIX = join(PACKAGE, 'dist', 'cactal-vscode.vsix');
let scratch: string;

const fromVsix = (entry: string): string => execFileSync('unzip', ['-p', VSIX, entry], { encoding: 'utf8', maxBuffer: 64 * 1024 * 1024 });

beforeAll(() => {
    scratch = mkdtempSync(join(tmpdir(), 'cactal-vsix-'));
    execFileSync('npm', ['run', 'package'], { cwd: PACKAGE, stdio: 'pipe', timeout: 300_000 });
}, 300_000);
afterAll(() => rmSync(scratch, { recursive: true, force: true }));

describe('cactal-vscode.vsix', () => {
    it('contributes the cactal language for .contract files with the language package\'s TextMate grammar', () => {
        const manifest = JSON.parse(fromVsix('extension/package.json')) as {
            main: string;
            contributes: { languages: Array<{ id: string; extensions: string[] }>; grammars: Array<{ language: string; scopeName: string; path: string }> };
        };
        // .scenario files too (they were not contributed: no checks, completion nor hover in VS Code), with their # comments
        expect(manifest.contributes.languages).toEqual([
            expect.objectContaining({ id: 'cactal', extensions: ['.contract'] }),
            expect.objectContaining({ id: 'cactal-scenario', extensions: ['.scenario'], configuration: './scenario-language-configuration.json' }),
        ]);
        expect(JSON.parse(fromVsix('extension/scenario-language-configuration.json')).comments).toEqual({ lineComment: '#' });
        expect(fromVsix(`extension/${manifest.main.replace(/^\.\//, '')}`)).toContain('cactal-scenario');
        const grammar = manifest.contributes.grammars[0]!;
        const packed = fromVsix(`extension/${grammar.path.replace(/^\.\//, '')}`);
        const generated = readFileSync(join(PACKAGE, '..', 'language', 'syntaxes', 'cactal.tmLanguage.json'), 'utf8');
        expect(packed).toBe(generated);
        expect(JSON.parse(packed).scopeName).toBe(grammar.scopeName);
        expect(fromVsix(`extension/${manifest.main.replace(/^\.\//, '')}`)).toContain('Cactal language server');
    });

    it('carries a language server that runs alone and publishes diagnostics over stdio', async () => {
        const server = join(scratch, 'server.js');
        execFileSync('sh', ['-c', `unzip -p "$1" extension/dist/server.js > "$2"`, 'sh', VSIX, server]);
        const child = spawn(process.execPath, [server, '--stdio'], { cwd: scratch, stdio: 'pipe' });
        const connection = createProtocolConnection(new StreamMessageReader(child.stdout), new StreamMessageWriter(child.stdin));
        try {
            const diagnostics = new Promise<PublishDiagnosticsParams>((resolve) => connection.onNotification(PublishDiagnosticsNotification.type, resolve));
            connection.onRequest('workspace/configuration', (p: { items: unknown[] }) => p.items.map(() => null));
            connection.listen();
            const init = await connection.sendRequest(InitializeRequest.type, { processId: process.pid, rootUri: pathToFileURL(scratch).toString(), capabilities: {}, workspaceFolders: null });
            expect(init.capabilities.hoverProvider).toBeTruthy();
            await connection.sendNotification(InitializedNotification.type, {});
            const uri = pathToFileURL(join(scratch, 'bad.contract')).toString();
            await connection.sendNotification(DidOpenTextDocumentNotification.type, { textDocument: { uri, languageId: 'cactal', version: 1, text: 'synchronous module msa { scheduling { C=1ms; } }' } });
            const published = await diagnostics;
            expect(published.uri).toBe(uri);
            expect(published.diagnostics.length).toBeGreaterThan(0);
            await connection.sendRequest(ShutdownRequest.type);
        } finally {
            connection.dispose();
            child.kill();
        }
    }, 60_000);
});
