/**
 * The browser copies of a file's unsaved edits (docs/ide.md "Saving"): one localStorage entry per
 * address, file and tab (page load) that edited it, so that two tabs of one browser editing the
 * same file while the server is away keep both texts. A tab writes only its own entry: never
 * another's, even to keep it (an entry shared by the tabs and rewritten by each, read-modify-write,
 * could put back a copy another tab had just dropped). A tab drops its own copy once the server
 * confirms its save; another tab's copy left there (that tab closed, or reloaded, before it could
 * save) is taken up by a tab that loads the file, or that saved it, and merged with the disk as any
 * restored copy is (workspace.ts), then dropped by it.
 * Pure: the entries' keys and texts (browser-copies.test.ts); browser-copy-store.ts reads and writes them.
 */

/** One tab's copy: its text and the base it was edited from. */
export interface BrowserCopy {
  text: string;
  /** The disk's text the tab edited (undefined: a bare copy of an older version). */
  baseText?: string;
  baseVersion?: string;
  /** A save in flight when the copy was made: if the disk holds it after a reload, it landed and is the base. */
  sentText?: string;
  /** When it was kept (ms since the epoch): copies are taken up oldest first. */
  at?: number;
}

/** Where a tab's copy is: the workspace root (the address's), the file, the tab. */
export interface CopyPlace {
  root: string;
  path: string;
  tab: string;
}

/** The keys of the copies, one per tab: COPY_PREFIX + JSON [root, path, tab] (a root or a path may hold any character). */
export const COPY_PREFIX = 'contract-studio:unsaved-copy:';
/** The keys of the entries of earlier versions: one per root and file (`LEGACY_PREFIX` + root + `:` + path), the tabs' copies inside. */
export const LEGACY_PREFIX = 'contract-studio:unsaved:';
/** The tab id of a copy made by a version that kept one copy per file (one text for all tabs). */
export const SHARED_COPY = 'shared';

export function copyKey(place: CopyPlace): string {
  return COPY_PREFIX + JSON.stringify([place.root, place.path, place.tab]);
}

/** The place a copy's key names; undefined for any other key. */
export function parseCopyKey(key: string): CopyPlace | undefined {
  if (!key.startsWith(COPY_PREFIX)) return undefined;
  try {
    const v = JSON.parse(key.slice(COPY_PREFIX.length)) as unknown;
    if (Array.isArray(v) && v.length === 3 && v.every((x) => typeof x === 'string')) return { root: v[0], path: v[1], tab: v[2] };
  } catch {
    /* not one of ours */
  }
  return undefined;
}

/** The file an entry of an earlier version under `root` is of; undefined for any other key. */
export function parseLegacyKey(key: string, root: string): string | undefined {
  const prefix = `${LEGACY_PREFIX}${root}:`;
  return key.startsWith(prefix) && key.length > prefix.length ? key.slice(prefix.length) : undefined;
}

function copyOf(v: unknown): BrowserCopy | undefined {
  const c = v as Partial<BrowserCopy> | null;
  if (!c || typeof c !== 'object' || typeof c.text !== 'string') return undefined;
  return {
    text: c.text,
    ...(typeof c.baseText === 'string' ? { baseText: c.baseText } : {}),
    ...(typeof c.baseVersion === 'string' ? { baseVersion: c.baseVersion } : {}),
    ...(typeof c.sentText === 'string' ? { sentText: c.sentText } : {}),
    ...(typeof c.at === 'number' && Number.isFinite(c.at) ? { at: c.at } : {}),
  };
}

/** A tab's copy as stored under its own key; undefined when there is none, or it is malformed. */
export function parseCopy(raw: string | null): BrowserCopy | undefined {
  if (raw === null) return undefined;
  try {
    return copyOf(JSON.parse(raw));
  } catch {
    return undefined;
  }
}

/**
 * The copies in an entry of an earlier version, by tab: one entry per file holding every tab's
 * (`v: 2`); a single copy (`v: 1`, made before copies were kept by tab) or a bare text (before
 * versions) as the one copy of SHARED_COPY. Nothing stored: none.
 */
export function parseLegacyCopies(raw: string | null): Map<string, BrowserCopy> {
  const out = new Map<string, BrowserCopy>();
  if (raw === null) return out;
  let v: unknown;
  try {
    v = JSON.parse(raw);
  } catch {
    out.set(SHARED_COPY, { text: raw }); // an old bare copy
    return out;
  }
  const o = v as { v?: unknown; copies?: unknown; baseText?: unknown } | null;
  if (o && o.v === 2 && o.copies && typeof o.copies === 'object') {
    for (const [tab, c] of Object.entries(o.copies as Record<string, unknown>)) {
      const copy = copyOf(c);
      if (copy) out.set(tab, copy);
    }
    return out;
  }
  const single = o && o.v === 1 && typeof o.baseText === 'string' ? copyOf(o) : undefined;
  out.set(SHARED_COPY, single ?? { text: typeof v === 'string' ? v : raw });
  return out;
}
