/**
 * Hover (docs/ide.md "Editor services"): what a name designates — its type, a port's direction/kind/index and type,
 * the value a declaration starts with (written or default), a module's C, and on a schema its
 * utilisation (sum C / PERIOD) and critical path (longest chain of C through the precedence graph),
 * and the periodic schemas it conflicts with (they share a module: ORD refuses one while the other
 * is active, docs/engines.md).
 * Works on declarations and on every cross-reference, including port references by index.
 */
import { AstUtils, CstUtils, type AstNode, type LangiumDocument, type MaybePromise } from 'langium';
import type { Hover, HoverParams } from 'vscode-languageserver-protocol';
import { AstNodeHoverProvider, type LangiumServices } from 'langium/lsp';
import {
    isConstant, isEnumMember, isEnumType, isDataType, isField, isModuleEvent, isFunctionArgument, isFunctionParameter, isFunctionPrototype, isLocalVariable, isModule,
    isModel, isParameter, isPort, isRule, isSchema, isSchemaParameter, isSupervisionFunction, isSupervisor, isTimeProperty,
    type DataType, type Field, type Module, type Port, type Schema, type Supervisor, type TimeProperty, type TypeRef, type Value
} from '../generated/ast.js';
import { computeTimeNs, parametersOf } from '../model/blocks.js';
import { sharedModules } from '../model/schema-conflicts.js';
import { portKind, portsOf } from '../model/ports.js';
import { formatNanoseconds, timeToNanoseconds } from '../model/time.js';
import { cLayout, typeName, typeOf, typeRefText, type CactalType } from '../model/types.js';
import { defaultValue, effectiveValue, formatConstant } from '../model/values.js';
import { schemaModules, schemaTiming } from '../validation/timing-analysis.js';

export class CactalHoverProvider extends AstNodeHoverProvider {
    private readonly documents: LangiumServices['shared']['workspace']['LangiumDocuments'];

    constructor(services: LangiumServices) {
        super(services);
        this.documents = services.shared.workspace.LangiumDocuments;
    }

    override async getHoverContent(document: LangiumDocument, params: HoverParams): Promise<Hover | undefined> {
        const root = document.parseResult.value.$cstNode;
        const leaf = root ? CstUtils.findLeafNodeAtOffset(root, document.textDocument.offsetAt(params.position)) : undefined;
        const node = leaf?.astNode;
        if (isModuleEvent(node) && node.ord && leaf && leaf.text === 'ORD') {
            return { contents: { kind: 'markdown', value: ordEventHover(node.ordPort) } };
        }
        // `C=1ms;`, `PERIOD=1s;`: the name and the value are not references, Langium has no hover there
        const property = node && AstUtils.getContainerOfType(node, isTimeProperty);
        if (property) return { contents: { kind: 'markdown', value: timePropertyHover(property) } };
        return super.getHoverContent(document, params);
    }

    protected override getAstNodeHoverContent(node: AstNode): MaybePromise<string | undefined> {
        return hoverMarkdown(node, isSchema(node) ? this.workspaceSchemas() : []);
    }

    /** Every schema of the loaded documents (schemas of other projects share no module node). */
    private workspaceSchemas(): Schema[] {
        return this.documents.all
            .flatMap((doc) => {
                const root = doc.parseResult?.value;
                return isModel(root) ? root.elements.filter(isSchema) : [];
            })
            .toArray();
    }
}

/** `1ms` -> `1,000 µs`: one unit for every figure of a timing hover (times: docs/language-reference.md §3, §4). */
export function formatMicroseconds(ns: number): string {
    return `${(ns / 1000).toLocaleString('en-US', { maximumFractionDigits: 3 })} µs`;
}

const PROPERTY_MEANING: Record<string, string> = {
    C: 'computation time (worst case) of one activation',
    PERIOD: 'period of the schema: its modules are activated once per period',
    CRITICAL_DELAY: 'deadline of a cycle after its tick: past it the scheduler emits ORD:0 (critical lateness)'
};

/**
 * Hover on a timing property: its value in µs and what it means; in a schema's realtime block also
 * the schema's utilisation and critical path (validation/timing-analysis.ts).
 */
export function timePropertyHover(property: TimeProperty): string {
    const ns = timeToNanoseconds(property.value?.text ?? '');
    const parts = [code(`${property.name}=${property.value?.text ?? '?'}`)];
    parts.push(Number.isNaN(ns) ? 'value: not a time literal (`500us`, `1ms`, `1s`)' : `= ${formatMicroseconds(ns)}`);
    const meaning = PROPERTY_MEANING[property.name];
    const owner = AstUtils.getContainerOfType(property, (n): n is Module | Schema => isModule(n) || isSchema(n));
    if (meaning) parts.push(`${property.name}: ${meaning}${owner ? ` (\`${owner.name}\`)` : ''}`);
    if (isSchema(owner) && owner.kind === 'periodic') {
        const timing = schemaTiming(owner);
        const path = timing.criticalPath;
        parts.push([
            `utilisation of \`${owner.name}\`: ${timing.utilisation !== undefined ? `${formatPercent(timing.utilisation)} (sum C = ${formatMicroseconds(timing.totalComputeNs)})` : 'unknown (no PERIOD)'}`,
            path ? `critical path: ${formatMicroseconds(path.ns)} (${path.modules.map((m) => m.name).join(' -> ')})` : 'critical path: none (no module, or the scheduling graph has a cycle)',
        ].map((f) => `- ${f}`).join('\n'));
    }
    return parts.join('\n\n');
}

/** The scheduler's events (docs/semantics.md "Scheduler: critical delay (ORD:0)", "Scheduler: conflict (ORD:1)"). */
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

const bytes = (n: number) => `${n.toLocaleString('en-US')} byte${n === 1 ? '' : 's'}`;

/** `size: 48 bytes (C double[6])`: the size of a value of the type in the generated C (LP64). */
function sizeLine(type: CactalType): string {
    const layout = cLayout(type);
    return layout ? `size: ${bytes(layout.size)}${type.kind === 'array' ? ` (${type.size} × ${typeName(type.element)})` : ''}` : '';
}

/** The C layout of a datatype: its size and each field's offset and size (LP64, as gcc lays it out). */
function datatypeLayout(dt: DataType): string {
    const whole = cLayout({ kind: 'struct', datatype: dt });
    if (!whole) return '';
    let offset = 0;
    const rows: string[] = [];
    for (const f of dt.fields) {
        const l = cLayout(typeOf(f.type));
        if (!l) return `size: ${bytes(whole.size)}`;
        offset = Math.ceil(offset / l.align) * l.align;
        rows.push(`- \`${f.name}\`: offset ${offset}, ${bytes(l.size)}`);
        offset += l.size;
    }
    return [`size: ${bytes(whole.size)}`, ...rows].join('\n');
}

function fieldLayout(field: Field): string {
    const dt = field.$container;
    let offset = 0;
    for (const f of dt.fields) {
        const l = cLayout(typeOf(f.type));
        if (!l) return '';
        offset = Math.ceil(offset / l.align) * l.align;
        if (f === field) return `offset ${offset} in \`${dt.name}\`, ${bytes(l.size)}${l.size !== 0 && typeOf(f.type).kind === 'array' ? ` (${typeName(typeOf(f.type))})` : ''}`;
        offset += l.size;
    }
    return '';
}

function ownerName(node: AstNode): string {
    const owner = AstUtils.getContainerOfType(node, (n): n is Module | Supervisor => isModule(n) || isSupervisor(n));
    return owner?.name ?? '?';
}

/**
 * Markdown describing a declaration (undefined for nodes without a hover). `schemas`: the
 * project's schemas, to list those a hovered schema conflicts with.
 */
export function hoverMarkdown(node: AstNode, schemas: readonly Schema[] = []): string | undefined {
    const parts: string[] = [];
    if (isDataType(node)) {
        parts.push(code(`datatype ${node.name} {${node.fields.map((f) => `${typeRefText(f.type)} ${f.name}`).join(', ')}}`));
        const value = defaultValue({ kind: 'struct', datatype: node });
        if (value) parts.push(`default: \`${formatConstant(value)}\``);
        parts.push(datatypeLayout(node));
    } else if (isField(node)) {
        parts.push(code(`${typeRefText(node.type)} ${node.name}`), `field of \`${node.$container.name}\``, valueLine(node), fieldLayout(node));
    } else if (isEnumType(node)) {
        parts.push(code(`enum ${node.name} {${node.members.map((m) => m.name).join(', ')}}`),
            `enumeration (extension): C \`${node.name}\` with members ${node.members.map((m, i) => `\`${node.name}_${m.name}\` = ${i}`).join(', ')}; 4 bytes; default \`${node.members[0] ? `${node.name}.${node.members[0].name}` : '?'}\``);
    } else if (isEnumMember(node)) {
        const owner = node.$container;
        parts.push(code(`${owner.name}.${node.name}`), `member ${owner.members.indexOf(node)} of enumeration \`${owner.name}\` (C \`${owner.name}_${node.name}\`)`);
    } else if (isConstant(node)) {
        parts.push(code(`const ${typeRefText(node.type)} ${node.name}`), 'named constant (extension): its value is written in the generated C wherever it is used', valueLine(node), sizeLine(typeOf(node.type)));
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
        parts.push(...schemaHover(node, schemas));
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
        valueLine(port),
        sizeLine(typeOf(port.type))
    ];
}

function schemaHover(schema: Schema, schemas: readonly Schema[]): string[] {
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
    const conflicts = schemas.filter((s) => s !== schema).map((s) => ({ s, modules: sharedModules(schema, s) })).filter((c) => c.modules.length > 0);
    if (conflicts.length) {
        parts.push(`conflicts with (shared modules: ORD refuses one while the other is active, ORD:1): ${conflicts
            .map((c) => `\`${c.s.name}\` (${c.modules.map((m) => m.name).join(', ')})`).join(', ')}`);
    }
    return parts;
}

/** `0.0012` -> `0.12%` (two significant decimals at most). */
export function formatPercent(ratio: number): string {
    const percent = ratio * 100;
    return `${Number(percent.toPrecision(percent >= 1 ? 4 : 2))}%`;
}
