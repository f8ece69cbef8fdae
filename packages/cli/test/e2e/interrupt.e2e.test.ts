/** Ctrl+C on `contract run`: the job is cancelled, every process stopped, exit 130, no workspace left. */
import { spawn } from 'node:child_process';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { BIN, leftoverWorkspaces, processesMentioning, scratchCopy, type Scratch } from './harness.js';

let scratch: Scratch;
beforeAll(() => { scratch = scratchCopy('tutorial'); });
afterAll(() => scratch?.dispose());

describe('contract run interrupted', () => {
    it('stops everything within seconds of SIGINT and exits 130', async () => {
        const child = spawn(process.execPath, [BIN, 'run', 'tutorial', '--sandbox', 'bwrap', '--duration', '60s'], {
            cwd: scratch.root,
            env: { ...process.env, CONTRACT_CACHE_DIR: scratch.cache },
            stdio: ['ignore', 'pipe', 'pipe'],
        });
        let stdout = '';
        let stderr = '';
        child.stderr.on('data', (d: Buffer) => { stderr += d.toString(); });
        const running = new Promise<void>((resolve) => {
            child.stdout.on('data', (d: Buffer) => {
                stdout += d.toString();
                if (stdout.includes('contract-launch: started GLB.mission')) resolve();
            });
        });
        const exited = new Promise<number | null>((resolve) => child.on('exit', (code) => resolve(code)));
        await running;
        const sent = Date.now();
        child.kill('SIGINT');
        const code = await exited;
        expect(Date.now() - sent).toBeLessThan(5000);
        expect(code).toBe(130);
        expect(stderr).toContain('FAILED: cancelled');
        expect(processesMentioning(scratch.root)).toEqual([]);
        expect(leftoverWorkspaces(scratch)).toEqual([]);
    }, 240_000);
});
