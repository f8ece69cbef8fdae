/**
 * Protected regions of generated C (docs/codegen.md "Protected regions"): `/*PROTECTED REGION ID(<id>) ENABLED START*\/`
 * ... `/*PROTECTED REGION END*\/`. The editable span of a region is the text strictly between the
 * end of its START marker and the beginning of its END marker (offsets into the file). The one
 * reading of the markers is @contract-studio/conventions' scanRegions (codegen and the server's
 * guard use it too), so a region the server accepts is never read-only here.
 */
import { scanRegions } from '@contract-studio/conventions';

export interface ProtectedRegion {
  id: string;
  enabled: boolean;
  /** Offset just after the START marker. */
  start: number;
  /** Offset of the END marker. */
  end: number;
}

export interface RegionScan {
  regions: ProtectedRegion[];
  /** Malformed structure (START without END, nested START, END without START, duplicate ID). */
  errors: Array<{ offset: number; message: string }>;
}

/** The regions and structural errors of a generated file, read as codegen and the server's guard read them. */
export function scanProtectedRegions(text: string): RegionScan {
  const scan = scanRegions(text);
  return {
    regions: scan.regions.map((r) => ({ id: r.id, enabled: r.enabled, start: r.contentStart, end: r.contentEnd })),
    errors: scan.errors.map((e) => ({ offset: e.offset, message: e.message })),
  };
}

/** True when every [start, end) offset range lies within one region's editable span. */
export function editsAllowed(regions: ProtectedRegion[], ranges: Array<{ start: number; end: number }>): boolean {
  return ranges.every((r) => regions.some((g) => r.start >= g.start && r.end <= g.end));
}

/**
 * The text outside the regions, used to prove a save kept the generated skeleton: equal
 * skeletons before and after mean only protected content changed.
 */
export function skeletonOf(text: string, regions = scanProtectedRegions(text).regions): string {
  let out = '';
  let pos = 0;
  for (const r of regions) {
    out += text.slice(pos, r.start) + '\u0000';
    pos = r.end;
  }
  return out + text.slice(pos);
}
