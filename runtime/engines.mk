# engines.mk — build, test and benchmark the ORD and supervisor engines (included by
# runtime/Makefile; also usable alone: make -f engines.mk test-engines). Paths are relative
# to runtime/.
#   make test-engines    core tests (virtual clock) plain and under ASan+UBSan
#   make bench-engines   writes ../bench/parts/engines.json
ENG_CC      ?= gcc
ENG_WARN    := -std=c11 -Wall -Wextra -Werror
ENG_INC     := -Iinclude -Isrc/engines -Itests/engines
ENG_SAN     := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
ENG_OUT     := build/engines
ENG_CORE    := src/engines/engine_values.c src/engines/engine_check.c src/engines/sup_core.c \
               src/engines/ord_core.c
ENG_HDRS    := $(wildcard include/contract/*.h src/engines/*.h tests/engines/*.h tests/engines/*.def)
ENG_TESTS   := $(wildcard tests/engines/*.c)

.PHONY: test-engines bench-engines

$(ENG_OUT)/engine-tests: $(ENG_CORE) $(ENG_TESTS) $(ENG_HDRS)
	@mkdir -p $(ENG_OUT)
	$(ENG_CC) $(ENG_WARN) -O2 -g $(ENG_INC) $(ENG_CORE) $(ENG_TESTS) -o $@

$(ENG_OUT)/engine-tests-san: $(ENG_CORE) $(ENG_TESTS) $(ENG_HDRS)
	@mkdir -p $(ENG_OUT)
	$(ENG_CC) $(ENG_WARN) -O1 -g $(ENG_SAN) $(ENG_INC) $(ENG_CORE) $(ENG_TESTS) -o $@

test-engines: $(ENG_OUT)/engine-tests $(ENG_OUT)/engine-tests-san
	@echo "== engine core tests"
	@$(ENG_OUT)/engine-tests
	@echo "== engine core tests (ASan+UBSan)"
	@$(ENG_OUT)/engine-tests-san
