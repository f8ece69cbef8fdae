import { describe, expect, it } from 'vitest';
import { BUILD_WITHOUT_FILE, gccProblems } from './gcc-problems.js';

describe('a build\'s diagnostics as Problems rows', () => {
  it('a file of src-gen: its path under the project, line, column, region; a linker error (no column) at column 1', () => {
    expect(gccProblems([
      { severity: 'error', message: "'x' undeclared", file: 'generated/architecture/modules/MAA_mod/module.c', line: 42, column: 7, protectedRegion: { id: 'protect_init_MAA' } },
      { severity: 'error', message: "undefined reference to `gripper_ready' (in function _init_module)", file: 'generated/architecture/modules/MAA_mod/module.c', line: 242, column: null, protectedRegion: null },
      { severity: 'note', message: 'first defined here', file: 'generated/architecture/common/h.h', line: 3, column: null },
    ], 'cell/src-gen/')).toEqual([
      { path: 'cell/src-gen/generated/architecture/modules/MAA_mod/module.c', line: 42, column: 7, message: "'x' undeclared (in region protect_init_MAA)", severity: 'error', source: 'gcc' },
      { path: 'cell/src-gen/generated/architecture/modules/MAA_mod/module.c', line: 242, column: 1, message: "undefined reference to `gripper_ready' (in function _init_module)", severity: 'error', source: 'gcc' },
      { path: 'cell/src-gen/generated/architecture/common/h.h', line: 3, column: 1, message: 'first defined here', severity: 'info', source: 'gcc' },
    ]);
  });

  it('no place, or a file outside the project: one group that opens nothing, the place in the message (never src-gen/null or src-gen//usr/...)', () => {
    const rows = gccProblems([
      { severity: 'error', message: 'cannot find -lgripper: No such file or directory', file: null, line: null, column: null },
      { severity: 'error', message: "conflicting types for 'size_t'", file: '/usr/include/stddef.h', line: 209, column: 23 },
    ], 'src-gen/');
    expect(rows.map((r) => [r.path, r.line, r.message])).toEqual([
      [BUILD_WITHOUT_FILE, 1, 'cannot find -lgripper: No such file or directory'],
      [BUILD_WITHOUT_FILE, 1, "/usr/include/stddef.h:209: conflicting types for 'size_t'"],
    ]);
  });

  it('a crash the run found (origin run) is labelled run, not gcc: no compiler said it', () => {
    const [row] = gccProblems([
      { severity: 'error', message: 'CTL crashed here: signal 8 (SIGFPE), in _exec: an integer division by zero, or INT_MIN / -1', file: 'generated/architecture/modules/CTL_mod/module.c', line: 244, column: null, protectedRegion: { id: 'protect_exec_CTL' }, origin: 'run' },
    ], 'linebot/src-gen/');
    expect(row).toMatchObject({ path: 'linebot/src-gen/generated/architecture/modules/CTL_mod/module.c', line: 244, severity: 'error', source: 'run' });
  });
});
