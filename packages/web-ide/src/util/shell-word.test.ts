import { describe, expect, it } from 'vitest';
import { spawnSync } from 'node:child_process';
import { shellWord } from './shell-word.js';

describe('shellWord', () => {
  it('leaves a plain path as it is, and quotes one the shell would split or expand, so that sh reads it back as one word', () => {
    expect(shellWord('scenarios/x.scenario')).toBe('scenarios/x.scenario');
    expect(shellWord('.')).toBe('.');
    for (const word of ['scenarios/new dir/x.scenario', "it's.scenario", 'a$HOME`id`*?.scenario', 'tab\there', '', 'line\nbreak']) {
      const quoted = shellWord(word);
      expect(quoted).not.toBe(word);
      const echoed = spawnSync('sh', ['-c', `printf '%s' ${quoted}`], { encoding: 'utf8' });
      expect(echoed.stdout).toBe(word);
    }
  });
});
