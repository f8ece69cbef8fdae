/**
 * POST /api/rename-entity and the project's `.scenario` files (rename-api.ts): the real IDE server
 * on copies of the tutorial (its two scenarios), real files, links and FIFOs.
 */
import { describe, it, expect, beforeAll, afterAll } from 'vitest';
import { cpSync, existsSync, readFileSync, writeFileSync, symlinkSync } from 'node:fs';
import { execFileSync } from 'node:child_process';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import type { IdeServer } from './ide-server.js';
import { startTempIdeServer, type TempIdeServer } from './temp-ide-server.test-support.js';
import type { RenameEntityResponse } from './api-types.js';

const TUTORIAL = join(fileURLToPath(new URL('../../..', import.meta.url)), 'examples/tutorial');
const MOBILE_ROBOT = join(fileURLToPath(new URL('../../..', import.meta.url)), 'examples/mobile-robot');

let base: string;
let ws: string;
let ide: IdeServer;

/** ws/<name>: the tutorial's sources and scenarios (no src-gen). */
function project(name: string): string {
  const dir = join(ws, name);
  cpSync(TUTORIAL, dir, { recursive: true, filter: (src) => !src.includes('src-gen') });
  return dir;
}

async function rename(body: unknown): Promise<{ status: number; body: RenameEntityResponse & { error?: string } }> {
  const res = await fetch(`${ide.url}/api/rename-entity`, { method: 'POST', headers: { 'content-type': 'application/json', 'x-contract-token': ide.token }, body: JSON.stringify(body) });
  return { status: res.status, body: (await res.json()) as RenameEntityResponse & { error?: string } };
}

const scenario = (p: string, name: string) => readFileSync(join(p, 'scenarios', name), 'utf8');

let server: TempIdeServer;
beforeAll(async () => {
  server = await startTempIdeServer('ide-rename-api-');
  ({ base, ws, ide } = server);
});
afterAll(() => server.close());

describe('a rename carried into the .scenario files', () => {
  it('a supervision function: SUP.action becomes SUP.react in start, stop and expect lines, token by token; comments stay', async () => {
    const p = project('sf');
    const before = scenario(p, 'commutation.scenario');
    const r = await rename({ project: 'sf', from: 'action', to: 'react', kind: 'supervision function', owner: 'SUP' });
    expect(r.status).toBe(200);
    const after = scenario(p, 'commutation.scenario');
    expect(after).toContain('start SUP.react(consigne = {1.0, 2.0, 3.0})\n');
    expect(after).toContain('expect rule SUP.react.FIRST inactive\n');
    expect(after).not.toMatch(/^(?!#|scenario )[^\n]*SUP\.action/m); // no step names the old function (comments and the title are free text)
    expect(after).toContain('# The report\'s §4.7 story (docs/simulation.md): SUP.action\'s rule FIRST'); // a comment is not a step
    // every changed line is listed, as a workspace path with its line before and after
    const changed = before.split('\n').filter((l, i) => l !== after.split('\n')[i]).length;
    expect(r.body.scenarios.filter((e) => e.file === 'sf/scenarios/commutation.scenario')).toHaveLength(changed);
    expect(r.body.scenarios[0]).toMatchObject({ file: expect.stringMatching(/^sf\/scenarios\/.*\.scenario$/), before: expect.stringContaining('SUP.action'), after: expect.stringContaining('SUP.react') });
    expect(r.body.scenariosLeft).toEqual([]);
    // a schema's or module's generated files are not touched for a supervision function
    expect(r.body.movedPaths).toEqual([]);
  });

  it('a schema: expect schema lines follow; an owner-less supervision function, an unknown kind and a bad owner are 400', async () => {
    const p = project('sch');
    // and expect deadline misses / overruns lines
    const file = join(p, 'scenarios', 'commutation.scenario');
    writeFileSync(file, `${readFileSync(file, 'utf8')}expect deadline misses schemaCommande1 == 0\nexpect overruns schemaCommande1 == 0\n`);
    const r = await rename({ project: 'sch', from: 'schemaCommande1', to: 'command1', kind: 'schema' });
    expect(r.status).toBe(200);
    expect(scenario(p, 'commutation.scenario')).toContain('expect schema command1 active\n');
    expect(scenario(p, 'commutation.scenario')).toContain('expect deadline misses command1 == 0\nexpect overruns command1 == 0\n');
    expect(scenario(p, 'commutation.scenario')).not.toMatch(/\bschemaCommande1\b/);
    expect((await rename({ project: 'sch', from: 'action', to: 'x', kind: 'supervision function' })).status).toBe(400);
    expect((await rename({ project: 'sch', from: 'a', to: 'b', kind: 'rule label' })).status).toBe(400);
    expect((await rename({ project: 'sch', from: 'a', to: 'b', kind: 'port', owner: '../MAA' })).status).toBe(400);
    expect((await rename({ project: 7, from: 'a', to: 'b', kind: 'schema' })).status).toBe(400);
  });

  it('a module: M:P, expect module and the port of its events follow; a port of another module of that name does not', async () => {
    const p = project('mod');
    const r = await rename({ project: 'mod', from: 'MAA', to: 'MAZ', kind: 'module' });
    expect(r.status).toBe(200);
    const text = scenario(p, 'commutation.scenario');
    expect(text).toContain('t=300ms MAZ:2 connection_status = "disconnected"\n');
    expect(text).toContain('expect module MAZ stopped\n');
    // the scenario's title is free text: left as written
    expect(text).toContain('scenario SUP.action: FIRST, SECOND on MAA:2 "disconnected", the commutation\n');
    // a port rename names its module: another module's scenario lines stay
    const port = await rename({ project: 'mod', from: 'connection_status', to: 'link', kind: 'port', owner: 'MSC' });
    expect(port.status).toBe(200);
    expect(scenario(p, 'commutation.scenario')).toContain('MAZ:2 connection_status = "disconnected"');
  });

  it('a rule label, a local (qualified or bare) and a parameter of SUP.action: only that function\'s names follow', async () => {
    const p = project('fn');
    expect((await rename({ project: 'fn', from: 'SECOND', to: 'LINK_LOST', kind: 'rule label', owner: 'SUP.action' })).status).toBe(200);
    expect((await rename({ project: 'fn', from: 'temp_message', to: 'last_message', kind: 'local', owner: 'SUP.action' })).status).toBe(200);
    expect((await rename({ project: 'fn', from: 'temp_mess_type', to: 'last_type', kind: 'local', owner: 'SUP.action' })).status).toBe(200);
    expect((await rename({ project: 'fn', from: 'consigne', to: 'setpoint', kind: 'function parameter', owner: 'SUP.action' })).status).toBe(200);
    const text = scenario(p, 'commutation.scenario');
    expect(text).toContain('expect rule SUP.action.LINK_LOST active\n');
    expect(text).toContain('expect local SUP.action.last_message == {"hello", 2, {0.5, 0.5, 0.5}}\n');
    expect(text).toContain('expect local last_type == "commutation"\n');
    expect(text).toContain('start SUP.action(setpoint = {1.0, 2.0, 3.0})\n');
    // the title is free text; another function's rule of that name would not be renamed
    expect(text).toContain('FIRST, SECOND on MAA:2');
    const other = await rename({ project: 'fn', from: 'FIRST', to: 'ONE', kind: 'rule label', owner: 'GLB.mission' });
    expect(other.body.scenarios).toEqual([]);
    expect(scenario(p, 'commutation.scenario')).toContain('expect rule SUP.action.FIRST inactive\n');
    // the owner of these kinds is SUP.function
    expect((await rename({ project: 'fn', from: 'FIRST', to: 'ONE', kind: 'rule label', owner: 'SUP' })).status).toBe(400);
    expect((await rename({ project: 'fn', from: 'FIRST', to: 'ONE', kind: 'rule label' })).status).toBe(400);
    expect((await rename({ project: 'fn', from: 'x', to: 'y', kind: 'port', owner: 'SUP.action' })).status).toBe(400);
  });

  it('a scenario that is a link, a FIFO or a file over 1 MiB is left alone; the files beside it are renamed', async () => {
    const p = project('hostile');
    const outside = join(base, 'outside.scenario');
    writeFileSync(outside, 'expect module MAA running\n');
    symlinkSync(outside, join(p, 'scenarios', 'link.scenario'));
    execFileSync('mkfifo', [join(p, 'scenarios', 'pipe.scenario')]);
    writeFileSync(join(p, 'scenarios', 'big.scenario'), 'expect module MAA running\n' + '#'.repeat(2 << 20) + '\n');
    const r = await rename({ project: 'hostile', from: 'MAA', to: 'MAZ', kind: 'module' });
    expect(r.status).toBe(200);
    expect(readFileSync(outside, 'utf8')).toBe('expect module MAA running\n');
    expect(readFileSync(join(p, 'scenarios', 'big.scenario'), 'utf8').startsWith('expect module MAA running\n')).toBe(true);
    expect(scenario(p, 'commutation.scenario')).toContain('expect module MAZ stopped\n');
    expect(new Set(r.body.scenarios.map((e) => e.file))).toEqual(new Set(['hostile/scenarios/commutation.scenario', 'hostile/scenarios/mission.scenario']));
  });

  it('the scenarios of a subfolder that is a project of its own are not renamed with this one', async () => {
    const p = project('outer');
    const inner = join(p, 'inner');
    cpSync(TUTORIAL, inner, { recursive: true, filter: (src) => !src.includes('src-gen') });
    const r = await rename({ project: 'outer', from: 'MAA', to: 'MAZ', kind: 'module' });
    expect(r.status).toBe(200);
    expect(scenario(p, 'commutation.scenario')).toContain('expect module MAZ stopped');
    expect(scenario(inner, 'commutation.scenario')).toContain('expect module MAA stopped');
  });
});

describe('a rename of an enumeration or of one of its members carried into src-gen', () => {
  const VEL = 'src-gen/generated/architecture/modules/VEL_mod/module.c';
  const COMMON = 'src-gen/generated/architecture/common';

  it('an enumeration: common/Shared<Enum>.h moves, its type and constants in the regions\' code follow; a member: its constant follows', async () => {
    const p = join(ws, 'enum');
    cpSync(MOBILE_ROBOT, p, { recursive: true });
    expect(readFileSync(join(p, VEL), 'latin1')).toContain('if (mode == DriveMode_SAFESTOP) { v = 0.0; w = 0.0; }');
    const r = await rename({ project: 'enum', from: 'DriveMode', to: 'Mode', kind: 'enumeration', members: ['TELEOP', 'AUTO', 'SAFESTOP'] });
    expect(r.status).toBe(200);
    expect(r.body.movedPaths).toEqual([{ from: 'generated/architecture/common/SharedDriveMode.h', to: 'generated/architecture/common/SharedMode.h' }]);
    expect(existsSync(join(p, COMMON, 'SharedDriveMode.h'))).toBe(false);
    expect(existsSync(join(p, COMMON, 'SharedMode.h'))).toBe(true);
    expect(r.body.rewritten).toEqual([expect.objectContaining({ file: 'generated/architecture/modules/VEL_mod/module.c', id: 'protect_exec_VEL', occurrences: 2 })]);
    expect(readFileSync(join(p, VEL), 'latin1')).toContain('print_Mode(&mode);');
    expect(readFileSync(join(p, VEL), 'latin1')).toContain('if (mode == Mode_SAFESTOP) { v = 0.0; w = 0.0; }');

    const member = await rename({ project: 'enum', from: 'SAFESTOP', to: 'HALT', kind: 'enumeration member', owner: 'Mode' });
    expect(member.status).toBe(200);
    expect(member.body.movedPaths).toEqual([]);
    expect(member.body.rewritten).toEqual([expect.objectContaining({ file: 'generated/architecture/modules/VEL_mod/module.c', occurrences: 1 })]);
    expect(readFileSync(join(p, VEL), 'latin1')).toContain('if (mode == Mode_HALT) { v = 0.0; w = 0.0; }');
    // a member's rename needs its enumeration; members only name an enumeration's, as identifiers
    expect((await rename({ project: 'enum', from: 'HALT', to: 'STOP', kind: 'enumeration member' })).status).toBe(400);
    expect((await rename({ project: 'enum', from: 'Mode', to: 'Gear', kind: 'enumeration', members: ['A', 'b-c'] })).status).toBe(400);
    expect((await rename({ project: 'enum', from: 'Pose', to: 'Place', kind: 'datatype', members: ['A'] })).status).toBe(400);
  });
});
