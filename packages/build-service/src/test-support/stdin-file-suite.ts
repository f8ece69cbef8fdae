/**
 * A module's stdin from a file of the project (the run request's `stdin`: docs/build-service-api.md;
 * pipeline/stdin-files.ts), run for bwrap and docker on the report's tutorial: MSC reads every line
 * of its stdin with scanf in its init and prints them, then says it reached EOF; MSD does the same
 * and reads nothing (its stdin is /dev/null). The project given as files, and as a folder (as the
 * IDE and `contract run` give it: `serve` gets the folder the service may build projects in).
 */
import { chmodSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import type { SandboxName } from '../sandbox/types.js';
import type { LineEvent } from '../pipeline/job-events.js';
import type { TestBuildServer } from './build-server.js';
import { getJob, postJob, readEvents } from './client.js';
import { tutorialFiles, withRegion } from './tutorial.js';

const moduleFile = (name: string) => `src-gen/generated/architecture/modules/${name}_mod/module.c`;

/** Module `name`'s init reads its stdin to the end with scanf, a line at a time, and prints each line. */
const readsStdin = (files: Record<string, string>, name: string) =>
  withRegion(files, moduleFile(name), `protect_init_${name}`,
    `    { char line[80]; int n = 0; while (scanf(" %79[^\\n]", line) == 1) printf("${name} read: %s\\n", line), n++; printf("${name} read EOF after %d line(s)\\n", n); fflush(stdout); }`, true);

const COMMANDS = 'forward 2\nturn left\nstop\n';

export function stdinFileSuite(sandbox: SandboxName, serve: (projectRoots: string[]) => TestBuildServer): void {
  const projects = mkdtempSync(join(tmpdir(), `stdin-${sandbox}-`));
  chmodSync(projects, 0o711);
  const served = serve([projects]);
  afterAll(() => rmSync(projects, { recursive: true, force: true }));

  async function run(project: Record<string, unknown>, stdin: Record<string, string>): Promise<{ job: Record<string, any>; out: string[] }> {
    const r = await postJob(served.url, { sandbox, action: 'run', duration: 2, project, stdin });
    expect(r.status, JSON.stringify(r.json)).toBe(201);
    const events = await readEvents(served.url, r.json.id as string);
    const out = events.filter((e): e is LineEvent => e.type === 'line').map((e) => `${e.source}: ${e.line}`);
    return { job: await getJob(served.url, r.json.id as string), out };
  }

  async function project(): Promise<Record<string, string>> {
    return readsStdin(readsStdin(await tutorialFiles(), 'MSC'), 'MSD');
  }

  describe(`a module's stdin from a file of the project (${sandbox})`, () => {
    test('a project given as files: MSC reads the file to its end, MSD reads /dev/null', async () => {
      const files = { ...(await project()), 'commands.txt': COMMANDS };
      const { job, out } = await run({ files }, { MSC: 'commands.txt' });
      expect(job.status, `${job.result?.message}\n${out.slice(-20).join('\n')}`).toBe('succeeded');
      expect(out.filter((l) => l.startsWith('MSC: ')), out.slice(-20).join('\n')).toEqual(expect.arrayContaining(['MSC: MSC read: forward 2', 'MSC: MSC read: turn left', 'MSC: MSC read: stop', 'MSC: MSC read EOF after 3 line(s)']));
      expect(out).toContain('MSD: MSD read EOF after 0 line(s)');
      expect(out.filter((l) => / reads its stdin from /.test(l))).toEqual([expect.stringMatching(/^launcher: module MSC reads its stdin from \S+$/)]);
    });

    test('a project given as a folder (the IDE, contract run): its file in a subfolder; a file it does not have ends the run before it starts', async () => {
      const dir = join(projects, 'robot');
      for (const [rel, text] of Object.entries(await project())) {
        mkdirSync(dirname(join(dir, rel)), { recursive: true });
        writeFileSync(join(dir, rel), text);
      }
      mkdirSync(join(dir, 'input'));
      writeFileSync(join(dir, 'input', 'msc.txt'), COMMANDS);
      const { job, out } = await run({ dir }, { MSC: 'input/msc.txt' });
      expect(job.status, `${job.result?.message}\n${out.slice(-20).join('\n')}`).toBe('succeeded');
      expect(out).toEqual(expect.arrayContaining(['MSC: MSC read: forward 2', 'MSC: MSC read: turn left', 'MSC: MSC read: stop', 'MSC: MSC read EOF after 3 line(s)', 'MSD: MSD read EOF after 0 line(s)']));
      const missing = await run({ dir }, { MSC: 'input/nothing.txt' });
      expect(missing.job.status).toBe('failed');
      expect(missing.job.result.message).toContain('stdin of MSC: input/nothing.txt is not a regular file of the project (not there, a folder, or reached through a symbolic link); nothing was run');
      expect(missing.out.filter((l) => /^MS[CD]: /.test(l))).toEqual([]);
    });
  });
}
