/**
 * The protected regions of a generated C file by line, to map gcc's errors to the region the user
 * edits. The markers are read by @contract-studio/conventions' scanRegions, as codegen merges them
 * and the IDE guards them (spaces inside markers, trimmed IDs, `additionnal` read as `additional`),
 * so a gcc error is placed in the same region the generator sees. A malformed file keeps the
 * regions that are well formed. Lines are 1-based; a region spans from its START marker line to
 * its END marker line.
 */
import { scanRegions } from '@contract-studio/conventions';

export interface ProtectedRegion {
  id: string;
  startLine: number;
  endLine: number;
}

export function findProtectedRegions(text: string): ProtectedRegion[] {
  return scanRegions(text).regions.map((r) => ({ id: r.id, startLine: r.line, endLine: r.endLine }));
}

/** The region containing `line`, if any (marker lines count as inside). */
export function regionAt(regions: readonly ProtectedRegion[], line: number): ProtectedRegion | null {
  for (const r of regions) if (line >= r.startLine && line <= r.endLine) return r;
  return null;
}
