/**
 * `contract simulate DIR SCENARIO...` without the printing (docs/simulation.md §3): loads and
 * checks the project, reads and checks each scenario against it, generates the tables in memory,
 * builds (or reuses) the harness and runs every scenario. Used by the CLI, the tests and the
 * benchmark.
 */
import { readRegularFile } from './read-regular-file.js';
import { dirname, join, relative, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { loadWorkspace, type LoadedWorkspace, type WorkspaceDiagnostic } from '@contract-studio/language/node';
import { MAX_SCENARIO_BYTES, parseScenario, type ParsedScenario, type ScenarioDiagnostic } from './scenario/index.js';
import { checkScenario, indexModels, type ModelIndex, type ResolvedLocal } from './scenario/index.js';
import { simulationSources } from './harness/tables.js';
import { buildHarness, type HarnessBuild } from './harness/build.js';
import type { CompileFailure } from './harness/compile-diagnostics.js';
import { chooseConfinement, type Confinement, type SimulatorSandboxChoice } from './harness/confine.js';
import { runScenario, type RunOptions, type ScenarioResult } from './runner/run-scenario.js';
import { SRC_GEN_DIR } from '@contract-studio/conventions';

/** The repository's runtime/ (from dist/ or src/ of this package). */
export const DEFAULT_RUNTIME_DIR = resolve(dirname(fileURLToPath(import.meta.url)), '..', '..', '..', 'runtime');

export interface PreparedProject {
    workspace: LoadedWorkspace;
    index: ModelIndex;
    build: HarnessBuild;
    /** How the harness is run (the one its build used). */
    confinement: Confinement;
    warnings: string[];
}

export interface ProjectProblems {
    /** Errors of the model (as `contract check` prints them). */
    modelErrors: WorkspaceDiagnostic[];
    /** Harness generation/build problem. */
    buildError?: string;
    /**
     * When the project's C (the protected regions of its common headers) did not compile: gcc's
     * diagnostics at the user's src-gen files, lines and regions (`buildError` tells them too).
     */
    compile?: CompileFailure;
    /** The sandbox asked for cannot be had here (what to install, or `--sandbox none`). */
    sandboxError?: string;
}

export interface SimulateOptions extends RunOptions {
    runtimeDir: string;
    /** The build cache folder (`--cache-dir`; default `$CONTRACT_CACHE_DIR`, else XDG): simulators go in its `sim/`. */
    cacheDir?: string;
    /** Told when the harness build waits for another build holding its lock. */
    onWait?: (what: string) => void;
    /** Bound of the project's `.contract` files together (the language's ModelTooLargeError over it); none by default. */
    maxModelBytes?: number;
    /** Where the project's C runs (harness/confine.ts): default `$CONTRACT_SIMULATOR_SANDBOX`, else `auto` (bubblewrap). */
    sandbox?: SimulatorSandboxChoice;
}

/** Loads the project and builds its simulator; problems when the model has errors or the build fails. */
export async function prepareProject(dir: string, options: SimulateOptions): Promise<PreparedProject | ProjectProblems> {
    const workspace = await loadWorkspace(dir, { confineImportsTo: dir, maxModelBytes: options.maxModelBytes });
    const modelErrors = workspace.diagnostics.filter((d) => d.severity === 'error');
    if (modelErrors.length) return { modelErrors };
    // a folder with no model: said once, not as "no supervisor ..." on every line of the scenario
    if (workspace.documents.length === 0) {
        return { modelErrors: [{ file: '.', line: 1, column: 1, endLine: 1, endColumn: 1, severity: 'error', code: 'no-model', message: 'no .contract file in this folder (or below it): DIR is the folder of the project\'s .contract files' }] };
    }
    const docs = [...workspace.documents].sort((a, b) => {
        const ua = a.document.uri.toString();
        const ub = b.document.uri.toString();
        return ua < ub ? -1 : ua > ub ? 1 : 0;
    });
    let sources;
    try {
        sources = simulationSources(docs.map((d) => d.model), join(dir, SRC_GEN_DIR));
    } catch (e) {
        return { modelErrors: [], buildError: `cannot generate the engines' tables: ${e instanceof Error ? e.message : String(e)}` };
    }
    const confinement = await chooseConfinement(options.sandbox);
    if ('error' in confinement) return { modelErrors: [], sandboxError: confinement.error };
    const build = await buildHarness(sources, { runtimeDir: options.runtimeDir, cacheDir: options.cacheDir, onWait: options.onWait, confinement });
    if ('error' in build) return { modelErrors: [], buildError: build.error, ...(build.compile ? { compile: build.compile } : {}) };
    return { workspace, index: indexModels(docs.map((d) => d.model)), build, confinement, warnings: sources.warnings };
}

export interface LoadedScenario {
    file: string;
    /** Path as given (for messages). */
    display: string;
    parsed: ParsedScenario;
    locals: Map<number, ResolvedLocal>;
    diagnostics: ScenarioDiagnostic[];
}

/**
 * Reads a scenario file: a regular file (no link followed), at most MAX_SCENARIO_BYTES, of UTF-8
 * text (a byte order mark is dropped by the parser). Anything else is refused, saying where: a
 * byte that is no UTF-8 was read as U+FFFD, and an event's value then changed without a word.
 */
export function readScenarioFile(path: string): string | { error: string } {
    const data = readRegularFile(path, MAX_SCENARIO_BYTES);
    if (!Buffer.isBuffer(data)) return data;
    return decodeScenarioText(data);
}

/** A scenario file's bytes as text, or why they are not UTF-8 text (UTF-16, a byte of another encoding, with its line). */
export function decodeScenarioText(data: Buffer): string | { error: string } {
    if ((data[0] === 0xff && data[1] === 0xfe) || (data[0] === 0xfe && data[1] === 0xff)) return { error: 'UTF-16 text (its byte order mark says so): save it as UTF-8' };
    try {
        return new TextDecoder('utf-8', { fatal: true, ignoreBOM: true }).decode(data);
    } catch {
        // where: the first byte the lenient decoder replaces
        const text = data.toString('utf8');
        const at = text.indexOf('\ufffd');
        const line = at < 0 ? 1 : text.slice(0, at).split('\n').length;
        const byteAt = Buffer.byteLength(text.slice(0, Math.max(0, at)));
        return { error: `not UTF-8 text: byte 0x${(data[byteAt] ?? 0).toString(16).padStart(2, '0')} on line ${line} is no UTF-8 (Latin-1? save it as UTF-8)` };
    }
}

/** Parses and checks a scenario text against the project's model. */
export function loadScenario(file: string, display: string, text: string, index: ModelIndex): LoadedScenario {
    const parsed = parseScenario(text);
    // the steps that parsed are checked too: every problem of the file at once, as the language server shows them
    const check = checkScenario(parsed.steps, index);
    const diagnostics = [...parsed.diagnostics, ...check.diagnostics].sort((a, b) => a.line - b.line || a.column - b.column);
    return { file, display, parsed, locals: check.locals, diagnostics };
}

/** Runs a loaded scenario; what the run keeps of it is its own (run-scenario.ts): let `s` go meanwhile, and its steps go with it. */
export function runLoadedScenario(project: PreparedProject, s: LoadedScenario, options: RunOptions = {}): Promise<ScenarioResult> {
    return runScenario(project.build.exe, s.display, s.parsed, s.locals, { ...options, confinement: project.confinement });
}

/** Display path of a file for messages: relative to cwd when inside it. */
export function displayPath(cwd: string, file: string): string {
    const rel = relative(cwd, file);
    return rel && !rel.startsWith('..') ? rel : file;
}
