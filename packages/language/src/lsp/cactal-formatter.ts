/**
 * Formatter (docs/ide.md "Editor services"): canonical spacing and indentation, idempotent, AST-preserving.
 *
 * It re-lays out the token stream instead of editing whitespace node by node: every gap between
 * two tokens becomes nothing, one space, a newline or a blank line, decided by the two tokens and
 * their place in the AST (block braces open an indented block, `;` ends a line, a rule's actions
 * sit one level deeper than its label, values and conditions stay on one line). Comments are kept
 * where they were: a comment that followed a token on the same line stays there, others get their
 * own line. At most one blank line written by the user is kept between lines; top-level elements
 * are separated by one. `==*` / `==>` are written `=*` / `=>`.
 *
 * Safety: a document with syntax errors is not formatted, and the result is re-lexed and compared
 * with the input's tokens; any difference (other than the event-mode spelling) cancels formatting.
 */
import { CstUtils, isLeafCstNode, type CstNode, type LangiumDocument } from 'langium';
import type { Formatter } from 'langium/lsp';
import type { IToken } from 'chevrotain';
import { MessageType, ShowMessageNotification, type DocumentOnTypeFormattingOptions, type TextEdit } from 'vscode-languageserver-protocol';
import { isRule, isModel, type Model } from '../generated/ast.js';
import type { CactalServices } from '../cactal-module.js';

const INDENT = '    ';

const UNSAFE = 'Not formatted: the new layout would not keep the same tokens, so the file was left as it is (a formatter limitation: please report the file).';

/** The first lexer or parser error of a parse, as `line L, column C: message`. */
function syntaxErrorOf(parseResult: LangiumDocument['parseResult']): string | undefined {
    const lex = parseResult.lexerErrors[0];
    if (lex) return `line ${lex.line ?? '?'}, column ${lex.column ?? '?'}: ${lex.message}`;
    const parse = parseResult.parserErrors[0];
    if (!parse) return undefined;
    const t = parse.token;
    const at = Number.isFinite(t.startLine) ? `line ${t.startLine}, column ${t.startColumn}` : 'end of file';
    return `${at}: ${parse.message}`;
}

/** AST types whose `{ ... }` is an indented block (the others — values, datatypes, persistence — stay inline). */
const BLOCK_TYPES = new Set([
    'Module', 'ParametersBlock', 'SchedulingBlock', 'DataFlowsBlock', 'EventFlowsBlock', 'Schema', 'RealtimeBlock',
    'ModulesBlock', 'SchedulingGraphBlock', 'CommunicationsBlock', 'SchedulerConfiguration', 'SchedulerModules',
    'SchedulerSchemas', 'Supervisor', 'SupervisionFunction', 'LocalBlock', 'RulesBlock'
]);

/** Tokens after which `(` is preceded by a space (operators); after names it is not (`MSA()`, `started(`). */
const SPACE_BEFORE_PAREN = new Set(['=', '==', '!=', '<', '>', '<=', '>=', '|', '&', 'and', 'or', '->', '=*', '=>', '==*', '==>', '*']);

/** Event modes: in `subscribe MAA:2 =* :2` the colon after a mode is spaced. */
const EVENT_MODES = new Set(['=*', '=>', '==*', '==>']);

/** Containers in which `X:N` is written without spaces (a module's port, an `ORD:n` event, a rule label). */
const TIGHT_COLON = new Set(['DataCommunication', 'EventCommunication', 'ModuleEvent', 'Rule']);

type Layout = 'none' | 'space' | 'newline' | 'blank';

interface Item {
    token: IToken;
    comment: boolean;
    /** The CST leaf of a real token (context), undefined for comments. */
    leaf?: CstNode;
    text: string;
}

export class CactalFormatter implements Formatter {
    private readonly services: CactalServices;

    constructor(services: CactalServices) {
        this.services = services;
    }

    formatDocument(document: LangiumDocument): TextEdit[] {
        const text = document.textDocument.getText();
        const result = this.tryFormat(document);
        if ('reason' in result) {
            // an editor shows nothing for an empty edit list: say why the file stayed as it was
            void this.services.shared.lsp.Connection?.sendNotification(ShowMessageNotification.type, { type: MessageType.Warning, message: result.reason });
            return [];
        }
        return minimalEdit(document, text, result.text);
    }

    /** Range formatting formats the whole document (the layout of a block depends on its context). */
    formatDocumentRange(document: LangiumDocument): TextEdit[] {
        return this.formatDocument(document);
    }

    formatDocumentOnType(): TextEdit[] {
        return [];
    }

    get formatOnTypeOptions(): DocumentOnTypeFormattingOptions | undefined {
        return undefined;
    }

    /** The formatted text of a parsed document, or undefined when it cannot be formatted safely. */
    formatText(document: LangiumDocument): string | undefined {
        const result = this.tryFormat(document);
        return 'text' in result ? result.text : undefined;
    }

    /** The formatted text, or why the document is left as it is (shown to the user by formatDocument). */
    tryFormat(document: LangiumDocument): { text: string } | { reason: string } {
        const { parseResult } = document;
        const syntax = syntaxErrorOf(parseResult);
        if (syntax) return { reason: `Not formatted: ${syntax}. Fix the syntax error first: the formatter only lays out a file it can parse.` };
        const root = (parseResult.value as Model).$cstNode;
        if (!root || !isModel(parseResult.value)) return { reason: 'Not formatted: the file holds no Cactal model.' };
        const text = document.textDocument.getText();
        const lexed = this.services.parser.Lexer.tokenize(text);
        const lexError = lexed.errors[0];
        if (lexError) return { reason: `Not formatted: line ${lexError.line ?? '?'}, column ${lexError.column ?? '?'}: ${lexError.message}.` };

        const leaves = new Map<number, CstNode>();
        for (const node of CstUtils.streamCst(root)) {
            if (isLeafCstNode(node) && !node.hidden) leaves.set(node.offset, node);
        }
        const items: Item[] = [
            ...lexed.tokens.map((token) => ({ token, comment: false, leaf: leaves.get(token.startOffset), text: token.image })),
            ...lexed.hidden.filter((t) => /COMMENT/.test(t.tokenType.name)).map((token) => ({ token, comment: true, text: commentText(token) }))
        ].sort((a, b) => a.token.startOffset - b.token.startOffset);
        if (items.some((i) => !i.comment && !i.leaf)) return { reason: UNSAFE };
        for (const item of items) {
            if (!item.comment && (item.text === '==*' || item.text === '==>')) item.text = item.text.slice(1);
        }
        const out = layout(items, text, (parseResult.value as Model));
        return sameTokens(this.services, text, out) ? { text: out } : { reason: UNSAFE };
    }
}

/** The formatted text of the items. */
function layout(items: Item[], source: string, model: Model): string {
    const firstOfElement = new Set<number>();
    const lastOfStatement = new Set<number>();
    for (const node of [...model.imports, ...model.elements]) {
        const cst = node.$cstNode;
        if (!cst) continue;
        if (node.$type !== 'Import') firstOfElement.add(cst.offset);
        lastOfStatement.add(lastLeafOffset(cst));
    }

    let out = '';
    let depth = 0;
    let prevReal: Item | undefined;
    let prev: Item | undefined;
    let newlineRequired = false;
    /** Open inline brackets (values, argument lists, conditions): a line broken inside them (after a comment) is indented once more. */
    let inline = 0;
    for (let i = 0; i < items.length; i++) {
        const item = items[i]!;
        const gapText = prev ? source.slice(prev.token.endOffset! + 1, item.token.startOffset) : '';
        const newlines = (gapText.match(/\n/g) ?? []).length;
        if (item.comment) {
            if (prev && newlines === 0) {
                out += ' ' + item.text;
            } else if (prev) {
                // own-line comment: a top-level element's blank line goes before its leading comments
                const nextReal = items.slice(i + 1).find((x) => !x.comment);
                const blank = (newlines >= 2 && !(prev === prevReal && isBlockOpen(prev))) || (!prev.comment && nextReal !== undefined && firstOfElement.has(nextReal.token.startOffset) && prevReal !== undefined);
                out += (blank ? '\n\n' : '\n') + INDENT.repeat(depth + (inline > 0 ? 1 : 0)) + item.text;
            } else {
                out += item.text;
            }
            newlineRequired = item.token.tokenType.name === 'SL_COMMENT' ? true : newlineRequired;
            if (item.token.tokenType.name !== 'SL_COMMENT') {
                const nextStart = items[i + 1]?.token.startOffset ?? source.length;
                if (/\n/.test(source.slice(item.token.endOffset! + 1, nextStart))) newlineRequired = true;
            }
            prev = item;
            continue;
        }

        let kind: Layout = prevReal ? decide(prevReal, item, firstOfElement, lastOfStatement) : 'none';
        if (isBlockClose(item)) depth = Math.max(0, depth - 1);
        if (prev?.comment) {
            if (newlineRequired || kind === 'newline' || kind === 'blank') kind = newlines >= 2 && !isBlockClose(item) ? 'blank' : 'newline';
            else kind = 'space';
        } else if (kind === 'newline' && newlines >= 2 && !isBlockOpen(prevReal!) && !isBlockClose(item)) {
            kind = 'blank';
        }
        newlineRequired = false;
        if (prev) {
            if (kind === 'space') out += ' ';
            else if (kind === 'newline') out += '\n' + INDENT.repeat(depth + (inline > 0 && !isInlineClose(item) ? 1 : 0));
            else if (kind === 'blank') out += '\n\n' + INDENT.repeat(depth + (inline > 0 && !isInlineClose(item) ? 1 : 0));
        }
        out += item.text;
        if (isBlockOpen(item)) depth++;
        if (isInlineOpen(item)) inline++;
        if (isInlineClose(item)) inline = Math.max(0, inline - 1);
        const bracket = ruleBracket(item);
        if (bracket === 'pre-close') depth++;
        if (bracket === 'post-close') depth = Math.max(0, depth - 1);
        prevReal = item;
        prev = item;
    }
    return out.length ? out + '\n' : '';
}

function lastLeafOffset(cst: CstNode): number {
    let last = cst.offset;
    for (const node of CstUtils.streamCst(cst)) {
        if (isLeafCstNode(node) && !node.hidden) last = node.offset;
    }
    return last;
}

/** The layout between two consecutive real tokens. */
function decide(a: Item, b: Item, firstOfElement: Set<number>, lastOfStatement: Set<number>): Layout {
    if (firstOfElement.has(b.token.startOffset)) return 'blank';
    if (b.leaf?.astNode.$type === 'Import' && b.text === 'import') return 'newline';
    if (lastOfStatement.has(a.token.startOffset)) return 'newline';
    if (a.text === ';') return 'newline';
    if (isBlockOpen(a) || isBlockClose(b)) return 'newline';
    if (isBlockClose(a)) return b.text === ';' ? 'none' : 'newline';
    const ra = ruleBracket(a);
    const rb = ruleBracket(b);
    if (ra === 'pre-close' || ra === 'post-close' || rb === 'post-open') return 'newline';
    if (b.leaf?.astNode.$type === 'Rule' && b.leaf === firstLeaf(b.leaf.astNode.$cstNode)) return 'newline';
    return spacing(a, b);
}

function spacing(a: Item, b: Item): Layout {
    const at = a.leaf?.astNode.$type;
    const bt = b.leaf?.astNode.$type;
    if ([';', ',', ')', ']', '.'].includes(b.text)) return 'none';
    if (['(', '[', '.'].includes(a.text)) return 'none';
    if (a.text === '{' && !isBlockOpen(a)) return 'none';
    if (b.text === '}' && !isBlockClose(b)) return 'none';
    if (b.text === '{' && bt === 'Persistence') return 'none';
    // array sizes and element indexes hug what they follow: `float[6] q`, `scan.ranges[90]`
    if (b.text === '[' && (bt === 'ArrayDimension' || bt === 'IndexSegment')) return 'none';
    if (bt === 'ModuleEvent' && (b.text === '<' || b.text === '>')) return 'none';
    if (at === 'ModuleEvent' && a.text === '<') return 'none';
    if (b.text === ':') {
        if (bt && TIGHT_COLON.has(bt)) return 'none';
        if (bt === 'Subscribe' && !EVENT_MODES.has(a.text)) return 'none';
        return 'space';
    }
    if (a.text === ':') return 'none';
    if (b.text === '(') {
        if (at === 'ModuleEvent' && a.text === '>') return 'none';
        return SPACE_BEFORE_PAREN.has(a.text) ? 'space' : 'none';
    }
    return 'space';
}

function isInlineOpen(item: Item): boolean {
    return !item.comment && (item.text === '(' || item.text === '[' || (item.text === '{' && !isBlockOpen(item)));
}

function isInlineClose(item: Item): boolean {
    return !item.comment && (item.text === ')' || item.text === ']' || (item.text === '}' && !isBlockClose(item)));
}

function isBlockOpen(item: Item): boolean {
    return item.text === '{' && !item.comment && BLOCK_TYPES.has(item.leaf?.astNode.$type ?? '');
}

function isBlockClose(item: Item): boolean {
    return item.text === '}' && !item.comment && BLOCK_TYPES.has(item.leaf?.astNode.$type ?? '');
}

/** Which of a rule's brackets a token is: `[pre]` or `[post]`. */
function ruleBracket(item: Item): 'pre-open' | 'pre-close' | 'post-open' | 'post-close' | undefined {
    const node = item.leaf?.astNode;
    if (!isRule(node) || (item.text !== '[' && item.text !== ']')) return undefined;
    const offset = item.token.startOffset;
    if (item.text === '[') return offset < (node.precondition?.$cstNode?.offset ?? Number.POSITIVE_INFINITY) ? 'pre-open' : 'post-open';
    return offset < (node.postcondition?.$cstNode?.offset ?? Number.POSITIVE_INFINITY) ? 'pre-close' : 'post-close';
}

function firstLeaf(cst: CstNode | undefined): CstNode | undefined {
    if (!cst) return undefined;
    for (const node of CstUtils.streamCst(cst)) {
        if (isLeafCstNode(node) && !node.hidden) return node;
    }
    return undefined;
}

/** A comment as written out: a line comment loses its trailing blanks. */
function commentText(token: IToken): string {
    return token.tokenType.name === 'SL_COMMENT' ? token.image.trimEnd() : token.image;
}

/** True when `after` lexes to the same tokens as `before` (event modes compared in their short form). */
function sameTokens(services: CactalServices, before: string, after: string): boolean {
    const norm = (text: string): string[] => {
        const lexed = services.parser.Lexer.tokenize(text);
        if (lexed.errors.length) return ['<error>'];
        return [...lexed.tokens, ...lexed.hidden.filter((t) => /COMMENT/.test(t.tokenType.name))]
            .sort((x, y) => x.startOffset - y.startOffset)
            .map((t) => (t.image === '==*' || t.image === '==>' ? t.image.slice(1) : commentText(t)));
    };
    const a = norm(before);
    const b = norm(after);
    return a.length === b.length && a.every((t, i) => t === b[i]);
}

/** One edit replacing only the part of the text that changed (keeps the editor's cursor and undo tidy). */
function minimalEdit(document: LangiumDocument, before: string, after: string): TextEdit[] {
    if (before === after) return [];
    let start = 0;
    while (start < before.length && start < after.length && before[start] === after[start]) start++;
    let endBefore = before.length;
    let endAfter = after.length;
    while (endBefore > start && endAfter > start && before[endBefore - 1] === after[endAfter - 1]) { endBefore--; endAfter--; }
    const doc = document.textDocument;
    return [{ range: { start: doc.positionAt(start), end: doc.positionAt(endBefore) }, newText: after.slice(start, endAfter) }];
}
