// Synthetic Cactal architecture generator (valid Cactal: 0 errors), shared by the language and
// codegen benchmarks. Defaults: 1,000 modules (800 synchronous, 200 asynchronous), 200 schemas
// (160 periodic with 5 modules each, 40 event with 5 each), 20 supervisors, 10 type files and
// one scheduler configuration = 1,231 files.
import { mkdirSync, writeFileSync } from 'node:fs';
import { dirname, join } from 'node:path';

const LETTERS = 'ABCDEFGHIJKLMNOPQRSTUVWXYZ';

/** Three-letter name number i (AAA, AAB, ...), never ORD. */
export function threeLetterName(i) {
    const reservedIndex = (14 * 26 + 17) * 26 + 3; // ORD
    const n = i >= reservedIndex ? i + 1 : i;
    return LETTERS[Math.floor(n / 676) % 26] + LETTERS[Math.floor(n / 26) % 26] + LETTERS[n % 26];
}

/**
 * @param {{ typeFiles?: number, periodicSchemas?: number, eventSchemas?: number, modulesPerSchema?: number, supervisors?: number }} [options]
 * @returns {Map<string, string>} relative path -> file content
 */
export function generateSyntheticArchitecture(options = {}) {
    const T = options.typeFiles ?? 10;
    const P = options.periodicSchemas ?? 160;
    const E = options.eventSchemas ?? 40;
    const K = options.modulesPerSchema ?? 5;
    const S = options.supervisors ?? 20;
    const files = new Map();
    let nameCounter = 0;
    const nextName = () => threeLetterName(nameCounter++);

    for (let t = 0; t < T; t++) {
        files.set(`types/types${t}.contract`, [
            `// synthetic types ${t}`,
            `datatype Vec${t} {float x = 0.0, float y = 0.0, float z = 0.0};`,
            `datatype Msg${t} {string text, int code = 0, Vec${t} where};`,
            `datatype Fail${t} {string name, int value};`,
            `function bool check${t}(string a, Vec${t} v);`,
            `function void apply${t}(string a, float b);`,
            ''
        ].join('\n'));
    }

    /** schema index -> { name, kind, type, modules: [{name, file}] } */
    const schemas = [];
    const syncModules = [];
    for (let s = 0; s < P + E; s++) {
        const periodic = s < P;
        const t = s % T;
        const schemaName = periodic ? `periodic${s}` : `event${s - P}`;
        const modules = [];
        for (let m = 0; m < K; m++) {
            const name = nextName();
            const file = `modules/${name}.contract`;
            modules.push({ name, file });
            const lines = [`import "../types/types${t}.contract";`, ''];
            if (periodic) {
                syncModules.push({ name, file });
                lines.push(
                    `synchronous module ${name} {`,
                    `    parameters { Vec${t} gain = {1.0, 2.0, 3.0} :0; int mode = ${m} :1; }`,
                    `    scheduling { C=10us; }`,
                    `    data flows {`,
                    `        in :0 Vec${t} in_value;`,
                    `        out :0 Vec${t} out_value;`,
                    `    }`,
                    `    event flows { out :1 Fail${t} failing; }`,
                    `}`, '');
            } else {
                lines.push(
                    `asynchronous module ${name} {`,
                    `    parameters { Vec${t} gain :0; }`,
                    `    event flows {`,
                    `        in :0 Msg${t} request;`,
                    `        out :0 Msg${t} reply;`,
                    `        out :1 Fail${t} failing;`,
                    `    }`,
                    `}`, '');
            }
            files.set(file, lines.join('\n'));
        }
        const imports = [`import "../types/types${t}.contract";`, ...modules.map((m) => `import "../${m.file}";`)];
        const body = periodic ? [
            `periodic schema ${schemaName}(Vec${t} gain = {0.5, 0.5, 0.5}, int mode = 1) {`,
            `    realtime { PERIOD=100ms; CRITICAL_DELAY=50ms; }`,
            `    modules {`,
            ...modules.map((m, i) => `        ${m.name} (${i === 0 ? 'gain:0, mode:1' : i === 1 ? '{1.0, 0.0, 0.0}:0' : ''});`),
            `    }`,
            `    scheduling graph {`,
            ...modules.slice(1).map((m, i) => `        ${modules[i].name} -> ${m.name};`),
            `    }`,
            `    communications {`,
            ...modules.slice(1).map((m, i) => `        ${modules[i].name}:0 -> ${m.name}:0 * ${1 + (i % 2)};`),
            `    }`,
            `}`
        ] : [
            `event schema ${schemaName}(Vec${t} gain = {0.1, 0.2, 0.3}) {`,
            `    modules {`,
            ...modules.map((m, i) => `        ${m.name} (${i === 0 ? 'gain:0' : ''});`),
            `    }`,
            `    communications {`,
            ...modules.slice(1).map((m, i) => `        ${modules[i].name}:0 ${i % 2 ? '=>' : '=*'} ${m.name}:0;`),
            `    }`,
            `}`
        ];
        const file = `schemas/${schemaName}.contract`;
        files.set(file, [...imports, '', ...body, ''].join('\n'));
        schemas.push({ name: schemaName, file, periodic, type: t, modules });
    }

    const periodicSchemas = schemas.filter((s) => s.periodic);
    files.set('sched.contract', [
        ...syncModules.map((m) => `import "${m.file}";`),
        ...periodicSchemas.map((s) => `import "${s.file}";`),
        '',
        'scheduler configuration {',
        '    modules {',
        ...syncModules.map((m) => `        ${m.name};`),
        '    }',
        '    schemas {',
        ...periodicSchemas.map((s) => `        ${s.name};`),
        '    }',
        '}',
        ''
    ].join('\n'));

    // supervisors: supervisor i uses the schemas of its type class, split between the supervisors of that class
    const supNames = [];
    for (let i = 0; i < S; i++) supNames.push(nextName());
    for (let i = 0; i < S; i++) {
        const t = i % T;
        const peers = Math.max(1, Math.ceil(S / T));
        const slot = Math.floor(i / T);
        const mine = (list) => list.filter((s) => s.type === t).filter((_s, k, arr) => Math.floor(k * peers / arr.length) === slot);
        const myPeriodic = mine(periodicSchemas);
        const myEvent = mine(schemas.filter((s) => !s.periodic));
        const children = i === 0 ? supNames.slice(1) : [];
        const subscribed = myPeriodic.map((s) => s.modules[s.modules.length - 1]);
        const imports = [
            `import "types/types${t}.contract";`,
            ...subscribed.map((m) => `import "${m.file}";`),
            ...myEvent.map((s) => `import "${s.modules[0].file}";`),
            ...[...myPeriodic, ...myEvent].map((s) => `import "${s.file}";`),
            'import "sched.contract";',
            ...children.map((c) => `import "supervisors/${c}.contract";`)
        ];
        const rel = (line) => line.replace('import "', 'import "../');
        const ports = [
            ...myPeriodic.map((_s, k) => `        in :${k} Fail${t} f${k};`),
            `        in :${myPeriodic.length} Msg${t} message;`,
            `        out :0 string status;`
        ];
        const rules = [];
        myPeriodic.forEach((s, k) => {
            const mod = subscribed[k];
            rules.push(
                `            P${k}: [elapsed=${k + 1}ms]`,
                `                subscribe ${mod.name}:1 => :${k};`,
                `                activate schema ${s.name}(gain = tgt, mode = ${k})`,
                `                [${mod.name}:1(fail = f${k}, status_text = "failed")]`);
        });
        myEvent.forEach((s, k) => {
            rules.push(
                `            E${k}: [started(P0)]`,
                `                activate schema ${s.name}(gain = tgt);`,
                `                activate resttime module ${s.modules[0].name}`,
                `                [endof(P0)]`);
        });
        if (myPeriodic.length > 0) {
            const mod = subscribed[0];
            rules.push(
                `            WATCH: [(started(P0){infinite} and ${mod.name}:1<(f0.value > 3) | f0.name == "x">(fail = f0))]`,
                `                compute apply${t}("watch", tgt.x);`,
                `                notify :0 (status = status_text)`,
                `                [duration(WATCH)=10s]`);
        }
        children.forEach((c, k) => {
            rules.push(
                `            CHILD${k}: [elapsed=${k + 1}ms]`,
                `                activate supervisor ${c}.run()`,
                `                [elapsed=20s]`);
        });
        files.set(`supervisors/${supNames[i]}.contract`, [
            ...imports.map(rel),
            '',
            `supervisor ${supNames[i]} {`,
            '    event flows {',
            ...ports,
            '    }',
            `    run(Vec${t} target = {1.0, 2.0, 3.0}) {`,
            '        local {',
            `            Vec${t} tgt = target;`,
            `            Fail${t} fail;`,
            '            string status_text = "ok";',
            '        }',
            '        rules {',
            ...rules,
            '        }',
            '    }',
            '}',
            ''
        ].join('\n'));
    }
    return files;
}

/** Writes the architecture under `dir`; returns the number of files written. */
export function writeSyntheticArchitecture(dir, options = {}) {
    const files = generateSyntheticArchitecture(options);
    for (const [path, content] of files) {
        const full = join(dir, path);
        mkdirSync(dirname(full), { recursive: true });
        writeFileSync(full, content);
    }
    return files.size;
}
