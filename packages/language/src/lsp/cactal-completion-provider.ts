/**
 * Completion (docs/ide.md "Editor services"): keywords and names in scope come from Langium's default provider over
 * the Cactal scope provider (so only names the file's imports make visible are offered). Port
 * references complete with the indexes of the module being referenced, with the port's name and
 * type as detail. Inside a comment or a string nothing is offered (comment-or-string.ts).
 */
import { AstUtils, GrammarAST, stream, type AstNode, type AstNodeDescription, type AstNodeDescriptionProvider, type LangiumDocument, type MaybePromise, type ReferenceInfo, type Stream } from 'langium';
import { DefaultCompletionProvider, type CompletionAcceptor, type CompletionContext, type CompletionValueItem } from 'langium/lsp';
import { CompletionItemKind, InsertTextFormat, type CancellationToken, type CompletionList, type CompletionParams } from 'vscode-languageserver-protocol';
import { isModule, isParameter, isEnumMember, isPort, isSupervisor } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';
import { portKind, portsOfKind, type PortDirection, type PortKind } from '../model/ports.js';
import { typeRefText } from '../model/types.js';
import { textContextAt } from './comment-or-string.js';

/** Port references whose owner is written just before (`MSC:`), with the kind and direction they name. */
const OWNER_PORTS: Record<string, { owner: string; kind: PortKind; direction: PortDirection }> = {
    'DataCommunication.sourcePort': { owner: 'source', kind: 'data', direction: 'out' },
    'DataCommunication.targetPort': { owner: 'target', kind: 'data', direction: 'in' },
    'EventCommunication.sourcePort': { owner: 'source', kind: 'event', direction: 'out' },
    'EventCommunication.targetPort': { owner: 'target', kind: 'event', direction: 'in' },
    'ModuleEvent.port': { owner: 'source', kind: 'event', direction: 'out' },
    'Subscribe.sourcePort': { owner: 'source', kind: 'event', direction: 'out' }
};

/** A whole construct offered where its first keyword may start (`label` is what the list shows). */
interface Snippet { label: string; text: string; detail: string }

/**
 * Where a rule's actions or conditions may start (an empty line of a rule body), the keyword alone
 * (`activate`, `[`) says little: the whole forms are offered as snippets too, keyed by the grammar
 * rule and keyword the parser expects next (docs/language-reference.md §6 "Conditions", "Actions").
 */
const RULE_SNIPPETS: Record<string, Snippet[]> = {
    'ActivateSchema:activate': [
        { label: 'activate schema', text: 'activate schema ${1:schema}(${2})', detail: 'action: start a schema (parameters by name)' },
        { label: 'activate supervisor', text: 'activate supervisor ${1:SUP}.${2:function}(${3})', detail: 'action: run a supervision function' },
        { label: 'activate critical module', text: 'activate critical module ${1:module}', detail: 'action: activate an asynchronous module now' },
        { label: 'activate resttime module', text: 'activate resttime module ${1:module}', detail: 'action: activate an asynchronous module in rest time' }
    ],
    'Parameterize:parameterize': [{ label: 'parameterize', text: 'parameterize ${1:module}(${2:value} :${3:0})', detail: 'action: set parameter ports of a module' }],
    'Compute:compute': [{ label: 'compute', text: 'compute ${1:function}(${2})', detail: 'action: call a C function' }],
    'Subscribe:subscribe': [{ label: 'subscribe', text: 'subscribe ${1:MODULE}:${2:0} =* :${3:0}', detail: 'action: listen to a module\'s event port (=* continuous, => one shot)' }],
    'Notify:notify': [{ label: 'notify', text: 'notify :${1:0}', detail: 'action: emit on an out event port of the supervisor' }],
    'Rule:[': [
        { label: '[started(rule)]', text: '[started(${1:rule})]', detail: 'condition: a rule has started' },
        { label: '[endof(rule)]', text: '[endof(${1:rule})]', detail: 'condition: a rule has finished' },
        { label: '[elapsed=time]', text: '[elapsed=${1:1ms}]', detail: 'condition: time since the function started' },
        { label: '[duration(rule)=time]', text: '[duration(${1:rule})=${2:1ms}]', detail: 'condition: a rule has run for a time' },
        { label: '[MODULE:port]', text: '[${1:MODULE}:${2:0}]', detail: 'condition: an event of a module or supervisor port' },
        { label: '[ORD:0]', text: '[ORD:${1|0,1|}]', detail: 'condition: a scheduler event (0 critical lateness, 1 refused activation)' }
    ]
};

const ACTION_SNIPPETS = ['ActivateSchema:activate', 'Parameterize:parameterize', 'Compute:compute', 'Subscribe:subscribe', 'Notify:notify'].flatMap((k) => RULE_SNIPPETS[k]!);

export class CactalCompletionProvider extends DefaultCompletionProvider {
    private readonly descriptions: AstNodeDescriptionProvider;

    constructor(services: CactalServices) {
        super(services);
        this.descriptions = services.workspace.AstNodeDescriptionProvider;
    }

    /** Nothing inside a comment or a string: a space there (a trigger character) must not bring up keywords. */
    override async getCompletion(document: LangiumDocument, params: CompletionParams, cancelToken?: CancellationToken): Promise<CompletionList | undefined> {
        const offset = document.textDocument.offsetAt(params.position);
        if (textContextAt(document.textDocument.getText(), offset) !== 'code') return { isIncomplete: false, items: [] };
        return super.getCompletion(document, params, cancelToken);
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

    protected override completionForKeyword(context: CompletionContext, keyword: GrammarAST.Keyword, acceptor: CompletionAcceptor): MaybePromise<void> {
        const rule = AstUtils.getContainerOfType(keyword, GrammarAST.isParserRule)?.name;
        const key = `${rule}:${keyword.value}`;
        let snippets = RULE_SNIPPETS[key] ?? [];
        // after `action;` the parser takes the `;` as the optional last one and expects only the
        // closing `[`: another action may follow too
        if (key === 'Rule:[' && /;\s*$/.test(context.textDocument.getText().slice(0, context.tokenOffset))) {
            snippets = [...ACTION_SNIPPETS, ...snippets];
        }
        for (const snippet of snippets) {
            acceptor(context, {
                label: snippet.label, kind: CompletionItemKind.Snippet, detail: snippet.detail,
                insertText: snippet.text, insertTextFormat: InsertTextFormat.Snippet, sortText: '0'
            });
        }
        return super.completionForKeyword(context, keyword, acceptor);
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
        if (isEnumMember(node)) {
            const owner = node.$container;
            const index = owner.members.indexOf(node);
            return {
                nodeDescription: description,
                kind: CompletionItemKind.EnumMember,
                detail: `${owner.name}.${node.name} (member ${index} of ${owner.name})`,
                sortText: String(index).padStart(6, '0')
            };
        }
        return super.createReferenceCompletionItem(description, refInfo, context);
    }
}
