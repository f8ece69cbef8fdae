/**
 * Ctrl+C on `contract run` (or its output's reader gone: `| head`): the job is cancelled, its
 * launcher stops the architecture as at the end of a run (supervisors first, every module's exit
 * record written), exit 130, no process or workspace left, and the CSV logs saved in PROJECT/logs
 * as a finished run's are.
 * `kill -9` of `contract build` mid-make: the project's kept work tree is not trusted by the next
 * build (docs/getting-started.md "The build cache"), which is not blocked by the dead one's lock.
 */
import { spawn, type ChildProcessByStdio } from 'node:child_process';
import { readdirSync, readFileSync } from 'node:fs';
import { join } from 'node:path';
import type { Readable } from 'node:stream';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { BIN, contract, leftoverWorkspaces, processesMentioning, seededScratchCopy, type Scratch } from './harness.js';

let scratch: Scratch;
beforeAll(async () => { scratch = await seededScratchCopy('tutorial'); }, 240_000);
afterAll(() => scratch?.dispose());

/** `contract run tutorial` for 60 s; resolves once its output has a line with `until` (default: the mission started), with its exit and its stderr so far. */
async function runningTutorial(until = 'contract-launch: started GLB.mission'): Promise<{ child: ChildProcessByStdio<null, Readable, Readable>; exited: Promise<number | null>; stderr: () => string }> {
    const child = spawn(process.execPath, [BIN, 'run', 'tutorial', '--sandbox', 'bwrap', '--duration', '60s'], {
        cwd: scratch.root,
        env: { ...process.env, CONTRACT_CACHE_DIR: scratch.cache },
        stdio: ['ignore', 'pipe', 'pipe'],
    });
    let stdout = '';
    let stderr = '';
    const exited = new Promise<number | null>((resolve) => child.on('exit', (code) => resolve(code)));
    // the launcher's lines come on stderr, the modules' stdout lines on stdout
    await new Promise<void>((resolve) => {
        child.stderr.on('data', (d: Buffer) => {
            stderr += d.toString();
            if (stderr.includes(until)) resolve();
        });
        child.stdout.on('data', (d: Buffer) => {
            stdout += d.toString();
            if (stdout.includes(until)) resolve();
        });
    });
    return { child, exited, stderr: () => stderr };
}

describe('contract run interrupted', () => {
    it('stops the architecture as at the end of a run on SIGINT, within seconds, and exits 130', async () => {
        // once SUP's SECOND rule is active (it asked ORD for schemaCommande1), half a second more
        const run = await runningTutorial('[SUP] rule action.SECOND active');
        await new Promise((r) => setTimeout(r, 500));
        const sent = Date.now();
        run.child.kill('SIGINT');
        const code = await run.exited;
        expect(Date.now() - sent).toBeLessThan(5000);
        expect(code).toBe(130);
        expect(run.stderr()).toContain('FAILED: cancelled');
        expect(processesMentioning(scratch.root)).toEqual([]);
        expect(leftoverWorkspaces(scratch)).toEqual([]);
        // what the run wrote until then is kept: its logs in tutorial/logs, GLB's with the mission it started
        const logs = join(scratch.root, 'tutorial', 'logs');
        const csv = readdirSync(logs).filter((n) => n.endsWith('.csv'));
        expect(csv.map((n) => n.split('_')[0]).sort()).toEqual(['GLB', 'MAA', 'MAB', 'MSA', 'MSB', 'MSC', 'MSD', 'ORD', 'SUP']);
        const log = (m: string): string => readFileSync(join(logs, csv.find((n) => n.startsWith(`${m}_`))!), 'utf8');
        expect(log('GLB')).toContain(',supervisor,,,0,"function mission(consigne = {i=0.0,j=0.0,k=0.0}) started"');
        expect(run.stderr()).toContain('CSV logs: 9 file(s) in tutorial/logs\n'); // from where the command ran
        // the launcher stopped it (docs/build-service-api.md "Cancel"): every module wrote its last
        // records and its exit record; SUP stopped before ORD, which deactivated schemaCommande1
        for (const m of ['GLB', 'MAA', 'MAB', 'MSA', 'MSB', 'MSC', 'MSD', 'ORD', 'SUP']) expect(log(m).trimEnd().split('\n').at(-1), m).toMatch(/,module_exit,,,0,status=0 records=\d+$/);
        expect(log('SUP')).toContain(',supervisor,ORD,,0,"undo: deactivate schema schemaCommande1 (activation #');
        expect(log('ORD')).toMatch(/,scheduler,,,0,deactivate schemaCommande1 \(activation #\d+ from SUP\)\n/);
        // the run directory's files are no news
        expect(run.stderr()).not.toContain('left files in its run directory');
    }, 240_000);

    it('stops as on Ctrl+C when the reader of its output goes away (`contract run … | head`): exit 130, no stack trace, nothing left running', async () => {
        const run = await runningTutorial();
        const closed = Date.now();
        run.child.stdout.destroy(); // the reader is gone: the run's next line meets a closed pipe
        const code = await run.exited;
        expect(Date.now() - closed).toBeLessThan(10_000);
        expect(code).toBe(130);
        expect(run.stderr()).toContain('FAILED: cancelled');
        expect(run.stderr()).not.toMatch(/EPIPE|Unhandled|    at /);
        expect(processesMentioning(scratch.root)).toEqual([]);
        expect(leftoverWorkspaces(scratch)).toEqual([]);
    }, 240_000);
});

describe('contract build killed with -9', () => {
    it('leaves a work tree the next build empties and rebuilds, without waiting for a lock', async () => {
        // an empty cache: the killed build must be compiling (the run above left a built tree)
        expect(contract(['cache', 'clear'], scratch).code).toBe(0);
        const child = spawn(process.execPath, [BIN, 'build', 'tutorial', '--sandbox', 'bwrap', '--verbose'], {
            cwd: scratch.root,
            env: { ...process.env, CONTRACT_CACHE_DIR: scratch.cache },
            stdio: ['ignore', 'ignore', 'pipe'],
        });
        let stderr = '';
        const compiling = new Promise<void>((resolve) => {
            child.stderr.on('data', (d: Buffer) => {
                stderr += d.toString();
                if (/^g?cc .* -o MAA /m.test(stderr)) resolve();
            });
        });
        const exited = new Promise<void>((resolve) => child.on('exit', () => resolve()));
        await Promise.race([compiling, exited]);
        expect(stderr).toMatch(/^g?cc .* -o MAA /m);
        child.kill('SIGKILL');
        await exited;
        const t0 = Date.now();
        const again = contract(['build', 'tutorial', '--sandbox', 'bwrap', '--verbose'], scratch);
        expect(again.code, again.stderr).toBe(0);
        expect(again.stderr).not.toContain('waiting for the other command');
        expect(again.stderr).toContain('no build ended in this workspace since it was emptied: building from scratch');
        expect(again.stderr).toMatch(/^g?cc .* -o ORD /m);
        expect(Date.now() - t0).toBeLessThan(120_000);
    }, 240_000);
});
