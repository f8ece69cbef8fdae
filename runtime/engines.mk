# engines.mk — build, test and benchmark the ORD and supervisor engines (included by
# runtime/Makefile; also usable alone: make -f engines.mk test-engines). Paths are relative
# to runtime/.
#   make test-engines    core tests (virtual clock) plain and under ASan+UBSan, then the
#                        integration test with real processes (plain and ASan+UBSan)
#   make bench-engines   writes ../bench/parts/engines.json
ENG_CC      ?= gcc
ENG_WARN    := -std=c11 -Wall -Wextra -Werror -pthread
ENG_INC     := -Iinclude -Isrc/engines -Itests/engines -Isim
ENG_SAN     := -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
ENG_OUT     := $(BUILD)/engines
ENG_CORE    := src/engines/engine_values.c src/engines/value_ops.c src/engines/engine_check.c src/engines/sup_core.c src/engines/sup_claims.c \
               src/engines/ord_core.c src/engines/ord_stuck_cause.c
ENG_HDRS    := $(wildcard include/contract/*.h src/engines/*.h tests/engines/*.h tests/engines/*.def sim/*.h) tests/test_select.h
ENG_TESTS   := $(wildcard tests/engines/*.c)
# libmodule-free parts of the bindings, tested with the cores
ENG_UNITS   := src/engines/hold_lock.c
# the simulator's harness (sim/sim.mk), tested with the cores (tests/engines/test_sim.c)
ENG_UNITS   += sim/sim_world.c sim/sim_protocol.c

.PHONY: test-engines bench-engines

$(ENG_OUT)/engine-tests: $(ENG_CORE) $(ENG_UNITS) $(ENG_TESTS) $(ENG_HDRS)
	@mkdir -p $(ENG_OUT)
	$(ENG_CC) $(ENG_WARN) -O2 -g $(ENG_INC) $(ENG_CORE) $(ENG_UNITS) $(ENG_TESTS) -o $@

$(ENG_OUT)/engine-tests-san: $(ENG_CORE) $(ENG_UNITS) $(ENG_TESTS) $(ENG_HDRS)
	@mkdir -p $(ENG_OUT)
	$(ENG_CC) $(ENG_WARN) -O1 -g $(ENG_SAN) $(ENG_INC) $(ENG_CORE) $(ENG_UNITS) $(ENG_TESTS) -o $@

# T='word ...' runs only the core tests whose names contain one of the words (`test_` optional;
# a word that names none fails, with the near names; T=--list lists them) and not the
# integration test (ITEST_ONLY=... make -C runtime test-engines-integration runs its scenarios)
test-engines: $(ENG_OUT)/engine-tests $(ENG_OUT)/engine-tests-san
	@echo "== engine core tests"
	@$(ENG_OUT)/engine-tests $(T)
ifeq ($(filter --list,$(T)),)
	@echo "== engine core tests (ASan+UBSan)"
	@$(ENG_OUT)/engine-tests-san $(T)
endif
ifeq ($(strip $(T)),)
	@$(MAKE) --no-print-directory test-engines-integration
else
	@echo "(T=$(T): the integration test is not run; ITEST_ONLY=name make -C runtime test-engines-integration runs its scenarios)"
endif

# ---- integration test: real processes through libmodule (needs the runtime Makefile's
# $(BUILD)/libmodule.a, $(BUILD)/san/libmodule.a and $(BUILD)/contract-launch) ----
ENG_IT_SRC  := tests/engines/integration
ENG_IT_DEPS := $(wildcard $(ENG_IT_SRC)/*.h) $(wildcard include/*/*.h) tests/engines/engine_executable.h
ENG_IT_MAIN := $(wildcard $(ENG_IT_SRC)/itest*.c) $(ENG_IT_SRC)/stall_watch.c

# The test's executables: ENG_IT_FROM_<exe> = its source in $(ENG_IT_SRC), ENG_IT_FLAGS_<exe> =
# its -D flags. Each is built twice: $(ENG_OUT)/it (plain) and $(ENG_OUT)/it-san (ASan+UBSan).
ENG_IT_EXES := IMA IMB IMC ORD ISU AMX GLT SLV SHA SHB rsc/ORD RMA RMB RMC RSU HTA HTB \
               undo/ORD UMA AMY UPA USM PQS AMB DLA DLB AMD AME stk/ORD SKS STK OKM CRS AMS FLM AMF AMC
$(foreach m,IMA IMB IMC RMA RMB RMC UMA,$(eval ENG_IT_FROM_$(m) := imod.c)$(eval ENG_IT_FLAGS_$(m) := -DIMOD_NAME='"$(m)"'))
ENG_IT_FLAGS_RMB += -DIMOD_SLOW_AT=4
ENG_IT_FROM_ORD := iord.c
ENG_IT_FROM_rsc/ORD := iord.c
ENG_IT_FLAGS_rsc/ORD := -DIORD_RSC
ENG_IT_FROM_ISU := isup.c
ENG_IT_FROM_AMX := amod.c
ENG_IT_FROM_GLT := inest.c
ENG_IT_FLAGS_GLT := -DINEST_TOP
ENG_IT_FROM_SLV := inest.c
ENG_IT_FROM_SHA := ishare.c
ENG_IT_FLAGS_SHA := -DISHARE_TOP
ENG_IT_FROM_SHB := ishare.c
ENG_IT_FROM_RSU := ireactivate.c
ENG_IT_FROM_HTA := itoggle.c
ENG_IT_FLAGS_HTA := -DITOGGLE_TOP
ENG_IT_FROM_HTB := itoggle.c
ENG_IT_FROM_undo/ORD := iord.c
ENG_IT_FLAGS_undo/ORD := -DIORD_UNDO
ENG_IT_FROM_AMY := amod.c
ENG_IT_FLAGS_AMY := -DAMOD_NAME='"AMY"'
ENG_IT_FROM_UPA := iundo.c
ENG_IT_FLAGS_UPA := -DIUNDO_TOP
ENG_IT_FROM_USM := iundo.c
ENG_IT_FROM_PQS := ilate.c
ENG_IT_FROM_AMB := amod.c
ENG_IT_FLAGS_AMB := -DAMOD_NAME='"AMB"' -DAMOD_BUSY_MS=300
ENG_IT_FROM_AMS := amod.c
ENG_IT_FLAGS_AMS := -DAMOD_NAME='"AMS"' -DAMOD_BUSY_MS=5000
ENG_IT_FROM_DLA := icross.c
ENG_IT_FLAGS_DLA := -DICROSS_TOP
ENG_IT_FROM_DLB := icross.c
ENG_IT_FROM_stk/ORD := iord.c
ENG_IT_FLAGS_stk/ORD := -DIORD_STK
ENG_IT_FROM_SKS := istuck.c
$(foreach m,STK OKM CRS FLM,$(eval ENG_IT_FROM_$(m) := imod.c)$(eval ENG_IT_FLAGS_$(m) := -DIMOD_NAME='"$(m)"'))
ENG_IT_FLAGS_STK += -DIMOD_STUCK_AT=5
ENG_IT_FLAGS_CRS += -DIMOD_KILLED_AT=5
ENG_IT_FLAGS_FLM += -DIMOD_WORK_NS=3000000
ENG_IT_FROM_AMF := amod.c
ENG_IT_FLAGS_AMF := -DAMOD_NAME='"AMF"' -DAMOD_PERIOD_NS=0
ENG_IT_FROM_AMC := amod.c
ENG_IT_FLAGS_AMC := -DAMOD_NAME='"AMC"' -DAMOD_EVENT_MS=5
$(foreach m,AMD AME,$(eval ENG_IT_FROM_$(m) := amod.c)$(eval ENG_IT_FLAGS_$(m) := -DAMOD_NAME='"$(m)"' -DAMOD_BUSY_MS=250 -DAMOD_BUSY_ALWAYS=1))

# $(1) = output dir, $(2) = libmodule.a, $(3) = extra flags, $(4) = executable
define ENG_IT_EXE
$(1)/$(4): $(ENG_IT_SRC)/$(ENG_IT_FROM_$(4)) $(2) $(ENG_IT_DEPS)
	@mkdir -p $$(@D)
	$$(ENG_CC) $(ENG_WARN) -O2 $(3) -Iinclude $(ENG_IT_FLAGS_$(4)) $$< $(2) -o $$@
endef
$(foreach e,$(ENG_IT_EXES),$(eval $(call ENG_IT_EXE,$(ENG_OUT)/it,$(BUILD)/libmodule.a,,$(e))))
$(foreach e,$(ENG_IT_EXES),$(eval $(call ENG_IT_EXE,$(ENG_OUT)/it-san,$(BUILD)/san/libmodule.a,$(ENG_SAN),$(e))))
# the driver (itest) starts and watches the executables: it is built once, the sanitised set takes a copy
$(ENG_OUT)/it/itest: $(ENG_IT_MAIN) $(ENG_IT_DEPS)
	@mkdir -p $(@D)
	$(ENG_CC) $(ENG_WARN) -O2 -pthread $(ENG_IT_MAIN) -o $@
$(ENG_OUT)/it-san/itest: $(ENG_OUT)/it/itest
	@mkdir -p $(@D)
	cp $< $@
ENG_IT_BINS := $(ENG_IT_EXES) itest

.PHONY: test-engines-integration
test-engines-integration: $(addprefix $(ENG_OUT)/it/,$(ENG_IT_BINS)) \
                          $(addprefix $(ENG_OUT)/it-san/,$(ENG_IT_BINS)) $(BUILD)/contract-launch
	@echo "== engine integration test (real processes)"
	@$(ENG_OUT)/it/itest $(ENG_OUT)/it $(BUILD)/contract-launch
	@echo "== engine integration test (real processes, ASan+UBSan)"
	@$(ENG_OUT)/it-san/itest $(ENG_OUT)/it-san $(BUILD)/contract-launch

# ---- benchmark -> ../bench/parts/engines.json (see tests/engines/bench/bench_engines.c) ----
ENG_BENCH_SRC := tests/engines/bench
ENG_BENCH_OUT := $(ENG_OUT)/bench
ENG_BENCH_SECONDS ?= 10.2

$(ENG_BENCH_OUT)/BMA $(ENG_BENCH_OUT)/BMB $(ENG_BENCH_OUT)/BMC: $(ENG_IT_SRC)/imod.c $(ENG_IT_SRC)/imodule.h $(BUILD)/libmodule.a
	@mkdir -p $(ENG_BENCH_OUT)
	$(ENG_CC) $(ENG_WARN) -O2 -Iinclude -DIMOD_NAME='"$(notdir $@)"' -DIMOD_WORK_NS=20000 $< $(BUILD)/libmodule.a -o $@
$(ENG_BENCH_OUT)/ORD: $(ENG_BENCH_SRC)/bord.c $(ENG_BENCH_SRC)/btables.h tests/engines/engine_executable.h $(BUILD)/libmodule.a
	@mkdir -p $(ENG_BENCH_OUT)
	$(ENG_CC) $(ENG_WARN) -O2 -Iinclude $< $(BUILD)/libmodule.a -o $@
$(ENG_BENCH_OUT)/BSU: $(ENG_BENCH_SRC)/bsup.c $(ENG_BENCH_SRC)/btables.h tests/engines/engine_executable.h $(BUILD)/libmodule.a
	@mkdir -p $(ENG_BENCH_OUT)
	$(ENG_CC) $(ENG_WARN) -O2 -Iinclude $< $(BUILD)/libmodule.a -o $@
$(ENG_BENCH_OUT)/bench_engines: $(ENG_BENCH_SRC)/bench_engines.c $(ENG_BENCH_SRC)/platform_probe.c \
                                 $(ENG_BENCH_SRC)/platform_probe.h launcher/rt_placement.c launcher/rt_placement.h \
                                 $(ENG_CORE) $(ENG_HDRS)
	@mkdir -p $(ENG_BENCH_OUT)
	$(ENG_CC) $(ENG_WARN) -O2 $(ENG_INC) -Ilauncher $< $(ENG_BENCH_SRC)/platform_probe.c launcher/rt_placement.c \
	  $(ENG_CORE) -o $@

bench-engines: $(addprefix $(ENG_BENCH_OUT)/,BMA BMB BMC ORD BSU bench_engines) $(BUILD)/contract-launch
	@mkdir -p ../bench/parts
	$(ENG_BENCH_OUT)/bench_engines $(ENG_BENCH_OUT) $(BUILD)/contract-launch ../bench/parts/engines.json $(ENG_BENCH_SECONDS)
	@cat ../bench/parts/engines.json
