/**
 * What every build-service benchmark shares: its progress line on stderr, rounding, percentiles,
 * the part it writes (bench/parts/<name>.json, merged into bench/results.json by
 * bench/run-all.mjs), its exit on failure, and (the trace benches) a build server over a temp root
 * with the "New project" template.
 */
import { chmodSync, mkdirSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { PROJECT_TEMPLATES } from '@contract-studio/language';
import { createBuildServer, type BuildServer, type BuildServerOptions } from '../server.js';
import { REPO, snapshotRuntime } from '../test-support/tutorial.js';

/** A progress line, `[bench <tag>] ...`, on stderr (stdout stays free for the part). */
export function benchLog(tag: string): (line: string) => void {
  return (line) => void process.stderr.write(`[bench ${tag}] ${line}\n`);
}

export function round(x: number, digits = 3): number {
  return Math.round(x * 10 ** digits) / 10 ** digits;
}

/** The p-th percentile (nearest rank from below) of xs; NaN when empty. */
export function pct(xs: number[], p: number): number {
  const s = [...xs].sort((a, b) => a - b);
  return s.length ? s[Math.min(s.length - 1, Math.floor((p / 100) * s.length))]! : NaN;
}

export function median(xs: number[]): number {
  const s = [...xs].sort((a, b) => a - b);
  return s.length % 2 ? s[(s.length - 1) / 2]! : (s[s.length / 2 - 1]! + s[s.length / 2]!) / 2;
}

/**
 * Least squares of log(ratio) on x (the pairs' steal difference): the ratio at x = 0 and the
 * correlation (0 when the ratios do not vary); null when x does not vary (nothing stolen) or a
 * ratio is not finite and positive.
 */
export function ratioAtZero(ratios: number[], x: number[]): { ratio: number; r: number } | null {
  const y = ratios.map(Math.log);
  const n = y.length;
  const mx = x.reduce((a, b) => a + b, 0) / n;
  const my = y.reduce((a, b) => a + b, 0) / n;
  let sxx = 0;
  let sxy = 0;
  let syy = 0;
  for (let i = 0; i < n; i++) {
    sxx += (x[i]! - mx) ** 2;
    sxy += (x[i]! - mx) * (y[i]! - my);
    syy += (y[i]! - my) ** 2;
  }
  if (!(sxx > 0) || !y.every(Number.isFinite)) return null;
  const slope = sxy / sxx;
  return { ratio: Math.exp(my - slope * mx), r: syy > 0 ? sxy / Math.sqrt(sxx * syy) : 0 };
}

/** Writes bench/parts/<name>.json. */
export function writePart(name: string, out: Record<string, unknown>): void {
  mkdirSync(join(REPO, 'bench', 'parts'), { recursive: true });
  writeFileSync(join(REPO, 'bench', 'parts', `${name}.json`), JSON.stringify(out, null, 2) + '\n');
}

/** Runs a benchmark's main; a failure is one FAILED line and exit status 1. */
export function runBench(say: (line: string) => void, main: () => Promise<void>): void {
  main().catch((e) => {
    say(`FAILED: ${(e as Error).stack ?? e}`);
    process.exit(1);
  });
}

/** The "New project" template (docs/getting-started.md) written to `dir`, each file through `edit`. */
export function writeTemplateProject(dir: string, edit: (text: string) => string = (t) => t): void {
  mkdirSync(dir, { recursive: true });
  for (const [name, text] of Object.entries(PROJECT_TEMPLATES)) writeFileSync(join(dir, name), edit(text));
}

export interface BenchServer {
  url: string;
  server: BuildServer;
  /** The folder the server may build projects from (<root>/projects). */
  projects: string;
  /** Closes the server, removes the root and the runtime snapshot. */
  close(): Promise<void>;
}

/**
 * A build server (no token, one job at a time) over a fresh temp root (mode 755: the jobs' uids
 * walk through it to their work dirs) holding its cache and projects folder, on a snapshot of the
 * runtime.
 */
export async function startBenchServer(prefix: string, options: Pick<BuildServerOptions, 'log'> = {}): Promise<BenchServer> {
  const root = mkdtempSync(join(tmpdir(), prefix));
  chmodSync(root, 0o755);
  const projects = join(root, 'projects');
  mkdirSync(projects);
  const runtimeSource = snapshotRuntime();
  const server = createBuildServer({ token: false, port: 0, concurrency: 1, cacheDir: join(root, 'cache'), runtimeSource, projectRoots: [projects], ...options });
  const { url } = await server.listen();
  return {
    url, server, projects,
    async close() {
      await server.close();
      rmSync(root, { recursive: true, force: true });
      rmSync(runtimeSource, { recursive: true, force: true });
    },
  };
}
