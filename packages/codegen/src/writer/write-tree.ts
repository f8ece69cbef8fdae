import { existsSync, readFileSync, readdirSync, rmdirSync, statSync, unlinkSync } from 'node:fs';
import { basename, dirname, join, posix } from 'node:path';
import { mergeRegions, userRegions } from '../regions/merge-regions.js';
import { RegionSyntaxError } from '../regions/region-error.js';
import { bytesOf, toByteString } from './byte-string.js';
import { writeFileAtomic } from './atomic-write.js';
import { MANIFEST_NAME, hashContent, loadManifest, looksLikeDefault, regionDefaults, serialiseManifest } from './manifest.js';
import { ORPHANS_DIR, regionOrphanText, writeOrphan } from './orphans.js';
import { emptyReport, type GenerationReport } from './report.js';

/** One file the generators produced: path relative to the output folder ('/'-separated) and its text. */
export interface GeneratedFile {
    path: string;
    content: string;
}

export interface WriteTreeOptions {
    /** Folder (relative to the output folder) that only the generator writes; scanned for stale files when there is no manifest. */
    managedRoot?: string;
}

type DefaultsOf = (path: string) => Record<string, string> | undefined;

function defaultCheck(defaults: Record<string, string> | undefined) {
    return (id: string, content: string) => {
        const known = defaults?.[id];
        return known !== undefined ? known === hashContent(content) : looksLikeDefault(content);
    };
}

/** Files under `root` holding protected-region markers (the generator's files when no manifest says so). */
function scanGeneratedFiles(outDir: string, root: string): string[] {
    const found: string[] = [];
    const walk = (rel: string) => {
        const abs = join(outDir, rel);
        if (!existsSync(abs)) return;
        for (const entry of readdirSync(abs, { withFileTypes: true })) {
            const child = posix.join(rel, entry.name);
            if (entry.isDirectory()) walk(child);
            else if (entry.isFile() && statSync(join(outDir, child)).size < 4_000_000) {
                if (readFileSync(join(outDir, child), 'latin1').includes('PROTECTED REGION')) found.push(child);
            }
        }
    };
    walk(root);
    return found.sort();
}

/** Removes now-empty folders from `dir` up to (excluding) the output folder. */
function pruneEmptyDirs(outDir: string, rel: string): void {
    let dir = posix.dirname(rel);
    while (dir !== '.' && dir !== '' && dir !== ORPHANS_DIR) {
        const abs = join(outDir, dir);
        try {
            if (readdirSync(abs).length > 0) return;
            rmdirSync(abs);
        } catch {
            return;
        }
        dir = posix.dirname(dir);
    }
}

/**
 * Writes a generated tree into `outDir`, merging protected regions with what is there:
 * ENABLED regions keep their content byte for byte, vanished user code goes to `orphans/`,
 * malformed files are left untouched (error with file and line), unchanged files are not
 * rewritten, every write is atomic. Returns what happened.
 */
export function writeTree(outDir: string, files: GeneratedFile[], options: WriteTreeOptions = {}): GenerationReport {
    const report = emptyReport();
    const loaded = loadManifest(outDir);
    if (!loaded.manifest && 'problem' in loaded && loaded.problem) {
        report.warnings.push({ file: MANIFEST_NAME, message: loaded.problem });
    }
    const oldDefaults: DefaultsOf = (p) => loaded.manifest?.files[p];
    const newManifest = new Map<string, Record<string, string>>();
    const sorted = [...files].sort((a, b) => (a.path < b.path ? -1 : a.path > b.path ? 1 : 0));
    const produced = new Set(sorted.map((f) => f.path));

    const knownDirs = new Set<string>();
    const listings = new Map<string, Set<string>>();
    /** Whether `abs` may exist: one directory listing per folder instead of one failed open per new file. */
    const mayExist = (abs: string): boolean => {
        const dir = dirname(abs);
        let names = listings.get(dir);
        if (!names) {
            try {
                names = new Set(readdirSync(dir));
                knownDirs.add(dir);
            } catch {
                names = new Set();
            }
            listings.set(dir, names);
        }
        return names.has(basename(abs));
    };
    for (const file of sorted) {
        const generated = toByteString(file.content);
        newManifest.set(file.path, regionDefaults(generated, file.path));
        const abs = join(outDir, file.path);
        try {
            const existing = mayExist(abs) ? readIfPresent(abs) : undefined;
            if (existing === undefined) {
                writeFileAtomic(abs, bytesOf(generated), knownDirs);
                report.created.push(file.path);
                report.filesWritten++;
                continue;
            }
            if (existing === generated) {
                // identical to the fresh output: nothing to merge (every region holds the default)
                report.unchanged.push(file.path);
                continue;
            }
            const merged = mergeRegions(generated, existing, file.path, defaultCheck(oldDefaults(file.path)));
            if (merged.orphans.length > 0) {
                const orphan = writeOrphan(outDir, file.path, regionOrphanText(file.path, existing, merged.orphans));
                if (orphan.written) report.filesWritten++;
                report.orphaned.push(orphan.path);
                report.warnings.push({
                    file: file.path,
                    line: merged.orphans[0]!.line,
                    message: `user code of vanished protected region(s) ${merged.orphans.map((r) => r.id).join(', ')} moved to ${orphan.path}`,
                });
            }
            if (merged.text === existing) {
                report.unchanged.push(file.path);
            } else {
                writeFileAtomic(abs, bytesOf(merged.text), knownDirs);
                report.updated.push(file.path);
                report.filesWritten++;
            }
        } catch (e) {
            recordFailure(report, file.path, e, 'left untouched');
            // keep what we knew of the untouched file so that its defaults stay recognisable
            const previous = oldDefaults(file.path);
            if (previous) newManifest.set(file.path, previous);
        }
    }

    const previousFiles = loaded.manifest
        ? Object.keys(loaded.manifest.files).sort()
        : scanGeneratedFiles(outDir, options.managedRoot ?? 'generated');
    for (const path of previousFiles) {
        if (produced.has(path)) continue;
        const abs = join(outDir, path);
        if (!existsSync(abs)) continue;
        try {
            const existing = readFileSync(abs, 'latin1');
            const owned = userRegions(existing, path, defaultCheck(oldDefaults(path)));
            if (owned.length > 0) {
                const orphan = writeOrphan(outDir, path, existing);
                if (orphan.written) report.filesWritten++;
                report.orphaned.push(orphan.path);
                report.warnings.push({
                    file: path,
                    message: `its entity no longer exists; the file holds user code (${owned.map((r) => r.id).join(', ')}) and was moved to ${orphan.path}`,
                });
            } else {
                report.removed.push(path);
            }
            unlinkSync(abs);
            pruneEmptyDirs(outDir, path);
        } catch (e) {
            recordFailure(report, path, e, 'its entity no longer exists, but the file was left untouched');
            const previous = oldDefaults(path);
            if (previous) newManifest.set(path, previous);
        }
    }

    const manifestText = serialiseManifest(newManifest);
    const manifestFile = join(outDir, MANIFEST_NAME);
    try {
        if (readIfPresent(manifestFile) !== manifestText) {
            writeFileAtomic(manifestFile, Buffer.from(manifestText, 'utf8'));
            report.filesWritten++;
        }
    } catch (e) {
        report.errors.push({ file: MANIFEST_NAME, message: `cannot write the manifest: ${(e as Error).message}` });
    }
    return report;
}

/** The file's bytes as a byte string, or undefined when it does not exist. */
function readIfPresent(abs: string): string | undefined {
    try {
        return readFileSync(abs, 'latin1');
    } catch (e) {
        if ((e as NodeJS.ErrnoException).code === 'ENOENT') return undefined;
        throw e;
    }
}

function recordFailure(report: GenerationReport, path: string, e: unknown, consequence: string): void {
    if (e instanceof RegionSyntaxError && !e.file.endsWith('(generated output)')) {
        report.errors.push({ file: path, line: e.line, message: `${e.detail}; ${consequence}` });
    } else if (e instanceof RegionSyntaxError) {
        throw e; // a generator bug, not a user problem
    } else {
        report.errors.push({ file: path, message: `${(e as Error).message}; ${consequence}` });
    }
}
