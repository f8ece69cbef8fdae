# sim.mk — the simulator's harness (docs/simulation.md), included by runtime/Makefile:
#   build/sim/libcontractsim.a  the engine cores + the harness + tools.c, compiled once;
#   build/sim/sim_main.o        main(): a project's simulator is these two linked with its
#                               generated vocabulary.c files and a sim_tables.c (the runner
#                               compiles only those, packages/simulator/src/harness/build.ts).
# Its tests are part of the engine core tests (tests/engines/test_sim.c, `make test-engines`).
SIM_DIR   := sim
SIM_OUT   := $(BUILD)/sim
SIM_SRCS  := src/engines/engine_values.c src/engines/value_ops.c src/engines/engine_check.c src/engines/sup_core.c \
             src/engines/sup_claims.c src/engines/ord_core.c src/engines/ord_stuck_cause.c src/tools.c \
             $(SIM_DIR)/sim_world.c $(SIM_DIR)/sim_protocol.c
SIM_HDRS  := $(wildcard include/*.h include/*/*.h src/engines/*.h $(SIM_DIR)/*.h)
SIM_CFLAGS := -std=c11 -Wall -Wextra $(WERROR) -O2 -g -Iinclude -Isrc/engines -I$(SIM_DIR)
SIM_OBJS  := $(patsubst %.c,$(SIM_OUT)/obj/%.o,$(notdir $(SIM_SRCS)))

vpath %.c src/engines src $(SIM_DIR)
$(SIM_OUT)/obj/%.o: %.c $(SIM_HDRS) $(BUILD_CONFIG)
	@mkdir -p $(dir $@)
	$(CC) $(SIM_CFLAGS) -c $< -o $@

$(SIM_OUT)/libcontractsim.a: $(SIM_OBJS)
	@rm -f $@
	$(AR) rcs $@ $^

$(SIM_OUT)/sim_main.o: $(SIM_DIR)/sim_main.c $(SIM_HDRS) $(BUILD_CONFIG)
	@mkdir -p $(dir $@)
	$(CC) $(SIM_CFLAGS) -c $< -o $@

.PHONY: sim
sim: $(SIM_OUT)/libcontractsim.a $(SIM_OUT)/sim_main.o
all: sim
