# `make bench`: runtime benchmark -> ../bench/parts/runtime.json (see bench/runtime_bench.c).
BENCH_DIR  := $(BUILD)/bench
BENCH_OUT  ?= ../bench/parts/runtime.json
ROUNDTRIPS ?= 100000

$(BENCH_DIR)/PONG $(BENCH_DIR)/SRC $(BENCH_DIR)/SINK: bench/bench_modules.c $(BUILD)/libmodule.a $(HDRS)
	@mkdir -p $(BENCH_DIR)
	$(CC) $(ALLFLAGS) -DBENCH_$(notdir $@) $< $(BUILD)/libmodule.a -o $@
$(BENCH_DIR)/runtime-bench: bench/runtime_bench.c $(BUILD)/libmodule.a $(HDRS)
	@mkdir -p $(BENCH_DIR)
	$(CC) $(ALLFLAGS) $< $(BUILD)/libmodule.a -o $@

.PHONY: bench
bench: $(BENCH_DIR)/PONG $(BENCH_DIR)/SRC $(BENCH_DIR)/SINK $(BENCH_DIR)/runtime-bench
	@mkdir -p $(dir $(BENCH_OUT))
	$(BENCH_DIR)/runtime-bench $(BENCH_DIR) $(BENCH_OUT) $(ROUNDTRIPS)
