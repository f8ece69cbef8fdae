/**
 * Protected regions of generated C (docs/codegen.md "Protected regions"): `/*PROTECTED REGION ID(<id>) ENABLED START*\/`
 * ... `/*PROTECTED REGION END*\/`. The editable span of a region is the text strictly between the
 * end of its START marker and the beginning of its END marker (offsets into the file).
 */
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

// The same marker syntax as codegen's parser (packages/codegen/src/regions/markers.ts), which the
// server's guard uses: spaces inside the markers are tolerated there, so they must be here too.
const MARKERS = /\/\*\s*PROTECTED\s+REGION\s+ID\s*\(([^()\r\n]*)\)\s*(ENABLED\s+)?START\s*\*\/|\/\*\s*PROTECTED\s+REGION\s+END\s*\*\//g;

export function scanProtectedRegions(text: string): RegionScan {
  const regions: ProtectedRegion[] = [];
  const errors: RegionScan['errors'] = [];
  const seen = new Set<string>();
  let open: { id: string; enabled: boolean; start: number; at: number } | undefined;
  for (const m of text.matchAll(MARKERS)) {
    const at = m.index;
    if (m[1] === undefined) {
      if (!open) {
        errors.push({ offset: at, message: 'PROTECTED REGION END without a START' });
        continue;
      }
      regions.push({ id: open.id, enabled: open.enabled, start: open.start, end: at });
      open = undefined;
      continue;
    }
    const id = (m[1] ?? '').trim().replace(/additionnal/g, 'additional'); // as codegen's normaliseRegionId
    if (open) errors.push({ offset: at, message: `region ${id} starts inside region ${open.id} (nested START)` });
    if (seen.has(id)) errors.push({ offset: at, message: `duplicate region ID ${id}` });
    seen.add(id);
    open = { id, enabled: m[2] !== undefined, start: at + m[0].length, at };
  }
  if (open) errors.push({ offset: open.at, message: `region ${open.id} has no PROTECTED REGION END` });
  return { regions, errors };
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
