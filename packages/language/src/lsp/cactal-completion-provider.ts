/**
 * Completion (SPEC §2.7): keywords and names in scope come from Langium's default provider over
 * the Cactal scope provider (so only names the file's imports make visible are offered). Port
 * references complete with the indexes of the module being referenced, with the port's name and
 * type as detail.
 */
import { stream, type AstNode, type AstNodeDescription, type AstNodeDescriptionProvider, type ReferenceInfo, type Stream } from 'langium';
import { DefaultCompletionProvider, type CompletionContext, type CompletionValueItem } from 'langium/lsp';
import { CompletionItemKind } from 'vscode-languageserver-protocol';
import { isModule, isParameter, isPort, isSupervisor } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { portKind, portsOfKind, type PortDirection, type PortKind } from '../model/ports.js';
import { typeRefText } from '../model/types.js';

/** Port references whose owner is written just before (`MSC:`), with the kind and direction they name. */
const OWNER_PORTS: Record<string, { owner: string; kind: PortKind; direction: PortDirection }> = {
    'DataCommunication.sourcePort': { owner: 'source', kind: 'data', direction: 'out' },
    'DataCommunication.targetPort': { owner: 'target', kind: 'data', direction: 'in' },
    'EventCommunication.sourcePort': { owner: 'source', kind: 'event', direction: 'out' },
    'EventCommunication.targetPort': { owner: 'target', kind: 'event', direction: 'in' },
    'ModuleEvent.port': { owner: 'source', kind: 'event', direction: 'out' },
    'Subscribe.sourcePort': { owner: 'source', kind: 'event', direction: 'out' }
};

export class CactalCompletionProvider extends DefaultCompletionProvider {
    private readonly descriptions: AstNodeDescriptionProvider;

    constructor(services: CactalServices) {
        super(services);
        this.descriptions = services.workspace.AstNodeDescriptionProvider;
    }

    /**
     * While a line is being typed (`MSC:` with nothing after), the parser has not built the
     * communication yet, so the owner is read from the text before the cursor and looked up in scope.
     */
    protected override getReferenceCandidates(refInfo: ReferenceInfo, context: CompletionContext): Stream<AstNodeDescription> {
        const candidates = super.getReferenceCandidates(refInfo, context);
        const spec = OWNER_PORTS[`${refInfo.container.$type}.${refInfo.property}`];
        const written = (refInfo.container as unknown as Record<string, { ref?: AstNode } | undefined>)[spec?.owner ?? ''];
        if (!spec || written?.ref) return candidates;
        const before = context.textDocument.getText().slice(0, context.tokenOffset);
        const name = /([A-Za-z_]\w*)\s*:\s*$/.exec(before)?.[1];
        if (!name) return candidates;
        const ownerScope = this.scopeProvider.getScope({ ...refInfo, property: spec.owner, reference: { $refText: name } as ReferenceInfo['reference'] });
        const owner = ownerScope.getElement(name)?.node;
        if (!isModule(owner) && !isSupervisor(owner)) return candidates;
        return stream(portsOfKind(owner, spec.kind, spec.direction).map((port) => this.descriptions.createDescription(port, String(port.index))));
    }

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
