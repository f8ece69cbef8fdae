/**
 * Keeps `.scenario` documents out of Langium's document builder: they are not Cactal (no
 * grammar, no AST), the scenario support (`scenario-server.ts`) checks them itself. Without this
 * an opened scenario would be handed to the builder as a changed document and fail to parse.
 */
import { DefaultDocumentUpdateHandler } from 'langium/lsp';
import type { TextDocumentChangeEvent } from 'vscode-languageserver';
import type { DidChangeWatchedFilesParams } from 'vscode-languageserver-protocol';
import type { TextDocument } from 'vscode-languageserver-textdocument';
import { isScenarioUri } from './scenario-project.js';

export class CactalDocumentUpdateHandler extends DefaultDocumentUpdateHandler {
    override didChangeContent(change: TextDocumentChangeEvent<TextDocument>): void {
        if (isScenarioUri(change.document.uri)) return;
        super.didChangeContent(change);
    }

    override didChangeWatchedFiles(params: DidChangeWatchedFilesParams): void {
        const changes = (params?.changes ?? []).filter((c) => !isScenarioUri(c.uri));
        if (changes.length || !params?.changes?.length) super.didChangeWatchedFiles({ ...params, changes });
    }
}
