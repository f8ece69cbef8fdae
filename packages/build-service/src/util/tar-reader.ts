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
  /** The content of a regular file that fits in the buffer; null otherwise. */
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

function paxPath(records: Buffer): string | null {
  let pos = 0;
  let path: string | null = null;
  while (pos < records.length) {
    const space = records.indexOf(0x20, pos);
    if (space < 0) break;
    const len = Number(records.subarray(pos, space).toString('ascii'));
    if (!Number.isInteger(len) || len <= 0) break;
    const record = records.subarray(space + 1, pos + len - 1).toString('utf8');
    const eq = record.indexOf('=');
    if (eq > 0 && record.slice(0, eq) === 'path') path = record.slice(eq + 1);
    pos += len;
  }
  return path;
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
  const entries: TarEntry[] = [];
  let pos = 0;
  let longName: string | null = null;
  while (pos + BLOCK <= archive.length) {
    const header = archive.subarray(pos, pos + BLOCK);
    if (header.every((b) => b === 0)) break;
    const size = octal(header, 124, 12);
    if (size === null) break;
    const flag = String.fromCharCode(header[156]!).replace('\0', '');
    const dataStart = pos + BLOCK;
    const complete = size <= archive.length - dataStart;
    const body = complete ? archive.subarray(dataStart, dataStart + size) : null;
    if (flag === 'x' || flag === 'L') {
      if (!body) break;
      longName = flag === 'x' ? paxPath(body) : text(body, 0, body.length);
    } else if (flag !== 'g') {
      const prefix = text(header, 345, 155);
      const name = longName ?? (prefix ? `${prefix}/${text(header, 0, 100)}` : text(header, 0, 100));
      longName = null;
      const kind = kindOf(flag);
      entries.push({ name: name.replace(/^\.\//, '').replace(/\/$/, ''), kind, size, data: kind === 'file' ? body : null });
    }
    if (!complete) break;
    pos = dataStart + Math.ceil(size / BLOCK) * BLOCK;
  }
  return entries;
}
