/**
 * Monaco's word-based suggestions (every word of the open files, listed as plain text) are off for
 * the languages whose completion comes from the language server, Cactal and its scenarios: where
 * the server knew no candidate (a module name typed with a letter no module has, a new rule label)
 * Monaco listed the file's words instead (`r1`, `realtime`, `rules`...), none of them a name the
 * model accepts there, and a word list once shown stayed while the typing went on. The C files keep
 * them (no language server there). Set as a language override (`[cactal]`) of Monaco's
 * configuration, which its word provider reads for each model: the same editor shows both kinds
 * of files.
 */
import { StandaloneServices } from 'monaco-editor/editor/standalone/browser/standaloneServices.js';
import { IConfigurationService } from 'monaco-editor/platform/configuration/common/configuration.js';

export function turnOffWordSuggestions(languageIds: readonly string[]): void {
  const config = StandaloneServices.get(IConfigurationService);
  for (const id of languageIds) config.updateValue(`[${id}]`, { 'editor.wordBasedSuggestions': 'off' });
}
