/**
 * The host-side trust boundary of a sandbox (docs/sandbox.md: "Host clean-up", "Limits", "Build
 * products between jobs"), run for bwrap and docker: a job filling /work hits the disk limit by
 * name; a 1,200-level tree with chmod 000 folders and links out is cleaned up; an executable a run
 * replaced (dated 2100) is never run by the next job, while a no-op rebuild stays a no-op; what a
 * run leaves in its log folder is gone before the next job.
 */
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, test } from 'vitest';
import { createBuildServer, type BuildServer } from '../server.js';
import type { SandboxName } from '../sandbox/types.js';
import { diskFiller, honestProgram, makeProject, poisoner, runLeaver } from './c-projects.js';
import { getJob, postJob, readEvents } from './client.js';
import { hostileTreeProgram } from './hostile-tree.js';
import { freshWorkspaces, useScratch } from './scratch.js';

type AnyJob = Record<string, any>;

export function hostTrustSuite(sandbox: SandboxName): void {
  describe(`host trust boundary (${sandbox})`, () => {
    const { temp, serve } = useScratch();
    const projects = temp('contract-trust-projects-');
    const start = async (cacheDir = temp('contract-trust-cache-')): Promise<{ url: string; server: BuildServer; cacheDir: string }> => {
      const server = createBuildServer({ token: false, port: 0, cacheDir, projectRoots: [projects], concurrency: 2 });
      serve(server);
      return { url: (await server.listen()).url, server, cacheDir };
    };
    const runJob = async (url: string, body: Record<string, unknown>): Promise<AnyJob> => {
      const r = await postJob(url, { sandbox, ...body });
      expect(r.status, JSON.stringify(r.json)).toBe(201);
      const events = await readEvents(url, r.json.id as string);
      return { ...(await getJob(url, r.json.id as string)), events };
    };
    const lines = (job: AnyJob): string[] => job.events.filter((e: any) => e.type === 'line').map((e: any) => e.line as string);
    const project = (name: string, files: Record<string, string>): string => {
      const dir = join(projects, name);
      mkdirSync(dir, { recursive: true });
      for (const [rel, text] of Object.entries(files)) writeFileSync(join(dir, rel), text);
      return dir;
    };

    test('a job filling /work is stopped by the disk limit, named', async () => {
      const { url } = await start();
      const t0 = Date.now();
      const job = await runJob(url, { action: 'run', kind: 'make', project: { files: makeProject(diskFiller) }, limits: { workDiskMiB: 32, runSeconds: 50 } });
      // the message names what filled the disk: the biggest files of the work dir
      expect(job.result.message).toMatch(/^killed: disk limit 32 MiB \(work dir\): filled by (\S*fill-\d+\.bin 1 MiB, ){4}\S*fill-\d+\.bin 1 MiB \(of (at least )?[\d.]+ MiB in \d+ file\(s\)\)$/);
      expect(job.result.limitHit).toEqual({ name: 'workDiskMiB', value: 32 * 1024 * 1024, unit: 'bytes', mechanism: sandbox === 'docker' ? 'docker-tmpfs-volume' : 'tmpfs-size' });
      expect(job.result.mechanisms.disk).toBe(sandbox === 'docker' ? 'docker-tmpfs-volume' : 'tmpfs-size');
      expect(lines(job).some((l) => /write failed after (2\d|3[01]) MiB: No space left on device/.test(l))).toBe(true);
      expect(Date.now() - t0).toBeLessThan(45_000); // the disk limit, not the run time limit
    });

    test('a 1,200-level tree with chmod 000 folders and links out is cleaned up, and the project builds again', async () => {
      const outside = temp('contract-trust-outside-');
      writeFileSync(join(outside, 'keep.txt'), 'keep\n');
      const files = makeProject(honestProgram(1), { 'mktree.c': hostileTreeProgram(1200, outside) });
      // each build makes one more tree (a fresh folder: the last one's deepest folders are chmod 000)
      files.Makefile = files.Makefile!.replace('all: prog', 'all: prog tree').replace('.PHONY: all run', () => 'tree:\n\tgcc -o /tmp/mktree mktree.c && d=$$(mktemp -d tree.XXXXXX) && cd $$d && /tmp/mktree\n.PHONY: all run tree');
      const dir = project('deep', files);
      const first = await start();
      const a = await runJob(first.url, { action: 'build', kind: 'make', project: { dir } });
      expect(a.status, JSON.stringify(lines(a).slice(-8))).toBe('succeeded');
      const inline = await runJob(first.url, { action: 'build', kind: 'make', project: { files } });
      expect(inline.status, inline.result.message).toBe('succeeded');
      await first.server.close();
      const leftovers = (): string[] => freshWorkspaces(first.cacheDir);
      expect(leftovers()).toEqual([]);
      expect(readFileSync(join(outside, 'keep.txt'), 'utf8')).toBe('keep\n');
      // a later service on the same cache folder builds the project (twice: the tree is there again)
      const second = await start(first.cacheDir);
      for (let i = 0; i < 2; i++) {
        const b = await runJob(second.url, { action: 'build', kind: 'make', project: { dir } });
        expect(b.status, b.result.message).toBe('succeeded');
      }
      await second.server.close();
      expect(leftovers()).toEqual([]);
      expect(readFileSync(join(outside, 'keep.txt'), 'utf8')).toBe('keep\n');
    });

    test("what a run leaves in its log folder (an old log, a link `previous` to /, a chmod 000 folder) is gone before the next job: its logs are its own, and it runs", async () => {
      const { url } = await start();
      const files = makeProject(runLeaver);
      files.Makefile = files.Makefile!.replace('\t./prog', '\t./prog $(LOG_DIR)');
      const dir = project('leaver', files);
      const left = await runJob(url, { action: 'run', kind: 'make', project: { dir } });
      expect(left.status, left.result.message).toBe('succeeded');
      expect(lines(left)).toContain('left its marks');
      expect((left.artifacts as { files: { name: string }[] }).files.map((f) => f.name)).toEqual(['OLD_1.csv']);
      writeFileSync(join(dir, 'main.c'), honestProgram(1));
      for (let i = 0; i < 2; i++) {
        const next = await runJob(url, { action: 'run', kind: 'make', project: { dir } });
        expect(next.status, next.result.message).toBe('succeeded');
        expect(lines(next)).toContain('honest done');
        expect((next.artifacts as { files: { name: string }[] }).files).toEqual([]);
        expect(lines(next).some((l) => /could not be removed|from scratch/.test(l)), lines(next).join('\n')).toBe(false);
      }
    });

    test('an executable a run replaced (dated 2100) is rebuilt, not run, by the next job; a no-op rebuild stays a no-op', async () => {
      const { url } = await start();
      const dir = project('poison', makeProject(honestProgram(1)));
      const build = await runJob(url, { action: 'run', kind: 'make', project: { dir } });
      expect(build.status, build.result.message).toBe('succeeded');
      // no-op: same project, nothing changed since the last build -> make compiles nothing
      const noop = await runJob(url, { action: 'run', kind: 'make', project: { dir } });
      expect(noop.status, noop.result.message).toBe('succeeded');
      expect(lines(noop).some((l) => l.includes('-o prog main.c'))).toBe(false);
      expect(lines(noop).some((l) => /not trusted|from scratch/.test(l))).toBe(false);
      // the attack: a run replaces ./prog with a script dated 2100 ...
      writeFileSync(join(dir, 'main.c'), poisoner);
      const poison = await runJob(url, { action: 'run', kind: 'make', project: { dir } });
      expect(lines(poison)).toContain('poisoning ./prog');
      // ... and the next job, with clean code, must build and run its own program
      writeFileSync(join(dir, 'main.c'), honestProgram(1));
      const clean = await runJob(url, { action: 'run', kind: 'make', project: { dir } });
      expect(clean.status, clean.result.message).toBe('succeeded');
      expect(lines(clean)).not.toContain('POISONED');
      expect(lines(clean)).toContain('honest done');
      expect(lines(clean).some((l) => l.includes('the work dir changed after the last build ended'))).toBe(true);
    });
  });
}
