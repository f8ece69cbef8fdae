/**
 * The Cactal editor services (docs/ide.md "Editor services"), bound over Langium's LSP defaults. Browser-safe: the
 * web IDE runs them in a Web Worker, `src/node/main.ts` over stdio. Find references and document
 * highlights are Langium's defaults: they already follow every cross-reference, ports by index too.
 */
import type { Module } from 'langium';
import type { PartialLangiumServices } from 'langium/lsp';
import type { CactalServices } from '../cactal-module.js';
import { CactalCodeActionProvider } from './cactal-code-action-provider.js';
import { CactalCompletionProvider } from './cactal-completion-provider.js';
import { CactalDefinitionProvider } from './cactal-definition-provider.js';
import { CactalDocumentSymbolProvider } from './cactal-document-symbol-provider.js';
import { CactalFormatter } from './cactal-formatter.js';
import { CactalHoverProvider } from './cactal-hover-provider.js';
import { CactalRenameProvider } from './cactal-rename-provider.js';
import { CactalSemanticTokenProvider } from './cactal-semantic-token-provider.js';

export const CactalLspModule: Module<CactalServices, PartialLangiumServices> = {
    lsp: {
        DocumentSymbolProvider: () => new CactalDocumentSymbolProvider(),
        HoverProvider: (services) => new CactalHoverProvider(services),
        Formatter: (services) => new CactalFormatter(services),
        RenameProvider: (services) => new CactalRenameProvider(services),
        DefinitionProvider: (services) => new CactalDefinitionProvider(services),
        CodeActionProvider: (services) => new CactalCodeActionProvider(services),
        SemanticTokenProvider: (services) => new CactalSemanticTokenProvider(services),
        CompletionProvider: (services) => new CactalCompletionProvider(services)
    }
};
