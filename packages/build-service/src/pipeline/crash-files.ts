/**
 * The crash files of a run's logs folder (docs/runtime-api.md "Crash file"): `<MODULE>.crash`, the
 * crash report a crashed module wrote, saved by contract-launch. Read by `contract trace LOGDIR`,
 * which tells each crash site without the build service (logs brought back from a robot).
 *
 * Everything read from the folder is hostile: a file counts only when it is a regular file (no
 * link followed) named `<MODULE>.crash`, MAX_CRASH_FILE_BYTES at most, holding one whole report in
 * the exact format that names that module (CrashReports). The frames are mapped only in the
 * module's executable where the generated Makefile builds it beside the default logs folder
 * (`LOGDIR/../modules/<M>_mod/<M>`), never a path the file names, and only when its ELF build-id
 * is the one the report names (a rebuilt executable is not the one that crashed): addr2line is
 * run without a shell, with hex offsets only, bounded in time and output.
 */
import { execFile } from 'node:child_process';
import { constants, lstatSync, promises as fsp } from 'node:fs';
import { isAbsolute, join, relative, resolve } from 'node:path';
import { SRC_GEN_ARCHITECTURE_DIR } from '@contract-studio/conventions';
import { crashFrameTexts, crashHeadText, placeAsTold, type PlaceWhere } from './crash-frames.js';
import { addr2lineArgs, CrashReports, MAX_ADDR2LINE_CHARS, parseAddr2line, type CrashReport } from './crash-reports.js';

/** A crash file's bytes, at most (the runtime's block: 51 lines of 160 characters at most). */
export const MAX_CRASH_FILE_BYTES = 32 * 1024;
/** Crash files read in one folder, at most. */
export const MAX_CRASH_FILES = 16;
/** addr2line's time, at most. */
const ADDR2LINE_TIMEOUT_MS = 10_000;
/** Bytes of an executable's headers and notes read to find its build-id, at most. */
const ELF_READ_MAX = 64 * 1024;
const CRASH_FILE_NAME = /^([A-Za-z_]\w{0,63})\.crash$/;

/** The module a crash file's name names (`EST.crash`: EST), undefined for any other name. */
export function crashFileModule(name: string): string | undefined {
  return CRASH_FILE_NAME.exec(name)?.[1];
}

/** What a logs folder's crash file tells. */
export interface CrashFileSite {
  module: string;
  report: CrashReport;
  /** The lines to print, without their end of line. */
  lines: string[];
}

/** The contents of a regular file (no link followed) up to `max` bytes; null when it is not one or is longer. */
async function readBounded(path: string, max: number): Promise<Buffer | null> {
  let fh: fsp.FileHandle | undefined;
  try {
    fh = await fsp.open(path, constants.O_RDONLY | constants.O_NOFOLLOW | constants.O_NONBLOCK);
    const st = await fh.stat();
    if (!st.isFile() || st.size > max) return null;
    const buf = Buffer.alloc(max + 1);
    const { bytesRead } = await fh.read(buf, 0, max + 1, 0);
    return bytesRead > max ? null : buf.subarray(0, bytesRead);
  } catch {
    return null;
  } finally {
    await fh?.close().catch(() => {});
  }
}

/** The report a crash file holds for `module`, in the exact format, else undefined. */
export function crashReportOfFile(text: string, module: string): CrashReport | undefined {
  const reports = new CrashReports();
  for (const line of text.split('\n')) reports.line(line, module);
  return reports.of(module);
}

/**
 * The GNU build-id (NT_GNU_BUILD_ID, hex) of an ELF file (64 or 32 bits, little- or big-endian)
 * from its program headers' PT_NOTE segments, reading ELF_READ_MAX bytes at most; null when it has
 * none or is no ELF file.
 */
export async function elfBuildId(path: string): Promise<string | null> {
  const buf = await readHead(path, ELF_READ_MAX);
  if (!buf || buf.length < 52 || buf.readUInt32BE(0) !== 0x7f454c46) return null;
  const is64 = buf[4] === 2;
  const le = buf[5] === 1;
  const u16 = (o: number): number => (le ? buf.readUInt16LE(o) : buf.readUInt16BE(o));
  const u32 = (o: number): number => (le ? buf.readUInt32LE(o) : buf.readUInt32BE(o));
  const word = (o: number): number => (is64 ? Number(le ? buf.readBigUInt64LE(o) : buf.readBigUInt64BE(o)) : u32(o));
  if (is64 && buf.length < 64) return null;
  const phoff = word(is64 ? 32 : 28);
  const phentsize = u16(is64 ? 54 : 42);
  const phnum = u16(is64 ? 56 : 44);
  for (let i = 0; i < phnum && i < 64; i++) {
    const ph = phoff + i * phentsize;
    if (ph + (is64 ? 56 : 32) > buf.length) return null;
    if (u32(ph) !== 4 /* PT_NOTE */) continue;
    const offset = word(ph + (is64 ? 8 : 4));
    const size = word(ph + (is64 ? 32 : 16));
    let p = offset;
    const end = Math.min(offset + size, buf.length);
    while (p + 12 <= end) {
      const namesz = u32(p), descsz = u32(p + 4), type = u32(p + 8);
      const desc = p + 12 + ((namesz + 3) & ~3);
      if (desc + descsz > end) break;
      if (type === 3 /* NT_GNU_BUILD_ID */ && namesz === 4 && buf.toString('latin1', p + 12, p + 15) === 'GNU' && descsz > 0 && descsz <= 64) {
        return buf.subarray(desc, desc + descsz).toString('hex');
      }
      p = desc + ((descsz + 3) & ~3);
    }
  }
  return null;
}

async function readHead(path: string, max: number): Promise<Buffer | null> {
  let fh: fsp.FileHandle | undefined;
  try {
    fh = await fsp.open(path, constants.O_RDONLY | constants.O_NOFOLLOW | constants.O_NONBLOCK);
    if (!(await fh.stat()).isFile()) return null;
    const buf = Buffer.alloc(max);
    const { bytesRead } = await fh.read(buf, 0, max, 0);
    return buf.subarray(0, bytesRead);
  } catch {
    return null;
  } finally {
    await fh?.close().catch(() => {});
  }
}

/** addr2line's output for `argv` (from addr2lineArgs), no shell; null when it fails. */
function runAddr2line(argv: string[]): Promise<string | null> {
  return new Promise((resolve) => {
    execFile(argv[0]!, argv.slice(1), { timeout: ADDR2LINE_TIMEOUT_MS, maxBuffer: MAX_ADDR2LINE_CHARS, encoding: 'utf8', env: { PATH: '/usr/local/bin:/usr/bin:/bin', LC_ALL: 'C' } }, (err, out) => resolve(err ? null : out));
  });
}

/** The module's executable as the generated Makefile builds it beside the default logs folder. */
export function executableBesideLogs(logDir: string, module: string): string {
  return join(logDir, '..', 'modules', `${module}_mod`, module);
}

/**
 * What a report says: its head, then each frame (crash-frames.ts, the form `contract run --verbose`
 * prints too) mapped (`#0 est_update at FILE:248`, a frame in inlined code as one line: `#1 _exec
 * at FILE:132 (inlined into ModuleMain at FILE:133)`) when `places` are given, else its raw offsets
 * and the addr2line command that maps them (`why`: why they are not mapped). `executable`: the one
 * that crashed (its build-id the report's), named in that command; null when none was found, the
 * command then naming where the build puts it (`ARCH/modules/M_mod/M`), never a path that is not
 * that executable. `where`: how a place's file is shown (placesBesideLogs).
 */
export function crashSiteLines(report: CrashReport, executable: string | null, places: ReturnType<typeof parseAddr2line> | null, why: string, where: PlaceWhere = placeAsTold): string[] {
  const lines = [crashHeadText(report)];
  lines.push(...crashFrameTexts(report, places, where).map((t) => `  ${t}`));
  if (!places) {
    const exe = executable ?? `ARCH/modules/${report.module}_mod/${report.module}`;
    const argv = addr2lineArgs(report, exe);
    lines.push(`  not mapped to the code: ${why}`);
    if (argv.length) {
      lines.push(executable !== null
        ? `  map them with the executable that crashed: ${['addr2line', '-f', '-i', '-e', exe, ...argv.slice(6)].join(' ')} (each caller's return address less 1: its call)`
        : `  map them with ${report.module}'s executable of the build that crashed${report.buildId ? ` (its build-id must be ${report.buildId}: \`readelf -n\` shows it)` : ''}: ${['addr2line', '-f', '-i', '-e', exe, ...argv.slice(6)].join(' ')} ` +
          `(ARCH: the generated architecture folder it was built in, a project's src-gen/generated/architecture; each caller's return address less 1: its call)`);
    }
  }
  return lines;
}

/**
 * How the places of an executable beside `logDir` are shown, as `contract run` shows them: when the
 * logs folder is the generated architecture's own (`PROJECT/src-gen/generated/architecture/logs`,
 * `make run`'s default), a file of the project as the project names it
 * (`src-gen/generated/architecture/modules/M_mod/module.c:248`); a file of the runtime it was built
 * with (`RUNTIME/src/F`, where RUNTIME holds `include/libmodule/libmodule.h`, as the generated
 * Makefile's CONTRACT_RUNTIME must) as `runtime/src/F`; any other (or a relative path) as addr2line
 * tells it.
 */
export function placesBesideLogs(logDir: string): PlaceWhere {
  const arch = resolve(logDir, '..');
  const suffix = `/${SRC_GEN_ARCHITECTURE_DIR}`;
  const project = arch.endsWith(suffix) ? arch.slice(0, -suffix.length) || '/' : null;
  const runtimes = new Map<string, boolean>();
  const isRuntime = (dir: string): boolean => {
    let known = runtimes.get(dir);
    if (known === undefined) runtimes.set(dir, (known = runtimes.size < 16 && isRegularFile(join(dir, RUNTIME_HEADER))));
    return known;
  };
  return (p) => {
    if (!isAbsolute(p.file)) return placeAsTold(p);
    const rel = project === null ? '' : relative(project, p.file);
    if (rel && !rel.startsWith('..') && !isAbsolute(rel)) return `${rel}:${p.line ?? '?'}`;
    const inRuntime = RUNTIME_SOURCE.exec(p.file);
    return inRuntime && isRuntime(inRuntime[1]!) ? `runtime/${inRuntime[2]}:${p.line ?? '?'}` : placeAsTold(p);
  };
}

/** The runtime's header, which the generated Makefile checks its CONTRACT_RUNTIME by. */
const RUNTIME_HEADER = 'include/libmodule/libmodule.h';
const RUNTIME_SOURCE = /^(\/.{0,4000}?)\/((?:src|include|launcher)\/[^/]{1,255})$/;

function isRegularFile(path: string): boolean {
  try {
    return lstatSync(path).isFile();
  } catch {
    return false;
  }
}

/**
 * The crash files of `logDir`, each told (crashSiteLines), in module order; `problems` gets a line
 * for each file named like one that is not read. Never throws.
 */
export async function readCrashFiles(logDir: string, problems: string[] = []): Promise<CrashFileSite[]> {
  const names = (await fsp.readdir(logDir).catch(() => [] as string[])).filter((n) => n.endsWith('.crash')).sort();
  const sites: CrashFileSite[] = [];
  for (const name of names) {
    const m = CRASH_FILE_NAME.exec(name);
    if (!m) { problems.push(`${name}: not a crash file's name (MODULE.crash): not read`); continue; }
    if (sites.length >= MAX_CRASH_FILES) { problems.push(`${name}: more than ${MAX_CRASH_FILES} crash files: not read`); continue; }
    const module = m[1]!;
    const bytes = await readBounded(join(logDir, name), MAX_CRASH_FILE_BYTES);
    const report = bytes ? crashReportOfFile(bytes.toString('latin1'), module) : undefined;
    if (!report) { problems.push(`${name}: not a regular file of at most ${MAX_CRASH_FILE_BYTES} bytes holding one crash report of ${module}: not read`); continue; }
    const exe = executableBesideLogs(logDir, module);
    const id = await elfBuildId(exe);
    let places: ReturnType<typeof parseAddr2line> | null = null;
    let why: string;
    let crashed: string | null = null;
    if (id === null) why = (await fsp.lstat(exe).then(() => true, () => false))
      ? `${exe} has no build-id: not an executable the build made`
      : `no executable of ${module} at ${exe} (looked for beside the logs folder, where the generated Makefile builds it: a logs folder copied elsewhere has none there)`;
    else if (!report.buildId) why = `the report names no build-id: ${exe} may not be the executable that crashed`;
    else if (id !== report.buildId) why = `${exe} is another build (build-id ${id}), not the executable that crashed`;
    else {
      crashed = exe;
      const argv = addr2lineArgs(report, exe);
      const out = argv.length ? await runAddr2line(argv) : null;
      places = out === null ? null : parseAddr2line(out);
      why = argv.length ? 'addr2line failed' : 'no frame in the executable';
    }
    sites.push({ module, report, lines: crashSiteLines(report, crashed, places, why, placesBesideLogs(logDir)) });
  }
  return sites;
}
