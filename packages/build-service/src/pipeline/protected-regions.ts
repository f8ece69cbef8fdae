/**
 * Finds the protected regions of a generated C file:
 *   /*PROTECTED REGION ID(<id>) ENABLED START*\/ ... /*PROTECTED REGION END*\/
 * Lines are 1-based; a region spans from its START marker line to its END marker line.
 */
export interface ProtectedRegion {
  id: string;
  startLine: number;
  endLine: number;
}

const START = /\/\*\s*PROTECTED REGION ID\(\s*([^)]*?)\s*\)\s*(?:ENABLED\s+)?START\s*\*\//;
const END = /\/\*\s*PROTECTED REGION END\s*\*\//;

export function findProtectedRegions(text: string): ProtectedRegion[] {
  const regions: ProtectedRegion[] = [];
  let open: { id: string; startLine: number } | undefined;
  const lines = text.split('\n');
  for (let i = 0; i < lines.length; i++) {
    const line = lines[i] ?? '';
    const start = START.exec(line);
    if (start) {
      open = { id: start[1] ?? '', startLine: i + 1 };
      // START and END on the same line: an empty one-line region
      if (END.test(line.slice(start.index + start[0].length))) {
        regions.push({ ...open, endLine: i + 1 });
        open = undefined;
      }
      continue;
    }
    if (open && END.test(line)) {
      regions.push({ ...open, endLine: i + 1 });
      open = undefined;
    }
  }
  return regions;
}

/** The region containing `line`, if any (marker lines count as inside). */
export function regionAt(regions: readonly ProtectedRegion[], line: number): ProtectedRegion | null {
  for (const r of regions) if (line >= r.startLine && line <= r.endLine) return r;
  return null;
}
