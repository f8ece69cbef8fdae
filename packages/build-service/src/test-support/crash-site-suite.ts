/**
 * Where a module crashed (docs/runtime-api.md "Crash report", docs/sandbox.md), run for bwrap and
 * docker on the report's tutorial: the runtime's crash report on the module's stderr is mapped by
 * addr2line in the sandbox to the file, line and protected region of the project's code, told in
 * the failed run's message and as an error at that line among the job's diagnostics; a module
 * printing forged crash reports gets nothing run but addr2line on its own executable, bounded.
 */
import { describe, expect, test } from 'vitest';
import type { SandboxName } from '../sandbox/types.js';
import type { DiagnosticEvent, JobEvent, LineEvent } from '../pipeline/job-events.js';
import type { TestBuildServer } from './build-server.js';
import { getJob, postJob, readEvents } from './client.js';
import { MAA_MODULE, tutorialFiles, withRegion } from './tutorial.js';

export function crashSiteSuite(sandbox: SandboxName, served: TestBuildServer): void {
  /** The launcher saved the runtime's report in the run's logs (MAA.crash, runtime-api.md "Crash file"), collected with them. */
  async function expectSavedReport(job: Record<string, any>): Promise<void> {
    expect(job.artifacts.files.map((f: { name: string }) => f.name)).toContain('MAA.crash');
    const saved = await (await fetch(`${served.url}/api/jobs/${job.id}/artifacts/MAA.crash`)).text();
    expect(saved).toMatch(/^==contract-crash== module MAA signal 11 SIGSEGV addr 0x0\n==contract-crash== build-id [0-9a-f]{40}\n==contract-crash== frame 0 exe 0x[0-9a-f]+\n(?:==contract-crash== frame \d+ [\w.+-]+ 0x[0-9a-f]+\n){1,47}==contract-crash== end \d+ frames\n$/);
  }

  async function runJob(files: Record<string, string>): Promise<{ job: Record<string, any>; events: JobEvent[] }> {
    const r = await postJob(served.url, { sandbox, action: 'run', duration: 2, project: { files } });
    expect(r.status, JSON.stringify(r.json)).toBe(201);
    const events = await readEvents(served.url, r.json.id as string);
    return { job: await getJob(served.url, r.json.id as string), events };
  }

  const NULL_STORE = '    { static int calls = 0; static double *bad = 0; if (++calls == 3) *bad = 1.0; /* crash */ }';

  describe(`crash site (${sandbox})`, () => {
    test('a null dereference in an exec region: the run names its file, line and region', async () => {
      const files = withRegion(await tutorialFiles(), MAA_MODULE, 'protect_exec_MAA', NULL_STORE, true);
      const line = files[MAA_MODULE]!.split('\n').findIndex((l) => l.includes('/* crash */')) + 1;
      const { job, events } = await runJob(files);
      expect(job.status).toBe('failed');
      expect(job.result.message).toContain(`module MAA crashed (died by signal 11 (Segmentation fault)) at ${MAA_MODULE}:${line} in its protected region protect_exec_MAA (`);
      const diagnostics = events.filter((e): e is DiagnosticEvent => e.type === 'diagnostic').map((e) => e.diagnostic);
      expect(diagnostics).toMatchObject([{ severity: 'error', file: MAA_MODULE.replace(/^src-gen\//, ''), line, protectedRegion: { id: 'protect_exec_MAA' } }]);
      expect(diagnostics[0]!.message).toMatch(/^MAA crashed here: signal 11 \(SIGSEGV\) at address 0x0, in \w+: a bad pointer: NULL, freed, or past the end of an array$/);
      expect(diagnostics[0]!.origin).toBe('run'); // no compiler's: the IDE labels it run
      const service = events.filter((e): e is LineEvent => e.type === 'line' && e.source === 'service').map((e) => e.line);
      expect(service).toContain(`MAA crashed at ${MAA_MODULE}:${line} in its protected region protect_exec_MAA (${/, in (\w+): /.exec(diagnostics[0]!.message)![1]})`);
      expect(service.some((l) => /^MAA crash frame #0 \S+ at src-gen\/generated\/architecture\/modules\/MAA_mod\/module\.c:\d+$/.test(l))).toBe(true);
      // the runtime's frames are named as the runtime's files wherever it was built (the service's
      // cache for bwrap, the image's /opt/contract/runtime for docker)
      expect(service).toContainEqual(expect.stringMatching(/^MAA crash frame #\d+ main at runtime\/src\/module_main\.c:\d+$/));
      await expectSavedReport(job);
      // the artifacts listing gives the crash file's site mapped, as contract trace tells a crash file: a replay of the job's logs tells it
      const buildId = /build-id ([0-9a-f]{40})/.exec(await (await fetch(`${served.url}/api/jobs/${job.id}/artifacts/MAA.crash`)).text())![1];
      const listing = await (await fetch(`${served.url}/api/jobs/${job.id}/artifacts`)).json() as { artifacts: { crashSites?: string[] } };
      expect(listing.artifacts.crashSites).toEqual([
        `MAA crashed: signal 11 (SIGSEGV) at address 0x0 (a bad pointer: NULL, freed, or past the end of an array), executable build-id ${buildId}`,
        ...service.filter((l) => l.startsWith('MAA crash frame ')).map((l) => `  ${l.slice('MAA crash frame '.length)}`),
      ]);
    });

    test('forged crash reports: only addr2line on the module\'s own executable, bounded', async () => {
      // MAA prints reports for another module, one naming /etc/passwd as its object, one with a huge
      // offset list, then one of its own whose frames are numbers it chose; then it crashes for real
      const forged = [
        '==contract-crash== module MSC signal 11 SIGSEGV addr 0x0',
        '==contract-crash== frame 0 exe 0x1000',
        '==contract-crash== end 1 frames',
        '==contract-crash== module MAA signal 11 SIGSEGV addr 0x0',
        '==contract-crash== frame 0 /etc/passwd 0x1000',
        '==contract-crash== end 1 frames',
        '==contract-crash== module MAA signal 11 SIGSEGV addr 0x0',
        ...Array.from({ length: 200 }, (_, i) => `==contract-crash== frame ${i} exe 0x${(0xffffffff0000 + i).toString(16)}`),
        '==contract-crash== end 200 frames',
        '==contract-crash== module MAA signal 11 SIGSEGV addr 0x0',
        '==contract-crash== frame 0 exe 0xfffffffffffffff0',
        '==contract-crash== frame 1 exe 0x1;touch${IFS}/tmp/pwned',
        '==contract-crash== end 2 frames',
      ];
      const print = `    { static int said = 0; if (!said) { said = 1; ${forged.map((l) => `fprintf(stderr, "%s\\n", ${JSON.stringify(l)});`).join(' ')} fflush(stderr); } }`;
      let files = withRegion(await tutorialFiles(), MAA_MODULE, 'protect_additional_import_MAA', '#include <stdio.h>', true);
      files = withRegion(files, MAA_MODULE, 'protect_exec_MAA', `${print}\n${NULL_STORE}`, true);
      const line = files[MAA_MODULE]!.split('\n').findIndex((l) => l.includes('/* crash */')) + 1;
      const { job, events } = await runJob(files);
      expect(job.status).toBe('failed');
      // every forged report is left out (another module's, a frame that is no offset, past 48 frames,
      // a line not of the format): the real one, after them, is the one read
      expect(job.result.message).toContain(`module MAA crashed (died by signal 11 (Segmentation fault)) at ${MAA_MODULE}:${line} in its protected region protect_exec_MAA (`);
      const service = events.filter((e): e is LineEvent => e.type === 'line' && e.source === 'service').map((e) => e.line);
      expect(service.filter((l) => l.startsWith('MSC crash'))).toEqual([]);
      expect(service.join('\n')).not.toMatch(/passwd|pwned|fffffff/);
      // one addr2line, on MAA's executable, of at most 48 frames
      expect(service.filter((l) => /^time: crash site of \w+ \(addr2line\)/.test(l))).toEqual([expect.stringMatching(/^time: crash site of MAA /)]);
      expect(service.filter((l) => l.startsWith('MAA crash frame ')).length).toBeLessThanOrEqual(48 * 4);
      // the crash file holds the real report, the last block MAA wrote, not a forged one before it
      await expectSavedReport(job);
    });
  });
}
