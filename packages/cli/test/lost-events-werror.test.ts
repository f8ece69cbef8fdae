/**
 * Real bwrap builds and runs of the `contract new` project (LOC, CTL, supervisor MIS):
 * - a lost event fails the run: CTL's posts to a subscriber that is not running fail (as one to a
 *   mailbox full for the 2 s PostEvent waits does): the events are lost. Before, the run ended
 *   `ok: run finished (exit 0)` and `contract trace`'s line of counts had no count of failed posts;
 * - `--werror`: a warning in a protected region fails the build, shown; without it the build passes.
 */
import { readdirSync, readFileSync, writeFileSync } from 'node:fs';
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

    it('lost by a running subscriber too slow to take them (its mailbox full for over 2 s): the failed posts waited 2 s each, events-lost, exit 4', async () => {
        await newProject('slow');
        // LOC and CTL released side by side (no precedence): LOC is the subscriber, running, that
        // reads no request for 5 s in its first release; CTL, 300 ms into its own, posts a burst of 15
        // to it. The first ones fill LOC's mailbox; each post then waits the 2 s PostEvent waits for
        // room and fails (the event lost), until LOC reads its mailbox again.
        const schema = join(root, 'slow', 'schema.contract');
        const graphless = readFileSync(schema, 'utf8').replace(/ *scheduling graph \{ LOC -> CTL; \}\n/, '');
        expect(graphless).not.toContain('scheduling graph');
        writeFileSync(schema, graphless);
        expect(await runCli(['generate', 'slow'], capture(root))).toBe(0);
        region('slow', 'LOC', 'protect_additional_import_LOC', '#include <unistd.h>');
        region('slow', 'LOC', 'protect_exec_LOC', '    { static int calls = 0; if (++calls == 1) sleep(5); }');
        region('slow', 'CTL', 'protect_additional_import_CTL', '#include <unistd.h>');
        region('slow', 'CTL', 'protect_exec_CTL', [
            '    { static int calls = 0; if (++calls == 1) { usleep(300000); SubscribeUserToEvent("LOC", 5, 0, EVENT_CONTINUOUS);',
            '      for (int i = 0; i < 15; i++) { strcpy(status, "late"); PostEvent(&status); } } }',
        ].join('\n'));
        const io = capture(root);
        const code = await runCli(['run', 'slow', '--sandbox', 'bwrap', '--duration', '8s', '--logs', 'slow-logs', '--format', 'json'], io);
        const out = JSON.parse(io.stdout) as { result: { ok: boolean; issues: { kind: string; module?: string; message: string }[] } };
        const said = JSON.stringify(out.result.issues, null, 1);

        // the record: CTL's posts to LOC, the failed ones each 2 s after the post before it (the wait for
        // room in a running subscriber's full mailbox; a post to one not running fails at once)
        const logs = join(root, 'slow-logs');
        const ctl = readFileSync(join(logs, readdirSync(logs).find((f) => f.startsWith('CTL_'))!), 'utf8');
        const posts = ctl.split('\n').filter((l) => /,event_posted,LOC,0,/.test(l)).map((l) => ({ ns: Number(l.split(',')[0]), failed: l.endsWith('to_port=5 failed') }));
        const failed = posts.filter((p) => p.failed);
        expect(posts, ctl).toHaveLength(15);
        expect(failed.length, ctl).toBeGreaterThanOrEqual(1);
        for (const p of failed) {
            const before = posts[posts.indexOf(p) - 1]!;
            expect(p.ns - before.ns, `a failed post ${(p.ns - before.ns) / 1e6} ms after the post before it`).toBeGreaterThanOrEqual(1.9e9);
        }
        // LOC was running all along, and read its mailbox again: the posts after it had room reached it
        expect(posts.at(-1)!.failed, ctl).toBe(false);

        // the run issue, in the words the docs give, naming the runtime's cause: LOC's full mailbox
        const lost = out.result.issues.filter((i) => i.kind === 'events-lost');
        expect(lost, said).toHaveLength(1);
        expect(lost[0]!.module).toBe('CTL');
        const one = failed.length === 1;
        expect(lost[0]!.message).toMatch(new RegExp(`^${failed.length} ${one ? 'event' : 'events'} CTL posted to LOC ${one ? 'was' : 'were'} lost \\(CTL:0 -> LOC:5\\): ` +
            `${one ? 'its post' : 'their posts'} failed \\(PostEvent gives up after waiting 2 s for room in LOC's full mailbox, at once when LOC is not running\\); ` +
            'the last: EVENT request to LOC: mailbox full: the module did not read its requests in time [^\\n]*$'));
        expect(out.result.ok).toBe(false);
        expect(code).toBe(4);
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
