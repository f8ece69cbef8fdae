/**
 * A module printing past the run's output limit (docs/sandbox.md "Limits": the limit does not kill)
 * keeps its period whatever its reader does: a real bwrap run of the `contract new` project whose CTL
 * prints without end — 1,000 lines (about 25 KB) in every release of its 10 ms period — with a
 * 64 KiB output limit, and a reader that stops reading for 3 s once the limit is reached (this
 * process, where the service runs, blocked from the output-truncated notice on: a busy or slow
 * reader). contract-launch drops the lines past the limit itself (CONTRACT_OUTPUT_LIMIT_BYTES), so
 * CTL's output is drained whether the reader reads or not: CTL finishes its releases and answers the
 * stop's KILL. Before, every line past the cut still went through contract-launch, one write each,
 * to the reader that dropped it: with the reader stalled, the launcher blocked on its full stdout,
 * CTL on its full pipe, and ORD reported CTL stuck (a release not finished after 10 periods, at
 * least 1 s: docs/engines.md §4). A flood alone, without the stall (100,000 lines in one release;
 * 2,000 lines a release), did not tell the two launchers apart: the old relay kept up with it.
 */
import { readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';

let root: string;
beforeAll(async () => {
    root = await makeSeededScratch('contract-output-flood-');
}, 240_000);
afterAll(() => removeSeededScratch(root));

/** Blocks this process (the in-process service, its reading of the run's output with it) for `ms`. */
const stall = (ms: number) => Atomics.wait(new Int32Array(new SharedArrayBuffer(4)), 0, 0, ms);

it('a module printing without end past the output limit keeps its period while the reader stalls: its releases finish, no stuck or KILL problem', async () => {
    expect(await runCli(['new', 'flood'], capture(root))).toBe(0);
    expect(await runCli(['generate', 'flood'], capture(root))).toBe(0);
    const file = join(root, 'flood/src-gen/generated/architecture/modules/CTL_mod/module.c');
    const source = readFileSync(file, 'utf8');
    const flooding = source.replace(/(PROTECTED REGION ID\(protect_exec_CTL\) ENABLED START\*\/)/,
        '$1\n    { static long release = 0; release++; for (long i = 0; i < 1000; i++) printf("line %ld of release %ld\\n", i, release); }');
    expect(flooding).not.toBe(source);
    writeFileSync(file, flooding);
    const io = capture(root);
    let stalledAt = 0;
    const out = io.out.bind(io);
    io.out = (text: string) => {
        out(text);
        // the service's notice of the cut, passed on as it comes: from here the reader reads nothing for 3 s
        if (!stalledAt && text.startsWith('[output truncated: stdout limit 64 KiB reached')) {
            stalledAt = Date.now();
            stall(3000);
        }
    };
    const code = await runCli(['run', 'flood', '--sandbox', 'bwrap', '--duration', '5s', '--limit', 'outputBytesPerStream=65536'], io);
    expect(stalledAt, `${io.stdout.slice(-1500)}\n${io.stderr.slice(-3000)}`).toBeGreaterThan(0);
    const logs = join(root, 'flood/logs');
    const ord = readFileSync(join(logs, readdirSync(logs).find((f) => f.startsWith('ORD_'))!), 'utf8');
    const released = ord.split('\n').filter((l) => l.includes(',ord_release,CTL,')).length;
    const finished = ord.split('\n').filter((l) => l.includes(',ord_finished,CTL,')).length;
    const said = `${released} releases of CTL, ${finished} finished\n${io.stderr}`;
    // the cut is the only problem: no module stuck, none hung at the stop
    expect(code, said).toBe(4);
    expect(io.stderr, said).toMatch(/^FAILED: run finished with 1 problem\(s\): the run's stdout went past the output limit \(64 KiB per stream\)/m);
    expect(io.stderr, said).not.toMatch(/stuck|did not end on its KILL/);
    expect(io.stderr, said).toContain('contract-launch: all modules stopped cleanly\n');
    // CTL went on being released at its 10 ms period through the stall (500 in 5 s; a loaded machine
    // gives fewer) and finished them, all but the one the stop may cut
    expect(released, said).toBeGreaterThan(150);
    expect(finished, said).toBeGreaterThanOrEqual(released - 1);
    expect(ord, said).not.toContain('stuck: CTL');
}, 240_000);
