/**
 * src/validation/c-names/header-names.ts is generated from the headers of the generated C and the
 * runtime library with gcc and nm (docs/language-reference.md, "Reserved names"); this fails when
 * it no longer matches them (after a change to runtime/include, or with another gcc or C library).
 */
import { execFileSync, spawnSync } from 'node:child_process';
import { fileURLToPath } from 'node:url';
import { describe, expect, it } from 'vitest';

const runtime = fileURLToPath(new URL('../../../runtime', import.meta.url));
const script = fileURLToPath(new URL('../scripts/generate-c-names.mjs', import.meta.url));

describe('the reserved C names list', () => {
    it('is up to date with the headers and the runtime library (run `npm run c-names -w packages/language`)', () => {
        execFileSync('make', ['-s', '-C', runtime, 'build/libmodule.a'], { stdio: 'pipe' });
        const result = spawnSync(process.execPath, [script, '--check'], { encoding: 'utf8' });
        expect(result.stderr).toBe('');
        expect(result.status).toBe(0);
    }, 60_000);
});
