import { statSync } from 'node:fs';
import { resolve } from 'node:path';
import { startIdeServer, DEFAULT_PORT } from './ide-server.js';
import { BuildLimitsRefused } from './integrations.js';
import { addLimitOption, emptyLimitOptions } from '@contract-studio/conventions';

export interface ServeArgs {
  workspace: string;
  port: number;
  host: string;
  /** The build service's sandbox for the IDE's jobs (default auto: bubblewrap where it works, else Docker). */
  sandbox: ServeSandbox;
  /** `--limit NAME=VALUE`: the build service's limits for the IDE's jobs (docs/sandbox.md "Limits"), above or below the defaults. */
  limits: Record<string, number>;
  /** The same values as written (messages quote them; a count or a size must be written as the whole number it is). */
  limitTexts: Record<string, string>;
}

/** The sandboxes `--sandbox` takes (`none` is not one: the IDE's build service refuses it). */
export const SERVE_SANDBOXES = ['auto', 'bwrap', 'docker'] as const;
export type ServeSandbox = (typeof SERVE_SANDBOXES)[number];
const USAGE = 'usage: contract serve [DIR] [--port N] [--host ADDR] [--sandbox auto|bwrap|docker] [--limit NAME=VALUE]...\n(contract serve --help lists every option)';

/** Parses `[DIR] [--port N] [--host H] [--sandbox S]`; throws with a usage message on bad input. */
export function parseServeArgs(argv: string[], defaultDir: string): ServeArgs {
  // no prototype: `--limit __proto__=1` is a name like any other (refused as unknown), not a prototype
  const out: ServeArgs = { workspace: defaultDir, port: DEFAULT_PORT, host: '127.0.0.1', sandbox: 'auto', ...emptyLimitOptions() };
  for (let i = 0; i < argv.length; i++) {
    const a = argv[i]!;
    if (a === '--port' || a === '-p') {
      const n = Number(argv[++i]);
      if (!Number.isInteger(n) || n < 0 || n > 65535) throw new Error(`--port needs a number 0..65535, got ${argv[i] ?? 'nothing'}\n${USAGE}`);
      out.port = n;
    } else if (a.startsWith('--port=')) {
      return parseServeArgs([...argv.slice(0, i), '--port', a.slice(7), ...argv.slice(i + 1)], defaultDir);
    } else if (a === '--host') {
      const h = argv[++i];
      if (!h) throw new Error(`--host needs an address\n${USAGE}`);
      out.host = h;
    } else if (a === '--sandbox' || a.startsWith('--sandbox=')) {
      const s = a === '--sandbox' ? argv[++i] : a.slice('--sandbox='.length);
      if (!SERVE_SANDBOXES.includes(s as ServeSandbox)) throw new Error(`--sandbox needs one of ${SERVE_SANDBOXES.join(', ')}, got ${s ?? 'nothing'}\n${USAGE}`);
      out.sandbox = s as ServeSandbox;
    } else if (a === '--limit' || a.startsWith('--limit=')) {
      // the reading contract run and contract build share (conventions' limit-option.ts)
      const refused = addLimitOption(out, a === '--limit' ? argv[++i] : a.slice('--limit='.length));
      if (refused) throw new Error(`${refused}\n${USAGE}`);
    } else if (a.startsWith('-')) {
      throw new Error(`unknown option ${a}\n${USAGE}`);
    } else out.workspace = a;
  }
  out.workspace = resolve(out.workspace);
  return out;
}

/** Runs the server until SIGINT/SIGTERM; returns the exit code on failure to start. */
export async function runServe(argv: string[], defaultDir: string): Promise<number> {
  let args: ServeArgs;
  try {
    args = parseServeArgs(argv, defaultDir);
  } catch (e) {
    console.error(`contract serve: ${(e as Error).message}`);
    return 2;
  }
  // a DIR that is not there (or not a folder) is bad usage, said before anything starts
  const dir = statSync(args.workspace, { throwIfNoEntry: false });
  if (!dir?.isDirectory()) {
    console.error(`contract serve: ${args.workspace} is ${dir ? 'not a folder' : 'not there'}: give the workspace folder (the project, or a folder of projects)\n${USAGE}`);
    return 2;
  }
  try {
    const ide = await startIdeServer(args);
    // the URL carries the session token (session-token.ts): only whoever reads this output may drive the IDE
    console.log(`ContrACT Studio IDE: ${ide.openUrl}  (workspace ${JSON.stringify(ide.workspace)})`);
    console.log(`  ${ide.buildServiceNote}`);
    if (args.host !== '127.0.0.1' && args.host !== 'localhost') console.warn(`  warning: listening on ${args.host}, reachable from other machines`);
    const stop = () => {
      void ide.close().then(() => process.exit(0));
    };
    process.once('SIGINT', stop);
    process.once('SIGTERM', stop);
    return await new Promise<number>(() => undefined);
  } catch (e) {
    // a limit the build service does not know, or a value it refuses: bad usage, said by the
    // service's own check as the server starts (nothing runs yet: it is the first thing started)
    if (e instanceof BuildLimitsRefused) {
      console.error(`contract serve: --limit: ${e.message}\n${USAGE}`);
      return 2;
    }
    const err = e as NodeJS.ErrnoException;
    if (err.code === 'EADDRINUSE') console.error(`contract serve: port ${args.port} is in use; pick another with --port N`);
    else console.error(`contract serve: ${err.message}`);
    return 1;
  }
}
