import { describe, expect, test } from 'vitest';
import { addr2lineArgs, crashSite, crashSiteLine, crashSiteOfLine, CrashReports, parseAddr2line, MAX_FRAMES } from './crash-reports.js';

const head = (m: string) => `==contract-crash== module ${m} signal 11 SIGSEGV addr 0x0`;
const frame = (i: number, obj: string, off: string) => `==contract-crash== frame ${i} ${obj} 0x${off}`;
const end = (n: number) => `==contract-crash== end ${n} frames`;

function read(lines: string[], source = 'EST'): CrashReports {
  const r = new CrashReports();
  for (const l of lines) r.line(l, source);
  return r;
}

describe('CrashReports: the runtime crash report read from a module\'s output', () => {
  test('a whole block of the module that wrote it', () => {
    const r = read([head('EST'), frame(0, 'exe', '40d8'), frame(1, 'libc.so.6', '2724a'), end(2)]);
    expect(r.of('EST')).toEqual({ module: 'EST', signal: 11, signalName: 'SIGSEGV', address: '0', frames: [{ object: 'exe', offset: 0x40d8n }, { object: 'libc.so.6', offset: 0x2724an }] });
  });

  test('forged blocks are left out: another module\'s, a path as object, a gap, too many frames, a wrong count, a long line, no end', () => {
    expect(read([head('MSC'), frame(0, 'exe', '1'), end(1)]).of('MSC')).toBeUndefined();
    expect(read([head('MSC'), frame(0, 'exe', '1'), end(1)]).of('EST')).toBeUndefined();
    expect(read([head('EST'), frame(0, '/etc/passwd', '1'), end(1)]).of('EST')).toBeUndefined();
    expect(read([head('EST'), frame(0, '../x', '1'), end(1)]).of('EST')).toBeUndefined();
    expect(read([head('EST'), frame(1, 'exe', '1'), end(1)]).of('EST')).toBeUndefined();
    expect(read([head('EST'), frame(0, 'exe', '1;rm'), end(1)]).of('EST')).toBeUndefined();
    expect(read([head('EST'), frame(0, 'exe', '1'), frame(1, 'exe', '2'), end(1)]).of('EST')).toBeUndefined();
    expect(read([head('EST'), frame(0, 'exe', '1')]).of('EST')).toBeUndefined();
    expect(read([head('EST'), frame(0, 'exe', '1'.repeat(17)), end(1)]).of('EST')).toBeUndefined();
    const many = [head('EST'), ...Array.from({ length: MAX_FRAMES + 1 }, (_, i) => frame(i, 'exe', (i + 1).toString(16))), end(MAX_FRAMES + 1)];
    expect(read(many).of('EST')).toBeUndefined();
    expect(read([`${head('EST')}${' '.repeat(200)}`, frame(0, 'exe', '1'), end(1)]).of('EST')).toBeUndefined();
  });

  test('the last whole block counts (the crash handler\'s, written just before the death): a forged one before it does not stand for it', () => {
    const r = read([head('EST'), frame(0, '/etc/passwd', '1'), end(1), head('EST'), frame(0, 'exe', 'abc'), end(1), head('EST'), frame(0, 'exe', 'def'), end(1)]);
    expect(r.of('EST')!.frames).toEqual([{ object: 'exe', offset: 0xdefn }]);
    // a block left unfinished or malformed after a whole one does not erase it
    const cut = read([head('EST'), frame(0, 'exe', 'abc'), end(1), head('EST'), frame(0, '/etc/passwd', '1'), end(1), head('EST'), frame(0, 'exe', '1')]);
    expect(cut.of('EST')!.frames).toEqual([{ object: 'exe', offset: 0xabcn }]);
  });

  test('addr2line is given the executable the service names and the offsets only (a caller\'s: the byte before its return address)', () => {
    const r = read([head('EST'), frame(0, 'exe', '40d8'), frame(1, 'libc.so.6', '2724a'), frame(2, 'exe', '3b42'), end(3)]);
    expect(addr2lineArgs(r.of('EST')!, '/work/m/EST')).toEqual(['addr2line', '-a', '-f', '-i', '-e', '/work/m/EST', '0x40d8', '0x3b41']);
    const none = read([head('EST'), frame(0, 'libc.so.6', '1'), end(1)]);
    expect(addr2lineArgs(none.of('EST')!, '/work/m/EST')).toEqual([]);
  });
});

const OUT = [
  '0x00000000000040d8', 'est_update', '/work/src-gen/generated/architecture/modules/EST_mod/module.c:248',
  '_exec_module_state', '/work/src-gen/generated/architecture/modules/EST_mod/module.c:131 (discriminator 2)',
  '0x0000000000003b41', 'main', '/var/cache/contract-studio/runtime-0123456789abcdef/src/module_main.c:72',
  '',
].join('\n');

const ctx = { cwd: '/work/src-gen/generated/architecture/modules/EST_mod', root: '/work/src-gen', regions: new Map([['generated/architecture/modules/EST_mod/module.c', [{ id: 'protect_exec_EST', startLine: 240, endLine: 250 }]]]) };

describe('crashSite: the first place in the project\'s code', () => {
  const report = read([head('EST'), frame(0, 'exe', '40d8'), frame(1, 'libc.so.6', '2724a'), frame(2, 'exe', '3b42'), end(3)]).of('EST')!;

  test('addr2line\'s places, inlined ones too', () => {
    expect(parseAddr2line(OUT)).toEqual([
      [{ function: 'est_update', file: '/work/src-gen/generated/architecture/modules/EST_mod/module.c', line: 248 }, { function: '_exec_module_state', file: '/work/src-gen/generated/architecture/modules/EST_mod/module.c', line: 131 }],
      [{ function: 'main', file: '/var/cache/contract-studio/runtime-0123456789abcdef/src/module_main.c', line: 72 }],
    ]);
    expect(parseAddr2line('0x1\n??\n??:0\n')).toEqual([[{ function: '?', file: null, line: null }]]);
  });

  test('the site: file relative to the project, the region, the function; an error at that line', () => {
    const site = crashSite(report, parseAddr2line(OUT), ctx, 'src-gen', '/opt/contract/runtime')!;
    expect(site.said).toBe(' at src-gen/generated/architecture/modules/EST_mod/module.c:248 in its protected region protect_exec_EST (est_update)');
    expect(site.diagnostic).toMatchObject({ severity: 'error', file: 'generated/architecture/modules/EST_mod/module.c', line: 248, protectedRegion: { id: 'protect_exec_EST' }, message: 'EST crashed here: signal 11 (SIGSEGV) at address 0x0, in est_update: a bad pointer: NULL, freed, or past the end of an array', origin: 'run' });
    expect(site.frames).toEqual([
      // a frame in inlined code is one frame (crash-frames.ts, as contract trace tells it)
      '#0 est_update at src-gen/generated/architecture/modules/EST_mod/module.c:248 (inlined into _exec_module_state at src-gen/generated/architecture/modules/EST_mod/module.c:131)',
      '#1 libc.so.6+0x2724a',
      '#2 main at runtime/src/module_main.c:72',
    ]);
    expect(crashSiteOfLine(crashSiteLine('EST', site))).toEqual({ module: 'EST', said: site.said });
  });

  test('a crash in the runtime is told as the runtime\'s; no place known: no site', () => {
    const inRuntime = '0x00000000000040d8\nput_record\n/opt/contract/runtime/src/csvlog.c:310\n0x0000000000003b41\nmain\n/opt/contract/runtime/src/module_main.c:72\n';
    expect(crashSite(report, parseAddr2line(inRuntime), ctx, 'src-gen', '/opt/contract/runtime')).toMatchObject({ said: ' in the runtime, at runtime/src/csvlog.c:310 (put_record): no frame of the project\'s code was found', diagnostic: null });
    expect(crashSite(report, parseAddr2line('0x1\n??\n??:0\n0x2\n??\n??:0\n'), ctx, 'src-gen', '/opt/contract/runtime')).toBeNull();
  });
});
