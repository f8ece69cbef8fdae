/**
 * End-to-end: `contract serve` of a folder of several projects (field test: a folder of 7 projects
 * showed 84 errors "Schema 'altHold' is defined more than once (also in althold.contract)", the
 * other file in another project). The language worker checks names and the project-wide rules per
 * project, by the rule of docs/codegen.md "Where a project is", from the tree the IDE tells it:
 * a/ holds a src-gen/ (rule 1), b/ and c/ none (each first-level folder is a project, rule 3),
 * group/p/ and group/q/ each hold a src-gen/ (two projects: without their trees, group/ is one).
 * The Problems shown are those of `contract check` of the folder.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { startSession, openIde, shot, TUTORIAL, type Session } from './harness.js';

let s: Session;

/** The Problems rows: `path: message`, in their order. */
async function problems(): Promise<string[]> {
  return s.page.locator('.problem-row').evaluateAll((rows) => rows.map((r) => `${r.getAttribute('data-path')}: ${r.querySelector('.msg')?.textContent ?? ''}`));
}

const errors = () => s.page.locator('#status-problems').getAttribute('data-errors');

describe('a workspace of several projects in the IDE', () => {
  beforeAll(async () => {
    s = await startSession({ buildService: false, empty: true, port: 42010 });
    const w = (path: string, text: string) => {
      mkdirSync(dirname(join(s.workspace, path)), { recursive: true });
      writeFileSync(join(s.workspace, path), text);
    };
    cpSync(TUTORIAL, join(s.workspace, 'a'), { recursive: true, filter: (src) => !/[/]logs$/.test(src) });
    cpSync(TUTORIAL, join(s.workspace, 'b'), { recursive: true, filter: (src) => !/[/](logs|src-gen)$/.test(src) });
    // c: its datatype named as in a and b, and defined twice in c
    w('c/types.contract', 'datatype TypeA {float i = 0.0};\n');
    w('c/lib/types.contract', 'datatype TypeA {float i = 0.0};\n');
    w('group/p/x.contract', 'datatype Pose {float x = 0.0};\n');
    w('group/q/y.contract', 'datatype Pose {float x = 0.0};\n');
    mkdirSync(join(s.workspace, 'group/p/src-gen'));
    mkdirSync(join(s.workspace, 'group/q/src-gen'));
    await openIde(s);
  }, 60_000);
  afterAll(async () => {
    await s?.close();
  });

  it('shows each project\'s problems only, an "also in" named by its path in the project, as contract check does', async () => {
    await expect.poll(errors, { timeout: 30_000 }).toBe('2');
    await shot(s.page, 'several-projects-problems');
    expect(await problems()).toEqual([
      "c/lib/types.contract: Datatype 'TypeA' is defined more than once in the project (also in types.contract); datatype names are unique across the project.",
      "c/types.contract: Datatype 'TypeA' is defined more than once in the project (also in lib/types.contract); datatype names are unique across the project.",
    ]);
    const { loadWorkspace } = await import('@contract-studio/language/node');
    const checked = await loadWorkspace(s.workspace);
    expect(checked.layout.roots).toEqual(['a', 'b', 'c', 'group/p', 'group/q']);
    expect(checked.diagnostics.map((d) => `${d.file}: ${d.message}`).sort()).toEqual((await problems()).sort());
  }, 60_000);

  it('follows the tree: without their src-gen/, group/p and group/q are one project, group/', async () => {
    rmSync(join(s.workspace, 'group/p/src-gen'), { recursive: true });
    rmSync(join(s.workspace, 'group/q/src-gen'), { recursive: true });
    await expect.poll(errors, { timeout: 30_000 }).toBe('4');
    await shot(s.page, 'several-projects-one-group');
    const rows = await problems();
    expect(rows).toContain("group/p/x.contract: Datatype 'Pose' is defined more than once in the project (also in q/y.contract); datatype names are unique across the project.");
    expect(rows).toContain("group/q/y.contract: Datatype 'Pose' is defined more than once in the project (also in p/x.contract); datatype names are unique across the project.");
  }, 60_000);
});
