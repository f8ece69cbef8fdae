/**
 * A module printing past the run's output limit (docs/sandbox.md "Limits": the limit does not kill)
 * keeps its period: a real bwrap run of the `contract new` project whose CTL prints 100,000 lines
 * (about 2.4 MB) in its first release, with a 64 KiB output limit (the 1 MiB default is kept line by
 * line by the service: on a loaded machine that alone can take more than ORD's 1 s; and 10 MB take
 * a loaded machine's module itself more than 1 s to print). Before, every
 * line past the cut still went through contract-launch, one write each, to the service that
 * dropped it: CTL blocked on its full stdout pipe for seconds, ORD reported it stuck and it did not
 * answer the stop's KILL. Now contract-launch drops the lines past the limit itself
 * (CONTRACT_OUTPUT_LIMIT_BYTES) and relays the others in blocks.
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

it('a module printing past the output limit keeps its period: its releases finish, the run ends with no stuck or KILL problem', async () => {
    expect(await runCli(['new', 'flood'], capture(root))).toBe(0);
    expect(await runCli(['generate', 'flood'], capture(root))).toBe(0);
    const file = join(root, 'flood/src-gen/generated/architecture/modules/CTL_mod/module.c');
    const source = readFileSync(file, 'utf8');
    const flooding = source.replace(/(PROTECTED REGION ID\(protect_exec_CTL\) ENABLED START\*\/)/,
        '$1\n    { static long release = 0; if (++release == 1) for (long i = 0; i < 100000; i++) printf("line %ld of the flood\\n", i); }');
    expect(flooding).not.toBe(source);
    writeFileSync(file, flooding);
    const io = capture(root);
    const code = await runCli(['run', 'flood', '--sandbox', 'bwrap', '--duration', '3s', '--limit', 'outputBytesPerStream=65536', '--format', 'json'], io);
    const out = JSON.parse(io.stdout) as { result: { issues: { kind: string; message: string }[] }; output: { source: string; line: string }[] };
    const said = JSON.stringify(out.result.issues, null, 1);
    // the cut is the only problem: no module stuck, none hung at the stop
    expect(out.result.issues.map((i) => i.kind), said).toEqual(['output-truncated']);
    expect(code).toBe(4);
    const launcher = out.output.filter((l) => l.source === 'launcher').map((l) => l.line);
    expect(launcher, launcher.join('\n')).toContain('all modules stopped cleanly');
    // CTL went on being released at its 10 ms period (300 in 3 s; a loaded machine gives fewer) and finished them
    const logs = join(root, 'flood/logs');
    const ord = readFileSync(join(logs, readdirSync(logs).find((f) => f.startsWith('ORD_'))!), 'utf8');
    const releases = ord.split('\n').filter((l) => l.includes(',ord_release,CTL,')).length;
    expect(releases).toBeGreaterThan(100);
    expect(ord).not.toContain('stuck: CTL');
}, 240_000);
