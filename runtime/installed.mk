# An installed ContrACT runtime (make install PREFIX=...): include/ and build/ only, already built,
# nothing to build here. A generated architecture's make calls this Makefile for build/libmodule.a and
# build/contract-launch, passing on its CC: a compiler other than the one build/ was built with (another
# target: a cross gcc against a runtime built for this machine, or the reverse) is refused here, naming
# both, rather than failing at the link with "file in wrong format".
BUILD := build
include build-config.mk

ifneq ($(and $(call given,CC),$(filter BUILT_CC,$(.VARIABLES))),)
GIVEN_CC_ID := $(call compiler_identity,$(CC))
# the same target (any version, any name: cc and gcc) links; a compiler that cannot run here is
# compared by name
ifneq ($(if $(GIVEN_CC_ID),$(firstword $(GIVEN_CC_ID)),$(CC)),$(if $(GIVEN_CC_ID),$(BUILT_TARGET),$(BUILT_CC)))
$(error the runtime installed in $(CURDIR) was built with CC=$(BUILT_CC) (target $(or $(BUILT_TARGET),unknown), gcc $(or $(BUILT_VERSION),unknown)), not CC=$(CC) ($(if $(GIVEN_CC_ID),target $(firstword $(GIVEN_CC_ID)),cannot be run here)): its build/libmodule.a does not link with that compiler. Give CC=$(BUILT_CC) (or no CC), or install a runtime built with CC=$(CC) (make -C <runtime sources> CC=$(CC) install PREFIX=...), or name its source folder: CONTRACT_RUNTIME=<runtime sources>, built when needed)
endif
endif

.PHONY: all
all:
	@true
