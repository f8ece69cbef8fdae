/**
 * The `.scenario` language in Monaco (docs/simulation.md "Editing scenarios", docs/ide.md):
 * language id `cactal-scenario` and a small Monarch grammar for colours. Diagnostics, completion
 * and hover come from the language server in the worker (`src/lsp/`), which checks scenarios with
 * the simulator's own parser and model checks.
 */
import { STEP_DIRECTIVES } from '@contract-studio/language/scenario';
import { monaco } from './monaco.js';

export const SCENARIO_LANGUAGE_ID = 'cactal-scenario';

export const scenarioMonarch: monaco.languages.IMonarchLanguage = {
  defaultToken: '',
  // the parser's steps (one list: a new step is coloured too), its header words, `at` and `once`
  directives: [...STEP_DIRECTIVES, 'scenario', 'until', 'at', 'once'],
  expectations: ['rule', 'schema', 'function', 'module', 'local', 'deadline', 'misses', 'overruns'],
  states: ['active', 'inactive', 'running', 'stopped'],
  tokenizer: {
    root: [
      [/#.*$/, 'comment'],
      [/^(\s*)(scenario)(\b[^#]*)/, ['', 'keyword', 'string']],
      [/\bt\s*=/, 'keyword'],
      [/\d+(\.\d+)?(ns|us|ms|s)\b/, 'number.time'],
      [/\b(ORD|[A-Z]{3})(?=\s*:\s*\d)/, 'type.identifier.module'],
      [/:\s*\d+/, 'number.port'],
      [/[a-zA-Z_]\w*/, { cases: { '@directives': 'keyword', '@expectations': 'keyword', '@states': 'constant', '@default': 'identifier' } }],
      [/-?\d*\.\d+([eE][-+]?\d+)?|-?\d+\.\d*([eE][-+]?\d+)?|-?\d+[eE][-+]?\d+/, 'number.float'],
      [/-?\d+/, 'number'],
      [/"([^"\\]|\\.)*$/, 'string.invalid'],
      [/"/, 'string', '@string'],
      [/==|=/, 'operator'],
      [/[{}()]/, '@brackets'],
      [/[,.:]/, 'delimiter'],
    ],
    string: [
      [/[^\\"]+/, 'string'],
      [/\\./, 'string.escape'],
      [/"/, 'string', '@pop'],
    ],
  },
};

export function registerScenarioLanguage(): void {
  monaco.languages.register({ id: SCENARIO_LANGUAGE_ID, extensions: ['.scenario'], aliases: ['Cactal scenario', 'scenario'] });
  monaco.languages.setMonarchTokensProvider(SCENARIO_LANGUAGE_ID, scenarioMonarch);
  monaco.languages.setLanguageConfiguration(SCENARIO_LANGUAGE_ID, {
    comments: { lineComment: '#' },
    brackets: [['{', '}'], ['(', ')']],
    autoClosingPairs: [
      { open: '{', close: '}' },
      { open: '(', close: ')' },
      { open: '"', close: '"', notIn: ['string', 'comment'] },
    ],
    wordPattern: /[A-Za-z_][A-Za-z0-9_]*|-?\d+(\.\d*)?(ns|us|ms|s)?/,
  });
}
