/**
 * Checks a parsed scenario against the project's model (docs/simulation.md "Values and names"):
 * every supervisor, function, rule, local, schema, module, event port and parameter named must
 * exist, and every value must fit its type — through the language's own value checker
 * (`checkValue`, the one that checks defaults and parameterisations), fed with AST-shaped
 * literals built from the scenario's values. Returns diagnostics and, for `expect local NAME`,
 * the function that owns NAME. Never throws.
 */
import { isEnumType, isModule, isSchema, isSupervisor, type EnumType, type Model, type Module, type Supervisor, type SupervisionFunction } from '../generated/ast.js';
import { localsOf, rulesOf } from '../model/blocks.js';
import { portsOfKind } from '../model/ports.js';
import { typeName, typeOf, type CactalType } from '../model/types.js';
import { checkValue } from '../validation/value-checker.js';
import { didYouMean } from './did-you-mean.js';
import type { ScenarioDiagnostic, ScenarioValue, SourceSpan, Step } from './parse.js';

export interface ModelIndex {
    supervisors: Map<string, Supervisor>;
    modules: Map<string, Module>;
    schemas: Set<string>;
    /** The periodic ones (ORD's: deadlines, overruns); absent means not known (no check). */
    periodic?: Set<string>;
    /** Enumerations (extension), for values `Mode.AUTO`; absent means none. */
    enums?: Map<string, EnumType>;
}

export function indexModels(models: Model[]): ModelIndex {
    const index: ModelIndex = { supervisors: new Map(), modules: new Map(), schemas: new Set(), periodic: new Set(), enums: new Map() };
    for (const m of models) {
        for (const e of m.elements) {
            if (isEnumType(e)) index.enums!.set(e.name, e);
            else if (isSupervisor(e)) index.supervisors.set(e.name, e);
            else if (isModule(e)) index.modules.set(e.name, e);
            else if (isSchema(e)) {
                index.schemas.add(e.name);
                if (e.kind === 'periodic') index.periodic!.add(e.name);
            }
        }
    }
    return index;
}

/** `expect local NAME` resolved to its owner. */
export interface ResolvedLocal {
    supervisor: string;
    function: string;
}

export interface ScenarioCheck {
    diagnostics: ScenarioDiagnostic[];
    /** By step index: the owner of each `expect local` local. */
    locals: Map<number, ResolvedLocal>;
}

type Lit = { $type: string; value?: unknown; elements?: Lit[]; $cstNode?: { text: string }; span: SourceSpan };

/** The scenario value as the literal nodes `checkValue` reads (the language's Value types). */
function asAst(v: ScenarioValue, index: ModelIndex): Lit {
    switch (v.kind) {
        case 'enum': {
            // read like the Cactal `Mode.AUTO` (a VariableRef naming the enumeration, then its member)
            const enumType = index.enums?.get(v.enumName);
            const member = enumType?.members.find((m) => m.name === v.member);
            if (!enumType || !member) throw new Error(`unknown member ${v.text}`); // reported before (unknownMembers)
            return {
                $type: 'VariableRef', ordSchema: false, span: v.span,
                variable: { ref: enumType, $refText: enumType.name },
                path: [{ $type: 'FieldSegment', field: { ref: member, $refText: member.name } }]
            } as unknown as Lit;
        }
        case 'int': return { $type: 'IntLiteral', value: v.value, $cstNode: { text: v.text }, span: v.span };
        case 'real': return { $type: 'RealLiteral', value: v.value, $cstNode: { text: v.text }, span: v.span };
        case 'string': return { $type: 'StringLiteral', value: v.value, span: v.span };
        case 'bool': return { $type: 'BoolLiteral', value: v.value, span: v.span };
        case 'struct': return { $type: 'StructValue', elements: v.elements.map((e) => asAst(e, index)), span: v.span };
    }
}

/** The `Enum.MEMBER` values of `v` whose enumeration or member does not exist. */
function unknownMembers(v: ScenarioValue, index: ModelIndex): Array<Extract<ScenarioValue, { kind: 'enum' }>> {
    if (v.kind === 'struct') return v.elements.flatMap((e) => unknownMembers(e, index));
    if (v.kind !== 'enum') return [];
    return index.enums?.get(v.enumName)?.members.some((m) => m.name === v.member) ? [] : [v];
}

function functionOf(sup: Supervisor, name: string): SupervisionFunction | undefined {
    return sup.functions.find((f) => f.name === name);
}

export function checkScenario(steps: Step[], index: ModelIndex): ScenarioCheck {
    const diagnostics: ScenarioDiagnostic[] = [];
    const locals = new Map<number, ResolvedLocal>();
    // a message quotes what was written: a 10,000-character name is cut, not echoed whole
    const error = (span: SourceSpan, code: string, message: string) =>
        diagnostics.push({ ...span, severity: 'error', code, message: message.length > 300 ? `${message.slice(0, 300)}…` : message });
    const list = (names: Iterable<string>) => {
        const all = [...names];
        return all.length ? all.slice(0, 12).join(', ') + (all.length > 12 ? ', ...' : '') : 'none';
    };
    const value = (v: ScenarioValue, type: CactalType, what: string) => {
        const unknown = unknownMembers(v, index);
        for (const bad of unknown) {
            const e = index.enums?.get(bad.enumName);
            error(bad.span, 'scenario-value-type', e
                ? `'${bad.member}' is not a member of enumeration ${e.name}; its members: ${list(e.members.map((m) => m.name))}`
                : `no enumeration '${bad.enumName}' in the project (enumerations: ${list(index.enums?.keys() ?? [])})`);
        }
        if (unknown.length > 0) return;
        try {
            checkValue(asAst(v, index) as never, type, ((_severity: string, message: string, info: { node: Lit }) => {
                error(info.node?.span ?? v.span, 'scenario-value-type', message);
            }) as never, { allowVariables: false, what });
        } catch (e) {
            error(v.span, 'scenario-value-type', `cannot check this value (${e instanceof Error ? e.message : String(e)})`);
        }
    };
    const supervisor = (name: { text: string; span: SourceSpan }) => {
        const s = index.supervisors.get(name.text);
        if (!s) error(name.span, 'scenario-unknown-supervisor', `no supervisor '${name.text}' in the project (supervisors: ${list(index.supervisors.keys())})${didYouMean(name.text, index.supervisors.keys())}`);
        return s;
    };
    const fn = (sup: Supervisor | undefined, name: { text: string; span: SourceSpan }) => {
        if (!sup) return undefined;
        const f = functionOf(sup, name.text);
        if (!f) error(name.span, 'scenario-unknown-function', `supervisor ${sup.name} has no function '${name.text}' (functions: ${list(sup.functions.map((x) => x.name))})${didYouMean(name.text, sup.functions.map((x) => x.name))}`);
        return f;
    };
    /** Whether the project has schema `text`; when not, the error names those it has. */
    const schema = (text: string, span: SourceSpan): boolean => {
        if (index.schemas.has(text)) return true;
        error(span, 'scenario-unknown-schema', `no schema '${text}' in the project (schemas: ${list(index.schemas)})${didYouMean(text, index.schemas)}`);
        return false;
    };
    const module = (name: { text: string; span: SourceSpan }) => {
        if (!index.modules.has(name.text)) error(name.span, 'scenario-unknown-module', `no module '${name.text}' in the project (modules: ${list(index.modules.keys())})${didYouMean(name.text, index.modules.keys())}`);
        return index.modules.get(name.text);
    };

    steps.forEach((step, i) => {
        switch (step.kind) {
            case 'start': {
                const f = fn(supervisor(step.supervisor), step.function);
                if (!f) return;
                const seen = new Set<string>();
                for (const arg of step.args) {
                    const p = f.parameters.find((x) => x.name === arg.name.text);
                    if (!p) {
                        error(arg.name.span, 'scenario-unknown-parameter', `${step.supervisor.text}.${f.name} has no parameter '${arg.name.text}' (parameters: ${list(f.parameters.map((x) => x.name))})${didYouMean(arg.name.text, f.parameters.map((x) => x.name))}`);
                        continue;
                    }
                    if (seen.has(p.name)) error(arg.name.span, 'scenario-duplicate-parameter', `parameter '${p.name}' is given twice`);
                    seen.add(p.name);
                    value(arg.value, typeOf(p.type), `parameter '${p.name}'`);
                }
                return;
            }
            case 'stop':
                fn(supervisor(step.supervisor), step.function);
                return;
            case 'crash':
                module(step.module);
                return;
            case 'finish': {
                const m = module(step.module);
                if (m && m.kind !== 'asynchronous') error(step.module.span, 'scenario-not-asynchronous', `${m.name} is a synchronous module: each of its releases ends by itself (exec sets how long one takes); finish ends the run of an asynchronous module`);
                return;
            }
            case 'exec':
                // a synchronous module's releases, an asynchronous one's handling of each event of a connected event flow
                module(step.module);
                return;
            case 'event': {
                const src = step.module.text;
                if (src === 'ORD') {
                    if (step.port !== 0 && step.port !== 1) error(step.portSpan, 'scenario-unknown-port', `ORD has event ports 0 (deadline miss) and 1 (conflict), not ${step.port}`);
                    if (step.portName) error(step.portName.span, 'scenario-unknown-port', 'ORD\'s events carry the schema name only: write ORD:0 "schema"');
                    if (!step.value) error(step.span, 'scenario-missing-value', 'an ORD event carries a schema name: ORD:0 "schemaName"');
                    else if (step.value.kind !== 'string') value(step.value, { kind: 'primitive', name: 'string' }, 'the schema name of an ORD event');
                    else schema(step.value.value, step.value.span);
                    return;
                }
                const owner: Module | Supervisor | undefined = index.modules.get(src) ?? index.supervisors.get(src);
                if (!owner) {
                    // only those that have out event ports can be the source of an event step
                    const emitters = [...index.modules.values(), ...index.supervisors.values()].filter((o) => portsOfKind(o, 'event', 'out').length > 0).map((o) => o.name);
                    error(step.module.span, 'scenario-unknown-module', `no module or supervisor '${src}' emits events in the project (those that do: ${list(emitters)})${didYouMean(src, emitters)}`);
                    return;
                }
                const port = portsOfKind(owner, 'event', 'out').find((p) => p.index === step.port);
                if (!port) {
                    const outs = portsOfKind(owner, 'event', 'out').map((p) => `:${p.index} ${p.name}`);
                    error(step.portSpan, 'scenario-unknown-port', `${src} has no out event port ${step.port} (out event ports: ${list(outs)})`);
                    return;
                }
                if (step.portName && step.portName.text !== port.name) error(step.portName.span, 'scenario-port-name', `${src}:${step.port} is '${port.name}', not '${step.portName.text}'`);
                if (step.value) value(step.value, typeOf(port.type), `${src}:${step.port} (${typeName(typeOf(port.type))} ${port.name})`);
                return;
            }
            case 'expect': {
                const e = step.expectation;
                switch (e.kind) {
                    case 'rule': {
                        const f = fn(supervisor(e.supervisor), e.function);
                        if (f && !rulesOf(f).some((r) => r.name === e.rule.text)) {
                            error(e.rule.span, 'scenario-unknown-rule', `${e.supervisor.text}.${f.name} has no rule '${e.rule.text}' (rules: ${list(rulesOf(f).map((r) => r.name))})${didYouMean(e.rule.text, rulesOf(f).map((r) => r.name))}`);
                        }
                        return;
                    }
                    case 'function':
                        fn(supervisor(e.supervisor), e.function);
                        return;
                    case 'schema':
                        schema(e.schema.text, e.schema.span);
                        return;
                    case 'module':
                        module(e.module);
                        return;
                    case 'count':
                        if (schema(e.schema.text, e.schema.span) && index.periodic && !index.periodic.has(e.schema.text)) {
                            error(e.schema.span, 'scenario-not-periodic', `${e.schema.text} is an event schema: it has no period, so no deadline misses nor overruns (ORD counts those of periodic schemas: ${list(index.periodic)})`);
                        }
                        return;
                    case 'local': {
                        let owners: Array<{ sup: Supervisor; f: SupervisionFunction }> = [];
                        if (e.supervisor && e.function) {
                            const sup = supervisor(e.supervisor);
                            const f = fn(sup, e.function);
                            if (!sup || !f) return;
                            owners = [{ sup, f }];
                        } else {
                            for (const sup of index.supervisors.values())
                                for (const f of sup.functions) if (localsOf(f).some((l) => l.name === e.local.text)) owners.push({ sup, f });
                            if (owners.length > 1) {
                                error(e.local.span, 'scenario-ambiguous-local', `'${e.local.text}' is a local of ${owners.map((o) => `${o.sup.name}.${o.f.name}`).join(' and ')}: write SUP.function.${e.local.text}`);
                                return;
                            }
                        }
                        const owner = owners[0];
                        const local = owner && localsOf(owner.f).find((l) => l.name === e.local.text);
                        if (!owner || !local) {
                            const where = owner ? `${owner.sup.name}.${owner.f.name} has no local` : 'no function of the project has a local';
                            const known = owner ? ` (locals: ${list(localsOf(owner.f).map((l) => l.name))})` : '';
                            const near = owner ? didYouMean(e.local.text, localsOf(owner.f).map((l) => l.name)) : '';
                            error(e.local.span, 'scenario-unknown-local', `${where} '${e.local.text}'${known}${near}`);
                            return;
                        }
                        locals.set(i, { supervisor: owner.sup.name, function: owner.f.name });
                        value(e.value, typeOf(local.type), `local '${local.name}'`);
                        return;
                    }
                }
            }
        }
    });
    return { diagnostics, locals };
}
