import { writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { afterAll, beforeAll, describe, expect, it } from 'vitest';
import { generateFiles } from './generate-files.js';
import { writeTree } from '../writer/write-tree.js';
import { tutorialModel } from '../test-support/tutorial-model.js';
import { tempDir } from '../test-support/temp-dir.js';
import { RUNTIME_DIR, STRICT_CFLAGS, ensureRuntimeLibrary, run } from '../test-support/c-toolchain.js';

/** A C program exercising the generated per-type functions of the report's types (TypeA..TypeE). */
const PROGRAM = String.raw`
#include <stdio.h>
#include <string.h>
#include "SharedTypeE.h"
#include "SharedTypeB.h"
#include "SharedFunctiontestit.h"
#include "SharedFunctiondoit.h"
#define CHECK(c) do { if (!(c)) { printf("FAILED line %d: %s\n", __LINE__, #c); return 1; } } while (0)
int main(void) {
    TypeE e, back;
    unsigned char buffer[4096];
    memset(&e, 0, sizeof e); memset(&back, 0, sizeof back);
    char text[] = " { { \"FU FU\\\"x\" , 7, {1.5, -2, 3e2} } , {\"name\", -678} } trailing";
    int n = get_TypeE(&e, text);
    CHECK(n > 0 && strncmp(&text[n], " trailing", 9) == 0);
    CHECK(strcmp(e.message.message, "FU FU\"x") == 0);
    CHECK(e.message.messagetype == 7);
    CHECK(e.message.value.i == 1.5 && e.message.value.j == -2.0 && e.message.value.k == 300.0);
    CHECK(strcmp(e.data_.dataname, "name") == 0 && e.data_.datavalue == -678);
    unsigned int size = serialize_TypeE(&e, buffer);
    CHECK(size == 256 + sizeof(long) + 3 * sizeof(double) + 256 + sizeof(long));
    CHECK(deserialize_TypeE(&back, buffer) == size);
    CHECK(eq_TypeE(&e, &back) == 1 && diff_TypeE(&e, &back) == 0);
    back.data_.datavalue = 1;
    CHECK(eq_TypeE(&e, &back) == 0 && diff_TypeE(&e, &back) == 1);
    TypeE kept = e;
    CHECK(get_TypeE(&kept, "{{\"a\", 1, {1.0, 2.0}}, {\"b\", 2}}") == -1); /* missing field */
    CHECK(get_TypeE(&kept, "{{\"a\", 1.5, {1.0, 2.0, 3.0}}, {\"b\", 2}}") == -1); /* real for int */
    CHECK(eq_TypeE(&kept, &e) == 1); /* untouched on a parse error */
    TypeA a = {1.0, 2.0, 3.0}, b = {2.0, 3.0, 4.0}, c;
    CHECK(inf_TypeA(&a, &b) == 1 && sup_TypeA(&b, &a) == 1 && inf_TypeA(&b, &a) == 0);
    CHECK(infeq_TypeA(&a, &a) == 1 && supeq_TypeA(&a, &a) == 1 && supeq_TypeA(&a, &b) == 0);
    set_TypeA(&c, &b);
    CHECK(eq_TypeA(&c, &b) == 1);
    TypeB tb;
    CHECK(get_TypeB(&tb, "{{1.0,1.0,1.0},1}") > 0 && tb.coord.k == 1.0 && tb.frfrrrf == 1);
    CHECK(testit("x", &a) == 0); /* the generated default of a bool function */
    double d = 1.0; doit("s", &d);
    print_TypeE(&e); printf("\n");
    printf("ALL OK\n");
    return 0;
}
`;

describe('generated Shared<Type>.h functions (compiled C, ASan/UBSan)', () => {
    let dir: string;
    let cleanup: () => void;
    let lib: string;
    beforeAll(() => {
        ({ dir, cleanup } = tempDir('codegen-ctypes-'));
        lib = ensureRuntimeLibrary();
        writeTree(dir, generateFiles(tutorialModel()));
    }, 120_000);
    afterAll(() => cleanup());

    it('round-trips serialize/deserialize, parses nested structs and strings with get_, compares, prints', () => {
        const common = join(dir, 'generated/architecture/common');
        const src = join(dir, 'types_test.c');
        writeFileSync(src, PROGRAM);
        const exe = join(dir, 'types_test');
        run('gcc', [...STRICT_CFLAGS, '-fsanitize=address,undefined', '-fno-sanitize-recover=undefined', `-I${RUNTIME_DIR}/include`, `-I${common}`, src, lib, '-o', exe]);
        const out = run(exe, []);
        expect(out).toContain('ALL OK');
        expect(out).toContain('(object type TypeE : message : (object type TypeC : message : FU FU"x ; messagetype : 7 ;');
    }, 120_000);
});
