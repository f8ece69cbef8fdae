/**
 * What `contract trace` tells of a run's logs or of a trace file (`contract run --trace`, `contract
 * simulate --trace`): its story, and its records as JSON lines (`--format json`).
 */
import { expect } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';

/** The story and the records of `target` (a logs folder or a trace file), read from `cwd`. */
export async function toldTrace(cwd: string, target: string): Promise<{ story: string; json: Record<string, unknown>[] }> {
    const text = capture(cwd);
    expect(await runCli(['trace', target], text), text.stderr).toBe(0);
    const json = capture(cwd);
    expect(await runCli(['trace', target, '--format', 'json'], json), json.stderr).toBe(0);
    return { story: text.stdout, json: json.stdout.trim().split('\n').map((l) => JSON.parse(l) as Record<string, unknown>) };
}
