/**
 * Where a module crashed: the runtime's crash report (runtime/src/crash_report.c), one block a
 * crashed module writes on its stderr, read from the run's output, and the frames it names mapped
 * to function, file and line by addr2line on the module's executable (built with -g) after the run.
 *
 *   ==contract-crash== module EST signal 11 SIGSEGV addr 0x0
 *   ==contract-crash== build-id 87975f83592c177c758e701ac13508592189f578
 *   ==contract-crash== frame 0 exe 0x40d8
 *   ==contract-crash== frame 1 libc.so.6 0x2724a
 *   ==contract-crash== end 2 frames
 *
 * The block is a module's output: anything may be written in its place. Only the exact format is
 * read, each line bounded; a block counts only when the module that wrote it (the launcher's tag)
 * is the module it names, its frames numbered from 0 without a gap, at most MAX_FRAMES, and its end
 * line counts them; the last whole block of a module (the crash handler writes its block just
 * before the process dies: one the module's code printed before does not stand for it), of
 * MAX_MODULES modules at most. What it
 * names is never run: the executable addr2line reads is the one the service knows for the module,
 * and only offsets (numbers) are passed to it.
 */
import { posix } from 'node:path';
import { crashSignalMeaning } from '@contract-studio/conventions';
import { crashFrameTexts } from './crash-frames.js';
import { located, relativeToRoot, type DiagnosticContext, type GccDiagnostic } from './gcc-diagnostics.js';

export const CRASH_MARK = '==contract-crash==';
/** Frames of a block, at most (the runtime writes 48 at most). */
export const MAX_FRAMES = 48;
/** Modules whose blocks are kept, at most. */
const MAX_MODULES = 64;
/** Characters of addr2line's output read, at most. */
export const MAX_ADDR2LINE_CHARS = 256 * 1024;

const HEAD = /^==contract-crash== module ([A-Za-z_]\w{0,63}) signal (\d{1,2}) (SIG[A-Z]{2,6}|\?) addr 0x([0-9a-f]{1,16})$/;
const FRAME = /^==contract-crash== frame (\d{1,2}) (exe|\?|[A-Za-z0-9_.+-]{1,47}) 0x([0-9a-f]{1,16})$/;
const END = /^==contract-crash== end (\d{1,2}) frames$/;
/** The executable's build-id (GNU ld's NT_GNU_BUILD_ID, hex), right after the head when it has one. */
const BUILD_ID = /^==contract-crash== build-id ((?:[0-9a-f]{2}){1,64})$/;
/** The longest line of a block (a longer one is not the runtime's). */
const MAX_LINE = 160;

export interface CrashFrame {
  /** `exe`: the module's executable (its code and the runtime linked in); else a library's file name, or `?`. */
  object: string;
  /** Offset in that object (hex digits), or the address itself for `?`. */
  offset: bigint;
}

export interface CrashReport {
  module: string;
  signal: number;
  signalName: string;
  /** si_addr, hex digits. */
  address: string;
  /** The crashed executable's build-id (hex digits), when it has one. */
  buildId?: string;
  frames: CrashFrame[];
}

/** One place of a frame as addr2line tells it (several for a frame in inlined code, innermost first). */
export interface CrashPlace {
  function: string;
  /** As addr2line prints it (absolute inside the sandbox), null when it does not know. */
  file: string | null;
  line: number | null;
}

export class CrashReports {
  private readonly done = new Map<string, CrashReport>();
  private readonly open = new Map<string, CrashReport>();

  /** A line of the run's output, without its tag; `source`: the module the launcher tagged it with. */
  line(text: string, source: string): void {
    if (!text.startsWith(CRASH_MARK) || text.length > MAX_LINE) return;
    const head = HEAD.exec(text);
    if (head) {
      // a module names itself only; a second head starts the block anew (a whole one read before
      // stays until this one is whole: the crash handler's block is the last the module writes)
      const known = this.open.has(source) || this.done.has(source);
      if (head[1] !== source || (!known && this.open.size + this.done.size >= MAX_MODULES)) return;
      this.open.set(source, { module: source, signal: Number(head[2]), signalName: head[3]!, address: head[4]!, frames: [] });
      return;
    }
    const report = this.open.get(source);
    if (!report) return;
    const id = report.frames.length === 0 && report.buildId === undefined ? BUILD_ID.exec(text) : null;
    if (id) {
      report.buildId = id[1]!;
      return;
    }
    const frame = FRAME.exec(text);
    if (frame) {
      if (Number(frame[1]) !== report.frames.length || report.frames.length >= MAX_FRAMES) this.open.delete(source);
      else report.frames.push({ object: frame[2]!, offset: BigInt(`0x${frame[3]!}`) });
      return;
    }
    const end = END.exec(text);
    this.open.delete(source);
    if (end && Number(end[1]) === report.frames.length && report.frames.length) this.done.set(source, report);
  }

  /** The last whole block `module` wrote, if it wrote one. */
  of(module: string): CrashReport | undefined {
    return this.done.get(module);
  }
}

/**
 * addr2line's arguments for the frames of `report` in the executable (-a: each address's places
 * follow it; -f: function names; -i: inlined functions too): a caller's frame is a return address,
 * its call the byte before; frame 0 is the instruction that faulted. Empty when none is in it.
 */
export function addr2lineArgs(report: CrashReport, executable: string): string[] {
  const offsets = report.frames.flatMap((f, i) => (f.object === 'exe' ? [`0x${(i === 0 ? f.offset : f.offset - 1n).toString(16)}`] : []));
  return offsets.length ? ['addr2line', '-a', '-f', '-i', '-e', executable, ...offsets] : [];
}

const ADDRESS_LINE = /^0x[0-9a-f]{1,16}$/;
const PLACE_LINE = /^(.{1,4096}):(\d{1,9}|\?)(?: \(discriminator \d+\))?$/;

/**
 * addr2line's output (-a -f -i) for the offsets addr2lineArgs passed: the places of each, in their
 * order; a frame whose places cannot be read has none. Bounded by MAX_ADDR2LINE_CHARS.
 */
export function parseAddr2line(output: string): CrashPlace[][] {
  const lines = output.slice(0, MAX_ADDR2LINE_CHARS).split('\n');
  const frames: CrashPlace[][] = [];
  let i = 0;
  while (i < lines.length) {
    if (!ADDRESS_LINE.test(lines[i]!)) { i++; continue; }
    const places: CrashPlace[] = [];
    i++;
    while (i + 1 < lines.length && !ADDRESS_LINE.test(lines[i]!)) {
      const fn = lines[i]!;
      const at = PLACE_LINE.exec(lines[i + 1]!);
      i += 2;
      if (!at) continue;
      const known = at[1] !== '??';
      places.push({ function: fn === '??' ? '?' : fn.slice(0, 200), file: known ? at[1]! : null, line: known && at[2] !== '?' && at[2] !== '0' ? Number(at[2]) : null });
    }
    frames.push(places);
  }
  return frames;
}

/**
 * A file of the runtime's sources compiled into the module (`runtime/src/core.c`), null for any
 * other: under the runtime as the sandbox sees it (the image's, built in place), or in a folder of
 * the service's runtime cache, where it was built (`runtime-<key>`, `.building-<key>-<pid>-<r>`:
 * its debug information names the folder it was compiled in).
 */
function runtimeFile(file: string, cwd: string, runtimeDir: string): string | null {
  const abs = posix.resolve(cwd, file);
  const rel = posix.relative(runtimeDir, abs);
  if (!rel.startsWith('..') && !posix.isAbsolute(rel)) return posix.join('runtime', rel);
  const cached = RUNTIME_CACHE_FILE.exec(abs);
  return cached ? posix.join('runtime', cached[1]!) : null;
}

const RUNTIME_CACHE_FILE = /\/(?:runtime-[0-9a-f]{16}|\.building-[0-9a-f]{16}-\d{1,10}-[0-9a-f]{8})\/((?:src|include|launcher)\/.{1,400})$/;

/** The job's log line that tells a module's crash site (read back by the CLI: crashSiteOfLine). */
export function crashSiteLine(module: string, site: CrashSite): string {
  return `${module} crashed${site.said}`;
}

const CRASH_SITE_LINE = /^([A-Za-z_]\w{0,63}) crashed( at .{1,2000}| in the runtime, .{1,2000})$/;

/** The module and its site (` at FILE:LINE ...`) of a crashSiteLine, undefined for any other line. */
export function crashSiteOfLine(line: string): { module: string; said: string } | undefined {
  const m = line.length <= 4200 ? CRASH_SITE_LINE.exec(line) : null;
  return m ? { module: m[1]!, said: m[2]! } : undefined;
}

/** Where a crash happened, told as a place of the project (or of the runtime when the crash is in it). */
export interface CrashSite {
  /** ` at src-gen/generated/.../module.c:248 in its protected region protect_exec_EST (est_update)`. */
  said: string;
  /** The Problems panel's error at that line (a place of the project only), `origin: 'run'`, its message ending with what the signal means (`: an integer division by zero ...`). */
  diagnostic: GccDiagnostic | null;
  /** Each frame, as said with --verbose (crash-frames.ts): `#0 est_update at src-gen/...:248`, a frame in inlined code one line. */
  frames: string[];
}

/**
 * The first place in the project's code (its files under the tree root, not the runtime's): the
 * crash site; else the first place in the runtime's files (`in the runtime, at ...`); null when no
 * place is known. `treeRoot`: the tree root as the project names it (`src-gen`), `runtimeDir`: the
 * runtime as the sandbox sees it.
 */
export function crashSite(report: CrashReport, places: CrashPlace[][], ctx: DiagnosticContext, treeRoot: string, runtimeDir: string): CrashSite | null {
  const shown = (file: string): string => posix.join(treeRoot, file);
  let project: { place: CrashPlace; d: GccDiagnostic } | undefined;
  let runtime: CrashPlace | undefined;
  // each place's file: the project's as the project names it, the runtime's as the runtime's, else as compiled
  const where = (p: CrashPlace & { file: string }): string => {
    const d = located({ severity: 'error', message: '', line: p.line, column: null, children: [] }, p.file, ctx);
    const inRuntime = runtimeFile(p.file, ctx.cwd, runtimeDir);
    const ours = relativeToRoot(p.file, ctx) !== null && inRuntime === null;
    if (ours && p.line !== null && !project) project = { place: p, d };
    else if (!ours && inRuntime !== null && p.line !== null && !runtime) runtime = p;
    return `${ours ? shown(d.file!) : inRuntime ?? p.file}:${p.line ?? '?'}`;
  };
  const told = crashFrameTexts(report, places, where);
  if (project) {
    const { place, d } = project;
    const region = d.protectedRegion ? ` in its protected region ${d.protectedRegion.id}` : '';
    const said = ` at ${shown(d.file!)}:${d.line}${region} (${place.function})`;
    const message = `${report.module} crashed here: signal ${report.signal} (${report.signalName})${report.signal === 11 || report.signal === 7 ? ` at address 0x${report.address}` : ''}, in ${place.function}`;
    const meaning = crashSignalMeaning(report.signal);
    // no compiler's diagnostic: the run's (the Problems panel labels it `run`)
    return { said, diagnostic: { ...d, message: message + d.message + (meaning ? `: ${meaning}` : ''), origin: 'run' }, frames: told };
  }
  if (runtime) {
    const rel = runtimeFile(runtime.file!, ctx.cwd, runtimeDir)!;
    return { said: ` in the runtime, at ${rel}:${runtime.line} (${runtime.function}): no frame of the project's code was found`, diagnostic: null, frames: told };
  }
  return null;
}
