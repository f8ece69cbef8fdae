/**
 * Builds the plain Architecture from Langium documents of the Cactal language
 * (@contract-studio/language). References are read by their written text, port references by
 * their index, so that the result stays well defined even for partially linked input.
 */
import type { AstNode } from 'langium';
import {
    communicationsOf, computeTimeNs, criticalDelayNs, dataPortsOf, eventPortsOf, localsOf, moduleInstancesOf,
    parametersOf, periodNs, precedencesOf, rulesOf, scheduledModulesOf, scheduledSchemasOf, timeToNanoseconds,
    isDataType, isFunctionPrototype, isModule, isSchema, isSchedulerConfiguration, isSupervisor,
    isIntLiteral, isRealLiteral, isStringLiteral, isStructValue, isVariableRef, isDataCommunication,
    isEqualityTest, isRelationalTest, isFunctionTest, isStartedEvent, isEndofEvent, isDurationEvent, isElapsedEvent,
    isActivateSchema, isActivateSupervisor, isActivateModule, isParameterize, isCompute, isSubscribe, isNotify,
    type Model, type TypeRef as AstTypeRef, type Value as AstValue, type Port as AstPort, type Parameter as AstParameter,
    type Condition as AstCondition, type Event as AstEvent, type Action as AstAction, type Persistence as AstPersistence,
    type Extraction, type ParameterSetting, type TestOperand, type Test as AstTest, type Module as AstModule,
    type Supervisor as AstSupervisor, type Schema as AstSchema, type SupervisionFunction as AstFunction,
    eventInPort, isBoolLiteral, isConstant, isEnumType, isFieldSegment, constantValue, exactIntegerText, segmentIndex, typeOf, typeOfVariableRef,
    type CactalType, type ConstantValue, type PathSegment as AstPathSegment,
} from '@contract-studio/language';
import type {
    Action, Architecture, Assignment, Condition, Datatype, Event, PathSegment, FunctionPrototype, Module, NamedValue, ParamSetting,
    Persistence, PortDecl, Schema, Supervisor, SupervisionFunction, Test, TypeRef, Value,
} from './architecture.js';

/** A language type as the generators see it (unknown parts keep their written names). */
function fromCactalType(t: CactalType): TypeRef | undefined {
    switch (t.kind) {
        case 'primitive': return t.name === 'void' ? undefined : { primitive: t.name };
        case 'struct': return { datatype: t.datatype.name };
        case 'enum': return { enum: t.enumType.name };
        case 'array': {
            const element = fromCactalType(t.element);
            return element ? { array: element, size: t.size } : undefined;
        }
        default: return undefined;
    }
}

function typeRef(t: AstTypeRef | undefined): TypeRef {
    if (t?.primitive === 'int' || t?.primitive === 'float' || t?.primitive === 'string' || t?.primitive === 'bool') {
        if (t.dimensions.length === 0) return { primitive: t.primitive };
    }
    return fromCactalType(typeOf(t)) ?? { datatype: t?.datatype?.$refText ?? '?' };
}

/** A constant of the language's value model as a written value. */
function fromConstant(c: ConstantValue): Value {
    switch (c.kind) {
        case 'int': return c.text === undefined ? { kind: 'int', value: c.value } : { kind: 'int', value: c.value, text: c.text };
        case 'float': return { kind: 'real', value: c.value };
        case 'string': return { kind: 'string', value: c.value };
        case 'bool': return { kind: 'bool', value: c.value };
        case 'enum': return { kind: 'enum', enum: c.enumType.name, member: c.member };
        case 'array': return { kind: 'struct', elements: c.elements.map(fromConstant) };
        case 'struct': return { kind: 'struct', elements: c.fields.map((f) => fromConstant(f.value)) };
    }
}

function value(v: AstValue | TestOperand | undefined): Value | undefined {
    if (!v) return undefined;
    if (isIntLiteral(v)) {
        // the text as written: the number it was read as is exact up to 2^53 only
        const text = exactIntegerText(v.$cstNode?.text);
        return text === undefined ? { kind: 'int', value: Number(v.value) } : { kind: 'int', value: Number(v.value), text };
    }
    if (isRealLiteral(v)) return { kind: 'real', value: Number(v.value) };
    if (isStringLiteral(v)) return { kind: 'string', value: v.value };
    if (isBoolLiteral(v)) return { kind: 'bool', value: v.value };
    if (isStructValue(v)) return { kind: 'struct', elements: v.elements.map((e) => value(e) ?? { kind: 'int', value: 0 }) };
    if (isVariableRef(v)) {
        const head = v.variable?.ref;
        if (isEnumType(head)) {
            const first = v.path[0];
            return { kind: 'enum', enum: head.name, member: isFieldSegment(first) ? (first.field?.$refText ?? '?') : '?' };
        }
        if (isConstant(head)) {
            // named constants are folded: the generated C holds their values
            const c = constantValue(v, typeOfVariableRef(v));
            return c ? fromConstant(c) : { kind: 'int', value: 0 };
        }
        return { kind: 'var', name: v.ordSchema ? 'ord_schema' : (v.variable?.$refText ?? '?'), path: pathOf(v.path) };
    }
    return undefined;
}

function pathOf(path: AstPathSegment[]): PathSegment[] {
    return path.map((s) => isFieldSegment(s) ? (s.field?.$refText ?? '?') : (segmentIndex(s) ?? 0));
}

const indexOf = (ref: { $refText?: string } | undefined): number => Number(ref?.$refText ?? -1);

function port(p: AstPort | AstParameter): PortDecl {
    const decl: PortDecl = { name: p.name, index: Number(p.index), type: typeRef(p.type) };
    const initial = value(p.value);
    if (initial) decl.initial = initial;
    return decl;
}

function named(n: { name: string; type: AstTypeRef; value?: AstValue }): NamedValue {
    const out: NamedValue = { name: n.name, type: typeRef(n.type) };
    const d = value(n.value);
    if (d) out.default = d;
    return out;
}

function settings(list: ParameterSetting[]): ParamSetting[] {
    return list.map((s) => ({ port: indexOf(s.port), value: value(s.value) ?? { kind: 'int', value: 0 } }));
}

function moduleOf(m: AstModule): Module {
    const data = dataPortsOf(m);
    const events = eventPortsOf(m);
    const out: Module = {
        name: m.name,
        kind: m.kind === 'asynchronous' ? 'asynchronous' : 'synchronous',
        parameters: parametersOf(m).map(port),
        dataIn: data.filter((p) => p.direction === 'in').map(port),
        dataOut: data.filter((p) => p.direction === 'out').map(port),
        eventIn: events.filter((p) => p.direction === 'in').map(port),
        eventOut: events.filter((p) => p.direction === 'out').map(port),
    };
    const c = computeTimeNs(m);
    if (c !== undefined) out.wcetNs = c;
    return out;
}

function schemaOf(s: AstSchema): Schema {
    const out: Schema = {
        name: s.name,
        kind: s.kind === 'event' ? 'event' : 'periodic',
        parameters: s.parameters.map(named),
        modules: moduleInstancesOf(s).map((i) => ({ module: i.module.$refText, settings: settings(i.parameters) })),
        precedences: precedencesOf(s).map((p) => ({ before: p.from.$refText, after: p.to.$refText })),
        dataFlows: [],
        eventFlows: [],
    };
    const period = periodNs(s);
    const critical = criticalDelayNs(s);
    if (period !== undefined) out.periodNs = period;
    if (critical !== undefined) out.criticalDelayNs = critical;
    for (const c of communicationsOf(s)) {
        const base = { source: c.source.$refText, sourcePort: indexOf(c.sourcePort), target: c.target.$refText, targetPort: indexOf(c.targetPort) };
        if (isDataCommunication(c)) out.dataFlows.push({ ...base, periodicity: c.periodicity ?? 1 });
        else out.eventFlows.push({ ...base, oneShot: c.mode === '=>' || c.mode === '==>' });
    }
    return out;
}

function persistence(p: AstPersistence | undefined): Persistence {
    if (!p) return undefined;
    if (p.infinite) return 'infinite';
    return { ns: p.time ? timeToNanoseconds(p.time.text) : 0 };
}

function assignment(x: Extraction): Assignment {
    return {
        target: x.target.ordSchema ? 'ord_schema' : (x.target.variable?.$refText ?? '?'),
        path: pathOf(x.target.path),
        value: value(x.value) ?? { kind: 'int', value: 0 },
    };
}

function test(t: AstTest): Test {
    if (isFunctionTest(t)) return { op: 'call', function: t.function.$refText, args: t.args.map((a) => value(a) ?? { kind: 'int', value: 0 }) };
    const op = (isEqualityTest(t) || isRelationalTest(t) ? t.operator : '==') as Exclude<Test['op'], 'call'>;
    return { op, left: value(t.left) ?? { kind: 'int', value: 0 }, right: value(t.right) ?? { kind: 'int', value: 0 } };
}

function event(e: AstEvent): Event {
    const p = persistence(e.persistence);
    if (isStartedEvent(e)) return { kind: 'started', rule: e.rule.$refText, persistence: p };
    if (isEndofEvent(e)) return { kind: 'endof', rule: e.rule.$refText, persistence: p };
    if (isDurationEvent(e)) return { kind: 'duration', rule: e.rule.$refText, timeNs: timeToNanoseconds(e.time.text), persistence: p };
    if (isElapsedEvent(e)) return { kind: 'elapsed', timeNs: timeToNanoseconds(e.time.text), persistence: p };
    return {
        kind: 'module',
        source: e.ord ? 'ORD' : (e.source?.$refText ?? '?'),
        port: e.ord ? Number(e.ordPort) : indexOf(e.port),
        inPort: eventInPort(e).port?.index ?? -1,
        tests: e.tests.map((c) => c.tests.map(test)),
        persistence: p,
        extractions: e.extractions.map(assignment),
    };
}

function condition(c: AstCondition | undefined): Condition {
    return c ? c.clauses.map((clause) => clause.events.map(event)) : [];
}

function action(a: AstAction): Action | undefined {
    const v = (x: AstValue | undefined) => value(x) ?? { kind: 'int', value: 0 } as Value;
    if (isActivateSchema(a)) return { kind: 'schema', schema: a.schema.$refText, assignments: a.assignments.map((x) => ({ parameter: x.parameter.$refText, value: v(x.value) })) };
    if (isActivateSupervisor(a)) return { kind: 'supervisor', supervisor: a.supervisor.$refText, function: a.function.$refText, assignments: a.assignments.map((x) => ({ parameter: x.parameter.$refText, value: v(x.value) })) };
    if (isActivateModule(a)) return { kind: a.priority === 'critical' ? 'critical' : 'resttime', module: a.module.$refText };
    if (isParameterize(a)) return { kind: 'parameterize', module: a.module.$refText, settings: settings(a.parameters) };
    if (isCompute(a)) return { kind: 'compute', function: a.function.$refText, args: a.args.map(v) };
    if (isSubscribe(a)) return { kind: 'subscribe', source: a.source.$refText, sourcePort: indexOf(a.sourcePort), inPort: indexOf(a.targetPort), oneShot: a.mode === '=>' || a.mode === '==>' };
    if (isNotify(a)) return { kind: 'notify', port: indexOf(a.port), assignments: a.assignments.map(assignment) };
    return undefined;
}

function functionOf(f: AstFunction): SupervisionFunction {
    return {
        name: f.name,
        parameters: f.parameters.map(named),
        locals: localsOf(f).map(named),
        rules: rulesOf(f).map((r) => ({
            label: r.name,
            pre: condition(r.precondition),
            actions: r.actions.flatMap((a) => action(a) ?? []),
            post: condition(r.postcondition),
        })),
    };
}

function supervisorOf(s: AstSupervisor): Supervisor {
    const events = eventPortsOf(s);
    return {
        name: s.name,
        eventIn: events.filter((p) => p.direction === 'in').map(port),
        eventOut: events.filter((p) => p.direction === 'out').map(port),
        functions: s.functions.map(functionOf),
    };
}

/** The architecture of a set of Cactal models (give them in a stable order, e.g. sorted by file). */
export function architectureFromModels(models: Model[]): Architecture {
    const arch: Architecture = { datatypes: [], functions: [], modules: [], schemas: [], supervisors: [] };
    for (const model of models) {
        for (const e of model.elements as AstNode[]) {
            if (isDataType(e)) arch.datatypes.push({ name: e.name, fields: e.fields.map(named) } satisfies Datatype);
            else if (isEnumType(e)) (arch.enums ??= []).push({ name: e.name, members: e.members.map((m) => m.name) });
            else if (isConstant(e)) {
                const c = constantValue(e.value, typeOf(e.type));
                if (c) (arch.constants ??= []).push({ name: e.name, type: typeRef(e.type), value: fromConstant(c) });
            }
            else if (isFunctionPrototype(e)) arch.functions.push({
                name: e.name,
                returns: e.returnType.primitive === 'bool' ? 'bool' : 'void',
                args: e.args.map((a) => ({ name: a.name, type: typeRef(a.type) })),
            } satisfies FunctionPrototype);
            else if (isModule(e)) arch.modules.push(moduleOf(e));
            else if (isSchema(e)) arch.schemas.push(schemaOf(e));
            else if (isSupervisor(e)) arch.supervisors.push(supervisorOf(e));
            else if (isSchedulerConfiguration(e) && !arch.scheduler) arch.scheduler = {
                modules: scheduledModulesOf(e).map((r) => r.$refText),
                schemas: scheduledSchemasOf(e).map((r) => r.$refText),
            };
        }
    }
    return arch;
}
