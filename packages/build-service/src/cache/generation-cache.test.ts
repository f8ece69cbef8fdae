/**
 * Generated trees by inputs (generation-cache.ts) through the real prepare step on the tutorial:
 * a fresh workspace stores its tree; another fresh workspace with the same inputs takes it
 * (same bytes, no generator run); other inputs or a damaged entry run the generator; a lower
 * `generatedFiles` limit still holds on a cached tree.
 */
import { mkdirSync, mkdtempSync, readdirSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, test } from 'vitest';
import { DEFAULT_LIMITS, LimitHitError } from '../limits.js';
import { prepareWorkspace } from '../pipeline/prepare.js';
import type { Workspace } from '../pipeline/workspaces.js';
import { tutorialFiles, withRegion, MAA_MODULE } from '../test-support/tutorial.js';
import { listFilesNoFollow, readFileNoFollow } from '../util/safe-fs.js';
import { GenerationCache } from './generation-cache.js';

const scratch = mkdtempSync(join(tmpdir(), 'generation-cache-test-'));
afterAll(() => rmSync(scratch, { recursive: true, force: true }));
let n = 0;

function workspace(): Workspace {
  const root = join(scratch, `ws${n++}`);
  mkdirSync(join(root, 'stage'), { recursive: true });
  mkdirSync(join(root, 'work'));
  return { root, stageDir: join(root, 'stage'), workDir: join(root, 'work'), owner: { uid: process.getuid!(), gid: process.getgid!() }, reused: false, acceptedOutputs: null, reset: async () => {}, release: async () => {} };
}

async function stagedTree(ws: Workspace): Promise<Map<string, string>> {
  const dir = join(ws.stageDir, 'project', 'src-gen');
  const out = new Map<string, string>();
  for (const rel of await listFilesNoFollow(dir)) out.set(rel, (await readFileNoFollow(dir, rel))!.toString('utf8'));
  return out;
}

describe('GenerationCache in prepare', () => {
  const cache = new GenerationCache(join(scratch, 'generated'));

  test('same inputs in a new workspace: the stored tree, byte for byte, without the generator', async () => {
    const files = await tutorialFiles();
    const firstLog: string[] = [];
    const first = workspace();
    expect((await prepareWorkspace(first, { files }, 'cactal', DEFAULT_LIMITS, (l) => firstLog.push(l), undefined, cache)).ok).toBe(true);
    expect(firstLog.join('\n')).not.toContain('taken from the build cache');
    expect(readdirSync(join(scratch, 'generated'))).toHaveLength(1);

    const secondLog: string[] = [];
    const second = workspace();
    const out = await prepareWorkspace(second, { files }, 'cactal', DEFAULT_LIMITS, (l) => secondLog.push(l), undefined, cache);
    expect(out.ok).toBe(true);
    expect(secondLog.join('\n')).toContain('generated tree taken from the build cache (same inputs and generator)');
    expect(await stagedTree(second)).toEqual(await stagedTree(first));
    expect(out.regions.size).toBeGreaterThan(0);
  });

  test('other inputs run the generator', async () => {
    const files = withRegion(await tutorialFiles(), MAA_MODULE, 'protect_init_MAA', '    /* another edit */', true);
    const log: string[] = [];
    await prepareWorkspace(workspace(), { files }, 'cactal', DEFAULT_LIMITS, (l) => log.push(l), undefined, cache);
    expect(log.join('\n')).not.toContain('taken from the build cache');
  });

  test('a damaged entry is ignored: the generator runs', async () => {
    for (const f of readdirSync(join(scratch, 'generated'))) writeFileSync(join(scratch, 'generated', f), 'not gzip');
    const log: string[] = [];
    const out = await prepareWorkspace(workspace(), { files: await tutorialFiles() }, 'cactal', DEFAULT_LIMITS, (l) => log.push(l), undefined, cache);
    expect(out.ok).toBe(true);
    expect(log.join('\n')).not.toContain('taken from the build cache');
  });

  test('the generatedFiles limit holds for a cached tree', async () => {
    const files = await tutorialFiles();
    await prepareWorkspace(workspace(), { files }, 'cactal', DEFAULT_LIMITS, () => {}, undefined, cache);
    const hit = await prepareWorkspace(workspace(), { files }, 'cactal', { ...DEFAULT_LIMITS, generatedFiles: 5 }, () => {}, undefined, cache).catch((e: unknown) => e);
    expect(hit).toBeInstanceOf(LimitHitError);
    expect((hit as LimitHitError).hit).toEqual({ name: 'generatedFiles', value: 5, unit: 'count', mechanism: 'service-check' });
  });
});
