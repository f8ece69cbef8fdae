import { mkdirSync, mkdtempSync, rmSync, utimesSync, writeFileSync, chmodSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, test } from 'vitest';
import { hostWorkTreeDigest } from './work-tree-digest.js';

let work: string;
beforeEach(() => {
  work = mkdtempSync(join(tmpdir(), 'digest-work-'));
  mkdirSync(join(work, 'mod'));
  writeFileSync(join(work, 'mod', 'prog'), 'ELF');
  writeFileSync(join(work, 'main.c'), 'int main(void){return 0;}');
});
afterEach(() => rmSync(work, { recursive: true, force: true }));

describe('work-tree digest (build products between jobs)', () => {
  test('stable when nothing changed; logs/ and run/ do not count', async () => {
    const d = await hostWorkTreeDigest(work);
    expect(d).toMatch(/^[0-9a-f]{64}$/);
    mkdirSync(join(work, 'logs'));
    writeFileSync(join(work, 'logs', 'MAA.csv'), 'a;b\n');
    mkdirSync(join(work, 'run'));
    expect(await hostWorkTreeDigest(work)).toBe(d);
  });

  test.each([
    ['same bytes rewritten', (w: string) => writeFileSync(join(w, 'mod', 'prog'), 'ELF')],
    ['re-dated to 2100', (w: string) => utimesSync(join(w, 'mod', 'prog'), new Date('2100-01-01'), new Date('2100-01-01'))],
    ['a new file', (w: string) => writeFileSync(join(w, 'mod', 'extra.o'), '')],
    ['made executable', (w: string) => chmodSync(join(w, 'main.c'), 0o755)],
  ])('changes when a product is %s', async (_what, change) => {
    const d = await hostWorkTreeDigest(work);
    await new Promise((r) => setTimeout(r, 20)); // a new ctime
    change(work);
    expect(await hostWorkTreeDigest(work)).not.toBe(d);
  });
});
