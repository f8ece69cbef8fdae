/**
 * Completion (SPEC §2.7): keywords and names in scope come from Langium's default provider over
 * the Cactal scope provider (so only names the file's imports make visible are offered). Port
 * references complete with the indexes of the module being referenced, with the port's name and
 * type as detail.
 */
import type { AstNodeDescription, ReferenceInfo } from 'langium';
import { DefaultCompletionProvider, type CompletionContext, type CompletionValueItem } from 'langium/lsp';
import { CompletionItemKind } from 'vscode-languageserver-protocol';
import { isParameter, isPort } from '../generated/ast.js';
import { portKind } from '../model/ports.js';
import { typeRefText } from '../model/types.js';

export class CactalCompletionProvider extends DefaultCompletionProvider {
    protected override createReferenceCompletionItem(description: AstNodeDescription, refInfo: ReferenceInfo, context: CompletionContext): CompletionValueItem {
        const node = description.node;
        if (isPort(node)) {
            return {
                nodeDescription: description,
                kind: CompletionItemKind.Field,
                detail: `${node.direction} ${portKind(node)} :${node.index} ${typeRefText(node.type)} ${node.name}`,
                sortText: String(node.index).padStart(6, '0')
            };
        }
        if (isParameter(node)) {
            return {
                nodeDescription: description,
                kind: CompletionItemKind.Field,
                detail: `parameter :${node.index} ${typeRefText(node.type)} ${node.name}`,
                sortText: String(node.index).padStart(6, '0')
            };
        }
        return super.createReferenceCompletionItem(description, refInfo, context);
    }
}
