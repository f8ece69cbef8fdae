/**
 * A minimal reader of the tar archives the Docker Engine's archive API returns (ustar, with PAX
 * `x` and GNU `L` long names). It only reports entries: name, kind, size and, for regular files,
 * the bytes. Links are reported as links and never resolved. An incomplete trailing entry (an
 * archive cut at a size bound) ends the listing instead of failing.
 */
export type TarEntryKind = 'file' | 'dir' | 'symlink' | 'other';

export interface TarEntry {
  name: string;
  kind: TarEntryKind;
  size: number;
  /** The content of a regular file that fits in the buffer (firstTarEntry: the part of it the buffer holds); null otherwise. */
  data: Buffer | null;
}

const BLOCK = 512;

function text(buf: Buffer, start: number, length: number): string {
  const raw = buf.subarray(start, start + length);
  const nul = raw.indexOf(0);
  return raw.subarray(0, nul < 0 ? raw.length : nul).toString('utf8');
}

function octal(buf: Buffer, start: number, length: number): number | null {
  if (buf[start]! & 0x80) {
    // base-256 (GNU) for sizes above 8 GiB: far above any bound, report as huge
    return Number.MAX_SAFE_INTEGER;
  }
  const s = text(buf, start, length).trim();
  if (s === '') return 0;
  // a header field that is not octal: the archive is not one this reader trusts past this point
  if (!/^[0-7]+$/.test(s)) return null;
  return parseInt(s, 8);
}

/** The PAX records a listing needs: the path, and the size of a file above the header's 8 GiB. */
function paxFields(records: Buffer): { path: string | null; size: number | null } {
  let pos = 0;
  let path: string | null = null;
  let size: number | null = null;
  while (pos < records.length) {
    const space = records.indexOf(0x20, pos);
    if (space < 0) break;
    const len = Number(records.subarray(pos, space).toString('ascii'));
    if (!Number.isInteger(len) || len <= 0) break;
    const record = records.subarray(space + 1, pos + len - 1).toString('utf8');
    const eq = record.indexOf('=');
    if (eq > 0 && record.slice(0, eq) === 'path') path = record.slice(eq + 1);
    if (eq > 0 && record.slice(0, eq) === 'size' && /^\d+$/.test(record.slice(eq + 1))) size = Number(record.slice(eq + 1));
    pos += len;
  }
  return { path, size };
}

function kindOf(flag: string): TarEntryKind {
  if (flag === '0' || flag === '' || flag === '7') return 'file';
  if (flag === '5') return 'dir';
  if (flag === '2' || flag === '1') return 'symlink';
  return 'other';
}

/**
 * Lists the entries of a (possibly truncated) tar archive. Never throws: the archive holds what
 * the sandbox left in its work dir, so a header it cannot read ends the listing like a cut archive.
 */
export function readTar(archive: Buffer): TarEntry[] {
  return entriesOf(archive, false);
}

/**
 * The first entry of an archive's beginning (a bounded read of a one-file archive), with as much of
 * its body as the buffer holds (the whole body when it is there); null when no entry is readable.
 */
export function firstTarEntry(archive: Buffer): TarEntry | null {
  return entriesOf(archive, true)[0] ?? null;
}

function entriesOf(archive: Buffer, firstOnly: boolean): TarEntry[] {
  const entries: TarEntry[] = [];
  let pos = 0;
  let longName: string | null = null;
  let paxSize: number | null = null;
  while (pos + BLOCK <= archive.length) {
    const header = archive.subarray(pos, pos + BLOCK);
    if (header.every((b) => b === 0)) break;
    const headerSize = octal(header, 124, 12);
    if (headerSize === null) break;
    const flag = String.fromCharCode(header[156]!).replace('\0', '');
    const meta = flag === 'x' || flag === 'L' || flag === 'g';
    // a PAX size (a file above 8 GiB) is the size of the entry that follows it
    const size = meta ? headerSize : (paxSize ?? headerSize);
    if (!meta) paxSize = null;
    const dataStart = pos + BLOCK;
    const complete = size <= archive.length - dataStart;
    const body = complete ? archive.subarray(dataStart, dataStart + size) : null;
    if (flag === 'x' || flag === 'L') {
      if (!body) break;
      if (flag === 'x') ({ path: longName, size: paxSize } = paxFields(body));
      else longName = text(body, 0, body.length);
    } else if (flag !== 'g') {
      const prefix = text(header, 345, 155);
      const name = longName ?? (prefix ? `${prefix}/${text(header, 0, 100)}` : text(header, 0, 100));
      longName = null;
      const kind = kindOf(flag);
      const held = firstOnly ? archive.subarray(dataStart, Math.min(archive.length, dataStart + size)) : body;
      entries.push({ name: name.replace(/^\.\//, '').replace(/\/$/, ''), kind, size, data: kind === 'file' ? held : null });
      if (firstOnly) break;
    }
    if (!complete) break;
    pos = dataStart + Math.ceil(size / BLOCK) * BLOCK;
  }
  return entries;
}
