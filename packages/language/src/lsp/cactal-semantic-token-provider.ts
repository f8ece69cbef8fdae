/**
 * Semantic highlighting (docs/ide.md "Editor services"): keywords; types (datatypes, primitive types); modules and
 * supervisors (class); schemas (namespace); ports and parameters (property), including port
 * references by index; rule labels (`label`, a token type added to the standard legend);
 * functions; variables and fields; time literals (number).
 */
import { AstUtils, GrammarAST, type AstNode, type CstNode } from 'langium';
import { AbstractSemanticTokenProvider, AllSemanticTokenTypes, type SemanticTokenAcceptor } from 'langium/lsp';
import { SemanticTokenModifiers, SemanticTokenTypes } from 'vscode-languageserver-protocol';
import {
    isArrayDimension, isConstant, isEnumMember, isEnumType, isIndexSegment, isActivateModule, isActivateSchema, isActivateSupervisor, isCompute, isDataCommunication, isDataType, isDurationEvent,
    isEndofEvent, isEventCommunication, isField, isFieldSegment, isFunctionArgument, isFunctionParameter,
    isFunctionPrototype, isFunctionTest, isLocalVariable, isModule, isModuleEvent, isModuleInstance, isNotify, isParameter,
    isParameterSetting, isParameterize, isPort, isPrecedence, isRule, isSchedulerModules, isSchedulerSchemas, isSchema,
    isSchemaArgument, isSchemaParameter, isStartedEvent, isSubscribe, isSupervisionFunction, isSupervisor, isTimeProperty,
    isTimeValue, isTypeRef, isVariableRef, isFunctionArgumentAssignment
} from '../generated/ast.js';

/** The extra token type for rule labels. */
export const LABEL_TOKEN = 'label';

const DECL = SemanticTokenModifiers.declaration;

export class CactalSemanticTokenProvider extends AbstractSemanticTokenProvider {
    override get tokenTypes(): Record<string, number> {
        const types = AllSemanticTokenTypes;
        return { ...types, [LABEL_TOKEN]: Math.max(...Object.values(types)) + 1 };
    }

    protected highlightElement(node: AstNode, acceptor: SemanticTokenAcceptor): void {
        this.highlightKeywords(node, acceptor);
        const T = SemanticTokenTypes;
        if (isDataType(node)) acceptor({ node, property: 'name', type: T.type, modifier: DECL });
        else if (isEnumType(node)) acceptor({ node, property: 'name', type: T.enum, modifier: DECL });
        else if (isEnumMember(node)) acceptor({ node, property: 'name', type: T.enumMember, modifier: DECL });
        else if (isConstant(node)) acceptor({ node, property: 'name', type: T.variable, modifier: [DECL, SemanticTokenModifiers.readonly] });
        else if (isArrayDimension(node) || isIndexSegment(node)) {
            if (node.constant) acceptor({ node, property: 'constant', type: T.variable, modifier: SemanticTokenModifiers.readonly });
        }
        else if (isField(node)) acceptor({ node, property: 'name', type: T.property, modifier: DECL });
        else if (isTypeRef(node)) {
            if (node.primitive) acceptor({ node, property: 'primitive', type: T.type, modifier: SemanticTokenModifiers.defaultLibrary });
            else acceptor({ node, property: 'datatype', type: T.type });
        } else if (isFunctionPrototype(node)) acceptor({ node, property: 'name', type: T.function, modifier: DECL });
        else if (isFunctionArgument(node) || isSchemaParameter(node) || isFunctionParameter(node)) acceptor({ node, property: 'name', type: T.parameter, modifier: DECL });
        else if (isModule(node) || isSupervisor(node)) acceptor({ node, property: 'name', type: T.class, modifier: DECL });
        else if (isParameter(node) || isPort(node)) {
            acceptor({ node, property: 'name', type: T.property, modifier: DECL });
            acceptor({ node, property: 'index', type: T.number });
        } else if (isSchema(node)) acceptor({ node, property: 'name', type: T.namespace, modifier: DECL });
        else if (isSupervisionFunction(node)) acceptor({ node, property: 'name', type: T.method, modifier: DECL });
        else if (isLocalVariable(node)) acceptor({ node, property: 'name', type: T.variable, modifier: DECL });
        else if (isRule(node)) acceptor({ node, property: 'name', type: LABEL_TOKEN, modifier: DECL });
        else if (isTimeProperty(node)) acceptor({ node, property: 'name', type: T.property });
        else if (isTimeValue(node)) acceptor({ node, property: 'text', type: T.number });
        else if (isModuleInstance(node) || isParameterize(node) || isActivateModule(node)) acceptor({ node, property: 'module', type: T.class });
        else if (isPrecedence(node)) {
            acceptor({ node, property: 'from', type: T.class });
            acceptor({ node, property: 'to', type: T.class });
        } else if (isDataCommunication(node) || isEventCommunication(node)) {
            acceptor({ node, property: 'source', type: T.class });
            acceptor({ node, property: 'sourcePort', type: T.property });
            acceptor({ node, property: 'target', type: T.class });
            acceptor({ node, property: 'targetPort', type: T.property });
        } else if (isParameterSetting(node)) acceptor({ node, property: 'port', type: T.property });
        else if (isModuleEvent(node)) {
            if (node.source) {
                acceptor({ node, property: 'source', type: T.class });
                acceptor({ node, property: 'port', type: T.property });
            } else acceptor({ node, keyword: 'ORD', type: T.class });
        } else if (isSubscribe(node)) {
            acceptor({ node, property: 'source', type: T.class });
            acceptor({ node, property: 'sourcePort', type: T.property });
            acceptor({ node, property: 'targetPort', type: T.property });
        } else if (isNotify(node)) acceptor({ node, property: 'port', type: T.property });
        else if (isStartedEvent(node) || isEndofEvent(node) || isDurationEvent(node)) acceptor({ node, property: 'rule', type: LABEL_TOKEN });
        else if (isActivateSchema(node)) acceptor({ node, property: 'schema', type: T.namespace });
        else if (isActivateSupervisor(node)) {
            acceptor({ node, property: 'supervisor', type: T.class });
            acceptor({ node, property: 'function', type: T.method });
        } else if (isSchemaArgument(node) || isFunctionArgumentAssignment(node)) acceptor({ node, property: 'parameter', type: T.parameter });
        else if (isCompute(node) || isFunctionTest(node)) acceptor({ node, property: 'function', type: T.function });
        else if (isVariableRef(node) && node.variable) {
            const head = node.variable.ref;
            if (isEnumType(head)) acceptor({ node, property: 'variable', type: T.enum });
            else if (isConstant(head)) acceptor({ node, property: 'variable', type: T.variable, modifier: SemanticTokenModifiers.readonly });
            else acceptor({ node, property: 'variable', type: T.variable });
        } else if (isFieldSegment(node)) acceptor({ node, property: 'field', type: isEnumMember(node.field?.ref) ? T.enumMember : T.property });
        else if (isSchedulerModules(node)) node.modules.forEach((_, index) => acceptor({ node, property: 'modules', index, type: T.class }));
        else if (isSchedulerSchemas(node)) node.schemas.forEach((_, index) => acceptor({ node, property: 'schemas', index, type: T.namespace }));
    }

    /** Alphabetic keywords written by this node's own rule (`module`, `data`, `flows`, `activate`...), not by its children. */
    private highlightKeywords(node: AstNode, acceptor: SemanticTokenAcceptor): void {
        const visit = (cst: CstNode & { content?: CstNode[] }): void => {
            for (const child of cst.content ?? []) {
                if (child.astNode !== node) continue;
                const source = child.grammarSource;
                if (GrammarAST.isKeyword(source)) {
                    if (/^[A-Za-z]/.test(source.value) && source.value !== 'ORD') acceptor({ cst: child, type: SemanticTokenTypes.keyword });
                } else if (!GrammarAST.isCrossReference(source) && !isNameOrValue(child)) {
                    visit(child as CstNode & { content?: CstNode[] });
                }
            }
        };
        if (node.$cstNode) visit(node.$cstNode as CstNode & { content?: CstNode[] });
    }
}

/** A child written through `name=` (a Name may be a keyword word) or `primitive=` (highlighted as a type): not a keyword token. */
function isNameOrValue(cst: CstNode): boolean {
    const assignment = AstUtils.getContainerOfType(cst.grammarSource, GrammarAST.isAssignment);
    return assignment?.feature === 'name' || assignment?.feature === 'primitive';
}
