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
