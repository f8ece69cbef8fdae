/**
 * Minimal LSP client over a language server's stdio (Content-Length framing), for the tests that
 * drive the built `contract-language-server` (lsp-server.test.ts, lsp-scenario-server.test.ts).
 */
import { spawn, type ChildProcessWithoutNullStreams } from 'node:child_process';
import { existsSync } from 'node:fs';
import { fileURLToPath, pathToFileURL } from 'node:url';

/** The built stdio server (`contract-language-server`): `npm run build -w packages/language` first. */
export const SERVER = fileURLToPath(new URL('../dist/node/main.js', import.meta.url));

/**
 * How long a test waits for the server's answer or notification: an answer, not a latency. `make
 * test` runs this suite at nice 19 beside two lanes of sandboxes and browsers, where a server can
 * wait for a CPU for tens of seconds (an `initialize` took over 20 s there once). LSP_TEST_MS bounds
 * a whole test or hook that waits for several.
 */
export const LSP_WAIT_MS = 120_000;
export const LSP_TEST_MS = 300_000;

/** Minimal LSP client over the server's stdio (Content-Length framing). */
export class Client {
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
            const timer = setTimeout(() => reject(new Error(`${method}: no answer in ${LSP_WAIT_MS / 1000} s`)), LSP_WAIT_MS);
            this.pending.set(id, (msg) => {
                clearTimeout(timer);
                if (msg.error) reject(new Error(msg.error.message)); else resolve(msg.result as T);
            });
            this.send({ jsonrpc: '2.0', id, method, params });
        });
    }

    /** LSP shutdown then exit; the server is killed when it has not exited 3 s later. */
    async stop(): Promise<void> {
        await this.request('shutdown', null).catch(() => undefined);
        this.notify('exit', null);
        if (this.child.exitCode !== null) return;
        await new Promise<void>((resolve) => {
            const t = setTimeout(() => { this.child.kill(); resolve(); }, 3000);
            this.child.on('exit', () => { clearTimeout(t); resolve(); });
        });
    }

    notify(method: string, params: unknown): void {
        this.send({ jsonrpc: '2.0', method, params });
    }

    /** The diagnostics last published for `uri`, or undefined before the first. */
    latestDiagnostics<D = { code?: string; message: string }>(uri: string): D[] | undefined {
        const published = this.notifications.filter((n) => n.method === 'textDocument/publishDiagnostics' && (n.params as { uri: string }).uri === uri);
        return (published[published.length - 1]?.params as { diagnostics: D[] } | undefined)?.diagnostics;
    }

    /** How many diagnostics notifications arrived for `uri` so far. */
    publishedCount(uri: string): number {
        return this.notifications.filter((n) => n.method === 'textDocument/publishDiagnostics' && (n.params as { uri: string }).uri === uri).length;
    }
}

/** Polls `condition` every 50 ms for up to `ms`. */
export async function waitFor(condition: () => boolean, ms = LSP_WAIT_MS): Promise<void> {
    const deadline = Date.now() + ms;
    while (Date.now() < deadline && !condition()) await new Promise((r) => setTimeout(r, 50));
}

/**
 * Starts the built server over stdio and initializes it, on workspace folder `folder` (its rootUri
 * too), or on none (`null`: a client that sends no folder), the client offering `clientCapabilities`
 * (none by default); the capabilities it answered.
 */
export async function startServer(folder: string | null, clientCapabilities: Record<string, unknown> = {}): Promise<{ client: Client; capabilities: Record<string, unknown> }> {
    if (!existsSync(SERVER)) throw new Error(`${SERVER} is missing: run \`npm run build -w packages/language\` first`);
    const client = new Client(spawn(process.execPath, [SERVER, '--stdio'], { stdio: 'pipe' }));
    const uri = folder === null ? null : pathToFileURL(folder).toString();
    const init = await client.request<{ capabilities: Record<string, unknown> }>('initialize', {
        processId: process.pid, rootUri: uri, capabilities: clientCapabilities,
        workspaceFolders: uri === null ? null : [{ uri, name: 'ws' }],
    });
    client.notify('initialized', {});
    return { client, capabilities: init.capabilities };
}
