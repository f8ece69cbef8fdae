/**
 * Builds, with a shell (descriptor-relative `cd`, as a sandboxed program would), the trees host
 * clean-up must survive (docs/sandbox.md, "Host clean-up"): `depth` nested folders (names long
 * enough that the full path exceeds PATH_MAX), a fifo and a symlink to `outside` every 100 levels,
 * a few folders made chmod 000 on the way back up.
 */
export function hostileTreeScript(depth: number, outside: string): string {
  return [
    'set -e',
    `i=0; while [ $i -lt ${depth} ]; do`,
    '  mkdir nested_dir && cd -P nested_dir',
    '  if [ $((i % 100)) -eq 50 ]; then mkfifo fifo; ln -s ' + JSON.stringify(outside) + ' out; fi',
    '  i=$((i+1))',
    'done',
    'echo leaf > leaf.txt',
    // chmod 000 on the way up: the deepest folder and two in the middle lose every permission bit
    `i=0; while [ $i -lt ${depth} ]; do cd -P ..; i=$((i+1)); case $i in 1|${Math.floor(depth / 2)}|${depth - 1}) chmod 000 nested_dir;; esac; done`,
  ].join('\n');
}

/**
 * The same tree made by a C program (what a sandboxed build or run can do, in milliseconds): with
 * mkdirat/openat it goes as deep as it likes, whatever PATH_MAX says.
 */
export function hostileTreeProgram(depth: number, outside: string): string {
  return `#define _GNU_SOURCE
#include <fcntl.h>
#include <stdio.h>
#include <sys/stat.h>
#include <unistd.h>
int main(void) {
  int fds[${depth + 1}];
  fds[0] = open(".", O_RDONLY | O_DIRECTORY);
  for (int i = 0; i < ${depth}; i++) {
    if (mkdirat(fds[i], "nested_dir", 0755) != 0) { perror("mkdirat"); return 1; }
    fds[i + 1] = openat(fds[i], "nested_dir", O_RDONLY | O_DIRECTORY);
    if (fds[i + 1] < 0) { perror("openat"); return 1; }
    if (i % 100 == 50) { mkfifoat(fds[i + 1], "fifo", 0644); symlinkat(${JSON.stringify(outside)}, fds[i + 1], "out"); }
    if (i > 64) close(fds[i - 64]); /* keep a window of descriptors open */
  }
  int leaf = openat(fds[${depth}], "leaf.txt", O_WRONLY | O_CREAT, 0644);
  if (leaf >= 0) { write(leaf, "leaf\\n", 5); close(leaf); }
  /* the deepest folders lose every permission bit */
  for (int i = ${depth}; i > ${depth} - 3; i--) fchmod(fds[i], 0);
  printf("made a %d-level tree\\n", ${depth});
  return 0;
}
`;
}
