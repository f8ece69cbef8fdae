import { describe, it, expect } from 'vitest';
import { copyKey, parseCopyKey, parseLegacyCopies, SHARED_COPY, LEGACY_PREFIX } from './browser-copies.js';
import { BrowserCopyStore, type CopyStorage } from './browser-copy-store.js';

/** Storage as the browser's localStorage behaves (keys in insertion order), for Node. */
class MemoryStorage implements CopyStorage {
  readonly items = new Map<string, string>();
  get length(): number {
    return this.items.size;
  }
  key(i: number): string | null {
    return [...this.items.keys()][i] ?? null;
  }
  getItem(k: string): string | null {
    return this.items.get(k) ?? null;
  }
  setItem(k: string, v: string): void {
    this.items.set(k, String(v));
  }
  removeItem(k: string): void {
    this.items.delete(k);
  }
}

const ROOT = '/home/me/robot';

describe('browser copies of unsaved edits, one key per tab', () => {
  it("a second tab's copy of the same file is kept beside the first's, under its own key; each sees the other's, oldest first", () => {
    const storage = new MemoryStorage();
    const store = new BrowserCopyStore(storage, ROOT);
    store.put('a.contract', 'tab-a', { text: 'A edit', baseText: 'base', baseVersion: 'v1', at: 1 });
    store.put('a.contract', 'tab-b', { text: 'B edit', baseText: 'base', baseVersion: 'v1', at: 2 });
    expect(storage.items.size).toBe(2);
    expect(store.get('a.contract', 'tab-a')?.text).toBe('A edit');
    expect(store.get('a.contract', 'tab-b')?.text).toBe('B edit');
    expect(store.others('a.contract', 'tab-b').map(([id]) => id)).toEqual(['tab-a']);
    expect(store.others('a.contract', 'tab-c').map(([id]) => id)).toEqual(['tab-a', 'tab-b']);
    expect(store.paths()).toEqual(['a.contract']);
  });

  it("a tab's write or drop of its copy never touches another tab's entry (no read-modify-write of a shared one)", () => {
    const storage = new MemoryStorage();
    const a = new BrowserCopyStore(storage, ROOT);
    const b = new BrowserCopyStore(storage, ROOT);
    a.put('a.contract', 'tab-a', { text: 'A', at: 1 });
    const before = storage.items.get(copyKey({ root: ROOT, path: 'a.contract', tab: 'tab-a' }));
    // B writes, A drops, B writes again: the shared entry of before put A's dropped copy back here
    b.put('a.contract', 'tab-b', { text: 'B', at: 2 });
    a.drop('a.contract', 'tab-a');
    b.put('a.contract', 'tab-b', { text: 'B2', at: 3 });
    expect(before).toBeDefined();
    expect(b.others('a.contract', 'tab-b')).toEqual([]);
    expect(a.others('a.contract', 'tab-a')).toEqual([['tab-b', { text: 'B2', at: 3 }]]);
  });

  it('keys hold any root and path (colons, quotes) and other workspaces are not mixed in', () => {
    const storage = new MemoryStorage();
    const place = { root: '/a:b', path: 'x:"y".contract', tab: 'tab-1' };
    expect(parseCopyKey(copyKey(place))).toEqual(place);
    expect(parseCopyKey('contract-studio:layout')).toBeUndefined();
    expect(parseCopyKey('contract-studio:unsaved-copy:not json')).toBeUndefined();
    new BrowserCopyStore(storage, '/a').put('f.contract', 't', { text: 'in /a' });
    new BrowserCopyStore(storage, '/a:b').put('f.contract', 't', { text: 'in /a:b' });
    expect(new BrowserCopyStore(storage, '/a').others('f.contract', 'me')).toEqual([['t', { text: 'in /a' }]]);
  });

  it('the entries of earlier versions (one per file: every tab inside, a single copy, a bare text) move to one key per tab, none lost', () => {
    const storage = new MemoryStorage();
    const v2 = { v: 2, copies: { 'tab-a': { text: 'A', baseText: 'base', at: 1 }, 'tab-b': { text: 'B', at: 2 } } };
    storage.setItem(`${LEGACY_PREFIX}${ROOT}:a.contract`, JSON.stringify(v2));
    storage.setItem(`${LEGACY_PREFIX}${ROOT}:dir/b.contract`, JSON.stringify({ v: 1, text: 'old copy', baseText: 'base', baseVersion: 'v0', sentText: 'sent' }));
    storage.setItem(`${LEGACY_PREFIX}${ROOT}:c.contract`, 'bare text');
    storage.setItem(`${LEGACY_PREFIX}/elsewhere:a.contract`, 'another workspace');
    const store = new BrowserCopyStore(storage, ROOT);
    expect(store.migrateLegacy().sort()).toEqual(['a.contract', 'c.contract', 'dir/b.contract']);
    expect(store.others('a.contract', 'me')).toEqual([['tab-a', { text: 'A', baseText: 'base', at: 1 }], ['tab-b', { text: 'B', at: 2 }]]);
    expect(store.get('dir/b.contract', SHARED_COPY)).toEqual({ text: 'old copy', baseText: 'base', baseVersion: 'v0', sentText: 'sent' });
    expect(store.get('c.contract', SHARED_COPY)).toEqual({ text: 'bare text' });
    expect(store.paths().sort()).toEqual(['a.contract', 'c.contract', 'dir/b.contract']);
    // the old entries are gone, but another workspace's
    expect([...storage.items.keys()].filter((k) => k.startsWith(LEGACY_PREFIX))).toEqual([`${LEGACY_PREFIX}/elsewhere:a.contract`]);
    expect(store.migrateLegacy()).toEqual([]);
  });

  it('an old entry whose copies the storage refuses (full) stays, to be moved at the next load', () => {
    const storage = new MemoryStorage();
    storage.setItem(`${LEGACY_PREFIX}${ROOT}:a.contract`, JSON.stringify({ v: 2, copies: { t: { text: 'kept' } } }));
    const full = Object.assign(Object.create(storage) as MemoryStorage, { setItem: () => { throw new Error('QuotaExceededError'); } });
    expect(new BrowserCopyStore(full, ROOT).migrateLegacy()).toEqual([]);
    expect(storage.items.has(`${LEGACY_PREFIX}${ROOT}:a.contract`)).toBe(true);
  });

  it('malformed copies are skipped, not thrown on', () => {
    const raw = JSON.stringify({ v: 2, copies: { a: { text: 1 }, b: null, c: { text: 'ok', at: 'x' } } });
    expect([...parseLegacyCopies(raw)]).toEqual([['c', { text: 'ok' }]]);
    const storage = new MemoryStorage();
    storage.setItem(copyKey({ root: ROOT, path: 'a.contract', tab: 't' }), '{not json');
    expect(new BrowserCopyStore(storage, ROOT).others('a.contract', 'me')).toEqual([]);
  });
});
