/**
 * `contract serve [DIR] [--port N] [--host ADDR] [--sandbox S] [--limit NAME=VALUE]...`: the web IDE and the build service on one
 * localhost port, opening the workspace folder DIR (default: the repository's tutorial example).
 * The server lives in @contract-studio/web-ide (loaded at run time, so `contract check` etc. do
 * not pay for it). Runs until Ctrl+C; exit 1 when it cannot start (port in use, no folder), 2 on bad usage.
 */
import { existsSync } from 'node:fs';
import { resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { EXIT_FAILURE, type CliIO, type Command } from '../command.js';

const TUTORIAL = fileURLToPath(new URL('../../../../examples/tutorial', import.meta.url));

interface WebIde {
    runServe(argv: string[], defaultDir: string): Promise<number>;
}

export const serveCommand: Command = {
    name: 'serve',
    summary: 'serve the web IDE + build service on a workspace folder (localhost)',
    usage: [
        'usage: contract serve [DIR] [--port N] [--host ADDR] [--sandbox auto|bwrap|docker] [--limit NAME=VALUE]...',
        '  DIR: workspace folder (default: the tutorial example)',
        '  --sandbox: where the IDE\'s builds and runs go (default auto: bubblewrap where it works, else Docker; docker needs an engine and the image: scripts/docker-up.sh)',
        '  --port: TCP port (default 7400; 0 = any free port); the URL is printed on start',
        '  --host: address to bind (default 127.0.0.1; anything else is reachable from other machines)',
        '  --limit NAME=VALUE: a build service limit for the IDE\'s jobs, above or below its default (repeatable; docs/sandbox.md "Limits"):',
        '           memoryMiB, processes, buildSeconds, runSeconds, outputBytesPerStream, workDiskMiB, tmpMiB, prepareSeconds, modelBytes, generatedFiles;',
        '           e.g. an hour-long run: --limit runSeconds=3660 --limit workDiskMiB=4096 --limit memoryMiB=4096 (the CSV logs are in both)',
    ].join('\n'),
    async run(args: string[], io: CliIO): Promise<number> {
        let ide: WebIde;
        try {
            const name = '@contract-studio/web-ide';
            ide = (await import(name)) as WebIde;
        } catch (err) {
            io.err(`contract serve: the web IDE is not available (${err instanceof Error ? err.message.split('\n')[0] : String(err)}); install @contract-studio/web-ide next to the CLI, or run \`npm run build\` at the repository root\n`);
            return EXIT_FAILURE;
        }
        const argv = args.map((a, i) => (!a.startsWith('-') && !['--port', '-p', '--host', '--sandbox', '--limit'].includes(args[i - 1] ?? '') ? resolve(io.cwd, a) : a));
        const fallback = existsSync(TUTORIAL) ? TUTORIAL : io.cwd;
        return ide.runServe(argv, fallback);
    },
};
