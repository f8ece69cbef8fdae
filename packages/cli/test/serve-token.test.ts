/**
 * `contract serve` prints the URL to open with the server's session token; the API refuses a
 * client without it (another local user or program) and serves the one that opened the URL.
 */
import { spawn, type ChildProcess } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { BIN } from './e2e/harness.js';

let child: ChildProcess | undefined;
const dir = mkdtempSync(join(tmpdir(), 'contract-serve-'));
afterAll(async () => {
    if (child && child.exitCode === null) {
        const exited = new Promise((r) => child!.once('exit', r));
        child.kill('SIGTERM');
        await exited;
    }
    rmSync(dir, { recursive: true, force: true });
});

function firstLine(c: ChildProcess): Promise<string> {
    return new Promise((resolve, reject) => {
        let out = '';
        c.stdout!.on('data', (d: Buffer) => {
            out += d.toString('utf8');
            const nl = out.indexOf('\n');
            if (nl >= 0) resolve(out.slice(0, nl));
        });
        c.once('exit', (code) => reject(new Error(`contract serve exited ${code} before printing its URL`)));
    });
}

describe('contract serve', () => {
    it('prints a URL with the session token; the API needs it', async () => {
        writeFileSync(join(dir, 'a.contract'), 'datatype T {int x};\n');
        child = spawn(process.execPath, [BIN, 'serve', dir, '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
        const line = await firstLine(child);
        const m = /^ContrACT Studio IDE: (http:\/\/127\.0\.0\.1:\d+)\/\?token=([A-Za-z0-9_-]{43}) /.exec(line);
        expect(m, line).not.toBeNull();
        const [, base, token] = m!;
        expect((await fetch(`${base}/api/tree`)).status).toBe(401);
        const put = await fetch(`${base}/api/file?path=b.contract`, { method: 'PUT', body: 'x' });
        expect(put.status).toBe(401);
        // the browser's way: the printed URL sets the cookie, which then opens the API
        const open = await fetch(`${base}/?token=${token}`, { redirect: 'manual' });
        expect(open.status).toBe(303);
        const cookie = open.headers.get('set-cookie')!.split(';')[0]!;
        const file = await fetch(`${base}/api/file?path=a.contract`, { headers: { cookie } });
        expect(file.status).toBe(200);
        expect(((await file.json()) as { content: string }).content).toBe(readFileSync(join(dir, 'a.contract'), 'utf8'));
    }, 60_000);

    it('--sandbox docker makes Docker the default of the IDE\'s jobs (GET /api/sandboxes says it); a sandbox it does not take is refused, exit 2', async () => {
        const bad = spawn(process.execPath, [BIN, 'serve', dir, '--port', '0', '--sandbox', 'none'], { stdio: ['ignore', 'pipe', 'pipe'] });
        let err = '';
        bad.stderr!.on('data', (d: Buffer) => (err += d.toString('utf8')));
        expect(await new Promise((r) => bad.once('exit', r))).toBe(2);
        expect(err).toContain('--sandbox needs one of auto, bwrap, docker, got none');
        const docker = spawn(process.execPath, [BIN, 'serve', dir, '--port', '0', '--sandbox', 'docker'], { stdio: ['ignore', 'pipe', 'inherit'] });
        try {
            const m = /^ContrACT Studio IDE: (http:\/\/127\.0\.0\.1:\d+)\/\?token=([A-Za-z0-9_-]{43}) /.exec(await firstLine(docker))!;
            const res = await fetch(`${m[1]}/api/sandboxes`, { headers: { 'x-contract-token': m[2]! } });
            expect(res.status).toBe(200);
            expect(((await res.json()) as { default: string }).default).toBe('docker');
        } finally {
            const exited = new Promise((r) => docker.once('exit', r));
            docker.kill('SIGTERM');
            await exited;
        }
    }, 60_000);

    it('--limit NAME=VALUE sets the build service\'s limits for the IDE\'s jobs (an hour-long run); an unknown limit or a bad value is refused, exit 2', async () => {
        for (const [arg, message] of [
            ['bogus=1', 'unknown limit "bogus"'], ['__proto__=1', 'unknown limit "__proto__"'], ['runSeconds=0', '--limit needs NAME=VALUE with a positive number'],
            ['runSeconds', '--limit needs NAME=VALUE'], ['runSeconds=99999999999999999999', 'limit runSeconds must be at most 2147483 s (about 24.8 days, a timer\'s range), got 99999999999999999999\n'], ['buildSeconds=2200000', 'limit buildSeconds must be at most 2147483 s'],
            // counts and sizes are whole numbers (a cgroup's pids.max refuses 10.5), bounded
            ['processes=10.5', 'limit processes must be a whole number (a count or a size), got 10.5'], ['runSeconds=0.0000001', 'limit runSeconds must be at least 0.001 s'], ['memoryMiB=9000000000', 'limit memoryMiB must be at most 8589934592, got 9000000000'],
            // the value as written, not as a JavaScript number shows it (17 digits and more are rounded); a count or size
            // written with a fraction is refused even when the number it became is whole
            ['processes=12345678901234567', 'limit processes must be at most 4194304, got 12345678901234567\n'],
            ['generatedFiles=10.0000000000000001', 'limit generatedFiles must be a whole number (a count or a size), got 10.0000000000000001\n'],
        ]) {
            const bad = spawn(process.execPath, [BIN, 'serve', dir, '--port', '0', '--limit', arg!], { stdio: ['ignore', 'pipe', 'pipe'] });
            let err = '';
            bad.stderr!.on('data', (d: Buffer) => (err += d.toString('utf8')));
            expect(await new Promise((r) => bad.once('exit', r))).toBe(2);
            expect(err).toContain(message);
        }
        // a job may only lower the server's limits: asking 3600 s of run passes with --limit runSeconds=3660, not without
        const ask = async (extra: string[]): Promise<number> => {
            const c = spawn(process.execPath, [BIN, 'serve', dir, '--port', '0', ...extra], { stdio: ['ignore', 'pipe', 'inherit'] });
            try {
                const m = /^ContrACT Studio IDE: (http:\/\/127\.0\.0\.1:\d+)\/\?token=([A-Za-z0-9_-]{43}) /.exec(await firstLine(c))!;
                const headers = { 'x-contract-token': m[2]!, 'content-type': 'application/json' };
                const res = await fetch(`${m[1]}/api/jobs`, { method: 'POST', headers, body: JSON.stringify({ action: 'build', project: { dir }, limits: { runSeconds: 3600 } }) });
                if (res.status === 201) {
                    const { id } = (await res.json()) as { id: string };
                    await fetch(`${m[1]}/api/jobs/${id}/cancel`, { method: 'POST', headers });
                }
                return res.status;
            } finally {
                const exited = new Promise((r) => c.once('exit', r));
                c.kill('SIGTERM');
                await exited;
            }
        };
        expect(await ask([])).toBe(400);
        expect(await ask(['--limit', 'runSeconds=3660', '--limit=workDiskMiB=1024'])).toBe(201);
        // a time limit written `.5` or `3660.` is a number too (it was refused as "needs a positive number")
        expect(await ask(['--limit', 'runSeconds=3660.'])).toBe(201);
        expect(await ask(['--limit', 'runSeconds=.5'])).toBe(400);
    }, 90_000);
});
