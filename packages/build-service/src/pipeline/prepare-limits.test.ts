/**
 * The host-side prepare step is bounded (docs/sandbox.md, "Limits"): a model above `modelBytes` is
 * refused before loading, generation stops at `prepareSeconds` (worker terminated) and at its heap
 * bound, and a generation that wrote more than `generatedFiles` is refused, each with the limit's name.
 */
import { mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { generateSyntheticArchitecture } from '@contract-studio/language/bench';
import { afterEach, describe, expect, test } from 'vitest';
import { DEFAULT_LIMITS, LimitHitError, type Limits } from '../limits.js';
import { tutorialFiles } from '../test-support/tutorial.js';
import { prepareWorkspace } from './prepare.js';
import type { Workspace } from './workspaces.js';

const roots: string[] = [];
afterEach(() => {
  for (const r of roots.splice(0)) rmSync(r, { recursive: true, force: true });
});

function workspace(): Workspace {
  const root = mkdtempSync(join(tmpdir(), 'prepare-limits-'));
  roots.push(root);
  mkdirSync(join(root, 'stage'));
  mkdirSync(join(root, 'work'));
  return { root, stageDir: join(root, 'stage'), workDir: join(root, 'work'), owner: { uid: process.getuid!(), gid: process.getgid!() }, reused: false, acceptedOutputs: null, reset: async () => {}, release: async () => {} };
}

async function hitOf(p: Promise<unknown>): Promise<unknown> {
  try {
    await p;
  } catch (e) {
    if (e instanceof LimitHitError) return { ...e.hit, message: e.message };
    throw e;
  }
  return null;
}

const limits = (over: Partial<Limits>): Limits => ({ ...DEFAULT_LIMITS, ...over });

describe('prepare limits', () => {
  test('the tutorial prepares within the default limits', async () => {
    const out = await prepareWorkspace(workspace(), { files: await tutorialFiles() }, 'cactal', limits({}), () => {});
    expect(out.ok).toBe(true);
    expect(out.synced).toBeGreaterThan(10);
  });

  test('a model above modelBytes is refused before it is loaded', async () => {
    const files = { ...(await tutorialFiles()), 'padding.contract': `// ${'x'.repeat(1100 * 1024)}\n` };
    expect(await hitOf(prepareWorkspace(workspace(), { files }, 'cactal', limits({}), () => {}))).toEqual({
      name: 'modelBytes', value: 1024 * 1024, unit: 'bytes', mechanism: 'service-check', message: 'model size limit 1 MiB',
    });
  });

  test('generation that outlives prepareSeconds is stopped', async () => {
    const files = Object.fromEntries(generateSyntheticArchitecture({ periodicSchemas: 120, eventSchemas: 30 }));
    const t0 = Date.now();
    expect(await hitOf(prepareWorkspace(workspace(), { files }, 'cactal', limits({ prepareSeconds: 1 }), () => {}))).toMatchObject({
      name: 'prepareSeconds', value: 1, mechanism: 'service-timer', message: 'prepare time limit 1 s',
    });
    expect(Date.now() - t0).toBeLessThan(20_000);
  });

  test('a generation writing more than generatedFiles is refused', async () => {
    expect(await hitOf(prepareWorkspace(workspace(), { files: await tutorialFiles() }, 'cactal', limits({ generatedFiles: 5 }), () => {}))).toEqual({
      name: 'generatedFiles', value: 5, unit: 'count', mechanism: 'service-check', message: 'generated file limit 5',
    });
  });
});
