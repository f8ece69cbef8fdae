import { describe, expect, it } from 'vitest';
import { isRuntimeSourcePart } from './runtime-parts.js';

describe('the runtime source parts', () => {
    it('takes the build\'s files and folders, not the tests, benchmarks or image scripts', () => {
        for (const rel of ['Makefile', 'engines.mk', 'src', 'src/csvlog.c', 'include/contract/vocabulary.h', 'launcher/launch.c', 'sim']) expect(isRuntimeSourcePart(rel), rel).toBe(true);
        for (const rel of ['tests', 'tests/test_tools.c', 'bench/x.c', 'docker/build-image-offline.sh', 'srcx/a.c', 'Makefile.old', '']) expect(isRuntimeSourcePart(rel), rel).toBe(false);
    });
});
