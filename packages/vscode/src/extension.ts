/**
 * The Cactal extension: starts the ContrACT Studio language server over stdio (the one bundled in
 * dist/server.js, or `cactal.server.path`) for the .contract and .scenario files of the workspace.
 */
import * as path from 'node:path';
import type { ExtensionContext } from 'vscode';
import { workspace } from 'vscode';
import { LanguageClient, TransportKind, type LanguageClientOptions, type ServerOptions } from 'vscode-languageclient/node';

let client: LanguageClient | undefined;

export async function activate(context: ExtensionContext): Promise<void> {
    const configured = workspace.getConfiguration('cactal').get<string>('server.path', '');
    const module = configured || context.asAbsolutePath(path.join('dist', 'server.js'));
    const serverOptions: ServerOptions = {
        run: { module, transport: TransportKind.stdio },
        debug: { module, transport: TransportKind.stdio, options: { execArgv: ['--nolazy', '--inspect=6009'] } },
    };
    const clientOptions: LanguageClientOptions = {
        // .scenario files too (language id cactal-scenario): the server checks them against the model
        documentSelector: [{ scheme: 'file', language: 'cactal' }, { scheme: 'file', language: 'cactal-scenario' }],
        synchronize: { fileEvents: workspace.createFileSystemWatcher('**/*.{contract,scenario}') },
    };
    client = new LanguageClient('cactal', 'Cactal language server', serverOptions, clientOptions);
    await client.start();
}

export async function deactivate(): Promise<void> {
    await client?.stop();
    client = undefined;
}
