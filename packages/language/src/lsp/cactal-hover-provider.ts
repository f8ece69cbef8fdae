/**
 * Hover (SPEC §2.7): what a name designates — its type, a port's direction/kind/index and type,
 * the value a declaration starts with (written or default), a module's C, and on a schema its
 * utilisation (sum C / PERIOD) and critical path (longest chain of C through the precedence graph).
 * Works on declarations and on every cross-reference, including port references by index.
 */
import { AstUtils, CstUtils, type AstNode, type LangiumDocument, type MaybePromise } from 'langium';
import type { Hover, HoverParams } from 'vscode-languageserver-protocol';
import { AstNodeHoverProvider } from 'langium/lsp';
import {
    isDataType, isField, isModuleEvent, isFunctionArgument, isFunctionParameter, isFunctionPrototype, isLocalVariable, isModule,
    isParameter, isPort, isRule, isSchema, isSchemaParameter, isSupervisionFunction, isSupervisor,
    type Module, type Port, type Schema, type Supervisor, type TypeRef, type Value
} from '../generated/ast.js';
import { computeTimeNs, parametersOf } from '../model/blocks.js';
import { portKind, portsOf } from '../model/ports.js';
import { formatNanoseconds } from '../model/time.js';
import { typeRefText } from '../model/types.js';
import { defaultValue, effectiveValue, formatConstant } from '../model/values.js';
import { schemaModules, schemaTiming } from '../validation/timing-analysis.js';

export class CactalHoverProvider extends AstNodeHoverProvider {
    override async getHoverContent(document: LangiumDocument, params: HoverParams): Promise<Hover | undefined> {
        const root = document.parseResult.value.$cstNode;
        const leaf = root ? CstUtils.findLeafNodeAtOffset(root, document.textDocument.offsetAt(params.position)) : undefined;
        const node = leaf?.astNode;
        if (isModuleEvent(node) && node.ord && leaf && leaf.text === 'ORD') {
            return { contents: { kind: 'markdown', value: ordEventHover(node.ordPort) } };
        }
        return super.getHoverContent(document, params);
    }

    protected override getAstNodeHoverContent(node: AstNode): MaybePromise<string | undefined> {
        return hoverMarkdown(node);
    }
}

/** The scheduler's events (SPEC §4.2). */
export function ordEventHover(port: number | undefined): string {
    const meaning = port === 0
        ? 'a periodic schema\'s cycle has not finished at tick + CRITICAL_DELAY (critical lateness); data: the schema name'
        : port === 1
            ? 'an activation was refused because the schema shares a module with an active schema; data: the refused schema\'s name'
            : 'not an event of the scheduler (ORD emits :0 and :1)';
    return `${code(`ORD:${port ?? '?'}`)}\n\nscheduler event: ${meaning}`;
}

const code = (text: string): string => '```cactal\n' + text + '\n```';

/** The value line of a typed declaration: `= written` or `= default (default)`. */
function valueLine(node: { type: TypeRef; value?: Value }): string {
    const value = effectiveValue(node);
    if (!value) return node.value ? `value: \`${node.value.$cstNode?.text ?? '?'}\`` : '';
    return `value: \`${formatConstant(value)}\`${node.value ? '' : ' (default)'}`;
}

function ownerName(node: AstNode): string {
    const owner = AstUtils.getContainerOfType(node, (n): n is Module | Supervisor => isModule(n) || isSupervisor(n));
    return owner?.name ?? '?';
}

/** Markdown describing a declaration (undefined for nodes without a hover). */
export function hoverMarkdown(node: AstNode): string | undefined {
    const parts: string[] = [];
    if (isDataType(node)) {
        parts.push(code(`datatype ${node.name} {${node.fields.map((f) => `${typeRefText(f.type)} ${f.name}`).join(', ')}}`));
        const value = defaultValue({ kind: 'struct', datatype: node });
        if (value) parts.push(`default: \`${formatConstant(value)}\``);
    } else if (isField(node)) {
        parts.push(code(`${typeRefText(node.type)} ${node.name}`), `field of \`${node.$container.name}\``, valueLine(node));
    } else if (isFunctionPrototype(node)) {
        parts.push(code(`function ${typeRefText(node.returnType)} ${node.name}(${node.args.map((a) => `${typeRefText(a.type)} ${a.name}`).join(', ')})`));
    } else if (isFunctionArgument(node)) {
        parts.push(code(`${typeRefText(node.type)} ${node.name}`), `argument of function \`${node.$container.name}\``);
    } else if (isModule(node)) {
        parts.push(...moduleHover(node));
    } else if (isParameter(node)) {
        parts.push(code(`${typeRefText(node.type)} ${node.name} :${node.index}`), `parameter port :${node.index} of \`${ownerName(node)}\`, type \`${typeRefText(node.type)}\``, valueLine(node));
    } else if (isPort(node)) {
        parts.push(...portHover(node));
    } else if (isSchema(node)) {
        parts.push(...schemaHover(node));
    } else if (isSchemaParameter(node)) {
        parts.push(code(`${typeRefText(node.type)} ${node.name}`), `parameter of schema \`${node.$container.name}\``, valueLine(node));
    } else if (isSupervisor(node)) {
        parts.push(code(`supervisor ${node.name}`),
            portsOf(node).map((p) => `- ${p.direction} event :${p.index} \`${typeRefText(p.port.type)} ${p.port.name}\``).join('\n'),
            `functions: ${node.functions.map((f) => `\`${f.name}\``).join(', ') || 'none'}`);
    } else if (isSupervisionFunction(node)) {
        parts.push(code(`${node.$container.name}.${node.name}(${node.parameters.map((p) => `${typeRefText(p.type)} ${p.name}`).join(', ')})`), 'supervision function');
    } else if (isFunctionParameter(node)) {
        parts.push(code(`${typeRefText(node.type)} ${node.name}`), `parameter of supervision function \`${node.$container.name}\``, valueLine(node));
    } else if (isLocalVariable(node)) {
        const fn = AstUtils.getContainerOfType(node, isSupervisionFunction);
        parts.push(code(`${typeRefText(node.type)} ${node.name}`), `local of supervision function \`${fn?.name ?? '?'}\``, valueLine(node));
    } else if (isRule(node)) {
        const fn = AstUtils.getContainerOfType(node, isSupervisionFunction);
        parts.push(code(`${node.name}: [...]`), `rule of supervision function \`${fn?.name ?? '?'}\` (${node.actions.length} action${node.actions.length === 1 ? '' : 's'})`);
    } else {
        return undefined;
    }
    return parts.filter((p) => p.length > 0).join('\n\n');
}

function moduleHover(module: Module): string[] {
    const c = computeTimeNs(module);
    const lines = [
        ...parametersOf(module).map((p) => `- parameter :${p.index} \`${typeRefText(p.type)} ${p.name}\``),
        ...portsOf(module).map((p) => `- ${p.direction} ${p.kind} :${p.index} \`${typeRefText(p.port.type)} ${p.port.name}\``)
    ];
    return [
        code(`${module.kind} module ${module.name}`),
        c !== undefined ? `C = ${formatNanoseconds(c)}` : (module.kind === 'synchronous' ? 'C: not given' : ''),
        lines.join('\n')
    ];
}

function portHover(port: Port): string[] {
    const kind = portKind(port);
    return [
        code(`${port.direction} :${port.index} ${typeRefText(port.type)} ${port.name}`),
        `${port.direction} ${kind} port :${port.index} of \`${ownerName(port)}\`, type \`${typeRefText(port.type)}\``,
        valueLine(port)
    ];
}

function schemaHover(schema: Schema): string[] {
    const parts = [code(`${schema.kind} schema ${schema.name}(${schema.parameters.map((p) => `${typeRefText(p.type)} ${p.name}`).join(', ')})`)];
    if (schema.kind !== 'periodic') return parts;
    const timing = schemaTiming(schema);
    const delay = timing.criticalDelayNs;
    const path = timing.criticalPath;
    const figures = [
        `PERIOD = ${timing.periodNs !== undefined ? formatNanoseconds(timing.periodNs) : 'not given'}` +
            (delay !== undefined ? `, CRITICAL_DELAY = ${formatNanoseconds(delay)}` : ''),
        `utilisation: ${timing.utilisation !== undefined ? `${formatPercent(timing.utilisation)} (sum C = ${formatNanoseconds(timing.totalComputeNs)})` : 'unknown (no PERIOD)'}`,
        path
            ? `critical path: ${formatNanoseconds(path.ns)} (${path.modules.map((m) => m.name).join(' -> ')})`
            : 'critical path: none (no module, or the scheduling graph has a cycle)'
    ];
    const missingC = schemaModules(schema).filter((m) => computeTimeNs(m) === undefined).map((m) => m.name);
    if (missingC.length) figures.push(`without C: ${missingC.join(', ')}`);
    parts.push(figures.map((f) => `- ${f}`).join('\n'));
    return parts;
}

/** `0.0012` -> `0.12%` (two significant decimals at most). */
export function formatPercent(ratio: number): string {
    const percent = ratio * 100;
    return `${Number(percent.toPrecision(percent >= 1 ? 4 : 2))}%`;
}
