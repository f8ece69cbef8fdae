/**
 * A project that an older `contract new` made has no `.gitignore`, while ContrACT Studio writes
 * files into it that are no source (logs/ and logs/previous/, src-gen/.contract-regions.json, ...).
 * When a command has just created such a file and the project is a git work tree that does not
 * ignore it, the command says once which lines of the `.gitignore` `contract new` writes
 * (project-gitignore.ts) to add: only then, so not at every command (the file exists afterwards).
 * Git decides what it ignores (`git check-ignore`: every .gitignore, info/exclude, the global
 * excludes); without git, or outside a work tree, nothing is said.
 */
import { execFile } from 'node:child_process';
import { PROJECT_GITIGNORE } from './project-gitignore.js';

/** Each pattern line of PROJECT_GITIGNORE with a path that it ignores (asked of git). */
function entries(): { line: string; probe: string }[] {
    return PROJECT_GITIGNORE.split('\n')
        .filter((l) => l !== '' && !l.startsWith('#'))
        .map((line) => ({ line, probe: line.endsWith('/') ? `${line}previous/x` : line.replace(/^\*/, 'x') }));
}

/** The paths of `paths` (relative to `dir`) that git ignores; undefined when `dir` is no git work tree or git cannot tell. */
function ignoredOf(dir: string, paths: string[]): Promise<Set<string> | undefined> {
    return new Promise((done) => {
        execFile('git', ['-C', dir, 'check-ignore', '--', ...paths], { timeout: 10_000 }, (err, stdout) => {
            // exit 1: none ignored; 128 (not a work tree) and a missing git: nothing known
            const code = (err as (Error & { code?: unknown }) | null)?.code;
            if (err && code !== 1) return done(undefined);
            done(new Set(stdout.split('\n').filter((l) => l !== '')));
        });
    });
}

/**
 * What to say when the command created `created` (paths relative to the project folder `dir`,
 * `projectLabel` as the user named it), or undefined: nothing created, no git work tree, or every
 * file created ignored already.
 */
export async function gitignoreHint(dir: string, projectLabel: string, created: string[]): Promise<string | undefined> {
    if (created.length === 0) return undefined;
    const all = entries();
    const ignored = await ignoredOf(dir, [...created, ...all.map((e) => e.probe)]);
    if (!ignored) return undefined;
    const committed = created.filter((p) => !ignored.has(p));
    if (committed.length === 0) return undefined;
    const missing = all.filter((e) => !ignored.has(e.probe)).map((e) => e.line);
    return `note: ${projectLabel} is a git repository whose .gitignore does not ignore ${committed.join(', ')}, just written by ContrACT Studio (no source: git add would commit it). ` +
        `Add these lines of the .gitignore that contract new writes (docs/getting-started.md "Keeping a project in git"):\n${missing.map((l) => `  ${l}\n`).join('')}`;
}
