/**
 * The browser copies of unsaved edits of one workspace (address) in the browser's storage
 * (browser-copies.ts): each tab's under its own key, written and dropped by that tab only — but for
 * the copy of a tab gone, dropped by the tab that took it up — and the entries of earlier versions
 * (one per file, every tab's copy inside) moved to those keys.
 */
import { copyKey, parseCopy, parseCopyKey, parseLegacyCopies, parseLegacyKey, type BrowserCopy } from './browser-copies.js';

/** What the store needs of `localStorage`. */
export type CopyStorage = Pick<Storage, 'getItem' | 'setItem' | 'removeItem' | 'key' | 'length'>;

export class BrowserCopyStore {
  constructor(private readonly storage: CopyStorage, private readonly root: string) {}

  /** Keeps tab `tab`'s copy of `path` (throws when the storage refuses it: full). */
  put(path: string, tab: string, copy: BrowserCopy): void {
    this.storage.setItem(copyKey({ root: this.root, path, tab }), JSON.stringify(copy));
  }

  get(path: string, tab: string): BrowserCopy | undefined {
    return parseCopy(this.storage.getItem(copyKey({ root: this.root, path, tab })));
  }

  drop(path: string, tab: string): void {
    this.storage.removeItem(copyKey({ root: this.root, path, tab }));
  }

  /** The copies of `path` of other tabs than `tab`, oldest first. */
  others(path: string, tab: string): Array<[string, BrowserCopy]> {
    const out: Array<[string, BrowserCopy]> = [];
    for (const key of this.keys()) {
      const place = parseCopyKey(key);
      if (!place || place.root !== this.root || place.path !== path || place.tab === tab) continue;
      const copy = parseCopy(this.storage.getItem(key));
      if (copy) out.push([place.tab, copy]);
    }
    return out.sort((a, b) => (a[1].at ?? 0) - (b[1].at ?? 0));
  }

  /** The files that have copies (any tab's). */
  paths(): string[] {
    const out = new Set<string>();
    for (const key of this.keys()) {
      const place = parseCopyKey(key);
      if (place?.root === this.root) out.add(place.path);
    }
    return [...out];
  }

  /**
   * Moves the copies an earlier version kept (one entry per file, every tab's inside) each to its
   * tab's key, then removes the entry: nobody's copy is lost on an upgrade. A tab's copy already
   * under its own key is kept when newer. An entry whose copies could not all be written (storage
   * full) stays, and is moved again at the next load. Returns the files moved.
   */
  migrateLegacy(): string[] {
    const moved: string[] = [];
    for (const key of this.keys()) {
      const path = parseLegacyKey(key, this.root);
      if (path === undefined) continue;
      try {
        for (const [tab, copy] of parseLegacyCopies(this.storage.getItem(key))) {
          const mine = this.get(path, tab);
          if (!mine || (mine.at ?? 0) < (copy.at ?? 0)) this.put(path, tab, copy);
        }
        this.storage.removeItem(key);
        moved.push(path);
      } catch {
        /* storage full: the entry stays, moved at the next load */
      }
    }
    return moved;
  }

  /** The storage's keys, listed first (the loop then removes and adds freely). */
  private keys(): string[] {
    const out: string[] = [];
    for (let i = 0; i < this.storage.length; i++) {
      const key = this.storage.key(i);
      if (key !== null) out.push(key);
    }
    return out;
  }
}
