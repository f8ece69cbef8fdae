/**
 * Real bwrap builds and runs of the `contract new` project (LOC, CTL, supervisor MIS):
 * - a lost event fails the run: CTL's posts to a subscriber that is not running fail (as one to a
 *   mailbox full for the 2 s PostEvent waits does): the events are lost. Before, the run ended
 *   `ok: run finished (exit 0)` and `contract trace`'s line of counts had no count of failed posts;
 * - `--werror`: a warning in a protected region fails the build, shown; without it the build passes.
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { runCli } from '../src/cli.js';
import { capture } from './capture-io.js';
import { makeSeededScratch, removeSeededScratch } from './scratch.js';

let root: string;
beforeAll(async () => {
    root = await makeSeededScratch('contract-lost-events-');
}, 240_000);
afterAll(() => removeSeededScratch(root));

const moduleFile = (dir: string, m: string) => join(root, dir, `src-gen/generated/architecture/modules/${m}_mod/module.c`);

/** Puts `code` at the start of module `m`'s protected region `region`. */
function region(dir: string, m: string, region: string, code: string): void {
    const file = moduleFile(dir, m);
    const source = readFileSync(file, 'utf8');
    const edited = source.replace(new RegExp(`(PROTECTED REGION ID\\(${region}\\) ENABLED START\\*/)`), `$1\n${code}`);
    expect(edited).not.toBe(source);
    writeFileSync(file, edited);
}

async function newProject(name: string): Promise<void> {
    expect(await runCli(['new', name], capture(root))).toBe(0);
    expect(await runCli(['generate', name], capture(root))).toBe(0);
}

describe('a lost event', () => {
    it('fails the run (events-lost, exit 4) and is counted by contract trace', async () => {
        await newProject('lossy');
        // CTL: a subscriber that is not running (GHOST) added to its output event port 0, then 3 posts
        // in its first release (MIS's rule ends at its first event, and with it the schema): each
        // fails at once for GHOST (no mailbox), the event is lost (MIS, subscribed by its rule, gets it)
        region('lossy', 'CTL', 'protect_exec_CTL', [
            '    { static int calls = 0; if (++calls == 1) { SubscribeUserToEvent("GHOST", 3, 0, EVENT_CONTINUOUS);',
            '      for (int i = 0; i < 3; i++) { strcpy(status, "lost"); PostEvent(&status); } } }',
        ].join('\n'));
        const io = capture(root);
        const code = await runCli(['run', 'lossy', '--sandbox', 'bwrap', '--duration', '2s', '--logs', 'lossy-logs', '--format', 'json'], io);
        const out = JSON.parse(io.stdout) as { result: { ok: boolean; issues: { kind: string; module?: string; message: string }[] } };
        const lost = out.result.issues.filter((i) => i.kind === 'events-lost');
        expect(lost, JSON.stringify(out.result.issues, null, 1)).toHaveLength(1);
        expect(lost[0]!.module).toBe('CTL');
        expect(lost[0]!.message).toMatch(/^3 events CTL posted to GHOST were lost \(CTL:0 -> GHOST:3\): their posts failed \(PostEvent gives up after waiting 2 s for room in GHOST's full mailbox, at once when GHOST is not running\); the last: EVENT request to GHOST: [^\n]+$/);
        expect(out.result.ok).toBe(false);
        expect(code).toBe(4);

        // the trace counts the failed posts, and tells the flow at the end in the same words
        const story = capture(root);
        expect(await runCli(['trace', join(root, 'lossy-logs')], story)).toBe(0);
        expect(story.stdout).toContain(', 3 event posts that failed (the event lost), ');
        expect(story.stdout).toContain(`\n${lost[0]!.message}\n`);
    }, 240_000);
});

describe('contract build --werror', () => {
    it('fails the build on a warning in a protected region, shown at its line; the same project builds without it', async () => {
        await newProject('strict');
        region('strict', 'CTL', 'protect_exec_CTL', '    int unused_in_region = 3;');
        const line = readFileSync(moduleFile('strict', 'CTL'), 'utf8').split('\n').findIndex((l) => l.includes('unused_in_region')) + 1;
        // without the option: the warning is printed, the build succeeds
        const plain = capture(root);
        expect(await runCli(['build', 'strict', '--sandbox', 'bwrap'], plain)).toBe(0);
        expect(plain.stderr).toMatch(new RegExp(`module\\.c:${line}:\\d+: warning: unused variable .unused_in_region.`));
        // with it: the same warning is an error and the build fails, though the executables were up to date
        const strict = capture(root);
        expect(await runCli(['build', 'strict', '--sandbox', 'bwrap', '--werror'], strict)).toBe(1);
        expect(strict.stderr).toMatch(new RegExp(`module\\.c:${line}:\\d+: error: unused variable .unused_in_region. \\[-Werror=unused-variable\\]`));
        // a run with it runs nothing
        const run = capture(root);
        expect(await runCli(['run', 'strict', '--sandbox', 'bwrap', '--werror', '--duration', '1s'], run)).toBe(1);
        expect(run.stdout + run.stderr).not.toContain('contract-launch: run directory');
        // and without it again, it builds
        expect(await runCli(['build', 'strict', '--sandbox', 'bwrap'], capture(root))).toBe(0);
    }, 240_000);
});
