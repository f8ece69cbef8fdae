import { describe, expect, it } from 'vitest';
import { parseJsonBody } from './json-body.js';

describe('parseJsonBody', () => {
  it('gives the value of JSON text, and names the parser\'s error for any other text', () => {
    expect(parseJsonBody('{"a":[1,null]}')).toEqual({ ok: true, value: { a: [1, null] } });
    expect(parseJsonBody('null')).toEqual({ ok: true, value: null });
    const bad = parseJsonBody('{"a":');
    expect(bad.ok).toBe(false);
    expect(!bad.ok && bad.error).toMatch(/^invalid JSON: \S/);
    let parserError = '';
    try {
      JSON.parse('{"a":');
    } catch (e) {
      parserError = (e as Error).message;
    }
    expect(!bad.ok && bad.error).toBe(`invalid JSON: ${parserError}`);
  });
});
