import { describe, it, expect } from 'vitest';
import { mkdtempSync, mkdirSync, writeFileSync, readFileSync, existsSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { renameInGeneratedTree, renameRegionId } from './rename-generated.js';

describe('renameRegionId', () => {
  it('renames only whole name parts', () => {
    expect(renameRegionId('protect_init_MAA', 'MAA', 'MAB')).toBe('protect_init_MAB');
    expect(renameRegionId('protect_eq_TypeA', 'TypeA', 'Pose')).toBe('protect_eq_Pose');
    expect(renameRegionId('protect_eq_TypeAB', 'TypeA', 'Pose')).toBe('protect_eq_TypeAB');
    expect(renameRegionId('MAA.init', 'MAA', 'XYZ')).toBe('XYZ.init');
  });
});

describe('renameInGeneratedTree', () => {
  it('moves the module folder and rewrites its region IDs, keeping user code', async () => {
    const root = mkdtempSync(join(tmpdir(), 'ide-rename-'));
    const mod = join(root, 'generated', 'architecture', 'modules', 'MSC_mod');
    mkdirSync(mod, { recursive: true });
    const body = '/*PROTECTED REGION ID(protect_init_MSC) ENABLED START*/\nmy_code();\n/*PROTECTED REGION END*/\n' +
      '/*PROTECTED REGION ID(protect_exec_MSCX) ENABLED START*/\nother();\n/*PROTECTED REGION END*/\n';
    writeFileSync(join(mod, 'module.c'), body);
    const report = await renameInGeneratedTree(root, 'MSC', 'MSK');
    const moved = join(root, 'generated', 'architecture', 'modules', 'MSK_mod', 'module.c');
    expect(existsSync(mod)).toBe(false);
    const text = readFileSync(moved, 'utf8');
    expect(text).toContain('ID(protect_init_MSK) ENABLED START*/\nmy_code();');
    expect(text).toContain('ID(protect_exec_MSCX)');
    expect(report.regionIds).toEqual([{ file: 'generated/architecture/modules/MSK_mod/module.c', from: 'protect_init_MSC', to: 'protect_init_MSK' }]);
  });

  it('refuses to overwrite an existing target', async () => {
    const root = mkdtempSync(join(tmpdir(), 'ide-rename-'));
    mkdirSync(join(root, 'MSC_mod'));
    mkdirSync(join(root, 'MSK_mod'));
    await expect(renameInGeneratedTree(root, 'MSC', 'MSK')).rejects.toThrow(/already exists/);
  });
});

describe('renameInGeneratedTree for datatypes and functions', () => {
  it('renames Shared<T>.h / SharedFunction<f>.h and their region IDs, leaving other entities alone', async () => {
    const root = mkdtempSync(join(tmpdir(), 'ide-rename-'));
    const common = join(root, 'generated', 'architecture', 'common');
    mkdirSync(common, { recursive: true });
    const region = (id: string, body: string) => `/*PROTECTED REGION ID(${id}) ENABLED START*/\n${body}\n/*PROTECTED REGION END*/\n`;
    writeFileSync(join(common, 'SharedTypeF.h'), region('protect_eq_TypeF', 'return a->fufu == b->fufu;'));
    writeFileSync(join(common, 'SharedTypeA.h'), region('protect_eq_TypeA', 'keep'));
    writeFileSync(join(common, 'SharedFunctiondoit.h'), region('protect_function_impl_doit', 'do_it_by_hand();'));
    await renameInGeneratedTree(root, 'TypeF', 'Pose');
    await renameInGeneratedTree(root, 'doit', 'execute');
    expect(readFileSync(join(common, 'SharedPose.h'), 'utf8')).toBe(region('protect_eq_Pose', 'return a->fufu == b->fufu;'));
    expect(readFileSync(join(common, 'SharedFunctionexecute.h'), 'utf8')).toBe(region('protect_function_impl_execute', 'do_it_by_hand();'));
    expect(readFileSync(join(common, 'SharedTypeA.h'), 'utf8')).toBe(region('protect_eq_TypeA', 'keep'));
    expect(existsSync(join(common, 'SharedTypeF.h'))).toBe(false);
  });

  it('refuses names that are not identifiers', async () => {
    await expect(renameInGeneratedTree(tmpdir(), '../x', 'y')).rejects.toThrow(/invalid entity name/);
  });
});
