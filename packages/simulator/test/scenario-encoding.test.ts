/**
 * A scenario file is UTF-8 text: a byte order mark (a Windows editor's) is dropped, a UTF-16 file
 * or a byte of another encoding is refused saying where — before, a BOM made line 1 "expected a
 * directive", and a Latin-1 `"déjà"` was sent as `"d\uFFFDj\uFFFD"` without a word.
 */
import { mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterAll, describe, expect, it } from 'vitest';
import { decodeScenarioText, parseScenario, readScenarioFile } from '../src/index.js';

const dir = mkdtempSync(join(tmpdir(), 'scenario-encoding-'));
afterAll(() => rmSync(dir, { recursive: true, force: true }));

describe('a scenario file\'s encoding', () => {
    it('a UTF-8 byte order mark is dropped: the file parses as without it', () => {
        const text = 'start SUP.action()\nt=1ms MAA:2 connection_status = "déjà"\n';
        writeFileSync(join(dir, 'bom.scenario'), Buffer.concat([Buffer.from([0xef, 0xbb, 0xbf]), Buffer.from(text)]));
        const read = readScenarioFile(join(dir, 'bom.scenario'));
        expect(typeof read).toBe('string');
        const parsed = parseScenario(read as string);
        expect(parsed.diagnostics).toEqual([]);
        expect(parsed.steps).toEqual(parseScenario(text).steps);
    });

    it('UTF-16, or a byte that is no UTF-8, is refused with where and what to do', () => {
        expect(decodeScenarioText(Buffer.from('\ufeffstart SUP.action()\n', 'utf16le'))).toEqual({ error: 'UTF-16 text (its byte order mark says so): save it as UTF-8' });
        const latin1 = Buffer.from('start SUP.action()\n# ok\nt=1ms MAA:2 connection_status = "déjà"\n', 'latin1');
        expect(decodeScenarioText(latin1)).toEqual({ error: 'not UTF-8 text: byte 0xe9 on line 3 is no UTF-8 (Latin-1? save it as UTF-8)' });
        writeFileSync(join(dir, 'latin1.scenario'), latin1);
        expect(readScenarioFile(join(dir, 'latin1.scenario'))).toEqual({ error: 'not UTF-8 text: byte 0xe9 on line 3 is no UTF-8 (Latin-1? save it as UTF-8)' });
        // valid UTF-8 (a U+FFFD written as such included) is read as it is
        expect(decodeScenarioText(Buffer.from('t=1ms MAA:2 connection_status = "\ufffd"\n'))).toBe('t=1ms MAA:2 connection_status = "\ufffd"\n');
    });
});
