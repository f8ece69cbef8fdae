/**
 * vitest globalSetup: one build-cache folder for the whole run (every test file reads it through
 * `inject('simulatorCache')` in support.ts), removed when the run ends.
 */
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import type { TestProject } from 'vitest/node';

declare module 'vitest' {
    export interface ProvidedContext {
        simulatorCache: string;
    }
}

export default function setup(project: TestProject): () => void {
    const dir = mkdtempSync(join(tmpdir(), 'contract-sim-test-'));
    project.provide('simulatorCache', dir);
    return () => rmSync(dir, { recursive: true, force: true, maxRetries: 3 });
}
