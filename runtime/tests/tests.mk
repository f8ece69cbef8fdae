# C tests: every test executable is built twice, normally (build/tests) and under
# ASan+UBSan (build/san/tests); `make test` runs the runner on both sets. The runner is linked with
# -Wl,--wrap=write: test_log_writer.c can stall writes as a slow disk does; -Wl,--wrap=pthread_create: it
# can refuse the log writer's thread as the process limit does (EAGAIN); -Wl,--wrap=fstatvfs: it can make
# the disk as full as it likes (the logs' disk reserve).
TEST_SRCS    := tests/runner.c tests/harness.c tests/test_tools.c tests/test_modules.c tests/test_processes.c \
                tests/test_ext_types.c tests/test_log_writer.c
TEST_HDRS    := $(wildcard tests/*.h tests/modules/*.h tests/report_msc/*.h tests/report_maa/*.h)
TEST_INC     := -Itests -Itests/report_msc
# The report's MSC and MAA module.c provoke these warnings by themselves (REQ_UNKNOWN fall-through,
# unused argc/argv and handler parameters, "%d" for an int field that Cactal maps to long):
# allowed for those two files only.
REPORT_ALLOW := -Wno-implicit-fallthrough -Wno-unused-parameter -Wno-format

# $(1) = output dir, $(2) = library, $(3) = extra flags, $(4) = launcher
define TEST_SET
$(1)/P $(1)/C1 $(1)/C2: tests/modules/tmod.c $(2) $(HDRS) $(TEST_HDRS)
	@mkdir -p $(1)
	$$(CC) $$(ALLFLAGS) $(3) $(TEST_INC) -DTMOD_NAME='"$$(notdir $$@)"' $$< $(2) -o $$@
$(1)/ECHO: tests/modules/emod.c $(2) $(HDRS) $(TEST_HDRS)
	@mkdir -p $(1)
	$$(CC) $$(ALLFLAGS) $(3) $(TEST_INC) $$< $(2) -o $$@
$(1)/controlECHO: tests/modules/control_echo.c $(2) $(HDRS) $(TEST_HDRS)
	@mkdir -p $(1)
	$$(CC) $$(ALLFLAGS) $(3) $(TEST_INC) -Itests/modules $$< $(2) -o $$@
$(1)/MSC: tests/report_msc/module.c $(2) $(HDRS) $(TEST_HDRS)
	@mkdir -p $(1)
	$$(CC) $$(ALLFLAGS) $(3) $(REPORT_ALLOW) $(TEST_INC) $$< $(2) -o $$@
$(1)/MAA: tests/report_maa/module.c $(2) $(HDRS) $(TEST_HDRS)
	@mkdir -p $(1)
	$$(CC) $$(ALLFLAGS) $(3) $(REPORT_ALLOW) $(TEST_INC) -Itests/report_maa $$< $(2) -o $$@
$(1)/controlMSC: tests/report_msc/controlMSC.c $(2) $(HDRS) $(TEST_HDRS)
	@mkdir -p $(1)
	$$(CC) $$(ALLFLAGS) $(3) $(TEST_INC) $$< $(2) -o $$@
$(1)/contract-launch: $(4)
	@mkdir -p $(1)
	cp $$< $$@
$(1)/runner: $(TEST_SRCS) $(2) $(HDRS) $(TEST_HDRS)
	@mkdir -p $(1)
	$$(CC) $$(ALLFLAGS) $(3) $(TEST_INC) $(TEST_SRCS) $(2) -lm -pthread -Wl,--wrap=write -Wl,--wrap=pthread_create -Wl,--wrap=fstatvfs -o $$@
endef

TEST_BINS = P C1 C2 ECHO controlECHO MSC MAA controlMSC contract-launch runner
$(eval $(call TEST_SET,$(BUILD)/tests,$(BUILD)/libmodule.a,,$(BUILD)/contract-launch))
$(eval $(call TEST_SET,$(BUILD)/san/tests,$(BUILD)/san/libmodule.a,$(SANFLAGS),$(BUILD)/san/contract-launch))

.PHONY: test-c test-san test-build test-names
test-build: $(addprefix $(BUILD)/tests/,$(TEST_BINS)) $(addprefix $(BUILD)/san/tests/,$(TEST_BINS))

test-c: $(addprefix $(BUILD)/tests/,$(TEST_BINS))
	@echo "== C tests (-Wall -Wextra -Werror)"
	$(BUILD)/tests/runner $(BUILD)/tests $(T)

test-san: $(addprefix $(BUILD)/san/tests/,$(TEST_BINS))
	@echo "== C tests under -fsanitize=address,undefined"
	ASAN_OPTIONS=detect_leaks=1:abort_on_error=0 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
	  $(BUILD)/san/tests/runner $(BUILD)/san/tests $(T)

# the runners' choice of tests by name (T=...): a name that chooses none fails (check_test_names.sh)
test-names: $(BUILD)/tests/runner $(BUILD)/tests/P $(BUILD)/engines/engine-tests
	@echo "== choosing tests by name"
	@bash tests/check_test_names.sh $(BUILD)/tests/runner $(BUILD)/tests $(BUILD)/engines/engine-tests

test: all test-c test-san
	@if [ -f engines.mk ]; then $(MAKE) --no-print-directory test-engines test-names; fi
