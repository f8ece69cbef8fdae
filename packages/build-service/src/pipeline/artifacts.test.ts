import { mkdirSync, mkdtempSync, rmSync, symlinkSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { afterEach, beforeEach, describe, expect, test } from 'vitest';
import { RUN_LOG_MAX_BYTES, RUNTIME_LOG_MAX_BYTES, runLogMaxBytes, SERVICE_BOUNDS } from '../limits.js';
import { ARTIFACT_BOUNDS, artifactBoundsFor, artifactBytes, collectRunArtifacts, hostWorkDirReader, listHostDir } from './artifacts.js';
import { parseRecordLine } from '../trace/parse.js';
import { describeWorkUsage, hostWorkUsage } from './work-usage.js';

let work: string;
let outside: string;
beforeEach(() => {
  work = mkdtempSync(join(tmpdir(), 'artifacts-work-'));
  outside = mkdtempSync(join(tmpdir(), 'artifacts-host-'));
  writeFileSync(join(outside, 'secret.csv'), 'host secret\n');
});
afterEach(() => {
  rmSync(work, { recursive: true, force: true });
  rmSync(outside, { recursive: true, force: true });
});

describe('artifactBoundsFor: a run\'s logs are collected as far as its modules were let write them', () => {
  const MiB = 1024 * 1024;
  test('a large work dir\'s bound (over the 256 MiB default) is the file bound; a smaller one, or none, leaves the default', () => {
    // a 1 GiB work dir less a 6 MiB build: ORD may write 763.5 MiB, all of it collected
    const big = runLogMaxBytes(1018 * MiB);
    expect(artifactBoundsFor(big)).toEqual({ ...ARTIFACT_BOUNDS, fileBytes: big });
    expect(artifactBoundsFor(big).fileBytes).toBeGreaterThan(RUNTIME_LOG_MAX_BYTES);
    expect(artifactBoundsFor(runLogMaxBytes(64 * 1024 * MiB)).fileBytes).toBe(RUN_LOG_MAX_BYTES);
    expect(artifactBoundsFor(2 * RUN_LOG_MAX_BYTES).fileBytes).toBe(RUN_LOG_MAX_BYTES); // never more
    // the default work dir (188 MiB logs), a Makefile project (no bound given): the collector's default
    expect(artifactBoundsFor(runLogMaxBytes(250 * MiB))).toBe(ARTIFACT_BOUNDS);
    expect(artifactBoundsFor(null)).toBe(ARTIFACT_BOUNDS);
    expect(artifactBoundsFor(Number.NaN)).toBe(ARTIFACT_BOUNDS);
    expect(ARTIFACT_BOUNDS.fileBytes).toBe(RUNTIME_LOG_MAX_BYTES);
  });
});

describe('collectRunArtifacts on a host work dir (bwrap, none)', () => {
  test('takes the regular files of logs/, never a planted link, and says what it left out', async () => {
    mkdirSync(join(work, 'logs'));
    mkdirSync(join(work, 'run'));
    writeFileSync(join(work, 'logs', 'MAA_21-Nov-2026-22h57m07s.csv'), 'a;b\n1;2\n');
    writeFileSync(join(work, 'logs', 'ORD_x.csv'), 'c\n');
    symlinkSync(join(outside, 'secret.csv'), join(work, 'logs', 'planted.csv'));
    symlinkSync(outside, join(work, 'logs', 'dirlink'));
    mkdirSync(join(work, 'logs', 'sub'));
    writeFileSync(join(work, 'logs', '.hidden'), 'h');
    writeFileSync(join(work, 'run', 'MAA.sock'), '');
    const a = await collectRunArtifacts(hostWorkDirReader, work);
    expect(a.files.map((f) => [f.name, f.path, f.size, artifactBytes(f).toString()])).toEqual([
      ['MAA_21-Nov-2026-22h57m07s.csv', 'logs/MAA_21-Nov-2026-22h57m07s.csv', 8, 'a;b\n1;2\n'],
      ['ORD_x.csv', 'logs/ORD_x.csv', 2, 'c\n'],
    ]);
    expect(Object.fromEntries(a.skipped.map((s) => [s.name, s.reason]))).toEqual({
      '.hidden': 'name not allowed (letters, digits, _ . - only)',
      dirlink: 'not a regular file (symlink): not followed',
      'planted.csv': 'not a regular file (symlink): not followed',
      sub: 'not a regular file (dir): not followed',
    });
    expect(a.runDirLeftovers).toEqual(['MAA.sock']);
    expect(a.files.some((f) => artifactBytes(f).toString().includes('host secret'))).toBe(false);
  });

  test('a logs/ that is a link is not entered', async () => {
    symlinkSync(outside, join(work, 'logs'));
    const a = await collectRunArtifacts(hostWorkDirReader, work);
    expect(a.files).toEqual([]);
    expect(a.skipped).toEqual([{ name: 'logs', reason: 'logs/ is a symlink, not a directory: not followed' }]);
  });

  test('no logs/ at all gives an empty result', async () => {
    expect(await collectRunArtifacts(hostWorkDirReader, work)).toEqual({ files: [], skipped: [], runDirLeftovers: [] });
  });

  test('a log above the file or total bound is kept up to it, cut after a whole record, with a log-capped record', async () => {
    mkdirSync(join(work, 'logs'));
    const record = (k: number): string => `${1000 + k},2026-11-24T18:00:00.000000Z,MOT,ev,,,0,d\n`; // 46 bytes
    const csv = (n: number): string => Array.from({ length: n }, (_, k) => record(k)).join('');
    writeFileSync(join(work, 'logs', 'MOT_1.csv'), csv(60)); // 2760 bytes
    writeFileSync(join(work, 'logs', 'MOT_2.csv'), csv(200)); // 9200 bytes > the 4096-byte file bound
    writeFileSync(join(work, 'logs', 'MOT_3.csv'), csv(60));
    writeFileSync(join(work, 'logs', 'MOT_4.csv'), csv(60)); // the total bound is all but spent
    const a = await collectRunArtifacts(hostWorkDirReader, work, { entries: 100, files: 10, fileBytes: 4096, totalBytes: 9400 });
    expect(a.files.map((f) => [f.name, f.capped])).toEqual([
      ['MOT_1.csv', null],
      ['MOT_2.csv', '9200 bytes: the first 3542 kept (the 4096-byte file bound of the build service)'],
      ['MOT_3.csv', null],
    ]);
    const cut = artifactBytes(a.files[1]!).toString().split('\n');
    expect(cut.slice(0, 77)).toEqual(csv(77).split('\n').slice(0, 77)); // whole records, in order
    // at the time of the last record kept (1076): a record a trace reader reads, after what was kept
    expect(cut[77]).toMatch(/^1076,\d{4}-.*Z,MOT,log-capped,build-service,,9200,collected the first 3542 of 9200 bytes \(the 4096-byte bound of the build service\)$/);
    expect(cut[78]).toBe('');
    // the trace reader reads it as the log-capped record it is (a record with no time was 'unknown')
    expect(parseRecordLine('MOT_2.csv', 78, cut[77]!)).toMatchObject({ kind: 'log-capped', monoNs: '1076', module: 'MOT', peer: 'build-service' });
    expect(artifactBytes(a.files[2]!).toString()).toBe(csv(60));
    expect(a.skipped).toEqual([{ name: 'MOT_4.csv', reason: 'the 9400-byte total bound is reached', bound: true }]);
    expect(a.files[1]!.gzip.length).toBeLessThan(a.files[1]!.size);
  });

  test("a cut file that kept no record (a planted file of zeros) gets its log-capped record at the run's latest record, not at time 0", async () => {
    mkdirSync(join(work, 'logs'));
    writeFileSync(join(work, 'logs', 'BIG_1.csv'), Buffer.alloc(9000)); // sorts first, no line end
    writeFileSync(join(work, 'logs', 'MOT_1.csv'), 'mono_ns,wall_time,module,event,peer,port,size,detail\n5000,w,MOT,ev,,,0,d\n7000,w,MOT,ev,,,0,d\n');
    writeFileSync(join(work, 'logs', 'ORD_1.csv'), '6000,w,ORD,ev,,,0,d\n');
    const a = await collectRunArtifacts(hostWorkDirReader, work, { entries: 100, files: 10, fileBytes: 4096, totalBytes: 1 << 20 });
    expect(a.files.map((f) => f.name)).toEqual(['BIG_1.csv', 'MOT_1.csv', 'ORD_1.csv']);
    const big = artifactBytes(a.files[0]!).toString();
    expect(big).toMatch(/^7000,\d{4}-.*Z,BIG,log-capped,build-service,,9000,collected the first 0 of 9000 bytes \(the 4096-byte bound of the build service\)\n$/);
    expect(a.files[0]!.size).toBe(big.length);
    // the latest by value: a forged log's leading zeros do not make its time later
    writeFileSync(join(work, 'logs', 'ZZZ_1.csv'), '0000006500,w,ZZZ,ev,,,0,d\n');
    const zeros = await collectRunArtifacts(hostWorkDirReader, work, { entries: 100, files: 10, fileBytes: 4096, totalBytes: 1 << 20 });
    expect(artifactBytes(zeros.files[0]!).toString()).toMatch(/^7000,/);
    rmSync(join(work, 'logs', 'ZZZ_1.csv'));
    // alone, it has no other time than 0
    rmSync(join(work, 'logs', 'MOT_1.csv'));
    rmSync(join(work, 'logs', 'ORD_1.csv'));
    const alone = await collectRunArtifacts(hostWorkDirReader, work, { entries: 100, files: 10, fileBytes: 4096, totalBytes: 1 << 20 });
    expect(artifactBytes(alone.files[0]!).toString()).toMatch(/^0,/);
  });

  test('a log the disk refused (its log-capped record says so) is said to be cut by the full disk, not by its bound', async () => {
    mkdirSync(join(work, 'logs'));
    const text = 'mono_ns,wall_time,module,event,peer,port,size,detail\n1,t,CTL,run_started,,,0,a\n2,t,CTL,log-capped,,,24568,log could not be written past 24568 bytes (No space left on device): later records are not written\n';
    writeFileSync(join(work, 'logs', 'CTL_1.csv'), text);
    const a = await collectRunArtifacts(hostWorkDirReader, work);
    expect(a.files.map((f) => [f.name, f.capped])).toEqual([['CTL_1.csv', 'the disk refused its module\'s writes past 23.99 KiB (the work dir was full): later records were not written']]);
  });

  test('a log the logs\' disk reserve stopped says what filled the work dir (its biggest files, measured), not that the logs did', async () => {
    mkdirSync(join(work, 'logs'));
    const text = 'mono_ns,wall_time,module,event,peer,port,size,detail\n1,t,CTL,run_started,,,0,a\n2,t,CTL,log-capped,,,5200,log stopped at 5200 bytes: its disk had 100 bytes free; less than the logs\' 1048576-byte reserve (CONTRACT_LOG_DISK_RESERVE_BYTES) and the 80 bytes to write: later records are not written\n';
    writeFileSync(join(work, 'logs', 'CTL_1.csv'), text);
    writeFileSync(join(work, 'bigfile'), Buffer.alloc(3 * 1024 * 1024));
    let asked = 0;
    const a = await collectRunArtifacts(hostWorkDirReader, work, ARTIFACT_BOUNDS, undefined, {
      workFilledBy: async () => {
        asked++;
        const usage = await hostWorkUsage(work);
        return usage ? describeWorkUsage(usage) : null;
      },
    });
    expect(a.files[0]!.capped).toMatch(/^its module stopped writing at 5\.08 KiB: the work dir was nearly full, filled by bigfile 3 MiB, logs\/CTL_1\.csv \d+ B \(of 3 MiB in 2 file\(s\)\) \(the logs' disk reserve, CONTRACT_LOG_DISK_RESERVE_BYTES, keeps its last room\): later records were not written$/);
    expect(asked).toBe(1);
    // not measured: no guess either
    const unknown = await collectRunArtifacts(hostWorkDirReader, work);
    expect(unknown.files[0]!.capped).toBe('its module stopped writing at 5.08 KiB: the work dir was nearly full (the logs\' disk reserve, CONTRACT_LOG_DISK_RESERVE_BYTES, keeps its last room): later records were not written');
  });

  test("a log whose only log-capped record is the runtime's last one after the disk refused it (`K records not written after the log could not be written past N bytes`) is said to be cut by the full disk, with what the disk took", async () => {
    mkdirSync(join(work, 'logs'));
    const text = 'mono_ns,wall_time,module,event,peer,port,size,detail\n1,t,CTL,run_started,,,0,a\n2,t,CTL,log-capped,,,4085,257 records not written after the log could not be written past 4085 bytes (No space left on device)\n';
    writeFileSync(join(work, 'logs', 'CTL_1.csv'), text);
    const a = await collectRunArtifacts(hostWorkDirReader, work);
    expect(a.files.map((f) => [f.name, f.capped])).toEqual([['CTL_1.csv', 'the disk refused its module\'s writes past 3.99 KiB (the work dir was full): later records were not written']]);
    // the runtime's exit record at its bound is still the bound's
    writeFileSync(join(work, 'logs', 'CTL_1.csv'), text.replace(/4085,257 records.*\n$/, '65536,257 records not written after the log reached its 65536-byte bound\n'));
    const bound = await collectRunArtifacts(hostWorkDirReader, work);
    expect(bound.files[0]!.capped).toBe('the module reached its CSV log bound of 64 KiB (CONTRACT_LOG_MAX_BYTES): later records were not written');
  });

  test("a log the runtime capped itself (its log-capped records at the end) is flagged, not cut", async () => {
    mkdirSync(join(work, 'logs'));
    const text = 'mono_ns,wall_time,module,event,peer,port,size,detail\n1,t,MSC,run_started,,,0,a\n2,t,MSC,log-capped,,,8192,log reached its 8192-byte bound\n3,t,MSC,log-capped,,,8192,5 records not written\n';
    writeFileSync(join(work, 'logs', 'MSC_1.csv'), text);
    const a = await collectRunArtifacts(hostWorkDirReader, work);
    expect(a.files.map((f) => [f.name, f.capped])).toEqual([['MSC_1.csv', 'the module reached its CSV log bound of 8 KiB (CONTRACT_LOG_MAX_BYTES): later records were not written']]);
    expect(artifactBytes(a.files[0]!).toString()).toBe(text);
  });

  test('only the file count leaves whole logs out, and says so', async () => {
    mkdirSync(join(work, 'logs'));
    for (const name of ['a.csv', 'b.csv', 'c.csv']) writeFileSync(join(work, 'logs', name), 'x\n');
    const few = await collectRunArtifacts(hostWorkDirReader, work, { entries: 100, files: 2, fileBytes: 100, totalBytes: 1000 });
    expect(few.files.map((f) => f.name)).toEqual(['a.csv', 'b.csv']);
    expect(few.skipped).toEqual([{ name: 'c.csv', reason: 'more than 2 files', bound: true }]);
  });

  test("the modules' logs are collected before other files, even past the file bound and the entries looked at (a module wrote 1500 F_*.csv there)", async () => {
    mkdirSync(join(work, 'logs'));
    const logs = ['CTL_7-Dec-2026-02h45m54s.csv', 'MIS_7-Dec-2026-02h45m54s.csv', 'ORD_7-Dec-2026-02h45m54s.csv'];
    for (let i = 0; i < 1500; i++) writeFileSync(join(work, 'logs', `F_${i}.csv`), '');
    for (const name of logs) writeFileSync(join(work, 'logs', name), 'mono_ns\n');
    const a = await collectRunArtifacts(hostWorkDirReader, work, { entries: 100, files: 10, fileBytes: 100, totalBytes: 10_000 });
    expect(a.files.map((f) => f.name).slice(0, 3)).toEqual(logs);
    expect(a.files).toHaveLength(10);
    expect(a.skipped.filter((s) => s.bound)).toHaveLength(90);
    expect(a.skipped.at(-1)).toEqual({ name: 'logs/', reason: 'more than 100 entries: the others were not looked at' });
  });

  test('a logs/ and run/ of thousands of entries: a bounded number is looked at and listed', async () => {
    mkdirSync(join(work, 'logs'));
    mkdirSync(join(work, 'run'));
    const n = SERVICE_BOUNDS.listedEntries * 2;
    for (let i = 0; i < n; i++) {
      writeFileSync(join(work, 'logs', `m${String(i).padStart(5, '0')}.csv`), 'x\n');
      writeFileSync(join(work, 'run', `s${i}`), '');
    }
    const a = await collectRunArtifacts(hostWorkDirReader, work);
    expect(a.files).toHaveLength(256); // the file bound
    expect(a.skipped.length).toBeLessThanOrEqual(SERVICE_BOUNDS.listedEntries - 256 + 1);
    expect(a.skipped.at(-1)).toEqual({ name: 'logs/', reason: `more than ${SERVICE_BOUNDS.listedEntries} entries: the others were not looked at` });
    expect(a.runDirLeftovers.length).toBeLessThanOrEqual(SERVICE_BOUNDS.listedEntries);
  });

  test('a logs/ with 3,000 entries is looked at only up to the entry bound', async () => {
    mkdirSync(join(work, 'logs'));
    for (let i = 0; i < 3000; i++) writeFileSync(join(work, 'logs', `f${i}.csv`), '');
    const listing = await listHostDir(work, 'logs', 50);
    expect(listing && 'entries' in listing && listing.entries.length).toBe(50);
    const a = await collectRunArtifacts(hostWorkDirReader, work, { entries: 50, files: 10, fileBytes: 100, totalBytes: 1000 });
    expect(a.files).toHaveLength(10);
    expect(a.skipped.at(-1)).toEqual({ name: 'logs/', reason: 'more than 50 entries: the others were not looked at' });
    expect(a.skipped).toHaveLength(41);
  });
});
