/**
 * Renames and the user code inside protected regions (docs/codegen.md, "Renames"): a renamed port's
 * uses in its module's regions follow (whole C identifiers in code only), what cannot be changed is
 * listed with file and line; the carry-over of a module keeps the manifest's skeleton hashes valid
 * and updates the default MODULE_DESCRIPTION.
 */
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { describe, expect, it } from 'vitest';
import { region } from '../regions/markers.js';
import { scratchDirs } from '../test-support/temp-dir.js';
import { cWords, renameIdentifier } from './c-identifiers.js';
import { renameInGeneratedTree } from './rename-generated.js';
import { carryRefusedMessage, findRegionMentions, identifierRenames, mentionMatcher, renameIdentifierInGeneratedTree, renameIdentifiersInGeneratedTree } from './rename-user-code.js';
import { writeTree } from './write-tree.js';

/** A fresh output folder per call, removed after each test. */
const out = scratchDirs();
const path = (m: string) => `generated/architecture/modules/${m}_mod/module.c`;

describe('C words', () => {
    it('whole identifiers with their context: code, member, comment, string; numbers are no words', () => {
        const words = cWords('a = in_x + s.in_x + p -> in_x + my_in_x + in_x2 + 1e5; // in_x\n/* in_x */ "in_x\\"" \'x\' 0x1p-3');
        expect(words.filter((w) => w.word === 'in_x').map((w) => [w.context, w.member])).toEqual([
            ['code', false], ['code', true], ['code', true], ['comment', false], ['comment', false], ['string', false],
        ]);
        expect(words.map((w) => w.word)).not.toContain('e5');
        expect(renameIdentifier('in_x.x = s.in_x + in_x; /* in_x */ "in_x"', 'in_x', 'pos')).toEqual({ text: 'pos.x = s.in_x + pos; /* in_x */ "in_x"', count: 2 });
    });
});

describe('renameIdentifierInGeneratedTree (a renamed port or parameter)', () => {
    const file = (m: string, exec: string, other = '//TODO') =>
        `double in_coordinates;\n${region(`protect_internal_vars_${m}`, `\n${other}\n`)}\nint f(void){\n${region(`protect_exec_${m}`, `\n${exec}\n`)}\n}\n`;

    it('rewrites the uses in code of the owner\'s regions only, reports what stays (comments, strings) with file:line; the skeleton is unchanged', () => {
        const dir = out();
        writeTree(dir, [{ path: path('MSC'), content: file('MSC', '//TODO') }, { path: path('MSD'), content: file('MSD', '//TODO') }]);
        const user = 'TypeA t = in_coordinates; /* copy of in_coordinates */\nprintf("in_coordinates %f", in_coordinates.x + t.in_coordinates);';
        writeFileSync(join(dir, path('MSC')), file('MSC', user));
        writeFileSync(join(dir, path('MSD')), file('MSD', 'use(in_coordinates);'));
        const r = renameIdentifierInGeneratedTree(dir, 'MSC', 'in_coordinates', 'position');
        expect(r.refused).toBeUndefined();
        expect(r.rewritten).toEqual([{ file: path('MSC'), line: 6, id: 'protect_exec_MSC', occurrences: 2 }]);
        expect(readFileSync(join(dir, path('MSC')), 'latin1')).toBe(file('MSC', 'TypeA t = position; /* copy of in_coordinates */\nprintf("in_coordinates %f", position.x + t.in_coordinates);'));
        expect(readFileSync(join(dir, path('MSD')), 'latin1')).toBe(file('MSD', 'use(in_coordinates);'));
        expect(r.remaining.map((m) => [m.file, m.line, m.id, m.context])).toEqual([
            [path('MSC'), 7, 'protect_exec_MSC', 'comment'],
            [path('MSC'), 8, 'protect_exec_MSC', 'string'],
        ]);
        // the generated code outside the regions is the generator's: the next generation (with the new name) reports no edit outside
        const again = writeTree(dir, [{ path: path('MSC'), content: file('MSC', '//TODO').replace('double in_coordinates;', 'double position;') }, { path: path('MSD'), content: file('MSD', '//TODO') }]);
        expect([again.orphaned, again.warnings]).toEqual([[], []]);
        expect(readFileSync(join(dir, path('MSC')), 'latin1')).toContain('TypeA t = position;');
    });

    it('refuses when the new name is already a word of that code, changing nothing and listing every use with its line', () => {
        const dir = out();
        mkdirSync(join(dir, 'generated/architecture/modules/MSC_mod'), { recursive: true });
        const text = file('MSC', 'double position = in_coordinates.x;', 'static int n; // in_coordinates');
        writeFileSync(join(dir, path('MSC')), text);
        const r = renameIdentifierInGeneratedTree(dir, 'MSC', 'in_coordinates', 'position');
        expect(r.refused).toEqual({ file: path('MSC'), line: 7, id: 'protect_exec_MSC', word: 'position', context: 'code' });
        expect(carryRefusedMessage(r.refused!, ['in_coordinates'])).toBe(`'position' is already used in the code of protected region protect_exec_MSC (${path('MSC')}:7): uses of 'in_coordinates' were not rewritten`);
        expect(r.rewritten).toEqual([]);
        expect(readFileSync(join(dir, path('MSC')), 'latin1')).toBe(text);
        expect(r.remaining.map((m) => [m.line, m.id, m.context])).toEqual([[3, 'protect_internal_vars_MSC', 'comment'], [7, 'protect_exec_MSC', 'code']]);
    });

    it('a file whose code already uses the new name and not the old one (rewritten before a rename was killed) does not stop the others', () => {
        const dir = out();
        for (const m of ['MSA', 'MSB', 'MSC']) mkdirSync(join(dir, `generated/architecture/modules/${m}_mod`), { recursive: true });
        writeFileSync(join(dir, path('MSA')), file('MSA', 'Pose a = p_in; print_Pose(&a);'));
        writeFileSync(join(dir, path('MSB')), file('MSB', 'Position b = p_in; print_Position(&b);'));
        writeFileSync(join(dir, path('MSC')), file('MSC', 'Position c = p_in;', 'static int eq_Pose; // a name of its own: eq_Position is not used here'));
        const r = renameIdentifiersInGeneratedTree(dir, identifierRenames('datatype', 'Position', 'Pose'));
        expect(r.refused).toBeUndefined();
        expect(r.rewritten.map((x) => [x.file, x.occurrences])).toEqual([[path('MSB'), 2], [path('MSC'), 1]]);
        expect(readFileSync(join(dir, path('MSA')), 'latin1')).toBe(file('MSA', 'Pose a = p_in; print_Pose(&a);'));
        expect(readFileSync(join(dir, path('MSB')), 'latin1')).toBe(file('MSB', 'Pose b = p_in; print_Pose(&b);'));
        expect(readFileSync(join(dir, path('MSC')), 'latin1')).toContain('Pose c = p_in;');
    });

    it('a file using the old name and the new one as two things, in two of its regions, is a capture: refused, nothing changed anywhere', () => {
        const dir = out();
        for (const m of ['MSB', 'MSC']) mkdirSync(join(dir, `generated/architecture/modules/${m}_mod`), { recursive: true });
        writeFileSync(join(dir, path('MSB')), file('MSB', 'Position b = p_in;'));
        const capture = file('MSC', 'Position c = p_in; (void)Pose;', 'static double Pose;');
        writeFileSync(join(dir, path('MSC')), capture);
        const r = renameIdentifiersInGeneratedTree(dir, identifierRenames('datatype', 'Position', 'Pose'));
        expect(r.refused).toEqual({ file: path('MSC'), line: 3, id: 'protect_internal_vars_MSC', word: 'Pose', context: 'code' });
        expect(r.rewritten).toEqual([]);
        expect(readFileSync(join(dir, path('MSB')), 'latin1')).toBe(file('MSB', 'Position b = p_in;'));
        expect(readFileSync(join(dir, path('MSC')), 'latin1')).toBe(capture);
    });

    it('findRegionMentions: a datatype\'s generated names count, member names do not', () => {
        const dir = out();
        mkdirSync(join(dir, 'generated/architecture/modules/MSC_mod'), { recursive: true });
        writeFileSync(join(dir, path('MSC')), file('MSC', 'TypeA a; print_TypeA(&a); a.TypeA = 1;'));
        expect(findRegionMentions(dir, mentionMatcher('datatype', 'TypeA')).map((m) => [m.line, m.word])).toEqual([[7, 'TypeA'], [7, 'print_TypeA']]);
        expect(findRegionMentions(join(dir, 'missing'), mentionMatcher('port', 'x'))).toEqual([]);
    });

    it('a renamed datatype: the type and its generated functions in every region\'s code, member names and text left alone', () => {
        const dir = out();
        mkdirSync(join(dir, 'generated/architecture/modules/MSC_mod'), { recursive: true });
        writeFileSync(join(dir, path('MSC')), file('MSC', 'TypeA a; print_TypeA(&a); a.TypeA = eq_TypeA(&a, &a); /* TypeA */', 'static TypeA last;'));
        const r = renameIdentifiersInGeneratedTree(dir, identifierRenames('datatype', 'TypeA', 'Vec3'));
        expect(r.rewritten.map((x) => [x.id, x.occurrences])).toEqual([['protect_internal_vars_MSC', 1], ['protect_exec_MSC', 3]]);
        expect(readFileSync(join(dir, path('MSC')), 'latin1')).toBe(file('MSC', 'Vec3 a; print_Vec3(&a); a.TypeA = eq_Vec3(&a, &a); /* TypeA */', 'static Vec3 last;'));
        expect(r.remaining.map((m) => [m.word, m.context])).toEqual([['TypeA', 'comment']]);
        expect(identifierRenames('schema', 'a', 'b').size).toBe(0);
    });

    it('a renamed enumeration: the type, its generated functions and its constants (Mode_AUTO) in every region\'s code; text and other enumerations left alone', () => {
        const dir = out();
        mkdirSync(join(dir, 'generated/architecture/modules/MSC_mod'), { recursive: true });
        const exec = 'Mode m = Mode_AUTO; if (eq_Mode(&m, &mode)) print_Mode(&m); Gear g = Gear_AUTO; /* Mode_AUTO */ puts("Mode_SAFE");';
        writeFileSync(join(dir, path('MSC')), file('MSC', exec, 'static Mode last = Mode_SAFE;'));
        const renames = identifierRenames('enumeration', 'Mode', 'Drive', { members: ['AUTO', 'SAFE'] });
        expect(renames.get('Mode_AUTO')).toBe('Drive_AUTO');
        const r = renameIdentifiersInGeneratedTree(dir, renames);
        expect(r.refused).toBeUndefined();
        expect(r.rewritten.map((x) => [x.id, x.occurrences])).toEqual([['protect_internal_vars_MSC', 2], ['protect_exec_MSC', 4]]);
        expect(readFileSync(join(dir, path('MSC')), 'latin1')).toBe(file('MSC',
            'Drive m = Drive_AUTO; if (eq_Drive(&m, &mode)) print_Drive(&m); Gear g = Gear_AUTO; /* Mode_AUTO */ puts("Mode_SAFE");', 'static Drive last = Drive_SAFE;'));
        expect(r.remaining.map((m) => [m.word, m.context])).toEqual([['Mode_AUTO', 'comment'], ['Mode_SAFE', 'string']]);
        // what is left afterwards, as the rename lists it: the constants and the header count
        expect(mentionMatcher('enumeration', 'Mode', { members: ['AUTO'] })('Mode_AUTO')).toBe(true);
        expect(mentionMatcher('enumeration', 'Mode')('SharedMode')).toBe(true);
    });

    it('a renamed enumeration member: its constant only (Mode_AUTO -> Mode_AUTOMATIC), not another enumeration\'s nor the bare word', () => {
        const dir = out();
        mkdirSync(join(dir, 'generated/architecture/modules/MSC_mod'), { recursive: true });
        writeFileSync(join(dir, path('MSC')), file('MSC', 'int AUTO = 1; Mode m = Mode_AUTO; Gear g = Gear_AUTO; (void)AUTO;'));
        const renames = identifierRenames('enumeration member', 'AUTO', 'AUTOMATIC', { enumeration: 'Mode' });
        expect([...renames]).toEqual([['Mode_AUTO', 'Mode_AUTOMATIC']]);
        const r = renameIdentifiersInGeneratedTree(dir, renames);
        expect(r.rewritten.map((x) => [x.id, x.occurrences])).toEqual([['protect_exec_MSC', 1]]);
        expect(readFileSync(join(dir, path('MSC')), 'latin1')).toBe(file('MSC', 'int AUTO = 1; Mode m = Mode_AUTOMATIC; Gear g = Gear_AUTO; (void)AUTO;'));
        // the bare member name is no C name of the enumeration: not a mention of it
        const matches = mentionMatcher('enumeration member', 'AUTO', { enumeration: 'Mode' });
        expect([matches('AUTO'), matches('Mode_AUTO'), matches('Gear_AUTO')]).toEqual([false, true, false]);
    });
});

describe('renameInGeneratedTree and the manifest', () => {
    const module = (m: string, description = `"synchronous module ${m}"`) =>
        `char MODULE_NAME[] = "${m}";\nMODULE_DESCRIPTION(${region(`protect_description_${m}`, description)});\n${region(`protect_exec_${m}`, '\nstep();\n')}\n`;

    it('the rewritten region IDs are no edit outside the regions; an edit made before still is', async () => {
        const dir = out();
        writeTree(dir, [{ path: path('MSC'), content: module('MSC') }, { path: path('MSD'), content: module('MSD') }]);
        writeFileSync(join(dir, path('MSD')), readFileSync(join(dir, path('MSD')), 'latin1') + 'int mine;\n');
        await renameInGeneratedTree(dir, 'MSC', 'MSK');
        await renameInGeneratedTree(dir, 'MSD', 'MSE');
        const r = writeTree(dir, [{ path: path('MSK'), content: module('MSK') }, { path: path('MSE'), content: module('MSE') }]);
        expect(r.warnings.map((w) => w.file)).toEqual([path('MSE')]);
        expect(r.warnings[0]!.message).toMatch(/^edited outside its protected regions/);
        expect(r.orphaned).toEqual([`orphans/${path('MSE')}`]);
    });

    it('the default MODULE_DESCRIPTION follows the rename; one the user wrote does not', async () => {
        const dir = out();
        writeTree(dir, [{ path: path('MSC'), content: module('MSC') }, { path: path('MSD'), content: module('MSD', '"my MSD driver"') }]);
        const report = await renameInGeneratedTree(dir, 'MSC', 'MSK');
        expect(report.descriptions).toEqual([{ file: path('MSK'), line: 2, from: '"synchronous module MSC"', to: '"synchronous module MSK"' }]);
        await renameInGeneratedTree(dir, 'MSD', 'MSE');
        expect(readFileSync(join(dir, path('MSK')), 'latin1')).toContain(region('protect_description_MSK', '"synchronous module MSK"'));
        expect(readFileSync(join(dir, path('MSE')), 'latin1')).toContain(region('protect_description_MSE', '"my MSD driver"'));
        const r = writeTree(dir, [{ path: path('MSK'), content: module('MSK') }, { path: path('MSE'), content: module('MSE') }]);
        expect([r.orphaned, r.warnings]).toEqual([[], []]);
        expect(readFileSync(join(dir, path('MSK')), 'latin1')).toBe(module('MSK'));
    });
});
