import { posix } from 'node:path';
import { mergeRegions, userRegions } from '../regions/merge-regions.js';
import { carryRenamedRegions, type GeneratedOutput } from '../regions/carry-renamed-regions.js';
import { fillRegions, planMisplacedRegions, withoutForeignRegions } from '../regions/misplaced-regions.js';
import { SRC_GEN_DIR, scanRegions } from '@contract-studio/conventions';
import { RegionSyntaxError } from '../regions/region-error.js';
import { bytesOf, toByteString } from './byte-string.js';
import { blankLines, decodeLineHashes, describeEdits, editsOutside, regionLineHashes, runsText, skeletonLines } from './skeleton-lines.js';
import { linesNotRegenerated } from './outside-regions.js';
import { CONFLICTED, MANIFEST_NAME, fileRecord, hasCrlfEndings, hashContent, loadManifest, looksLikeDefault, mergedDefaults, manifestTextLike, regionsHoldingCode, serialiseManifest, skeletonHash, unreadableManifestAdvice, type LoadedManifest, type ManifestLoad } from './manifest.js';
import { ORPHANS_DIR, existingOrphans, fileOrphanText, regionOrphanText, writeOrphan } from './orphans.js';
import { OutputTree } from './output-tree.js';
import { emptyReport, type GenerationReport } from './report.js';
import { UnsafePathError } from './safe-paths.js';
import { RENAME_JOURNAL_NAME, hasRenameJournal } from './rename-journal.js';
import { conflictRefusal } from './conflicts.js';
import { REGION_COPY_NAME, loadRegionCopy, regionBodies, writeRegionCopy, type RegionBodies } from './region-copy.js';

/** One file the generators produced: path relative to the output folder ('/'-separated) and its text. */
export interface GeneratedFile {
    path: string;
    content: string;
    /**
     * For a file that depends on what the others hold once written, protected regions included (an
     * executable's Makefile names the headers its code includes): its text from the tree as written
     * (`textOf`: a file's text after this generation, undefined when there is none; throws when it
     * cannot tell). Such a file holds no protected region; `content` is its text for a fresh tree.
     */
    derive?: (textOf: (path: string) => string | undefined) => string;
}

export interface WriteTreeOptions {
    /** Folder (relative to the output folder) that only the generator writes; scanned for stale files when there is no manifest. */
    managedRoot?: string;
    /**
     * What to do with user code the merge cannot place (a vanished region, a region without
     * ENABLED, code outside the regions): 'orphan' (default) moves it to `orphans/`; 'refuse' (a
     * build's generation into its private copy of the project, where an orphan reaches no one)
     * leaves the file untouched with an error naming the region, file and line, saying to run
     * `contract generate` on the project, and leaves a file of a deleted entity holding user code
     * in place with a warning.
     */
    displacedCode?: 'orphan' | 'refuse';
}

type DefaultsOf = (path: string) => Record<string, string> | undefined;

function defaultCheck(defaults: Record<string, string> | undefined) {
    return (id: string, content: string) => {
        const known = defaults?.[id];
        return known !== undefined ? known === hashContent(content) : looksLikeDefault(content);
    };
}

/** The manifest's verdict on a region's content when it knows the default (true/false), else undefined. */
function knownDefaultCheck(defaults: Record<string, string> | undefined) {
    return (id: string, content: string) => {
        const known = defaults?.[id];
        return known !== undefined ? known === hashContent(content) : undefined;
    };
}

/** What a build reads of a project's file, at most (the build service's projectFileBytes; the IDE opens the same). */
const MAX_SOURCE_BYTES = 8 * 1024 * 1024;

/** 1-based number of the first line of `a` that differs from `b`'s line of the same number. */
export function firstDifferingLine(a: string, b: string): number {
    let line = 1;
    const n = Math.min(a.length, b.length);
    for (let i = 0; i < n && a.charCodeAt(i) === b.charCodeAt(i); i++) if (a.charCodeAt(i) === 10) line++;
    return line;
}

/**
 * Where `existing` was written outside its regions: the lines that are not the generator's, from
 * the line hashes the manifest recorded when it wrote the file (skeleton-lines.ts); without them
 * (an older manifest), the first line that differs from the regenerated file `regenerated`.
 * Undefined when the line hashes say that nothing but what loses no code differs: whitespace-only
 * lines, and the lines of regions `carriedHome` (cut from this file, their code carried back).
 */
function whereEditedOutside(existing: string, file: string, recordedLines: string | undefined, regenerated: string, carriedHome: Iterable<string>): { line: number; where: string } | undefined {
    if (recordedLines !== undefined) {
        const homeLines = regionLineHashes(regenerated, `${file} (generated output)`, carriedHome);
        const edits = editsOutside(decodeLineHashes(recordedLines), skeletonLines(existing, file), { written: blankLines(existing), removed: (h) => homeLines.has(h) });
        const described = describeEdits(edits);
        if (described.line !== undefined) return { line: described.line, where: described.where };
        if (edits.excused > 0) return undefined;
    }
    const line = firstDifferingLine(existing, regenerated);
    return { line, where: `first line that differs from the regenerated file: ${line}` };
}

/**
 * Files under `root` holding protected-region markers (the generator's files when no manifest says
 * so), but those in `skip` (generated again: not read); links are skipped. Each folder's names go
 * to `listings`, so that writing the new files lists no folder a second time.
 */
function scanGeneratedFiles(tree: OutputTree, root: string, skip: ReadonlySet<string>, listings: Map<string, Set<string>>): string[] {
    const found: string[] = [];
    const walk = (rel: string) => {
        const entries = tree.list(rel) ?? [];
        listings.set(rel, new Set(entries.map((e) => e.name)));
        for (const entry of entries) {
            const child = posix.join(rel, entry.name);
            if (entry.isDirectory()) walk(child);
            else if (entry.isFile() && !skip.has(child)) {
                let text: string | undefined;
                try {
                    text = tree.read(child, 4_000_000);
                } catch (e) {
                    if (e instanceof UnsafePathError) continue; // too large, or swapped for something else: not ours
                    throw e;
                }
                if (text?.includes('PROTECTED REGION')) found.push(child);
            }
        }
    };
    walk(root);
    return found.sort();
}

/**
 * Symlinks met in the output tree, each with the files refused because of it: reported as one
 * error per link (a linked folder would otherwise give one error per generated file under it).
 */
class Refusals {
    private readonly byLink = new Map<string, { error: UnsafePathError; files: string[] }>();

    add(path: string, error: UnsafePathError): void {
        const key = error.link ?? path;
        const entry = this.byLink.get(key) ?? { error, files: [] };
        entry.files.push(path);
        this.byLink.set(key, entry);
    }

    report(report: GenerationReport): void {
        for (const [link, { error, files }] of [...this.byLink.entries()].sort(([a], [b]) => (a < b ? -1 : a > b ? 1 : 0))) {
            const under = files.filter((f) => f !== link);
            const what = under.length === 0
                ? 'left untouched'
                : `${under.length} file(s) not read, written or deleted: ${under.slice(0, 3).join(', ')}${under.length > 3 ? ', ...' : ''}`;
            report.errors.push({ file: link, message: `${error.message}; ${what}` });
        }
    }
}

/**
 * Writes a generated tree into `outDir`, merging protected regions with what is there:
 * ENABLED regions keep their content byte for byte, vanished user code goes to `orphans/`,
 * malformed files are left untouched (error with file and line), unchanged files are not
 * rewritten, every write is atomic. Returns what happened.
 *
 * Everything read from `outDir` is untrusted (docs/codegen.md, "What generate refuses"): every
 * access goes through OutputTree (no `..`, no absolute path, no link on the way), manifest
 * entries with a bad path are dropped with a warning, and a symlink met in the tree is an error
 * naming it, with nothing read, written or deleted through it. Throws UnsafePathError when
 * `outDir` itself is a link or not a folder.
 */
export function writeTree(outDir: string, files: GeneratedFile[], options: WriteTreeOptions = {}): GenerationReport {
    const tree = new OutputTree(outDir);
    try {
        tree.prepare();
        // one writer of the tree at a time: a terminal's generate and the IDE's saves (tree-lock.ts)
        tree.lock();
        // a rename killed half-way (rename-journal.ts): the model given is the half-renamed one, and
        // generating from it would move the renamed code to orphans/; the writers that read the model
        // after taking the lock (contract generate, rename, Generate All) finish the rename first
        if (hasRenameJournal(tree)) {
            const report = emptyReport();
            report.errors.push({ file: RENAME_JOURNAL_NAME, message: `an interrupted rename left its journal here: the .contract files and the generated tree are half renamed. \`contract generate\` on the project (or the IDE's Generate All) finishes the rename; when it could not (a warning says why), remove this file; nothing was generated` });
            return report;
        }
        return writeInto(tree, files, options);
    } finally {
        tree.close();
    }
}

function writeInto(tree: OutputTree, files: GeneratedFile[], options: WriteTreeOptions): GenerationReport {
    const report = emptyReport();
    const refusals = new Refusals();
    let loaded: ManifestLoad = { problems: [] };
    let manifestRefused = false;
    try {
        loaded = loadManifest(tree);
    } catch (e) {
        if (!(e instanceof UnsafePathError)) throw e;
        refusals.add(MANIFEST_NAME, e);
        manifestRefused = true;
    }
    const refuseDisplacing = options.displacedCode === 'refuse';
    // a manifest there but unreadable (git conflict markers...): no record of what the generator
    // wrote, so it cannot tell its own lines from code written outside the regions. A build refuses
    // (it would build without that code); generate copies each file that differs from what it now
    // writes to orphans/, and writes the manifest anew unless a refused file's record would be lost
    const unreadable = loaded.unreadable;
    let unreadableNote: { file: string; message: string } | undefined;
    for (const problem of loaded.problems) {
        if (unreadable !== undefined && refuseDisplacing) {
            report.errors.push({ file: MANIFEST_NAME, message: `${problem}: with no record of what the generator wrote, a build cannot tell its lines from code written outside the protected regions, and would leave that code out; ${unreadableManifestAdvice(unreadable)}, then build again` });
        } else {
            const warning = { file: MANIFEST_NAME, message: problem };
            report.warnings.push(warning);
            if (unreadable !== undefined) unreadableNote = warning;
        }
    }
    /** A file refused (left untouched) while the manifest was unreadable: no record of it to write. */
    let refusedUnrecorded = false;
    const oldDefaults: DefaultsOf = (p) => loaded.manifest?.files.get(p);
    const newManifest = new Map<string, Record<string, string>>();
    const newSkeletons = new Map<string, string>();
    const newSkeletonLines = new Map<string, string>();
    /** path -> the IDs of its regions holding user code as written or kept by this generation (Manifest.userCode). */
    const newUserCode = new Map<string, string[]>();
    /** path -> the IDs of its regions whose code a deletion lost, still said (Manifest.lostUserCode). */
    const newLostUserCode = new Map<string, string[]>();
    // the last generation's copy of the regions' user code (region-copy.ts): a deleted file gets it back
    const copy = loaded.manifest ? loadRegionCopy(tree, new Set(loaded.manifest.files.keys())) : { bodies: new Map() as RegionBodies };
    if (copy.problem) {
        report.warnings.push({ file: REGION_COPY_NAME, message: `${copy.problem}: no protected region of a deleted generated file can be restored from it (such a file is generated anew with the defaults, and said); written anew by this generation from the files as they are` });
    }
    /** path -> the contents of its regions holding user code after this generation (the copy written at the end). */
    const newBodies: RegionBodies = new Map();
    const recordBodies = (path: string, text: string, held: readonly string[]) => {
        if (held.length > 0) newBodies.set(path, regionBodies(text, path, held));
        else newBodies.delete(path);
    };
    /**
     * A file whose regions' code a deletion lost (the manifest's lostUserCode) and that now holds
     * code in none of them (`heldNow`): said again, and kept in the record; one holding code there
     * again (restored, or written anew) drops the record.
     */
    const sayStillLost = (path: string, heldNow: readonly string[]) => {
        const lost = loaded.manifest?.lostUserCode.get(path);
        if (!lost || lost.some((id) => heldNow.includes(id))) return;
        newLostUserCode.set(path, lost);
        report.warnings.push({ file: path, message: stillLostUserCode(path, lost) });
    };
    /** The skeleton hash recorded when the file was last written (undefined: no manifest, an older or unreadable one). */
    const recordedSkeleton = (p: string) => loaded.manifest?.skeletons.get(p);
    /** Why a file has no recorded skeleton, as a clause. */
    const noRecord = (): string => {
        if (unreadable !== undefined) return `the manifest ${unreadable}`;
        if (manifestRefused) return 'the manifest is not read (a link)';
        if (loaded.manifest) return 'the manifest holds no record of its text (a manifest of an older version)';
        return `there is no manifest (${MANIFEST_NAME}) recording what the generator wrote`;
    };
    const keepPrevious = (path: string) => {
        if (unreadable !== undefined) refusedUnrecorded = true;
        const previous = oldDefaults(path);
        if (previous) newManifest.set(path, previous);
        const skeleton = recordedSkeleton(path);
        if (skeleton !== undefined) newSkeletons.set(path, skeleton);
        else newSkeletons.delete(path);
        const lines = loaded.manifest?.skeletonLines.get(path);
        if (lines !== undefined) newSkeletonLines.set(path, lines);
        else newSkeletonLines.delete(path);
        const held = loaded.manifest?.userCode.get(path);
        if (held !== undefined) newUserCode.set(path, held);
        else newUserCode.delete(path);
        const lost = loaded.manifest?.lostUserCode.get(path);
        if (lost !== undefined) newLostUserCode.set(path, lost);
        else newLostUserCode.delete(path);
        const bodies = copy.bodies.get(path);
        if (bodies !== undefined) newBodies.set(path, bodies);
        else newBodies.delete(path);
    };
    /** No manifest there at all (not an unreadable or older one): a tree of another version or tool, or one whose manifest was deleted. */
    const noManifestAtAll = !loaded.manifest && unreadable === undefined && !manifestRefused;
    /**
     * A manifest of a version before skeleton records (it holds of each file only its regions'
     * default hashes, `{}` for a file without regions: nothing of the text outside them).
     */
    const olderManifest = loaded.manifest !== undefined && !loaded.manifest.recordsSkeletons && unreadable === undefined;
    /**
     * The copies in orphans/ of the files that, with no manifest at all or one of an older version,
     * held lines this generator does not write: one warning for them all.
     */
    const copiedWithoutRecord: string[] = [];
    const sorted = [...files].sort((a, b) => (a.path < b.path ? -1 : a.path > b.path ? 1 : 0));
    const produced = new Set(sorted.map((f) => f.path));
    /** Every region ID of the new output, read once when a carry-over asks (carry-renamed-regions.ts). */
    let output: GeneratedOutput | undefined;
    const outputOf = (): GeneratedOutput => (output ??= { ids: new Set(sorted.flatMap((f) => (f.derive ? [] : scanRegions(f.content).regions.map((r) => r.id)))), paths: [...produced] });

    // the generator's files before this generation: the manifest's, else (none, or unreadable) the
    // files holding protected regions, found before writing (a new tree has none: nothing is listed or
    // read back); a file generated again is no candidate for removal and is not read
    let previousFiles: string[] = [];
    const listings = new Map<string, Set<string>>(); // folder -> its names before writing
    if (loaded.manifest) {
        previousFiles = [...loaded.manifest.files.keys()].sort();
    } else {
        const root = options.managedRoot ?? 'generated';
        try {
            previousFiles = scanGeneratedFiles(tree, root, produced, listings);
        } catch (e) {
            recordFailure(report, refusals, root, e, 'not scanned for files of deleted entities');
        }
    }

    const parentOf = (rel: string): string => (posix.dirname(rel) === '.' ? '' : posix.dirname(rel));
    /** Whether the nearest folder above `dir` that was listed did not hold the way down to it (then `dir` did not exist). */
    const knownAbsent = (dir: string): boolean => {
        for (let child = dir; child !== ''; child = parentOf(child)) {
            const names = listings.get(parentOf(child));
            if (names) return !names.has(posix.basename(child));
        }
        return false;
    };
    /**
     * Whether `rel` may exist: one directory listing per folder instead of one failed open per new
     * file, and none for a folder under one that was listed without it (a new tree: none at all).
     */
    const mayExist = (rel: string): boolean => {
        const dir = parentOf(rel);
        let names = listings.get(dir);
        if (!names) {
            names = knownAbsent(dir) ? new Set<string>() : new Set((tree.list(dir) ?? []).map((e) => e.name));
            listings.set(dir, names);
        }
        return names.has(posix.basename(rel));
    };
    /** The files on disk, read once (a region found in the wrong file is looked for before writing). */
    const texts = new Map<string, string | undefined>();
    const readExisting = (path: string): string | undefined => {
        if (!texts.has(path)) texts.set(path, mayExist(path) ? tree.read(path) : undefined);
        return texts.get(path);
    };
    // regions a git merge (or a paste) put in another generated file than their own (misplaced-regions.ts;
    // a derived file, a Makefile, holds no region)
    const misplaced = planMisplacedRegions(sorted.filter((f) => !f.derive), (path) => {
        try {
            const text = readExisting(path);
            return text !== undefined && conflictRefusal(text) ? null : text;
        } catch {
            return null; // reported when the file itself is written
        }
    }, (path, id, content) => defaultCheck(oldDefaults(path))(id, content));
    /** The text of each generated file after this generation (what it holds on disk), as it was written or left. */
    const onDisk = new Map<string, string>();
    const textOf = (path: string): string | undefined => {
        if (produced.has(path)) {
            const text = onDisk.get(path);
            if (text === undefined) throw new Error(`${path} could not be written`);
            return text;
        }
        return mayExist(path) ? tree.read(path) : undefined; // a user's file (a header in common/)
    };
    // the files derived from the others (derive) come last, from the tree as written
    const inWritingOrder = function* (): Generator<GeneratedFile> {
        for (const file of sorted) if (!file.derive) yield file;
        for (const file of sorted) if (file.derive) yield { path: file.path, content: file.derive(textOf) };
    };
    for (const file of inWritingOrder()) {
        const generated = toByteString(file.content);
        /** Regions of this file found in another one, whose code comes home. */
        const carriedIn = misplaced.into.get(file.path);
        const record = fileRecord(generated, file.path);
        newManifest.set(file.path, record.defaults);
        newSkeletons.set(file.path, record.skeleton);
        // the same skeleton as recorded: the same line hashes (they are the skeleton's lines)
        const recordedLines = recordedSkeleton(file.path) === record.skeleton ? loaded.manifest?.skeletonLines.get(file.path) : undefined;
        newSkeletonLines.set(file.path, recordedLines ?? record.lines());
        try {
            let existing = readExisting(file.path);
            if (existing === undefined) {
                let text = carriedIn ? fillRegions(generated, file.path, carriedIn) : generated;
                // a file deleted by hand whose regions held code: that code back from the copy
                const restored = restorableBodies(copy.bodies.get(file.path), record.defaults, carriedIn);
                if (restored.size > 0) {
                    text = fillRegions(text, file.path, restored);
                    report.warnings.push({ file: file.path, message: restoredMessage(file.path, [...restored.keys()]) });
                }
                // a manifest of an older version with a copy of this one: the copy tells what held code
                const lost = restored.size > 0 && !loaded.manifest?.recordsUserCode ? undefined : deletedUserCode(tree, file.path, loaded.manifest, new Map([...(carriedIn ?? []), ...restored]));
                if (lost) {
                    report.warnings.push({ file: file.path, message: lost.message });
                    newLostUserCode.set(file.path, lost.regions);
                }
                tree.write(file.path, bytesOf(text));
                onDisk.set(file.path, text);
                if (carriedIn || restored.size > 0) {
                    const held = regionsHoldingCode(text, file.path, record.defaults);
                    newUserCode.set(file.path, held);
                    recordBodies(file.path, text, held);
                }
                report.created.push(file.path);
                report.filesWritten++;
                continue;
            }
            onDisk.set(file.path, existing); // until it is rewritten below
            if (existing === generated && !carriedIn) {
                // identical to the fresh output: nothing to merge (every region holds the default)
                sayStillLost(file.path, []);
                report.unchanged.push(file.path);
                continue;
            }
            const conflict = conflictRefusal(existing);
            if (conflict) {
                report.errors.push({ file: file.path, line: conflict.line, message: conflict.message });
                keepPrevious(file.path);
                continue;
            }
            const original = existing;
            // a rename merged by git left the old entity's region ID in the new entity's file
            const carry = carryRenamedRegions(existing, file.path, Object.keys(record.defaults), outputOf);
            existing = carry.text;
            for (const c of carry.carried) {
                report.warnings.push({
                    file: file.path,
                    line: c.line,
                    message: `protected region ${c.from} carried over to ${c.to}: nothing generates ${c.from} any more and this file had no ${c.to} of its own (a rename merged by git?); its code is kept byte for byte under the new ID: check that it belongs here`,
                });
            }
            const merged = mergeRegions(generated, existing, file.path, defaultCheck(oldDefaults(file.path)), knownDefaultCheck(oldDefaults(file.path)));
            if (carriedIn) merged.text = fillRegions(merged.text, file.path, carriedIn);
            const carriedOut = misplaced.outOf.get(file.path) ?? [];
            for (const m of carriedOut) {
                report.warnings.push({
                    file: file.path,
                    line: m.line,
                    message: `protected region ${m.id} is no region of this file but of ${m.to} (a git merge or a paste put it here?): its code was carried there, byte for byte, into its ${m.id}, which held the generated default; check that it belongs there`,
                });
            }
            merged.orphans = merged.orphans.filter((r) => !carriedOut.some((m) => m.id === r.id));            // user code this generation would move aside: code outside the regions (the skeleton
            // differs from the one written last time, and from the fresh one: a file edited into what
            // the generator now writes loses nothing), regions without ENABLED, vanished regions
            const displaced: { line: number; what: string; orphan: () => string; message: (orphan: string) => string; unrecorded?: { where: string } }[] = [];
            const recorded = recordedSkeleton(file.path);
            // a region of another file found here is none of this file's skeleton (carried home, or orphaned below)
            const ownSkeleton = () => {
                const skeleton = skeletonHash(existing!, file.path);
                return skeleton === recorded || skeleton === record.skeleton ? skeleton : skeletonHash(withoutForeignRegions(existing!, file.path, misplaced.homes), file.path);
            };
            if (recorded !== undefined) {
                const skeleton = ownSkeleton();
                const edited = skeleton !== recorded && skeleton !== record.skeleton
                    ? whereEditedOutside(existing, file.path, loaded.manifest?.skeletonLines.get(file.path), merged.text, carriedIn?.keys() ?? [])
                    : undefined;
                if (edited) {
                    const { line, where } = edited;
                    displaced.push({
                        line,
                        what: `edited outside its protected regions (${where})`,
                        orphan: () => fileOrphanText(file.path, original, [where], undefined, 'skeleton'),
                        message: (orphan) => `edited outside its protected regions (${where}): that code is regenerated, not kept; the file as it was is in ${orphan} (move your code into a protected region)`,
                    });
                }
            } else if (ownSkeleton() !== record.skeleton) {
                // no record of what the generator wrote in it (no manifest, an older or unreadable one):
                // the lines a regeneration would lose, from the regenerated file (outside-regions.ts)
                const lost = linesNotRegenerated(existing, merged.text, file.path);
                if (lost.length > 0) {
                    const where = `${runsText(lost)} not in the regenerated file`;
                    const what = `holds lines outside its protected regions that this generator does not write (${where}): an older generator's lines or code of yours, and ${noRecord()}, so the generator cannot tell which`;
                    displaced.push({
                        line: lost[0]!,
                        what,
                        orphan: () => fileOrphanText(file.path, original, [`${where}; ${noRecord()}`], undefined, 'unrecorded'),
                        message: (orphan) => `${what}: the file as it was is copied to ${orphan} before it is regenerated (move any code of yours there into a protected region, then delete the copy; an older generator's lines need nothing)`,
                        unrecorded: { where },
                    });
                }
            }
            if (merged.disabled.length > 0) {
                const ids = merged.disabled.map((r) => r.id).join(', ');
                displaced.push({
                    line: merged.disabled[0]!.line,
                    what: `protected region(s) ${ids} not ENABLED, holding user code the generated default would replace`,
                    orphan: () => regionOrphanText(file.path, existing, merged.disabled, undefined, 'disabled'),
                    message: (orphan) => `protected region(s) ${ids} not ENABLED: their content was replaced by the generated default; what they held is in ${orphan} (put ENABLED back in the start marker to keep your code)`,
                });
            }
            if (merged.orphans.length > 0) {
                const ids = merged.orphans.map((r) => r.id).join(', ');
                // a region of another generated file (found here, but not carried home): says where it belongs
                const homes = new Map(merged.orphans.flatMap((r) => (misplaced.homes.has(r.id) ? [[r.id, misplaced.homes.get(r.id)!] as const] : [])));
                const elsewhere = [...homes].map(([id, home]) => `; ${id} is no region of this file but of ${home} (a git merge or a paste put it here?), whose ${id} holds code of its own (or it is in more than one file): not carried there, paste its code into that region by hand`).join('');
                displaced.push({
                    line: merged.orphans[0]!.line,
                    what: `protected region(s) ${ids} hold user code but are not generated in this file${homes.size === merged.orphans.length ? '' : ' any more (a renamed or removed module, port, datatype or function)'}${elsewhere}`,
                    orphan: () => regionOrphanText(file.path, existing, merged.orphans, undefined, 'vanished', homes),
                    message: (orphan) => `user code of ${homes.size === merged.orphans.length ? '' : 'vanished '}protected region(s) ${ids} moved to ${orphan}${elsewhere}`,
                });
            }
            if (refuseDisplacing && displaced.length > 0) {
                for (const d of displaced) {
                    report.errors.push({
                        file: file.path,
                        line: d.line,
                        message: `${d.what}: a build leaves no user code out; run \`contract generate\` on the project (Generate All in the IDE: it moves that code to src-gen/orphans/, where you get it back), then build again; left untouched`,
                    });
                }
                keepPrevious(file.path);
                continue;
            }
            for (const d of displaced) {
                const orphan = writeOrphan(tree, file.path, d.orphan());
                if (orphan.written) report.filesWritten++;
                report.orphaned.push(orphan.path);
                // a tree with no manifest at all (another version's or tool's), or an older version's
                // manifest that records no file's text: said once, below
                if (d.unrecorded && (noManifestAtAll || olderManifest)) copiedWithoutRecord.push(orphan.path);
                else report.warnings.push({ file: file.path, line: d.line, message: d.message(orphan.path) });
            }
            // a file with CRLF line endings (a Windows checkout) keeps them: the generator's lines are
            // written CRLF too, not LF beside the regions' CRLF (every line a diff)
            if (hasCrlfEndings(existing)) merged.text = merged.text.replace(/(?<!\r)\n/g, '\r\n');
            if (merged.text.length > MAX_SOURCE_BYTES) {
                report.warnings.push({
                    file: file.path,
                    line: 1,
                    message: `is ${merged.text.length} bytes with its protected regions, above the ${MAX_SOURCE_BYTES} a build reads of a project's file (and the IDE opens): contract build and Build & Run will refuse the project; keep large data out of the regions (a file the code reads)`,
                });
            }
            const defaults = merged.text === generated ? record.defaults : mergedDefaults(merged.text, file.path, record.defaults, oldDefaults(file.path));
            newManifest.set(file.path, defaults);
            const held = merged.text === generated ? [] : regionsHoldingCode(merged.text, file.path, defaults);
            if (held.length > 0) newUserCode.set(file.path, held);
            recordBodies(file.path, merged.text, held);
            sayStillLost(file.path, held);
            if (merged.text === original) {
                report.unchanged.push(file.path);
            } else {
                tree.write(file.path, bytesOf(merged.text));
                onDisk.set(file.path, merged.text);
                report.updated.push(file.path);
                report.filesWritten++;
            }
        } catch (e) {
            onDisk.delete(file.path); // not known: what derives from it assumes the worst
            recordFailure(report, refusals, file.path, e, 'left untouched');
            // keep what we knew of the untouched file so that its defaults (and skeleton) stay recognisable
            keepPrevious(file.path);
        }
    }

    for (const path of previousFiles) {
        if (produced.has(path)) continue;
        try {
            const existing = tree.read(path);
            if (existing === undefined) continue;
            const conflict = conflictRefusal(existing);
            if (conflict) {
                report.errors.push({ file: path, line: conflict.line, message: conflict.message });
                keepPrevious(path);
                continue;
            }
            const owned = userRegions(existing, path, defaultCheck(oldDefaults(path)));
            const recorded = recordedSkeleton(path);
            // no record (no manifest, an older or unreadable one): code may have been written outside its
            // regions, and nothing is generated to compare it with: the file is kept whole
            const editedOutside = recorded !== undefined ? skeletonHash(existing, path) !== recorded : true;
            const outside = recorded !== undefined ? 'code outside the protected regions' : `perhaps code outside the protected regions (${noRecord()})`;
            if ((owned.length > 0 || editedOutside) && refuseDisplacing) {
                const what = [...owned.map((r) => r.id), ...(editedOutside ? [outside] : [])];
                report.warnings.push({
                    file: path,
                    message: `its entity no longer exists; the file holds user code (${what.join(', ')}), which this build leaves out; \`contract generate\` on the project moves it to src-gen/orphans/`,
                });
                keepPrevious(path);
                continue;
            }
            if (owned.length > 0 || editedOutside) {
                const what = [...owned.map((r) => r.id), ...(editedOutside ? [outside] : [])];
                const orphan = writeOrphan(tree, path, fileOrphanText(path, existing, what));
                if (orphan.written) report.filesWritten++;
                report.orphaned.push(orphan.path);
                report.warnings.push({
                    file: path,
                    message: `its entity no longer exists; the file holds user code (${what.join(', ')}) and was moved to ${orphan.path}`,
                });
            } else {
                report.removed.push(path);
            }
            tree.remove(path);
            tree.pruneEmptyDirs(path, (dir) => dir === ORPHANS_DIR);
        } catch (e) {
            recordFailure(report, refusals, path, e, 'its entity no longer exists, but the file was left untouched');
            keepPrevious(path);
        }
    }

    if (copiedWithoutRecord.length > 0) report.warnings.unshift({ file: MANIFEST_NAME, message: unrecordedTreeSummary(copiedWithoutRecord, olderManifest) });
    if (unreadableNote && refusedUnrecorded && !refuseDisplacing) {
        // written anew, it would hold no record of the refused files: once resolved, their code
        // outside the regions would pass for the generator's. Left as it is, the next generation
        // still has no record, and copies a resolved file that differs to orphans/
        unreadableNote.message += `; left as it is while generated files are refused (errors above): written anew, it would hold no record of what the generator wrote in them; ${unreadableManifestAdvice(unreadable!)}`;
    } else if (!manifestRefused) {
        if (unreadableNote) unreadableNote.message += `, and written anew by this generation${unreadable === CONFLICTED ? `; next time, resolve such a conflict before generating: ${unreadableManifestAdvice(unreadable)}` : ''}`;
        try {
            const previous = tree.read(MANIFEST_NAME);
            // a CRLF checkout's manifest keeps its line endings (as the C files do): not rewritten for them alone
            const manifestText = manifestTextLike(previous, serialiseManifest(newManifest, newSkeletons, newSkeletonLines, newUserCode, newLostUserCode));
            if (previous !== manifestText) {
                tree.write(MANIFEST_NAME, Buffer.from(manifestText, 'utf8'));
                report.filesWritten++;
            }
            if (writeRegionCopy(tree, newBodies)) report.filesWritten++;
        } catch (e) {
            if (e instanceof UnsafePathError) refusals.add(MANIFEST_NAME, e);
            else report.errors.push({ file: MANIFEST_NAME, message: `cannot write the manifest: ${(e as Error).message}` });
        }
    }
    // in path order, as the files are given (the derived ones were written last)
    for (const list of [report.created, report.updated, report.unchanged]) list.sort();
    refusals.report(report);
    return report;
}

/** How many copies the summary of a tree without a manifest names; the rest are counted (all are in the report's `orphaned`). */
const NAMED_COPIES = 3;

/**
 * The one warning for a tree with no manifest at all, or with a manifest of an older version that
 * records no file's text (`older`) (docs/codegen.md, "Without a record"): its files holding lines
 * outside their regions that this generator does not write were copied to `copies` (orphans/...)
 * before they were regenerated.
 */
function unrecordedTreeSummary(copies: readonly string[], older: boolean): string {
    const named = copies.slice(0, NAMED_COPIES).join(', ') + (copies.length > NAMED_COPIES ? ` and ${copies.length - NAMED_COPIES} more` : '');
    const files = copies.length === 1 ? '1 file holds' : `${copies.length} files hold`;
    const why = older
        ? 'written by an older version of ContrACT Studio, it records of each file only the defaults of its protected regions, nothing of its text outside them (a file without regions, a Makefile, not at all).'
        : 'not there: this tree has no record of what was generated in it (a tree of another version of ContrACT Studio, or of another tool such as the ContrACT Eclipse tool?).';
    return `${why} ${files} lines outside the protected regions that this generator does not write, an older generator's lines or code of yours (it cannot tell which): each was regenerated, its regions' code kept, and copied first as it was to ${ORPHANS_DIR}/ under its own path (${named}). Move any code of yours found there into a protected region, then delete the copies; an older generator's lines need nothing. The manifest is written now: the next generation tells the generator's lines from yours`;
}

/**
 * What to say of generated file `path`, missing from the tree (deleted by hand?) though `manifest`
 * recorded that its regions held code when it was last generated (Manifest.userCode), or that a
 * deletion lost their code before (lostUserCode), or, a manifest of an older version that does not
 * tell (no userCode), listed it with regions: it is generated with the defaults, and the warning
 * names the regions (but those whose code comes back from another file, `carriedIn`) and how to
 * get the code back. The regions are recorded as lost (lostUserCode): every later generation and
 * build says it again until one holds code again. Undefined when none held code.
 */
function deletedUserCode(tree: OutputTree, path: string, manifest: LoadedManifest | undefined, carriedIn: ReadonlyMap<string, string> | undefined): { message: string; regions: string[] } | undefined {
    if (!manifest) return undefined;
    const notCarried = (ids: readonly string[]) => ids.filter((id) => !carriedIn?.has(id));
    const known = notCarried([...new Set([...(manifest.userCode.get(path) ?? []), ...(manifest.lostUserCode.get(path) ?? [])])]);
    const copies = existingOrphans(tree, path);
    const copy = copies.length > 0 ? `; a copy of it orphaned earlier is in ${copies[copies.length - 1]}` : '';
    const restore = `restore the file (\`git checkout -- ${SRC_GEN_DIR}/${path}\` in the project folder, or \`git restore\`) and generate again`;
    if (known.length > 0) {
        return { regions: known, message: `was not there (deleted?), though its protected region(s) ${known.join(', ')} held code when it was last generated: generated anew with the defaults, without that code. To get it back, ${restore}${copy}` };
    }
    if (manifest.recordsUserCode) return undefined;
    const unknown = notCarried(Object.keys(manifest.files.get(path) ?? {}));
    if (unknown.length === 0) return undefined;
    return {
        regions: unknown,
        message: `was not there (deleted?), and the manifest, written by an older version of ContrACT Studio, does not record whether its protected region(s) ${unknown.join(', ')} held code: generated anew with the defaults. If they held code, ${restore}${copy}; if not, write anything (a comment) in one of them to stop this warning`,
    };
}

/**
 * The contents of the copy (`saved`, a file's) that a file generated anew takes back: those of
 * regions the generator still writes in it (`defaults`), that hold no default, but those carried
 * in from another file (`carriedIn`).
 */
function restorableBodies(saved: ReadonlyMap<string, string> | undefined, defaults: Record<string, string>, carriedIn: ReadonlyMap<string, string> | undefined): Map<string, string> {
    const out = new Map<string, string>();
    for (const [id, body] of saved ?? []) {
        if (defaults[id] !== undefined && defaults[id] !== hashContent(body) && !carriedIn?.has(id)) out.set(id, body);
    }
    return out;
}

/** What to say of generated file `path`, deleted, generated anew with regions `ids` restored from the copy. */
function restoredMessage(path: string, ids: readonly string[]): string {
    return `was not there (deleted?): restored ${ids.length} protected region(s) of ${SRC_GEN_DIR}/${path} (${ids.join(', ')}) from the last generation's copy (${SRC_GEN_DIR}/${REGION_COPY_NAME}), as they were when it was last generated or built; check them`;
}

/** What to say of generated file `path` whose regions `lost` (Manifest.lostUserCode) still hold only their defaults. */
function stillLostUserCode(path: string, lost: readonly string[]): string {
    return `its protected region(s) ${lost.join(', ')} hold only their defaults since the file was deleted and generated anew (their code, or what they may have held, is in neither the file nor the build). To get it back, restore the file as it was before it was deleted (\`git log -- ${SRC_GEN_DIR}/${path}\`, then \`git checkout <commit> -- ${SRC_GEN_DIR}/${path}\` in the project folder) and generate again; if you do not want it back, write anything (a comment) in one of them to stop this warning`;
}

function recordFailure(report: GenerationReport, refusals: Refusals, path: string, e: unknown, consequence: string): void {
    if (e instanceof UnsafePathError && e.link !== undefined) {
        refusals.add(path, e);
    } else if (e instanceof RegionSyntaxError && !e.file.endsWith('(generated output)')) {
        report.errors.push({ file: path, line: e.line, message: `${e.detail}; ${consequence}` });
    } else if (e instanceof RegionSyntaxError) {
        throw e; // a generator bug, not a user problem
    } else {
        report.errors.push({ file: path, message: `${(e as Error).message}; ${consequence}` });
    }
}
