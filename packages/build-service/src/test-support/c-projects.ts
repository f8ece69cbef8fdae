/**
 * Small hand-written C projects ("kind": "make") used by the tests and the benchmark: an honest
 * program, and the adversarial ones of issue 6 (each must be stopped with the right message).
 */
export function makeProject(mainC: string, extraFiles: Record<string, string> = {}): Record<string, string> {
  return {
    Makefile: [
      'CC ?= gcc',
      'all: prog',
      'prog: main.c',
      '\t$(CC) -std=c11 -Wall -Wextra -O1 $(EXTRA_CFLAGS) -o prog main.c',
      'run: prog',
      '\t./prog',
      '.PHONY: all run',
      '',
    ].join('\n'),
    'main.c': mainC,
    ...extraFiles,
  };
}

const HEAD = '#define _GNU_SOURCE\n#include <stdio.h>\n#include <stdlib.h>\n#include <string.h>\n#include <unistd.h>\n';

/** Prints `lines` numbered lines on stdout and stderr, interleaved. */
export function honestProgram(lines = 50): string {
  return `${HEAD}
int main(void) {
  for (int i = 0; i < ${lines}; i++) {
    printf("out %d\\n", i); fflush(stdout);
    fprintf(stderr, "err %d\\n", i);
  }
  puts("honest done");
  return 0;
}
`;
}

export const forkBomb = `${HEAD}
#include <errno.h>
int main(void) {
  for (;;) {
    pid_t p = fork();
    if (p < 0) { perror("fork"); sleep(1); }
  }
}
`;

/** Allocates and touches 4 GiB. */
export const bigAllocation = `${HEAD}
int main(void) {
  size_t total = (size_t)4 << 30, chunk = (size_t)64 << 20, got = 0;
  while (got < total) {
    char *p = malloc(chunk);
    if (!p) { perror("malloc"); return 3; }
    memset(p, 1, chunk);
    got += chunk;
  }
  printf("allocated %zu bytes\\n", got);
  return 0;
}
`;

export const infiniteLoop = `${HEAD}
int main(void) {
  puts("looping"); fflush(stdout);
  volatile unsigned long n = 0;
  for (;;) n++;
}
`;

/** Tries to connect to 127.0.0.1:<port>; prints CONNECTED or the error, exits 0 either way. */
export function connectProgram(port: number): string {
  return `${HEAD}
#include <arpa/inet.h>
#include <errno.h>
#include <netinet/in.h>
#include <sys/socket.h>
int main(void) {
  int s = socket(AF_INET, SOCK_STREAM, 0);
  if (s < 0) { printf("socket failed: %s\\n", strerror(errno)); return 0; }
  struct sockaddr_in a; memset(&a, 0, sizeof a);
  a.sin_family = AF_INET; a.sin_port = htons(${port}); a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  if (connect(s, (struct sockaddr *)&a, sizeof a) == 0) { puts("CONNECTED"); write(s, "pwned\\n", 6); }
  else printf("connect failed: %s\\n", strerror(errno));
  close(s);
  return 0;
}
`;
}

/** Tries to create each of the given absolute paths; prints WROTE <path> or the error. */
export function writeOutsideProgram(paths: string[]): string {
  return `${HEAD}
#include <errno.h>
int main(void) {
  const char *paths[] = { ${paths.map((p) => JSON.stringify(p)).join(', ')} };
  for (size_t i = 0; i < sizeof paths / sizeof paths[0]; i++) {
    FILE *f = fopen(paths[i], "w");
    if (f) { fputs("pwned\\n", f); fclose(f); printf("WROTE %s\\n", paths[i]); }
    else printf("refused %s: %s\\n", paths[i], strerror(errno));
  }
  return 0;
}
`;
}

/** Writes 100 MiB on stdout. */
export const outputFlood = `${HEAD}
int main(void) {
  static char line[1024];
  memset(line, 'x', sizeof line - 1); line[sizeof line - 1] = '\\n';
  for (int i = 0; i < 100 * 1024; i++) fwrite(line, 1, sizeof line, stdout);
  puts("flood done");
  return 0;
}
`;

/** A compile error (for diagnostics tests). */
export const brokenProgram = `${HEAD}
int main(void) {
  int unused;
  return undeclared_thing;
}
`;

/** Tries to create a user namespace (a way to regain capabilities inside the sandbox). */
export const nestedUserNamespace = `${HEAD}
#include <errno.h>
#include <sched.h>
int main(void) {
  if (unshare(CLONE_NEWUSER) == 0) puts("USERNS CREATED");
  else printf("unshare refused: %s\\n", strerror(errno));
  return 0;
}
`;

/**
 * Fills its working directory (/work) with 1 MiB files and keeps trying after the first refused
 * write (so only a kill ends it before the run time limit).
 */
export const diskFiller = `${HEAD}
#include <errno.h>
int main(void) {
  static char chunk[1 << 20];
  memset(chunk, 'd', sizeof chunk);
  int reported = 0;
  for (unsigned long i = 0;; i++) {
    char name[64];
    snprintf(name, sizeof name, "fill-%lu.bin", i % 100000);
    FILE *f = fopen(name, "w");
    size_t put = f ? fwrite(chunk, 1, sizeof chunk, f) : 0;
    int failed = !f || put != sizeof chunk || fclose(f) != 0;
    if (failed && !reported) { printf("write failed after %lu MiB: %s\\n", i, strerror(errno)); fflush(stdout); reported = 1; }
  }
}
`;

/**
 * A run that replaces its own executable with a script dated 2100, so that a later job on the
 * same workspace would see it as newer than any source (the stale-build-product attack).
 */
export const poisoner = `${HEAD}
int main(void) {
  puts("poisoning ./prog"); fflush(stdout);
  return system("rm -f prog && printf '#!/bin/sh\\\\necho POISONED\\\\n' > prog && chmod +x prog && touch -d 2100-01-01 prog");
}
`;

/**
 * A run that leaves hostile things in its log folder (argv[1]): an old log, `previous` a link to
 * `/`, and a folder made unreadable (chmod 000) with one inside it.
 */
export const runLeaver = `${HEAD}#include <sys/stat.h>
int main(int argc, char **argv) {
  if (argc < 2) return 2;
  char p[512];
  mkdir(argv[1], 0755);
  snprintf(p, sizeof p, "%s/OLD_1.csv", argv[1]);
  FILE *f = fopen(p, "w");
  if (!f) return 3;
  fputs("mono_ns,wall_time,module,event,peer,port,size,detail\\n1,w,OLD,user,,,0,left by an earlier run\\n", f);
  fclose(f);
  snprintf(p, sizeof p, "%s/previous", argv[1]);
  if (symlink("/", p) != 0) return 4;
  snprintf(p, sizeof p, "%s/locked", argv[1]);
  mkdir(p, 0755);
  snprintf(p, sizeof p, "%s/locked/inner", argv[1]);
  mkdir(p, 0755);
  snprintf(p, sizeof p, "%s/locked", argv[1]);
  chmod(p, 0);
  puts("left its marks");
  return 0;
}
`;

