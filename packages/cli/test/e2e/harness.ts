/**
 * End-to-end harness: runs the real `contract` binary (packages/cli/bin/contract.js) on a copy of
 * an example, with its own cache folder (CONTRACT_CACHE_DIR) so the test can prove that nothing of
 * the run is left behind (no process, no workspace).
 */
import { spawnSync } from 'node:child_process';
import { chmodSync, cpSync, mkdtempSync, readdirSync, readFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { expect } from 'vitest';
import { seedRuntime } from '@contract-studio/build-service/test-support/runtime-seed';
import { readLogs, type LogRecord } from './csv-log.js';
import { removeScratch } from '../scratch.js';

export const REPO = fileURLToPath(new URL('../../../../', import.meta.url));
export const BIN = join(REPO, 'packages/cli/bin/contract.js');

export interface Scratch {
    root: string;
    project: string;
    cache: string;
    logs: string;
    dispose(): void;
}

/** A temp folder with a copy of examples/<name> (without logs) and an empty cache folder. */
export function scratchCopy(example: string): Scratch {
    const root = mkdtempSync(join(tmpdir(), `contract-e2e-${example}-`));
    chmodSync(root, 0o711); // the sandbox's own uid must reach the cache folder inside
    const project = join(root, example);
    cpSync(join(REPO, 'examples', example), project, { recursive: true, filter: (src) => !/\/logs$/.test(src) });
    return {
        root,
        project,
        cache: join(root, 'cache'),
        logs: join(root, 'logs'),
        dispose: () => removeScratch(root),
    };
}

/**
 * scratchCopy, its cache holding the test run's built runtime (build-service test-support
 * runtime-seed: `make test` builds it once for all the files that do not test a cold cache).
 */
export async function seededScratchCopy(example: string): Promise<Scratch> {
    const scratch = scratchCopy(example);
    await seedRuntime(scratch.cache);
    return scratch;
}

export interface CliRun {
    code: number | null;
    stdout: string;
    stderr: string;
}

export function contract(args: string[], scratch: Scratch, timeoutMs = 240_000): CliRun {
    const r = spawnSync(process.execPath, [BIN, ...args], {
        cwd: scratch.root,
        encoding: 'utf8',
        timeout: timeoutMs,
        maxBuffer: 64 * 1024 * 1024,
        env: { ...process.env, CONTRACT_CACHE_DIR: scratch.cache },
    });
    return { code: r.status, stdout: r.stdout ?? '', stderr: r.stderr ?? '' };
}

/** Processes whose command line mentions `marker` (e.g. the scratch folder). */
export function processesMentioning(marker: string): string[] {
    const found: string[] = [];
    for (const pid of readdirSync('/proc').filter((p) => /^\d+$/.test(p))) {
        if (Number(pid) === process.pid) continue;
        let cmdline = '';
        try {
            cmdline = readFileSync(`/proc/${pid}/cmdline`, 'utf8').replace(/\0/g, ' ');
        } catch {
            continue;
        }
        if (cmdline.includes(marker)) found.push(`${pid}: ${cmdline.trim()}`);
    }
    return found;
}

/**
 * Per-job workspaces left in the cache (`<cache>/ws/`, removed when the service closes). A
 * project's own work tree (`<cache>/projects/`) is kept on purpose: the build cache.
 */
export function leftoverWorkspaces(scratch: Scratch): string[] {
    try {
        return readdirSync(join(scratch.cache, 'ws')).map((n) => join('ws', n));
    } catch {
        return []; // no ws folder: removed
    }
}

export interface RunJson {
    ok: boolean;
    status: string;
    sandbox: string;
    result: { ok: boolean; step: string; message: string };
    diagnostics: { severity: string; message: string }[];
    prepareDiagnostics: unknown[];
    logsDir: string | null;
    logs: string[];
    moduleFailures: { module: string; how: string }[];
    runDirLeftovers: string[];
    output: { source: string; stream: string; line: string }[];
}

export interface ExampleRun {
    json: RunJson;
    code: number | null;
    /** The CSV logs written to scratch.logs. */
    logs: LogRecord[];
}

/** `contract run <example> --sandbox <sandbox> --duration <duration>` with its CSV logs in scratch.logs. */
export function runExample(example: string, sandbox: string, duration: string, scratch: Scratch): ExampleRun {
    const r = contract(['run', example, '--sandbox', sandbox, '--duration', duration, '--logs', scratch.logs, '--format', 'json'], scratch);
    return { json: JSON.parse(r.stdout) as RunJson, code: r.code, logs: readLogs(scratch.logs) };
}

/**
 * A run that went to its end: exit 0, no module failure, every module stopped cleanly, nothing left
 * behind (no socket or pid file in the run directory, no process, no workspace), `csvLogs` logs back.
 */
export function expectCleanRun(run: ExampleRun, scratch: Scratch, csvLogs: number): void {
    expect(run.json.result.message).toBe('run finished (exit 0)');
    expect(run.code).toBe(0);
    expect(run.json.moduleFailures).toEqual([]);
    expect(run.json.output.some((l) => l.source === 'launcher' && l.line === 'all modules stopped cleanly')).toBe(true);
    expect(run.json.runDirLeftovers).toEqual([]);
    expect(processesMentioning(scratch.root)).toEqual([]);
    expect(leftoverWorkspaces(scratch)).toEqual([]);
    expect(run.json.logs.length).toBe(csvLogs);
}
