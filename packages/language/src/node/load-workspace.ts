/**
 * loadWorkspace(dir): parses, links and validates every `.contract` file under `dir` (Node file
 * system) and returns the documents with their diagnostics in a tool-friendly form (1-based lines
 * and columns, paths relative to `dir`). Used by `contract check`, code generation and the build service.
 */
import { lstatSync, readFileSync, statSync } from 'node:fs';
import { readdir, stat } from 'node:fs/promises';
import { dirname, isAbsolute, join, relative, resolve, sep } from 'node:path';
import { GrammarUtils, URI, type LangiumDocument } from 'langium';
import { NodeFileSystem } from 'langium/node';
import type { Diagnostic } from 'vscode-languageserver-types';
import { createCactalServices, type CactalServices } from '../cactal-module.js';
import type { Import, Model } from '../generated/ast.js';
import { DEFAULT_MAX_IMPORT_BYTES, lexicalRefusal, resolveConfinedImport } from './confined-import.js';
import { SRC_GEN_DIR, projectRootsOf } from '@contract-studio/conventions';

export type SeverityName = 'error' | 'warning' | 'info' | 'hint';

export interface WorkspaceDiagnostic {
    /** Path relative to the workspace directory, with `/` separators. */
    file: string;
    /** 1-based. */
    line: number;
    /** 1-based. */
    column: number;
    endLine: number;
    endColumn: number;
    severity: SeverityName;
    code: string;
    message: string;
    /** Extra data of the diagnostic (for quick fixes), if any. */
    data?: unknown;
}

export interface WorkspaceDocument {
    /** Path relative to the workspace directory, with `/` separators (`../lib/x.contract` for a file imported from outside it). */
    file: string;
    /** Absolute path. */
    path: string;
    document: LangiumDocument<Model>;
    model: Model;
}

export interface LoadedWorkspace {
    /** Absolute path of the workspace directory. */
    dir: string;
    documents: WorkspaceDocument[];
    /** All diagnostics, sorted by file, line, column. */
    diagnostics: WorkspaceDiagnostic[];
    /** The services that built the workspace (to reuse for further queries). */
    services: CactalServices;
    /**
     * The projects of the workspace by the rule of docs/codegen.md "Where a project is" (conventions'
     * project-root.ts): their roots relative to the workspace directory ('' = the directory itself),
     * sorted, and the generated trees met on the way that are not used. Each document was checked
     * with the documents of its project only.
     */
    layout: { roots: string[]; unusedTrees: string[] };
}

/** `path` is a folder, not a link (a project's generated tree: a linked `src-gen` is refused by generate). */
export function isTreeFolder(path: string): boolean {
    return lstatSync(path, { throwIfNoEntry: false })?.isDirectory() ?? false;
}

export interface LoadWorkspaceOptions {
    /** Services to reuse (default: fresh Node services). */
    services?: CactalServices;
    /** Directory names not to descend into (default: node_modules, .git, src-gen). */
    skipDirs?: string[];
    /**
     * When set, imports are loaded only from inside this folder (no `..` escape, no absolute path,
     * no symbolic link on the way, regular files of at most `maxImportBytes`); any other import gets
     * an `import-refused` error naming it and why, and the file is never read (confined-import.ts).
     * The build service sets it to the staged project (docs/sandbox.md "Imports stay in the project");
     * unset (the CLI and the IDE), files imported from outside DIR are loaded too.
     */
    confineImportsTo?: string;
    /** Bound of one imported file under `confineImportsTo` (default 8 MiB). */
    maxImportBytes?: number;
    /**
     * Bound of the `.contract` files found in DIR, all together: over it, ModelTooLargeError before
     * any is parsed (a server loading models for clients: the IDE's Generate All and Simulate).
     */
    maxModelBytes?: number;
}

/** The project's `.contract` files are more than `maxModelBytes` together (nothing was parsed). */
export class ModelTooLargeError extends Error {
    constructor(readonly bytes: number, readonly limit: number) {
        super(`the project's .contract files hold ${bytes} bytes, over the limit of ${limit} bytes (a model that large is not loaded: split it, or check for generated text pasted in)`);
        this.name = 'ModelTooLargeError';
    }
}

/**
 * Code of the loader's warning for an import of the project that is a symbolic link: followed here
 * (`contract check`), but the build service never reads a project's source through a link and
 * refuses the build (docs/sandbox.md).
 */
export const IMPORT_LINK_CODE = 'import-link';

/** Code of the loader's diagnostic for an import that `confineImportsTo` does not allow. */
export const IMPORT_REFUSED_CODE = 'import-refused';

/**
 * Code of the loader's error for a `.contract` file larger than a build reads: the bound of one
 * imported file (DEFAULT_MAX_IMPORT_BYTES, 8 MiB, as the build service's projectFileBytes).
 */
export const SOURCE_TOO_LARGE_CODE = 'source-too-large';
/** Code of the loader's warning for a `.contract` entry that is a link or no regular file, which a build refuses. */
export const SOURCE_NOT_FILE_CODE = 'source-not-file';

const SEVERITIES: Record<number, SeverityName> = { 1: 'error', 2: 'warning', 3: 'info', 4: 'hint' };
const DEFAULT_SKIP = ['node_modules', '.git', SRC_GEN_DIR];

/** Every `.contract` file under `dir`, sorted, as absolute paths. */
export async function findContractFiles(dir: string, skipDirs: string[] = DEFAULT_SKIP, notFiles?: Array<{ path: string; what: string; folder?: true }>): Promise<string[]> {
    const found: string[] = [];
    async function walk(d: string): Promise<void> {
        let entries;
        try {
            entries = await readdir(d, { withFileTypes: true });
        } catch (e) {
            // the project's own folder unreadable is the command's error; a sub-folder that cannot be
            // listed (its path too long for the system, no permission) is said, and the others read
            if (d === dir) throw e;
            const code = (e as NodeJS.ErrnoException).code;
            notFiles?.push({ path: d, folder: true, what: `a folder that could not be listed (${code === 'ENAMETOOLONG' ? 'its path is longer than the system allows' : code ?? (e as Error).message}): any .contract file in it is not read` });
            return;
        }
        for (const e of entries) {
            const full = join(d, e.name);
            if (e.isDirectory()) {
                if (!skipDirs.includes(e.name)) await walk(full);
            } else if (e.isFile() && e.name.endsWith('.contract')) {
                found.push(full);
            } else if (e.name.endsWith('.contract')) {
                // not read as a file of the project (a build refuses the project for it): said by loadWorkspace
                notFiles?.push({ path: full, what: e.isSymbolicLink() ? 'a symbolic link' : 'not a regular file (a FIFO, socket or device)' });
            }
        }
    }
    await walk(dir);
    return found.sort();
}

function isFile(path: string): boolean {
    try {
        return statSync(path).isFile();
    } catch {
        return false;
    }
}

/** Converts an LSP diagnostic of a file into the 1-based tool form. */
export function toWorkspaceDiagnostic(file: string, d: Diagnostic): WorkspaceDiagnostic {
    const code = d.code ?? (d.data as { code?: string } | undefined)?.code ?? 'unknown';
    const out: WorkspaceDiagnostic = {
        file,
        line: d.range.start.line + 1,
        column: d.range.start.character + 1,
        endLine: d.range.end.line + 1,
        endColumn: d.range.end.character + 1,
        severity: SEVERITIES[d.severity ?? 1] ?? 'error',
        code: String(code),
        message: d.message
    };
    if (d.data !== undefined) out.data = d.data;
    return out;
}

/** A file of the project (under `root`) that is a symbolic link, or reached through one (a linked folder). */
function isLinkInside(root: string, path: string): boolean {
    const rel = relative(root, path);
    if (rel.startsWith('..') || isAbsolute(rel)) return false;
    let at = root;
    for (const part of rel.split(sep)) {
        at = join(at, part);
        try {
            if (lstatSync(at).isSymbolicLink()) return true;
        } catch {
            return false;
        }
    }
    return false;
}

/** Where an import's path is written (the whole import when its path has no node), for a diagnostic on it. */
function importPathRange(imp: Import) {
    return ((imp.$cstNode && GrammarUtils.findNodeForProperty(imp.$cstNode, 'path')) ?? imp.$cstNode)?.range;
}

/** A warning on an import of the project that is a link: `contract check` reads it, a build refuses it. */
function reportLinkedImport(document: LangiumDocument<Model>, imp: Import): void {
    const range = importPathRange(imp);
    if (!range) return;
    (document.diagnostics ??= []).push({ range, severity: 2, code: IMPORT_LINK_CODE, source: 'cactal',
        message: `"${imp.path}" is a symbolic link, or in a linked folder: read here, but a build (contract build, the IDE's build service) and contract simulate never read a project's source through a link and refuse it; put the file itself there` });
}

/** Replaces the validator's "does not exist" on a refused import by the reason it was not loaded. */
function reportRefusedImport(document: LangiumDocument<Model>, imp: Import, reason: string): void {
    const range = importPathRange(imp);
    if (!range) return;
    const same = (d: Diagnostic) => d.range.start.line === range.start.line && d.range.start.character === range.start.character;
    const kept = (document.diagnostics ?? []).filter((d) => !(d.code === 'import-missing-file' && same(d)));
    kept.push({ range, severity: 1, code: IMPORT_REFUSED_CODE, source: 'cactal', message: `import "${imp.path}" is refused: ${reason} (imports must stay inside the project folder)` });
    document.diagnostics = kept;
}

export async function loadWorkspace(dir: string, options: LoadWorkspaceOptions = {}): Promise<LoadedWorkspace> {
    const root = resolve(dir);
    const info = await stat(root).catch(() => undefined);
    if (!info?.isDirectory()) throw new Error(`${dir} is not a directory`);
    const services = options.services ?? createCactalServices(NodeFileSystem).Cactal;
    const shared = services.shared;
    services.projects.Projects.configure({ openedFolders: [URI.file(root)], probe: (folder) => isTreeFolder(join(folder.fsPath, SRC_GEN_DIR)) });
    const notFiles: Array<{ path: string; what: string; folder?: true }> = [];
    const found = await findContractFiles(root, options.skipDirs, notFiles);
    // a file larger than a build reads is not read either (a 700 MB file ended check with V8's "Cannot create a string longer than ...")
    const tooLarge: Array<{ path: string; bytes: number }> = [];
    const files: string[] = [];
    let modelBytes = 0;
    for (const f of found) {
        const bytes = (await stat(f).catch(() => undefined))?.size ?? 0;
        if (bytes > DEFAULT_MAX_IMPORT_BYTES) tooLarge.push({ path: f, bytes });
        else {
            files.push(f);
            modelBytes += bytes;
        }
    }
    if (options.maxModelBytes !== undefined && modelBytes > options.maxModelBytes) throw new ModelTooLargeError(modelBytes, options.maxModelBytes);
    const documents: WorkspaceDocument[] = [];
    const loaded = new Set<string>();
    const langiumDocs = shared.workspace.LangiumDocuments;
    const confine = options.confineImportsTo === undefined ? undefined : resolve(options.confineImportsTo);
    const refused: { document: LangiumDocument<Model>; imp: Import; reason: string }[] = [];
    const links: { document: LangiumDocument<Model>; imp: Import }[] = [];
    const load = (path: string, text = readFileSync(path, 'utf8')) => {
        loaded.add(path);
        const uri = URI.file(path);
        if (langiumDocs.hasDocument(uri)) langiumDocs.deleteDocument(uri);
        const document = shared.workspace.LangiumDocumentFactory.fromString<Model>(text, uri);
        langiumDocs.addDocument(document);
        documents.push({ file: relative(root, path).split(sep).join('/'), path, document, model: document.parseResult.value });
    };
    for (const path of files) load(path);
    // files imported from outside DIR (shared libraries: import "../lib/types.contract") are part of the build too
    for (let i = 0; i < documents.length; i++) {
        const { path, model } = documents[i]!;
        for (const imp of model?.imports ?? []) {
            if (imp.path === undefined) continue;
            if (confine !== undefined && !imp.path.endsWith('.contract')) {
                // never loaded, but still named as refused rather than "does not exist" when it points out
                const reason = lexicalRefusal(confine, path, imp.path);
                if (reason) refused.push({ document: documents[i]!.document, imp, reason });
                continue;
            }
            if (!imp.path.endsWith('.contract')) continue;
            if (confine !== undefined) {
                if (!isAbsolute(imp.path) && loaded.has(resolve(dirname(path), imp.path))) continue;
                const found = resolveConfinedImport(confine, path, imp.path, options.maxImportBytes);
                if (found.kind === 'refused') refused.push({ document: documents[i]!.document, imp, reason: found.reason });
                else if (found.kind === 'ok' && !loaded.has(found.path)) load(found.path, found.text);
                continue;
            }
            const target = resolve(dirname(path), imp.path);
            if (!isFile(target)) continue;
            if (isLinkInside(root, target)) links.push({ document: documents[i]!.document, imp });
            if (loaded.has(target)) continue;
            load(target);
        }
    }
    await shared.workspace.DocumentBuilder.build(documents.map((d) => d.document), { validation: true });
    for (const r of refused) reportRefusedImport(r.document, r.imp, r.reason);
    for (const l of links) reportLinkedImport(l.document, l.imp);
    const diagnostics = documents.flatMap((d) => (d.document.diagnostics ?? []).map((diag) => toWorkspaceDiagnostic(d.file, diag)));
    const whole = (path: string, severity: SeverityName, code: string, message: string): WorkspaceDiagnostic =>
        ({ file: relative(root, path).split(sep).join('/'), line: 1, column: 1, endLine: 1, endColumn: 1, severity, code, message });
    for (const t of tooLarge) diagnostics.push(whole(t.path, 'error', SOURCE_TOO_LARGE_CODE, `${t.bytes} bytes, above the ${DEFAULT_MAX_IMPORT_BYTES} a project's file may hold: not read (a build refuses the project for it too)`));
    for (const n of notFiles) {
        if (loaded.has(n.path)) continue; // imported: read, and said on its import (import-link)
        if (n.folder) {
            const shown = whole(n.path, 'warning', SOURCE_NOT_FILE_CODE, n.what);
            diagnostics.push({ ...shown, file: shown.file.length > 300 ? `${shown.file.slice(0, 300)}...` : shown.file });
            continue;
        }
        diagnostics.push(whole(n.path, 'warning', SOURCE_NOT_FILE_CODE, `${n.what}: not read here, and a build (contract build, the IDE's build service) refuses the project for it, nothing built; put the file itself there`));
    }
    diagnostics.sort((a, b) => a.file.localeCompare(b.file) || a.line - b.line || a.column - b.column);
    const probed = new Map<string, boolean>();
    const hasTree = (folder: string) => probed.get(folder) ?? probed.set(folder, isTreeFolder(join(root, folder, SRC_GEN_DIR))).get(folder)!;
    const layout = projectRootsOf(documents.map((d) => d.file), hasTree);
    return { dir: root, documents, diagnostics, services, layout: { roots: layout.roots, unusedTrees: layout.unusedTrees } };
}
