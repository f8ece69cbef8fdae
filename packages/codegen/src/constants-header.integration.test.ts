/**
 * Named constants reach the generated C (docs/codegen.md "Named constants in C"): a project with a
 * constant of every kind generates `common/constants.h`, every module.c includes it, and code in a
 * module's protected regions that uses the constants by name (array sizes, loops, `#if`, `case`,
 * struct and array constants) builds with -Werror and reads the values written in Cactal.
 */
import { readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { EmptyFileSystem } from 'langium';
import { createCactalServices } from '@contract-studio/language';
import { describe, expect, it } from 'vitest';
import { generateFromArchitecture } from './generate-architecture.js';
import { generateFiles } from './generators/generate-files.js';
import { architectureFromModels } from './model/from-langium.js';
import { loadProject } from './test-support/load-project.js';
import { readTree, tempDir } from './test-support/temp-dir.js';
import { RUNTIME_DIR, STRICT_CFLAGS, ensureRuntimeLibrary, run } from './test-support/c-toolchain.js';
import { tutorialModel } from './test-support/tutorial-model.js';

const FILES: Record<string, string> = {
    'types.contract': `
enum Mode { IDLE, TELEOP, AUTO }
datatype Pose {float x, float y, float theta};
datatype Tagged {string name, Pose at, int[2] ids};
const int NJOINTS = 6;
const int OFFSET = -40;
const float GAIN = 0.1;
const float BIG = 1.5e300;
const float TINY = -2.5e-7;
const bool VERBOSE = true;
const bool QUIET = false;
const string FRAME = "base \\"link\\" \\\\ ??";
const Mode START_MODE = Mode.AUTO;
const float[3] WEIGHTS = {0.5, 1.0, 2.0};
const int[2][2] GRID = {{1, 2}, {3, 4}};
const Pose HOME = {1.0, 2.0, 0.25};
const Tagged DOCK = {"dock", {3.0, 4.0, 0.5}, {7, 8}};
const Pose[2] ROUTE = {{0.0, 0.0, 0.0}, {5.0, 6.0, 1.0}};
const string[2] NAMES = {"left", "right"};
`,
    'arm.contract': `import "types.contract";
synchronous module ARM {
    scheduling { C=1ms; }
    data flows { out :0 float[NJOINTS] q; }
}
`,
    'sched.contract': `import "arm.contract";
periodic schema move() {
    realtime { PERIOD=10ms; CRITICAL_DELAY=10ms; }
    modules { ARM (); }
}
scheduler configuration { modules { ARM; } schemas { move; } }
`,
};

const EXPECTED_HEADER = `//          named constants of the architecture (generated; do not edit)
#ifndef CONTRACT_GENERATED_CONSTANTS_H
#define CONTRACT_GENERATED_CONSTANTS_H
#include <stdbool.h>
#include "SharedMode.h"
#include "SharedPose.h"
#include "SharedTagged.h"

#define NJOINTS (6)
#define OFFSET (-40)
#define GAIN (0.1)
#define BIG (1.5e+300)
#define TINY (-2.5e-7)
#define VERBOSE (true)
#define QUIET (false)
#define FRAME "base \\"link\\" \\\\ \\?\\?"
#define START_MODE (Mode_AUTO)
#define WEIGHTS ((double[3]){ 0.5, 1.0, 2.0 })
#define GRID ((long[2][2]){ { 1, 2 }, { 3, 4 } })
#define HOME ((Pose){ 1.0, 2.0, 0.25 })
#define DOCK ((Tagged){ "dock", { 3.0, 4.0, 0.5 }, { 7, 8 } })
#define ROUTE ((Pose[2]){ { 0.0, 0.0, 0.0 }, { 5.0, 6.0, 1.0 } })
#define NAMES ((char[2][256]){ "left", "right" })

#endif
`;

/** User code for the protected regions of ARM's module.c: every constant used by name. */
const USER_IMPORTS = `#include <stdlib.h>
#if NJOINTS != 6 || !VERBOSE || QUIET || OFFSET >= 0
#error the constants are not preprocessor integers
#endif
static long joints[NJOINTS];
static const char *const frame = FRAME " (robot)";`;

const USER_STATE = `(void)stateindex;
int a[NJOINTS];
for (int i = 0; i < NJOINTS; i++) { a[i] = i; joints[i] = a[i]; q[i] = WEIGHTS[i % 3]; }
switch (a[5]) { case NJOINTS - 1: break; default: abort(); }
Pose home = HOME;
Tagged dock = DOCK;
Mode mode = START_MODE;
printf("NJOINTS=%d OFFSET=%d GAIN=%.17g BIG=%.17g TINY=%.17g VERBOSE=%d\\n", NJOINTS, OFFSET, GAIN, BIG, TINY, (int)VERBOSE);
printf("FRAME=%s|%s mode=%d\\n", FRAME, frame, (int)mode);
printf("home=%g,%g,%g route1=%g,%g grid=%ld,%ld\\n", home.x, home.y, HOME.theta, ROUTE[1].x, ROUTE[1].y, GRID[0][1], GRID[1][0]);
printf("dock=%s,%g,%ld names=%s,%s joints=%ld q=%g\\n", dock.name, dock.at.y, DOCK.ids[1], NAMES[0], NAMES[1], joints[5], q[5]);
*stateindex = -1;`;

/** Replaces the body of protected region `id` of a generated file (what a user does in the editor). */
function fillRegion(source: string, id: string, body: string): string {
    const start = source.indexOf(id);
    expect(start, `region ${id}`).toBeGreaterThan(0);
    const bodyStart = source.indexOf('\n', start) + 1;
    const end = source.indexOf('/*PROTECTED REGION END*/', bodyStart);
    expect(end).toBeGreaterThan(bodyStart);
    return source.slice(0, bodyStart) + body + '\n' + source.slice(end);
}

describe('named constants in the generated C', () => {
    it('common/constants.h defines every constant by name, in declaration order', async () => {
        const services = createCactalServices(EmptyFileSystem).Cactal;
        const { models, errors } = await loadProject(services, FILES);
        expect(errors).toEqual([]);
        const files = new Map(generateFiles(architectureFromModels(models)).map((f) => [f.path, f.content]));
        expect(files.get('generated/architecture/common/constants.h')).toBe(EXPECTED_HEADER);
        expect(files.get('generated/architecture/modules/ARM_mod/module.c')).toMatch(/#include "tools.h"\n#include "constants.h"\n/);
    });

    it('a project without constants has no constants.h and its modules do not include it', () => {
        const files = generateFiles(tutorialModel());
        expect(files.map((f) => f.path).filter((p) => p.includes('constants'))).toEqual([]);
        expect(files.filter((f) => f.content.includes('constants.h'))).toEqual([]);
    });

    it('user code in a protected region uses the constants: it builds with -Werror and reads the Cactal values', async () => {
        const services = createCactalServices(EmptyFileSystem).Cactal;
        const { models, errors } = await loadProject(services, FILES);
        expect(errors).toEqual([]);
        const { dir, cleanup } = tempDir('codegen-constants-');
        try {
            const report = generateFromArchitecture(architectureFromModels(models), dir);
            expect(report.errors).toEqual([]);
            expect(readTree(dir).get('generated/architecture/common/constants.h')).toBe(EXPECTED_HEADER);
            const arch = join(dir, 'generated', 'architecture');
            const modulePath = join(arch, 'modules', 'ARM_mod', 'module.c');
            let source = readFileSync(modulePath, 'utf8');
            source = fillRegion(source, 'protect_additional_import_ARM', USER_IMPORTS);
            source = fillRegion(source, 'protect_exec_ARM', USER_STATE);
            writeFileSync(modulePath, source);
            // the user's code is kept by a regeneration
            expect(generateFromArchitecture(architectureFromModels(models), dir).errors).toEqual([]);
            expect(readFileSync(modulePath, 'utf8')).toContain('int a[NJOINTS];');

            ensureRuntimeLibrary();
            const out = run('make', ['-j2', '-C', arch, 'all', `CONTRACT_RUNTIME=${RUNTIME_DIR}`, 'EXTRA_CFLAGS=-Werror -O0']);
            expect(out).not.toMatch(/warning:/);

            // the region's code, run on its own: the values are those of the .contract
            const main = join(dir, 'values.c');
            writeFileSync(main, [
                '#include <stdio.h>', '#include <stdlib.h>', '#include "tools.h"', '#include "constants.h"',
                USER_IMPORTS.replace('#include <stdlib.h>\n', ''),
                'int main(void) {', '    int state = 0; int *stateindex = &state; double q[NJOINTS];',
                USER_STATE, '    return 0;', '}'
            ].join('\n'));
            const exe = join(dir, 'values');
            run('gcc', [...STRICT_CFLAGS, '-pedantic', `-I${RUNTIME_DIR}/include`, `-I${join(arch, 'common')}`, `-I${join(arch, 'modules', 'ORD_mod')}`, main, '-o', exe]);
            expect(run(exe, []).split('\n')).toEqual([
                'NJOINTS=6 OFFSET=-40 GAIN=0.10000000000000001 BIG=1.5000000000000001e+300 TINY=-2.4999999999999999e-07 VERBOSE=1',
                'FRAME=base "link" \\ ??|base "link" \\ ?? (robot) mode=2',
                'home=1,2,0.25 route1=5,6 grid=2,3',
                'dock=dock,4,8 names=left,right joints=5 q=2',
                ''
            ]);
        } finally {
            cleanup();
        }
    }, 300_000);
});
