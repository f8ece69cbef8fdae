# build-config.mk — build/build-config, the toolchain build/ was built with, read and compared.
# Included by this folder's Makefile and by an installed runtime's (installed.mk).
#
# build/build-config holds make assignments: BUILT_CC, BUILT_AR, BUILT_CFLAGS, BUILT_CPPFLAGS,
# BUILT_WERROR, and the compiler's target and version (BUILT_TARGET: $(CC) -dumpmachine,
# BUILT_VERSION: -dumpfullversion), so that a compiler of the same name for another machine (a
# native ARM robot's gcc) is seen as another compiler.
BUILD         ?= build
BUILD_CONFIG  := $(BUILD)/build-config
TOOLCHAIN_VARS := CC AR CFLAGS CPPFLAGS WERROR

define newline


endef

# What build/build-config recorded (an older one, a single line "CC=... AR=...", records nothing).
BUILT_WITH := $(file <$(BUILD_CONFIG))
ifeq ($(firstword $(BUILT_WITH)),BUILT_CC)
$(eval $(BUILT_WITH))
endif

# given: the variable was set on make's command line or in the environment (a recursive make
# passes its command line's on): not make's default, not this Makefile's.
given = $(filter command environment,$(firstword $(origin $(1))))

# The target and version of a compiler, "TARGET VERSION", empty when it cannot be run here.
compiler_identity = $(strip $(shell $(1) -dumpmachine 2>/dev/null && $(1) -dumpfullversion 2>/dev/null))
