import { describe, expect, it } from 'vitest';
import { visibleText } from './visible-text.js';

describe('visibleText', () => {
  it('writes a bidi override, an isolate, a mark, a separator or a control as its escape: the text reads in its order', () => {
    expect(visibleText('live \u202e BIDI evil')).toBe('live \\u202e BIDI evil');
    expect(visibleText('ORD_\u2067vsc.1.csv\u2069 \u200f\u2028x\x1b[2J\x00\x7f\u009b')).toBe('ORD_\\u2067vsc.1.csv\\u2069 \\u200f\\u2028x\\u001b[2J\\u0000\\u007f\\u009b');
  });
  it('keeps a tab and any other text as it is', () => {
    expect(visibleText('a\tb é ✓ 日本 مرحبا')).toBe('a\tb é ✓ 日本 مرحبا');
  });
});

describe('visibleText and the characters of no width', () => {
  it('writes U+200B-U+200D, the word joiner U+2060 and the BOM U+FEFF as their escapes: two values that differ never look the same', () => {
    expect(visibleText('"go\u200b" "go\u200c\u200d" \u2060x\ufeff')).toBe('"go\\u200b" "go\\u200c\\u200d" \\u2060x\\ufeff');
    expect(visibleText('go\u200b', { keepNewlines: true })).not.toBe(visibleText('go', { keepNewlines: true }));
    // the characters around them that are seen stay as they are
    expect(visibleText('\u200a\u2010\u2061\ufefe')).toBe('\u200a\u2010\u2061\ufefe');
  });
});

describe('visibleText with escapeTab (a name inside a message: the CLI\'s safeName)', () => {
  it('writes a tab as its escape too, and everything else as visibleText does', () => {
    expect(visibleText('t\tb\nc', { escapeTab: true })).toBe('t\\u0009b\\u000ac');
    const marks = 'x\u200ey\u200fz\u061cw\u202e';
    expect(visibleText(marks, { escapeTab: true })).toBe(visibleText(marks));
    expect(visibleText('a é ✓ 日本 مرحبا', { escapeTab: true })).toBe('a é ✓ 日本 مرحبا');
  });
});

describe('visibleText with keepNewlines (many lines, each shown as one: all the CLI prints)', () => {
  it('keeps newlines and tabs, and writes the rest as visibleText does', () => {
    expect(visibleText('a\tb\nc\u200fd\r\n', { keepNewlines: true })).toBe('a\tb\nc\\u200fd\\u000d\n');
  });
});
