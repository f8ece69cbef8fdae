/**
 * The committed src/generated/ and syntaxes/ are Langium's output for the committed grammar: the
 * build regenerates them only when the grammar's hash changed (scripts/generate-parser.mjs), since
 * Langium's CLI does not run on Node 24.20+. A grammar edited without regenerating fails here.
 */
import { spawnSync } from 'node:child_process';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';

const script = join(__dirname, '..', 'scripts', 'generate-parser.mjs');

describe('generated parser', () => {
    it('src/generated/ was made from the committed grammar and langium-config.json (its inputs hash is current)', () => {
        const check = spawnSync(process.execPath, [script, '--check'], { encoding: 'utf8' });
        expect(check.stderr).toBe('');
        expect(check.status).toBe(0);
    });
});
