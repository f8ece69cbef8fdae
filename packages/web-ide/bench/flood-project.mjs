// A project whose module floods its stdout: the tutorial with MSA printing `rate` lines a second
// for `seconds` from a thread its init starts (its exec region keeps its period). Used by
// log-flood-bench.mjs and test/e2e/log-flood.e2e.test.ts.
import { cpSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { fileURLToPath } from 'node:url';

const root = fileURLToPath(new URL('../../..', import.meta.url));

/** Writes the flooding tutorial into `dir` (created). Each line: `flood 0000123: the quick brown fox jumps over the lazy dog`; the last: `flood done: N lines`. */
export function floodProject(dir, rate, seconds) {
  cpSync(join(root, 'examples/tutorial'), dir, { recursive: true, filter: (src) => !/[/]logs$/.test(src) });
  const file = join(dir, 'src-gen/generated/architecture/modules/MSA_mod/module.c');
  let c = readFileSync(file, 'utf8');
  const region = (id, body) => {
    const re = new RegExp(`(/\\*PROTECTED REGION ID\\(${id}\\) ENABLED START\\*/)[\\s\\S]*?(/\\*PROTECTED REGION END\\*/)`);
    if (!re.test(c)) throw new Error(`no region ${id} in ${file}`);
    c = c.replace(re, (_m, a, b) => `${a}\n${body}\n${b}`);
  };
  region('protect_additional_import_MSA', `#include <pthread.h>
static void *flood(void *arg) {
    (void)arg;
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    long n = 0;
    for (long ms = 0; ms < ${seconds * 1000}L; ms++) {
        for (long i = 0; i < ${Math.max(1, Math.round(rate / 1000))}L; i++)
            printf("flood %07ld: the quick brown fox jumps over the lazy dog\\n", n++);
        t.tv_nsec += 1000000L;
        if (t.tv_nsec >= 1000000000L) { t.tv_nsec -= 1000000000L; t.tv_sec++; }
        clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &t, NULL);
    }
    printf("flood done: %ld lines\\n", n);
    return NULL;
}`);
  region('protect_init_MSA', `    pthread_t th;
    if (pthread_create(&th, NULL, flood, NULL) == 0) pthread_detach(th);
    return 1;`);
  writeFileSync(file, c);
}

