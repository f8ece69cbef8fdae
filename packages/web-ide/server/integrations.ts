/**
 * Lazy, typed access to the sibling packages (language, codegen, build service). They are loaded
 * on first use so the file API and the editor keep working when one of them is not built; the
 * user then gets a clear error naming the missing package instead of a crash.
 */
import type { GenerateReport } from './api-types.js';
import type { RegionParser } from './region-guard.js';
import { HttpError } from './http-error.js';

export interface BuildServerLike {
  handle(req: import('node:http').IncomingMessage, res: import('node:http').ServerResponse): boolean | Promise<boolean>;
  handleUpgrade?(req: import('node:http').IncomingMessage, socket: import('node:stream').Duplex, head: Buffer): boolean;
  close(): Promise<void>;
}

async function importPackage<T>(name: string): Promise<T> {
  try {
    return (await import(name)) as T;
  } catch (e) {
    throw new HttpError(503, `${name} is not available (${(e as Error).message.split('\n')[0]}); run \`npm run build\` at the repository root`);
  }
}

export async function loadWorkspaceDocuments(dir: string): Promise<{ documents: unknown[]; diagnostics?: unknown }> {
  const lang = await importPackage<{ loadWorkspace(dir: string): Promise<{ documents: unknown[]; diagnostics?: unknown }> }>(
    '@contract-studio/language/node',
  );
  return lang.loadWorkspace(dir);
}

export async function runCodegen(documents: unknown[], outDir: string, options: Record<string, unknown>): Promise<GenerateReport> {
  const codegen = await importPackage<{
    generateArchitecture(documents: unknown[], outDir: string, options: Record<string, unknown>): Promise<GenerateReport> | GenerateReport;
  }>('@contract-studio/codegen');
  return codegen.generateArchitecture(documents, outDir, options);
}

/**
 * codegen's carry-over of a renamed entity in a generated tree (paths and region IDs), the one
 * `contract rename` uses too (docs/codegen.md, "Renames").
 */
export async function renameGeneratedEntity(srcGen: string, from: string, to: string): Promise<RenameEntityReport> {
  const codegen = await importPackage<{
    renameInGeneratedTree(srcGen: string, from: string, to: string): Promise<RenameEntityReport>;
  }>('@contract-studio/codegen');
  return codegen.renameInGeneratedTree(srcGen, from, to);
}

export interface RenameEntityReport {
  movedPaths: Array<{ from: string; to: string }>;
  rewrittenFiles: string[];
  regionIds: Array<{ file: string; from: string; to: string }>;
}

/** codegen's protected-region parser (parseRegions + RegionSyntaxError), for the guard of generated files. */
export async function loadRegionParser(): Promise<RegionParser> {
  const codegen = await importPackage<Partial<RegionParser>>('@contract-studio/codegen');
  if (typeof codegen.parseRegions !== 'function' || typeof codegen.RegionSyntaxError !== 'function') {
    throw new HttpError(503, '@contract-studio/codegen does not export parseRegions/RegionSyntaxError; run `npm run build` at the repository root');
  }
  return { parseRegions: codegen.parseRegions, RegionSyntaxError: codegen.RegionSyntaxError };
}

/**
 * codegen's checks of an output tree (safe-paths.ts, output-tree.ts): the IDE reads the
 * generator's manifest and carries renames over in src-gen with the same rules as Generate All
 * (plain relative paths, no symlink anywhere; docs/codegen.md, "What generate refuses").
 */
export interface TreeChecks {
  checkTreeRoot(root: string): boolean;
  /** Holds opened folders until close(). */
  OutputTree: new (root: string) => { close(): void };
  loadManifest(tree: unknown): { manifest?: { files: Map<string, unknown> }; problems: string[] };
}

export async function loadTreeChecks(): Promise<TreeChecks> {
  const codegen = await importPackage<Partial<TreeChecks>>('@contract-studio/codegen');
  if (typeof codegen.checkTreeRoot !== 'function' || typeof codegen.OutputTree !== 'function' || typeof codegen.loadManifest !== 'function') {
    throw new HttpError(503, '@contract-studio/codegen does not export checkTreeRoot/OutputTree/loadManifest; run `npm run build` at the repository root');
  }
  return { checkTreeRoot: codegen.checkTreeRoot, OutputTree: codegen.OutputTree, loadManifest: codegen.loadManifest };
}

/**
 * The build service mounted by the IDE server. It uses the same persistent build cache as
 * `contract build` (docs/getting-started.md "The build cache": `$CONTRACT_CACHE_DIR`, else the XDG
 * cache folder), so Build & Run after a CLI build (or the reverse) compiles nothing new; when that
 * folder is refused, the reason is logged and the service keeps a private temporary cache.
 */
export async function createEmbeddedBuildServer(workspaceRoot: string, log: (line: string) => void = (l) => process.stderr.write(`${l}\n`)): Promise<BuildServerLike | string> {
  try {
    const name = '@contract-studio/build-service';
    const bs = (await import(name)) as {
      createBuildServer(options: Record<string, unknown>): BuildServerLike;
      resolveCacheDir(explicit: string | undefined): { dir: string };
      prepareCacheDir(dir: string, jobUidsMustTraverse: boolean): string | null;
    };
    const cache = bs.resolveCacheDir(undefined);
    const refused = bs.prepareCacheDir(cache.dir, process.getuid?.() === 0);
    if (refused) log(`build cache: ${refused}; using a private temporary cache instead`);
    const cacheOptions = refused ? {} : { cacheDir: cache.dir, persistentWorkspaces: true };
    return bs.createBuildServer({ host: '127.0.0.1', port: 0, projectRoots: [workspaceRoot], basePath: '/api', concurrency: 1, ...cacheOptions });
  } catch (e) {
    return `build service unavailable: ${(e as Error).message.split('\n')[0]}`;
  }
}

/** The simulator's programmatic API (`contract simulate` without the printing), loaded on first use. */
export type SimulatorApi = typeof import('@contract-studio/simulator');

export async function loadSimulator(): Promise<SimulatorApi> {
  const sim = await importPackage<Partial<SimulatorApi>>('@contract-studio/simulator');
  if (typeof sim.prepareProject !== 'function' || typeof sim.loadScenario !== 'function' || typeof sim.runLoadedScenario !== 'function') {
    throw new HttpError(503, '@contract-studio/simulator does not export prepareProject/loadScenario/runLoadedScenario; run `npm run build` at the repository root');
  }
  return sim as SimulatorApi;
}
