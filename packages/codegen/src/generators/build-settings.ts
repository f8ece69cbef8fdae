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
        '$(error no ContrACT runtime at CONTRACT_RUNTIME=$(CONTRACT_RUNTIME): set CONTRACT_RUNTIME to the runtime/ folder of ContrACT Studio, e.g. make CONTRACT_RUNTIME=/path/to/contract-studio/runtime, or install one there: make install PREFIX=$(CONTRACT_RUNTIME) from that runtime/ folder (an installed CLI gives its sources: contract runtime-source DIR))',
        'endif',
        'endif',
    ].join('\n');
}

/**
 * Compiler settings shared by the Makefiles of executables and tools (the runtime library holds
 * libmodule and the engines). What the generated C needs to compile right (C11, POSIX 2008, the
 * runtime's and the tree's include folders, the runtime library) is always applied: `CFLAGS`,
 * `CPPFLAGS` or `LDLIBS` given on make's command line add to it (`override`), never drop it.
 * `CFLAGS` itself is the optimisation, debug and warning flags: given, it replaces them;
 * `EXTRA_CFLAGS` adds to them. `CC` not given (make's own default, `cc`) is the compiler the runtime
 * was built with (its `build/build-config`: a runtime cross-built is linked with the same cross gcc),
 * else `gcc`, the runtime's default.
 */
export function makeSettings(extraIncludes: string[]): string {
    return [
        runtimeSettings(),
        "# the compiler: CC=... given, else the runtime's (the one its build/build-config records), else gcc",
        'ifeq ($(origin CC),default)',
        "CC := $(or $(shell sed -n 's/^BUILT_CC := //p' $(CONTRACT_RUNTIME)/build/build-config 2>/dev/null),gcc)",
        'endif',
        '# the language and what the generated C needs: always given (CFLAGS and CPPFLAGS add to them)',
        'CONTRACT_CFLAGS = -std=c11',
        `CONTRACT_CPPFLAGS = -D_POSIX_C_SOURCE=200809L -I$(CONTRACT_RUNTIME)/include ${extraIncludes.map((i) => `-I${i}`).join(' ')}`,
        '# optimisation, debug and warnings: CFLAGS=... replaces them, EXTRA_CFLAGS=... adds to them',
        '# (the build service adds -fdiagnostics-format=json)',
        'CFLAGS ?= -Wall -Wextra -O2 -g',
        'override CFLAGS := $(CONTRACT_CFLAGS) $(CFLAGS) $(EXTRA_CFLAGS)',
        'override CPPFLAGS := $(CONTRACT_CPPFLAGS) $(CPPFLAGS)',
        'CONTRACT_LIB = $(CONTRACT_RUNTIME)/build/libmodule.a',
        'override LDLIBS := $(LDLIBS) $(CONTRACT_LIB) -lpthread -lrt -lm',
    ].join('\n');
}
