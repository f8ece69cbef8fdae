import { posix } from 'node:path';

/** Folder of the architecture inside the output folder. */
export const ARCH_DIR = 'generated/architecture';

/**
 * How generated Makefiles find the runtime (docs/architecture.md Seam 3): `CONTRACT_RUNTIME`,
 * a path relative to the architecture folder or absolute, written as the Makefiles' default.
 */
export interface BuildSettings {
    /** CONTRACT_RUNTIME as seen from the architecture folder. */
    runtimeFromArchitecture: string;
}

/** CONTRACT_RUNTIME default for a Makefile at `dirFromArchitecture` (e.g. `modules/MSC_mod`). */
export function runtimeFrom(settings: BuildSettings, dirFromArchitecture: string): string {
    const r = settings.runtimeFromArchitecture;
    if (posix.isAbsolute(r)) return r;
    const up = dirFromArchitecture.split('/').filter(Boolean).map(() => '..');
    return posix.normalize(posix.join(...up, r));
}

/** Compiler settings shared by every generated Makefile (the runtime library holds libmodule and the engines). */
export function makeSettings(runtime: string, extraIncludes: string[]): string {
    return [
        `CONTRACT_RUNTIME ?= ${runtime}`,
        'CFLAGS ?= -std=c11 -Wall -Wextra -O2 -g',
        '# extra flags from the caller (the build service adds -fdiagnostics-format=json)',
        'CFLAGS += $(EXTRA_CFLAGS)',
        `CPPFLAGS += -D_POSIX_C_SOURCE=200809L -I$(CONTRACT_RUNTIME)/include ${extraIncludes.map((i) => `-I${i}`).join(' ')}`,
        'CONTRACT_LIB = $(CONTRACT_RUNTIME)/build/libmodule.a',
        'LDLIBS += $(CONTRACT_LIB) -lpthread -lrt -lm',
    ].join('\n');
}
