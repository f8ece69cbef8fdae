/**
 * The server-side guard of generated C (docs/codegen.md "Protected regions", docs/ide.md "Using it"): a save of a generated file may change the
 * content of its protected regions, never the generated code around them. Pure decision on texts;
 * the region parser is codegen's `parseRegions` (passed in, see integrations.ts).
 *
 * Texts are byte strings (each char = one byte, 'latin1'), so that a merge keeps the bytes of the
 * file on disk and of the incoming regions exactly, whatever their encoding.
 */
import type { Region } from '@contract-studio/codegen';

/** A protected region as codegen's parser returns it (type only: codegen is loaded lazily). */
export type GuardRegion = Region;

/** codegen's parseRegions and RegionSyntaxError (see integrations.ts: loadRegionParser). */
export interface RegionParser {
  parseRegions(text: string, file: string): { regions: GuardRegion[] };
  RegionSyntaxError: new (file: string, line: number, detail: string) => Error & { file: string; line: number; detail: string };
}

export type GuardDecision =
  /** Write the incoming text as it is (only region content changed, or the disk file was malformed). */
  | { kind: 'write'; text: string }
  /** The generated code differs from the disk's: write the disk text with the incoming regions in it. */
  | { kind: 'merge'; text: string; reason: string }
  /** Nothing may be written. */
  | { kind: 'refuse'; message: string; region?: string; line?: number };

export const MERGE_REASON =
  'the generated code outside the protected regions changed on disk (Generate All) or was edited: your regions were kept and the file reloaded';
export const WHOLE_FILE_REASON = 'generated whole: edit the .contract model instead (this file has no protected region)';

/** Text outside the regions + the sequence of region IDs: equal skeletons = only region content differs. */
function sameSkeleton(a: string, ra: GuardRegion[], b: string, rb: GuardRegion[]): boolean {
  if (ra.length !== rb.length) return false;
  let pa = 0;
  let pb = 0;
  for (let i = 0; i < ra.length; i++) {
    const x = ra[i]!;
    const y = rb[i]!;
    if (x.id !== y.id || a.slice(pa, x.start) !== b.slice(pb, y.start)) return false;
    pa = x.end;
    pb = y.end;
  }
  return a.slice(pa) === b.slice(pb);
}

/** The disk text with the content (and ENABLED flag) of each region replaced by the incoming one of the same ID. */
function mergeInto(disk: string, diskRegions: GuardRegion[], incoming: string, incomingRegions: GuardRegion[]): string {
  const byId = new Map(incomingRegions.map((r) => [r.id, r]));
  let out = '';
  let pos = 0;
  for (const r of diskRegions) {
    const mine = byId.get(r.id);
    out += disk.slice(pos, r.start);
    if (!mine) out += disk.slice(r.start, r.end);
    else {
      const startMarker = mine.enabled === r.enabled ? disk.slice(r.start, r.contentStart) : incoming.slice(mine.start, mine.contentStart);
      out += startMarker + mine.content + disk.slice(r.contentEnd, r.end);
    }
    pos = r.end;
  }
  return out + disk.slice(pos);
}

/**
 * Decides what a save of generated file `file` writes, given the incoming text and the file on
 * disk (both byte strings):
 * - same text, or same generated code around the regions -> write the incoming text;
 * - malformed incoming text (START without END, nested, duplicate ID) -> refuse, with its line;
 * - a disk file without regions (generated whole) -> refuse any change;
 * - a malformed disk file -> write the (well-formed) incoming text: it repairs the file;
 * - an incoming region whose ID is not on disk any more -> refuse, naming it;
 * - otherwise -> merge the incoming regions into the disk text.
 */
export function guardGeneratedWrite(incoming: string, disk: string, file: string, parser: RegionParser): GuardDecision {
  if (incoming === disk) return { kind: 'write', text: incoming };
  let mine: GuardRegion[];
  try {
    mine = parser.parseRegions(incoming, file).regions;
  } catch (e) {
    if (!(e instanceof parser.RegionSyntaxError)) throw e;
    return { kind: 'refuse', message: `${e.message} — nothing was written`, line: e.line };
  }
  let theirs: GuardRegion[];
  try {
    theirs = parser.parseRegions(disk, file).regions;
  } catch (e) {
    if (!(e instanceof parser.RegionSyntaxError)) throw e;
    return { kind: 'write', text: incoming };
  }
  if (theirs.length === 0) return { kind: 'refuse', message: `${file}: ${WHOLE_FILE_REASON}` };
  if (sameSkeleton(incoming, mine, disk, theirs)) return { kind: 'write', text: incoming };
  const onDisk = new Set(theirs.map((r) => r.id));
  const gone = mine.find((r) => !onDisk.has(r.id));
  if (gone) {
    return {
      kind: 'refuse',
      region: gone.id,
      line: gone.line,
      message: `${file}:${gone.line}: protected region '${gone.id}' no longer exists in the file on disk (Generate All removed it: ` +
        'its port or entity left the model; code it held on disk went to src-gen/orphans/) — nothing was written',
    };
  }
  return { kind: 'merge', text: mergeInto(disk, theirs, incoming, mine), reason: MERGE_REASON };
}
