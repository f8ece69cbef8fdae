import { SANDBOX_RUNTIME_DIR } from '@contract-studio/conventions';

/**
 * The `CONTRACT_RUNTIME` default of every generated Makefile: where the `contract-gcc` image installs
 * the runtime (docs/architecture.md, Seam 3). It is a fixed path, never the generator's own
 * location, so that one model generates the same bytes from any folder on any machine (src-gen is
 * committed: docs/ci.md); the runtime is a build-time input (`make CONTRACT_RUNTIME=...`).
 */
export const DEFAULT_RUNTIME = SANDBOX_RUNTIME_DIR;

/**
 * The `CONTRACT_RUNTIME` lines of a generated Makefile: the default, then a stop with a message
 * saying how to set it when that folder holds no runtime (except for `make clean`, which needs none).
 */
export function runtimeSettings(): string {
    return [
        `CONTRACT_RUNTIME ?= ${DEFAULT_RUNTIME}`,
        'ifeq ($(wildcard $(CONTRACT_RUNTIME)/include/libmodule/libmodule.h),)',
        'ifneq ($(MAKECMDGOALS),clean)',
        '$(error no ContrACT runtime at CONTRACT_RUNTIME=$(CONTRACT_RUNTIME): set CONTRACT_RUNTIME to the runtime/ folder of ContrACT Studio, e.g. make CONTRACT_RUNTIME=/path/to/contract-studio/runtime)',
        'endif',
        'endif',
    ].join('\n');
}

/** Compiler settings shared by the Makefiles of executables and tools (the runtime library holds libmodule and the engines). */
export function makeSettings(extraIncludes: string[]): string {
    return [
        runtimeSettings(),
        'CFLAGS ?= -std=c11 -Wall -Wextra -O2 -g',
        '# extra flags from the caller (the build service adds -fdiagnostics-format=json)',
        'CFLAGS += $(EXTRA_CFLAGS)',
        `CPPFLAGS += -D_POSIX_C_SOURCE=200809L -I$(CONTRACT_RUNTIME)/include ${extraIncludes.map((i) => `-I${i}`).join(' ')}`,
        'CONTRACT_LIB = $(CONTRACT_RUNTIME)/build/libmodule.a',
        'LDLIBS += $(CONTRACT_LIB) -lpthread -lrt -lm',
    ].join('\n');
}
