import { describe, it, expect } from 'vitest';
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';
import { parseRegions, RegionSyntaxError, region } from '@contract-studio/codegen';
import { guardGeneratedWrite, MERGE_REASON, type RegionParser } from './region-guard.js';

const parser: RegionParser = { parseRegions, RegionSyntaxError };
const FILE = 'src-gen/generated/architecture/modules/MAA_mod/module.c';
const TUTORIAL_MAA = join(fileURLToPath(new URL('../../..', import.meta.url)), 'examples/tutorial/src-gen/generated/architecture/modules/MAA_mod/module.c');
/** Byte string of a UTF-8 text, as the guard sees files. */
const bytes = (s: string) => Buffer.from(s, 'utf8').toString('latin1');

const oldSkeleton = (exec: string, init = '//TODO') =>
  `#include "x.h"\nlong a = 0;\n${region('protect_init_M', init)}\nvoid f(void) {\n${region('protect_exec_M', exec)}\n}\n`;
// what Generate All writes after a port was added: new variable, new region, same IDs otherwise
const newSkeleton = (exec: string, init = '//TODO', react = '//TODO') =>
  `#include "x.h"\nlong a = 0;\nlong added_port = 0;\n${region('protect_init_M', init)}\nvoid f(void) {\n${region('protect_exec_M', exec)}\n}\n` +
  `void react(void) {\n${region('protect_react_M', react)}\n}\n`;

describe('guardGeneratedWrite (server guard of generated C)', () => {
  it('writes the incoming text when only region content changed (the normal save)', () => {
    const disk = oldSkeleton('//TODO');
    const incoming = oldSkeleton('\n  run();\n');
    expect(guardGeneratedWrite(incoming, disk, FILE, parser)).toEqual({ kind: 'write', text: incoming });
  });

  it('writes an identical text as is, also for a file without regions', () => {
    const whole = 'int main(void) { return contract_ord_main(&ORD); }\n';
    expect(guardGeneratedWrite(whole, whole, FILE, parser)).toEqual({ kind: 'write', text: whole });
  });

  it('merges the incoming regions into a regenerated skeleton, byte for byte', () => {
    const userExec = bytes('\r\n\t/* é user code, CRLF and tabs kept */  \n  run();\n');
    const disk = newSkeleton('//TODO', '/* init changed on disk */', '/* new region default */');
    const stale = oldSkeleton(userExec, '//TODO');
    const d = guardGeneratedWrite(stale, disk, FILE, parser);
    expect(d.kind).toBe('merge');
    if (d.kind !== 'merge') return;
    // skeleton and the region the tab did not know from disk; both known regions from the tab
    expect(d.text).toBe(newSkeleton(userExec, '//TODO', '/* new region default */'));
    expect(d.reason).toBe(MERGE_REASON);
  });

  it('merges a write that changed the generated code into the disk skeleton (another client)', () => {
    const disk = oldSkeleton('//TODO');
    const hostile = oldSkeleton('mine();').replace('long a = 0;', 'long a = 42; /* hand edit outside regions */');
    const d = guardGeneratedWrite(hostile, disk, FILE, parser);
    expect(d).toMatchObject({ kind: 'merge', text: oldSkeleton('mine();') });
  });

  it('takes the ENABLED flag from the incoming text', () => {
    const disk = newSkeleton('//TODO');
    const incoming = oldSkeleton('x();').replace('ID(protect_exec_M) ENABLED START', 'ID(protect_exec_M) START');
    const d = guardGeneratedWrite(incoming, disk, FILE, parser);
    expect(d.kind).toBe('merge');
    if (d.kind !== 'merge') return;
    expect(d.text).toContain('/*PROTECTED REGION ID(protect_exec_M) START*/x();/*PROTECTED REGION END*/');
    expect(d.text).toContain('long added_port = 0;');
    expect(parseRegions(d.text, FILE).regions.map((r) => [r.id, r.enabled])).toEqual([
      ['protect_init_M', true], ['protect_exec_M', false], ['protect_react_M', true],
    ]);
  });

  it('refuses a region that no longer exists on disk, naming it and its line', () => {
    const disk = oldSkeleton('//TODO').replace(region('protect_init_M', '//TODO'), '');
    const incoming = oldSkeleton('x();', '/* my init */');
    const d = guardGeneratedWrite(incoming, disk, FILE, parser);
    expect(d).toMatchObject({ kind: 'refuse', region: 'protect_init_M', line: 3 });
    if (d.kind === 'refuse') expect(d.message).toMatch(/protected region 'protect_init_M' no longer exists.*nothing was written/);
  });

  it('refuses malformed incoming text with the line: START without END, nested START, duplicate ID', () => {
    const disk = oldSkeleton('//TODO');
    const noEnd = oldSkeleton('x();').replace(/\/\*PROTECTED REGION END\*\/\n\}/, '\n}');
    const nested = oldSkeleton(`\n${region('protect_init_M', '')}`);
    const duplicate = `${oldSkeleton('x();')}${region('protect_exec_M', 'again')}\n`;
    const refusals = [noEnd, nested, duplicate].map((t) => guardGeneratedWrite(t, disk, FILE, parser));
    expect(refusals.map((d) => d.kind)).toEqual(['refuse', 'refuse', 'refuse']);
    const [a, b, c] = refusals.map((d) => (d.kind === 'refuse' ? d : undefined)!);
    expect([a.line, a.message]).toEqual([5, expect.stringMatching(/module\.c:5: .*START without END/)]);
    expect([b.line, b.message]).toEqual([6, expect.stringMatching(/module\.c:6: nested/)]);
    expect([c.line, c.message]).toEqual([7, expect.stringMatching(/module\.c:7: duplicate .*protect_exec_M/)]);
  });

  it('refuses any change to a generated file without regions (generated whole)', () => {
    const ord = 'int ModuleMain(int argc, const char *argv[]) { return contract_ord_main(&ORD_TABLES); }\n';
    const d = guardGeneratedWrite(ord.replace('ORD_TABLES', 'MY_TABLES'), ord, FILE, parser);
    expect(d).toMatchObject({ kind: 'refuse', message: expect.stringMatching(/generated whole: edit the \.contract model instead/) });
    // adding regions to such a file does not make it editable
    expect(guardGeneratedWrite(ord + region('mine', 'x'), ord, FILE, parser).kind).toBe('refuse');
  });

  it('lets a well-formed text replace a malformed file on disk (repair)', () => {
    const broken = oldSkeleton('//TODO').replace(/\/\*PROTECTED REGION END\*\/\n\}/, '\n}');
    const fixed = oldSkeleton('x();');
    expect(guardGeneratedWrite(fixed, broken, FILE, parser)).toEqual({ kind: 'write', text: fixed });
  });

  it('on the tutorial MAA module.c: a stale tab with an added port in the skeleton keeps all its regions', () => {
    const disk = readFileSync(TUTORIAL_MAA, 'latin1');
    const marker = 'ID(protect_exec_MAA) ENABLED START*/';
    const edited = disk.replace(marker, `${marker}\n    /* edited in the tab */`);
    expect(guardGeneratedWrite(edited, disk, FILE, parser)).toEqual({ kind: 'write', text: edited });
    const regenerated = disk.replace('ModuleProduce IPRODUCE[]', '/* regenerated */\nModuleProduce IPRODUCE[]');
    const d = guardGeneratedWrite(edited, regenerated, FILE, parser);
    expect(d).toMatchObject({ kind: 'merge', text: edited.replace('ModuleProduce IPRODUCE[]', '/* regenerated */\nModuleProduce IPRODUCE[]') });
  });
});
