import { describe, it, expect } from 'vitest';
import { shortAtWord } from './short-text.js';

describe('shortAtWord', () => {
  it('keeps a text that fits', () => {
    expect(shortAtWord('Build & Run job 12 · ended: succeeded', 40)).toBe('Build & Run job 12 · ended: succeeded');
  });

  it('ends a longer one at a word boundary with an ellipsis, within the bound', () => {
    const label = 'Build & Run job j-608c · as streamed · ended: failed: run failed: module EST crashed (died by signal 11 (Segmentation fault)) at src-gen/generated/architecture/modules/EST_mod/module.c:251 in its protected region protect_exec_EST (_exec_module_state) (contract-launch exit 1; make exit 2)';
    const short = shortAtWord(label, 200);
    expect(short.length).toBeLessThanOrEqual(200);
    expect(short).toBe('Build & Run job j-608c · as streamed · ended: failed: run failed: module EST crashed (died by signal 11 (Segmentation fault)) at src-gen/generated/architecture/modules/EST_mod/module.c:251 in its…');
    // a cut that falls at the end of a word keeps that word
    expect(shortAtWord('one two three four', 10)).toBe('one two…');
    expect(shortAtWord('one two three four', 9)).toBe('one two…');
  });

  it('cuts a single word longer than half the bound inside it, never inside a character', () => {
    expect(shortAtWord('a'.repeat(30), 10)).toBe(`${'a'.repeat(9)}…`);
    expect(shortAtWord(`x ${'😀'.repeat(10)}`, 8)).toBe('x 😀😀…');
  });
});
