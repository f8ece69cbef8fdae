/**
 * The errors of a failed simulator compile, told against the user's own files (docs/simulation.md
 * §3): gcc sees the simulator's copies in a temporary folder of the cache, which means nothing to
 * the user, so each diagnostic is read with the build service's parser
 * (`@contract-studio/build-service/gcc`: the text-format reader a build job falls back to; the
 * compile keeps gcc's text format, which any `$CC` writes, where `-fdiagnostics-format=json` is
 * gcc's alone) and placed in the project's src-gen: its path relative to src-gen (as a build job
 * reports a Cactal project's), the line in the user's file and the protected region it is in. The
 * folder's path appears nowhere.
 *
 * A common header's copy is the generated file with the user's regions carried over byte for byte:
 * when it is the user's file byte for byte, lines are the same; otherwise a line inside a carried
 * region is mapped through that region's START marker (both copies hold the same region text). A
 * line outside the regions of a copy that differs from the user's file (a src-gen older than the
 * model, or none) cannot be mapped: the diagnostic keeps the copy's line and says so.
 */
import { ARCHITECTURE_DIR } from '@contract-studio/conventions';
import {
    cutText, findProtectedRegions, LinkErrorReader, movedToRegion, parseGccTextLine, parseLinkerLine, regionAt, renderDiagnostic, type DiagnosticContext, type GccDiagnostic, type ProtectedRegion,
} from '@contract-studio/build-service/gcc';
import { readUserFile } from './user-file.js';
import type { SimSources } from './tables.js';

export interface CompileFailure {
    /**
     * gcc's diagnostics of every unit that failed, each once: files relative to the project's
     * src-gen (`generated/architecture/common/X.h`), lines of the user's files, the protected
     * region they are in; gcc's notes as children of the error they follow (as a build job's).
     */
    diagnostics: GccDiagnostic[];
    /** Output of a unit that gave no diagnostic (the compiler did not run, crashed...), the build folder's path taken out. */
    other: string[];
    /** 'link': the units compiled and the link failed (a function the user's code calls that nobody defines). */
    stage?: 'link';
}

/** Diagnostics told at most (the first errors are the ones to fix), and lines of other output. */
const MAX_DIAGNOSTICS = 50;
const MAX_OTHER_LINES = 20;
const MAX_OTHER_LINE_CHARS = 500;

/** One file of the simulator's build folder and the user's copy of it. */
interface Placed {
    /** Relative to src-gen; undefined for the simulator's own `sim_tables.c`. */
    userPath: string | undefined;
    simRegions: ProtectedRegion[];
    /** The user's file when it is read (undefined: none, unreadable). */
    userText: string | undefined;
    userRegions: ProtectedRegion[];
    /** The user's file is the copy compiled, byte for byte. */
    same: boolean;
}

class FilePlacer {
    private readonly files = new Map<string, Placed>();
    private readonly contents: Map<string, string>;

    constructor(private readonly src: SimSources) {
        this.contents = new Map(src.files.map((f) => [f.path, f.content]));
    }

    /** The placement of `rel` (a path of the build folder), or undefined when the simulator did not write it. */
    file(rel: string): Placed | undefined {
        const known = this.files.get(rel);
        if (known) return known;
        const content = this.contents.get(rel);
        if (content === undefined) return undefined;
        const userPath = rel === 'sim_tables.c' ? undefined : `${ARCHITECTURE_DIR}/${rel}`;
        // read only now, for a file an error points into: a build that compiles reads nothing more
        const userText = userPath && this.src.srcGen ? readUserFile(this.src.srcGen, userPath) : undefined;
        const placed: Placed = {
            userPath,
            simRegions: findProtectedRegions(content),
            userText,
            userRegions: userText === undefined ? [] : findProtectedRegions(userText),
            same: userText === content,
        };
        this.files.set(rel, placed);
        return placed;
    }

    /** `d` (its file relative to the build folder) told against the user's file. */
    place(d: GccDiagnostic): GccDiagnostic {
        const children = d.children.map((c) => this.place(c));
        if (d.file?.startsWith('/')) {
            // a header outside the build folder (the runtime's, the system's): its own path, not one under src-gen
            return { ...d, file: null, message: `${d.file}:${d.line ?? 0}:${d.column ?? 0}: ${d.message}`, protectedRegion: null, children };
        }
        const f = d.file === null ? undefined : this.file(d.file);
        if (!f || d.line === null) return { ...d, children };
        if (!f.userPath) {
            // a problem of the simulator's own table file: no file of the user's to name
            return { ...d, file: null, message: `sim_tables.c:${d.line}:${d.column ?? 0} (the simulator's own table file): ${d.message}`, protectedRegion: null, children };
        }
        if (f.same) return { ...d, file: f.userPath, protectedRegion: regionAt(f.userRegions, d.line), children };
        const inCopy = regionAt(f.simRegions, d.line);
        const mine = inCopy ? f.userRegions.find((r) => r.id === inCopy.id) : undefined;
        const moved = inCopy && mine && movedToRegion(d, inCopy, mine);
        if (moved) return { ...moved, file: f.userPath, children };
        const why = f.userText === undefined ? 'you have no readable copy of it' : 'your copy differs';
        return {
            ...d, file: f.userPath, protectedRegion: inCopy, children,
            message: `${d.message} (line ${d.line} of the file as the simulator generated it: ${why}; contract generate brings src-gen/ up to date)`,
        };
    }
}

/** `text` with every mention of the build folder taken out (relative paths remain). */
export function withoutFolder(text: string, work: string): string {
    return text.split(`${work}/`).join('').split(work).join('.');
}

/**
 * The diagnostics of the failed compiles: `outputs[i]` is what the compiler of `units[i]` wrote
 * (text format), in the build folder `work`.
 */
export function compileDiagnostics(outputs: readonly string[], work: string, src: SimSources): CompileFailure {
    const ctx: DiagnosticContext = { cwd: work, root: work, regions: new Map() };
    const placer = new FilePlacer(src);
    const seen = new Set<string>();
    const diagnostics: GccDiagnostic[] = [];
    const other: string[] = [];
    let left = 0;
    for (const output of outputs) {
        const mine: GccDiagnostic[] = [];
        for (const line of output.split('\n')) {
            // gcc's own lines start at the first column; its excerpt of the source (`   16 |   x oops;`) is indented
            if (!line || /^\s/.test(line)) continue;
            const d = parseGccTextLine(line, ctx);
            // a diagnostic is about a file of the build folder or a header outside it (the runtime's, the system's)
            if (!d || d.file === null || (!d.file.startsWith('/') && !placer.file(d.file))) continue;
            const placed = placer.place(d);
            // a note tells more about the error before it (as gcc's JSON nests it)
            const last = mine[mine.length - 1];
            if (placed.severity === 'note' && last) last.children.push(placed);
            else mine.push(placed);
        }
        for (const d of mine) {
            const key = JSON.stringify(d);
            if (seen.has(key)) continue; // a header's error, once for every unit that includes it
            seen.add(key);
            if (diagnostics.length < MAX_DIAGNOSTICS) diagnostics.push(d);
            else left++;
        }
        // no diagnostic: the compiler said something else (it did not start, it crashed): told as it is
        if (!mine.length) {
            for (const line of output.split('\n')) {
                if (line.trim() && other.length < MAX_OTHER_LINES) other.push(cutText(withoutFolder(line, work), MAX_OTHER_LINE_CHARS));
            }
        }
    }
    if (left) other.push(`(${left} more diagnostic(s) not shown)`);
    return { diagnostics, other };
}

/**
 * The errors of a failed link (`output`: what gcc and ld wrote), told against the user's files as
 * a compile's are: ld names the file and line from the units' debug information (the compile's
 * `-g1 -gdwarf-4`), the function the reference is in, and for a function defined twice, where it
 * was first defined (a note). ld's lines that name no file are told without the folder's path.
 */
export function linkDiagnostics(output: string, work: string, src: SimSources): CompileFailure {
    const ctx: DiagnosticContext = { cwd: work, root: work, regions: new Map() };
    const placer = new FilePlacer(src);
    const reader = new LinkErrorReader();
    const diagnostics: GccDiagnostic[] = [];
    const other: string[] = [];
    let left = 0;
    const told = (d: GccDiagnostic): GccDiagnostic => {
        if (d.file !== null && !d.file.startsWith('/') && placer.file(d.file)) return placer.place(d);
        // no place, or a file the simulator did not write (the runtime's): without the folder's path
        const where = d.file === null ? '' : `${withoutFolder(d.file, work)}:${d.line ?? 0}: `;
        return { ...d, file: null, line: null, column: null, protectedRegion: null, message: withoutFolder(`${where}${d.message}`, work), children: d.children.map(told) };
    };
    for (const line of output.split('\n')) {
        if (!line.trim() || line.startsWith('collect2: ')) continue;
        const ld = parseLinkerLine(line, ctx);
        const error = reader.read(ld);
        if (!ld && other.length < MAX_OTHER_LINES) other.push(cutText(withoutFolder(line, work), MAX_OTHER_LINE_CHARS));
        if (!error) continue;
        const d = told(error);
        if (!reader.first(JSON.stringify(d))) continue; // ld tells a reference again for every use in the function
        if (diagnostics.length < MAX_DIAGNOSTICS) diagnostics.push(d);
        else left++;
    }
    if (left) other.push(`(${left} more diagnostic(s) not shown)`);
    return { diagnostics, other, stage: 'link' };
}

/** The errors a failure counts (gcc's top-level errors; every other failure counts as one). */
export function errorCount(failure: CompileFailure): number {
    return failure.diagnostics.filter((d) => d.severity === 'error').length;
}

/** A compile failure in one message (the IDE's answer, library users): each diagnostic on a line of its own, at its src-gen path. */
export function describeCompileFailure(failure: CompileFailure): string {
    const errors = errorCount(failure);
    const lines = failure.diagnostics.map((d) => renderDiagnostic(d.file === null ? d : { ...d, file: `src-gen/${d.file}` }));
    return [`cannot ${failure.stage === 'link' ? 'link' : 'compile'} the project's C for the simulator${errors ? ` (${errors} error(s) in src-gen/)` : ''}:`, ...lines, ...failure.other].join('\n');
}
