/**
 * A real run of the tutorial (bubblewrap) with `--trace FILE.jsonl` whose module MAB is SIGKILLed
 * from outside about a second in. The trace file carries the launcher's end line of MAB as a
 * `launcher_line` object, at the time the launcher's lines file gives it and in time order among
 * the records, so `contract trace FILE` alone (no logs folder beside it) tells MAB gone at its last
 * record, the launcher's line as the evidence, before the run's stop. A launcher line forged into
 * the file whose pid is not the module's own (as its `module_started` record gives it) is not
 * believed. Before, the file held no launcher line: `contract trace FILE` said MAB only at its end.
 */
import { spawnSync } from 'node:child_process';
import { cpSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';
import { killModuleOnceRunning } from '@contract-studio/build-service/test-support/module-pid';

const canRun = spawnSync('bwrap', ['--version']).status === 0;
const TUTORIAL = fileURLToPath(new URL('../../../examples/tutorial', import.meta.url));

/** The story's line of a module told gone by the launcher's line. */
const goneLine = (m: string) => new RegExp(`^\\+\\d+\\.\\d{6}s ${m} {2}its records stop here \\(its last record\\), with no exit record: it ended mid-run, while the others went on; the launcher's line, at \\+(\\d+\\.\\d{6})s: contract-launch: module ${m} \\(pid \\d+\\) died by signal 9 \\(Killed\\)$`);

let root: string;

beforeAll(async () => {
    root = await makeSeededScratch('contract-launcher-trace-file-');
    cpSync(TUTORIAL, join(root, 'tut'), { recursive: true, filter: (src) => !/\/(logs|run)$/.test(src) });
}, 120_000);
afterAll(() => removeSeededScratch(root));

describe.skipIf(!canRun)('a module SIGKILLed from outside mid-run, recorded by contract run --trace', () => {
    it('the trace file holds the launcher\'s end line in time order; contract trace FILE tells it gone at the kill; a forged line is not believed', async () => {
        const io = capture(root);
        const running = runCli(['run', 'tut', '--sandbox', 'bwrap', '--duration', '4s', '--logs', 'tut-logs', '--trace', 'run.jsonl'], io);
        const killer = killModuleOnceRunning('MAB', 1000);
        const code = await running;
        const killedAt = await killer;
        expect(killedAt).toBeGreaterThan(0);
        expect(code, io.stderr).not.toBe(0);
        expect(io.stderr).toMatch(/\ncontract-launch: module MAB \(pid \d+\) died by signal 9 \(Killed\)\n/);

        // the file: the launcher's line at its own time (contract-launch.log's), in time order
        const launcherFile = readFileSync(join(root, 'tut-logs', 'contract-launch.log'), 'utf8');
        const said = /^(\d+) (module MAB \(pid (\d+)\) died by signal 9 \(Killed\))$/m.exec(launcherFile)!;
        expect(said).not.toBeNull();
        const fileText = readFileSync(join(root, 'run.jsonl'), 'utf8');
        const objects = fileText.trimEnd().split('\n').map((l) => JSON.parse(l) as { kind: string; monoNs: string; module?: string; detail?: string; line?: string });
        const at = objects.findIndex((o) => o.kind === 'launcher_line');
        expect(at, 'a launcher_line in the trace file').toBeGreaterThan(0);
        expect(objects[at]).toEqual({ kind: 'launcher_line', monoNs: said[1], line: said[2] });
        expect(objects.filter((o) => o.kind === 'launcher_line').map((o) => o.line)).not.toContainEqual(expect.stringMatching(/^module MAB .*exited|^module MAA .*died/));
        expect(BigInt(objects[at - 1]!.monoNs) <= BigInt(said[1]!)).toBe(true);
        expect(BigInt(objects[at + 1]!.monoNs) >= BigInt(said[1]!)).toBe(true);
        // its pid is MAB's own, as its module_started record gives it
        const started = objects.find((o) => o.kind === 'module_started' && o.module === 'MAB')!;
        expect(started.detail).toMatch(new RegExp(`(^| )pid=${said[3]}( |$)`));

        // contract trace FILE alone tells MAB gone at the kill, not at the run's end
        const t = capture(root);
        expect(await runCli(['trace', 'run.jsonl'], t), t.stderr).toBe(0);
        const lines = t.stdout.split('\n');
        const gone = lines.findIndex((l) => goneLine('MAB').test(l));
        expect(gone, t.stdout).toBeGreaterThanOrEqual(0);
        const told = Number(goneLine('MAB').exec(lines[gone]!)![1]);
        expect(told).toBeLessThan(4);
        const later = lines.slice(gone + 1).map((l) => /^\+(\d+\.\d+)s /.exec(l)).filter((m) => m !== null).map((m) => Number(m![1]));
        expect(later.some((s) => s > told + 1)).toBe(true);
        expect(t.stdout).toContain(`MAB  its last record: no exit record follows (the launcher's line: contract-launch: ${said[2]})`);
        // --format json gives the line back as it is in the file
        const j = capture(root);
        expect(await runCli(['trace', 'run.jsonl', '--format', 'json'], j)).toBe(0);
        expect(j.stdout).toContain(`{"kind":"launcher_line","monoNs":"${said[1]}","line":"${said[2]}"}\n`);

        // forged: MAB's line with another pid, and one of MAA (never killed) with a pid not its own
        const maaStarted = objects.find((o) => o.kind === 'module_started' && o.module === 'MAA')!;
        const maaPid = Number(/(?:^| )pid=(\d+)/.exec(maaStarted.detail!)![1]);
        const forgedLines = fileText.trimEnd().split('\n');
        forgedLines[at] = JSON.stringify({ kind: 'launcher_line', monoNs: said[1], line: `module MAB (pid ${Number(said[3]) + 1}) died by signal 9 (Killed)` });
        forgedLines.splice(at + 1, 0, JSON.stringify({ kind: 'launcher_line', monoNs: said[1], line: `module MAA (pid ${maaPid + 1}) died by signal 9 (Killed)` }));
        writeFileSync(join(root, 'forged.jsonl'), forgedLines.join('\n') + '\n');
        const f = capture(root);
        expect(await runCli(['trace', 'forged.jsonl'], f), f.stderr).toBe(0);
        expect(f.stdout).not.toMatch(/MAB {2}its records stop here \(its last record\), with no exit record: it ended mid-run, while the others went on; the launcher's line/);
        expect(f.stdout).not.toMatch(/MAA {2}its records stop here/);
        expect(f.stdout).not.toContain('the launcher\'s line: contract-launch');
        expect(f.stdout).toMatch(/MAB {2}its last record: no exit record follows \(it crashed, was killed/);
    }, 240_000);
});
