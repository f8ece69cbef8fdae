import { describe, expect, it } from 'vitest';
import { chordMatches, parseChord } from './commands.js';

const key = (init: Partial<KeyboardEvent>) => ({ ctrlKey: false, metaKey: false, shiftKey: false, altKey: false, key: '', code: '', ...init }) as KeyboardEvent;

describe('shortcut chords', () => {
  it('parses modifiers and the key', () => {
    expect(parseChord('Ctrl+Shift+G')).toEqual({ ctrl: true, shift: true, alt: false, key: 'g' });
    expect(parseChord('F1')).toEqual({ ctrl: false, shift: false, alt: false, key: 'f1' });
  });

  it('matches on the physical key, Ctrl or ⌘, and exactly the modifiers named', () => {
    const ctrlP = parseChord('Ctrl+P');
    expect(chordMatches(ctrlP, key({ ctrlKey: true, key: 'p', code: 'KeyP' }))).toBe(true);
    expect(chordMatches(ctrlP, key({ metaKey: true, key: 'p', code: 'KeyP' }))).toBe(true);
    expect(chordMatches(ctrlP, key({ ctrlKey: true, shiftKey: true, key: 'P', code: 'KeyP' }))).toBe(false);
    expect(chordMatches(ctrlP, key({ key: 'p', code: 'KeyP' }))).toBe(false);
    // Alt+Shift+D types "Î" on a Mac: the physical key still matches
    expect(chordMatches(parseChord('Alt+Shift+D'), key({ altKey: true, shiftKey: true, key: 'Î', code: 'KeyD' }))).toBe(true);
    expect(chordMatches(parseChord('F1'), key({ key: 'F1', code: 'F1' }))).toBe(true);
    expect(chordMatches(parseChord('F1'), key({ shiftKey: true, key: 'F1', code: 'F1' }))).toBe(false);
  });
});
