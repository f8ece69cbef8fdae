import { describe, it, expect } from 'vitest';
import { parseCopies, withCopy, othersCopies, SHARED_COPY } from './browser-copies.js';

describe('browser copies of unsaved edits, one per tab', () => {
  it("a second tab's copy of the same file is kept beside the first's, not over it", () => {
    const a = withCopy(null, 'tab-a', { text: 'A edit', baseText: 'base', baseVersion: 'v1', at: 1 });
    const both = withCopy(a, 'tab-b', { text: 'B edit', baseText: 'base', baseVersion: 'v1', at: 2 });
    const copies = parseCopies(both);
    expect(copies.get('tab-a')?.text).toBe('A edit');
    expect(copies.get('tab-b')?.text).toBe('B edit');
    // each tab sees the other's, oldest first
    expect(othersCopies(both, 'tab-b').map(([id]) => id)).toEqual(['tab-a']);
    expect(othersCopies(both, 'tab-c').map(([id]) => id)).toEqual(['tab-a', 'tab-b']);
  });

  it("a tab drops only its own copy; the entry goes with the last one", () => {
    const both = withCopy(withCopy(null, 'tab-a', { text: 'A' }), 'tab-b', { text: 'B' });
    const left = withCopy(both, 'tab-b', undefined);
    expect([...parseCopies(left).keys()]).toEqual(['tab-a']);
    expect(withCopy(left, 'tab-a', undefined)).toBeNull();
    expect(withCopy(null, 'tab-a', undefined)).toBeNull();
  });

  it('a copy an older version kept (one per file, or a bare text) is read as one shared copy, and kept beside a new one', () => {
    const v1 = JSON.stringify({ v: 1, text: 'old copy', baseText: 'base', baseVersion: 'v0', sentText: 'sent' });
    expect(parseCopies(v1).get(SHARED_COPY)).toEqual({ text: 'old copy', baseText: 'base', baseVersion: 'v0', sentText: 'sent' });
    expect(parseCopies('bare text').get(SHARED_COPY)).toEqual({ text: 'bare text' });
    const next = withCopy(v1, 'tab-a', { text: 'new' });
    expect([...parseCopies(next).keys()].sort()).toEqual(['shared', 'tab-a']);
  });

  it('malformed copies are skipped, not thrown on', () => {
    const raw = JSON.stringify({ v: 2, copies: { a: { text: 1 }, b: null, c: { text: 'ok', at: 'x' } } });
    expect([...parseCopies(raw)]).toEqual([['c', { text: 'ok' }]]);
  });
});
