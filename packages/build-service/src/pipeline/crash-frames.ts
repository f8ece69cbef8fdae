/**
 * A crash report's frames as text, the one form `contract run --verbose` (the job's
 * `M crash frame ...` lines, crash-reports.ts crashSite) and `contract trace` (the logs' crash
 * files, crash-files.ts) both print: `#0 est_update at FILE:248`; a frame in inlined code is one
 * line, its innermost place first, then each function it is inlined into, at the call
 * (`#1 _exec at FILE:132 (inlined into ModuleMain at FILE:133)`: addr2line -i's places of one
 * address); a place whose file is not known `at ?`; a frame not mapped, its object and offset (`#2 the executable+0x40d8`, `#3 libc.so.6+0x2724a`).
 */
import { crashSignalMeaning } from '@contract-studio/conventions';
import type { CrashPlace, CrashReport } from './crash-reports.js';

/**
 * A report's head, with what its signal means (conventions' crash-signals.ts): `EST crashed: signal
 * 11 (SIGSEGV) at address 0x0 (a bad pointer: NULL, freed, or past the end of an array), executable build-id 8797…`.
 */
export function crashHeadText(report: CrashReport): string {
  const addr = report.signal === 11 || report.signal === 7 ? ` at address 0x${report.address}` : '';
  const meaning = crashSignalMeaning(report.signal);
  return `${report.module} crashed: signal ${report.signal} (${report.signalName})${addr}${meaning ? ` (${meaning})` : ''}${report.buildId ? `, executable build-id ${report.buildId}` : ''}`;
}

/** How a caller shows the file and line of a place whose file is known (`src-gen/.../module.c:248`). */
export type PlaceWhere = (place: CrashPlace & { file: string }) => string;

/** `FILE:LINE` as addr2line tells it (`?` for a line it does not know). */
export const placeAsTold: PlaceWhere = (p) => `${p.file}:${p.line ?? '?'}`;

/**
 * Each frame of `report` as one text (without indent): mapped with `places` (addr2line's places of
 * each frame in the executable, in order; null or empty: not mapped), each place's file shown by `where`.
 */
export function crashFrameTexts(report: CrashReport, places: readonly (readonly CrashPlace[])[] | null, where: PlaceWhere = placeAsTold): string[] {
  let exeIndex = 0;
  return report.frames.map((f, i) => {
    const at = f.object === 'exe' && places ? places[exeIndex] ?? [] : [];
    if (f.object === 'exe') exeIndex++;
    if (!at.length) return `#${i} ${f.object === 'exe' ? 'the executable' : f.object}+0x${f.offset.toString(16)}`;
    const told = at.map((p) => `${p.function} at ${p.file === null ? '?' : where({ ...p, file: p.file })}`);
    return `#${i} ${told[0]}${told.length > 1 ? ` (inlined into ${told.slice(1).join(', inlined into ')})` : ''}`;
  });
}
