/** A `.contract` file left with git's merge conflict markers gets one clear error per marker line, not the parser's cascade. */
import { describe, expect, it } from 'vitest';
import { build, TYPES } from './helpers.js';

// a rule of a supervisor whose label and action two branches changed (the field test's nav.contract)
const SIDES = (ours: string, theirs: string) => `import "types.contract";
synchronous module GTG { scheduling { C=1ms; } }
supervisor NAV {
  guide () {
    rules {
<<<<<<< HEAD
      ${ours}
=======
      ${theirs}
>>>>>>> eng-b
    }
  }
}
`;

describe('merge conflict markers in a .contract file', () => {
    it('are one merge-conflict-marker error each, on its line, saying its side and what to do, and nothing else in that file', async () => {
        const built = await build({
            'types.contract': TYPES,
            'nav.contract': SIDES('GO: [elapsed=10ms] activate resttime module GTG [elapsed=50ms]', 'SLOW: [elapsed=20ms] activate resttime module GTG [elapsed=50ms]')
        });
        const nav = built.diagnostics.filter((d) => d.file === 'nav.contract');
        expect(nav.map((d) => `${d.line} ${d.severity} ${d.code}`)).toEqual(['6 error merge-conflict-marker', '8 error merge-conflict-marker', '10 error merge-conflict-marker']);
        expect(nav[0]!.message).toBe('Unresolved git merge conflict (marker lines 6, 8, 10): your side of the conflict begins here. Keep the lines you want, delete the marker lines, and save; nothing else in this file is checked until then.');
        expect(nav[1]!.message).toContain(': their side begins here.');
        expect(nav[2]!.message).toContain(': their side ends here.');
        expect(built.diagnostics.filter((d) => d.file !== 'nav.contract')).toEqual([]);
    });

    it('says diff3\'s common-ancestor marker too; a lone ======= line is no conflict (the parser reports it as usual)', async () => {
        const diff3 = SIDES('GO: [elapsed=10ms] activate resttime module GTG [elapsed=50ms]', 'SLOW: [elapsed=20ms] activate resttime module GTG [elapsed=50ms]')
            .replace('=======\n', '||||||| base\n      OLD: [elapsed=5ms] activate resttime module GTG [elapsed=50ms]\n=======\n');
        const built = await build({ 'types.contract': TYPES, 'nav.contract': diff3 });
        expect(built.diagnostics.map((d) => d.message.split(': ').slice(1).join(': ').split('.')[0])).toEqual([
            'your side of the conflict begins here', "the common ancestor's lines begin here", 'their side begins here', 'their side ends here'
        ]);
        const lone = await build({ 'types.contract': TYPES, 'nav.contract': 'import "types.contract";\n=======\nsynchronous module GTG { scheduling { C=1ms; } }\n' });
        expect(lone.diagnostics.map((d) => d.code)).not.toContain('merge-conflict-marker');
        expect(lone.diagnostics.map((d) => d.code)).toContain('parsing-error');
    });

    it('once resolved, the file is checked as usual (its own errors found again)', async () => {
        // the side kept names a module that does not exist
        const resolved = SIDES('GO: [elapsed=10ms] activate resttime module GTX [elapsed=50ms]', '').replace(/^(<{7}|={7}|>{7}).*\n/gm, '');
        const built = await build({ 'types.contract': TYPES, 'nav.contract': resolved });
        expect(built.diagnostics.filter((d) => d.severity === 'error').map((d) => `${d.line} ${d.code}`)).toEqual(['6 linking-error']);
    });
});
