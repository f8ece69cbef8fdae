// A field-sized Cactal architecture around one large supervisor file (valid Cactal: 0 errors), for
// the language server's latency benchmark and tests: 50 modules (40 synchronous in 8 periodic
// schemas, 10 asynchronous in 2 event schemas), 6 small supervisors, one scheduler configuration
// (the synthetic architecture of synthetic-architecture.js, scaled down) and the supervisor `BIG`
// (supervisors/BIG.contract, about 350 lines): 8 supervision functions whose rules have
// conditions on module ports and ORD events (tests, extractions, persistences) and a function
// that activates the small supervisors. 70 files.
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';
import { generateSyntheticArchitecture } from './synthetic-architecture.js';

/** Path of the large supervisor file in the generated architecture. */
export const LARGE_SUPERVISOR_FILE = 'supervisors/BIG.contract';

const WATCH_FUNCTIONS = 8;
const SYNC_MODULES = 40;

/**
 * @returns {Map<string, string>} relative path -> file content
 */
export function generateLargeSupervisorArchitecture() {
    const files = generateSyntheticArchitecture({ typeFiles: 1, periodicSchemas: 8, eventSchemas: 2, modulesPerSchema: 5, supervisors: 6 });
    /** module name -> file, in generation order (periodic schemas' modules first, then the event schemas') */
    const modules = [...files.keys()].filter((f) => f.startsWith('modules/'));
    const moduleName = (file) => file.slice('modules/'.length, -'.contract'.length);
    const syncModules = modules.slice(0, SYNC_MODULES);
    const asyncModules = modules.slice(SYNC_MODULES);
    const supervisors = [...files.keys()].filter((f) => f.startsWith('supervisors/')).map((f) => f.slice('supervisors/'.length, -'.contract'.length));

    files.set('types/limits.contract', [
        '// limits shared by the large supervisor',
        'const int FAIL_LIMIT = 3;',
        'const float SPEED_LIMIT = 2.5;',
        'enum Level { NOMINAL, DEGRADED, LOST }',
        'function bool tooMany(int count, int limit);',
        ''
    ].join('\n'));

    const used = new Set();
    const schemasUsed = new Set();
    const ports = [];
    const functions = [];
    for (let f = 0; f < WATCH_FUNCTIONS; f++) {
        const a = moduleName(syncModules[3 * f]);
        const b = moduleName(syncModules[3 * f + 1]);
        const c = moduleName(asyncModules[f]);
        used.add(syncModules[3 * f]).add(syncModules[3 * f + 1]).add(asyncModules[f]);
        const periodic = `periodic${Math.floor((3 * f) / 5)}`;
        const event = `event${f % 2}`;
        schemasUsed.add(`schemas/${periodic}.contract`).add(`schemas/${event}.contract`);
        const pa = 3 * f, pb = 3 * f + 1, pc = 3 * f + 2;
        ports.push(`        in :${pa} Fail0 fa${f};`, `        in :${pb} Fail0 fb${f};`, `        in :${pc} Msg0 msg${f};`);
        functions.push(
            `    // ${a} and ${b} of ${periodic}, the requests of ${c}`,
            `    watch${f}(Vec0 target = {1.0, 2.0, 3.0}, int level = ${f}) {`,
            '        local {',
            '            Vec0 goal = target;',
            '            Fail0 last;',
            '            string missed;',
            '            string status_text = "ok";',
            '            Level state = Level.NOMINAL;',
            '        }',
            '        rules {',
            '            LINK: [elapsed=1ms]',
            `                subscribe ${a}:1 => :${pa};`,
            `                subscribe ${b}:1 => :${pb};`,
            `                subscribe ${c}:0 =* :${pc};`,
            `                activate schema ${periodic}(gain = goal, mode = ${f})`,
            `                [${a}:1<fa${f}.value == 99>]`,
            `            WATCH: [${a}:1<(fa${f}.value > FAIL_LIMIT) | fa${f}.name == "overheat">(last = fa${f}) or ORD:0<ord_schema == "${periodic}">(missed = ord_schema)]`,
            `                compute apply0("watch", goal.x);`,
            '                notify :0 (report = status_text)',
            `                [${b}:1<((fb${f}.value >= 10) & fb${f}.name != "ok")>]`,
            `            TUNE: [(started(LINK){infinite} and ${b}:1<check0(fb${f}.name, goal)>(last = fb${f}))]`,
            `                parameterize ${a}({0.5, 0.5, ${f}.5} :0, 2 :1);`,
            '                notify :1 (alarm = last)',
            '                [duration(TUNE)=5s]',
            `            ASK: [${c}:0<((msg${f}.code > ${f}) & msg${f}.text == "go")>(goal = msg${f}.where, state = Level.DEGRADED) or endof(TUNE)]`,
            `                activate resttime module ${c}`,
            `                [${c}:0<(msg${f}.where.x < SPEED_LIMIT)>{10ms}]`,
            `            RECOVER: [ORD:1<ord_schema == "${periodic}">(missed = ord_schema) or endof(WATCH)]`,
            `                activate schema ${event}(gain = goal)`,
            `                [(${a}:1{5ms} and ${b}:1<tooMany(fb${f}.value, FAIL_LIMIT)>) or duration(RECOVER)=2s]`,
            '        }',
            '    }',
            ''
        );
    }
    const delegates = supervisors.slice(1, 4);
    functions.push(
        '    // hands the work to the lower supervisors, one after the other',
        '    delegate() {',
        '        local { string missed; }',
        '        rules {',
        ...delegates.flatMap((s, k) => [
            `            D${k}: [${k === 0 ? 'elapsed=1ms' : `endof(D${k - 1})`}]`,
            `                activate supervisor ${s}.run(target = {${k}.0, 0.0, 0.0})`,
            `                [ORD:0(missed = ord_schema) or duration(D${k})=${k + 1}s]`
        ]),
        '        }',
        '    }'
    );
    const imports = [
        'types/types0.contract', 'types/limits.contract',
        ...[...used].sort(), ...[...schemasUsed].sort(), 'sched.contract',
        ...delegates.map((s) => `supervisors/${s}.contract`)
    ].map((p) => `import "../${p}";`);
    files.set(LARGE_SUPERVISOR_FILE, [
        ...imports,
        '',
        '// The upper supervision level: each watch function follows two periodic modules and one',
        '// asynchronous module, and reacts to the scheduler\'s deadline misses (ORD:0) and refusals (ORD:1).',
        'supervisor BIG {',
        '    event flows {',
        ...ports,
        '        out :0 string report;',
        '        out :1 Fail0 alarm;',
        '    }',
        '',
        ...functions,
        '}',
        ''
    ].join('\n'));
    return files;
}

/** Writes the architecture under `dir`; returns the number of files written. */
export function writeLargeSupervisorArchitecture(dir) {
    const files = generateLargeSupervisorArchitecture();
    for (const [path, content] of files) {
        const full = join(dir, path);
        mkdirSync(dirname(full), { recursive: true });
        writeFileSync(full, content);
    }
    return files.size;
}
