/**
 * Cactal load + validate + generate of one job, bounded (docs/sandbox.md, "Limits"): it runs in a
 * worker thread with a heap bound (`memoryMiB`) and a wall time bound (`prepareSeconds`), and is
 * terminated on either, or on cancel; the number of files it wrote is checked against
 * `generatedFiles`. A model too big to load never reaches it (`modelBytes`, checked by prepare).
 * The worker links the language and codegen packages itself (architecture.md Seam 4).
 */
import { createRequire } from 'node:module';
import { pathToFileURL } from 'node:url';
import { Worker } from 'node:worker_threads';
import type { Limits } from '../limits.js';
import { LimitHitError } from '../limits.js';
import type { WorkspaceDiagnostic } from '@contract-studio/language/node';
import type { GenerationProblem } from '@contract-studio/codegen';
import { generationProblems, workspaceProblems, type CactalProblem, type GenerateOutcome } from './cactal-adapter.js';

/** The worker's code (CommonJS, given as text: it also runs from the TypeScript sources in tests). */
const WORKER_CODE = `
const { parentPort, workerData } = require('node:worker_threads');
const plain = (v) => JSON.parse(JSON.stringify(v === undefined ? null : v));
(async () => {
  const language = await import(workerData.language);
  const codegen = await import(workerData.codegen);
  if (typeof language.loadWorkspace !== 'function') throw new Error('@contract-studio/language/node has no loadWorkspace(dir)');
  if (typeof codegen.generateArchitecture !== 'function') throw new Error('@contract-studio/codegen has no generateArchitecture()');
  // a job never reads host files through its imports (docs/sandbox.md, "Imports stay in the project")
  const ws = await language.loadWorkspace(workerData.projectDir, { confineImportsTo: workerData.projectDir });
  const go = await new Promise((resolve) => {
    parentPort.once('message', resolve);
    parentPort.postMessage({ kind: 'loaded', diagnostics: plain(ws.diagnostics) });
  });
  if (!go) return;
  // the job's private copy of the project: user code the merge cannot place is refused, not moved
  // to an orphans/ nobody sees (and built without); contract generate on the project moves it
  const res = await codegen.generateArchitecture(ws.documents, workerData.outDir, { displacedCode: 'refuse' });
  const count = (k) => (Array.isArray(res[k]) ? res[k].length : 0);
  parentPort.postMessage({ kind: 'generated', written: count('created') + count('updated'), unchanged: count('unchanged'), errors: plain(res.errors), warnings: plain(res.warnings) });
})().catch((e) => parentPort.postMessage({ kind: 'error', message: String((e && e.message) || e) }));
`;

type WorkerMessage =
  | { kind: 'loaded'; diagnostics: WorkspaceDiagnostic[] }
  | { kind: 'generated'; written: number; unchanged: number; errors: GenerationProblem[]; warnings: GenerationProblem[] }
  | { kind: 'error'; message: string };

function resolvePackage(spec: string): string {
  try {
    return pathToFileURL(createRequire(import.meta.url).resolve(spec)).href;
  } catch (e) {
    throw new Error(`cannot load ${spec} (${(e as Error).message.split('\n')[0]}); build the workspace packages first ("npm run build")`);
  }
}

/**
 * Loads, validates and generates the project in `projectDir` into `outDir` within the limits;
 * throws a LimitHitError naming the limit that stopped it.
 */
export function generateProjectBounded(projectDir: string, outDir: string, limits: Limits, cancelled?: Promise<void>): Promise<GenerateOutcome> {
  const workerData = { language: resolvePackage('@contract-studio/language/node'), codegen: resolvePackage('@contract-studio/codegen'), projectDir, outDir };
  const worker = new Worker(WORKER_CODE, {
    eval: true,
    workerData,
    resourceLimits: { maxOldGenerationSizeMb: limits.memoryMiB, maxYoungGenerationSizeMb: Math.min(64, limits.memoryMiB / 4) },
    stdout: true,
    stderr: true,
  });
  worker.stdout.resume(); // the generator's own console output is not part of the job log
  worker.stderr.resume();
  return new Promise<GenerateOutcome>((resolve, reject) => {
    let problems: CactalProblem[] = [];
    let settled = false;
    const settle = (fn: () => void): void => {
      if (settled) return;
      settled = true;
      clearTimeout(timer);
      void worker.terminate();
      fn();
    };
    const timer = setTimeout(
      () => settle(() => reject(new LimitHitError({ name: 'prepareSeconds', value: limits.prepareSeconds, unit: 's', mechanism: 'service-timer' }))),
      limits.prepareSeconds * 1000,
    );
    void cancelled?.then(() => settle(() => reject(new Error('cancelled'))));
    worker.on('message', (m: WorkerMessage) => {
      if (m.kind === 'loaded') {
        problems = workspaceProblems(m.diagnostics);
        const go = !problems.some((p) => p.severity === 'error');
        worker.postMessage(go);
        if (!go) settle(() => resolve({ problems, written: 0, unchanged: 0 }));
      } else if (m.kind === 'generated') {
        if (m.written + m.unchanged > limits.generatedFiles) {
          settle(() => reject(new LimitHitError({ name: 'generatedFiles', value: limits.generatedFiles, unit: 'count', mechanism: 'service-check' })));
        } else {
          settle(() => resolve({ problems: [...problems, ...generationProblems(m)], written: m.written, unchanged: m.unchanged }));
        }
      } else settle(() => reject(new Error(m.message)));
    });
    worker.on('error', (e: Error & { code?: string }) => {
      if (e.code === 'ERR_WORKER_OUT_OF_MEMORY') {
        settle(() => reject(new LimitHitError({ name: 'memory', value: limits.memoryMiB * 1024 * 1024, unit: 'bytes', mechanism: 'worker-heap' })));
      } else settle(() => reject(e));
    });
    worker.on('exit', (code) => settle(() => reject(new Error(`the generator stopped (exit ${code})`))));
  });
}
