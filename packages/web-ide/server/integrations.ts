/**
 * Lazy, typed access to the sibling packages (language, codegen, build service, simulator). They
 * are loaded on first use so the file API and the editor keep working when one of them is not
 * built; the user then gets a clear error naming the missing package instead of a crash. The
 * types are the packages' own (type-only imports: nothing is loaded until a function runs).
 */
import type { LoadedWorkspace, ScenarioRename, WorkspaceDocument } from '@contract-studio/language/node';
import type { GenerationReport } from '@contract-studio/codegen';
import type { RegionParser } from './region-guard.js';
import { HttpError } from './http-error.js';

type LanguageNodeApi = typeof import('@contract-studio/language/node');
export type CodegenApi = typeof import('@contract-studio/codegen');
type FinishedRenameDescription = import('@contract-studio/codegen').FinishedRenameDescription;
type BuildServiceApi = typeof import('@contract-studio/build-service');

export type BuildServerLike = ReturnType<BuildServiceApi['createBuildServer']>;

async function importPackage<T>(name: string): Promise<T> {
  try {
    return (await import(name)) as T;
  } catch (e) {
    throw new HttpError(503, `${name} is not available (${(e as Error).message.split('\n')[0]}); run \`npm run build\` at the repository root`);
  }
}

/** The package, checked to export `names` as functions (a stale build of it may lack newer ones). */
export async function importWith<T, K extends keyof T>(name: string, names: readonly K[]): Promise<Pick<T, K>> {
  const mod = await importPackage<Partial<T>>(name);
  const missing = names.filter((n) => typeof mod[n] !== 'function');
  if (missing.length) throw new HttpError(503, `${name} does not export ${missing.join('/')}; run \`npm run build\` at the repository root`);
  return mod as Pick<T, K>;
}

/**
 * Bytes of `.contract` files the server loads for one Generate All or simulation: the build
 * service's model size limit (1 MiB). Parsing is superlinear in a rule's expression (a 578 KB
 * condition of 32,000 `or`: 8 s), and the server answers every tab on one thread.
 */
export const IDE_MAX_MODEL_BYTES = 1024 * 1024;

/** The project's model, refused with 413 when its files are over IDE_MAX_MODEL_BYTES together. */
export async function loadWorkspaceDocuments(dir: string): Promise<LoadedWorkspace> {
  const lang = await importWith<LanguageNodeApi, 'loadWorkspace'>('@contract-studio/language/node', ['loadWorkspace']);
  try {
    return await lang.loadWorkspace(dir, { maxModelBytes: IDE_MAX_MODEL_BYTES });
  } catch (e) {
    throw modelTooLarge(e) ?? e;
  }
}

/** The 413 of a model over the limit (the language's ModelTooLargeError), else undefined. */
export function modelTooLarge(e: unknown): HttpError | undefined {
  return e instanceof Error && e.name === 'ModelTooLargeError' ? new HttpError(413, e.message) : undefined;
}

export async function runCodegen(documents: WorkspaceDocument[], outDir: string): Promise<GenerationReport> {
  const codegen = await importWith<CodegenApi, 'generateArchitecture'>('@contract-studio/codegen', ['generateArchitecture']);
  return codegen.generateArchitecture(documents, outDir);
}

/**
 * The C identifiers a rename changes in the user code (the ones `contract rename` changes): a port's
 * or parameter's (only in its module's files: `owner`), a datatype's or an enumeration's (and its
 * generated functions; an enumeration's `members` name its constants), an enumeration member's
 * constant (`owner`: its enumeration), a function's.
 */
export async function userCodeRenames(kind: string, from: string, to: string, owner?: string, members?: string[]): Promise<UserCodeRenames> {
  const codegen = await importWith<CodegenApi, 'identifierRenames'>('@contract-studio/codegen', ['identifierRenames']);
  const renames = codegen.identifierRenames(kind, from, to, kind === 'enumeration member' ? { enumeration: owner } : { members });
  return { renames, ...(kind === 'port' || kind === 'parameter' ? { owner } : {}) };
}

export interface UserCodeRenames {
  renames: ReadonlyMap<string, string>;
  /** The module whose module.c alone holds them (a port or parameter), else absent: every file. */
  owner?: string;
}

type RenameJournal = import('@contract-studio/codegen').RenameJournal;
type JournaledRenameOptions<W> = import('@contract-studio/codegen').JournaledRenameOptions<W>;

/**
 * codegen's rename sequence (journaled-rename.ts, the one `contract rename` runs): `journal` written
 * in `srcGen` when `options.journaled`, the generated tree carried over (paths and region IDs, then
 * the identifiers of the user code), `options.writeFiles`, the journal removed. Killed after the
 * journal, the next Generate All (or `contract generate`) finishes the rename. A refused identifier
 * carry-over is said as the IDE says it (its file relative to src-gen).
 */
export async function journaledRename<W>(srcGen: string, journal: RenameJournal, options: JournaledRenameOptions<W>) {
  const codegen = await importWith<CodegenApi, 'runJournaledRename' | 'carryRefusedMessage'>('@contract-studio/codegen', ['runJournaledRename', 'carryRefusedMessage']);
  const { carried } = await codegen.runJournaledRename(srcGen, journal, options);
  const moved = carried.moved ?? { movedPaths: [], regionIds: [] };
  const { refused, ...code } = carried.code ?? { rewritten: [], remaining: [] };
  return { moved, code: { ...code, ...(refused ? { refused: codegen.carryRefusedMessage(refused, journal.identifiers.map(([from]) => from)) } : {}) } };
}

/**
 * The language package's carry-over of a rename into the project's `.scenario` files (the one
 * `contract rename` uses): the new texts of the files that name the entity, token by token; not written.
 */
export async function renameInScenarioFiles(dir: string, skip: string[], rename: ScenarioRename) {
  const lang = await importWith<LanguageNodeApi, 'projectScenarios' | 'renameInScenarios'>('@contract-studio/language/node', ['projectScenarios', 'renameInScenarios']);
  return lang.renameInScenarios(dir, lang.projectScenarios(dir, skip), rename);
}

/** codegen's protected-region parser (parseRegions + RegionSyntaxError), for the guard of generated files. */
export async function loadRegionParser(): Promise<RegionParser> {
  const codegen = await importWith<CodegenApi, 'parseRegions' | 'RegionSyntaxError'>('@contract-studio/codegen', ['parseRegions', 'RegionSyntaxError']);
  return { parseRegions: codegen.parseRegions, RegionSyntaxError: codegen.RegionSyntaxError };
}

/** codegen's write lock of a generated tree (tree-lock.ts): the IDE's saves of generated files take the one `contract generate` takes. */
/**
 * codegen's finishing of a rename killed half-way (rename-journal.ts: `contract rename` journals
 * its work in src-gen), run by Generate All and the rename, lock held, before the model is read:
 * what it did (codegen's describeFinishedRename), or why the journal was left; nothing when there
 * was no journal.
 */
export async function finishInterruptedRename(projectDir: string, srcGen: string, shown: (path: string) => string): Promise<JournalOutcome> {
  const codegen = await importWith<CodegenApi, 'finishInterruptedRename' | 'describeFinishedRename'>('@contract-studio/codegen', ['finishInterruptedRename', 'describeFinishedRename']);
  try {
    const done = await codegen.finishInterruptedRename(projectDir, srcGen);
    return done ? { finished: codegen.describeFinishedRename(done, shown) } : {};
  } catch (e) {
    return { refused: (e as Error).message };
  }
}

/** What became of a rename journal found in src-gen: the rename finished, or the journal refused (why); neither when there was none. */
export interface JournalOutcome {
  finished?: FinishedRenameDescription;
  refused?: string;
}

export async function loadTreeLock(): Promise<CodegenApi['lockTree']> {
  const codegen = await importWith<CodegenApi, 'lockTree'>('@contract-studio/codegen', ['lockTree']);
  return codegen.lockTree;
}

/**
 * codegen's checks of an output tree (safe-paths.ts, output-tree.ts): the IDE reads the
 * generator's manifest and carries renames over in src-gen with the same rules as Generate All
 * (plain relative paths, no symlink anywhere; docs/codegen.md, "What generate refuses").
 */
export type TreeChecks = Pick<CodegenApi, 'checkTreeRoot' | 'OutputTree' | 'loadManifest'>;

export async function loadTreeChecks(): Promise<TreeChecks> {
  return importWith<CodegenApi, keyof TreeChecks>('@contract-studio/codegen', ['checkTreeRoot', 'OutputTree', 'loadManifest']);
}

/**
 * Limits the build service refuses (`contract serve --limit`: an unknown name, a value out of its
 * range): the IDE server does not start, rather than start without its build service. The service's
 * own check is the only one (its message is this error's).
 */
export class BuildLimitsRefused extends Error {
  override readonly name = 'BuildLimitsRefused';
}

/**
 * The build service mounted by the IDE server. It uses the same persistent build cache as
 * `contract build` (docs/getting-started.md "The build cache": `$CONTRACT_CACHE_DIR`, else the XDG
 * cache folder), so Build & Run after a CLI build (or the reverse) compiles nothing new; when that
 * folder is refused, the reason is logged and the service keeps a private temporary cache.
 */
export async function createEmbeddedBuildServer(workspaceRoot: string, log: (line: string) => void = (l) => process.stderr.write(`${l}\n`), sandbox: 'auto' | 'bwrap' | 'docker' = 'auto', limits: Record<string, number> = {}, limitTexts: Record<string, string> = {}): Promise<BuildServerLike | string> {
  let bs: BuildServiceApi;
  try {
    const name = '@contract-studio/build-service';
    bs = (await import(name)) as BuildServiceApi;
  } catch (e) {
    return `build service unavailable: ${(e as Error).message.split('\n')[0]}`;
  }
  try {
    const cache = bs.resolveCacheDir(undefined);
    const refused = bs.prepareCacheDir(cache.dir, process.getuid?.() === 0);
    if (refused) log(`build cache: ${refused}; using a private temporary cache instead`);
    const cacheOptions = refused ? {} : { cacheDir: cache.dir, persistentWorkspaces: true };
    // `contract serve --sandbox bwrap|docker`: every job of the IDE in that one, a request naming another refused
    const only = sandbox === 'auto' ? {} : { onlySandbox: sandbox };
    return bs.createBuildServer({ host: '127.0.0.1', port: 0, projectRoots: [workspaceRoot], basePath: '/api', concurrency: 1, sandbox, ...only, ...cacheOptions, ...(Object.keys(limits).length ? { limits, limitTexts } : {}) });
  } catch (e) {
    // the limits asked (contract serve --limit): the service's own check, the only one
    if (e instanceof bs.LimitsError) throw new BuildLimitsRefused(e.message);
    return `build service unavailable: ${(e as Error).message.split('\n')[0]}`;
  }
}

/** The simulator's programmatic API (`contract simulate` without the printing), loaded on first use. */
export type SimulatorApi = typeof import('@contract-studio/simulator');

export async function loadSimulator(): Promise<SimulatorApi> {
  const sim = await importWith<SimulatorApi, 'prepareProject' | 'loadScenario' | 'runLoadedScenario' | 'decodeScenarioText'>('@contract-studio/simulator', ['prepareProject', 'loadScenario', 'runLoadedScenario', 'decodeScenarioText']);
  return sim as SimulatorApi;
}
