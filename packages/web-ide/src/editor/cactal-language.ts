import { monaco } from './monaco.js';
import { registerScenarioLanguage, SCENARIO_LANGUAGE_ID } from './scenario-language.js';
import { turnOffWordSuggestions } from './word-suggestions.js';

export const CACTAL_LANGUAGE_ID = 'cactal';

/** Monarch tokenizer for Cactal (syntax colours while the language server starts). */
export const cactalMonarch: monaco.languages.IMonarchLanguage = {
  defaultToken: '',
  keywords: [
    'import', 'datatype', 'function', 'synchronous', 'asynchronous', 'module', 'parameters', 'scheduling',
    'data', 'event', 'flows', 'in', 'out', 'periodic', 'schema', 'realtime', 'modules', 'graph',
    'communications', 'scheduler', 'configuration', 'schemas', 'supervisor', 'local', 'rules', 'activate',
    'parameterize', 'resttime', 'critical', 'compute', 'subscribe', 'notify', 'started', 'endof', 'duration',
    'elapsed', 'infinite', 'and', 'or',
  ],
  typeKeywords: ['int', 'float', 'string', 'bool', 'void'],
  constants: ['PERIOD', 'CRITICAL_DELAY', 'C', 'ORD'],
  operators: ['->', '=*', '=>', '==*', '==>', '==', '!=', '<=', '>=', '=', '&', '|', '*'],
  symbols: /[=><!&|*+-]+/,
  tokenizer: {
    root: [
      [/\b[A-Z]{3}\b(?=\s*[:.(;{]|\s*->|\s*$)/, 'type.identifier.module'],
      [/[a-zA-Z_]\w*/, { cases: { '@keywords': 'keyword', '@typeKeywords': 'type', '@constants': 'constant', '@default': 'identifier' } }],
      { include: '@whitespace' },
      [/\d+(\.\d*)?([eE][-+]?\d+)?(ns|us|ms|s)\b/, 'number.time'],
      [/-?\d*\.\d+([eE][-+]?\d+)?|-?\d+\.\d*([eE][-+]?\d+)?|-?\d+[eE][-+]?\d+/, 'number.float'],
      [/-?\d+/, 'number'],
      [/:\s*\d+/, 'number.port'],
      [/[{}()[\]]/, '@brackets'],
      [/@symbols/, { cases: { '@operators': 'operator', '@default': '' } }],
      [/[;,.:]/, 'delimiter'],
      [/"([^"\\]|\\.)*$/, 'string.invalid'],
      [/"/, 'string', '@string'],
    ],
    string: [
      [/[^\\"]+/, 'string'],
      [/\\./, 'string.escape'],
      [/"/, 'string', '@pop'],
    ],
    whitespace: [
      [/[ \t\r\n]+/, ''],
      [/\/\*/, 'comment', '@comment'],
      [/\/\/.*$/, 'comment'],
    ],
    comment: [
      [/[^/*]+/, 'comment'],
      [/\*\//, 'comment', '@pop'],
      [/[/*]/, 'comment'],
    ],
  },
};

export function registerCactalLanguage(): void {
  registerScenarioLanguage(); // .scenario files (docs/simulation.md "Editing scenarios")
  monaco.languages.register({ id: CACTAL_LANGUAGE_ID, extensions: ['.contract'], aliases: ['Cactal', 'cactal'] });
  monaco.languages.setMonarchTokensProvider(CACTAL_LANGUAGE_ID, cactalMonarch);
  monaco.languages.setLanguageConfiguration(CACTAL_LANGUAGE_ID, {
    comments: { lineComment: '//', blockComment: ['/*', '*/'] },
    brackets: [['{', '}'], ['(', ')'], ['[', ']']],
    autoClosingPairs: [
      { open: '{', close: '}' },
      { open: '(', close: ')' },
      { open: '[', close: ']' },
      { open: '"', close: '"', notIn: ['string', 'comment'] },
    ],
    surroundingPairs: [{ open: '{', close: '}' }, { open: '(', close: ')' }, { open: '"', close: '"' }],
    indentationRules: { increaseIndentPattern: /\{[^}]*$/, decreaseIndentPattern: /^\s*\}/ },
    wordPattern: /[A-Za-z_][A-Za-z0-9_]*|-?\d+(\.\d*)?(ns|us|ms|s)?/,
  });
  // completion is the language server's alone: real candidates, never the file's words (word-suggestions.ts)
  turnOffWordSuggestions([CACTAL_LANGUAGE_ID, SCENARIO_LANGUAGE_ID]);
}

/**
 * The IDE's dark theme. Its text colours keep a contrast of 4.5:1 or more (WCAG AA) on the editor,
 * the current line, the selection and the highlights of the word at the cursor; the line numbers
 * too (axe-core scans the editor with a file open: test/e2e/small-screens.e2e.test.ts; the
 * selection is measured in test/e2e/editor-colours.e2e.test.ts). The skeleton of a generated file
 * is greyed by one colour that keeps 4.5:1 on all of them (styles.css, `.gen-readonly-text`).
 */
export function defineStudioTheme(): void {
  monaco.editor.defineTheme('contract-dark', {
    base: 'vs-dark',
    inherit: true,
    rules: [
      { token: 'keyword', foreground: 'c586c0' },
      { token: 'type', foreground: '4ec9b0' },
      { token: 'type.identifier.module', foreground: 'e5c07b', fontStyle: 'bold' },
      { token: 'constant', foreground: '4fc1ff' },
      { token: 'number.time', foreground: 'd7ba7d' },
      { token: 'number', foreground: 'b5cea8' },
      { token: 'comment', foreground: '7fae6a', fontStyle: 'italic' },
      { token: 'string', foreground: 'ce9178' },
      { token: 'operator', foreground: '89ddff' },
      // semantic tokens (language server)
      { token: 'class', foreground: 'e5c07b', fontStyle: 'bold' },
      { token: 'namespace', foreground: '61afef' },
      { token: 'property', foreground: '9cdcfe' },
      { token: 'parameter', foreground: 'd19a66' },
      { token: 'variable', foreground: 'ec7a84' },
      { token: 'function', foreground: 'dcdcaa' },
      { token: 'method', foreground: 'dcdcaa' },
      { token: 'label', foreground: '56b6c2', fontStyle: 'bold' },
    ],
    colors: {
      'editor.background': '#15181e',
      'editor.lineHighlightBackground': '#1d222b',
      'editorGutter.background': '#15181e',
      'editorLineNumber.foreground': '#828998',
      'editorLineNumber.activeForeground': '#abb2bf',
      // the selected text: every token colour keeps 4.5:1 on it (#2c3b5a left keywords at 4.0:1); a
      // saturated blue as dark as the highlights below, told from them by its hue, 1.4:1 on the editor
      'editor.selectionBackground': '#113163',
      // the other places of the word at the cursor, and of the selected text: every token colour
      // keeps 4.5:1 on them (vs-dark's translucent grey, #454547 over the editor, left keywords at 3.4:1)
      'editor.wordHighlightBackground': '#283246',
      'editor.wordHighlightStrongBackground': '#283246',
      'editor.selectionHighlightBackground': '#283246',
      'editor.inactiveSelectionBackground': '#283246',
      // the brackets coloured by pair: vs-dark's orchid (#da70d6) and blue (#179fff) were at 4.4:1
      // and 4.5:1 on the selection and the highlights
      'editorBracketHighlight.foreground1': '#ffd700',
      'editorBracketHighlight.foreground2': '#e07fdc',
      'editorBracketHighlight.foreground3': '#3aa8ff',
      'editorWidget.background': '#1b1f27',
      'editorSuggestWidget.background': '#1b1f27',
      'editorHoverWidget.background': '#1b1f27',
    },
  });
}
