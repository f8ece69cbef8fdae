# ContrACT Studio — top-level entry points. See README.md.
#   make start   install what is missing, build, and serve the IDE + build service on the tutorial
#   make test    install what is missing, build, and run every test (TypeScript, C, browser, sandboxes)
#   make bench   run every benchmark, write bench/results.json
.PHONY: setup start test test-ts test-c bench clean

setup:
	bash scripts/setup.sh

start: setup
	node packages/cli/bin/contract.js serve examples/tutorial

test: setup
	node scripts/run-tests.mjs

bench: setup
	npm run bench

clean:
	$(MAKE) -C runtime clean
