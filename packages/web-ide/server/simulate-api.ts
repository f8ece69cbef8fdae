/**
 * POST /api/simulate: runs one scenario on the workspace's project in virtual time through
 * `@contract-studio/simulator`'s programmatic API (prepareProject, loadScenario,
 * runLoadedScenario: the code of `contract simulate`, docs/simulation.md §3), for the Simulate
 * panel (docs/simulation.md "In the IDE").
 *
 * Body: `{ project?: "folder", scenario: "text" }` or `{ project?, path: "x.scenario" }` (a
 * workspace file, read without following links). Answers 200 with the steps (SimulateResponse),
 * 422 with diagnostics when the model or the scenario has errors (nothing ran), 503 when the
 * simulator is not built. The simulators are kept in `sim/` of the build cache the embedded build
 * service uses (`$CONTRACT_CACHE_DIR`, else the XDG cache folder); when that folder is refused, the
 * reason is logged once and a private temporary cache is used, as the build service does.
 * Everything in the request is hostile: sizes are bounded, one
 * simulation runs at a time (at most 8 wait, then 429), each is bounded in wall time, and the
 * answer in size.
 */
import { inProjectFolder } from './project-folder.js';
import { mkdtempSync, rmSync } from 'node:fs';
import type { IncomingMessage, ServerResponse } from 'node:http';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { SRC_GEN_DIR } from '@contract-studio/conventions';
import { HttpError } from './http-error.js';
import { readJson, sendJson } from './http-util.js';
import type { WorkspacePaths } from './workspace-paths.js';
import { WorkspaceFs } from './workspace-fs.js';
import { IDE_MAX_MODEL_BYTES, loadSimulator, modelTooLarge, type SimulatorApi } from './integrations.js';
import type { SimulateDiagnostic, SimulateResponse, SimulateStep } from './api-types.js';

/** A session's scenario is small; this bounds what one request may make the harness do. */
export const MAX_SCENARIO_CHARS = 256 * 1024;
const RUN_TIMEOUT_MS = 10_000;
/**
 * What one answer keeps of the steps' lists (rule changes, actions, locals, schemas, typed records,
 * engine lines), all steps together, each list whole while it lasts: about 25 MB of JSON, the 1 ms
 * schema of 2 modules for 20 s of virtual time. What is left out is counted in the step's `dropped`.
 */
export const MAX_ITEMS_PER_ANSWER = 200_000;
const MAX_STEPS = 5_000;
const MAX_OUTPUT = 2_048;
const MAX_WAITING = 8;

export class SimulateApi {
  /** One simulation at a time: each is a native process, the machine's cores are shared. */
  private queue: Promise<unknown> = Promise.resolve();
  private waiting = 0;
  /** The build cache root the simulators go under (chosen on the first simulation). */
  private cacheRoot: string | undefined;
  /** The private temporary cache used instead of a refused one: removed by close(). */
  private privateCache: string | undefined;

  constructor(private readonly paths: WorkspacePaths, private readonly log: (line: string) => void = (l) => process.stderr.write(`${l}\n`)) {}

  private cacheFor(sim: SimulatorApi): string {
    if (this.cacheRoot === undefined) {
      const cache = sim.simulatorCacheDir(undefined);
      if ('error' in cache) {
        this.log(`simulator cache: ${cache.error}; using a private temporary cache instead`);
        this.cacheRoot = this.privateCache = mkdtempSync(join(tmpdir(), 'contract-ide-sim-'));
      } else this.cacheRoot = cache.root.dir;
    }
    return this.cacheRoot;
  }

  /** Removes the private temporary cache, if one was made (the server is closing). */
  close(): void {
    if (this.privateCache) rmSync(this.privateCache, { recursive: true, force: true });
    this.privateCache = undefined;
  }

  async handle(req: IncomingMessage, res: ServerResponse, url: URL): Promise<boolean> {
    if (url.pathname !== '/api/simulate') return false;
    if (req.method !== 'POST') throw new HttpError(405, 'POST /api/simulate');
    const body = await readJson(req);
    const project = body.project ?? '';
    if (typeof project !== 'string') throw new HttpError(400, 'project must be a workspace folder');
    const projectDir = this.paths.resolve(project);
    let text: string | undefined;
    let bytes: Buffer | undefined;
    let display = 'scenario';
    if (typeof body.scenario === 'string') text = body.scenario;
    else if (typeof body.path === 'string' && body.path.endsWith('.scenario')) {
      display = this.paths.toRelative(this.paths.resolve(body.path));
      bytes = await readBytes(this.paths.fs, display);
    } else if (typeof body.path === 'string') throw new HttpError(400, `path must name a .scenario file of the workspace (${JSON.stringify(body.path.slice(0, 200))} does not)`);
    else throw new HttpError(400, 'give the scenario text (scenario) or a workspace .scenario file (path)');
    const sim = await loadSimulator();
    // a file's bytes are UTF-8 text, or refused saying where (a Latin-1 value was read as U+FFFD), as contract simulate does
    if (bytes) {
      const decoded = sim.decodeScenarioText(bytes);
      if (typeof decoded !== 'string') throw new HttpError(422, `${display}: ${decoded.error}`);
      text = decoded;
    }
    if (text === undefined) throw new HttpError(400, 'give the scenario text (scenario) or a workspace .scenario file (path)');
    if (text.length > MAX_SCENARIO_CHARS) throw new HttpError(413, `scenario longer than ${MAX_SCENARIO_CHARS} characters`);
    // a client sending faster than the simulations run is told so instead of queueing without end
    if (this.waiting >= MAX_WAITING) throw new HttpError(429, `${MAX_WAITING} simulations already waiting: try again when they are done`);
    this.waiting++;
    const run = this.queue.then(() => this.simulate(sim, projectDir, display, text)).finally(() => this.waiting--);
    this.queue = run.catch(() => undefined);
    sendJson(res, 200, await run);
    return true;
  }

  private async simulate(sim: SimulatorApi, projectDir: string, display: string, text: string): Promise<SimulateResponse> {
    const t0 = performance.now();
    // the project as opened, not as named: a folder swapped for a link meanwhile is not followed (project-folder.ts)
    const prepared = await inProjectFolder(this.paths, projectDir,
      async (dir) => {
        const p = await sim.prepareProject(dir, {
          runtimeDir: process.env.CONTRACT_RUNTIME || sim.DEFAULT_RUNTIME_DIR, cacheDir: this.cacheFor(sim), maxModelBytes: IDE_MAX_MODEL_BYTES,
        }).catch((e: unknown) => {
          throw modelTooLarge(e) ?? e;
        });
        const named = (text: string) => text.split(dir).join(projectDir);
        if ('build' in p) p.warnings = p.warnings.map(named);
        else if (p.buildError) p.buildError = named(p.buildError);
        return p;
      }, { unanchor: false });
    if (!('build' in prepared)) {
      if (prepared.modelErrors.length) {
        const diagnostics: SimulateDiagnostic[] = prepared.modelErrors.slice(0, 200).map((d) => ({
          file: this.paths.toRelative(join(projectDir, d.file)), line: d.line, column: d.column, severity: 'error', message: d.message, code: d.code,
        }));
        throw new HttpError(422, `the model has ${prepared.modelErrors.length} error(s): fix them first`, { diagnostics });
      }
      if (prepared.sandboxError) throw new HttpError(503, prepared.sandboxError);
      if (prepared.compile?.diagnostics.length) {
        // the project's own C (a region of a src-gen common header): the user's to fix, at the user's
        // file, line and region, as the build log tells it; only the first errors
        const diagnostics: SimulateDiagnostic[] = prepared.compile.diagnostics.slice(0, 200).map((d) => ({
          ...(d.file !== null ? { file: this.paths.toRelative(join(projectDir, SRC_GEN_DIR, d.file)) } : {}),
          line: d.line ?? 1, column: d.column ?? 1, severity: d.severity === 'note' ? 'info' : d.severity,
          message: `${d.message}${d.protectedRegion ? ` (in protected region ${d.protectedRegion.id})` : ''}`,
        }));
        throw new HttpError(422, `the project's C does not ${prepared.compile.stage === 'link' ? 'link' : 'compile'} for the simulator: ${sim.errorCount(prepared.compile)} error(s) in ${SRC_GEN_DIR}/ (your code in its protected regions)`, { diagnostics });
      }
      throw new HttpError(500, prepared.buildError ?? 'the simulator could not be built');
    }
    const loaded = sim.loadScenario(join(projectDir, display), display, text, prepared.index);
    const errors = loaded.diagnostics.filter((d) => d.severity === 'error');
    if (errors.length) {
      const diagnostics: SimulateDiagnostic[] = loaded.diagnostics.slice(0, 200).map((d) => ({
        line: d.line, column: d.column, endColumn: d.endColumn, severity: d.severity, message: d.message, code: d.code,
      }));
      throw new HttpError(422, `the scenario has ${errors.length} error(s): nothing was simulated`, { diagnostics });
    }
    const r = await sim.runLoadedScenario(prepared, loaded, { timeoutMs: RUN_TIMEOUT_MS });
    const budget = { left: MAX_ITEMS_PER_ANSWER };
    const steps: SimulateStep[] = r.steps.slice(0, MAX_STEPS).map((s) => stepOf(s, budget));
    return {
      title: r.title, passed: r.passed, endNs: r.endNs, steps,
      failures: r.failures.slice(0, 200).map((f) => ({ line: f.line, message: f.message ?? '' })),
      error: r.error, ...(r.trimmed ? { trimmed: trimmedOf(r.trimmed) } : {}), warnings: prepared.warnings.slice(0, 50), eventsProcessed: r.eventsProcessed,
      ms: Math.round(performance.now() - t0), runMs: Math.round(r.ms),
    };
  }
}

type StepResult = Awaited<ReturnType<SimulatorApi['runLoadedScenario']>>['steps'][number];
type Trimmed = NonNullable<Awaited<ReturnType<SimulatorApi['runLoadedScenario']>>['trimmed']>;

/** A step as the panel names it. */
function stepWords(line: number, timeNs: number): string {
  return line ? `line ${line} (${(timeNs / 1e9).toFixed(6)}s)` : `the end (${(timeNs / 1e9).toFixed(6)}s)`;
}

/** What the simulator did not keep of the steps' records, in the panel's words (SimulateResponse.trimmed). */
function trimmedOf(t: Trimmed): NonNullable<SimulateResponse['trimmed']> {
  const message = `not whole: the steps' records passed the simulator's bound on a scenario's records; from ${stepWords(t.line, t.timeNs)} on, the steps were kept without their actions, typed records, schemas and locals (the schemas and locals shown, and the Monitor, stop before that step)`
    + (t.bareLine !== undefined ? `; from ${stepWords(t.bareLine, t.bareTimeNs ?? 0)} on, without their rule changes and output either (the rules shown stop before that step)` : '')
    + '; the verdicts and failures are the whole scenario\'s';
  return { line: t.line, timeNs: t.timeNs, ...(t.bareLine !== undefined ? { bareLine: t.bareLine, bareTimeNs: t.bareTimeNs ?? 0 } : {}), message };
}

/**
 * A step as answered: its lists kept while the answer's budget lasts (the small ones first), the
 * rest counted. Also what scripts/record-mission-steps.mjs records the Monitor's simulation fixture with.
 */
export function stepOf(s: StepResult, budget: { left: number }): SimulateStep {
  const rec = s.record;
  let dropped = rec.dropped ?? 0;
  const cut = <T>(xs: T[] | undefined): T[] => {
    const all = xs ?? [];
    const kept = all.length <= budget.left ? all : all.slice(0, Math.max(0, budget.left));
    budget.left -= kept.length;
    dropped += all.length - kept.length;
    return kept;
  };
  const rules = cut(rec.rules), actions = cut(rec.actions), schemas = cut(rec.schemas), locals = cut(rec.locals);
  const records = cut(rec.records), log = cut(rec.log);
  return {
    line: s.line, source: s.source.slice(0, 1000), timeNs: s.timeNs, kind: s.kind, ok: s.ok, message: s.message, ...(s.trimmed ? { trimmed: s.trimmed } : {}),
    rules, actions, log, records, schemas, locals,
    output: rec.output?.slice(0, MAX_OUTPUT), error: rec.error, ...(dropped ? { dropped } : {}),
  };
}

/** A workspace scenario file's bytes; a missing one, or a folder, said with its path. */
async function readBytes(fs: WorkspaceFs, rel: string): Promise<Buffer> {
  return fs.withParent(rel, false, async (dir, name) => {
    const { handle, stats } = await WorkspaceFs.openFile(dir, name, rel);
    try {
      if (stats.isDirectory()) throw new HttpError(400, `${rel} is a folder, not a scenario file`);
      if (stats.size > MAX_SCENARIO_CHARS * 4) throw new HttpError(413, `${rel} is too large for a scenario`);
      return await handle.readFile();
    } finally {
      await handle.close();
    }
  }).catch((e: unknown) => {
    if ((e instanceof HttpError && e.status === 404) || (e as NodeJS.ErrnoException)?.code === 'ENOENT') throw new HttpError(404, `no such scenario file in the workspace: ${rel}`);
    throw e;
  });
}

